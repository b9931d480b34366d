// Precision modes: fp24 rounds pixel-shader results to s16e7, _pp rounds to s10e5 when asked,
// fp64 computes in double. Expected values are worked out bit by bit in the comments.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "emu/engine_test_support.h"
#include "emu/src/numerics.h"

namespace sm2::test {
namespace {

OneInstruction pixel_fp24() {
    OneInstruction how;
    how.shader = ShaderType::Pixel;
    how.precision.precision = emu::Precision::Fp24;
    return how;
}

float mov_in(const OneInstruction& how, float x, bool pp = false) {
    return run_instruction(Opcode::Mov, pp ? rd(0).pp() : rd(0), {c(0)}, {{x, x, x, x}}, how)[0];
}

TEST(Fp24, RoundsTheMantissaToSixteenBitsToNearestEven) {
    const auto fp24 = pixel_fp24();
    // ulp of fp24 at 1 is 2^-16.
    EXPECT_EQ(mov_in(fp24, 1.0f + 0x1p-17f), 1.0f);                         // tie, 1.0 is even
    EXPECT_EQ(mov_in(fp24, 1.0f + 0x1p-16f + 0x1p-17f), 1.0f + 0x1p-15f);   // tie, odd -> up
    EXPECT_EQ(mov_in(fp24, 1.0f + 0x1p-17f + 0x1p-20f), 1.0f + 0x1p-16f);   // above half -> up
    EXPECT_EQ(mov_in(fp24, 1.0f + 0x1p-16f), 1.0f + 0x1p-16f);              // representable
    EXPECT_EQ(mov_in(fp24, -(1.0f + 0x1p-17f + 0x1p-20f)), -(1.0f + 0x1p-16f));
    // carry into the exponent: 2 - 2^-17 rounds to 2
    EXPECT_EQ(mov_in(fp24, 2.0f - 0x1p-17f), 2.0f);
}

TEST(Fp24, RoundsEveryArithmeticResult) {
    // rcp(3): 1/3 = 1.0101...b x 2^-2; sixteen fraction bits 0101010101010101, the rest 0101..
    // is below half: (1 + 21845/65536) / 4 = 87381/262144
    EXPECT_EQ(run_instruction(Opcode::Rcp, rd(0), {c(0).swz("x")}, {{3, 0, 0, 0}}, pixel_fp24())[0], 87381.0f / 262144.0f);
    // add: 1 + 2^-20 -> 1
    EXPECT_EQ(run_instruction(Opcode::Add, rd(0), {c(0), c(1)}, {{1, 1, 1, 1}, {0x1p-20f, 0, 0, 0}}, pixel_fp24())[0], 1.0f);
}

TEST(Fp24, ExponentRange) {
    const auto fp24 = pixel_fp24();
    // largest fp24: (2 - 2^-16) * 2^63; 2^64 overflows to inf
    EXPECT_EQ(mov_in(fp24, 0x1p63f * (2.0f - 0x1p-16f)), 0x1p63f * (2.0f - 0x1p-16f));
    EXPECT_EQ(run_instruction(Opcode::Mul, rd(0), {c(0), c(0)}, {{0x1p32f, 0, 0, 0}}, fp24)[0], kInf);
    EXPECT_EQ(mov_in(fp24, -0x1p64f), -kInf);
    // smallest normal 2^-62 stays; 2^-63 has no fp24 encoding (no denormals) and flushes to a
    // signed zero
    EXPECT_EQ(mov_in(fp24, 0x1p-62f), 0x1p-62f);
    EXPECT_TRUE(same_bits(mov_in(fp24, 0x1p-63f), 0.0f));
    EXPECT_TRUE(same_bits(mov_in(fp24, -0x1p-63f), -0.0f));
    EXPECT_TRUE(same_bits(mov_in(fp24, 1e-40f), 0.0f));
    EXPECT_TRUE(std::isnan(mov_in(fp24, kNaN)));
    EXPECT_EQ(mov_in(fp24, -kInf), -kInf);
}

TEST(Fp24, SaturateComesBeforeRounding) {
    // 1.5 -> sat 1 (exact in fp24)
    EXPECT_EQ(run_instruction(Opcode::Mov, rd(0).sat(), {c(0)}, {{1.5f, 0, 0, 0}}, pixel_fp24())[0], 1.0f);
}

TEST(Fp24, VertexShadersStayFp32) {
    OneInstruction vs;
    vs.precision.precision = emu::Precision::Fp24;
    EXPECT_EQ(mov_in(vs, 1.0f + 0x1p-20f), 1.0f + 0x1p-20f);
}

OneInstruction pixel_pp(emu::Precision full) {
    OneInstruction how;
    how.shader = ShaderType::Pixel;
    how.precision.precision = full;
    how.precision.partial_precision_fp16 = true;
    return how;
}

TEST(Fp16, PartialPrecisionRoundsToHalf) {
    const auto pp = pixel_pp(emu::Precision::Fp32);
    // ulp of half at 1 is 2^-10
    EXPECT_EQ(mov_in(pp, 1.0f + 0x1p-11f, true), 1.0f);                  // tie to even
    EXPECT_EQ(mov_in(pp, 1.0f + 0x1p-10f + 0x1p-11f, true), 1.0f + 0x1p-9f);
    EXPECT_EQ(mov_in(pp, 0.1f, true), 0.0999755859375f);  // 0.1 = 1.6 x 2^-4 -> 1638/1024 x 2^-4
    // range: 65504 is the largest half; 65519 rounds down to it; 65520 is the tie that overflows
    EXPECT_EQ(mov_in(pp, 65504.0f, true), 65504.0f);
    EXPECT_EQ(mov_in(pp, 65519.0f, true), 65504.0f);
    EXPECT_EQ(mov_in(pp, 65520.0f, true), kInf);
    EXPECT_EQ(mov_in(pp, -70000.0f, true), -kInf);
    // denormals: multiples of 2^-24; 1.5 x 2^-24 is a tie -> 2 x 2^-24; 2^-26 -> 0
    EXPECT_EQ(mov_in(pp, 0x1p-24f, true), 0x1p-24f);
    EXPECT_EQ(mov_in(pp, 0x1.8p-24f, true), 0x1p-23f);
    EXPECT_TRUE(same_bits(mov_in(pp, -0x1p-26f, true), -0.0f));
    EXPECT_EQ(mov_in(pp, 0x1p-14f + 0x1p-25f, true), 0x1p-14f);  // smallest normal; ulp 2^-24
}

TEST(Fp16, OnlyForPartialPrecisionInstructions) {
    EXPECT_EQ(mov_in(pixel_pp(emu::Precision::Fp32), 1.0f + 0x1p-11f, false), 1.0f + 0x1p-11f);
    // fp24 mode: full-precision results round to fp24, _pp ones to fp16
    EXPECT_EQ(mov_in(pixel_pp(emu::Precision::Fp24), 1.0f + 0x1p-11f, false), 1.0f + 0x1p-11f);
    EXPECT_EQ(mov_in(pixel_pp(emu::Precision::Fp24), 1.0f + 0x1p-11f, true), 1.0f);
}

TEST(Fp16, IgnoredUnlessAsked) {
    OneInstruction ps;
    ps.shader = ShaderType::Pixel;
    EXPECT_EQ(mov_in(ps, 1.0f + 0x1p-11f, true), 1.0f + 0x1p-11f);
}

// The roundings by their definitions, in double (every float and every rounded value is exact
// there): `bits` significant bits (the leading one included) to nearest even by nearbyint()
// (the default rounding mode), the range tested on the rounded value.
double significant_bits(double x, int bits) {
    int exponent = 0;
    const double fraction = std::frexp(x, &exponent);  // x = fraction * 2^exponent, |fraction| in [1/2, 1)
    return std::ldexp(std::nearbyint(std::ldexp(fraction, bits)), exponent - bits);
}
float fp24_by_definition(float x) {
    if (!std::isfinite(x)) return x;
    const double rounded = significant_bits(x, 17);
    if (std::fabs(rounded) >= 0x1p64) return std::copysign(kInf, x);
    if (std::fabs(rounded) < 0x1p-62) return std::copysign(0.0f, x);
    return static_cast<float>(rounded);
}
float fp16_by_definition(float x) {
    if (!std::isfinite(x)) return x;
    // Below 2^-14: half denormals, multiples of 2^-24.
    const double rounded = std::fabs(x) < 0x1p-14f ? std::ldexp(std::nearbyint(std::ldexp(double{x}, 24)), -24)
                                                   : significant_bits(x, 11);
    if (std::fabs(rounded) >= 65536.0) return std::copysign(kInf, x);
    return std::copysign(static_cast<float>(rounded), x);
}

// numerics.h's roundings (float operations: Veltkamp's splitting and compares on |x|) against
// their definitions: a spread over every exponent and sign, every tie of a sample (the dropped
// bits exactly half), and the floats around each limit (2^-62 and 2^64; half's 2^-24, 2^-14,
// 65504 and 65520), NaN payloads and infinities kept. (All 2^32 floats were compared by hand
// with each formulation these replaced.)
TEST(Rounding, Fp24AndFp16AreTheirDefinitionsBitForBit) {
    std::vector<uint32_t> inputs;
    std::mt19937 random(7);
    for (uint32_t i = 0; i < (1u << 22); ++i) inputs.push_back(i * 1024u + (random() & 1023u));
    for (uint32_t i = 0; i < (1u << 16); ++i) {
        const uint32_t bits = static_cast<uint32_t>(random());
        inputs.push_back((bits & ~0x7Fu) | 0x40u);      // an fp24 tie
        inputs.push_back((bits & ~0x1FFFu) | 0x1000u);  // a half tie
    }
    for (const float limit : {0x1p-62f, 0x1p64f, 0x1p-24f, 0x1p-14f, 65504.0f, 65520.0f}) {
        const auto bits = std::bit_cast<uint32_t>(limit);
        for (uint32_t d = 0; d < 512; ++d)
            for (const uint32_t sign : {0u, 0x80000000u})
                inputs.insert(inputs.end(), {(bits - d) | sign, (bits + d) | sign});
    }
    inputs.insert(inputs.end(), {0x7F800000u, 0xFF800000u, 0x7FC00001u, 0xFF812345u, 0x7F800001u, 0u, 0x80000000u});
    unsigned wrong24 = 0, wrong16 = 0;
    for (const uint32_t bits : inputs) {
        const float x = std::bit_cast<float>(bits);
        if (!same_bits(emu::numerics::round_to_fp24(x), fp24_by_definition(x)) && ++wrong24 <= 3)
            ADD_FAILURE() << "fp24 of bits 0x" << std::hex << bits;
        if (!same_bits(emu::numerics::round_to_fp16(x), fp16_by_definition(x)) && ++wrong16 <= 3)
            ADD_FAILURE() << "fp16 of bits 0x" << std::hex << bits;
    }
    EXPECT_EQ(wrong24, 0u);
    EXPECT_EQ(wrong16, 0u);
}

TEST(Fp64, ComputesInDouble) {
    ProgramBuilder p(ShaderType::Pixel);
    // 1 + 2^-30 is exact in double, 1 in float; rcp(3) is 1/3 to double precision
    p.op(Opcode::Add, rd(0), {c(0), c(1)}).op(Opcode::Rcp, rd(0).mask("y"), {c(2).swz("x")}).op(Opcode::Mov, oC(0), {r(0)});
    emu::LoweringOptions options;
    options.precision.precision = emu::Precision::Fp64;
    options.precision.partial_precision_fp16 = true;  // ignored by the reference
    const auto exe = lower_or_fail(p.program(), {}, options);
    emu::ReferenceBatch batch;
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1, 1, 1, 1}, {0x1p-30f, 0, 0, 0}, {3, 0, 0, 0}}), batch);
    EXPECT_EQ(batch.render_target(0)[0][0], 1.0 + 0x1p-30);
    EXPECT_EQ(batch.render_target(0)[1][0], 1.0 / 3.0);

    options.precision.precision = emu::Precision::Fp32;
    const auto fp32 = lower_or_fail(p.program(), {}, options);
    emu::Batch single;
    emu::execute(fp32, fp32.bind_constants(std::vector<Float4>{{1, 1, 1, 1}, {0x1p-30f, 0, 0, 0}, {3, 0, 0, 0}}), single);
    EXPECT_EQ(single.render_target(0)[0][0], 1.0f);
}

}  // namespace
}  // namespace sm2::test
