// The output merger (pipeline.md §7, §10, §12, §13): fog, alpha test, the depth/stencil stage
// (depth_stencil.h), blending, sRGB write, colour write masks and stores to up to four render
// targets, in D3D9's order:
//   fog on oC0.rgb -> (scissor: done by the rasterizer) -> alpha test on oC0.a ->
//   depth bias (in the interpolated depth) -> stencil test, depth test, stencil update ->
//   blending per target -> sRGB (target 0) -> write mask -> store.
// Pixels killed by texkill (batch.killed) or not covered write nothing.
//
// Blending is done in float. For fixed-point targets the shader colour and the result are
// clamped to [0, 1]; float targets keep the range. Destination colours are the stored texels as
// a sampler reads them (a format without alpha reads alpha 1). sRGB write blends in linear
// space: the stored value is converted to linear, blended, and converted back.
#pragma once

#include <array>
#include <cstdint>

#include "sm2/emu/batch.h"
#include "sm2/runtime/depth_stencil.h"
#include "sm2/runtime/interpolation.h"
#include "sm2/runtime/render_state.h"
#include "sm2/runtime/surface.h"

namespace sm2::runtime {

struct BlendState {
    bool enable = false;  // ALPHABLENDENABLE
    Blend src = Blend::One, dst = Blend::Zero;
    BlendOp op = BlendOp::Add;
    Blend src_alpha = Blend::One, dst_alpha = Blend::Zero;  // SEPARATEALPHABLENDENABLE, or
    BlendOp op_alpha = BlendOp::Add;                        // copies of the colour ones
    Vec4 factor{1.0f, 1.0f, 1.0f, 1.0f};                   // BLENDFACTOR / 255
};

struct OutputMergerState {
    bool fog_enable = false;
    FogMode fog_table_mode = FogMode::None;
    // Table fog of the interpolated oFog (the eye depth of a fixed-function W-fog draw) instead of
    // the pixel's depth.
    bool table_fog_of_w = false;
    float fog_start = 0.0f, fog_end = 1.0f, fog_density = 1.0f;
    Vec4 fog_color{};
    bool alpha_test = false;
    CompareFunc alpha_func = CompareFunc::Always;
    float alpha_ref = 0.0f;  // (ALPHAREF & 0xFF) / 255
    DepthStencilState depth_stencil{};
    BlendState blend{};
    std::array<uint32_t, kMaxRenderTargets> write_mask{0xF, 0xF, 0xF, 0xF};
    bool srgb_write = false;
};
[[nodiscard]] OutputMergerState output_merger_state(const RenderState& state);

struct RenderTargets {
    std::array<Surface*, kMaxRenderTargets> color{};  // null: no target in that slot
    DepthStencilSurface* depth_stencil = nullptr;
};

// §13 with a vertex shader: table fog (LINEAR/EXP/EXP2 of the pixel depth) when FOGTABLEMODE is
// not NONE, else the interpolated oFog.x; clamped to [0, 1]. 1 = no fog.
[[nodiscard]] float fog_factor(const OutputMergerState& state, float vertex_fog, float depth);
// `alpha FUNC ref` with alpha = oC0.a, clamped to [0, 1] when render target 0 clamps (UNORM and
// the other fixed-point formats) and as written on a float target (R16F .. A32B32G32R32F): there
// 1.5 passes GREATER 255 and -0.25 passes LESS 0. NaN fails every test but ALWAYS.
[[nodiscard]] bool alpha_test_passes(const OutputMergerState& state, float alpha, bool target_clamps);
// One blend (§12): src = shader colour, dst = stored colour. `fixed_point` clamps src and the
// result to [0, 1].
[[nodiscard]] Vec4 blend(const BlendState& state, const Vec4& src, const Vec4& dst, bool fixed_point);
// Whether a render-target format stores floats (no clamping).
[[nodiscard]] bool is_float_target(Format format);

struct MergeInput {
    const emu::Batch* batch = nullptr;     // after the pixel shader: oC0..3, oDepth
    const PixelLanes* lanes = nullptr;     // positions, depth, fog, facing
    emu::LaneMask live = 0;                // lanes to process (batch.killed is removed here)
    uint8_t color_outputs = 1;             // oC# the shader writes (bit n)
    bool shader_depth = false;             // oDepth written: replaces the biased depth
    bool depth_stencil_done = false;       // an early depth/stencil test already ran on `live`
    // Tests only: store every target through the per-pixel path (Surface::read/write), which
    // the 8-bit fast path must match byte for byte.
    bool generic_path = false;
    // Tests only: the 16-lane kernels' AVX2 instance even on a CPU with AVX-512.
    bool block_avx2 = false;
};

// How merge() stores into one render target: what depends on the state, the target and the
// shader's outputs alone, chosen once per draw by merge_plan() instead of once per batch.
enum class TargetPath : uint8_t {
    Skip,          // no target, not written by the shader, write mask 0, or not a target
    Unorm8Block,   // UNORM fields in 4-byte texels (8-bit ones: `bytes`), the 16-lane kernels
    Unorm8Block8,  // UNORM fields in 8-byte texels (A16B16G16R16), the 16-lane kernels
    Unorm8Lanes,   // 8-bit fields in 4-byte texels, without the 16-lane kernels; and sRGB writes to them
    FloatBlock,    // 32-bit float channels without blending, copied by the 16-lane kernels
    FloatLanes,    // the same copy, lane by lane
    FloatMerge,    // 16- or 32-bit float channels, blended or halves: read, blended, written a batch at a time
    PerPixel,      // every other target: Surface::read/write pixel by pixel
};
struct Unorm8Texel;  // output_merger.cpp's layouts of the UNORM and float paths
struct FloatTexel;
struct TargetPlan {
    TargetPath path = TargetPath::Skip;
    bool bytes = false;  // Unorm8Block: every field 8 bits
    bool fixed = true;   // not a float target: blending clamps
    bool srgb = false;   // sRGB write (target 0 only)
    uint32_t mask = 0;   // the colour write mask
    const FormatInfo* info = nullptr;
    // The target's layout for its path (Unorm8*: unorm8; FloatBlock, FloatLanes, FloatMerge:
    // floats), looked up once a draw: per batch, the tables' guarded statics cost scene 13 1%.
    const Unorm8Texel* unorm8 = nullptr;
    const FloatTexel* floats = nullptr;
    // Source-over blending (SRCALPHA, INVSRCALPHA, ADD) onto a block path's texels whose every
    // bit is a field's: a batch whose alpha saturates to +0 on every lane writes each texel back
    // as it was (merge() skips it).
    bool transparent_skips = false;
};
// The blending the 8-bit block kernel (Unorm8Block with `bytes`) is compiled for: Any tests the
// state per batch; the others hold it as a compile-time fact, so that the kernel's code carries
// no other blend and keeps every value in registers.
enum class KernelBlend : uint8_t { Any, Off, SourceOver, Additive };
struct MergePlan {
    std::array<TargetPlan, kMaxRenderTargets> targets{};
    KernelBlend blend = KernelBlend::Any;  // the state's blend, for the 8-bit block kernel
    bool avx512_block = false;  // the 16-lane kernels' instance: AVX-512, else AVX2 (where `block`)
    bool block = false;
    bool alpha_clamps = true;   // the alpha test clamps oC0.a (render target 0 is not a float target)
};
// The plan for `targets` under `state` and the shader outputs of `input` (color_outputs,
// generic_path, block_avx2); the same plan serves every batch of a draw.
[[nodiscard]] MergePlan merge_plan(const OutputMergerState& state, const RenderTargets& targets, const MergeInput& input);

// Runs every per-pixel operation for the live lanes; returns the lanes that wrote colour.
// Targets whose channels are each an 8-bit UNORM byte of a 4-byte texel (A8R8G8B8, X8R8G8B8,
// A8B8G8R8, X8B8G8R8) without sRGB write are blended a whole batch at a time on the stored
// bytes; every other target goes pixel by pixel through Surface::read/write. Same bytes either way.
// `plan`: merge_plan(state, targets, input), made once for the draw.
emu::LaneMask merge(const OutputMergerState& state, const RenderTargets& targets, const MergeInput& input,
                    const MergePlan& plan);
// merge() with its plan made for this call (tests, single batches).
emu::LaneMask merge(const OutputMergerState& state, const RenderTargets& targets, const MergeInput& input);

}  // namespace sm2::runtime
