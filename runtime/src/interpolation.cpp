// Attribute interpolation (pipeline.md §6.4). The model is described in setup.h.
#include "sm2/runtime/interpolation.h"

#include <cstddef>

#include <immintrin.h>

#include "unorm8_avx512.h"

// The block kernels, once per instruction set (block_instances.inc).
#define SM2_BLOCK_KERNELS "interpolation_block.inc"
#include "block_instances.inc"

namespace sm2::runtime {

// (Not target_clones: clang 14 compiled a cloned function declared in a header without the
// attribute for x86-64-v4 alone, an illegal instruction on CPUs without AVX-512. The block
// kernels above do the vector work.)
void interpolate(const PrimitiveSetup& p, std::span<const Quad> quads, uint16_t varyings,
                 emu::Batch& batch, PixelLanes& lanes, bool reference, bool depth) {
    constexpr unsigned N = emu::kBatchLanes;
    const size_t n = quads.size() < emu::kBatchQuads ? quads.size() : emu::kBatchQuads;
    lanes.quad_count = static_cast<unsigned>(n);
    lanes.coverage = 0;
    lanes.clockwise = p.clockwise;
    batch.lane_count = static_cast<unsigned>(4 * n);
    if (n == 0) return;  // no lane to fill (the loops below repeat the last quad's position)
    const uint16_t used = static_cast<uint16_t>(varyings & p.varying_mask);
    // Pixel positions and coverage; lanes past the last quad repeat its position (their values
    // are computed and never used).
    if (cpu_has_avx512()) {
        avx512::lane_positions_block(quads.data(), n, lanes);
    } else if (cpu_has_avx2()) {
        avx2::lane_positions_block(quads.data(), n, lanes);
    } else {
        for (unsigned lane = 0; lane < N; ++lane) {
            const Quad& quad = quads[lane / 4 < n ? lane / 4 : n - 1];
            lanes.x[lane] = quad.x + static_cast<int32_t>(lane & 1u);
            lanes.y[lane] = quad.y + static_cast<int32_t>(lane >> 1 & 1u);
        }
    }
    for (unsigned q = 0; q < n; ++q) lanes.coverage |= static_cast<emu::LaneMask>(quads[q].mask & 0xFu) << (4 * q);
    if (!reference && cpu_has_avx512()) {
        if (depth) avx512::weights_and_varyings_block<true>(p, used, batch, lanes);
        else avx512::weights_and_varyings_block<false>(p, used, batch, lanes);
        return;
    }
    if (!reference && cpu_has_avx2()) {
        if (depth) avx2::weights_and_varyings_block<true>(p, used, batch, lanes);
        else avx2::weights_and_varyings_block<false>(p, used, batch, lanes);
        return;
    }
    // Barycentric weights, depth and the perspective-correct weights, one loop per quantity over
    // all lanes (the compiler vectorizes them; each lane's arithmetic is the same as one at a time).
    alignas(64) std::array<float, N> c1, c2;
    const bool perspective = p.perspective;
    for (unsigned lane = 0; lane < N; ++lane) {
        const double dx = lanes.x[lane] - p.origin_x, dy = lanes.y[lane] - p.origin_y;
        const double b1 = p.b1.c + p.b1.dx * dx + p.b1.dy * dy;
        const double b2 = p.b2.c + p.b2.dx * dx + p.b2.dy * dy;
        if (depth) lanes.depth[lane] = static_cast<float>(p.z0 + b1 * p.dz1 + b2 * p.dz2 + p.depth_offset);
        const double f1 = b1 * p.rhw[1], f2 = b2 * p.rhw[2];
        const double sum = (1.0 - b1 - b2) * p.rhw[0] + f1 + f2;
        c1[lane] = static_cast<float>(perspective ? f1 / sum : b1);
        c2[lane] = static_cast<float>(perspective ? f2 / sum : b2);
    }
    for (unsigned v = 0; v < kVaryingCount; ++v) {
        if (!(used >> v & 1u)) continue;
        const Vec4& a0 = p.a0[v];
        const Vec4& d1 = p.d1[v];
        const Vec4& d2 = p.d2[v];
        if (v == kVaryingFog) {
            for (unsigned lane = 0; lane < N; ++lane) lanes.fog[lane] = a0[0] + c1[lane] * d1[0] + c2[lane] * d2[0];
            continue;
        }
        auto& reg = v < kVaryingTexCoord0 ? batch.input(v) : batch.texcoord(v - kVaryingTexCoord0);
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned lane = 0; lane < N; ++lane) reg[c][lane] = a0[c] + c1[lane] * d1[c] + c2[lane] * d2[c];
    }
}

}  // namespace sm2::runtime
