// m3x3 d.xyz, s0, s1: three dp3 rows; d.w untouched.
#include <gtest/gtest.h>

#include "conformance/matrix_test_support.h"

namespace sm2::test {
namespace {

TEST(M3x3, ThreeDotProducts) {
    // v = (1, 0, -1): 1-3 = -2, 5-7 = -2, 9-11 = -2
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x3, rd(0).mask("xyz"), {c(0), c(1)}, matrix_constants({1, 0, -1, 5})), -2.0f, -2.0f, -2.0f, 9.0f);
}

TEST(M3x3, NegateSaturate) {
    // -(1, 0, -1): 2, 2, 2 -> sat 1
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x3, rd(0).mask("xyz").sat(), {c(0).neg(), c(1)}, matrix_constants({1, 0, -1, 5})), 1.0f, 1.0f, 1.0f, 9.0f);
}

TEST(M3x3, ZeroTimesInfinity) {
    // v = (0, 1, 0) with row0 = (inf, 2, NaN): 0 + 2 + 0 = 2
    auto constants = matrix_constants({0, 1, 0, 0});
    constants[1] = {kInf, 2, kNaN, 0};
    EXPECT_EQ(run_instruction(Opcode::M3x3, rd(0).mask("xyz"), {c(0), c(1)}, constants)[0], 2.0f);
}

}  // namespace
}  // namespace sm2::test
