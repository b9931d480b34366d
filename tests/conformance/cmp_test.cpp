// cmp d, c, a, b (ps_2_0): (c >= 0) ? a : b per component; -0 >= 0 is true, NaN picks b.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

OneInstruction pixel() {
    OneInstruction how;
    how.shader = ShaderType::Pixel;
    return how;
}

TEST(Cmp, SelectsPerComponent) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Cmp, rd(0), {c(0), c(1), c(2)}, {{1, -1, 0, -0.0f}, {10, 20, 30, 40}, {-10, -20, -30, -40}}, pixel()),
                     10.0f, -20.0f, 30.0f, 40.0f);
}

TEST(Cmp, NaNAndInfinity) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Cmp, rd(0), {c(0), c(1), c(2)}, {{kNaN, kInf, -kInf, 1e-40f}, {10, 20, 30, 40}, {-10, -20, -30, -40}}, pixel()),
                     -10.0f, 20.0f, -30.0f, 40.0f);
}

TEST(Cmp, ModifiersMaskSaturate) {
    // condition -c0 = (-1, 1, ...): x picks c2.x = 2 -> sat 1; y picks c1.wzyx.y = 0.5
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Cmp, rd(0).mask("xy").sat(), {c(0).neg(), c(1).swz("wzyx"), c(2)}, {{1, -1, 0, 0}, {0, 0, 0.5f, 0}, {2, -2, 0, 0}}, pixel()),
                     1.0f, 0.5f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
