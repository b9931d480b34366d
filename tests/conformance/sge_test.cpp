// sge d, a, b (vs): (a >= b) ? 1 : 0 per component.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Sge, GreaterOrEqual) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sge, rd(0), {c(0), c(1)}, {{1, 2, 3, kInf}, {2, 2, 2, kInf}}), 0.0f, 1.0f, 1.0f, 1.0f);
}

TEST(Sge, NaNAndSignedZero) {
    // NaN compares false -> 0; -0 >= 0 is true
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sge, rd(0), {c(0), c(1)}, {{kNaN, 1, -0.0f, 0}, {1, kNaN, 0.0f, -0.0f}}), 0.0f, 0.0f, 1.0f, 1.0f);
}

TEST(Sge, NegateSwizzleMask) {
    // c0.wzyx = (4, 3, 2, 1) >= -c1 = (-4, 3, 3, -1) -> (1, 1, 0, 1); mask w
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sge, rd(0).mask("w"), {c(0).swz("wzyx"), c(1).neg()}, {{1, 2, 3, 4}, {4, -3, -3, 1}}), 9.0f, 9.0f, 9.0f, 1.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sge, rd(0), {c(0).swz("wzyx"), c(1).neg()}, {{1, 2, 3, 4}, {4, -3, -3, 1}}), 1.0f, 1.0f, 0.0f, 1.0f);
}

}  // namespace
}  // namespace sm2::test
