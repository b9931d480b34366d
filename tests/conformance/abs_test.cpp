// abs d, s: |s| per component.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Abs, AbsoluteValue) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Abs, rd(0), {c(0)}, {{-2, 3, -0.0f, -kInf}}), 2.0f, 3.0f, 0.0f, kInf);
}

TEST(Abs, NegateIsAppliedFirst) {
    // abs(-c0.yzxw) = |-(2, -3, 1, -4)| = (2, 3, 1, 4); mask xz
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Abs, rd(0).mask("xz"), {c(0).swz("yzxw").neg()}, {{1, 2, -3, -4}}), 2.0f, 9.0f, 1.0f, 9.0f);
}

TEST(Abs, SaturateAndNaN) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Abs, rd(0).sat(), {c(0)}, {{-2, -0.5f, kNaN, 0}}), 1.0f, 0.5f, 0.0f, 0.0f);
    EXPECT_TRUE(std::isnan(run_instruction(Opcode::Abs, rd(0), {c(0)}, {{kNaN, 0, 0, 0}})[0]));
}

}  // namespace
}  // namespace sm2::test
