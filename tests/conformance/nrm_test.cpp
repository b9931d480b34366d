// nrm d, s: s * rsq(dot3(s, s)); w is scaled too; a zero vector uses the factor FLT_MAX.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Nrm, NormalizesXyzAndScalesW) {
    // (3, 4, 0): length 5, factor rsq(25) = 0.2: (0.6, 0.8, 0, 2 * 0.2 = 0.4)
    EXPECT_FLOAT4_NEAR(run_instruction(Opcode::Nrm, rd(0), {c(0)}, {{3, 4, 0, 2}}), 0.6f, 0.8f, 0.0f, 0.4f, 1e-7f);
    // (0, 0, -2): factor 0.5: (0, 0, -1, 0)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Nrm, rd(0).mask("xyz"), {c(0)}, {{0, 0, -2, 7}}), 0.0f, 0.0f, -1.0f, 9.0f);
}

TEST(Nrm, ZeroVector) {
    // factor FLT_MAX: x, y, z = 0 * FLT_MAX = 0; w = 0.5 * FLT_MAX = 2^127 * (2 - 2^-23) / 2
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Nrm, rd(0), {c(0)}, {{0, 0, 0, 0.5f}}), 0.0f, 0.0f, 0.0f, kFltMax / 2);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Nrm, rd(0).mask("xyz"), {c(0)}, {{0, -0.0f, 0, 1}}), 0.0f, 0.0f, 0.0f, 9.0f);
}

TEST(Nrm, NegateSwizzleMaskSaturate) {
    // -c0.zyxw = -(4, 0, 3, 1) = (-4, -0, -3, -1); factor 0.2: (-0.8, 0, -0.6, -0.2) -> sat all 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Nrm, rd(0).sat(), {c(0).swz("zyxw").neg()}, {{3, 0, 4, 1}}), 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_FLOAT4_NEAR(run_instruction(Opcode::Nrm, rd(0).mask("xz"), {c(0).swz("zyxw").neg()}, {{3, 0, 4, 1}}), -0.8f, 9.0f, -0.6f, 9.0f, 1e-7f);
}

}  // namespace
}  // namespace sm2::test
