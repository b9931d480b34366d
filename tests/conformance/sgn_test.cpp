// sgn d, a, t1, t2 (vs): -1, 0 or 1 per component; t1 and t2 are scratch temps.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Sgn, SignOfEachComponent) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sgn, rd(0), {c(0), r(1), r(2)}, {{-3, 0, 5, -kInf}}), -1.0f, 0.0f, 1.0f, -1.0f);
}

TEST(Sgn, SignedZeroAndNaN) {
    // -0 == 0 -> 0 (+0); NaN: not < 0, not == 0 -> 1 (literal pseudo-code); tiny values keep their sign
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sgn, rd(0), {c(0), r(1), r(2)}, {{-0.0f, kNaN, 1e-40f, -1e-40f}}), 0.0f, 1.0f, 1.0f, -1.0f);
}

TEST(Sgn, NegateSwizzleMask) {
    // sgn(-c0.wzyx) = sgn(-(4, 0, -2, 1)) = (-1, 0, 1, -1); mask xyw
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Sgn, rd(0).mask("xyw"), {c(0).swz("wzyx").neg(), r(1), r(2)}, {{1, -2, 0, 4}}), -1.0f, 0.0f, 9.0f, -1.0f);
}

}  // namespace
}  // namespace sm2::test
