// The depth/stencil stage of the output merger (pipeline.md §7 steps 5-7, §9, §11) and the
// depth-stencil surface it works on.
//
// Depth is stored per format as D3D9 quantizes it: D16 round(z*65535), D24 round(z*(2^24-1)),
// D32 round(z*(2^32-1)) (exact integer arithmetic, halves round up), D32F_LOCKABLE/D24FS8 the
// float itself. The incoming depth (clamped to [0, 1]) is quantized the same way before the
// compare, so the test compares exactly what would be stored. Stencil is kept beside depth
// (D3D9 leaves the packing to the driver), with the format's bit count (8, 4, 1 or none).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/runtime/formats.h"
#include "sm2/runtime/render_state.h"
#include "sm2/runtime/surface.h"

namespace sm2::runtime {

struct DepthFormatInfo {
    uint8_t depth_bits = 0;    // 16, 24, 32 (also for the float formats: 32)
    uint8_t stencil_bits = 0;  // 0, 1, 4, 8
    bool float_depth = false;  // D32F_LOCKABLE, D24FS8
};
// nullopt for formats that are not depth formats.
[[nodiscard]] std::optional<DepthFormatInfo> depth_format_info(Format format);

// The value stored for depth z (clamped to [0, 1]; NaN stores 0): an unsigned integer for the
// fixed-point formats, the float's bits for the float formats.
[[nodiscard]] uint32_t quantize_depth(const DepthFormatInfo& info, float z);
// The depth a stored value stands for.
[[nodiscard]] float dequantize_depth(const DepthFormatInfo& info, uint32_t stored);

class DepthStencilSurface {
public:
    struct CreateResult;
    // Errors: not a depth format, zero or oversized dimensions.
    [[nodiscard]] static CreateResult create(Format format, uint32_t width, uint32_t height);

    [[nodiscard]] Format format() const { return format_; }
    [[nodiscard]] const DepthFormatInfo& info() const { return info_; }
    [[nodiscard]] uint32_t width() const { return width_; }
    [[nodiscard]] uint32_t height() const { return height_; }
    [[nodiscard]] uint32_t stencil_max() const { return info_.stencil_bits ? (1u << info_.stencil_bits) - 1 : 0; }

    [[nodiscard]] uint32_t stored_depth(uint32_t x, uint32_t y) const { return depth_[index(x, y)]; }
    [[nodiscard]] float depth(uint32_t x, uint32_t y) const { return dequantize_depth(info_, stored_depth(x, y)); }
    [[nodiscard]] uint32_t stencil(uint32_t x, uint32_t y) const { return stencil_[index(x, y)]; }
    void set_stored_depth(uint32_t x, uint32_t y, uint32_t value) { depth_[index(x, y)] = value; }
    void set_depth(uint32_t x, uint32_t y, float z) { depth_[index(x, y)] = quantize_depth(info_, z); }
    void set_stencil(uint32_t x, uint32_t y, uint32_t s) { stencil_[index(x, y)] = static_cast<uint8_t>(s & stencil_max()); }
    // The stored depth values, row by row (width() a row): the test's 16-lane path reads and
    // writes them directly.
    [[nodiscard]] uint32_t* depth_data() { return depth_.data(); }
    // The stored stencil values, one byte a pixel, laid out as depth_data().
    [[nodiscard]] uint8_t* stencil_data() { return stencil_.data(); }
    // Clear(D3DCLEAR_ZBUFFER / D3DCLEAR_STENCIL) inside `rect` (clipped to the surface).
    void clear(const PixelRect& rect, bool depth, float z, bool stencil, uint32_t s);

private:
    [[nodiscard]] size_t index(uint32_t x, uint32_t y) const { return static_cast<size_t>(y) * width_ + x; }
    Format format_ = Format::Unknown;
    DepthFormatInfo info_{};
    uint32_t width_ = 0, height_ = 0;
    std::vector<uint32_t, CacheLineAllocator<uint32_t>> depth_;  // rows on whole cache lines, as Surface
    std::vector<uint8_t> stencil_;
};

struct DepthStencilSurface::CreateResult {
    std::optional<DepthStencilSurface> surface;
    std::string error;
};

// `a FUNC b` (D3DCMPFUNC; pipeline.md §9).
template <typename T>
[[nodiscard]] constexpr bool compare(CompareFunc func, T a, T b) {
    switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return a < b;
    case CompareFunc::Equal: return a == b;
    case CompareFunc::LessEqual: return a <= b;
    case CompareFunc::Greater: return a > b;
    case CompareFunc::NotEqual: return a != b;
    case CompareFunc::GreaterEqual: return a >= b;
    case CompareFunc::Always: return true;
    }
    return false;
}

// D3DSTENCILOP on an n-bit stencil value (max = 2^n - 1); REPLACE stores ref & max.
[[nodiscard]] uint32_t apply_stencil_op(StencilOp op, uint32_t stored, uint32_t ref, uint32_t max);

// The depth/stencil state of a draw (from the render state).
struct DepthStencilState {
    bool depth_enable = false;  // ZENABLE TRUE or USEW (w-buffering is done as z-buffering)
    bool depth_write = true;
    CompareFunc depth_func = CompareFunc::LessEqual;
    bool stencil_enable = false;
    bool two_sided = false;
    StencilFace front{};  // clockwise triangles, lines, points
    StencilFace back{};   // counter-clockwise triangles when two_sided
    uint32_t ref = 0, mask = 0xFFFFFFFFu, write_mask = 0xFFFFFFFFu;
    // Whether the stage does anything (no buffer or nothing enabled: leave it out).
    [[nodiscard]] bool active() const { return depth_enable || stencil_enable; }
};
[[nodiscard]] DepthStencilState depth_stencil_state(const RenderState& state);

// Stencil test, depth test and stencil update (§7 steps 6-7, §11) for the `live` lanes of a
// pixel batch at (x[l], y[l]) with incoming depth depth[l] (bias applied, or oDepth; clamped to
// [0, 1] here). Writes depth (when enabled and passed) and stencil; returns the lanes that
// passed both tests. No surface: every live lane passes. Lanes outside the surface fail.
// On an integer depth of at most 24 bits or a float depth, with the lanes in quad order at
// distinct pixels, the test runs 16 lanes at once (AVX-512 or AVX2, depth_stencil_block.inc),
// with the same results as the lane-by-lane loop, which `per_lane` forces
// (DeviceOptions::reference_paths).
// (The test for a surface and an active state inline, in every caller: as a call a batch that
// returned at once it cost scene 13, which has no depth buffer, 0.8% of its run.)
[[nodiscard]] emu::LaneMask active_depth_stencil_test(const DepthStencilState& state, DepthStencilSurface& surface,
                                                      const std::array<int32_t, emu::kBatchLanes>& x,
                                                      const std::array<int32_t, emu::kBatchLanes>& y,
                                                      const std::array<float, emu::kBatchLanes>& depth,
                                                      emu::LaneMask live, bool clockwise, bool per_lane);
[[nodiscard]] inline emu::LaneMask depth_stencil_test(const DepthStencilState& state,
                                                      DepthStencilSurface* surface,
                                                      const std::array<int32_t, emu::kBatchLanes>& x,
                                                      const std::array<int32_t, emu::kBatchLanes>& y,
                                                      const std::array<float, emu::kBatchLanes>& depth,
                                                      emu::LaneMask live, bool clockwise, bool per_lane = false) {
    if (!surface || !state.active()) return live;
    return active_depth_stencil_test(state, *surface, x, y, depth, live, clockwise, per_lane);
}

}  // namespace sm2::runtime
