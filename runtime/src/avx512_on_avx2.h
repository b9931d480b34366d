// The AVX-512 intrinsics that the block kernels use (sampler_block.inc, unorm8_kernels.inc),
// under their own names, for CPUs with AVX2 and FMA but without AVX-512: a 512-bit value is two
// 256-bit registers (lanes 0-7 in `lo`, 8-15 in `hi`), a 16-bit mask stays a 16-bit integer and
// is widened to a vector where an operation takes it. Each function gives the bits that Intel's
// definition of the intrinsic gives, so a kernel compiled against this file computes what its
// AVX-512 instance computes (sampler_block_test runs both against the per-lane path).
//
// Include this file after every use of the real intrinsics in a translation unit: clang (and GCC
// without optimization) define some of them as macros, which this file #undefs so that the
// functions below can take their names inside namespace avx2.
#pragma once

#include <cstdint>
#include <cstring>

#include <immintrin.h>

#include "unorm8_avx512.h"  // SM2_AVX2, cpu_has_avx2()

#define SM2_AVX2_INLINE SM2_AVX2 __attribute__((always_inline)) inline

#undef _mm512_abs_ps
#undef _mm512_add_epi32
#undef _mm512_add_epi64
#undef _mm512_add_pd
#undef _mm512_add_ps
#undef _mm512_and_ps
#undef _mm512_and_si512
#undef _mm512_castpd256_pd512
#undef _mm512_castpd_si512
#undef _mm512_castps128_ps512
#undef _mm512_castps512_ps256
#undef _mm512_castps_pd
#undef _mm512_castps_si512
#undef _mm512_castsi128_si512
#undef _mm512_castsi256_si512
#undef _mm512_castsi512_pd
#undef _mm512_castsi512_ps
#undef _mm512_castsi512_si128
#undef _mm512_castsi512_si256
#undef _mm512_cmp_pd_mask
#undef _mm512_cmp_ps_mask
#undef _mm512_cmpeq_epi32_mask
#undef _mm512_cmpge_epi32_mask
#undef _mm512_cmpge_epu32_mask
#undef _mm512_cmplt_epi32_mask
#undef _mm512_cmplt_epu32_mask
#undef _mm512_cmpneq_epi32_mask
#undef _mm512_cvtepi32_epi64
#undef _mm512_cvtepi32_ps
#undef _mm512_cvtepi64_pd
#undef _mm512_cvtpd_ps
#undef _mm512_cvtps_pd
#undef _mm512_cvttpd_epi32
#undef _mm512_cvttps_epi32
#undef _mm512_div_pd
#undef _mm512_div_ps
#undef _mm512_extractf64x4_pd
#undef _mm512_extracti64x4_epi64
#undef _mm512_fmadd_ps
#undef _mm512_fnmadd_ps
#undef _mm512_fmsub_ps
#undef _mm512_i32gather_epi32
#undef _mm512_i32gather_epi64
#undef _mm512_i32gather_ps
#undef _mm512_inserti64x4
#undef _mm512_load_ps
#undef _mm512_load_si512
#undef _mm512_loadu_pd
#undef _mm512_loadu_ps
#undef _mm512_mask_add_pd
#undef _mm512_mask_cmpeq_epi32_mask
#undef _mm512_mask_cmple_epi32_mask
#undef _mm512_mask_i32gather_epi32
#undef _mm512_mask_i32gather_epi64
#undef _mm512_mask_i64gather_epi32
#undef _mm512_mask_i64gather_epi64
#undef _mm512_mask_mov_epi32
#undef _mm512_mask_mov_pd
#undef _mm512_mask_mov_ps
#undef _mm512_mask_mul_pd
#undef _mm512_mask_or_epi32
#undef _mm512_mask_sub_epi32
#undef _mm512_mask_sub_pd
#undef _mm512_maskz_mov_epi32
#undef _mm512_maskz_mov_pd
#undef _mm512_maskz_mov_ps
#undef _mm512_max_epi32
#undef _mm512_max_pd
#undef _mm512_max_ps
#undef _mm512_min_epi32
#undef _mm512_min_ps
#undef _mm512_movepi32_mask
#undef _mm512_mul_pd
#undef _mm512_mul_ps
#undef _mm512_mullo_epi32
#undef _mm512_or_ps
#undef _mm512_or_si512
#undef _mm512_permutex2var_epi16
#undef _mm512_permutex2var_epi32
#undef _mm512_permutex2var_epi64
#undef _mm512_permutex2var_ps
#undef _mm512_permutexvar_epi32
#undef _mm512_permutexvar_ps
#undef _mm512_roundscale_pd
#undef _mm512_roundscale_ps
#undef _mm512_set1_epi32
#undef _mm512_set1_epi64
#undef _mm512_set1_pd
#undef _mm512_set1_ps
#undef _mm512_setr_epi32
#undef _mm512_setzero_pd
#undef _mm512_setzero_ps
#undef _mm512_setzero_si512
#undef _mm512_slli_epi32
#undef _mm512_sqrt_pd
#undef _mm512_srai_epi32
#undef _mm512_srli_epi32
#undef _mm512_srli_epi64
#undef _mm512_srlv_epi32
#undef _mm512_store_ps
#undef _mm512_store_si512
#undef _mm512_storeu_pd
#undef _mm512_storeu_ps
#undef _mm512_sub_epi32
#undef _mm512_sub_epi64
#undef _mm512_sub_pd
#undef _mm512_sub_ps
#undef _mm512_xor_ps
#undef _mm512_xor_si512
#undef _mm256_cmp_ps_mask
#undef _mm256_mask_mov_epi32
#undef _mm256_mask_mov_ps
#undef _mm256_roundscale_ps
#undef _mm256_mask_storeu_epi32
#undef _mm256_maskz_loadu_epi32
#undef _mm512_alignr_epi32
#undef _mm512_loadu_si512
#undef _mm512_mask_add_epi32
#undef _mm512_mask_cmpneq_epi32_mask
#undef _mm512_mask_i32scatter_epi32
#undef _mm512_mask_i32scatter_ps
#undef _mm512_mask_storeu_epi64
#undef _mm512_maskz_loadu_epi64
#undef _mm512_maskz_permutex2var_epi32
#undef _mm512_storeu_si512
#undef _mm512_castpd_ps
#undef _mm512_cvtepi32_pd
#undef _mm512_insertf64x4
#undef _mm512_maskz_loadu_epi32
#undef _mm512_setr_epi64
#undef _mm512_mask_cmpge_epi64_mask
#undef _mm512_shuffle_epi8
#undef _mm512_shuffle_epi32
#undef _mm512_madd_epi16
#undef _mm512_mullo_epi16
#undef _mm512_srli_epi16
#undef _mm512_unpacklo_epi32
#undef _mm512_unpackhi_epi32
#undef _mm512_unpacklo_epi64
#undef _mm512_unpackhi_epi64
#undef _mm512_permutexvar_epi64

namespace sm2::runtime::avx2 {

// The block kernels' value types, for the AVX2 instances.
struct Floats512 {
    __m256 lo, hi;
};
struct Ints512 {
    __m256i lo, hi;
};
struct Doubles512 {
    __m256d lo, hi;
};

// ---------------------------------------------------------------------------------------------
// Masks: bit i of a 16-bit mask is 32-bit lane i; bit i of an 8-bit mask is 64-bit lane i.

// The lanes of `k` (bits 0-7, or 8-15 with `high`) as the sign bits of 32-bit lanes: bit i
// shifted up to bit 31 of lane i. The other bits are not defined: every user of these vectors
// reads sign bits only (blendv_ps, maskload/maskstore, the gathers' masks). One broadcast
// serves both halves, and a shift replaces the mask-and-compare per half.
SM2_AVX2_INLINE __m256i lanes32(unsigned k, bool high) {
    const __m256i to_sign = high ? _mm256_setr_epi32(23, 22, 21, 20, 19, 18, 17, 16)
                                 : _mm256_setr_epi32(31, 30, 29, 28, 27, 26, 25, 24);
    return _mm256_sllv_epi32(_mm256_set1_epi32(static_cast<int>(k)), to_sign);
}

// The lanes of 8-bit mask `k` (bits 0-3, or 4-7 with `high`) as the sign bits of 64-bit lanes
// (the other bits not defined, as lanes32()).
SM2_AVX2_INLINE __m256i lanes64(unsigned k, bool high) {
    const __m256i to_sign = high ? _mm256_setr_epi64x(59, 58, 57, 56) : _mm256_setr_epi64x(63, 62, 61, 60);
    return _mm256_sllv_epi64(_mm256_set1_epi64x(static_cast<long long>(k)), to_sign);
}

SM2_AVX2_INLINE __mmask16 mask32(__m256i lo, __m256i hi) {
    return static_cast<__mmask16>(static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(lo))) |
                                  (static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(hi))) << 8));
}

SM2_AVX2_INLINE __mmask8 mask64(__m256i lo, __m256i hi) {
    return static_cast<__mmask8>(static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(lo))) |
                                 (static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(hi))) << 4));
}

// ---------------------------------------------------------------------------------------------
// Set, load, store, cast

SM2_AVX2_INLINE Floats512 _mm512_set1_ps(float v) { return {_mm256_set1_ps(v), _mm256_set1_ps(v)}; }
SM2_AVX2_INLINE Doubles512 _mm512_set1_pd(double v) { return {_mm256_set1_pd(v), _mm256_set1_pd(v)}; }
SM2_AVX2_INLINE Ints512 _mm512_set1_epi32(int v) { return {_mm256_set1_epi32(v), _mm256_set1_epi32(v)}; }
SM2_AVX2_INLINE Ints512 _mm512_set1_epi64(long long v) { return {_mm256_set1_epi64x(v), _mm256_set1_epi64x(v)}; }
SM2_AVX2_INLINE Ints512 _mm512_setr_epi32(int e0, int e1, int e2, int e3, int e4, int e5, int e6, int e7, int e8, int e9,
                                          int e10, int e11, int e12, int e13, int e14, int e15) {
    return {_mm256_setr_epi32(e0, e1, e2, e3, e4, e5, e6, e7), _mm256_setr_epi32(e8, e9, e10, e11, e12, e13, e14, e15)};
}
SM2_AVX2_INLINE Ints512 _mm512_setr_epi64(long long e0, long long e1, long long e2, long long e3, long long e4,
                                          long long e5, long long e6, long long e7) {
    return {_mm256_setr_epi64x(e0, e1, e2, e3), _mm256_setr_epi64x(e4, e5, e6, e7)};
}
SM2_AVX2_INLINE Floats512 _mm512_setzero_ps() { return {_mm256_setzero_ps(), _mm256_setzero_ps()}; }
SM2_AVX2_INLINE Doubles512 _mm512_setzero_pd() { return {_mm256_setzero_pd(), _mm256_setzero_pd()}; }
SM2_AVX2_INLINE Ints512 _mm512_setzero_si512() { return {_mm256_setzero_si256(), _mm256_setzero_si256()}; }

SM2_AVX2_INLINE Floats512 _mm512_load_ps(const void* p) {
    const auto* f = static_cast<const float*>(p);
    return {_mm256_load_ps(f), _mm256_load_ps(f + 8)};
}
SM2_AVX2_INLINE Floats512 _mm512_loadu_ps(const void* p) {
    const auto* f = static_cast<const float*>(p);
    return {_mm256_loadu_ps(f), _mm256_loadu_ps(f + 8)};
}
SM2_AVX2_INLINE Doubles512 _mm512_loadu_pd(const void* p) {
    const auto* d = static_cast<const double*>(p);
    return {_mm256_loadu_pd(d), _mm256_loadu_pd(d + 4)};
}
SM2_AVX2_INLINE Ints512 _mm512_load_si512(const void* p) {
    const auto* v = static_cast<const __m256i*>(p);
    return {_mm256_load_si256(v), _mm256_load_si256(v + 1)};
}
SM2_AVX2_INLINE Ints512 _mm512_loadu_si512(const void* p) {
    const auto* v = static_cast<const __m256i*>(p);
    return {_mm256_loadu_si256(v), _mm256_loadu_si256(v + 1)};
}
SM2_AVX2_INLINE void _mm512_storeu_si512(void* p, Ints512 a) {
    auto* v = static_cast<__m256i*>(p);
    _mm256_storeu_si256(v, a.lo);
    _mm256_storeu_si256(v + 1, a.hi);
}
SM2_AVX2_INLINE void _mm512_store_ps(void* p, Floats512 a) {
    auto* f = static_cast<float*>(p);
    _mm256_store_ps(f, a.lo);
    _mm256_store_ps(f + 8, a.hi);
}
SM2_AVX2_INLINE void _mm512_storeu_ps(void* p, Floats512 a) {
    auto* f = static_cast<float*>(p);
    _mm256_storeu_ps(f, a.lo);
    _mm256_storeu_ps(f + 8, a.hi);
}
SM2_AVX2_INLINE void _mm512_storeu_pd(void* p, Doubles512 a) {
    auto* d = static_cast<double*>(p);
    _mm256_storeu_pd(d, a.lo);
    _mm256_storeu_pd(d + 4, a.hi);
}
SM2_AVX2_INLINE void _mm512_store_si512(void* p, Ints512 a) {
    auto* v = static_cast<__m256i*>(p);
    _mm256_store_si256(v, a.lo);
    _mm256_store_si256(v + 1, a.hi);
}

SM2_AVX2_INLINE Ints512 _mm512_castps_si512(Floats512 a) { return {_mm256_castps_si256(a.lo), _mm256_castps_si256(a.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_castsi512_ps(Ints512 a) { return {_mm256_castsi256_ps(a.lo), _mm256_castsi256_ps(a.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_castpd_ps(Doubles512 a) { return {_mm256_castpd_ps(a.lo), _mm256_castpd_ps(a.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_castps_pd(Floats512 a) { return {_mm256_castps_pd(a.lo), _mm256_castps_pd(a.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_castpd_si512(Doubles512 a) { return {_mm256_castpd_si256(a.lo), _mm256_castpd_si256(a.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_castsi512_pd(Ints512 a) { return {_mm256_castsi256_pd(a.lo), _mm256_castsi256_pd(a.hi)}; }
SM2_AVX2_INLINE __m256 _mm512_castps512_ps256(Floats512 a) { return a.lo; }
SM2_AVX2_INLINE __m256i _mm512_castsi512_si256(Ints512 a) { return a.lo; }
SM2_AVX2_INLINE __m128i _mm512_castsi512_si128(Ints512 a) { return _mm256_castsi256_si128(a.lo); }
// (The widening casts leave the upper lanes undefined in Intel's definition; here they are 0.)
SM2_AVX2_INLINE Floats512 _mm512_castps128_ps512(__m128 a) {
    return {_mm256_insertf128_ps(_mm256_setzero_ps(), a, 0), _mm256_setzero_ps()};
}
SM2_AVX2_INLINE Ints512 _mm512_castsi128_si512(__m128i a) {
    return {_mm256_inserti128_si256(_mm256_setzero_si256(), a, 0), _mm256_setzero_si256()};
}
SM2_AVX2_INLINE Ints512 _mm512_castsi256_si512(__m256i a) { return {a, _mm256_setzero_si256()}; }
SM2_AVX2_INLINE Doubles512 _mm512_castpd256_pd512(__m256d a) { return {a, _mm256_setzero_pd()}; }

SM2_AVX2_INLINE __m256d _mm512_extractf64x4_pd(Doubles512 a, int high) { return high & 1 ? a.hi : a.lo; }
SM2_AVX2_INLINE __m256i _mm512_extracti64x4_epi64(Ints512 a, int high) { return high & 1 ? a.hi : a.lo; }
SM2_AVX2_INLINE Doubles512 _mm512_insertf64x4(Doubles512 a, __m256d b, int high) {
    if (high & 1)
        a.hi = b;
    else
        a.lo = b;
    return a;
}
SM2_AVX2_INLINE Ints512 _mm512_inserti64x4(Ints512 a, __m256i b, int high) {
    if (high & 1)
        a.hi = b;
    else
        a.lo = b;
    return a;
}

// ---------------------------------------------------------------------------------------------
// Arithmetic and logic

SM2_AVX2_INLINE Floats512 _mm512_add_ps(Floats512 a, Floats512 b) { return {_mm256_add_ps(a.lo, b.lo), _mm256_add_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_sub_ps(Floats512 a, Floats512 b) { return {_mm256_sub_ps(a.lo, b.lo), _mm256_sub_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_mul_ps(Floats512 a, Floats512 b) { return {_mm256_mul_ps(a.lo, b.lo), _mm256_mul_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_div_ps(Floats512 a, Floats512 b) { return {_mm256_div_ps(a.lo, b.lo), _mm256_div_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_min_ps(Floats512 a, Floats512 b) { return {_mm256_min_ps(a.lo, b.lo), _mm256_min_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_max_ps(Floats512 a, Floats512 b) { return {_mm256_max_ps(a.lo, b.lo), _mm256_max_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_fmadd_ps(Floats512 a, Floats512 b, Floats512 c) {
    return {_mm256_fmadd_ps(a.lo, b.lo, c.lo), _mm256_fmadd_ps(a.hi, b.hi, c.hi)};
}
SM2_AVX2_INLINE Floats512 _mm512_fmsub_ps(Floats512 a, Floats512 b, Floats512 c) {
    return {_mm256_fmsub_ps(a.lo, b.lo, c.lo), _mm256_fmsub_ps(a.hi, b.hi, c.hi)};
}
SM2_AVX2_INLINE Floats512 _mm512_fnmadd_ps(Floats512 a, Floats512 b, Floats512 c) {
    return {_mm256_fnmadd_ps(a.lo, b.lo, c.lo), _mm256_fnmadd_ps(a.hi, b.hi, c.hi)};
}
SM2_AVX2_INLINE Floats512 _mm512_and_ps(Floats512 a, Floats512 b) { return {_mm256_and_ps(a.lo, b.lo), _mm256_and_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_or_ps(Floats512 a, Floats512 b) { return {_mm256_or_ps(a.lo, b.lo), _mm256_or_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_xor_ps(Floats512 a, Floats512 b) { return {_mm256_xor_ps(a.lo, b.lo), _mm256_xor_ps(a.hi, b.hi)}; }
SM2_AVX2_INLINE Floats512 _mm512_abs_ps(Floats512 a) {
    const __m256 magnitude = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF));
    return {_mm256_and_ps(a.lo, magnitude), _mm256_and_ps(a.hi, magnitude)};
}

SM2_AVX2_INLINE Doubles512 _mm512_add_pd(Doubles512 a, Doubles512 b) { return {_mm256_add_pd(a.lo, b.lo), _mm256_add_pd(a.hi, b.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_sub_pd(Doubles512 a, Doubles512 b) { return {_mm256_sub_pd(a.lo, b.lo), _mm256_sub_pd(a.hi, b.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_mul_pd(Doubles512 a, Doubles512 b) { return {_mm256_mul_pd(a.lo, b.lo), _mm256_mul_pd(a.hi, b.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_div_pd(Doubles512 a, Doubles512 b) { return {_mm256_div_pd(a.lo, b.lo), _mm256_div_pd(a.hi, b.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_sqrt_pd(Doubles512 a) { return {_mm256_sqrt_pd(a.lo), _mm256_sqrt_pd(a.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_max_pd(Doubles512 a, Doubles512 b) { return {_mm256_max_pd(a.lo, b.lo), _mm256_max_pd(a.hi, b.hi)}; }

SM2_AVX2_INLINE Ints512 _mm512_add_epi32(Ints512 a, Ints512 b) { return {_mm256_add_epi32(a.lo, b.lo), _mm256_add_epi32(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_sub_epi32(Ints512 a, Ints512 b) { return {_mm256_sub_epi32(a.lo, b.lo), _mm256_sub_epi32(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_add_epi64(Ints512 a, Ints512 b) { return {_mm256_add_epi64(a.lo, b.lo), _mm256_add_epi64(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_sub_epi64(Ints512 a, Ints512 b) { return {_mm256_sub_epi64(a.lo, b.lo), _mm256_sub_epi64(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_mullo_epi32(Ints512 a, Ints512 b) {
    return {_mm256_mullo_epi32(a.lo, b.lo), _mm256_mullo_epi32(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_min_epi32(Ints512 a, Ints512 b) { return {_mm256_min_epi32(a.lo, b.lo), _mm256_min_epi32(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_max_epi32(Ints512 a, Ints512 b) { return {_mm256_max_epi32(a.lo, b.lo), _mm256_max_epi32(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_and_si512(Ints512 a, Ints512 b) { return {_mm256_and_si256(a.lo, b.lo), _mm256_and_si256(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_or_si512(Ints512 a, Ints512 b) { return {_mm256_or_si256(a.lo, b.lo), _mm256_or_si256(a.hi, b.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_xor_si512(Ints512 a, Ints512 b) { return {_mm256_xor_si256(a.lo, b.lo), _mm256_xor_si256(a.hi, b.hi)}; }

// Shifts: counts above the element's width give 0 (arithmetic: the sign), in both instruction sets.
SM2_AVX2_INLINE Ints512 _mm512_slli_epi32(Ints512 a, unsigned count) {
    const __m128i n = _mm_cvtsi32_si128(static_cast<int>(count));
    return {_mm256_sll_epi32(a.lo, n), _mm256_sll_epi32(a.hi, n)};
}
SM2_AVX2_INLINE Ints512 _mm512_srli_epi32(Ints512 a, unsigned count) {
    const __m128i n = _mm_cvtsi32_si128(static_cast<int>(count));
    return {_mm256_srl_epi32(a.lo, n), _mm256_srl_epi32(a.hi, n)};
}
SM2_AVX2_INLINE Ints512 _mm512_srai_epi32(Ints512 a, unsigned count) {
    const __m128i n = _mm_cvtsi32_si128(static_cast<int>(count));
    return {_mm256_sra_epi32(a.lo, n), _mm256_sra_epi32(a.hi, n)};
}
SM2_AVX2_INLINE Ints512 _mm512_srli_epi64(Ints512 a, unsigned count) {
    const __m128i n = _mm_cvtsi32_si128(static_cast<int>(count));
    return {_mm256_srl_epi64(a.lo, n), _mm256_srl_epi64(a.hi, n)};
}
SM2_AVX2_INLINE Ints512 _mm512_srlv_epi32(Ints512 a, Ints512 count) {
    return {_mm256_srlv_epi32(a.lo, count.lo), _mm256_srlv_epi32(a.hi, count.hi)};
}

// Within each 128-bit block, as in AVX-512: the byte shuffle (an index byte with bit 7 set gives
// 0), the 16-bit multiply-adds of adjacent pairs, the interleaves, the 32-bit shuffle.
SM2_AVX2_INLINE Ints512 _mm512_shuffle_epi8(Ints512 a, Ints512 idx) {
    return {_mm256_shuffle_epi8(a.lo, idx.lo), _mm256_shuffle_epi8(a.hi, idx.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_madd_epi16(Ints512 a, Ints512 b) {
    return {_mm256_madd_epi16(a.lo, b.lo), _mm256_madd_epi16(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_mullo_epi16(Ints512 a, Ints512 b) {
    return {_mm256_mullo_epi16(a.lo, b.lo), _mm256_mullo_epi16(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_srli_epi16(Ints512 a, unsigned count) {
    const __m128i n = _mm_cvtsi32_si128(static_cast<int>(count));
    return {_mm256_srl_epi16(a.lo, n), _mm256_srl_epi16(a.hi, n)};
}
SM2_AVX2_INLINE Ints512 _mm512_unpacklo_epi32(Ints512 a, Ints512 b) {
    return {_mm256_unpacklo_epi32(a.lo, b.lo), _mm256_unpacklo_epi32(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_unpackhi_epi32(Ints512 a, Ints512 b) {
    return {_mm256_unpackhi_epi32(a.lo, b.lo), _mm256_unpackhi_epi32(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_unpacklo_epi64(Ints512 a, Ints512 b) {
    return {_mm256_unpacklo_epi64(a.lo, b.lo), _mm256_unpacklo_epi64(a.hi, b.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_unpackhi_epi64(Ints512 a, Ints512 b) {
    return {_mm256_unpackhi_epi64(a.lo, b.lo), _mm256_unpackhi_epi64(a.hi, b.hi)};
}
// (Broadcasts of one element of each block by their immediates, which an inlined call with a
// constant `order` folds to; any other order by VPERMILPS's per-lane control.)
SM2_AVX2_INLINE Ints512 _mm512_shuffle_epi32(Ints512 a, _MM_PERM_ENUM order) {
    switch (order) {
    case _MM_PERM_AAAA: return {_mm256_shuffle_epi32(a.lo, 0x00), _mm256_shuffle_epi32(a.hi, 0x00)};
    case _MM_PERM_BBBB: return {_mm256_shuffle_epi32(a.lo, 0x55), _mm256_shuffle_epi32(a.hi, 0x55)};
    case _MM_PERM_CCCC: return {_mm256_shuffle_epi32(a.lo, 0xAA), _mm256_shuffle_epi32(a.hi, 0xAA)};
    case _MM_PERM_DDDD: return {_mm256_shuffle_epi32(a.lo, 0xFF), _mm256_shuffle_epi32(a.hi, 0xFF)};
    default: break;
    }
    const int m = static_cast<int>(order);
    const __m256i control = _mm256_setr_epi32(m & 3, m >> 2 & 3, m >> 4 & 3, m >> 6 & 3, m & 3, m >> 2 & 3, m >> 4 & 3, m >> 6 & 3);
    return {_mm256_castps_si256(_mm256_permutevar_ps(_mm256_castsi256_ps(a.lo), control)),
            _mm256_castps_si256(_mm256_permutevar_ps(_mm256_castsi256_ps(a.hi), control))};
}

// ---------------------------------------------------------------------------------------------
// Conversions

SM2_AVX2_INLINE Floats512 _mm512_cvtepi32_ps(Ints512 a) { return {_mm256_cvtepi32_ps(a.lo), _mm256_cvtepi32_ps(a.hi)}; }
SM2_AVX2_INLINE Ints512 _mm512_cvttps_epi32(Floats512 a) { return {_mm256_cvttps_epi32(a.lo), _mm256_cvttps_epi32(a.hi)}; }
SM2_AVX2_INLINE Doubles512 _mm512_cvtps_pd(__m256 a) {
    return {_mm256_cvtps_pd(_mm256_castps256_ps128(a)), _mm256_cvtps_pd(_mm256_extractf128_ps(a, 1))};
}
SM2_AVX2_INLINE __m256 _mm512_cvtpd_ps(Doubles512 a) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm256_cvtpd_ps(a.lo)), _mm256_cvtpd_ps(a.hi), 1);
}
SM2_AVX2_INLINE __m256i _mm512_cvttpd_epi32(Doubles512 a) {
    return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm256_cvttpd_epi32(a.lo)), _mm256_cvttpd_epi32(a.hi), 1);
}
SM2_AVX2_INLINE Doubles512 _mm512_cvtepi32_pd(__m256i a) {
    return {_mm256_cvtepi32_pd(_mm256_castsi256_si128(a)), _mm256_cvtepi32_pd(_mm256_extracti128_si256(a, 1))};
}
SM2_AVX2_INLINE Ints512 _mm512_cvtepi32_epi64(__m256i a) {
    return {_mm256_cvtepi32_epi64(_mm256_castsi256_si128(a)), _mm256_cvtepi32_epi64(_mm256_extracti128_si256(a, 1))};
}
// AVX2 has no 64-bit integer to double conversion: each lane converted alone (rounded to nearest
// as the instruction does under the default rounding mode).
SM2_AVX2_INLINE Doubles512 _mm512_cvtepi64_pd(Ints512 a) {
    alignas(32) int64_t in[8];
    alignas(32) double out[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(in), a.lo);
    _mm256_store_si256(reinterpret_cast<__m256i*>(in + 4), a.hi);
    for (int i = 0; i < 8; ++i) out[i] = static_cast<double>(in[i]);
    return {_mm256_load_pd(out), _mm256_load_pd(out + 4)};
}

// roundscale with a scale of 0 (the immediate's high nibble) is round: its low nibble is the same
// rounding control as round's.
SM2_AVX2_INLINE __m256 round8(__m256 a, int control) {
    switch (control & 0x0F) {
    case _MM_FROUND_TO_NEAREST_INT: return _mm256_round_ps(a, _MM_FROUND_TO_NEAREST_INT);
    case _MM_FROUND_TO_NEG_INF: return _mm256_round_ps(a, _MM_FROUND_TO_NEG_INF);
    case _MM_FROUND_TO_POS_INF: return _mm256_round_ps(a, _MM_FROUND_TO_POS_INF);
    case _MM_FROUND_TO_ZERO: return _mm256_round_ps(a, _MM_FROUND_TO_ZERO);
    case _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC: return _mm256_round_ps(a, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC: return _mm256_round_ps(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC: return _mm256_round_ps(a, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC: return _mm256_round_ps(a, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
    default: return _mm256_round_ps(a, _MM_FROUND_CUR_DIRECTION);
    }
}
SM2_AVX2_INLINE __m256d round4(__m256d a, int control) {
    switch (control & 0x0F) {
    case _MM_FROUND_TO_NEAREST_INT: return _mm256_round_pd(a, _MM_FROUND_TO_NEAREST_INT);
    case _MM_FROUND_TO_NEG_INF: return _mm256_round_pd(a, _MM_FROUND_TO_NEG_INF);
    case _MM_FROUND_TO_POS_INF: return _mm256_round_pd(a, _MM_FROUND_TO_POS_INF);
    case _MM_FROUND_TO_ZERO: return _mm256_round_pd(a, _MM_FROUND_TO_ZERO);
    case _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC: return _mm256_round_pd(a, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC: return _mm256_round_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC: return _mm256_round_pd(a, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
    case _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC: return _mm256_round_pd(a, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
    default: return _mm256_round_pd(a, _MM_FROUND_CUR_DIRECTION);
    }
}
SM2_AVX2_INLINE Floats512 _mm512_roundscale_ps(Floats512 a, int control) { return {round8(a.lo, control), round8(a.hi, control)}; }
SM2_AVX2_INLINE Doubles512 _mm512_roundscale_pd(Doubles512 a, int control) { return {round4(a.lo, control), round4(a.hi, control)}; }
SM2_AVX2_INLINE __m256 _mm256_roundscale_ps(__m256 a, int control) { return round8(a, control); }

// ---------------------------------------------------------------------------------------------
// Compares into masks

// _mm256_cmp_ps/_pd for a predicate that is a constant only once inlined.
SM2_AVX2_INLINE __m256 compare8(__m256 a, __m256 b, int predicate) {
    switch (predicate) {
    case _CMP_EQ_OQ: return _mm256_cmp_ps(a, b, _CMP_EQ_OQ);
    case _CMP_LT_OS: return _mm256_cmp_ps(a, b, _CMP_LT_OS);
    case _CMP_LE_OS: return _mm256_cmp_ps(a, b, _CMP_LE_OS);
    case _CMP_UNORD_Q: return _mm256_cmp_ps(a, b, _CMP_UNORD_Q);
    case _CMP_NEQ_UQ: return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ);
    case _CMP_NLT_US: return _mm256_cmp_ps(a, b, _CMP_NLT_US);
    case _CMP_NLE_US: return _mm256_cmp_ps(a, b, _CMP_NLE_US);
    case _CMP_ORD_Q: return _mm256_cmp_ps(a, b, _CMP_ORD_Q);
    case _CMP_EQ_UQ: return _mm256_cmp_ps(a, b, _CMP_EQ_UQ);
    case _CMP_NGE_US: return _mm256_cmp_ps(a, b, _CMP_NGE_US);
    case _CMP_NGT_US: return _mm256_cmp_ps(a, b, _CMP_NGT_US);
    case _CMP_FALSE_OQ: return _mm256_cmp_ps(a, b, _CMP_FALSE_OQ);
    case _CMP_NEQ_OQ: return _mm256_cmp_ps(a, b, _CMP_NEQ_OQ);
    case _CMP_GE_OS: return _mm256_cmp_ps(a, b, _CMP_GE_OS);
    case _CMP_GT_OS: return _mm256_cmp_ps(a, b, _CMP_GT_OS);
    case _CMP_TRUE_UQ: return _mm256_cmp_ps(a, b, _CMP_TRUE_UQ);
    case _CMP_EQ_OS: return _mm256_cmp_ps(a, b, _CMP_EQ_OS);
    case _CMP_LT_OQ: return _mm256_cmp_ps(a, b, _CMP_LT_OQ);
    case _CMP_LE_OQ: return _mm256_cmp_ps(a, b, _CMP_LE_OQ);
    case _CMP_UNORD_S: return _mm256_cmp_ps(a, b, _CMP_UNORD_S);
    case _CMP_NEQ_US: return _mm256_cmp_ps(a, b, _CMP_NEQ_US);
    case _CMP_NLT_UQ: return _mm256_cmp_ps(a, b, _CMP_NLT_UQ);
    case _CMP_NLE_UQ: return _mm256_cmp_ps(a, b, _CMP_NLE_UQ);
    case _CMP_ORD_S: return _mm256_cmp_ps(a, b, _CMP_ORD_S);
    case _CMP_EQ_US: return _mm256_cmp_ps(a, b, _CMP_EQ_US);
    case _CMP_NGE_UQ: return _mm256_cmp_ps(a, b, _CMP_NGE_UQ);
    case _CMP_NGT_UQ: return _mm256_cmp_ps(a, b, _CMP_NGT_UQ);
    case _CMP_FALSE_OS: return _mm256_cmp_ps(a, b, _CMP_FALSE_OS);
    case _CMP_NEQ_OS: return _mm256_cmp_ps(a, b, _CMP_NEQ_OS);
    case _CMP_GE_OQ: return _mm256_cmp_ps(a, b, _CMP_GE_OQ);
    case _CMP_GT_OQ: return _mm256_cmp_ps(a, b, _CMP_GT_OQ);
    default: return _mm256_cmp_ps(a, b, _CMP_TRUE_US);
    }
}
SM2_AVX2_INLINE __m256d compare4(__m256d a, __m256d b, int predicate) {
    switch (predicate) {
    case _CMP_EQ_OQ: return _mm256_cmp_pd(a, b, _CMP_EQ_OQ);
    case _CMP_LT_OS: return _mm256_cmp_pd(a, b, _CMP_LT_OS);
    case _CMP_LE_OS: return _mm256_cmp_pd(a, b, _CMP_LE_OS);
    case _CMP_UNORD_Q: return _mm256_cmp_pd(a, b, _CMP_UNORD_Q);
    case _CMP_NEQ_UQ: return _mm256_cmp_pd(a, b, _CMP_NEQ_UQ);
    case _CMP_NLT_US: return _mm256_cmp_pd(a, b, _CMP_NLT_US);
    case _CMP_NLE_US: return _mm256_cmp_pd(a, b, _CMP_NLE_US);
    case _CMP_ORD_Q: return _mm256_cmp_pd(a, b, _CMP_ORD_Q);
    case _CMP_EQ_UQ: return _mm256_cmp_pd(a, b, _CMP_EQ_UQ);
    case _CMP_NGE_US: return _mm256_cmp_pd(a, b, _CMP_NGE_US);
    case _CMP_NGT_US: return _mm256_cmp_pd(a, b, _CMP_NGT_US);
    case _CMP_FALSE_OQ: return _mm256_cmp_pd(a, b, _CMP_FALSE_OQ);
    case _CMP_NEQ_OQ: return _mm256_cmp_pd(a, b, _CMP_NEQ_OQ);
    case _CMP_GE_OS: return _mm256_cmp_pd(a, b, _CMP_GE_OS);
    case _CMP_GT_OS: return _mm256_cmp_pd(a, b, _CMP_GT_OS);
    case _CMP_TRUE_UQ: return _mm256_cmp_pd(a, b, _CMP_TRUE_UQ);
    case _CMP_EQ_OS: return _mm256_cmp_pd(a, b, _CMP_EQ_OS);
    case _CMP_LT_OQ: return _mm256_cmp_pd(a, b, _CMP_LT_OQ);
    case _CMP_LE_OQ: return _mm256_cmp_pd(a, b, _CMP_LE_OQ);
    case _CMP_UNORD_S: return _mm256_cmp_pd(a, b, _CMP_UNORD_S);
    case _CMP_NEQ_US: return _mm256_cmp_pd(a, b, _CMP_NEQ_US);
    case _CMP_NLT_UQ: return _mm256_cmp_pd(a, b, _CMP_NLT_UQ);
    case _CMP_NLE_UQ: return _mm256_cmp_pd(a, b, _CMP_NLE_UQ);
    case _CMP_ORD_S: return _mm256_cmp_pd(a, b, _CMP_ORD_S);
    case _CMP_EQ_US: return _mm256_cmp_pd(a, b, _CMP_EQ_US);
    case _CMP_NGE_UQ: return _mm256_cmp_pd(a, b, _CMP_NGE_UQ);
    case _CMP_NGT_UQ: return _mm256_cmp_pd(a, b, _CMP_NGT_UQ);
    case _CMP_FALSE_OS: return _mm256_cmp_pd(a, b, _CMP_FALSE_OS);
    case _CMP_NEQ_OS: return _mm256_cmp_pd(a, b, _CMP_NEQ_OS);
    case _CMP_GE_OQ: return _mm256_cmp_pd(a, b, _CMP_GE_OQ);
    case _CMP_GT_OQ: return _mm256_cmp_pd(a, b, _CMP_GT_OQ);
    default: return _mm256_cmp_pd(a, b, _CMP_TRUE_US);
    }
}
SM2_AVX2_INLINE __mmask16 _mm512_cmp_ps_mask(Floats512 a, Floats512 b, int predicate) {
    return mask32(_mm256_castps_si256(compare8(a.lo, b.lo, predicate)), _mm256_castps_si256(compare8(a.hi, b.hi, predicate)));
}
SM2_AVX2_INLINE __mmask8 _mm512_cmp_pd_mask(Doubles512 a, Doubles512 b, int predicate) {
    return mask64(_mm256_castpd_si256(compare4(a.lo, b.lo, predicate)), _mm256_castpd_si256(compare4(a.hi, b.hi, predicate)));
}
SM2_AVX2_INLINE __mmask8 _mm256_cmp_ps_mask(__m256 a, __m256 b, int predicate) {
    return static_cast<__mmask8>(_mm256_movemask_ps(compare8(a, b, predicate)));
}

SM2_AVX2_INLINE __mmask16 _mm512_cmpeq_epi32_mask(Ints512 a, Ints512 b) {
    return mask32(_mm256_cmpeq_epi32(a.lo, b.lo), _mm256_cmpeq_epi32(a.hi, b.hi));
}
SM2_AVX2_INLINE __mmask16 _mm512_cmpneq_epi32_mask(Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(~_mm512_cmpeq_epi32_mask(a, b));
}
SM2_AVX2_INLINE __mmask16 _mm512_cmplt_epi32_mask(Ints512 a, Ints512 b) {
    return mask32(_mm256_cmpgt_epi32(b.lo, a.lo), _mm256_cmpgt_epi32(b.hi, a.hi));
}
SM2_AVX2_INLINE __mmask16 _mm512_cmpge_epi32_mask(Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(~_mm512_cmplt_epi32_mask(a, b));
}
// Unsigned compares: both sides' sign bits flipped turn them into signed ones.
SM2_AVX2_INLINE __mmask16 _mm512_cmplt_epu32_mask(Ints512 a, Ints512 b) {
    const __m256i flip = _mm256_set1_epi32(INT32_MIN);
    return mask32(_mm256_cmpgt_epi32(_mm256_xor_si256(b.lo, flip), _mm256_xor_si256(a.lo, flip)),
                  _mm256_cmpgt_epi32(_mm256_xor_si256(b.hi, flip), _mm256_xor_si256(a.hi, flip)));
}
SM2_AVX2_INLINE __mmask16 _mm512_cmpge_epu32_mask(Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(~_mm512_cmplt_epu32_mask(a, b));
}
SM2_AVX2_INLINE __mmask16 _mm512_mask_cmpeq_epi32_mask(__mmask16 k, Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(k & _mm512_cmpeq_epi32_mask(a, b));
}
SM2_AVX2_INLINE __mmask16 _mm512_mask_cmpneq_epi32_mask(__mmask16 k, Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(k & _mm512_cmpneq_epi32_mask(a, b));
}
SM2_AVX2_INLINE __mmask16 _mm512_mask_cmple_epi32_mask(__mmask16 k, Ints512 a, Ints512 b) {
    return static_cast<__mmask16>(k & ~mask32(_mm256_cmpgt_epi32(a.lo, b.lo), _mm256_cmpgt_epi32(a.hi, b.hi)));
}
// 64-bit lanes: a >= b where k has the lane's bit, as no b > a.
SM2_AVX2_INLINE __mmask8 _mm512_mask_cmpge_epi64_mask(__mmask8 k, Ints512 a, Ints512 b) {
    return static_cast<__mmask8>(k & ~mask64(_mm256_cmpgt_epi64(b.lo, a.lo), _mm256_cmpgt_epi64(b.hi, a.hi)));
}
SM2_AVX2_INLINE __mmask16 _mm512_movepi32_mask(Ints512 a) { return mask32(a.lo, a.hi); }

// ---------------------------------------------------------------------------------------------
// Masked moves and operations: lanes outside the mask keep `src` (maskz: become 0)

SM2_AVX2_INLINE __m256i select32(__m256i src, unsigned k, bool high, __m256i a) {
    return _mm256_castps_si256(
        _mm256_blendv_ps(_mm256_castsi256_ps(src), _mm256_castsi256_ps(a), _mm256_castsi256_ps(lanes32(k, high))));
}
SM2_AVX2_INLINE __m256i select64(__m256i src, unsigned k, bool high, __m256i a) {
    return _mm256_castpd_si256(
        _mm256_blendv_pd(_mm256_castsi256_pd(src), _mm256_castsi256_pd(a), _mm256_castsi256_pd(lanes64(k, high))));
}
SM2_AVX2_INLINE Ints512 _mm512_mask_mov_epi32(Ints512 src, __mmask16 k, Ints512 a) {
    return {select32(src.lo, k, false, a.lo), select32(src.hi, k, true, a.hi)};
}
SM2_AVX2_INLINE Ints512 _mm512_maskz_mov_epi32(__mmask16 k, Ints512 a) {
    return _mm512_mask_mov_epi32(_mm512_setzero_si512(), k, a);
}
SM2_AVX2_INLINE Floats512 _mm512_mask_mov_ps(Floats512 src, __mmask16 k, Floats512 a) {
    return _mm512_castsi512_ps(_mm512_mask_mov_epi32(_mm512_castps_si512(src), k, _mm512_castps_si512(a)));
}
SM2_AVX2_INLINE Floats512 _mm512_maskz_mov_ps(__mmask16 k, Floats512 a) { return _mm512_mask_mov_ps(_mm512_setzero_ps(), k, a); }
SM2_AVX2_INLINE Doubles512 _mm512_mask_mov_pd(Doubles512 src, __mmask8 k, Doubles512 a) {
    const Ints512 s = _mm512_castpd_si512(src), v = _mm512_castpd_si512(a);
    return _mm512_castsi512_pd({select64(s.lo, k, false, v.lo), select64(s.hi, k, true, v.hi)});
}
SM2_AVX2_INLINE Doubles512 _mm512_maskz_mov_pd(__mmask8 k, Doubles512 a) { return _mm512_mask_mov_pd(_mm512_setzero_pd(), k, a); }
SM2_AVX2_INLINE __m256 _mm256_mask_mov_ps(__m256 src, __mmask8 k, __m256 a) {
    return _mm256_castsi256_ps(select32(_mm256_castps_si256(src), k, false, _mm256_castps_si256(a)));
}
SM2_AVX2_INLINE __m256i _mm256_mask_mov_epi32(__m256i src, __mmask8 k, __m256i a) { return select32(src, k, false, a); }

// Masked loads and stores: lanes outside the mask neither read (they load 0) nor write, and
// cannot fault, as with AVX2's maskload/maskstore.
SM2_AVX2_INLINE __m256i _mm256_maskz_loadu_epi32(__mmask8 k, const void* p) {
    return _mm256_maskload_epi32(static_cast<const int*>(p), lanes32(k, false));
}
SM2_AVX2_INLINE void _mm256_mask_storeu_epi32(void* p, __mmask8 k, __m256i a) {
    _mm256_maskstore_epi32(static_cast<int*>(p), lanes32(k, false), a);
}
SM2_AVX2_INLINE Ints512 _mm512_maskz_loadu_epi32(__mmask16 k, const void* p) {
    const auto* q = static_cast<const int*>(p);
    return {_mm256_maskload_epi32(q, lanes32(k, false)), _mm256_maskload_epi32(q + 8, lanes32(k, true))};
}
SM2_AVX2_INLINE Ints512 _mm512_maskz_loadu_epi64(__mmask8 k, const void* p) {
    const auto* q = static_cast<const long long*>(p);
    return {_mm256_maskload_epi64(q, lanes64(k, false)), _mm256_maskload_epi64(q + 4, lanes64(k, true))};
}
SM2_AVX2_INLINE void _mm512_mask_storeu_epi64(void* p, __mmask8 k, Ints512 a) {
    auto* q = static_cast<long long*>(p);
    _mm256_maskstore_epi64(q, lanes64(k, false), a.lo);
    _mm256_maskstore_epi64(q + 4, lanes64(k, true), a.hi);
}

SM2_AVX2_INLINE Ints512 _mm512_mask_add_epi32(Ints512 src, __mmask16 k, Ints512 a, Ints512 b) {
    return _mm512_mask_mov_epi32(src, k, _mm512_add_epi32(a, b));
}
SM2_AVX2_INLINE Ints512 _mm512_mask_sub_epi32(Ints512 src, __mmask16 k, Ints512 a, Ints512 b) {
    return _mm512_mask_mov_epi32(src, k, _mm512_sub_epi32(a, b));
}
SM2_AVX2_INLINE Ints512 _mm512_mask_or_epi32(Ints512 src, __mmask16 k, Ints512 a, Ints512 b) {
    return _mm512_mask_mov_epi32(src, k, _mm512_or_si512(a, b));
}
SM2_AVX2_INLINE Doubles512 _mm512_mask_add_pd(Doubles512 src, __mmask8 k, Doubles512 a, Doubles512 b) {
    return _mm512_mask_mov_pd(src, k, _mm512_add_pd(a, b));
}
SM2_AVX2_INLINE Doubles512 _mm512_mask_sub_pd(Doubles512 src, __mmask8 k, Doubles512 a, Doubles512 b) {
    return _mm512_mask_mov_pd(src, k, _mm512_sub_pd(a, b));
}
SM2_AVX2_INLINE Doubles512 _mm512_mask_mul_pd(Doubles512 src, __mmask8 k, Doubles512 a, Doubles512 b) {
    return _mm512_mask_mov_pd(src, k, _mm512_mul_pd(a, b));
}

// ---------------------------------------------------------------------------------------------
// Permutes: each index's low bits choose a lane of `a` (permutex2var: one more bit chooses `b`)

// Lane idx & 15 of {lo, hi}, for the eight indices of `idx`.
SM2_AVX2_INLINE __m256i pick16(__m256i lo, __m256i hi, __m256i idx) {
    const __m256i from_lo = _mm256_permutevar8x32_epi32(lo, idx), from_hi = _mm256_permutevar8x32_epi32(hi, idx);
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(from_lo), _mm256_castsi256_ps(from_hi),
                                                _mm256_castsi256_ps(_mm256_slli_epi32(idx, 28))));
}
SM2_AVX2_INLINE Ints512 _mm512_permutexvar_epi32(Ints512 idx, Ints512 a) {
    return {pick16(a.lo, a.hi, idx.lo), pick16(a.lo, a.hi, idx.hi)};
}
SM2_AVX2_INLINE Floats512 _mm512_permutexvar_ps(Ints512 idx, Floats512 a) {
    return _mm512_castsi512_ps(_mm512_permutexvar_epi32(idx, _mm512_castps_si512(a)));
}
// Lane idx & 31 of {a, b}: bit 4 chooses b.
SM2_AVX2_INLINE __m256i pick32(Ints512 a, Ints512 b, __m256i idx) {
    const __m256i from_a = pick16(a.lo, a.hi, idx), from_b = pick16(b.lo, b.hi, idx);
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(from_a), _mm256_castsi256_ps(from_b),
                                                _mm256_castsi256_ps(_mm256_slli_epi32(idx, 27))));
}
SM2_AVX2_INLINE Ints512 _mm512_permutex2var_epi32(Ints512 a, Ints512 idx, Ints512 b) {
    return {pick32(a, b, idx.lo), pick32(a, b, idx.hi)};
}
SM2_AVX2_INLINE Floats512 _mm512_permutex2var_ps(Floats512 a, Ints512 idx, Floats512 b) {
    return _mm512_castsi512_ps(_mm512_permutex2var_epi32(_mm512_castps_si512(a), idx, _mm512_castps_si512(b)));
}
SM2_AVX2_INLINE Ints512 _mm512_maskz_permutex2var_epi32(__mmask16 k, Ints512 a, Ints512 idx, Ints512 b) {
    return _mm512_maskz_mov_epi32(k, _mm512_permutex2var_epi32(a, idx, b));
}
// Lanes shift..shift + 15 of b's 16 lanes followed by a's.
SM2_AVX2_INLINE Ints512 _mm512_alignr_epi32(Ints512 a, Ints512 b, int shift) {
    const Ints512 lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    return _mm512_permutex2var_epi32(b, _mm512_add_epi32(lane, _mm512_set1_epi32(shift & 15)), a);
}
// 16-bit lanes: lane idx & 63 of the 64 lanes of {a, b}, one by one (the kernels take their
// 16-bit permutes in the AVX-512 instance alone, kOneRegister).
SM2_AVX2_INLINE Ints512 _mm512_permutex2var_epi16(Ints512 a, Ints512 idx, Ints512 b) {
    alignas(32) uint16_t table[64], index[32], out[32];
    _mm512_store_si512(table, a);
    _mm512_store_si512(table + 32, b);
    _mm512_store_si512(index, idx);
    for (unsigned l = 0; l < 32; ++l) out[l] = table[index[l] & 63u];
    return _mm512_load_si512(out);
}
// The 32-bit lanes 2j and 2j + 1 of each 64-bit lane index j (`lanes`: j's mask, 7 or 15), by
// 64-bit shifts, which the compiler folds for a constant index (it does not fold VPERMD).
SM2_AVX2_INLINE __m256i dword_pairs(__m256i j, long long lanes) {
    j = _mm256_and_si256(j, _mm256_set1_epi64x(lanes));
    return _mm256_or_si256(_mm256_or_si256(_mm256_slli_epi64(j, 1), _mm256_slli_epi64(j, 33)), _mm256_set1_epi64x(1LL << 32));
}
// 64-bit lanes: lane idx & 7 of a's 8.
SM2_AVX2_INLINE Ints512 _mm512_permutexvar_epi64(Ints512 idx, Ints512 a) {
    return {pick16(a.lo, a.hi, dword_pairs(idx.lo, 7)), pick16(a.lo, a.hi, dword_pairs(idx.hi, 7))};
}
// 64-bit lanes: lane idx & 15 of the 16 lanes of {a, b}.
SM2_AVX2_INLINE Ints512 _mm512_permutex2var_epi64(Ints512 a, Ints512 idx, Ints512 b) {
    return {pick32(a, b, dword_pairs(idx.lo, 15)), pick32(a, b, dword_pairs(idx.hi, 15))};
}

// ---------------------------------------------------------------------------------------------
// Gathers: lanes outside the mask keep `src` and read nothing. AVX2's gathers take the scale as
// an immediate: the switches pick it once the call is inlined.

#define SM2_AVX2_GATHER_SCALES(call) \
    switch (scale) {                 \
    case 1: return call(1);          \
    case 2: return call(2);          \
    case 4: return call(4);          \
    default: return call(8);         \
    }

SM2_AVX2_INLINE __m256i gather32_i32(__m256i src, const void* base, __m256i idx, __m256i mask, int scale) {
    const auto* b = static_cast<const int*>(base);
#define SM2_CALL(s) _mm256_mask_i32gather_epi32(src, b, idx, mask, s)
    SM2_AVX2_GATHER_SCALES(SM2_CALL)
#undef SM2_CALL
}
SM2_AVX2_INLINE __m256i gather64_i32(__m256i src, const void* base, __m128i idx, __m256i mask, int scale) {
    const auto* b = static_cast<const long long*>(base);
#define SM2_CALL(s) _mm256_mask_i32gather_epi64(src, b, idx, mask, s)
    SM2_AVX2_GATHER_SCALES(SM2_CALL)
#undef SM2_CALL
}
SM2_AVX2_INLINE __m128i gather32_i64(__m128i src, const void* base, __m256i idx, __m128i mask, int scale) {
    const auto* b = static_cast<const int*>(base);
#define SM2_CALL(s) _mm256_mask_i64gather_epi32(src, b, idx, mask, s)
    SM2_AVX2_GATHER_SCALES(SM2_CALL)
#undef SM2_CALL
}
SM2_AVX2_INLINE __m256i gather64_i64(__m256i src, const void* base, __m256i idx, __m256i mask, int scale) {
    const auto* b = static_cast<const long long*>(base);
#define SM2_CALL(s) _mm256_mask_i64gather_epi64(src, b, idx, mask, s)
    SM2_AVX2_GATHER_SCALES(SM2_CALL)
#undef SM2_CALL
}
#undef SM2_AVX2_GATHER_SCALES

SM2_AVX2_INLINE Ints512 _mm512_mask_i32gather_epi32(Ints512 src, __mmask16 k, Ints512 idx, const void* base, int scale) {
    return {gather32_i32(src.lo, base, idx.lo, lanes32(k, false), scale),
            gather32_i32(src.hi, base, idx.hi, lanes32(k, true), scale)};
}
SM2_AVX2_INLINE Ints512 _mm512_i32gather_epi32(Ints512 idx, const void* base, int scale) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xFFFF, idx, base, scale);
}
SM2_AVX2_INLINE Floats512 _mm512_i32gather_ps(Ints512 idx, const void* base, int scale) {
    return _mm512_castsi512_ps(_mm512_i32gather_epi32(idx, base, scale));
}
SM2_AVX2_INLINE Ints512 _mm512_mask_i32gather_epi64(Ints512 src, __mmask8 k, __m256i idx, const void* base, int scale) {
    // Every lane: eight scalar loads. On Zen 3 the two VPGATHERDQs of four took the filter kernel
    // 11% longer (its share of bench_1024's profile, 42.9% -> 38.6%); the 32-bit gathers
    // (VPGATHERDD of eight) measured no better as loads and stay gathers.
    if (k == 0xFF) {
        alignas(32) int32_t at[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(at), idx);
        const auto* b = static_cast<const char*>(base);
        long long v[8];
        for (unsigned i = 0; i < 8; ++i) std::memcpy(&v[i], b + static_cast<ptrdiff_t>(at[i]) * scale, 8);
        return {_mm256_setr_epi64x(v[0], v[1], v[2], v[3]), _mm256_setr_epi64x(v[4], v[5], v[6], v[7])};
    }
    return {gather64_i32(src.lo, base, _mm256_castsi256_si128(idx), lanes64(k, false), scale),
            gather64_i32(src.hi, base, _mm256_extracti128_si256(idx, 1), lanes64(k, true), scale)};
}
SM2_AVX2_INLINE Ints512 _mm512_i32gather_epi64(__m256i idx, const void* base, int scale) {
    return _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), 0xFF, idx, base, scale);
}
SM2_AVX2_INLINE __m256i _mm512_mask_i64gather_epi32(__m256i src, __mmask8 k, Ints512 idx, const void* base, int scale) {
    // The 32-bit mask lanes of k's bits 0-3 and 4-7, as the 128-bit halves of lanes32(k).
    const __m256i mask = lanes32(k, false);
    const __m128i lo = gather32_i64(_mm256_castsi256_si128(src), base, idx.lo, _mm256_castsi256_si128(mask), scale);
    const __m128i hi = gather32_i64(_mm256_extracti128_si256(src, 1), base, idx.hi, _mm256_extracti128_si256(mask, 1), scale);
    return _mm256_inserti128_si256(_mm256_castsi128_si256(lo), hi, 1);
}
SM2_AVX2_INLINE Ints512 _mm512_mask_i64gather_epi64(Ints512 src, __mmask8 k, Ints512 idx, const void* base, int scale) {
    return {gather64_i64(src.lo, base, idx.lo, lanes64(k, false), scale),
            gather64_i64(src.hi, base, idx.hi, lanes64(k, true), scale)};
}

// Scatters: AVX2 has none; the lanes of the mask are stored one by one from lane 0 up, so that
// of two lanes at one address the higher one's value stays, as with AVX-512's scatters.
SM2_AVX2_INLINE void _mm512_mask_i32scatter_epi32(void* base, __mmask16 k, Ints512 idx, Ints512 v, int scale) {
    alignas(32) int32_t at[16], value[16];
    _mm512_store_si512(at, idx);
    _mm512_store_si512(value, v);
    for (unsigned l = 0; l < 16; ++l)
        if (k >> l & 1u)
            std::memcpy(static_cast<char*>(base) + static_cast<intptr_t>(at[l]) * scale, &value[l], sizeof(int32_t));
}
SM2_AVX2_INLINE void _mm512_mask_i32scatter_ps(void* base, __mmask16 k, Ints512 idx, Floats512 v, int scale) {
    _mm512_mask_i32scatter_epi32(base, k, idx, _mm512_castps_si512(v), scale);
}

// ---------------------------------------------------------------------------------------------
// Lane sets (unorm8_avx512.h): here a vector, all-ones on the lanes of the set, which a compare
// gives and a blend reads as it is.

using LaneSet = Ints512;
SM2_AVX2_INLINE LaneSet lanes_eq_epi32(Ints512 a, Ints512 b) {
    return {_mm256_cmpeq_epi32(a.lo, b.lo), _mm256_cmpeq_epi32(a.hi, b.hi)};
}
SM2_AVX2_INLINE LaneSet lanes_lt_epi32(Ints512 a, Ints512 b) {
    return {_mm256_cmpgt_epi32(b.lo, a.lo), _mm256_cmpgt_epi32(b.hi, a.hi)};
}
template <int Predicate>
SM2_AVX2_INLINE LaneSet lanes_cmp_ps(Floats512 a, Floats512 b) {
    return {_mm256_castps_si256(compare8(a.lo, b.lo, Predicate)), _mm256_castps_si256(compare8(a.hi, b.hi, Predicate))};
}
SM2_AVX2_INLINE LaneSet lanes_and(LaneSet a, LaneSet b) { return _mm512_and_si512(a, b); }
SM2_AVX2_INLINE LaneSet lanes_andnot(LaneSet a, LaneSet b) {  // b and not a
    return {_mm256_andnot_si256(a.lo, b.lo), _mm256_andnot_si256(a.hi, b.hi)};
}
SM2_AVX2_INLINE __mmask16 lanes_mask(LaneSet a) { return mask32(a.lo, a.hi); }
SM2_AVX2_INLINE Floats512 lanes_select_ps(Floats512 src, LaneSet s, Floats512 a) {
    return {_mm256_blendv_ps(src.lo, a.lo, _mm256_castsi256_ps(s.lo)), _mm256_blendv_ps(src.hi, a.hi, _mm256_castsi256_ps(s.hi))};
}
SM2_AVX2_INLINE Ints512 lanes_select_epi32(Ints512 src, LaneSet s, Ints512 a) {
    return _mm512_castps_si512(lanes_select_ps(_mm512_castsi512_ps(src), s, _mm512_castsi512_ps(a)));
}

// unorm8_avx512.h's floor_of_fmadd() for c = 0.5 (unorm8::encode_field()'s) and |a b + c| <
// 2^22, without embedded rounding: t = fl(a b + c) by one FMA, k = floor(t). Rounding is
// monotonic and the integers near a b + c are floats, so k is floor(a b + c) or one more, the
// latter only where t rounded up onto the integer k; then the residual fl(a b + (c - k)) (c - k
// exact, one rounding, which keeps the sign of a nonzero value) is negative, and its sign bit
// takes 1 off. (A zero residual is +0: a b + c = k exactly.)
SM2_AVX2_INLINE Ints512 floor_of_fmadd(Floats512 a, Floats512 b, Floats512 c) {
    const Floats512 k = _mm512_roundscale_ps(_mm512_fmadd_ps(a, b, c), _MM_FROUND_TO_NEG_INF);
    const Floats512 residual = _mm512_fmadd_ps(a, b, _mm512_sub_ps(c, k));
    return _mm512_add_epi32(_mm512_cvttps_epi32(k), _mm512_srai_epi32(_mm512_castps_si512(residual), 31));
}

// unorm8_avx512.h's nan_to_zero(): MAXPS(v, 0) + MINPS(v, 0) is v for every v but NaN, which
// both turn into their second operand, +0 (and -0 into +0).
SM2_AVX2_INLINE Floats512 nan_to_zero(Floats512 v) {
    const Floats512 zero = _mm512_setzero_ps();
    return _mm512_add_ps(_mm512_max_ps(v, zero), _mm512_min_ps(v, zero));
}

// unorm8_avx512.h's conversions, for the AVX2 instances.
#define SM2_BLOCK SM2_AVX2
namespace unorm8 {
#include "unorm8_kernels.inc"
}  // namespace unorm8
#undef SM2_BLOCK

}  // namespace sm2::runtime::avx2
