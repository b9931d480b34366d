// log d, s.r: log2(|s|) replicated; log(+-0) = -inf (docs/numerics.md).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

float log_of(float x) { return run_instruction(Opcode::Log, rd(0), {c(0).swz("z")}, {{0, 0, x, 0}})[0]; }

TEST(Log, PowersOfTwo) {
    EXPECT_EQ(log_of(8.0f), 3.0f);
    EXPECT_EQ(log_of(0.5f), -1.0f);
    EXPECT_EQ(log_of(1.0f), 0.0f);
    EXPECT_EQ(log_of(1024.0f), 10.0f);
    EXPECT_NEAR(log_of(3.0f), 1.5849625f, 2e-7f);
}

TEST(Log, SignIsIgnored) {
    EXPECT_EQ(log_of(-8.0f), 3.0f);
    EXPECT_EQ(log_of(-0.25f), -2.0f);
}

TEST(Log, SpecialValues) {
    EXPECT_TRUE(same_bits(log_of(0.0f), -kInf));
    EXPECT_TRUE(same_bits(log_of(-0.0f), -kInf));
    EXPECT_TRUE(same_bits(log_of(kInf), kInf));
    EXPECT_TRUE(same_bits(log_of(-kInf), kInf));
    EXPECT_TRUE(std::isnan(log_of(kNaN)));
}

TEST(Log, MaskSaturate) {
    // log_sat r0.w, c0.x: log2(4) = 2 -> 1; log2(0.5) = -1 -> 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Log, rd(0).mask("w").sat(), {c(0).swz("x")}, {{4, 0, 0, 0}}), 9.0f, 9.0f, 9.0f, 1.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Log, rd(0).mask("x").sat(), {c(0).swz("x").neg()}, {{0.5f, 0, 0, 0}}), 0.0f, 9.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
