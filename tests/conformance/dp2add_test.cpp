// dp2add d, a, b, c.r (ps_2_0): a.x*b.x + a.y*b.y + c replicated.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

OneInstruction pixel() {
    OneInstruction how;
    how.shader = ShaderType::Pixel;
    return how;
}

TEST(Dp2Add, TwoComponentDotPlusScalar) {
    // 1*3 + 2*4 + c2.z (5) = 16; a.zw and b.zw are ignored
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp2Add, rd(0), {c(0), c(1), c(2).swz("z")}, {{1, 2, 100, 100}, {3, 4, 100, 100}, {0, 0, 5, 0}}, pixel()),
                     16.0f, 16.0f, 16.0f, 16.0f);
}

TEST(Dp2Add, SwizzleNegateMaskSaturate) {
    // c0.yzxw = (2, 3, 1, 4): (2*0.25 + 3*0.25) - 0.5 = 0.75 into .x; saturated stays 0.75
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Dp2Add, rd(0).mask("x").sat(), {c(0).swz("yzxw"), c(1), c(2).swz("w").neg()},
                                     {{1, 2, 3, 4}, {0.25f, 0.25f, 0, 0}, {0, 0, 0, 0.5f}}, pixel()),
                     0.75f, 9.0f, 9.0f, 9.0f);
}

TEST(Dp2Add, ZeroTimesInfinity) {
    // 0*inf + 2*2 + 1 = 5
    EXPECT_EQ(run_instruction(Opcode::Dp2Add, rd(0), {c(0), c(1), c(2).swz("x")}, {{0, 2, 0, 0}, {kInf, 2, 0, 0}, {1, 0, 0, 0}}, pixel())[2], 5.0f);
}

}  // namespace
}  // namespace sm2::test
