// min d, a, b: (a < b) ? a : b per component; NaN follows the literal test.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Min, PicksTheSmaller) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Min, rd(0), {c(0), c(1)}, {{1, 5, -3, -kInf}, {2, 4, -2, 0}}), 1.0f, 4.0f, -3.0f, -kInf);
}

TEST(Min, NaNAndSignedZero) {
    // min(NaN, 1): NaN < 1 false -> 1; min(1, NaN): 1 < NaN false -> NaN;
    // min(-0, 0): -0 < 0 false -> +0; min(0, -0) -> -0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Min, rd(0), {c(0), c(1)}, {{kNaN, 1, -0.0f, 0.0f}, {1, kNaN, 0.0f, -0.0f}}),
                     1.0f, kNaN, 0.0f, -0.0f);
}

TEST(Min, ModifiersAndSaturate) {
    // min(-c0, c1.x) = min((-1, -2, 3, -0.5), 0.5) = (-1, -2, 0.5, -0.5) -> sat (0, 0, 0.5, 0); mask xz
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Min, rd(0).mask("xz").sat(), {c(0).neg(), c(1).swz("x")}, {{1, 2, -3, 0.5f}, {0.5f, 0, 0, 0}}),
                     0.0f, 9.0f, 0.5f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
