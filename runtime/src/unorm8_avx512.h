// The UNORM8 conversions of format_layout.h for 16 lanes in AVX-512 registers, shared by the
// sampler's and the output merger's block paths (callers check the CPU before calling).
#pragma once

#include <cstdint>

#include <immintrin.h>

// Functions marked SM2_AVX512 run only where cpu_has_avx512() holds.
#define SM2_AVX512 __attribute__((target("avx512f,avx512dq,avx512vl")))

// GCC 12's AVX-512 headers trip -Wuninitialized on their own _mm512_undefined_*() self-init:
// code that uses the intrinsics sits between SM2_AVX512_CODE_BEGIN and SM2_AVX512_CODE_END.
#if defined(__GNUC__) && !defined(__clang__)
#define SM2_AVX512_CODE_BEGIN                                   \
    _Pragma("GCC diagnostic push")                              \
    _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")       \
    _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")
#define SM2_AVX512_CODE_END _Pragma("GCC diagnostic pop")
#else
#define SM2_AVX512_CODE_BEGIN
#define SM2_AVX512_CODE_END
#endif

namespace sm2::runtime {

// Whether this CPU runs SM2_AVX512 code (the block paths of the sampler, the output merger and
// interpolation); asked once.
inline bool cpu_has_avx512() {
    static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                            __builtin_cpu_supports("avx512vl");
    return has;
}

}  // namespace sm2::runtime

namespace sm2::runtime::unorm8 {

// Decode: byte / 255 in float. The quotient without a division: q = b * (1/255) corrected once
// by its residual b - 255 q (exact in an FMA), which gives the correctly rounded b / 255 for
// each of the 256 bytes (sampler_block_test checks all of them against the division).
SM2_AVX512 inline __m512 decode(__m512 byte) {
    const __m512 reciprocal = _mm512_set1_ps(1.0f / 255.0f);
    const __m512 q = _mm512_mul_ps(byte, reciprocal);
    const __m512 residual = _mm512_fnmadd_ps(q, _mm512_set1_ps(255.0f), byte);
    return _mm512_fmadd_ps(residual, reciprocal, q);
}

// The same for a field of n <= 16 bits: v / max with max = 2^n - 1, its reciprocal corrected
// once by the residual; correctly rounded for every v of every n from 1 to 16 (checked
// exhaustively by sampler_block_test). `scale`, a power of two, multiplies the result for free:
// every step is the unscaled one times `scale` (exact away from subnormals), so the result is
// quotient(value, max) * scale bit for bit.
SM2_AVX512 inline __m512 quotient(__m512 value, float max, float scale = 1.0f) {
    const __m512 divisor = _mm512_set1_ps(max / scale);
    const __m512 reciprocal = _mm512_set1_ps(1.0f / max * scale);
    const __m512 q = _mm512_mul_ps(value, reciprocal);
    const __m512 residual = _mm512_fnmadd_ps(q, divisor, value);
    return _mm512_fmadd_ps(residual, reciprocal, q);
}

// The byte at bit `shift` of each 32-bit texel, decoded.
SM2_AVX512 inline __m512 decode_at(__m512i texels, unsigned shift) {
    const __m512i byte = _mm512_and_si512(_mm512_srli_epi32(texels, shift), _mm512_set1_epi32(0xFF));
    return decode(_mm512_cvtepi32_ps(byte));
}

// The field (v >> shift) & mask of each 32-bit texel, decoded as v / mask.
SM2_AVX512 inline __m512 decode_field(__m512i texels, unsigned shift, uint32_t mask) {
    const __m512i field = _mm512_and_si512(_mm512_srli_epi32(texels, shift), _mm512_set1_epi32(static_cast<int32_t>(mask)));
    return quotient(_mm512_cvtepi32_ps(field), static_cast<float>(mask));
}

// Encode of a value already in [0, 1] into a field of maximum `max` (255 for 8 bits, at most
// 65535): floor(double(v) * max + 0.5), exact in double (24 + 16 significant bits) and
// truncated (the sum is positive), as format_layout.h's encode.
SM2_AVX512 inline __m512i encode(__m512 unit, double max = 255.0) {
    const __m512d scale = _mm512_set1_pd(max), half = _mm512_set1_pd(0.5);
    const __m512d lo = _mm512_add_pd(_mm512_mul_pd(_mm512_cvtps_pd(_mm512_castps512_ps256(unit)), scale), half);
    const __m512d hi =
        _mm512_add_pd(_mm512_mul_pd(_mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(unit), 1))), scale), half);
    return _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(lo)), _mm512_cvttpd_epi32(hi), 1);
}

}  // namespace sm2::runtime::unorm8
