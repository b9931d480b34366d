// dp4 d, a, b: a.x*b.x + a.y*b.y + a.z*b.z + a.w*b.w replicated to the mask.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Dp4, DotProductOfAllFour) {
    // 1*5 + 2*6 + 3*7 + 4*8 = 5 + 12 + 21 + 32 = 70
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp4, rd(0), {c(0), c(1)}, {{1, 2, 3, 4}, {5, 6, 7, 8}}), 70.0f, 70.0f, 70.0f, 70.0f);
}

TEST(Dp4, SwizzleNegateMask) {
    // c0.wzyx . -c1.x = (4 + 3 + 2 + 1) * -2 = -20 into .xw
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp4, rd(0).mask("xw"), {c(0).swz("wzyx"), c(1).swz("x").neg()}, {{1, 2, 3, 4}, {2, 0, 0, 0}}),
                     -20.0f, 9.0f, 9.0f, -20.0f);
}

TEST(Dp4, ZeroTimesInfinityContributesZero) {
    // (1, 2, 0, 0) . (3, 4, inf, NaN) = 3 + 8 + 0 + 0 = 11
    EXPECT_EQ(run_instruction(Opcode::Dp4, rd(0), {c(0), c(1)}, {{1, 2, 0, 0}, {3, 4, kInf, kNaN}})[3], 11.0f);
}

TEST(Dp4, Saturate) {
    // (0.25, 0.25, 0.25, 0.25) . (1, 1, 1, -0.5) = 0.625
    EXPECT_EQ(run_instruction(Opcode::Dp4, rd(0).sat(), {c(0), c(1)}, {{0.25f, 0.25f, 0.25f, 0.25f}, {1, 1, 1, -0.5f}})[1], 0.625f);
    EXPECT_EQ(run_instruction(Opcode::Dp4, rd(0).sat(), {c(0), c(0)}, {{1, 1, 1, 1}})[1], 1.0f);  // 4 -> 1
}

}  // namespace
}  // namespace sm2::test
