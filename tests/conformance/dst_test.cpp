// dst d, a, b (vs): (1, a.y * b.y, a.z, b.w).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Dst, DistanceVector) {
    // d = 2: a = (_, d*d, d*d, _) = (7, 4, 4, 7), b = (_, 1/d, _, 1/d) = (7, 0.5, 7, 0.5):
    // (1, 4 * 0.5 = 2, 4, 0.5)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dst, rd(0), {c(0), c(1)}, {{7, 4, 4, 7}, {7, 0.5f, 7, 0.5f}}), 1.0f, 2.0f, 4.0f, 0.5f);
}

TEST(Dst, ZeroTimesInfinity) {
    // a.y = 0, b.y = inf: legacy multiply gives 0
    EXPECT_EQ(run_instruction(Opcode::Dst, rd(0), {c(0), c(1)}, {{0, 0, 0, 0}, {0, kInf, 0, 0}})[1], 0.0f);
}

TEST(Dst, NegateSwizzleMask) {
    // a = -c0.wzyx = -(4, 3, 2, 1) = (-4, -3, -2, -1); b = c1: (1, -3 * 2 = -6, -2, 5); mask yz
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dst, rd(0).mask("yz"), {c(0).swz("wzyx").neg(), c(1)}, {{1, 2, 3, 4}, {0, 2, 0, 5}}), 9.0f, -6.0f, -2.0f, 9.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dst, rd(0).sat(), {c(0).swz("wzyx").neg(), c(1)}, {{1, 2, 3, 4}, {0, 2, 0, 5}}), 1.0f, 0.0f, 0.0f, 1.0f);
}

}  // namespace
}  // namespace sm2::test
