// logp d, s.r (vs_2_0): log2(|s|) replicated, 0 -> -inf (as log), not the vs_1_1 layout.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Logp, ReplicatedLogarithm) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::LogP, rd(0), {c(0).swz("y")}, {{0, -16, 0, 0}}), 4.0f, 4.0f, 4.0f, 4.0f);
    const Float4 r = run_instruction(Opcode::LogP, rd(0).mask("z"), {c(0).swz("x")}, {{10, 0, 0, 0}});
    EXPECT_NEAR(r[2], 3.32192809f, 0x1p-10f);  // log2(10), at least 10 bits
    EXPECT_EQ(r[0], 9.0f);
}

TEST(Logp, ZeroIsMinusInfinity) {
    EXPECT_TRUE(same_bits(run_instruction(Opcode::LogP, rd(0), {c(0).swz("x")}, {{0, 0, 0, 0}})[1], -kInf));
}

}  // namespace
}  // namespace sm2::test
