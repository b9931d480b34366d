// frc d, s: s - floor(s), in [0, 1).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Frc, FractionalPart) {
    // 1.25 -> 0.25; -1.25 -> -1.25 - (-2) = 0.75; 3 -> 0; -0.5 -> 0.5
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Frc, rd(0), {c(0)}, {{1.25f, -1.25f, 3, -0.5f}}), 0.25f, 0.75f, 0.0f, 0.5f);
}

TEST(Frc, StaysBelowOne) {
    // -2^-30 - floor(-2^-30) = 1 - 2^-30, which rounds to 1 in float; the result is the largest
    // float below 1, 1 - 2^-24.
    EXPECT_EQ(run_instruction(Opcode::Frc, rd(0), {c(0)}, {{-0x1p-30f, 0, 0, 0}})[0], 1.0f - 0x1p-24f);
}

TEST(Frc, SpecialValues) {
    // frc(inf) = inf - inf = NaN; frc(NaN) = NaN; frc(-0) = -0 - (-0) = +0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Frc, rd(0), {c(0)}, {{kInf, -kInf, kNaN, -0.0f}}), kNaN, kNaN, kNaN, 0.0f);
}

TEST(Frc, NegateSwizzleMask) {
    // frc(-c0.w) = frc(-2.75) = 0.25 into .y
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Frc, rd(0).mask("y"), {c(0).swz("w").neg()}, {{0, 0, 0, 2.75f}}), 9.0f, 0.25f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
