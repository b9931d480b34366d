// Attribute interpolation (pipeline.md §6.4): fills a pixel batch for the pixel shader from a
// set-up primitive and up to four quads. Every attribute is perspective-correct (the 1/w
// model of setup.h), evaluated at the D3D9 pixel centre (px, py); flat-shaded colours were
// made constant by setup. Uncovered lanes of a quad get the same plane values extrapolated, so
// derivatives inside the quad stay defined (they are helper lanes for the output merger).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "sm2/emu/batch.h"
#include "sm2/runtime/rasterizer.h"

namespace sm2::runtime {

// Per-lane data the pixel stage needs beside the shader's registers.
struct PixelLanes {
    unsigned quad_count = 0;
    // (Each array on its own cache line: written and read as 64-byte vectors.)
    alignas(64) std::array<int32_t, emu::kBatchLanes> x{};
    alignas(64) std::array<int32_t, emu::kBatchLanes> y{};
    emu::LaneMask coverage = 0;  // lanes whose pixel the primitive covers
    // Zs at the pixel centre plus the primitive's depth bias (not yet clamped to [0, 1]; the
    // output merger uses oDepth instead when the shader writes it).
    alignas(64) std::array<float, emu::kBatchLanes> depth{};
    alignas(64) std::array<float, emu::kBatchLanes> fog{};  // interpolated oFog.x
    bool clockwise = true;       // front set for two-sided stencil
};

// Which ps inputs to write: bit kVaryingColor0/1 -> v0/v1, bit kVaryingTexCoord0 + n -> t#n,
// bit kVaryingFog -> lanes.fog.
[[nodiscard]] constexpr uint16_t ps_varyings_all() { return kAllVaryings; }

// Packs quads[0..n) (n <= emu::kBatchQuads) into lanes 4q..4q+3 and writes the ps inputs the
// mask selects (other registers are left as they are); sets batch.lane_count = 4n.
// reference: the portable loops even where AVX-512 code would run (the same bits; tests and
// DeviceOptions::reference_paths compare the two).
// depth: whether lanes.depth is read (a depth or stencil test, fog, pixel history); without, it
// is left as it was (a draw leaves out what it does not need).
void interpolate(const PrimitiveSetup& prim, std::span<const Quad> quads, uint16_t varyings,
                 emu::Batch& batch, PixelLanes& lanes, bool reference = false, bool depth = true);

}  // namespace sm2::runtime
