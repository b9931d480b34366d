// lit d, s (vs): (1, max(x, 0), x > 0 && y > 0 ? y^clamp(w) : 0, 1) with the power clamped to
// +-127.9961.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Lit, DiffuseAndSpecular) {
    // N.L = 0.5, N.H = 0.25, power 2: (1, 0.5, 0.25^2 = 0.0625, 1); z of the source is ignored
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{0.5f, 0.25f, 123, 2}}), 1.0f, 0.5f, 0.0625f, 1.0f);
}

TEST(Lit, BackFacingLightGivesNoDiffuseOrSpecular) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{-0.5f, 0.75f, 0, 2}}), 1.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{0.0f, 0.75f, 0, 2}}), 1.0f, 0.0f, 0.0f, 1.0f);
}

TEST(Lit, NoSpecularWhenNDotHIsNotPositive) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{0.25f, -0.5f, 0, 2}}), 1.0f, 0.25f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{0.25f, 0.0f, 0, 2}}), 1.0f, 0.25f, 0.0f, 1.0f);
}

TEST(Lit, PowerIsClamped) {
    // y = 2, w = 200: clamped to 127.9961 (as float 127.99610138), 2^127.99610138 =
    // 2^128 * 2^-0.00389862 = 3.4028237e38 * 0.99730133 = 3.39364e38 (2^200 would be inf)
    const float z = run_instruction(Opcode::Lit, rd(0), {c(0)}, {{1, 2, 0, 200}})[2];
    EXPECT_NEAR(z, 3.39364e38f, 0.00002e38f);
    // y = 0.5, w = -200: clamped to -127.9961, 0.5^-127.9961 = 2^127.9961 again
    EXPECT_NEAR(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{1, 0.5f, 0, -200}})[2], 3.39364e38f, 0.00002e38f);
}

TEST(Lit, PowerZeroGivesOne) {
    // y^0 = 1 for y > 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0), {c(0)}, {{0.5f, 0.3f, 0, 0}}), 1.0f, 0.5f, 1.0f, 1.0f);
}

TEST(Lit, NegateSwizzleMaskSaturate) {
    // c0.yxwz = (0.25, -2, -3, 0.5); negated (-0.25, 2, 3, -0.5): x <= 0 gives (1, 0, 0, 1)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0).mask("yz"), {c(0).swz("yxwz").neg()}, {{-2, 0.25f, 0.5f, -3}}), 9.0f, 0.0f, 0.0f, 9.0f);
    // c0.yxwz = (2, 0.5, 0, 1): x = 2, y = 0.5, power 1: (1, 2, 0.5, 1) -> sat (1, 1, 0.5, 1)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Lit, rd(0).sat(), {c(0).swz("yxwz")}, {{0.5f, 2, 1, 0}}), 1.0f, 1.0f, 0.5f, 1.0f);
}

}  // namespace
}  // namespace sm2::test
