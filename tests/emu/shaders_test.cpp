// Whole shaders, from assembly text and from the worked token examples of bytecode.md §13,
// lowered and run; expected values worked out by hand in the comments.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "emu/engine_test_support.h"
#include "isa/worked_examples.h"
#include "sm2/isa/bytecode.h"

namespace sm2::test {
namespace {

// bytecode.md §13 examples: the assembly in the assembler's corpus, the tokens in the isa tests.
std::string corpus(const char* name) {
    std::ifstream in(std::string(SM2_SOURCE_DIR) + "/tests/assembler/corpus/" + name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

void check_example_c(const isa::Program& program) {
    // The application leaves b0 FALSE and i0 zero: defb/defi decide. aL = 0..3 adds c10..c13.
    const auto exe = lower_or_fail(program);
    std::vector<Float4> constants(16, Float4{0, 0, 0, 0});
    constants[2] = {2, 2, 2, 2};
    constants[10] = {1, 0, 0, 0};
    constants[11] = {0, 1, 0, 0};
    constants[12] = {0, 0, 1, 0};
    constants[13] = {0, 0, 0, 1};
    emu::Batch batch;
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
        batch.set(batch.input(0), lane, static_cast<float>(lane), 1, 2, 3);
    emu::execute(exe, exe.bind_constants(constants), batch);
    // (v0 + (1, 1, 1, 1)) * 2 = ((lane + 1) * 2, 4, 6, 8)
    for (unsigned lane : {0u, 1u, 15u})
        EXPECT_FLOAT4_EQ(lane_value(batch.position(), lane), 2.0f * static_cast<float>(lane + 1), 4.0f, 6.0f, 8.0f);
    // mov, 4 x add, mul, mov: nothing of the flow control is left
    EXPECT_EQ(exe.steps().size(), 7u);
}

TEST(Shaders, ExampleCFromText) { check_example_c(assemble_or_fail(corpus("example_c_flow.asm"))); }

TEST(Shaders, ExampleCFromTokens) {
    const auto decoded = isa::decode(isa::examples::kExampleC);
    ASSERT_TRUE(decoded.ok()) << decoded.error->to_string();
    check_example_c(*decoded.program);
}

// bytecode.md §13 example B: transform, relative addressing, sincos, fog.
TEST(Shaders, ExampleB) {
    const auto exe = lower_or_fail(assemble_or_fail(corpus("example_b_vs.asm")));
    std::vector<Float4> constants(8, Float4{0, 0, 0, 0});
    constants[0] = {1, 0, 0, 0};  // identity
    constants[1] = {0, 1, 0, 0};
    constants[2] = {0, 0, 1, 0};
    constants[3] = {0, 0, 0, 1};
    constants[4] = {0, 0, 1, 0};  // light direction +z
    constants[7] = {1, 0.5f, 0.25f, 1};  // c[a0.x + 5] with a0.x = round(c8.w = 2) = 2
    emu::Batch batch;
    batch.broadcast(batch.input(0), 1, 2, 3, 1);
    batch.broadcast(batch.input(1), 0, 0, 0.5f, 0);
    batch.broadcast(batch.input(2), 0, 0, 0, 1);
    batch.input(1)[2][3] = -0.5f;  // lane 3 faces away: max(-0.5, 0) = 0
    emu::execute(exe, exe.bind_constants(constants), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position()), 1.0f, 2.0f, 3.0f, 1.0f);
    // N.L = 0.5: 0.5 * c7
    EXPECT_FLOAT4_EQ(lane_value(batch.color_out(0)), 0.5f, 0.25f, 0.125f, 0.5f);
    EXPECT_FLOAT4_EQ(lane_value(batch.color_out(0), 3), 0.0f, 0.0f, 0.0f, 0.0f);
    // sincos(0) = (cos 1, sin 0); oT0.zw keep (0, 1)
    EXPECT_FLOAT4_EQ(lane_value(batch.texcoord_out(0)), 1.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_EQ(batch.fog()[0][0], 1.0f);
}

// bytecode.md §13 example A: ps_2_0, two samplers, projected lookup, _pp, lrp_sat.
const char* const kExampleA = R"(ps_2_0
dcl t0.xy
dcl t1
dcl v0
dcl_2d s0
dcl_cube s1
def c0, 0.5, 1.0, 0.0, 0.25
texld r0, t0, s0
texldp_pp r1, t1, s1
mul_pp r0, r0, v0
lrp_sat r2, c0.x, r0, r1
mov r2.w, c0.y
mov oC0, r2
)";

// s0 returns (0.8, 0.6, 0.4, 1), s1 (0.2, 0.4, 0.6, 0.5); it records the variants it saw.
class TwoColourSampler : public emu::Sampler {
public:
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        const Float4 colour = request.sampler == 0 ? Float4{0.8f, 0.6f, 0.4f, 1} : Float4{0.2f, 0.4f, 0.6f, 0.5f};
        variants[request.sampler] = request.variant;
        for (unsigned c = 0; c < 4; ++c) texels[c].fill(colour[c]);
    }
    std::array<emu::TextureVariant, 2> variants{};
};

TEST(Shaders, ExampleA) {
    const auto exe = lower_or_fail(assemble_or_fail(kExampleA));
    emu::Batch batch;
    batch.broadcast(batch.input(0), 0.5f, 0.5f, 1, 1);
    TwoColourSampler sampler;
    emu::execute(exe, exe.bind_constants(), batch, &sampler);
    EXPECT_EQ(sampler.variants[0], emu::TextureVariant::Plain);
    EXPECT_EQ(sampler.variants[1], emu::TextureVariant::Projected);
    // r0 = (0.8, 0.6, 0.4, 1) * v0 = (0.4, 0.3, 0.4, 1); r2 = 0.5 * (r0 - r1) + r1
    // = (0.3, 0.35, 0.5, 0.75); w replaced by 1
    EXPECT_FLOAT4_NEAR(lane_value(batch.render_target(0), 9), 0.3f, 0.35f, 0.5f, 1.0f, 1e-7f);
}

TEST(Shaders, IndexedMatrixPalette) {
    // Each vertex picks its matrix with v1.x (0 or 3: the first row of the 3-row matrix).
    const auto exe = lower_or_fail(assemble_or_fail(R"(vs_2_0
dcl_position v0
dcl_blendindices v1
mova a0.x, v1.x
m4x3 r0.xyz, v0, c[a0.x + 10]
mov r0.w, v0.w
mov oPos, r0
)"));
    std::vector<Float4> constants(16, Float4{0, 0, 0, 0});
    constants[10] = {1, 0, 0, 1};  // matrix 0: translate by (1, 2, 3)
    constants[11] = {0, 1, 0, 2};
    constants[12] = {0, 0, 1, 3};
    constants[13] = {2, 0, 0, 0};  // matrix 1: scale by 2
    constants[14] = {0, 2, 0, 0};
    constants[15] = {0, 0, 2, 0};
    emu::Batch batch;
    batch.broadcast(batch.input(0), 1, 1, 1, 1);
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane) batch.input(1)[0][lane] = lane % 2 ? 3.0f : 0.0f;
    emu::execute(exe, exe.bind_constants(constants), batch);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 0), 2.0f, 3.0f, 4.0f, 1.0f);
    EXPECT_FLOAT4_EQ(lane_value(batch.position(), 1), 2.0f, 2.0f, 2.0f, 1.0f);
}

TEST(Shaders, NestedStaticBranchesAndRep) {
    const char* text = R"(vs_2_0
dcl_position v0
mov r0, c0
if b0
  rep i0
    add r0, r0, c1
  endrep
else
  if !b1
    mul r0, r0, c2
  endif
endif
callnz l0, !b2
mov oPos, r0
ret
label l0
add r0, r0, c3
ret
)";
    const std::vector<Float4> constants{{1, 1, 1, 1}, {1, 2, 3, 4}, {10, 10, 10, 10}, {100, 100, 100, 100}};
    auto run = [&](bool b0, bool b1, bool b2, int count) {
        emu::StaticFlowConstants flow;
        flow.booleans[0] = b0;
        flow.booleans[1] = b1;
        flow.booleans[2] = b2;
        flow.integers[0] = {count, 0, 0, 0};
        const auto exe = lower_or_fail(assemble_or_fail(text), flow);
        emu::Batch batch;
        emu::execute(exe, exe.bind_constants(constants), batch);
        return lane_value(batch.position());
    };
    // b0: c0 + 2 * c1 = (3, 5, 7, 9); !b2 true -> + 100
    EXPECT_FLOAT4_EQ(run(true, false, false, 2), 103.0f, 105.0f, 107.0f, 109.0f);
    // !b0, !b1: c0 * c2 = 10; b2 set -> no call
    EXPECT_FLOAT4_EQ(run(false, false, true, 2), 10.0f, 10.0f, 10.0f, 10.0f);
    // !b0, b1: c0 unchanged; + 100
    EXPECT_FLOAT4_EQ(run(false, true, false, 5), 101.0f, 101.0f, 101.0f, 101.0f);
    // b0 with rep count 0: c0 + 100
    EXPECT_FLOAT4_EQ(run(true, true, false, 0), 101.0f, 101.0f, 101.0f, 101.0f);
}

}  // namespace
}  // namespace sm2::test
