// slt d, a, b (vs): (a < b) ? 1 : 0 per component.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Slt, LessThan) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Slt, rd(0), {c(0), c(1)}, {{1, 2, 3, -kInf}, {2, 2, 2, 0}}), 1.0f, 0.0f, 0.0f, 1.0f);
}

TEST(Slt, NaNAndSignedZero) {
    // NaN compares false -> 0; -0 < 0 is false
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Slt, rd(0), {c(0), c(1)}, {{kNaN, 1, -0.0f, 0}, {1, kNaN, 0.0f, 0}}), 0.0f, 0.0f, 0.0f, 0.0f);
}

TEST(Slt, NegateSwizzleMask) {
    // -c0.x = -1 < c1 = (0, -2, -1, 5) -> (1, 0, 0, 1); mask xyz
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Slt, rd(0).mask("xyz"), {c(0).swz("x").neg(), c(1)}, {{1, 0, 0, 0}, {0, -2, -1, 5}}), 1.0f, 0.0f, 0.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
