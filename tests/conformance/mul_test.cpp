// mul d, a, b: r = a * b, with the legacy D3D9 rule 0 * anything = +0 (docs/numerics.md).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Mul, MultipliesComponentwise) {
    // (1.5*2, -2*3, 0.5*0.5, 4*-0.25)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mul, rd(0), {c(0), c(1)}, {{1.5f, -2, 0.5f, 4}, {2, 3, 0.5f, -0.25f}}),
                     3.0f, -6.0f, 0.25f, -1.0f);
}

TEST(Mul, ZeroTimesInfinityOrNaNIsZero) {
    // 0*inf = 0, inf*0 = 0, 0*NaN = 0, -0*-inf = +0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mul, rd(0), {c(0), c(1)}, {{0, kInf, 0, -0.0f}, {kInf, 0, kNaN, -kInf}}),
                     0.0f, 0.0f, 0.0f, 0.0f);
}

TEST(Mul, ZeroProductsArePositive) {
    // -0 * 5 = +0 and 3 * -0 = +0 (legacy multiply); inf * -2 = -inf; NaN * 1 = NaN
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mul, rd(0), {c(0), c(1)}, {{-0.0f, 3, kInf, kNaN}, {5, -0.0f, -2, 1}}),
                     0.0f, 0.0f, -kInf, kNaN);
}

TEST(Mul, NegateSwizzleMaskSaturate) {
    // -c0.zzzz * c1 = (-2*0.25, -2*-1, -2*0.5, -2*1) = (-0.5, 2, -1, -2) -> sat (0, 1, 0, 0); mask xy
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mul, rd(0).mask("xy").sat(), {c(0).swz("z").neg(), c(1)}, {{0, 0, 2, 0}, {0.25f, -1, 0.5f, 1}}),
                     0.0f, 1.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
