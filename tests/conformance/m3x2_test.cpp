// m3x2 d.xy, s0, s1: two dp3 rows; d.z and d.w untouched.
#include <gtest/gtest.h>

#include "conformance/matrix_test_support.h"

namespace sm2::test {
namespace {

TEST(M3x2, TwoDotProducts) {
    // v = (2, 1, 0): 2+2 = 4, 10+6 = 16
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x2, rd(0).mask("xy"), {c(0), c(1)}, matrix_constants({2, 1, 0, 0})), 4.0f, 16.0f, 9.0f, 9.0f);
}

TEST(M3x2, InPixelShaders) {
    OneInstruction ps;
    ps.shader = ShaderType::Pixel;
    // -v = (-2, -1, -0): -4, -16 -> sat 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x2, rd(0).mask("xy").sat(), {c(0).neg(), c(1)}, matrix_constants({2, 1, 0, 0}), ps), 0.0f, 0.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
