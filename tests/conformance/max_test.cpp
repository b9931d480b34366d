// max d, a, b: (a >= b) ? a : b per component; NaN follows the literal test.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Max, PicksTheLarger) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Max, rd(0), {c(0), c(1)}, {{1, 5, -3, kInf}, {2, 4, -2, 0}}), 2.0f, 5.0f, -2.0f, kInf);
}

TEST(Max, NaNAndSignedZero) {
    // max(NaN, 1): NaN >= 1 false -> 1; max(1, NaN) -> NaN; max(-0, 0): -0 >= 0 true -> -0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Max, rd(0), {c(0), c(1)}, {{kNaN, 1, -0.0f, 0.0f}, {1, kNaN, 0.0f, -0.0f}}),
                     1.0f, kNaN, -0.0f, 0.0f);
}

TEST(Max, ModifiersAndSaturate) {
    // max(c0.wzyx, -c1) = max((4, 3, 2, 1), (-1, -5, -1, -2)) = (4, 3, 2, 1) -> sat (1, 1, 1, 1); mask yw
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Max, rd(0).mask("yw").sat(), {c(0).swz("wzyx"), c(1).neg()}, {{1, 2, 3, 4}, {1, 5, 1, 2}}),
                     9.0f, 1.0f, 9.0f, 1.0f);
    // max(c0, 0) as a ReLU: (-1 -> 0, 0.5, 0, 2)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Max, rd(0), {c(0), c(1).swz("x")}, {{-1, 0.5f, 0, 2}, {0, 0, 0, 0}}), 0.0f, 0.5f, 0.0f, 2.0f);
}

}  // namespace
}  // namespace sm2::test
