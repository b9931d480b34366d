// m4x4 d, s0, s1: d.[xyzw] = dp4(s0, s1 + k) for rows k = 0..3.
#include <gtest/gtest.h>

#include "conformance/matrix_test_support.h"

namespace sm2::test {
namespace {

TEST(M4x4, FourDotProducts) {
    // v = (1, 0, 2, -1): row0 1+0+6-4 = 3; row1 5+0+14-8 = 11; row2 9+0+22-12 = 19; row3 13+0+30-16 = 27
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x4, rd(0), {c(0), c(1)}, matrix_constants({1, 0, 2, -1})), 3.0f, 11.0f, 19.0f, 27.0f);
}

TEST(M4x4, NegatedSwizzledVectorAndSaturate) {
    // -v.wzyx with v = (1, 0, 0, 0): (-0, -0, -0, -1): rows give -4, -8, -12, -16 -> sat 0
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x4, rd(0).sat(), {c(0).swz("wzyx").neg(), c(1)}, matrix_constants({1, 0, 0, 0})), 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M4x4, rd(0), {c(0).swz("wzyx").neg(), c(1)}, matrix_constants({1, 0, 0, 0})), -4.0f, -8.0f, -12.0f, -16.0f);
}

TEST(M4x4, RelativeRows) {
    // m4x4 r0, c0, c[a0.x + 0] with a0.x = 1: rows c1..c4
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mova, a0().mask("x"), {c(5).swz("x")}).op(Opcode::M4x4, oPos(), {c(0), c(0).rel_a0('x')});
    const auto exe = lower_or_fail(p.program());
    auto constants = matrix_constants({0, 1, 0, 0});
    constants.push_back({1, 0, 0, 0});
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(constants), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 2.0f, 6.0f, 10.0f, 14.0f);  // the y column
}

}  // namespace
}  // namespace sm2::test
