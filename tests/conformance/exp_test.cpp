// exp d, s.r: 2^s replicated (full precision).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

float exp_of(float x) { return run_instruction(Opcode::Exp, rd(0), {c(0).swz("y")}, {{0, x, 0, 0}})[3]; }

TEST(Exp, PowersOfTwo) {
    EXPECT_EQ(exp_of(3.0f), 8.0f);
    EXPECT_EQ(exp_of(-1.0f), 0.5f);
    EXPECT_EQ(exp_of(0.0f), 1.0f);
    EXPECT_EQ(exp_of(-0.0f), 1.0f);
    EXPECT_EQ(exp_of(10.0f), 1024.0f);
    EXPECT_NEAR(exp_of(0.5f), 1.41421356f, 2e-7f);
}

TEST(Exp, SpecialValues) {
    EXPECT_TRUE(same_bits(exp_of(-kInf), 0.0f));
    EXPECT_TRUE(same_bits(exp_of(kInf), kInf));
    EXPECT_TRUE(same_bits(exp_of(200.0f), kInf));  // 2^200 overflows float
    EXPECT_TRUE(std::isnan(exp_of(kNaN)));
}

TEST(Exp, MaskNegateSaturate) {
    // exp_sat r0.y, -c0.x with c0.x = -2: 2^2 = 4 -> 1
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Exp, rd(0).mask("y").sat(), {c(0).swz("x").neg()}, {{-2, 0, 0, 0}}),
                     9.0f, 1.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
