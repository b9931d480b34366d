// rcp d, s.r: 1/s replicated to the write mask; rcp(1) = 1 exactly, rcp(+0) = +inf,
// rcp(-0) = -inf (docs/numerics.md).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

float rcp_of(float x, Dst d = rd(0)) { return run_instruction(Opcode::Rcp, d, {c(0).swz("x")}, {{x, 0, 0, 0}})[1]; }

TEST(Rcp, NormalValues) {
    EXPECT_EQ(rcp_of(2.0f), 0.5f);
    EXPECT_EQ(rcp_of(-4.0f), -0.25f);
    EXPECT_EQ(rcp_of(0.125f), 8.0f);
    EXPECT_EQ(rcp_of(3.0f), 1.0f / 3.0f);  // correctly rounded: 0x3EAAAAAB
    EXPECT_EQ(rcp_of(1.0f), 1.0f);
}

TEST(Rcp, SpecialValues) {
    EXPECT_TRUE(same_bits(rcp_of(0.0f), kInf));
    EXPECT_TRUE(same_bits(rcp_of(-0.0f), -kInf));
    EXPECT_TRUE(same_bits(rcp_of(kInf), 0.0f));
    EXPECT_TRUE(same_bits(rcp_of(-kInf), -0.0f));
    EXPECT_TRUE(std::isnan(rcp_of(kNaN)));
}

TEST(Rcp, ReplicatesToTheMaskAndReadsTheSwizzledComponent) {
    // rcp r0.yw, -c0.z with c0.z = 4: -0.25 into y and w
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Rcp, rd(0).mask("yw"), {c(0).swz("z").neg()}, {{1, 2, 4, 8}}),
                     9.0f, -0.25f, 9.0f, -0.25f);
}

TEST(Rcp, Saturate) {
    // rcp(0.5) = 2 -> 1; rcp(0) = inf -> 1
    EXPECT_EQ(run_instruction(Opcode::Rcp, rd(0).sat(), {c(0).swz("x")}, {{0.5f, 0, 0, 0}})[0], 1.0f);
    EXPECT_EQ(run_instruction(Opcode::Rcp, rd(0).sat(), {c(0).swz("x")}, {{0.0f, 0, 0, 0}})[0], 1.0f);
    EXPECT_EQ(run_instruction(Opcode::Rcp, rd(0).sat(), {c(0).swz("x")}, {{-0.0f, 0, 0, 0}})[0], 0.0f);
}

}  // namespace
}  // namespace sm2::test
