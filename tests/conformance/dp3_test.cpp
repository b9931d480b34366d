// dp3 d, a, b: a.x*b.x + a.y*b.y + a.z*b.z replicated to the mask; w ignored.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Dp3, DotProductOfXyz) {
    // 1*4 + 2*5 + 3*6 = 32; w (100, 1000) is not used
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp3, rd(0), {c(0), c(1)}, {{1, 2, 3, 100}, {4, 5, 6, 1000}}), 32.0f, 32.0f, 32.0f, 32.0f);
}

TEST(Dp3, SwizzleNegateMask) {
    // -c0.zyxw . c1 = -(3*4 + 2*5 + 1*6) = -28 into .y
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp3, rd(0).mask("y"), {c(0).swz("zyxw").neg(), c(1)}, {{1, 2, 3, 4}, {4, 5, 6, 7}}),
                     9.0f, -28.0f, 9.0f, 9.0f);
}

TEST(Dp3, ZeroTimesInfinityContributesZero) {
    // (0, 1, 1) . (inf, 2, 3) = 0 + 2 + 3 = 5 (legacy multiply)
    EXPECT_EQ(run_instruction(Opcode::Dp3, rd(0), {c(0), c(1)}, {{0, 1, 1, 0}, {kInf, 2, 3, 0}})[0], 5.0f);
    // (1, 1, 0) . (inf, -inf, NaN) = inf - inf + 0 = NaN
    EXPECT_TRUE(std::isnan(run_instruction(Opcode::Dp3, rd(0), {c(0), c(1)}, {{1, 1, 0, 0}, {kInf, -kInf, kNaN, 0}})[0]));
}

TEST(Dp3, Saturate) {
    // (0.5, 0.5, 0.5) . (0.5, 0.5, 0.5) = 0.75; . (1, 1, 1) = 1.5 -> 1
    EXPECT_EQ(run_instruction(Opcode::Dp3, rd(0).sat(), {c(0), c(0)}, {{0.5f, 0.5f, 0.5f, 9}})[0], 0.75f);
    EXPECT_EQ(run_instruction(Opcode::Dp3, rd(0).sat(), {c(0), c(1)}, {{0.5f, 0.5f, 0.5f, 9}, {1, 1, 1, 1}})[0], 1.0f);
    EXPECT_EQ(run_instruction(Opcode::Dp3, rd(0).sat(), {c(0), c(1)}, {{0.5f, 0.5f, 0.5f, 9}, {-1, -1, -1, 1}})[0], 0.0f);
}

}  // namespace
}  // namespace sm2::test
