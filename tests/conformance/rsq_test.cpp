// rsq d, s.r: 1/sqrt(|s|) replicated; rsq(1) = 1 exactly, rsq(+-0) = +inf (docs/numerics.md).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

float rsq_of(float x) { return run_instruction(Opcode::Rsq, rd(0), {c(0).swz("x")}, {{x, 0, 0, 0}})[2]; }

TEST(Rsq, NormalValues) {
    EXPECT_EQ(rsq_of(4.0f), 0.5f);
    EXPECT_EQ(rsq_of(0.25f), 2.0f);
    EXPECT_EQ(rsq_of(16.0f), 0.25f);
    EXPECT_EQ(rsq_of(1.0f), 1.0f);
    EXPECT_NEAR(rsq_of(2.0f), 0.70710678f, 1e-7f);
}

TEST(Rsq, SignIsIgnored) {
    EXPECT_EQ(rsq_of(-4.0f), 0.5f);
    EXPECT_EQ(rsq_of(-1.0f), 1.0f);
}

TEST(Rsq, SpecialValues) {
    EXPECT_TRUE(same_bits(rsq_of(0.0f), kInf));
    EXPECT_TRUE(same_bits(rsq_of(-0.0f), kInf));
    EXPECT_TRUE(same_bits(rsq_of(kInf), 0.0f));
    EXPECT_TRUE(same_bits(rsq_of(-kInf), 0.0f));
    EXPECT_TRUE(std::isnan(rsq_of(kNaN)));
}

TEST(Rsq, ReplicateMaskNegateSaturate) {
    // rsq_sat r0.xz, -c0.w with c0.w = 0.25: 2 -> sat 1
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Rsq, rd(0).mask("xz").sat(), {c(0).swz("w").neg()}, {{1, 1, 1, 0.25f}}),
                     1.0f, 9.0f, 1.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
