// texld / texldp / texldb (ps_2_0): the coordinates as computed, the sampler index and the
// variant go to the Sampler; the returned float4 lands in the full-mask destination.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

// A 2D "texture" whose texel at (u, v) is (u, v, u * v, 1), with texldp dividing by w and
// texldb reporting its bias in z.
class FormulaSampler : public emu::Sampler {
public:
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        const auto& coordinates = *request.coordinates;
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            float u = coordinates[0][l], v = coordinates[1][l];
            if (request.variant == emu::TextureVariant::Projected) {
                u /= coordinates[3][l];
                v /= coordinates[3][l];
            }
            texels[0][l] = u;
            texels[1][l] = v;
            texels[2][l] = request.variant == emu::TextureVariant::Bias ? coordinates[3][l] : u * v;
            texels[3][l] = static_cast<float>(request.sampler);
        }
    }
};

Float4 sample_once(uint8_t variant, Float4 coordinates, unsigned sampler = 0, bool pp = false) {
    ProgramBuilder p(ShaderType::Pixel);
    p.tex(pp ? rd(1).pp() : rd(1), t(0), sampler, variant).op(Opcode::Mov, oC(0), {r(1)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.broadcast(batch.texcoord(0), coordinates[0], coordinates[1], coordinates[2], coordinates[3]);
    FormulaSampler formula;
    emu::execute(exe, exe.bind_constants(), batch, &formula);
    return lane_value(batch.render_target(0), 3);
}

TEST(Texld, PlainSample) {
    // (0.5, 0.25): (0.5, 0.25, 0.125, sampler 2)
    EXPECT_FLOAT4_EQ(sample_once(isa::kTexLdPlain, {0.5f, 0.25f, 0, 4}, 2), 0.5f, 0.25f, 0.125f, 2.0f);
}

TEST(Texld, ProjectedSampleDividesByW) {
    // (1, 0.5) / 4 = (0.25, 0.125), product 0.03125
    EXPECT_FLOAT4_EQ(sample_once(isa::kTexLdProject, {1, 0.5f, 0, 4}, 7), 0.25f, 0.125f, 0.03125f, 7.0f);
}

TEST(Texld, BiasedSampleHandsOverW) {
    EXPECT_FLOAT4_EQ(sample_once(isa::kTexLdBias, {0.5f, 0.5f, 0, -1.5f}, 15), 0.5f, 0.5f, -1.5f, 15.0f);
}

TEST(Texld, DependentReadFromATemp) {
    ProgramBuilder p(ShaderType::Pixel);
    // r0 = t0 * 2; texld r1, r0, s1
    p.op(Opcode::Add, rd(0), {t(0), t(0)}).tex(rd(1), r(0), 1).op(Opcode::Mov, oC(0), {r(1)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
        batch.set(batch.texcoord(0), lane, 0.0625f * static_cast<float>(lane), 0.25f, 0, 1);
    FormulaSampler formula;
    emu::execute(exe, exe.bind_constants(), batch, &formula);
    // lane 5: u = 2 * 0.3125 = 0.625, v = 0.5, u*v = 0.3125
    EXPECT_FLOAT4_EQ(lane_value(batch.render_target(0), 5), 0.625f, 0.5f, 0.3125f, 1.0f);
}

TEST(Texld, PartialPrecisionRoundsTheTexelToHalf) {
    emu::LoweringOptions options;
    options.precision.partial_precision_fp16 = true;
    ProgramBuilder p(ShaderType::Pixel);
    p.tex(rd(1).pp(), t(0), 0).op(Opcode::Mov, oC(0), {r(1)});
    const auto exe = lower_or_fail(p.program(), {}, options);
    emu::Batch batch;
    // u = 1 + 2^-12 is not a half (10 mantissa bits): rounds to 1; v = 0.25 is exact
    batch.broadcast(batch.texcoord(0), 1.0f + 0x1p-12f, 0.25f, 0, 1);
    FormulaSampler formula;
    emu::execute(exe, exe.bind_constants(), batch, &formula);
    // z = u * v = 0.25 + 2^-14 -> half spacing at 0.25 is 2^-12, so 0.25
    EXPECT_FLOAT4_EQ(lane_value(batch.render_target(0)), 1.0f, 0.25f, 0.25f, 0.0f);
}

}  // namespace
}  // namespace sm2::test
