// pow d, s0.r, s1.r: |s0| ^ s1 replicated, IEEE pow special cases (docs/numerics.md).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

float pow_of(float base, float exponent) {
    return run_instruction(Opcode::Pow, rd(0), {c(0).swz("x"), c(1).swz("y")}, {{base, 0, 0, 0}, {0, exponent, 0, 0}})[0];
}

TEST(Pow, NormalValues) {
    EXPECT_EQ(pow_of(2.0f, 3.0f), 8.0f);
    EXPECT_EQ(pow_of(4.0f, 0.5f), 2.0f);
    EXPECT_EQ(pow_of(2.0f, -2.0f), 0.25f);
    EXPECT_EQ(pow_of(9.0f, 1.5f), 27.0f);
}

TEST(Pow, BaseSignIsIgnored) {
    EXPECT_EQ(pow_of(-2.0f, 3.0f), 8.0f);   // |-2|^3, not -8
    EXPECT_EQ(pow_of(-4.0f, 0.5f), 2.0f);   // not NaN
}

TEST(Pow, ZeroBase) {
    EXPECT_EQ(pow_of(0.0f, 0.0f), 1.0f);
    EXPECT_TRUE(same_bits(pow_of(0.0f, 2.0f), 0.0f));
    EXPECT_TRUE(same_bits(pow_of(-0.0f, 3.0f), 0.0f));
    EXPECT_TRUE(same_bits(pow_of(0.0f, -1.0f), kInf));
}

TEST(Pow, OtherSpecialValues) {
    EXPECT_EQ(pow_of(kNaN, 0.0f), 1.0f);      // x^0 = 1
    EXPECT_EQ(pow_of(1.0f, kNaN), 1.0f);      // 1^y = 1
    EXPECT_TRUE(std::isnan(pow_of(2.0f, kNaN)));
    EXPECT_TRUE(same_bits(pow_of(2.0f, kInf), kInf));
    EXPECT_TRUE(same_bits(pow_of(0.5f, kInf), 0.0f));
}

TEST(Pow, MaskNegateSaturate) {
    // pow_sat r0.xy, c0.x, -c1.y: 2^-(-3) = 8 -> 1
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Pow, rd(0).mask("xy").sat(), {c(0).swz("x"), c(1).swz("y").neg()}, {{2, 0, 0, 0}, {0, -3, 0, 0}}),
                     1.0f, 1.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
