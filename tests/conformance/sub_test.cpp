// sub d, a, b: r = a - b (instructions.md §3).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Sub, SubtractsComponentwise) {
    // (1-10, 2-20, 3-30, 4-40)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sub, rd(0), {c(0), c(1)}, {{1, 2, 3, 4}, {10, 20, 30, 40}}),
                     -9.0f, -18.0f, -27.0f, -36.0f);
}

TEST(Sub, NegatedSecondOperandAdds) {
    // c0 - (-c1.x) = c0 + 10; mask .w
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sub, rd(0).mask("w"), {c(0), c(1).swz("x").neg()}, {{1, 2, 3, 4}, {10, 20, 30, 40}}),
                     9.0f, 9.0f, 9.0f, 14.0f);
}

TEST(Sub, SpecialValues) {
    // inf - inf = NaN; 0 - 0 = +0; -0 - 0 = -0; 1 - NaN = NaN
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sub, rd(0), {c(0), c(1)}, {{kInf, 0, -0.0f, 1}, {kInf, 0, 0, kNaN}}),
                     kNaN, 0.0f, -0.0f, kNaN);
}

TEST(Sub, Saturate) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sub, rd(0).sat(), {c(0), c(1)}, {{2, 0.5f, 0, 1}, {0.5f, 0.25f, 1, 0}}),
                     1.0f, 0.25f, 0.0f, 1.0f);
}

}  // namespace
}  // namespace sm2::test
