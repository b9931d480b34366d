// expp d, s.r (vs_2_0): the 2.0 form is 2^s replicated to the mask, not the vs_1_1 layout.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Expp, ReplicatedPowerOfTwo) {
    // 2^2.5 = 5.656854; every channel, not (2^floor, frac, 2^x, 1)
    const Float4 r = run_instruction(Opcode::ExpP, rd(0), {c(0).swz("x")}, {{2.5f, 0, 0, 0}});
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(r[k], 5.65685425f, 5.65685425f * 0x1p-10f);
}

TEST(Expp, ExactPowersAndSpecialValues) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::ExpP, rd(0).mask("xz"), {c(0).swz("w").neg()}, {{0, 0, 0, 4}}),
                     0.0625f, 9.0f, 0.0625f, 9.0f);  // 2^-4
    EXPECT_EQ(run_instruction(Opcode::ExpP, rd(0), {c(0).swz("x")}, {{-kInf, 0, 0, 0}})[0], 0.0f);
}

}  // namespace
}  // namespace sm2::test
