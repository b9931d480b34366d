// The numeric policy: every special value of the engine is decided here and nowhere else, and
// each decision is listed in docs/numerics.md with its source. The functions are templates over
// the storage type (float, or double in the fp64 reference mode) and small enough to inline
// into the interpreter's lane loops.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "sm2/emu/precision.h"

namespace sm2::emu::numerics {

template <typename Real>
constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// --- multiplication ---------------------------------------------------------------------
// D3D9 hardware multiplies "legacy" style: 0 * anything = +0, including 0 * inf and 0 * NaN
// (games depend on it; DXVK's d3d9 float emulation and AMD's v_mul_legacy do the same). Used
// by every product of the instruction set: mul, mad, dp2add, dp3, dp4, the matrix macros,
// lrp, crs, nrm, dst, lit.
template <typename Real>
inline Real mul(Real a, Real b) {
    // Computed unconditionally and selected with `|` rather than `||`: no branch, so the lane
    // loops stay vectorizable.
    const Real product = a * b;
    const bool neither_zero = (a != Real(0)) & (b != Real(0));  // (NaN != 0)
    return neither_zero ? product : Real(0);
}
// mad: the product rounded, then the sum rounded (no fused multiply-add).
template <typename Real>
inline Real mad(Real a, Real b, Real c) {
    return mul(a, b) + c;
}

// --- reciprocal and reciprocal square root --------------------------------------------------
// rcp of zero: +0 -> +inf; rcp of -0 -> -inf (IEEE sign of the reciprocal; D3D10 says the
// same). rcp(1) = 1 exactly (docs); rcp(+-inf) = +-0; NaN stays NaN.
template <typename Real>
inline Real rcp(Real x) {
    const Real reciprocal = Real(1) / x;  // IEEE division: +-inf for +-0, +-0 for +-inf
    return x == Real(1) ? Real(1) : reciprocal;
}

// rsq: 1/sqrt(|x|) (the sign is ignored); rsq of zero (either sign) = +inf; rsq(1) = 1
// exactly; rsq(inf) = 0; NaN stays NaN.
template <typename Real>
inline Real rsq(Real x) {
    const Real a = std::fabs(x);
    const Real reciprocal_root = Real(1) / std::sqrt(a);
    return a == Real(1) ? Real(1) : reciprocal_root;
}

// --- exponential, logarithm and power ---------------------------------------------------------
// On floats, exact exp, log and pow are the engine's own evaluation in double rather than the C
// library's: one rounding to float of a result good to about 2^-50 relative, so correctly
// rounded on every input measured (docs/numerics.md; glibc's exp2f, log2f and powf are not, on a
// few inputs in ten thousand). Branch-free and without 64-bit integer conversions (which have
// no AVX2 instruction), so the lane loops vectorize and compiled code runs 16 lanes at once.
// tests/emu/transcendentals_test.cpp holds the special values and a sample of the accuracy.

// log2(a) in double for a positive float a: the exponent of a's double plus log2 of its
// mantissa m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s), s = (m - 1) / (m + 1), by its series to
// s^19. a = 0 gives -1023 and a = inf 1024 (the callers take those apart); NaN gives NaN or
// anything (likewise).
inline double log2_in_double(float a) {
    const uint64_t bits = std::bit_cast<uint64_t>(static_cast<double>(a));
    // The biased exponent read as a double through 2^52 + k: exact, and a shift and an or
    // where converting a 64-bit integer would be a scalar instruction per lane.
    double e = std::bit_cast<double>((bits >> 52) | 0x4330000000000000ull) - (0x1p52 + 1023.0);
    double m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
    const bool high = m > 1.4142135623730951;
    m = high ? m * 0.5 : m;
    e = high ? e + 1.0 : e;
    const double s = (m - 1.0) / (m + 1.0);
    // p(y) = sum 2 / (2k + 1) y^k, y = s^2, k = 0..9, by Estrin's scheme: pairs of terms, then
    // pairs of pairs, so that the longest chain of dependent operations is 4 multiply-adds, not
    // Horner's 9 (the 16 lanes of a batch wait on that chain; the value differs from Horner's
    // in the last bits of the double alone). Each multiply-add fused (std::fma, one rounding):
    // a 512-bit operation fewer each, and the floats of exp, log and pow those of the unfused
    // series (docs/numerics.md: every float input of exp and log, a sample of pow's).
    const double y = s * s, y2 = y * y, y4 = y2 * y2, y8 = y4 * y4;
    const double a0 = std::fma(2.0 / 3.0, y, 2.0), a1 = std::fma(2.0 / 7.0, y, 2.0 / 5.0);
    const double a2 = std::fma(2.0 / 11.0, y, 2.0 / 9.0), a3 = std::fma(2.0 / 15.0, y, 2.0 / 13.0);
    const double a4 = std::fma(2.0 / 19.0, y, 2.0 / 17.0);
    const double b0 = std::fma(a1, y2, a0), b1 = std::fma(a3, y2, a2);
    const double p = std::fma(a4, y8, std::fma(b1, y4, b0));
    return std::fma(p * s, 1.4426950408889634, e);
}

// 2^t rounded once to float: t = n + f with n an integer and |f| <= 1/2, 2^f = e^(f ln 2) by its
// series to degree 12, 2^n built in the exponent field. t is clamped to [-200, 200] (float
// results 0 and inf beyond); a NaN t gives 1 (the callers choose NaN results themselves).
inline float exp2_rounded_to_float(double t) {
    t = t == t ? t : 0.0;
    t = t < -200.0 ? -200.0 : t;
    t = t > 200.0 ? 200.0 : t;
    // n = t rounded to an integer by adding 1.5 * 2^52: the sum's low bits are n in two's
    // complement, so 2^n's bits are (bits(sum) + 1023) << 52 (the sum's own exponent field
    // shifts out), again without a 64-bit integer conversion.
    const double shifted = t + 6755399441055744.0;
    const double n = shifted - 6755399441055744.0;
    const double x = (t - n) * 0.6931471805599453;
    // q(x) = sum x^k / k!, k = 0..12, by Estrin's scheme (as log2_in_double()'s series, fused
    // likewise): 4 dependent multiply-adds after the powers, not Horner's 12.
    const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    const double a0 = 1.0 + x, a1 = std::fma(1.0 / 6.0, x, 0.5), a2 = std::fma(1.0 / 120.0, x, 1.0 / 24.0);
    const double a3 = std::fma(1.0 / 5040.0, x, 1.0 / 720.0), a4 = std::fma(1.0 / 362880.0, x, 1.0 / 40320.0);
    const double a5 = std::fma(1.0 / 39916800.0, x, 1.0 / 3628800.0);
    const double b0 = std::fma(a1, x2, a0), b1 = std::fma(a3, x2, a2), b2 = std::fma(a5, x2, a4);
    const double q = std::fma(std::fma(1.0 / 479001600.0, x4, b2), x8, std::fma(b1, x4, b0));
    const double scale = std::bit_cast<double>((std::bit_cast<uint64_t>(shifted) + 1023u) << 52);
    return static_cast<float>(q * scale);
}

// exp: 2^x; exp(-inf) = 0, exp(+inf) = +inf, NaN stays NaN. expp (vs_2_0) is the same value
// (the docs only ask for 10 bits).
inline float exp2_float(float x) {
    const float result = exp2_rounded_to_float(static_cast<double>(x));
    return x == x ? result : x;
}
template <typename Real>
inline Real exp2(Real x) {
    if constexpr (std::is_same_v<Real, float>) return exp2_float(x);
    else return std::exp2(x);
}

// log: log2(|x|); log of zero (either sign) = -inf (hardware; the docs' pseudo-code says
// -FLT_MAX); log(inf) = inf; NaN stays NaN. logp (vs_2_0) is the same value.
// log's special values for a = |x|, around `finite`, the evaluation's result for a finite
// nonzero a: 0 -> -inf; inf and NaN stay. Selects only, so the lane loops vectorize (exact and
// fast log both).
inline float log2_special_values(float a, float finite) {
    const float special = a == 0.0f ? -kInfinity<float> : a;
    const bool not_finite_or_zero = (a == 0.0f) | (a == kInfinity<float>) | (a != a);
    return not_finite_or_zero ? special : finite;
}
inline float log2_float(float x) {
    const float a = std::fabs(x);
    return log2_special_values(a, static_cast<float>(log2_in_double(a)));
}
template <typename Real>
inline Real log2(Real x) {
    if constexpr (std::is_same_v<Real, float>) return log2_float(x);
    else return std::log2(std::fabs(x));
}

// pow: |base| ^ exponent with IEEE pow's special cases on the absolute base: 0^0 = 1,
// 0^(+y) = 0, 0^(-y) = +inf, x^0 = 1, 1^y = 1 (even for NaN y). On floats: 2^(exponent *
// log2|base|) with the product in double, rounded once; measured against long double powl over
// 5 * 10^7 inputs, every result in the normal range within 0.5 ulp.
inline float pow_float(float base, float exponent) {
    const float a = std::fabs(base);
    // (A NaN product, from a NaN operand or 0 * inf, has its result chosen by the special
    // cases below.)
    float result = exp2_rounded_to_float(static_cast<double>(exponent) * log2_in_double(a));
    const float inf = std::numeric_limits<float>::infinity();
    result = a == 0.0f ? (exponent > 0.0f ? 0.0f : inf) : result;
    result = a == inf ? (exponent > 0.0f ? inf : 0.0f) : result;
    result = ((a != a) | (exponent != exponent)) ? std::numeric_limits<float>::quiet_NaN() : result;
    return ((exponent == 0.0f) | (a == 1.0f)) ? 1.0f : result;
}

// pow_float() for a batch whose exponent is one integer n in [1, 256] on every lane (a constant,
// as specular exponents are): |base|^n as a product of doubles by repeated squaring. A product
// of n factors carries a relative error of at most (n - 1) 2^-53 / (1 - (n - 1) 2^-53) < 2^-45
// however it is grouped, so where r (1 - 2^-44) and r (1 + 2^-44) round to the same float, the
// exact power rounds to it too (rounding is monotonic): the correctly rounded result, which is
// what pow_float() gives. Returns false, with `out` unspecified, when a lane's rounding is not
// certain that way (an exact power on a rounding tie, or NaN): the caller then runs pow_float().
template <size_t N>
inline bool pow_float_integer(const std::array<float, N>& base, unsigned n, std::array<float, N>& out) {
    std::array<double, N> product, square;
    for (size_t l = 0; l < N; ++l) {
        square[l] = std::fabs(static_cast<double>(base[l]));
        product[l] = 1.0;
    }
    // The bits of n (at most 9) in a loop of fixed length, unrolled: where n is a constant (the
    // JIT's compiled shaders), the tests of its bits fold and no loop is left.
#pragma GCC unroll 9
    for (unsigned bit = 0; bit < 9; ++bit) {
        if (n >> bit & 1u)
            for (size_t l = 0; l < N; ++l) product[l] *= square[l];
        if (n >> bit <= 1u) break;
        for (size_t l = 0; l < N; ++l) square[l] *= square[l];
    }
    bool certain = true;
    for (size_t l = 0; l < N; ++l) {
        const float low = static_cast<float>(product[l] * (1.0 - 0x1p-44));
        const float high = static_cast<float>(product[l] * (1.0 + 0x1p-44));
        certain &= low == high;
        out[l] = low;
    }
    return certain;
}

// The exponent n of pow_float_integer() when every lane holds the same integer in [1, 256];
// 0 otherwise.
template <size_t N>
inline unsigned uniform_integer_exponent(const std::array<float, N>& exponent) {
    const float first = exponent[0];
    bool uniform = true;
    for (size_t l = 0; l < N; ++l) uniform &= exponent[l] == first;
    return uniform && first >= 1.0f && first <= 256.0f && first == std::trunc(first) ? static_cast<unsigned>(first) : 0u;
}

template <typename Real>
inline Real pow(Real base, Real exponent) {
    if constexpr (std::is_same_v<Real, float>) return pow_float(base, exponent);
    else return std::pow(std::fabs(base), exponent);
}

// --- comparisons: NaN follows the literal pseudo-code (a false test picks the second value) ---
template <typename Real>
inline Real min(Real a, Real b) { return a < b ? a : b; }
template <typename Real>
inline Real max(Real a, Real b) { return a >= b ? a : b; }
template <typename Real>
inline Real slt(Real a, Real b) { return a < b ? Real(1) : Real(0); }
template <typename Real>
inline Real sge(Real a, Real b) { return a >= b ? Real(1) : Real(0); }
// cmp: -0 >= 0 is true; NaN picks the third operand.
template <typename Real>
inline Real cmp(Real c, Real a, Real b) { return c >= Real(0) ? a : b; }
// sgn: -1, 0 (for +-0) or 1; NaN gives 1 (literal pseudo-code).
template <typename Real>
inline Real sgn(Real a) { return a < Real(0) ? Real(-1) : (a == Real(0) ? Real(0) : Real(1)); }

// _sat: clamp to [0, 1]; saturate(NaN) = 0 (D3D9 does not say; D3D10 defines 0); -0 -> +0.
template <typename Real>
inline Real saturate(Real x) {
    return x > Real(0) ? (x < Real(1) ? x : Real(1)) : Real(0);
}

// NaN results are stored as one bit pattern, the positive quiet NaN (D3D9 specifies no
// payload; GPUs return one canonical NaN). Which NaN an operation on two NaNs returns depends
// on the order the compiler happened to give its operands (x86 returns the first one), so
// without this the bytes of a NaN result would depend on the compiler: the interpreter built
// by g++ or by clang, or the JIT. Applied once, when a step's result is stored.
template <typename Real>
inline Real canonical_nan(Real x) {
    return x != x ? std::numeric_limits<Real>::quiet_NaN() : x;
}

// frc: x - floor(x), kept in [0, 1): a tiny negative x whose difference rounds up to 1 gives
// the largest value below 1. frc(+-inf) = NaN (inf - inf), NaN stays NaN.
template <typename Real>
inline Real frc(Real x) {
    constexpr Real below_one = Real(1) - std::numeric_limits<Real>::epsilon() / Real(2);  // nextafter(1, 0)
    const Real f = x - std::floor(x);
    return f >= Real(1) ? below_one : f;
}

// --- vector helpers ------------------------------------------------------------------------
// nrm of a zero vector: the docs' factor FLT_MAX (not rsq(0) = inf), so x, y, z come out as 0
// through the legacy multiply and w as w * FLT_MAX.
template <typename Real>
inline Real nrm_factor(Real length_squared) {
    return length_squared != Real(0) ? rsq(length_squared) : Real(std::numeric_limits<float>::max());
}

// lit: the specular power is clamped to [-127.9961, 127.9961] (8.8 fixed point in the docs).
constexpr float kLitPowerLimit = 127.9961f;
template <typename Real>
inline Real lit_power_clamp(Real p) {
    const Real limit = Real(kLitPowerLimit);
    return p < -limit ? -limit : (p > limit ? limit : p);
}

// mova: round to nearest, halves away from zero (Wine's sign(x) * floor(|x| + 0.5)). Values
// that are NaN or beyond +-2^24 become an address no constant has, so relative reads with it
// return (0,0,0,0).
constexpr int32_t kInvalidAddress = -(1 << 30);
template <typename Real>
inline int32_t mova_round(Real x) {
    const Real r = std::round(x);
    const bool valid = r >= Real(-16777216) && r <= Real(16777216);
    const auto address = static_cast<int32_t>(valid ? r : Real(0));
    return valid ? address : kInvalidAddress;
}

// texkill: a lane is discarded when any of the four components is below zero (Wine's test
// results on Windows hardware for SM2; -0 and NaN do not kill).
template <typename Real>
inline bool kills(Real x, Real y, Real z, Real w) {
    return (x < Real(0)) | (y < Real(0)) | (z < Real(0)) | (w < Real(0));
}

// --- fast transcendentals (Transcendentals::Fast) ----------------------------------------------
// Branch-free float approximations (selects only, no library calls) so the lane loops
// vectorize. Each meets the documented minimum precision of its instruction and keeps the
// special values of the exact functions above. Measured errors are in docs/numerics.md.
namespace fast {

// Rounds to the nearest integer (ties to even) for |x| < 2^22: adding 1.5 * 2^23 leaves no
// fraction bits.
inline float round_small(float x) {
    constexpr float kMagic = 12582912.0f;
    return (x + kMagic) - kMagic;
}

// 2^x: x = k + f with |f| <= 0.5; 2^f = e^(f ln 2) by its Taylor series to degree 7 (remainder
// below 2^-27); 2^k built in the exponent field in two halves so that 2^-151 .. 2^129 cover
// denormal results and overflow to inf. Documented minimum: 21 bits.
inline float exp2(float x) {
    const float clamped = x < -151.0f ? -151.0f : (x > 129.0f ? 129.0f : x);
    const float finite = x == x ? clamped : 0.0f;  // NaN is put back at the end
    const float k = round_small(finite);
    const float f = (finite - k) * 0.693147180559945309f;  // f * ln 2
    float p = 1.0f / 5040.0f;
    p = p * f + 1.0f / 720.0f;
    p = p * f + 1.0f / 120.0f;
    p = p * f + 1.0f / 24.0f;
    p = p * f + 1.0f / 6.0f;
    p = p * f + 0.5f;
    p = p * f + 1.0f;
    p = p * f + 1.0f;
    const auto exponent = static_cast<int32_t>(k);
    const int32_t half = exponent / 2;
    const int32_t rest = exponent - half;
    const float scale_a = std::bit_cast<float>(static_cast<uint32_t>(half + 127) << 23);
    const float scale_b = std::bit_cast<float>(static_cast<uint32_t>(rest + 127) << 23);
    const float result = p * scale_a * scale_b;
    return x == x ? result : x;
}

// log2(|x|): |x| = m * 2^e with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(s), s = (m-1)/(m+1),
// |s| <= 0.1716, by its series to s^11 (remainder below 2^-30). Denormals are scaled by 2^23
// first. 0 -> -inf, inf -> inf, NaN -> NaN. Documented minimum: 21 bits.
inline float log2(float x) {
    const float a = std::fabs(x);
    const bool denormal = a < 0x1p-126f;
    const float normal = denormal ? a * 0x1p23f : a;
    const auto bits = std::bit_cast<uint32_t>(normal);
    float exponent = static_cast<float>(static_cast<int32_t>(bits >> 23) - 127) - (denormal ? 23.0f : 0.0f);
    float m = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
    const bool high = m > 1.41421356f;
    m = high ? m * 0.5f : m;
    exponent = high ? exponent + 1.0f : exponent;
    const float s = (m - 1.0f) / (m + 1.0f);
    const float s2 = s * s;
    float p = 2.0f / 11.0f;
    p = p * s2 + 2.0f / 9.0f;
    p = p * s2 + 2.0f / 7.0f;
    p = p * s2 + 2.0f / 5.0f;
    p = p * s2 + 2.0f / 3.0f;
    p = p * s2 + 2.0f;
    const float result = exponent + (p * s) * 1.44269504088896341f;  // ln m / ln 2
    return log2_special_values(a, result);
}

// |base|^exponent = 2^(exponent * log2|base|) with the special cases of the exact pow: x^0 = 1
// and 1^y = 1 (even for NaN); 0 and inf come out of log2/exp2 right (0^+y = 0, 0^-y = inf).
// Documented minimum: 15 bits (the product's rounding costs about |exponent * log2|base|| *
// 2^-24 relative, at most 2^-17 for results inside the float range).
inline float pow(float base, float exponent) {
    const float a = std::fabs(base);
    const float result = exp2(exponent * log2(a));
    const bool always_one = (exponent == 0.0f) | (a == 1.0f);
    return always_one ? 1.0f : result;
}

// sin and cos: the angle is reduced to [-pi, pi] (2 pi in two parts), then the half-angle
// polynomial the D3DSINCOSCONST constants are made for (instructions.md §7). Documented maximum
// absolute error: 0.002 (this polynomial: 0.0018 for sin, 0.0007 for cos).
inline void sincos(float x, float& sine, float& cosine) {
    const float turns = round_small(x * 0.159154943091895336f);  // x / (2 pi)
    const bool reducible = (turns == turns) & (std::fabs(turns) < 4194304.0f);
    const float finite_turns = reducible ? turns : 0.0f;
    const float r = (x - finite_turns * 6.28318548f) + finite_turns * 1.7484555e-7f;
    const float z = r * r;
    const float h = ((-1.5500992e-6f * z + 0.00026041668f) * z - 0.020833334f) * z + 0.5f;  // sin(r/2)/r
    const float c = ((-2.1701389e-5f * z + 0.0026041667f) * z - 0.125f) * z + 1.0f;        // cos(r/2)
    const float half_sine = h * r;
    cosine = 1.0f - 2.0f * half_sine * half_sine;
    sine = 2.0f * half_sine * c;
}

}  // namespace fast

// --- precision modes -----------------------------------------------------------------------
// Denormals: fp32 and fp64 keep IEEE denormals (the engine never sets flush-to-zero); fp24
// has none (flushed to signed zero, as the s16e7 format has no denormals); fp16 keeps IEEE
// half denormals.

// Both roundings are branch-free (selects only), so that storing a step's result stays a
// vectorized loop, and use float operations only: LLVM's code generator analyses the known
// bits of every integer operation, through each step's rounding, which made integer
// formulations cost most of the compile of an fp24 routine (shader_bench jit/compile alu64
// fp24: 95-99 ms with fabs/copysign and integer rounding, 59-64 with an `and` taking the
// exponent; 0.83x of that with neither it nor copysign, in a slower hour 73 -> 61 ms). Every
// one of the 2^32 inputs gives the earlier formulations' bits (compared once by hand, clang
// and g++; Rounding.* checks the definitions on a sample, every limit and ties).
//
// Rounding to nearest even at the format's ulp by Veltkamp's splitting: for m kept mantissa
// bits, c = x (2^(23 - m) + 1) and c - (c - x) is x rounded to m + 1 significant bits, ties to
// even (no overflow or underflow for the normal ranges below: |c| < 2^72). The ranges are
// tests on |x| against the least magnitude that rounds to the limit: the limit less half the
// ulp kept (a tie, which rounds up, its last kept bit being odd).

namespace detail {
// x rounded to `kept` mantissa bits (Veltkamp's splitting), for a normal x whose product stays finite.
template <int kept>
inline float round_mantissa(float x) {
    const float split = x * static_cast<float>((1u << (23 - kept)) + 1u);
    return split - (split - x);
}
// What lies beyond a format's largest value (`magnitude` = |x| >= its limit): infinity with
// x's sign (x * inf for a finite nonzero x), or x itself where it is an infinity or a NaN (its
// payload kept).
inline float beyond_range(float x, float magnitude) {
    const float inf = kInfinity<float>;
    return magnitude < inf ? x * inf : x;
}
}  // namespace detail

// fp24 = s16e7: 16 mantissa bits, exponent bias 63, normal range [2^-62, (2 - 2^-16) * 2^63].
// Round to nearest even on the mantissa; beyond the range: +-inf; below 2^-62: +-0.
inline float round_to_fp24(float x) {
    const float magnitude = std::fabs(x);
    // Rounded, 2^-62 from the float of bits 0x207FFFC0 on, 2^64 from that of 0x5F7FFFC0.
    const float least = std::bit_cast<float>(0x207FFFC0u), overflow = std::bit_cast<float>(0x5F7FFFC0u);
    const bool in_range = magnitude >= least && magnitude < overflow;  // (false for NaN)
    // (Below the range x is finite: x * 0 is 0 with x's sign.)
    const float outside = !(magnitude < overflow) ? detail::beyond_range(x, magnitude) : x * 0.0f;
    return in_range ? detail::round_mantissa<16>(x) : outside;
}

// fp16 = IEEE binary16 (s10e5): round to nearest even, max 65504, denormals down to 2^-24.
inline float round_to_fp16(float x) {
    const float magnitude = std::fabs(x);
    // 2^-14 is the least normal half; from 65520, halfway between 65504 (the largest half) and
    // 65536, ties go to even: overflow.
    const float overflow = 65520.0f;
    const bool normal = magnitude >= 0x1p-14f && magnitude < overflow;
    // Half denormals are multiples of 2^-24; 0.5 has exactly that spacing, so adding and
    // removing it rounds to the nearest multiple (ties to even).
    const float denormal = std::copysign((magnitude + 0.5f) - 0.5f, x);
    const float outside = !(magnitude < overflow) ? detail::beyond_range(x, magnitude) : denormal;
    return normal ? detail::round_mantissa<10>(x) : outside;
}

// The rounding a step's result gets, decided once per step when a shader is lowered.
[[nodiscard]] ResultRounding result_rounding(const PrecisionOptions& options, bool pixel_shader,
                                             bool partial_precision);

inline float round_result(float x, ResultRounding rounding) {
    switch (rounding) {
    case ResultRounding::Fp24: return round_to_fp24(x);
    case ResultRounding::Fp16: return round_to_fp16(x);
    case ResultRounding::None: break;
    }
    return x;
}
inline double round_result(double x, ResultRounding rounding) {
    return rounding == ResultRounding::None ? x : round_result(static_cast<float>(x), rounding);
}

}  // namespace sm2::emu::numerics
