// The fast transcendentals over dense sweeps, against double-precision references: each must
// meet the documented minimum precision (instructions.md §5) and keep the special values of
// the numeric policy. The measured maxima are printed (docs/numerics.md quotes them).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "emu/engine_test_support.h"
#include "emu/src/numerics.h"

namespace sm2::test {
namespace {

// Runs "op r0, v0.x[, v1.x]" (or sincos) in fast or exact mode over `xs` (and `ys`) and returns
// component `component` of r0 for each input.
std::vector<float> evaluate(Opcode opcode, const std::vector<float>& xs, const std::vector<float>& ys,
                            emu::Transcendentals mode, unsigned component = 0) {
    ProgramBuilder p(ShaderType::Vertex);
    if (opcode == Opcode::SinCos)
        p.op(opcode, rd(0).mask("xy"), {v(0).swz("x"), c(0), c(1)});
    else if (opcode == Opcode::Pow)
        p.op(opcode, rd(0), {v(0).swz("x"), v(1).swz("x")});
    else
        p.op(opcode, rd(0), {v(0).swz("x")});
    emu::LoweringOptions options;
    options.keep_dead_code = true;
    options.precision.transcendentals = mode;
    const auto exe = lower_or_fail(p.program(), {}, options);
    const auto constants = exe.bind_constants();
    std::vector<float> out(xs.size());
    emu::Batch batch;
    for (size_t first = 0; first < xs.size(); first += emu::kBatchLanes) {
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            const size_t k = std::min(first + l, xs.size() - 1);
            batch.input(0)[0][l] = xs[k];
            batch.input(1)[0][l] = ys.empty() ? 0.0f : ys[k];
        }
        emu::execute(exe, constants, batch);
        for (unsigned l = 0; l < emu::kBatchLanes && first + l < xs.size(); ++l)
            out[first + l] = batch.temp(0)[component][l];
    }
    return out;
}

std::vector<float> linear_sweep(float from, float to, size_t count) {
    std::vector<float> xs(count);
    for (size_t k = 0; k < count; ++k)
        xs[k] = static_cast<float>(from + (static_cast<double>(to) - from) * static_cast<double>(k) / static_cast<double>(count - 1));
    return xs;
}

TEST(FastTranscendentals, Exp2MeetsTwentyOneBits) {
    const auto xs = linear_sweep(-125.0f, 127.0f, 400000);
    const auto fast = evaluate(Opcode::Exp, xs, {}, emu::Transcendentals::Fast);
    const auto exact = evaluate(Opcode::Exp, xs, {}, emu::Transcendentals::Exact);
    double worst = 0, worst_exact = 0;
    for (size_t k = 0; k < xs.size(); ++k) {
        const double reference = std::exp2(static_cast<double>(xs[k]));
        worst = std::max(worst, std::fabs(fast[k] - reference) / reference);
        worst_exact = std::max(worst_exact, std::fabs(exact[k] - reference) / reference);
    }
    std::printf("exp2: max relative error fast %.3g (2^%.1f), exact %.3g (2^%.1f)\n", worst, std::log2(worst),
                worst_exact, std::log2(worst_exact));
    EXPECT_LT(worst, std::ldexp(1.0, -21));
}

TEST(FastTranscendentals, Exp2SpecialValues) {
    const auto fast = evaluate(Opcode::Exp, {0.0f, 3.0f, -1.0f, -kInf, kInf, kNaN, 200.0f, -200.0f, -140.0f}, {},
                               emu::Transcendentals::Fast);
    EXPECT_EQ(fast[0], 1.0f);
    EXPECT_EQ(fast[1], 8.0f);
    EXPECT_EQ(fast[2], 0.5f);
    EXPECT_TRUE(same_bits(fast[3], 0.0f));
    EXPECT_EQ(fast[4], kInf);
    EXPECT_TRUE(std::isnan(fast[5]));
    EXPECT_EQ(fast[6], kInf);
    EXPECT_TRUE(same_bits(fast[7], 0.0f));
    EXPECT_EQ(fast[8], 0x1p-140f);  // denormal result
}

TEST(FastTranscendentals, Log2MeetsTwentyOneBits) {
    std::vector<float> xs;
    for (double e = -149.0; e < 128.0; e += 0.0007) xs.push_back(static_cast<float>(std::exp2(e)));
    for (const float x : linear_sweep(0.5f, 2.0f, 100000)) xs.push_back(x);
    const auto fast = evaluate(Opcode::Log, xs, {}, emu::Transcendentals::Fast);
    const auto exact = evaluate(Opcode::Log, xs, {}, emu::Transcendentals::Exact);
    // 21 bits of the result: absolute below 1, relative above (a float result near 127 has
    // an ulp of 2^-17 by itself).
    double worst = 0, worst_exact = 0;
    for (size_t k = 0; k < xs.size(); ++k) {
        const double reference = std::log2(static_cast<double>(xs[k]));
        worst = std::max(worst, std::fabs(fast[k] - reference) / std::max(1.0, std::fabs(reference)));
        worst_exact = std::max(worst_exact, std::fabs(exact[k] - reference) / std::max(1.0, std::fabs(reference)));
    }
    std::printf("log2: max error (absolute below 1, relative above) fast %.3g (2^%.1f), exact %.3g (2^%.1f)\n",
                worst, std::log2(worst), worst_exact, std::log2(worst_exact));
    EXPECT_LT(worst, std::ldexp(1.0, -21));
}

TEST(FastTranscendentals, Log2SpecialValues) {
    const auto fast = evaluate(Opcode::Log, {1.0f, 8.0f, -0.25f, 0.0f, -0.0f, kInf, kNaN, 0x1p-149f}, {},
                               emu::Transcendentals::Fast);
    EXPECT_EQ(fast[0], 0.0f);
    EXPECT_EQ(fast[1], 3.0f);
    EXPECT_EQ(fast[2], -2.0f);
    EXPECT_EQ(fast[3], -kInf);
    EXPECT_EQ(fast[4], -kInf);
    EXPECT_EQ(fast[5], kInf);
    EXPECT_TRUE(std::isnan(fast[6]));
    EXPECT_EQ(fast[7], -149.0f);
}

TEST(FastTranscendentals, PowMeetsFifteenBits) {
    std::vector<float> bases, exponents;
    for (const float b : linear_sweep(0.01f, 100.0f, 2000))
        for (const float e : linear_sweep(-8.0f, 8.0f, 161)) {
            bases.push_back(b);
            exponents.push_back(e);
        }
    const auto fast = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Fast);
    const auto exact = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Exact);
    double worst = 0, worst_exact = 0;
    for (size_t k = 0; k < bases.size(); ++k) {
        const double reference = std::pow(static_cast<double>(bases[k]), static_cast<double>(exponents[k]));
        if (reference < 0x1p-126 || reference > 0x1p127) continue;
        worst = std::max(worst, std::fabs(fast[k] - reference) / reference);
        worst_exact = std::max(worst_exact, std::fabs(exact[k] - reference) / reference);
    }
    std::printf("pow: max relative error fast %.3g (2^%.1f), exact %.3g (2^%.1f)\n", worst, std::log2(worst),
                worst_exact, std::log2(worst_exact));
    EXPECT_LT(worst, std::ldexp(1.0, -15));
}

TEST(FastTranscendentals, PowSpecialValuesFollowThePolicy) {
    // 0^0 = 1, 0^2 = 0, 0^-1 = inf, NaN^0 = 1, 1^NaN = 1, (-2)^3 = 8, 4^0.5 = 2
    const auto fast = evaluate(Opcode::Pow, {0, 0, 0, kNaN, 1, -2, 4}, {0, 2, -1, 0, kNaN, 3, 0.5f},
                               emu::Transcendentals::Fast);
    EXPECT_EQ(fast[0], 1.0f);
    EXPECT_TRUE(same_bits(fast[1], 0.0f));
    EXPECT_EQ(fast[2], kInf);
    EXPECT_EQ(fast[3], 1.0f);
    EXPECT_EQ(fast[4], 1.0f);
    EXPECT_NEAR(fast[5], 8.0f, 8.0f * 0x1p-15f);
    EXPECT_NEAR(fast[6], 2.0f, 2.0f * 0x1p-15f);
}

// Exact mode's pow is the engine's own double-precision evaluation (numerics.h pow_float), not
// the C library's powf: it must be correctly rounded. Against long double powl (64-bit
// mantissa) on 400 000 random bases in (0, 16) and exponents in (-40, 40), every result in the
// normal float range lies within 0.5 ulp (plus the reference's own 2^-40 ulp).
TEST(ExactTranscendentals, PowIsCorrectlyRoundedOnASample) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> base(0.0f, 16.0f), exponent(-40.0f, 40.0f);
    std::vector<float> bases(400000), exponents(400000);
    for (size_t k = 0; k < bases.size(); ++k) {
        bases[k] = base(rng);
        exponents[k] = exponent(rng);
    }
    const auto exact = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Exact);
    double worst = 0;
    size_t checked = 0;
    for (size_t k = 0; k < bases.size(); ++k) {
        const long double reference = powl(static_cast<long double>(bases[k]), static_cast<long double>(exponents[k]));
        if (!(reference >= 0x1p-126L && reference < 0x1p127L)) continue;
        const long double ulp = ldexpl(1.0L, ilogbl(reference) - 23);
        worst = std::max(worst, static_cast<double>(fabsl(static_cast<long double>(exact[k]) - reference) / ulp));
        ++checked;
    }
    std::printf("exact pow: %zu results in the normal range, max error %.6f ulp\n", checked, worst);
    EXPECT_GT(checked, 200000u);
    EXPECT_LE(worst, 0.5 + 0x1p-40);
}

// A batch whose exponent is one integer n in [1, 256] (a constant, as specular exponents are)
// takes repeated squaring in exact mode (numerics.h pow_float_integer). Its results must be
// bit for bit those of the general evaluation, which a batch of mixed exponents takes: the same
// (base, n) pairs are run once grouped by n and once shuffled across batches. Both must also be
// correctly rounded against long double powl.
TEST(ExactTranscendentals, PowWithOneIntegerExponentPerBatchMatchesTheGeneralPath) {
    constexpr unsigned kBatches = 256 * 40;
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> unit(0.0f, 2.0f), scale(-40.0f, 40.0f);
    std::vector<float> bases(kBatches * emu::kBatchLanes), exponents(bases.size());
    for (size_t k = 0; k < bases.size(); ++k) {
        const size_t batch = k / emu::kBatchLanes;
        // Half near 1 (where specular powers live), half spread over many binades, signs mixed.
        const float magnitude = batch % 2 == 0 ? unit(rng) : std::exp2(scale(rng));
        bases[k] = k % 3 == 0 ? -magnitude : magnitude;
        exponents[k] = static_cast<float>(1 + batch % 256);
    }
    std::vector<size_t> order(bases.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<float> mixed_bases(bases.size()), mixed_exponents(bases.size());
    for (size_t k = 0; k < order.size(); ++k) {
        mixed_bases[k] = bases[order[k]];
        mixed_exponents[k] = exponents[order[k]];
    }
    const auto grouped = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Exact);
    const auto mixed = evaluate(Opcode::Pow, mixed_bases, mixed_exponents, emu::Transcendentals::Exact);
    size_t differ = 0, checked = 0;
    double worst = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        const size_t at = order[k];
        differ += same_bits(mixed[k], grouped[at]) ? 0u : 1u;
        const long double reference = powl(fabsl(static_cast<long double>(bases[at])), static_cast<long double>(exponents[at]));
        if (!(reference >= 0x1p-126L && reference < 0x1p127L)) continue;
        const long double ulp = ldexpl(1.0L, ilogbl(reference) - 23);
        worst = std::max(worst, static_cast<double>(fabsl(static_cast<long double>(grouped[at]) - reference) / ulp));
        ++checked;
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(checked, bases.size() / 4);
    EXPECT_LE(worst, 0.5 + 0x1p-40);
}

// Fast mode takes the same squaring for a batch of one integer exponent (a specular power):
// its results there are exact mode's correctly rounded ones, not fast pow's 15+ bits.
TEST(FastTranscendentals, PowWithOneIntegerExponentPerBatchIsExactModes) {
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> unit(0.0f, 1.5f);
    std::vector<float> bases(64 * emu::kBatchLanes), exponents(bases.size());
    for (size_t k = 0; k < bases.size(); ++k) {
        bases[k] = unit(rng);
        exponents[k] = static_cast<float>(1 + (k / emu::kBatchLanes) % 64);
    }
    const auto fast = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Fast);
    const auto exact = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Exact);
    size_t differ = 0;
    for (size_t k = 0; k < bases.size(); ++k) differ += same_bits(fast[k], exact[k]) ? 0u : 1u;
    EXPECT_EQ(differ, 0u);
}

// Special values in a batch of one integer exponent (the first 16 lanes: every rounding
// certain), and the lanes whose rounding squaring cannot settle, which send their batch the
// general way (the second batch): NaN, and an exact power on a rounding tie ((2^-75)^2 =
// 2^-150, half the smallest denormal, rounds to even: 0).
TEST(ExactTranscendentals, PowWithOneIntegerExponentKeepsTheSpecialValues) {
    std::vector<float> bases{0.0f, -0.0f, kInf, -kInf, 1.0f, -3.0f, 0x3p-76f, 0.5f,
                             2.0f, 0x1p64f, 0x1p-64f, 1.5f, -1.0f, 0x1p-100f, 3.0f, 1e19f,
                             kNaN, 0x1p-75f, -0x1p-75f, 3.0f};
    const std::vector<float> exponents(bases.size(), 2.0f);
    const auto r = evaluate(Opcode::Pow, bases, exponents, emu::Transcendentals::Exact);
    EXPECT_TRUE(same_bits(r[0], 0.0f));
    EXPECT_TRUE(same_bits(r[1], 0.0f));  // |-0|^2 = +0
    EXPECT_EQ(r[2], kInf);
    EXPECT_EQ(r[3], kInf);
    EXPECT_EQ(r[4], 1.0f);
    EXPECT_EQ(r[5], 9.0f);  // |-3|^2
    EXPECT_EQ(r[6], 0x1p-149f);  // 1.125 * 2^-149 rounds to the smallest denormal
    EXPECT_EQ(r[7], 0.25f);
    EXPECT_EQ(r[8], 4.0f);
    EXPECT_EQ(r[9], kInf);  // 2^128 overflows
    EXPECT_EQ(r[10], 0x1p-128f);  // a denormal, exact
    EXPECT_EQ(r[11], 2.25f);
    EXPECT_EQ(r[12], 1.0f);
    EXPECT_TRUE(same_bits(r[13], 0.0f));  // 2^-200 underflows
    EXPECT_EQ(r[14], 9.0f);
    EXPECT_EQ(r[15], 1e38f);  // 10^38 correctly rounded
    EXPECT_TRUE(std::isnan(r[16]));
    EXPECT_TRUE(same_bits(r[17], 0.0f));
    EXPECT_TRUE(same_bits(r[18], 0.0f));
    EXPECT_EQ(r[19], 9.0f);
}

// IEEE pow's special cases on |base| in exact mode (docs/numerics.md rows "pow").
TEST(ExactTranscendentals, PowSpecialValues) {
    const float denormal = 0x1p-149f;
    const auto r = evaluate(Opcode::Pow,
                            {0, -0.0f, 0, kInf, kInf, 1, kNaN, kNaN, 2, 0.5f, 0.5f, 2, 2, 2, denormal, -3, 2},
                            {0, -3, 2, 2, -2, kNaN, 0, 1, kInf, kInf, -kInf, -kInf, 128, -149, 1, 2, -150},
                            emu::Transcendentals::Exact);
    EXPECT_EQ(r[0], 1.0f);            // 0^0
    EXPECT_EQ(r[1], kInf);            // |-0|^-3
    EXPECT_TRUE(same_bits(r[2], 0.0f));
    EXPECT_EQ(r[3], kInf);            // inf^2
    EXPECT_TRUE(same_bits(r[4], 0.0f));  // inf^-2
    EXPECT_EQ(r[5], 1.0f);            // 1^NaN
    EXPECT_EQ(r[6], 1.0f);            // NaN^0
    EXPECT_TRUE(std::isnan(r[7]));
    EXPECT_EQ(r[8], kInf);            // 2^inf
    EXPECT_TRUE(same_bits(r[9], 0.0f));  // 0.5^inf
    EXPECT_EQ(r[10], kInf);           // 0.5^-inf
    EXPECT_TRUE(same_bits(r[11], 0.0f));  // 2^-inf
    EXPECT_EQ(r[12], kInf);           // 2^128 overflows
    EXPECT_EQ(r[13], denormal);       // 2^-149: the smallest denormal, exact
    EXPECT_EQ(r[14], denormal);       // denormal^1
    EXPECT_EQ(r[15], 9.0f);           // |-3|^2
    EXPECT_TRUE(same_bits(r[16], 0.0f));  // 2^-150: half the smallest denormal rounds to even, 0
}

// Exact exp and log are the engine's own evaluations in double too (numerics.h exp2_float,
// log2_float): correctly rounded, where glibc's exp2f and log2f (used before) are not on a few
// inputs in ten thousand. Each result must be the float nearest the long double reference
// (64-bit mantissa): exp on 400 000 random x over the whole range of nonzero results, log on
// 400 000 random positive float bit patterns (denormals included) and 100 000 points in
// [0.25, 4], where the results are small and need their relative accuracy.
TEST(ExactTranscendentals, ExpIsCorrectlyRoundedOnASample) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> exponent(-150.0f, 128.0f);
    std::vector<float> xs(400000);
    for (float& x : xs) x = exponent(rng);
    const auto exact = evaluate(Opcode::Exp, xs, {}, emu::Transcendentals::Exact);
    size_t wrong = 0, denormal = 0;
    for (size_t k = 0; k < xs.size(); ++k) {
        const long double reference = exp2l(static_cast<long double>(xs[k]));
        wrong += !same_bits(exact[k], static_cast<float>(reference));
        denormal += reference < 0x1p-126L;
    }
    std::printf("exact exp: %zu results (%zu denormal or 0), %zu not the nearest float\n", xs.size(), denormal, wrong);
    EXPECT_GT(denormal, 1000u);
    EXPECT_EQ(wrong, 0u);
}

TEST(ExactTranscendentals, LogIsCorrectlyRoundedOnASample) {
    std::mt19937 rng(12);
    std::uniform_int_distribution<uint32_t> positive_bits(1, 0x7F7FFFFFu);
    std::vector<float> xs(400000);
    for (float& x : xs) x = std::bit_cast<float>(positive_bits(rng));
    for (const float x : linear_sweep(0.25f, 4.0f, 100000)) xs.push_back(x);
    const auto exact = evaluate(Opcode::Log, xs, {}, emu::Transcendentals::Exact);
    size_t wrong = 0;
    for (size_t k = 0; k < xs.size(); ++k)
        wrong += !same_bits(exact[k], static_cast<float>(log2l(static_cast<long double>(xs[k]))));
    std::printf("exact log: %zu results, %zu not the nearest float\n", xs.size(), wrong);
    EXPECT_EQ(wrong, 0u);
}

// Exact exp, log and pow are series of fused multiply-adds in double (numerics.h). The
// interpreter runs them in clones for x86-64-v4 and v3, where std::fma is one instruction, and
// the JIT in code for the host; this file's own calls of numerics.h, compiled for baseline
// x86-64, take the C library's fma. A fused multiply-add has one result, so every path must give
// the same bits: the engine's results do not depend on the instruction set it runs on.
TEST(ExactTranscendentals, EveryInstructionSetGivesTheSameBits) {
    std::mt19937 rng(13);
    std::uniform_int_distribution<uint32_t> bits;
    std::uniform_real_distribution<float> exponent(-150.0f, 128.0f), base(0.0f, 16.0f), power(-40.0f, 40.0f);
    // Half arbitrary bit patterns (denormals, infinities, NaNs), half the functions' ranges.
    std::vector<float> xs(200000), bases(200000), powers(200000);
    for (size_t k = 0; k < xs.size(); ++k) {
        const bool any = k % 2 != 0;
        xs[k] = any ? std::bit_cast<float>(bits(rng)) : exponent(rng);
        bases[k] = any ? std::bit_cast<float>(bits(rng)) : base(rng);
        powers[k] = any ? std::bit_cast<float>(bits(rng)) : power(rng);
    }
    const auto exps = evaluate(Opcode::Exp, xs, {}, emu::Transcendentals::Exact);
    const auto logs = evaluate(Opcode::Log, xs, {}, emu::Transcendentals::Exact);
    const auto pows = evaluate(Opcode::Pow, bases, powers, emu::Transcendentals::Exact);
    size_t wrong = 0;
    for (size_t k = 0; k < xs.size(); ++k) {
        wrong += !same_bits(exps[k], emu::numerics::exp2_float(xs[k]));
        wrong += !same_bits(logs[k], emu::numerics::log2_float(xs[k]));
        wrong += !same_bits(pows[k], emu::numerics::pow_float(bases[k], powers[k]));
    }
    EXPECT_EQ(wrong, 0u);
}

// docs/numerics.md rows "exp" and "log" in exact mode; the values exact where the result is a
// power of two or an integer, and sqrt(2) = 1.41421356.. between the floats 0x1.6a09e6p0
// (2.4e-8 below) and 0x1.6a09e8p0 (9.5e-8 above).
TEST(ExactTranscendentals, ExpAndLogSpecialValues) {
    const auto e = evaluate(Opcode::Exp, {0, 10, -1, -kInf, kInf, kNaN, 128, -149, -150, -149.5f, 0.5f, -0.0f}, {},
                            emu::Transcendentals::Exact);
    EXPECT_EQ(e[0], 1.0f);
    EXPECT_EQ(e[1], 1024.0f);
    EXPECT_EQ(e[2], 0.5f);
    EXPECT_TRUE(same_bits(e[3], 0.0f));
    EXPECT_EQ(e[4], kInf);
    EXPECT_TRUE(std::isnan(e[5]));
    EXPECT_EQ(e[6], kInf);                // 2^128 overflows
    EXPECT_EQ(e[7], 0x1p-149f);           // the smallest denormal, exact
    EXPECT_TRUE(same_bits(e[8], 0.0f));   // half of it: the tie rounds to even, 0
    EXPECT_EQ(e[9], 0x1p-149f);           // 0.71 of it rounds up
    EXPECT_EQ(e[10], 0x1.6a09e6p0f);
    EXPECT_EQ(e[11], 1.0f);
    const auto l = evaluate(Opcode::Log, {1, 8, -0.25f, 0, -0.0f, kInf, -kInf, kNaN, 0x1p-149f, 2.0f, 0x1.000002p0f}, {},
                            emu::Transcendentals::Exact);
    EXPECT_TRUE(same_bits(l[0], 0.0f));
    EXPECT_EQ(l[1], 3.0f);
    EXPECT_EQ(l[2], -2.0f);  // the sign is ignored
    EXPECT_EQ(l[3], -kInf);
    EXPECT_EQ(l[4], -kInf);
    EXPECT_EQ(l[5], kInf);
    EXPECT_EQ(l[6], kInf);
    EXPECT_TRUE(std::isnan(l[7]));
    EXPECT_EQ(l[8], -149.0f);  // a denormal input
    EXPECT_EQ(l[9], 1.0f);
    // log2(1 + 2^-23) = 2^-23 / ln 2 (1 - 2^-24 + ..) = 1.7198e-7: relative accuracy near 1.
    EXPECT_EQ(l[10], static_cast<float>(log2l(1.0L + 0x1p-23L)));
}

TEST(FastTranscendentals, SinCosWithinTheDocumentedAbsoluteError) {
    const auto xs = linear_sweep(-3.14159265f, 3.14159265f, 200000);
    const auto cosine = evaluate(Opcode::SinCos, xs, {}, emu::Transcendentals::Fast, 0);
    const auto sine = evaluate(Opcode::SinCos, xs, {}, emu::Transcendentals::Fast, 1);
    const auto exact_sine = evaluate(Opcode::SinCos, xs, {}, emu::Transcendentals::Exact, 1);
    double worst_sin = 0, worst_cos = 0, worst_exact = 0;
    for (size_t k = 0; k < xs.size(); ++k) {
        worst_sin = std::max(worst_sin, std::fabs(sine[k] - std::sin(static_cast<double>(xs[k]))));
        worst_cos = std::max(worst_cos, std::fabs(cosine[k] - std::cos(static_cast<double>(xs[k]))));
        worst_exact = std::max(worst_exact, std::fabs(exact_sine[k] - std::sin(static_cast<double>(xs[k]))));
    }
    std::printf("sincos: max absolute error fast sin %.3g, cos %.3g; exact sin %.3g\n", worst_sin, worst_cos, worst_exact);
    EXPECT_LT(worst_sin, 0.002);
    EXPECT_LT(worst_cos, 0.002);
}

TEST(FastTranscendentals, ReferenceModeIgnoresFast) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Exp, oPos(), {c(0).swz("x")});
    emu::LoweringOptions options;
    options.precision.precision = emu::Precision::Fp64;
    options.precision.transcendentals = emu::Transcendentals::Fast;
    EXPECT_EQ(lower_or_fail(p.program(), {}, options).transcendentals(), emu::Transcendentals::Exact);
}

}  // namespace
}  // namespace sm2::test
