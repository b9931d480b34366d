// mad d, a, b, c: r = a * b + c, product rounded before the sum (no fused multiply-add).
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Mad, MultipliesThenAdds) {
    // (2*3+1, -1*4+0.5, 0.5*0.5+0.25, 10*10-100)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mad, rd(0), {c(0), c(1), c(2)},
                                     {{2, -1, 0.5f, 10}, {3, 4, 0.5f, 10}, {1, 0.5f, 0.25f, -100}}),
                     7.0f, -3.5f, 0.5f, 0.0f);
}

TEST(Mad, ProductIsRoundedBeforeTheSum) {
    // a = 1 + 2^-12: a*a = 1 + 2^-11 + 2^-24 exactly; rounded to float (24-bit mantissa) the
    // 2^-24 term is a tie that goes to even: 1 + 2^-11. Then - (1 + 2^-11) = 0. A fused mad
    // would give 2^-24.
    const float a = 1.0f + 0x1p-12f;
    const float minus_c = -(1.0f + 0x1p-11f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mad, rd(0), {c(0), c(0), c(1)}, {{a, a, a, a}, {minus_c, minus_c, minus_c, minus_c}}),
                     0.0f, 0.0f, 0.0f, 0.0f);
}

TEST(Mad, ZeroTimesInfinityPlusOneIsOne) {
    // legacy multiply: 0*inf = 0, so 0*inf + 1 = 1; inf*2 + -inf = NaN
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mad, rd(0), {c(0), c(1), c(2)},
                                     {{0, kInf, kInf, 1}, {kInf, 0, 2, 1}, {1, 1, -kInf, 1}}),
                     1.0f, 1.0f, kNaN, 2.0f);
}

TEST(Mad, ModifiersAndSaturate) {
    // -c0.x * c1.yzxw + c2 = (-1*2+1, -1*3+4, -1*1+0.5, -1*4+4) = (-1, 1, -0.5, 0) -> sat (0, 1, 0, 0)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mad, rd(0).sat().mask("xyw"), {c(0).swz("x").neg(), c(1).swz("yzxw"), c(2)},
                                     {{1, 0, 0, 0}, {1, 2, 3, 4}, {1, 4, 0.5f, 4}}),
                     0.0f, 1.0f, 9.0f, 0.0f);
}

}  // namespace
}  // namespace sm2::test
