// sincos d.{x|y|xy}, s.r[, c1, c2]: d.x = cos(s), d.y = sin(s); z and w are left untouched (SM2
// leaves z undefined; docs/numerics.md). Exact libm results, well within the documented 0.002.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

// D3DSINCOSCONST1/2, the constants the vs form names (unused by the exact implementation).
const std::vector<Float4> kSinCosConstants{{0, 0, 0, 0}, {-1.5500992e-6f, -2.1701389e-5f, 0.0026041667f, 0.00026041668f},
                                           {-0.020833334f, -0.125f, 1.0f, 0.5f}};

Float4 sincos_of(float angle, Dst d, ShaderType shader = ShaderType::Vertex) {
    std::vector<Float4> constants = kSinCosConstants;
    constants[0] = {angle, 0, 0, 0};
    OneInstruction how;
    how.shader = shader;
    return run_instruction(Opcode::SinCos, d, {c(0).swz("x"), c(1), c(2)}, constants, how);
}

TEST(SinCos, KnownAngles) {
    EXPECT_FLOAT4_EQ(sincos_of(0.0f, rd(0).mask("xy")), 1.0f, 0.0f, 9.0f, 9.0f);
    // pi/2: cos = 0, sin = 1; pi: cos = -1, sin = 0; -pi/6: cos = sqrt(3)/2, sin = -0.5
    EXPECT_FLOAT4_NEAR(sincos_of(1.5707963f, rd(0).mask("xy")), 0.0f, 1.0f, 9.0f, 9.0f, 1e-6f);
    EXPECT_FLOAT4_NEAR(sincos_of(3.1415927f, rd(0).mask("xy")), -1.0f, 0.0f, 9.0f, 9.0f, 1e-6f);
    EXPECT_FLOAT4_NEAR(sincos_of(-0.52359878f, rd(0).mask("xy")), 0.8660254f, -0.5f, 9.0f, 9.0f, 1e-6f);
}

TEST(SinCos, SingleChannelMasks) {
    EXPECT_FLOAT4_NEAR(sincos_of(1.5707963f, rd(0).mask("y")), 9.0f, 1.0f, 9.0f, 9.0f, 1e-6f);
    EXPECT_FLOAT4_NEAR(sincos_of(3.1415927f, rd(0).mask("x")), -1.0f, 9.0f, 9.0f, 9.0f, 1e-6f);
}

TEST(SinCos, PixelShaderForm) {
    EXPECT_FLOAT4_NEAR(sincos_of(-1.5707963f, rd(0).mask("xy"), ShaderType::Pixel), 0.0f, -1.0f, 9.0f, 9.0f, 1e-6f);
}

TEST(SinCos, NegatedSource) {
    // sin(-(pi/6)) = -0.5
    std::vector<Float4> constants = kSinCosConstants;
    constants[0] = {0, 0.52359878f, 0, 0};
    EXPECT_FLOAT4_NEAR(run_instruction(Opcode::SinCos, rd(0).mask("xy"), {c(0).swz("y").neg(), c(1), c(2)}, constants),
                       0.8660254f, -0.5f, 9.0f, 9.0f, 1e-6f);
}

TEST(SinCos, OneSourceFormAsWineWritesIt) {
    // ps "sincos r0.xy, r1.x" without the constants (Wine's assembler)
    OneInstruction ps;
    ps.shader = ShaderType::Pixel;
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::SinCos, rd(0).mask("xy"), {c(0).swz("x")}, {{0, 0, 0, 0}}, ps), 1.0f, 0.0f, 9.0f, 9.0f);
}

}  // namespace
}  // namespace sm2::test
