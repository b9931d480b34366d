// mov d, s: r = s (instructions.md §3), with every source and destination modifier.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Mov, CopiesAllFourComponents) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0)}, {{1.5f, -2.0f, 0.0f, 1e30f}}),
                     1.5f, -2.0f, 0.0f, 1e30f);
}

TEST(Mov, NegateFlipsEverySign) {
    // -(1.5, -2, 0, -0) = (-1.5, 2, -0, +0)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0).neg()}, {{1.5f, -2.0f, 0.0f, -0.0f}}),
                     -1.5f, 2.0f, -0.0f, 0.0f);
}

TEST(Mov, SwizzleSelectsComponents) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0).swz("wzyx")}, {{1, 2, 3, 4}}), 4.0f, 3.0f, 2.0f, 1.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0).swz("yzxw")}, {{1, 2, 3, 4}}), 2.0f, 3.0f, 1.0f, 4.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0).swz("z")}, {{1, 2, 3, 4}}), 3.0f, 3.0f, 3.0f, 3.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0).swz("xxyy")}, {{1, 2, 3, 4}}), 1.0f, 1.0f, 2.0f, 2.0f);
}

TEST(Mov, WriteMaskLeavesOtherComponents) {
    // r0 starts (9, 9, 9, 9)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0).mask("xw"), {c(0)}, {{1, 2, 3, 4}}), 1.0f, 9.0f, 9.0f, 4.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0).mask("yz"), {c(0)}, {{1, 2, 3, 4}}), 9.0f, 2.0f, 3.0f, 9.0f);
}

TEST(Mov, SaturateClampsAndSendsNaNToZero) {
    // sat(-0.5) = 0, sat(0.5) = 0.5, sat(1.5) = 1, sat(NaN) = 0 (D3D10 rule)
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0).sat(), {c(0)}, {{-0.5f, 0.5f, 1.5f, kNaN}}),
                     0.0f, 0.5f, 1.0f, 0.0f);
    // sat(-inf) = 0, sat(+inf) = 1, sat(-0) = +0, sat(1) = 1
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0).sat(), {c(0)}, {{-kInf, kInf, -0.0f, 1.0f}}),
                     0.0f, 1.0f, 0.0f, 1.0f);
}

TEST(Mov, SpecialValuesPassUnchanged) {
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0), {c(0)}, {{kNaN, -kInf, -0.0f, 1e-40f}}),
                     kNaN, -kInf, -0.0f, 1e-40f);  // fp32 keeps denormals
}

TEST(Mov, WorksInPixelShaders) {
    OneInstruction ps;
    ps.shader = ShaderType::Pixel;
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::Mov, rd(0).sat().pp(), {c(0).swz("wzyx").neg()}, {{-1, 0.25f, 2, -0.5f}}, ps),
                     0.5f, 0.0f, 0.0f, 1.0f);  // -(w z y x) = (0.5, -2, -0.25, 1) saturated
}

}  // namespace
}  // namespace sm2::test
