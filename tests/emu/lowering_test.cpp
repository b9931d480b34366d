// Lowering: static flow control resolved for the draw's b#/i# values, loops unrolled with aL
// folded into constant indices, calls inlined, matrix macros expanded, dead code removed.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

using emu::OperandKind;
using emu::StaticFlowConstants;

// if b0 / else / endif choosing between c0 and c1 for oPos.
isa::Program if_else_program(bool negated) {
    ProgramBuilder p(ShaderType::Vertex);
    p.flow(Opcode::If, {negated ? b(0).logical_not() : b(0)})
        .op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::Else)
        .op(Opcode::Mov, rd(0), {c(1)})
        .flow(Opcode::EndIf)
        .op(Opcode::Mov, oPos(), {r(0)});
    return p.program();
}

TEST(Lowering, IfTakenKeepsTheIfBlockOnly) {
    StaticFlowConstants flow;
    flow.booleans[0] = true;
    const auto exe = lower_or_fail(if_else_program(false), flow);
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].sources[0].kind, OperandKind::Constant);
    EXPECT_EQ(exe.steps()[0].sources[0].index, 0u);
}

TEST(Lowering, IfNotTakenKeepsTheElseBlockOnly) {
    const auto exe = lower_or_fail(if_else_program(false), {});  // b0 defaults to FALSE
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].sources[0].index, 1u);
}

TEST(Lowering, IfNotInvertsTheCondition) {
    const auto exe = lower_or_fail(if_else_program(true), {});  // !FALSE = taken
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].sources[0].index, 0u);
}

TEST(Lowering, IfWithoutElseDroppedLeavesNothing) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::If, {b(3)})
        .op(Opcode::Add, rd(0), {r(0), c(1)})
        .flow(Opcode::EndIf)
        .op(Opcode::Mov, oPos(), {r(0)});
    EXPECT_EQ(lower_or_fail(p.program()).steps().size(), 2u);
    StaticFlowConstants flow;
    flow.booleans[3] = true;
    EXPECT_EQ(lower_or_fail(p.program(), flow).steps().size(), 3u);
}

TEST(Lowering, DefbOverridesTheApplicationValue) {
    ProgramBuilder p(ShaderType::Vertex);
    p.defb(0, true);
    for (const auto& ins : if_else_program(false).instructions) {
        isa::Program& program = const_cast<isa::Program&>(p.program());
        program.instructions.push_back(ins);
    }
    const auto exe = lower_or_fail(p.program(), {});  // application b0 = FALSE, defb says TRUE
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].sources[0].index, 0u);
}

isa::Program loop_program() {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::Loop, {aL(), i(0)})
        .op(Opcode::Add, rd(0), {r(0), c(10).rel_aL()})
        .flow(Opcode::EndLoop)
        .op(Opcode::Mov, oPos(), {r(0)});
    return p.program();
}

TEST(Lowering, LoopUnrollsWithStartAndStep) {
    StaticFlowConstants flow;
    flow.integers[0] = {3, 2, 2, 0};  // 3 iterations, aL = 2, 4, 6
    const auto exe = lower_or_fail(loop_program(), flow);
    ASSERT_EQ(exe.steps().size(), 5u);
    // c[aL + 10] -> c12, c14, c16
    EXPECT_EQ(exe.steps()[1].sources[1].kind, OperandKind::Constant);
    EXPECT_EQ(exe.steps()[1].sources[1].index, 12u);
    EXPECT_EQ(exe.steps()[2].sources[1].index, 14u);
    EXPECT_EQ(exe.steps()[3].sources[1].index, 16u);
}

TEST(Lowering, LoopWithNegativeStepCountsDown) {
    StaticFlowConstants flow;
    flow.integers[0] = {3, 5, -2, 0};  // aL = 5, 3, 1
    const auto exe = lower_or_fail(loop_program(), flow);
    ASSERT_EQ(exe.steps().size(), 5u);
    EXPECT_EQ(exe.steps()[1].sources[1].index, 15u);
    EXPECT_EQ(exe.steps()[2].sources[1].index, 13u);
    EXPECT_EQ(exe.steps()[3].sources[1].index, 11u);
}

TEST(Lowering, LoopRunsAndSumsTheAddressedConstants) {
    StaticFlowConstants flow;
    flow.integers[0] = {3, 2, 2, 0};
    const auto exe = lower_or_fail(loop_program(), flow);
    std::vector<Float4> constants(20, Float4{0, 0, 0, 0});
    constants[0] = {1, 1, 1, 1};
    constants[12] = {1, 2, 3, 4};
    constants[14] = {10, 20, 30, 40};
    constants[16] = {100, 200, 300, 400};
    constants[13] = {5000, 5000, 5000, 5000};  // not addressed: must not appear
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(constants), batch);
    // 1 + 1 + 10 + 100 = 112, 1 + 2 + 20 + 200 = 223, ...
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 5), 112.0f, 223.0f, 334.0f, 445.0f);
}

TEST(Lowering, LoopAddressOutsideTheConstantFileReadsZero) {
    StaticFlowConstants flow;
    flow.integers[0] = {1, 250, 0, 0};  // aL = 250, c[aL + 10] = c260 > c255
    const auto exe = lower_or_fail(loop_program(), flow);
    ASSERT_EQ(exe.steps().size(), 3u);
    EXPECT_EQ(exe.steps()[1].sources[1].kind, OperandKind::Zero);
}

TEST(Lowering, DefiOverridesTheApplicationLoopCount) {
    ProgramBuilder p(ShaderType::Vertex);
    p.defi(0, 2, 0, 1, 0);
    for (const auto& ins : loop_program().instructions)
        const_cast<isa::Program&>(p.program()).instructions.push_back(ins);
    StaticFlowConstants flow;
    flow.integers[0] = {7, 0, 1, 0};
    EXPECT_EQ(lower_or_fail(p.program(), flow).steps().size(), 4u);  // mov, 2 adds, mov
}

isa::Program rep_program() {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::Rep, {i(1)})
        .op(Opcode::Add, rd(0), {r(0), c(1)})
        .flow(Opcode::EndRep)
        .op(Opcode::Mov, oPos(), {r(0)});
    return p.program();
}

TEST(Lowering, RepCountZeroSkipsTheBody) {
    StaticFlowConstants flow;
    flow.integers[1] = {0, 0, 0, 0};
    EXPECT_EQ(lower_or_fail(rep_program(), flow).steps().size(), 2u);
}

TEST(Lowering, RepRepeatsTheBodyCountTimes) {
    StaticFlowConstants flow;
    flow.integers[1] = {3, 99, 99, 0};  // .y and .z mean nothing to rep
    const auto exe = lower_or_fail(rep_program(), flow);
    EXPECT_EQ(exe.steps().size(), 5u);
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1, 2, 3, 4}, {0.5f, 1, 2, 4}}), batch);
    // c0 + 3 * c1 = (1 + 1.5, 2 + 3, 3 + 6, 4 + 12)
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 2.5f, 5.0f, 9.0f, 16.0f);
}

isa::Program call_program() {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::Call, {l(1)})
        .flow(Opcode::CallNz, {l(2), b(1)})
        .op(Opcode::Mov, oPos(), {r(0)})
        .flow(Opcode::Ret)
        .flow(Opcode::Label, {l(1)})
        .op(Opcode::Add, rd(0), {r(0), c(1)})
        .flow(Opcode::Ret)
        .flow(Opcode::Label, {l(2)})
        .op(Opcode::Mul, rd(0), {r(0), c(2)})
        .flow(Opcode::Ret);
    return p.program();
}

TEST(Lowering, CallIsInlinedAndCallNzFollowsItsBoolean) {
    const auto not_taken = lower_or_fail(call_program(), {});
    ASSERT_EQ(not_taken.steps().size(), 3u);  // mov, add (from l1), mov oPos
    EXPECT_EQ(not_taken.steps()[1].opcode, Opcode::Add);

    StaticFlowConstants flow;
    flow.booleans[1] = true;
    const auto taken = lower_or_fail(call_program(), flow);
    ASSERT_EQ(taken.steps().size(), 4u);
    EXPECT_EQ(taken.steps()[2].opcode, Opcode::Mul);
    emu::Batch batch;
    emu::execute(taken, taken.bind_constants(std::vector<Float4>{{1, 2, 3, 4}, {1, 1, 1, 1}, {2, 3, 4, 5}}), batch);
    // (c0 + c1) * c2 = (2*2, 3*3, 4*4, 5*5)
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 4.0f, 9.0f, 16.0f, 25.0f);
}

TEST(Lowering, CallInsideALoopSeesTheCallersLoopCounter) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)})
        .flow(Opcode::Loop, {aL(), i(0)})
        .flow(Opcode::Call, {l(0)})
        .flow(Opcode::EndLoop)
        .op(Opcode::Mov, oPos(), {r(0)})
        .flow(Opcode::Ret)
        .flow(Opcode::Label, {l(0)})
        .op(Opcode::Add, rd(0), {r(0), c(20).rel_aL()})
        .flow(Opcode::Ret);
    StaticFlowConstants flow;
    flow.integers[0] = {2, 1, 3, 0};  // aL = 1, 4
    const auto exe = lower_or_fail(p.program(), flow);
    ASSERT_EQ(exe.steps().size(), 4u);
    EXPECT_EQ(exe.steps()[1].sources[1].index, 21u);
    EXPECT_EQ(exe.steps()[2].sources[1].index, 24u);
}

TEST(Lowering, RetInTheMainProgramEndsIt) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(0)}).flow(Opcode::Ret);
    EXPECT_EQ(lower_or_fail(p.program()).steps().size(), 1u);
}

TEST(Lowering, DeadCodeIsRemoved) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(1), {c(1)})           // never read
        .op(Opcode::Mov, rd(0), {c(0)})
        .op(Opcode::Mov, rd(2), {c(2)})        // overwritten before it is read
        .op(Opcode::Mov, rd(2), {c(3)})
        .op(Opcode::Add, oPos(), {r(0), r(2)});
    const auto exe = lower_or_fail(p.program());
    ASSERT_EQ(exe.steps().size(), 3u);
    EXPECT_EQ(exe.steps()[0].sources[0].index, 0u);
    EXPECT_EQ(exe.steps()[1].sources[0].index, 3u);
}

TEST(Lowering, WriteMasksShrinkToTheChannelsRead) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mul, rd(0), {c(0), c(1)})
        .op(Opcode::Mov, oPos(), {r(0).swz("x")});
    const auto exe = lower_or_fail(p.program());
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].dest.mask, 0x1);
    EXPECT_EQ(exe.steps()[0].sources[0].channels, 0x1);
}

TEST(Lowering, OutputsTheNextStageDoesNotReadAreNotComputed) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(0)}).op(Opcode::Mov, oT(3), {c(1)});
    emu::LoweringOptions options;
    options.outputs_read = 1u << (emu::slot::kPosition - emu::slot::kPosition);
    EXPECT_EQ(lower_or_fail(p.program(), {}, options).steps().size(), 1u);
    EXPECT_EQ(lower_or_fail(p.program()).steps().size(), 2u);
}

TEST(Lowering, TexkillIsNeverDead) {
    ProgramBuilder p(ShaderType::Pixel);
    p.op(Opcode::Sub, rd(0), {t(0), c(0)}).texkill(rd(0)).op(Opcode::Mov, oC(0), {c(1)});
    EXPECT_EQ(lower_or_fail(p.program()).steps().size(), 3u);
}

TEST(Lowering, AddressRegisterStaysDynamicAndIsKeptAlive) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mova, a0().mask("x"), {c(0).swz("x")})
        .op(Opcode::Mov, oPos(), {c(2).rel_a0('x')});
    const auto exe = lower_or_fail(p.program());
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_TRUE(exe.steps()[0].dest.address);
    EXPECT_EQ(exe.steps()[1].sources[0].kind, OperandKind::RelativeConstant);
    EXPECT_EQ(exe.steps()[1].sources[0].index, 2u);
}

TEST(Lowering, MatrixMacrosBecomeDotProducts) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::M4x4, oPos(), {v(0), c(4)}).op(Opcode::M3x2, oT(0).mask("xy"), {v(1), c(8)});
    const auto exe = lower_or_fail(p.program());
    ASSERT_EQ(exe.steps().size(), 6u);
    for (unsigned row = 0; row < 4; ++row) {
        EXPECT_EQ(exe.steps()[row].opcode, Opcode::Dp4);
        EXPECT_EQ(exe.steps()[row].dest.mask, 1u << row);
        EXPECT_EQ(exe.steps()[row].sources[1].index, 4u + row);
    }
    EXPECT_EQ(exe.steps()[4].opcode, Opcode::Dp3);
    EXPECT_EQ(exe.steps()[5].sources[1].index, 9u);
}

TEST(Lowering, ExecutedInstructionLimitIsEnforced) {
    StaticFlowConstants flow;
    flow.integers[1] = {20, 0, 0, 0};
    emu::LoweringOptions options;
    options.max_executed_instructions = 30;  // mov + rep + 20 * (add + endrep) + mov = 43
    const std::string error = lowering_error(rep_program(), flow, options);
    EXPECT_NE(error.find("executed-instruction limit of 30"), std::string::npos) << error;
    options.max_executed_instructions = 43;
    EXPECT_EQ(lowering_error(rep_program(), flow, options), "");
}

TEST(Lowering, ExecutedInstructionCountIsReported) {
    StaticFlowConstants flow;
    flow.integers[1] = {2, 0, 0, 0};
    emu::LoweringOptions options;
    // mov, rep, (add, endrep) x 2, mov
    EXPECT_EQ(lower_or_fail(rep_program(), flow, options).executed_instructions(), 7u);
}

TEST(Lowering, MalformedStructureIsAnErrorNotACrash) {
    ProgramBuilder else_alone(ShaderType::Vertex);
    else_alone.flow(Opcode::Else);
    EXPECT_NE(lowering_error(else_alone.program()).find("else without a matching if"), std::string::npos);

    ProgramBuilder unclosed(ShaderType::Vertex);
    unclosed.flow(Opcode::Rep, {i(0)}).op(Opcode::Mov, oPos(), {c(0)});
    EXPECT_NE(lowering_error(unclosed.program()).find("never closed"), std::string::npos);

    ProgramBuilder mismatched(ShaderType::Vertex);
    mismatched.flow(Opcode::Rep, {i(0)}).flow(Opcode::EndLoop);
    EXPECT_NE(lowering_error(mismatched.program()).find("without a matching start"), std::string::npos);

    ProgramBuilder missing_label(ShaderType::Vertex);
    missing_label.flow(Opcode::Call, {l(5)}).op(Opcode::Mov, oPos(), {c(0)});
    EXPECT_NE(lowering_error(missing_label.program()).find("l5, which is not defined"), std::string::npos);

    ProgramBuilder loop_counter_outside(ShaderType::Vertex);
    loop_counter_outside.op(Opcode::Mov, oPos(), {c(0).rel_aL()});
    EXPECT_NE(lowering_error(loop_counter_outside.program()).find("outside a loop"), std::string::npos);

    ProgramBuilder recursive(ShaderType::Vertex);
    recursive.flow(Opcode::Call, {l(0)}).flow(Opcode::Ret).flow(Opcode::Label, {l(0)})
        .flow(Opcode::Call, {l(0)}).flow(Opcode::Ret);
    EXPECT_NE(lowering_error(recursive.program()).find("calls nest deeper"), std::string::npos);
}

TEST(Shader, ReportsTheFlowConstantsItReads) {
    ProgramBuilder p(ShaderType::Vertex);
    p.defb(2, true)
        .flow(Opcode::If, {b(2)}).flow(Opcode::EndIf)
        .flow(Opcode::If, {b(5)}).flow(Opcode::EndIf)
        .flow(Opcode::Rep, {i(3)}).flow(Opcode::EndRep)
        .op(Opcode::Mov, oPos(), {c(0)});
    auto shader = emu::Shader::create(p.program());
    ASSERT_TRUE(shader.shader) << shader.error;
    EXPECT_EQ(shader.shader->booleans_read(), 1u << 5);  // b2 is defined by the shader
    EXPECT_EQ(shader.shader->integers_read(), 1u << 3);
}

TEST(Shader, FlowKeyKeepsOnlyWhatTheShaderReads) {
    ProgramBuilder p(ShaderType::Vertex);
    p.defb(2, true)
        .flow(Opcode::If, {b(2)}).flow(Opcode::EndIf)
        .flow(Opcode::If, {b(5)}).flow(Opcode::EndIf)
        .flow(Opcode::Rep, {i(3)}).flow(Opcode::EndRep)
        .op(Opcode::Mov, oPos(), {c(0)});
    auto shader = emu::Shader::create(p.program());
    ASSERT_TRUE(shader.shader) << shader.error;
    StaticFlowConstants first, second;
    first.booleans[5] = second.booleans[5] = true;
    first.integers[3] = second.integers[3] = {2, 0, 0, 0};
    first.booleans[7] = true;           // not read: must not split the cache
    second.integers[9] = {5, 5, 5, 0};  // not read
    second.booleans[2] = false;         // defined by the shader (defb b2, true)
    EXPECT_EQ(shader.shader->flow_key(first), shader.shader->flow_key(second));
    EXPECT_TRUE(shader.shader->flow_key(second).booleans[2]);
    second.booleans[5] = false;
    EXPECT_FALSE(shader.shader->flow_key(first) == shader.shader->flow_key(second));
}

TEST(Constants, DefOverridesTheApplicationValueWithoutChangingIt) {
    ProgramBuilder p(ShaderType::Vertex);
    p.def(1, 2.0f, 3.0f, 4.0f, 5.0f).op(Opcode::Add, oPos(), {c(0), c(1)});
    const auto exe = lower_or_fail(p.program());
    const std::vector<Float4> application{{1, 1, 1, 1}, {100, 100, 100, 100}};
    const emu::ConstantFile file = exe.bind_constants(application);
    EXPECT_EQ(file.registers.size(), 256u);
    EXPECT_FLOAT4_EQ(file.registers[1], 2.0f, 3.0f, 4.0f, 5.0f);
    EXPECT_FLOAT4_EQ(file.registers[7], 0.0f, 0.0f, 0.0f, 0.0f);  // never set: (0,0,0,0)
    EXPECT_FLOAT4_EQ(application[1], 100.0f, 100.0f, 100.0f, 100.0f);
    emu::Batch batch;
    emu::execute(exe, file, batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 3.0f, 4.0f, 5.0f, 6.0f);
}

TEST(Constants, PixelShadersHave32) {
    ProgramBuilder p(ShaderType::Pixel);
    p.op(Opcode::Mov, oC(0), {c(31)});
    EXPECT_EQ(lower_or_fail(p.program()).bind_constants().registers.size(), 32u);
}

}  // namespace
}  // namespace sm2::test

namespace sm2::test {
namespace {

TEST(Lowering, DescribeNamesRegisters) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::M4x4, oPos(), {v(0), c(0)}).op(Opcode::Mul, oD(1).mask("xy").sat(), {v(2).neg(), c(4).swz("x")});
    EXPECT_EQ(lower_or_fail(p.program()).describe(),
              "dp4 oPos.x, v0, c0\ndp4 oPos.y, v0, c1\ndp4 oPos.z, v0, c2\ndp4 oPos.w, v0, c3\n"
              "mul_sat oD1.xy, -v2, c4.xxxx\n");
}

TEST(Lowering, MovToTheAddressRegisterActsAsMova) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, a0().mask("x"), {c(0).swz("x")}).op(Opcode::Mov, oPos(), {c(1).rel_a0('x')});
    const auto exe = lower_or_fail(p.program());
    ASSERT_EQ(exe.steps().size(), 2u);
    EXPECT_EQ(exe.steps()[0].opcode, Opcode::Mova);
    emu::Batch batch;
    // a0.x = round(1.5) = 2 -> c3
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1.5f, 0, 0, 0}, {}, {}, {7, 7, 7, 7}}), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 7.0f, 7.0f, 7.0f, 7.0f);
}

}  // namespace
}  // namespace sm2::test
