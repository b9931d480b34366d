// lrp d, t, a, b: t * (a - b) + b per component (= t*a + (1-t)*b).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Lrp, Interpolates) {
    // t = (0, 1, 0.25, 0.5), a = 8, b = 4: (4, 8, 0.25*4+4 = 5, 0.5*4+4 = 6)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lrp, rd(0), {c(0), c(1), c(2)}, {{0, 1, 0.25f, 0.5f}, {8, 8, 8, 8}, {4, 4, 4, 4}}),
                     4.0f, 8.0f, 5.0f, 6.0f);
}

TEST(Lrp, ExtrapolatesOutsideZeroToOne) {
    // t = 2: 2*(8-4)+4 = 12; t = -1: -1*4+4 = 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lrp, rd(0).mask("xy"), {c(0), c(1), c(2)}, {{2, -1, 0, 0}, {8, 8, 8, 8}, {4, 4, 4, 4}}),
                     12.0f, 0.0f, 9.0f, 9.0f);
}

TEST(Lrp, ZeroWeightOfAnInfiniteDifference) {
    // t = 0, a = inf: 0 * inf + 4 = 4 (legacy multiply)
    EXPECT_EQ(run_instruction(Opcode::Lrp, rd(0), {c(0), c(1), c(2)}, {{0, 0, 0, 0}, {kInf, 0, 0, 0}, {4, 0, 0, 0}})[0], 4.0f);
}

TEST(Lrp, ModifiersSaturate) {
    // t = c0.x = 0.5, a = -c1 = (-2, 2, -4, 4), b = c2.yzxw = (1, 1, 1, 1):
    // 0.5*(a-1)+1 = (-0.5, 1.5, -1.5, 2.5) -> sat (0, 1, 0, 1)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lrp, rd(0).sat(), {c(0).swz("x"), c(1).neg(), c(2).swz("yzxw")}, {{0.5f, 0, 0, 0}, {2, -2, 4, -4}, {1, 1, 1, 1}}),
                     0.0f, 1.0f, 0.0f, 1.0f);
}

}  // namespace
}  // namespace sm2::test
