// Depth/stencil surface and tests (pipeline.md §9, §11). See depth_stencil.h.
#include "sm2/runtime/depth_stencil.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "quad_rows.h"
#include "unorm8_avx512.h"

namespace sm2::runtime {

std::optional<DepthFormatInfo> depth_format_info(Format format) {
    switch (format) {
    case Format::D16_LOCKABLE: case Format::D16: return DepthFormatInfo{16, 0, false};
    case Format::D32: return DepthFormatInfo{32, 0, false};
    case Format::D15S1: return DepthFormatInfo{15, 1, false};
    case Format::D24S8: return DepthFormatInfo{24, 8, false};
    case Format::D24X8: return DepthFormatInfo{24, 0, false};
    case Format::D24X4S4: return DepthFormatInfo{24, 4, false};
    case Format::D32F_LOCKABLE: return DepthFormatInfo{32, 0, true};
    case Format::D24FS8: return DepthFormatInfo{32, 8, true};
    default: return std::nullopt;
    }
}

uint32_t quantize_depth(const DepthFormatInfo& info, float z) {
    if (!(z > 0.0f)) z = 0.0f;  // also NaN
    if (z > 1.0f) z = 1.0f;
    if (info.float_depth) return std::bit_cast<uint32_t>(z);
    // round(z * (2^n - 1)) exactly: z = m * 2^-shift with an integer m of at most 24 bits (read
    // from the float's fields, no frexp), so the product is the integer m * (2^n - 1) (at most 56
    // bits) scaled by 2^-shift; round half up.
    const uint32_t bits = std::bit_cast<uint32_t>(z);
    const uint32_t biased = bits >> 23;                        // z in [0, 1]: the sign is 0
    const uint64_t m = (bits & 0x7FFFFFu) | (biased != 0 ? 0x800000u : 0u);
    const int shift = biased != 0 ? 150 - static_cast<int>(biased) : 149;  // >= 23; denormals: 2^-149 units
    const uint64_t product = m * ((uint64_t{1} << info.depth_bits) - 1);
    if (m == 0 || shift >= 64) return 0;
    return static_cast<uint32_t>((product + (uint64_t{1} << (shift - 1))) >> shift);
}

float dequantize_depth(const DepthFormatInfo& info, uint32_t stored) {
    if (info.float_depth) return std::bit_cast<float>(stored);
    return static_cast<float>(static_cast<double>(stored) /
                              static_cast<double>((uint64_t{1} << info.depth_bits) - 1));
}

DepthStencilSurface::CreateResult DepthStencilSurface::create(Format format, uint32_t width,
                                                              uint32_t height) {
    CreateResult r;
    const auto info = depth_format_info(format);
    if (!info) {
        r.error = "format " + std::to_string(static_cast<uint32_t>(format)) + " is not a depth-stencil format";
        return r;
    }
    if (width == 0 || height == 0 || width > 16384 || height > 16384) {
        r.error = "depth-stencil size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is not 1..16384";
        return r;
    }
    DepthStencilSurface s;
    s.format_ = format;
    s.info_ = *info;
    s.width_ = width;
    s.height_ = height;
    s.depth_.assign(static_cast<size_t>(width) * height, 0);
    s.stencil_.assign(static_cast<size_t>(width) * height, 0);
    r.surface = std::move(s);
    return r;
}

void DepthStencilSurface::clear(const PixelRect& rect, bool depth, float z, bool stencil, uint32_t s) {
    const PixelRect r = rect.intersect(PixelRect{0, 0, static_cast<int32_t>(width_), static_cast<int32_t>(height_)});
    if (r.empty()) return;
    const uint32_t q = quantize_depth(info_, z);
    const auto value = static_cast<uint8_t>(s & stencil_max());
    const auto count = static_cast<size_t>(r.right - r.left);
    for (int32_t y = r.top; y < r.bottom; ++y) {
        const size_t first = index(static_cast<uint32_t>(r.left), static_cast<uint32_t>(y));
        if (depth) std::fill_n(depth_.begin() + static_cast<std::ptrdiff_t>(first), count, q);
        if (stencil) std::fill_n(stencil_.begin() + static_cast<std::ptrdiff_t>(first), count, value);
    }
}

uint32_t apply_stencil_op(StencilOp op, uint32_t stored, uint32_t ref, uint32_t max) {
    switch (op) {
    case StencilOp::Keep: return stored;
    case StencilOp::Zero: return 0;
    case StencilOp::Replace: return ref & max;
    case StencilOp::IncrSat: return stored < max ? stored + 1 : max;
    case StencilOp::DecrSat: return stored > 0 ? stored - 1 : 0;
    case StencilOp::Invert: return ~stored & max;
    case StencilOp::Incr: return (stored + 1) & max;
    case StencilOp::Decr: return (stored - 1) & max;
    }
    return stored;
}

DepthStencilState depth_stencil_state(const RenderState& rs) {
    DepthStencilState s;
    s.depth_enable = rs.z_enable != ZBufferType::False;
    s.depth_write = rs.z_write_enable;
    s.depth_func = rs.z_func;
    s.stencil_enable = rs.stencil_enable;
    s.two_sided = rs.two_sided_stencil_mode;
    s.front = rs.stencil;
    s.back = rs.two_sided_stencil_mode ? rs.ccw_stencil : rs.stencil;
    s.ref = rs.stencil_ref;
    s.mask = rs.stencil_mask;
    s.write_mask = rs.stencil_write_mask;
    return s;
}

}  // namespace sm2::runtime

// The block kernels, once per instruction set (block_instances.inc).
#define SM2_BLOCK_KERNELS "depth_stencil_block.inc"
#include "block_instances.inc"

namespace sm2::runtime {

emu::LaneMask active_depth_stencil_test(const DepthStencilState& st, DepthStencilSurface& surface,
                                        const std::array<int32_t, emu::kBatchLanes>& x,
                                        const std::array<int32_t, emu::kBatchLanes>& y,
                                        const std::array<float, emu::kBatchLanes>& depth,
                                        emu::LaneMask live, bool clockwise, bool per_lane) {
    static_assert(emu::kBatchLanes == 16, "depth_stencil_block covers 16 lanes");
    if (!per_lane && (surface.info().float_depth || surface.info().depth_bits <= 24)) {
        emu::LaneMask passed = 0;
        if (cpu_has_avx512()) {
            if (avx512::depth_stencil_block(st, surface, x.data(), y.data(), depth.data(), live, clockwise, passed))
                return passed;
        } else if (cpu_has_avx2()) {
            if (avx2::depth_stencil_block(st, surface, x.data(), y.data(), depth.data(), live, clockwise, passed))
                return passed;
        }
    }
    const DepthFormatInfo& info = surface.info();
    const bool has_stencil = st.stencil_enable && info.stencil_bits > 0;
    const uint32_t max = surface.stencil_max();
    const StencilFace& face = (st.two_sided && !clockwise) ? st.back : st.front;
    emu::LaneMask passed = 0;
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        if (!(live >> l & 1u)) continue;
        if (x[l] < 0 || y[l] < 0 || static_cast<uint32_t>(x[l]) >= surface.width() ||
            static_cast<uint32_t>(y[l]) >= surface.height())
            continue;
        const auto px = static_cast<uint32_t>(x[l]), py = static_cast<uint32_t>(y[l]);
        bool stencil_pass = true;
        uint32_t stored_stencil = 0;
        if (st.stencil_enable) {
            // Without stencil bits the stored value reads 0 and nothing is written.
            stored_stencil = has_stencil ? surface.stencil(px, py) : 0;
            stencil_pass = compare(face.func, st.ref & st.mask, stored_stencil & st.mask);
        }
        bool depth_pass = true;
        uint32_t incoming = 0;
        if (stencil_pass && st.depth_enable) {
            incoming = quantize_depth(info, depth[l]);
            const uint32_t stored = surface.stored_depth(px, py);
            depth_pass = info.float_depth
                             ? compare(st.depth_func, std::bit_cast<float>(incoming), std::bit_cast<float>(stored))
                             : compare(st.depth_func, incoming, stored);
        }
        if (has_stencil) {
            const StencilOp op = !stencil_pass ? face.fail : !depth_pass ? face.zfail : face.pass;
            const uint32_t next = apply_stencil_op(op, stored_stencil, st.ref, max);
            const uint32_t wm = st.write_mask & max;
            surface.set_stencil(px, py, (stored_stencil & ~wm) | (next & wm));
        }
        if (!stencil_pass || !depth_pass) continue;
        if (st.depth_enable && st.depth_write) surface.set_stored_depth(px, py, incoming);
        passed |= emu::LaneMask{1} << l;
    }
    return passed;
}

}  // namespace sm2::runtime
