// nop: does nothing, in both profiles; it still counts as an executed instruction.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Nop, ChangesNothing) {
    for (ShaderType type : {ShaderType::Vertex, ShaderType::Pixel}) {
        ProgramBuilder p(type);
        p.op(Opcode::Mov, rd(0), {c(0)}).flow(Opcode::Nop).flow(Opcode::Nop);
        p.op(Opcode::Mov, type == ShaderType::Vertex ? oPos() : oC(0), {r(0)});
        const auto exe = lower_or_fail(p.program());
        EXPECT_EQ(exe.steps().size(), 2u);
        EXPECT_EQ(exe.executed_instructions(), 4u);  // mov, nop, nop, mov
        emu::Batch batch;
        emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1, 2, 3, 4}}), batch);
        EXPECT_FLOAT4_EQ(lane_value(type == ShaderType::Vertex ? batch.position() : batch.render_target(0)), 1.0f, 2.0f, 3.0f, 4.0f);
    }
}

}  // namespace
}  // namespace sm2::test
