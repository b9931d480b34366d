// Execution over batches of lanes: per-lane data, reads before writes, input defaults, the
// address register, texkill masks and the sampler interface.
#include <gtest/gtest.h>

#include <bit>
#include <limits>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(Execution, EveryLaneComputesItsOwnValue) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::M4x4, oPos(), {v(0), c(0)});
    const auto exe = lower_or_fail(p.program());
    // Rows of a scale-and-translate matrix: x' = 2x + 1, y' = 3y - 1, z' = z, w' = w.
    const std::vector<Float4> matrix{{2, 0, 0, 1}, {0, 3, 0, -1}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    emu::Batch batch;
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
        batch.set(batch.input(0), lane, static_cast<float>(lane), 10.0f + static_cast<float>(lane), 0.5f, 1.0f);
    emu::execute(exe, exe.bind_constants(matrix), batch);
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane) {
        const float x = static_cast<float>(lane);
        EXPECT_FLOAT4_EQ(lane_value(batch.position(), lane), 2 * x + 1, 3 * (10 + x) - 1, 0.5f, 1.0f);
    }
}

TEST(Execution, SourcesAreReadBeforeTheDestinationIsWritten) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)}).op(Opcode::Mul, rd(0), {r(0).swz("yzxw"), r(0)})
        .op(Opcode::Mov, oPos(), {r(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{2, 3, 5, 7}}), batch);
    // (y*x, z*y, x*z, w*w) = (6, 15, 10, 49)
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 6.0f, 15.0f, 10.0f, 49.0f);
}

TEST(Execution, MissingInputComponentsRead0001) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {v(3)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.input(3)[0].fill(0.25f);  // the vertex declaration supplies only .x
    emu::execute(exe, exe.bind_constants(), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 7), 0.25f, 0.0f, 0.0f, 1.0f);
}

// NaN results are stored as the positive quiet NaN 0x7FC00000 whatever NaN the arithmetic made:
// -NaN from the application (0xFFC00001), inf - inf (the default NaN x86 makes is 0xFFC00000),
// and a NaN with a payload moved unchanged (0x7FC12345).
TEST(Execution, NaNResultsAreStoredAsOneBitPattern) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, rd(0), {c(0)}).op(Opcode::Add, rd(0).mask("y"), {c(1), c(1).neg()}).op(Opcode::Mov, oPos(), {r(0)});
    const auto exe = lower_or_fail(p.program());
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Float4> constants{
        {std::bit_cast<float>(0xFFC00001u), 0.0f, std::bit_cast<float>(0x7FC12345u), 1.0f}, {inf, inf, inf, inf}};
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(constants), batch);
    for (unsigned c = 0; c < 3; ++c)
        EXPECT_EQ(std::bit_cast<uint32_t>(batch.position()[c][0]), 0x7FC00000u) << "component " << c;
    EXPECT_EQ(batch.position()[3][0], 1.0f);
}

TEST(Execution, UnsetConstantsReadZero) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(200)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 0.0f, 0.0f, 0.0f, 0.0f);
}

TEST(Execution, UnwrittenOutputComponentsKeep0001) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(0)}).op(Opcode::Mov, oD(0).mask("xy"), {c(1)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1, 1, 1, 1}, {0.5f, 0.25f, 0.75f, 0.125f}}), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.color_out(0)), 0.5f, 0.25f, 0.0f, 1.0f);
}

TEST(Execution, RelativeAddressingPerLane) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mova, a0().mask("x"), {v(0).swz("x")}).op(Opcode::Mov, oPos(), {c(2).rel_a0('x')});
    const auto exe = lower_or_fail(p.program());
    std::vector<Float4> constants(256, Float4{0, 0, 0, 0});
    for (unsigned k = 0; k < 256; ++k) constants[k] = {static_cast<float>(k), 0, 0, 1};
    emu::Batch batch;
    // a0.x = round(v0.x): lane 0: 0.4 -> 0 (c2); lane 1: 1.5 -> 2 (c4); lane 2: -1.5 -> -2 (c0);
    // lane 3: -2.5 -> -3 (c[-1]: outside, zero); lane 4: 253.0 -> c255; lane 5: 254 -> c256: zero;
    // lane 6: NaN -> no constant: zero.
    const float inputs[] = {0.4f, 1.5f, -1.5f, -2.5f, 253.0f, 254.0f, kNaN};
    for (unsigned lane = 0; lane < 7; ++lane) batch.input(0)[0][lane] = inputs[lane];
    emu::execute(exe, exe.bind_constants(constants), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 0), 2.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 1), 4.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 2), 0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 3), 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 4), 255.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 5), 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 6), 0.0f, 0.0f, 0.0f, 0.0f);
}

TEST(Execution, TexkillMarksLanesAndTheyKeepExecuting) {
    ProgramBuilder p(ShaderType::Pixel);
    p.texkill(td(0)).op(Opcode::Mov, oC(0), {t(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.broadcast(batch.texcoord(0), 0.5f, 0.5f, 0.5f, 0.5f);
    batch.texcoord(0)[0][1] = -0.25f;      // x < 0: killed
    batch.texcoord(0)[3][2] = -1.0f;       // w < 0: killed (all four components are tested)
    batch.texcoord(0)[2][3] = -0.0f;       // -0 is not below zero
    batch.texcoord(0)[1][4] = kNaN;        // NaN is not below zero
    emu::execute(exe, exe.bind_constants(), batch);
    EXPECT_EQ(batch.killed, (1u << 1) | (1u << 2));
    EXPECT_FLOAT4_EQ(lane_value(batch.render_target(0), 1), -0.25f, 0.5f, 0.5f, 0.5f);  // helper ran
}

TEST(Execution, TexkillWithAnXyzMaskIgnoresW) {
    ProgramBuilder p(ShaderType::Pixel);
    p.texkill(td(0).mask("xyz")).op(Opcode::Mov, oC(0), {t(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.broadcast(batch.texcoord(0), 0.5f, 0.5f, 0.5f, -1.0f);
    batch.texcoord(0)[2][0] = -1.0f;
    emu::execute(exe, exe.bind_constants(), batch);
    EXPECT_EQ(batch.killed, 1u);
}

// Records what the engine asks for and answers texel = (coord.x * 2, coord.y, sampler, variant).
class RecordingSampler : public emu::Sampler {
public:
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        ++calls;
        last_quads = request.quad_count;
        last_helpers = request.helper_lanes;
        last_w = (*request.coordinates)[3];
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            texels[0][l] = (*request.coordinates)[0][l] * 2.0f;
            texels[1][l] = (*request.coordinates)[1][l];
            texels[2][l] = static_cast<float>(request.sampler);
            texels[3][l] = static_cast<float>(request.variant);
        }
    }
    int calls = 0;
    unsigned last_quads = 0;
    emu::LaneMask last_helpers = 0;
    emu::FloatLanes last_w{};
};

TEST(Execution, TextureInstructionsGoThroughTheSampler) {
    for (uint8_t variant : {isa::kTexLdPlain, isa::kTexLdProject, isa::kTexLdBias}) {
        ProgramBuilder p(ShaderType::Pixel);
        p.tex(rd(0), t(1), 3, variant).op(Opcode::Mov, oC(0), {r(0)});
        const auto exe = lower_or_fail(p.program());
        emu::Batch batch;
        batch.lane_count = 8;  // two quads
        for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
            batch.set(batch.texcoord(1), lane, 0.125f * static_cast<float>(lane), 0.5f, 0.0f, 2.0f);
        RecordingSampler sampler;
        emu::execute(exe, exe.bind_constants(), batch, &sampler);
        EXPECT_EQ(sampler.calls, 1);
        EXPECT_EQ(sampler.last_quads, 2u);
        EXPECT_EQ(sampler.last_w[5], 2.0f);  // coordinates arrive unprojected
        EXPECT_FLOAT4_EQ(lane_value(batch.render_target(0), 5), 1.25f, 0.5f, 3.0f, static_cast<float>(variant));
    }
}

TEST(Execution, WithoutASamplerTexturesRead0001) {
    ProgramBuilder p(ShaderType::Pixel);
    p.tex(rd(0), t(0), 0).op(Opcode::Mov, oC(0), {r(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.render_target(0)), 0.0f, 0.0f, 0.0f, 1.0f);
}

TEST(Execution, KilledLanesAreHelpersForLaterSamples) {
    ProgramBuilder p(ShaderType::Pixel);
    p.texkill(td(0)).tex(rd(0), t(0), 0).op(Opcode::Mov, oC(0), {r(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.broadcast(batch.texcoord(0), 0.5f, 0.5f, 0.5f, 0.5f);
    batch.texcoord(0)[0][6] = -1.0f;
    RecordingSampler sampler;
    emu::execute(exe, exe.bind_constants(), batch, &sampler);
    EXPECT_EQ(sampler.last_helpers, 1u << 6);
}

TEST(Execution, Fp64ExecutableNeedsAReferenceBatch) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(0)});
    emu::LoweringOptions options;
    options.precision.precision = emu::Precision::Fp64;
    const auto exe = lower_or_fail(p.program(), {}, options);
    emu::Batch batch;
    EXPECT_THROW(emu::execute(exe, exe.bind_constants(), batch), std::invalid_argument);
    emu::ReferenceBatch reference;
    emu::execute(exe, exe.bind_constants(std::vector<Float4>{{1, 2, 3, 4}}), reference);
    EXPECT_EQ(reference.position()[3][9], 4.0);
}

}  // namespace
}  // namespace sm2::test

namespace sm2::test {
namespace {

TEST(RegisterUse, InputsReadAndOutputsWritten) {
    ProgramBuilder p(ShaderType::Pixel);
    // t0 read as .xy (via swizzle .xyyy for x/y/z/w of a full write), t2.w only; r5 dead
    p.op(Opcode::Mul, rd(0), {t(0).swz("xyyy"), t(2).swz("w")})
        .op(Opcode::Mov, rd(5), {t(3)})
        .op(Opcode::Mov, oC(0), {r(0)});
    const auto exe = lower_or_fail(p.program());
    EXPECT_EQ(exe.components_read()[emu::slot::kTexCoordFirst + 0], 0b0011);
    EXPECT_EQ(exe.components_read()[emu::slot::kTexCoordFirst + 2], 0b1000);
    EXPECT_EQ(exe.components_read()[emu::slot::kTexCoordFirst + 3], 0);  // only dead code read it
    EXPECT_EQ(exe.components_written()[emu::slot::kRenderTargetFirst], 0xF);
    EXPECT_EQ(exe.components_written()[emu::slot::kTempFirst + 5], 0);
}

}  // namespace
}  // namespace sm2::test
