// crs d, a, b: cross product of the xyz parts; w is never written.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Crs, CrossProduct) {
    // x cross y = z
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("xyz"), {c(0), c(1)}, {{1, 0, 0, 5}, {0, 1, 0, 5}}), 0.0f, 0.0f, 1.0f, 9.0f);
    // (1,2,3) x (4,5,6) = (2*6 - 3*5, 3*4 - 1*6, 1*5 - 2*4) = (-3, 6, -3)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("xyz"), {c(0), c(1)}, {{1, 2, 3, 0}, {4, 5, 6, 0}}), -3.0f, 6.0f, -3.0f, 9.0f);
}

TEST(Crs, PartialMasksLeaveTheRest) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("xz"), {c(0), c(1)}, {{1, 2, 3, 0}, {4, 5, 6, 0}}), -3.0f, 9.0f, -3.0f, 9.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("y"), {c(0), c(1)}, {{1, 2, 3, 0}, {4, 5, 6, 0}}), 9.0f, 6.0f, 9.0f, 9.0f);
}

TEST(Crs, NegateAndSaturate) {
    // -(1,2,3) x (4,5,6) = (3, -6, 3) -> sat (1, 0, 1)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("xyz").sat(), {c(0).neg(), c(1)}, {{1, 2, 3, 0}, {4, 5, 6, 0}}), 1.0f, 0.0f, 1.0f, 9.0f);
}

TEST(Crs, ZeroTimesInfinity) {
    // (0, 0, 1) x (inf, 0, 0): x = 0*0 - 1*0 = 0, y = 1*inf - 0*0 = inf, z = 0*0 - 0*inf = 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Crs, rd(0).mask("xyz"), {c(0), c(1)}, {{0, 0, 1, 0}, {kInf, 0, 0, 0}}), 0.0f, kInf, 0.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
