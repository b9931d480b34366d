// The block paths' CPU checks and target attributes, and the AVX-512 instance of the UNORM
// conversions of format_layout.h for 16 lanes (unorm8_kernels.inc; avx512_on_avx2.h holds the
// AVX2 instance), shared by the sampler's and the output merger's block paths (callers check
// the CPU before calling).
#pragma once

#include <cstdint>

#include <immintrin.h>

// Functions marked SM2_AVX512 run only where cpu_has_avx512() holds, SM2_AVX2 ones where
// cpu_has_avx2() does. Such a function calls no baseline (SSE) function in its loops: GCC does
// not always put a vzeroupper before the call, and the callee's SSE code then waits on the
// dirty upper halves (a quarter of scene 10's run on an Intel core). The scalar helpers it
// needs are inlined into it (sampler.cpp's SM2_SCALAR_HELPER); bench/sse_transitions.sh lists
// the calls of a build.
#define SM2_AVX512 __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw")))
#define SM2_AVX2 __attribute__((target("avx2,fma")))

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
                            __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
    return has;
}

// Whether this CPU runs SM2_AVX2 code (the block paths' instances for CPUs without AVX-512,
// avx512_on_avx2.h); asked once.
inline bool cpu_has_avx2() {
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return has;
}

// The reciprocal of a quotient v / max split as high = fl(1 / max) and low = fl(1 / max -
// high), so that v high + fl(v low), rounded once (unorm8::quotient_by()), is the correctly
// rounded v / max without a division, for max = 2^n - 1 (n <= 16) or a power of two times one,
// and v an integer float (the fields, the fixed8 filter's sums): the sum lies within 2^-47 of
// v / max relative to it (low's rounding and v low's each 2^-48), nearer than such a quotient
// lies to any rounding midpoint. sampler_block_test checks every field value of the formats'
// widths and every fixed8 sum of 1 to 10 bits against IEEE division; a one-off program checked
// every integer float up to max * 65536 for n = 1 to 16. `scale`, a power of two, multiplies
// the result exactly (both parts scaled alike).
struct SplitReciprocal {
    float high = 1.0f, low = 0.0f;
};
constexpr SplitReciprocal split_reciprocal(double max, double scale = 1.0) {
    const double r = scale / max;
    const auto high = static_cast<float>(r);
    return {high, static_cast<float>(r - static_cast<double>(high))};
}

}  // namespace sm2::runtime

namespace sm2::runtime::avx512 {

// The block kernels' value types, for the AVX-512 instances: the registers themselves.
using Floats512 = __m512;
using Ints512 = __m512i;
using Doubles512 = __m512d;

// A set of the 16 lanes for the kernels' selects (LaneSet): a mask register here; in the AVX2
// instance (avx512_on_avx2.h) a vector of all-ones and all-zeros lanes, so that a compare feeds
// its blends without the way through a 16-bit mask and back, two MOVMSKPS and a broadcast and
// shift per use. lanes_mask() gives the 16-bit mask where a kernel needs one (a branch, a
// masked load).
using LaneSet = __mmask16;
SM2_AVX512 __attribute__((always_inline)) inline LaneSet lanes_eq_epi32(Ints512 a, Ints512 b) {
    return _mm512_cmpeq_epi32_mask(a, b);
}
SM2_AVX512 __attribute__((always_inline)) inline LaneSet lanes_lt_epi32(Ints512 a, Ints512 b) {
    return _mm512_cmplt_epi32_mask(a, b);
}
template <int Predicate>
SM2_AVX512 __attribute__((always_inline)) inline LaneSet lanes_cmp_ps(Floats512 a, Floats512 b) {
    return _mm512_cmp_ps_mask(a, b, Predicate);
}
SM2_AVX512 __attribute__((always_inline)) inline LaneSet lanes_and(LaneSet a, LaneSet b) {
    return static_cast<LaneSet>(a & b);
}
SM2_AVX512 __attribute__((always_inline)) inline LaneSet lanes_andnot(LaneSet a, LaneSet b) {  // b and not a
    return static_cast<LaneSet>(~a & b);
}
SM2_AVX512 __attribute__((always_inline)) inline __mmask16 lanes_mask(LaneSet a) { return a; }
// `a` on the lanes of `s`, `src` on the others (_mm512_mask_mov_ps's order).
SM2_AVX512 __attribute__((always_inline)) inline Floats512 lanes_select_ps(Floats512 src, LaneSet s, Floats512 a) {
    return _mm512_mask_mov_ps(src, s, a);
}
SM2_AVX512 __attribute__((always_inline)) inline Ints512 lanes_select_epi32(Ints512 src, LaneSet s, Ints512 a) {
    return _mm512_mask_mov_epi32(src, s, a);
}

// floor(a b + c) as integers, exactly, where |a b + c| < 2^22 (unorm8::encode_field()): the FMA
// rounded toward -inf gives a float in [floor(y), y] for y = a b + c (floor(y), an integer
// below 2^24, is a float), whose conversion rounded toward -inf is floor(y). Two instructions
// with embedded rounding (the AVX2 instance, without it, corrects a rounded FMA by its
// residual: five more).
SM2_AVX512 __attribute__((always_inline)) inline Ints512 floor_of_fmadd(Floats512 a, Floats512 b, Floats512 c) {
    constexpr int kDown = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
    return _mm512_cvt_roundps_epi32(_mm512_fmadd_round_ps(a, b, c, kDown), kDown);
}

// v with NaN replaced by +0 (texel_space()'s no_nan()), every other value as it is: one
// VFIXUPIMMPS, whose table maps the two NaN classes to +0 and the six others to v (the AVX2
// instance takes MAXPS(v, 0) + MINPS(v, 0), which turns -0 into +0 too).
SM2_AVX512 __attribute__((always_inline)) inline Floats512 nan_to_zero(Floats512 v) {
    // One 4-bit token per input class, from bit 0: QNaN, SNaN, +-0, +1, -inf, +inf, negative,
    // positive; token 8 is +0, token 1 the input.
    constexpr int kNanToZero = 0x11111188;
    return _mm512_fixupimm_ps(v, v, _mm512_set1_epi32(kNanToZero), 0);
}

#define SM2_BLOCK SM2_AVX512
SM2_AVX512_CODE_BEGIN
namespace unorm8 {
#include "unorm8_kernels.inc"
}  // namespace unorm8
SM2_AVX512_CODE_END
#undef SM2_BLOCK

}  // namespace sm2::runtime::avx512

namespace sm2::runtime {
// The AVX-512 conversions, for the code that calls them outside namespace avx512 (the merger).
namespace unorm8 = avx512::unorm8;
}  // namespace sm2::runtime
