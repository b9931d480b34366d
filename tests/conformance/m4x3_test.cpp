// m4x3 d.xyz, s0, s1: three dp4 rows; d.w untouched.
#include <gtest/gtest.h>

#include "conformance/matrix_test_support.h"

namespace sm2::test {
namespace {

TEST(M4x3, ThreeDotProducts) {
    // v = (1, 1, 1, 1): row sums 10, 26, 42; w stays 9
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x3, rd(0).mask("xyz"), {c(0), c(1)}, matrix_constants({1, 1, 1, 1})), 10.0f, 26.0f, 42.0f, 9.0f);
}

TEST(M4x3, NegateAndSaturate) {
    // -(0, 0, 0, 0.0625): -0.25, -0.5, -0.75 -> sat 0; and without negate 0.25, 0.5, 0.75
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x3, rd(0).mask("xyz").sat(), {c(0).neg(), c(1)}, matrix_constants({0, 0, 0, 0.0625f})), 0.0f, 0.0f, 0.0f, 9.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x3, rd(0).mask("xyz").sat(), {c(0), c(1)}, matrix_constants({0, 0, 0, 0.0625f})), 0.25f, 0.5f, 0.75f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
