// add d, a, b: r = a + b (instructions.md §3).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Add, AddsComponentwise) {
    // (1+10, 2+20, 3+30, 4+40)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Add, rd(0), {c(0), c(1)}, {{1, 2, 3, 4}, {10, 20, 30, 40}}),
                     11.0f, 22.0f, 33.0f, 44.0f);
}

TEST(Add, NegateSwizzleAndMask) {
    // -c0.wzyx + c1 = (-4+10, -3+20, -2+30, -1+40); mask .xyz keeps w = 9
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Add, rd(0).mask("xyz"), {c(0).swz("wzyx").neg(), c(1)},
                                     {{1, 2, 3, 4}, {10, 20, 30, 40}}),
                     6.0f, 17.0f, 28.0f, 9.0f);
}

TEST(Add, SpecialValues) {
    // inf + -inf = NaN; inf + 1 = inf; -0 + -0 = -0; -0 + 0 = +0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Add, rd(0), {c(0), c(1)}, {{kInf, kInf, -0.0f, -0.0f}, {-kInf, 1, -0.0f, 0.0f}}),
                     kNaN, kInf, -0.0f, 0.0f);
}

TEST(Add, Saturate) {
    // 0.75 + 0.5 = 1.25 -> 1; 0.25 - 0.5 = -0.25 -> 0; 0.25 + 0.5 = 0.75; NaN -> 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Add, rd(0).sat(), {c(0), c(1)}, {{0.75f, 0.25f, 0.25f, kNaN}, {0.5f, -0.5f, 0.5f, 0}}),
                     1.0f, 0.0f, 0.75f, 0.0f);
}

}  // namespace
}  // namespace sm2::test
