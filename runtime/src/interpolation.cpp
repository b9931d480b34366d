// Attribute interpolation (pipeline.md §6.4). The model is described in setup.h.
#include "sm2/runtime/interpolation.h"

namespace sm2::runtime {

void interpolate(const PrimitiveSetup& p, std::span<const Quad> quads, uint16_t varyings,
                 emu::Batch& batch, PixelLanes& lanes) {
    const size_t n = quads.size() < emu::kBatchQuads ? quads.size() : emu::kBatchQuads;
    lanes.quad_count = static_cast<unsigned>(n);
    lanes.coverage = 0;
    lanes.clockwise = p.clockwise;
    batch.lane_count = static_cast<unsigned>(4 * n);
    const uint16_t used = static_cast<uint16_t>(varyings & p.varying_mask);
    for (size_t q = 0; q < n; ++q) {
        for (unsigned i = 0; i < 4; ++i) {
            const unsigned lane = static_cast<unsigned>(4 * q) + i;
            const int32_t px = quads[q].x + static_cast<int32_t>(i & 1u);
            const int32_t py = quads[q].y + static_cast<int32_t>(i >> 1);
            lanes.x[lane] = px;
            lanes.y[lane] = py;
            if (quads[q].mask >> i & 1u) lanes.coverage |= emu::LaneMask{1} << lane;
            const double dx = px - p.origin_x, dy = py - p.origin_y;
            const double b1 = p.b1.c + p.b1.dx * dx + p.b1.dy * dy;
            const double b2 = p.b2.c + p.b2.dx * dx + p.b2.dy * dy;
            lanes.depth[lane] = static_cast<float>(p.z0 + b1 * p.dz1 + b2 * p.dz2 + p.depth_offset);
            double w1 = b1, w2 = b2;
            if (p.perspective) {
                const double f1 = b1 * p.rhw[1], f2 = b2 * p.rhw[2];
                const double sum = (1.0 - b1 - b2) * p.rhw[0] + f1 + f2;
                w1 = f1 / sum;
                w2 = f2 / sum;
            }
            const auto c1 = static_cast<float>(w1), c2 = static_cast<float>(w2);
            for (unsigned v = 0; v < kVaryingCount; ++v) {
                if (!(used >> v & 1u)) continue;
                const Vec4& a0 = p.a0[v];
                const Vec4& d1 = p.d1[v];
                const Vec4& d2 = p.d2[v];
                if (v == kVaryingFog) {
                    lanes.fog[lane] = a0[0] + c1 * d1[0] + c2 * d2[0];
                    continue;
                }
                auto& reg = v < kVaryingTexCoord0 ? batch.input(v) : batch.texcoord(v - kVaryingTexCoord0);
                for (unsigned c = 0; c < 4; ++c) reg[c][lane] = a0[c] + c1 * d1[c] + c2 * d2[c];
            }
        }
    }
}

}  // namespace sm2::runtime
