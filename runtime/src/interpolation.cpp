// Attribute interpolation (pipeline.md §6.4). The model is described in setup.h.
#include "sm2/runtime/interpolation.h"

#include <cstddef>

#include <immintrin.h>

#include "unorm8_avx512.h"

namespace sm2::runtime {
namespace {

SM2_AVX512_CODE_BEGIN

// Each lane's pixel (lanes past quad n - 1 repeat its position), written with one 64-byte store
// per coordinate: the loops below load them as vectors, and a vector load of what 16 scalar
// stores just wrote stalls (no store forwarding) for about as long as the rest of the set-up.
SM2_AVX512 void lane_positions_avx512(const Quad* quads, size_t n, PixelLanes& lanes) {
    static_assert(sizeof(Quad) == 12 && offsetof(Quad, x) == 0 && offsetof(Quad, y) == 4, "3 words per quad");
    const __m512i quad_of_lane = _mm512_min_epi32(_mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3),
                                                  _mm512_set1_epi32(static_cast<int32_t>(n) - 1));
    const __m512i word = _mm512_mullo_epi32(quad_of_lane, _mm512_set1_epi32(3));
    // The n quads' 3n words in one masked load (nothing past them is read), spread to the lanes
    // by permutes: a gather of 16 words from the same 48 bytes costs several times more.
    const __m512i words = _mm512_maskz_loadu_epi32(static_cast<__mmask16>((1u << (3 * n)) - 1u), quads);
    const __m512i x = _mm512_permutexvar_epi32(word, words);
    const __m512i y = _mm512_permutexvar_epi32(_mm512_add_epi32(word, _mm512_set1_epi32(1)), words);
    const __m512i dx = _mm512_setr_epi32(0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1);
    const __m512i dy = _mm512_setr_epi32(0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1);
    _mm512_storeu_si512(lanes.x.data(), _mm512_add_epi32(x, dx));
    _mm512_storeu_si512(lanes.y.data(), _mm512_add_epi32(y, dy));
}

SM2_AVX512 inline __m512 join_halves(__m256 lo, __m256 hi) {
    return _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}

// a0 + c1 d1 + c2 d2 in float, left to right, for 16 lanes.
SM2_AVX512 inline __m512 attribute_at(float a0, float d1, float d2, __m512 c1, __m512 c2) {
    return _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(a0), _mm512_mul_ps(c1, _mm512_set1_ps(d1))),
                         _mm512_mul_ps(c2, _mm512_set1_ps(d2)));
}

// The weights, depth and the varyings of interpolate() for all 16 lanes, in AVX-512 registers:
// the same IEEE operations in the same order as the loops below (the compiler vectorized the
// varyings across the four components of a register instead of across the lanes).
SM2_AVX512 void weights_and_varyings_avx512(const PrimitiveSetup& p, uint16_t used, emu::Batch& batch,
                                            PixelLanes& lanes) {
    __m512 c1, c2;
    {
        __m256 half_c1[2], half_c2[2], half_depth[2];
        for (unsigned h = 0; h < 2; ++h) {
            const __m512d dx = _mm512_sub_pd(_mm512_cvtepi32_pd(_mm256_load_si256(reinterpret_cast<const __m256i*>(lanes.x.data() + 8 * h))),
                                             _mm512_set1_pd(p.origin_x));
            const __m512d dy = _mm512_sub_pd(_mm512_cvtepi32_pd(_mm256_load_si256(reinterpret_cast<const __m256i*>(lanes.y.data() + 8 * h))),
                                             _mm512_set1_pd(p.origin_y));
            const __m512d b1 = _mm512_add_pd(_mm512_add_pd(_mm512_set1_pd(p.b1.c), _mm512_mul_pd(_mm512_set1_pd(p.b1.dx), dx)),
                                             _mm512_mul_pd(_mm512_set1_pd(p.b1.dy), dy));
            const __m512d b2 = _mm512_add_pd(_mm512_add_pd(_mm512_set1_pd(p.b2.c), _mm512_mul_pd(_mm512_set1_pd(p.b2.dx), dx)),
                                             _mm512_mul_pd(_mm512_set1_pd(p.b2.dy), dy));
            const __m512d z = _mm512_add_pd(_mm512_add_pd(_mm512_add_pd(_mm512_set1_pd(p.z0), _mm512_mul_pd(b1, _mm512_set1_pd(p.dz1))),
                                                          _mm512_mul_pd(b2, _mm512_set1_pd(p.dz2))),
                                            _mm512_set1_pd(p.depth_offset));
            half_depth[h] = _mm512_cvtpd_ps(z);
            if (p.perspective) {
                const __m512d f1 = _mm512_mul_pd(b1, _mm512_set1_pd(p.rhw[1]));
                const __m512d f2 = _mm512_mul_pd(b2, _mm512_set1_pd(p.rhw[2]));
                const __m512d rest = _mm512_sub_pd(_mm512_sub_pd(_mm512_set1_pd(1.0), b1), b2);
                const __m512d sum = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(rest, _mm512_set1_pd(p.rhw[0])), f1), f2);
                half_c1[h] = _mm512_cvtpd_ps(_mm512_div_pd(f1, sum));
                half_c2[h] = _mm512_cvtpd_ps(_mm512_div_pd(f2, sum));
            } else {
                half_c1[h] = _mm512_cvtpd_ps(b1);
                half_c2[h] = _mm512_cvtpd_ps(b2);
            }
        }
        _mm512_store_ps(lanes.depth.data(), join_halves(half_depth[0], half_depth[1]));
        c1 = join_halves(half_c1[0], half_c1[1]);
        c2 = join_halves(half_c2[0], half_c2[1]);
    }
    for (unsigned v = 0; v < kVaryingCount; ++v) {
        if (!(used >> v & 1u)) continue;
        const Vec4& a0 = p.a0[v];
        const Vec4& d1 = p.d1[v];
        const Vec4& d2 = p.d2[v];
        if (v == kVaryingFog) {
            _mm512_store_ps(lanes.fog.data(), attribute_at(a0[0], d1[0], d2[0], c1, c2));
            continue;
        }
        auto& reg = v < kVaryingTexCoord0 ? batch.input(v) : batch.texcoord(v - kVaryingTexCoord0);
        for (unsigned c = 0; c < 4; ++c) _mm512_storeu_ps(reg[c].data(), attribute_at(a0[c], d1[c], d2[c], c1, c2));
    }
}

SM2_AVX512_CODE_END

}  // namespace

__attribute__((target_clones("arch=x86-64-v4", "default")))
void interpolate(const PrimitiveSetup& p, std::span<const Quad> quads, uint16_t varyings,
                 emu::Batch& batch, PixelLanes& lanes, bool reference) {
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
        lane_positions_avx512(quads.data(), n, lanes);
    } else {
        for (unsigned lane = 0; lane < N; ++lane) {
            const Quad& quad = quads[lane / 4 < n ? lane / 4 : n - 1];
            lanes.x[lane] = quad.x + static_cast<int32_t>(lane & 1u);
            lanes.y[lane] = quad.y + static_cast<int32_t>(lane >> 1 & 1u);
        }
    }
    for (unsigned q = 0; q < n; ++q) lanes.coverage |= static_cast<emu::LaneMask>(quads[q].mask & 0xFu) << (4 * q);
    if (!reference && cpu_has_avx512()) {
        weights_and_varyings_avx512(p, used, batch, lanes);
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
        lanes.depth[lane] = static_cast<float>(p.z0 + b1 * p.dz1 + b2 * p.dz2 + p.depth_offset);
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
