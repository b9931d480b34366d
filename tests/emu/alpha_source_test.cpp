// alpha_source_sampler(): the texld whose alpha the pixel shader's oC0.w follows, so that a
// transparent alpha there (+-0 or NaN) makes oC0.w saturate to +0: through mov and mul alone
// (D3D9's mul: 0 times anything is +0), and only where no other texld reads the same sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "emu/engine_test_support.h"
#include "sm2/emu/alpha_source.h"

namespace sm2::test {
namespace {

std::optional<unsigned> alpha_source_of(const std::string& body) {
    return emu::alpha_source_sampler(lower_or_fail(assemble_or_fail("ps_2_0\n" + body)));
}

TEST(AlphaSource, FollowsMovAndMulBackToTheTexld) {
    // Scene 13's slices: the volume's alpha times the slice opacity.
    EXPECT_EQ(alpha_source_of("dcl t0.xyz\ndcl_volume s0\ntexld r0, t0, s0\nmul r0.w, r0.w, c0.x\nmov oC0, r0\n"), 0u);
    // Negated, saturated, through temporaries and swizzles: -0 * c is +0, and saturate(+0) = +0.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s2\ntexld r1, t0, s2\nmov r2.x, -r1.w\nmul_sat r3.y, c1.x, r2.x\n"
                              "mov oC0.w, r3.y\nmov oC0.xyz, r1\n"),
              2u);
    // The value as the second source of a mul.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s3\ntexld r0, t0, s3\nmul r1.w, c0.x, r0.w\nmov r1.xyz, r0\nmov oC0, r1\n"), 3u);
    // The first source an input, the second the texture's alpha.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl t1\ndcl_2d s0\ntexld r0, t0, s0\nmul r0.w, t1.w, r0.w\nmov oC0, r0\n"), 0u);
    // Two samplers: the alpha is s1's.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl t1\ndcl_2d s0\ndcl_2d s1\ntexld r0, t0, s0\ntexld r1, t1, s1\n"
                              "mul r0.xyz, r0, r1\nmov r0.w, r1.w\nmov oC0, r0\n"),
              1u);
}

// alpha_source_texld(): the step of that texld, whose coordinate source a draw reads.
TEST(AlphaSource, NamesTheStepOfTheTexld) {
    const emu::Executable exe = lower_or_fail(assemble_or_fail(
        "ps_2_0\ndcl t0\ndcl t1\ndcl_2d s0\ndcl_2d s1\ntexld r0, t0, s0\ntexld r1, t1, s1\n"
        "mul r0.xyz, r0, r1\nmov r0.w, r1.w\nmov oC0, r0\n"));
    const std::optional<size_t> texld = emu::alpha_source_texld(exe);
    ASSERT_TRUE(texld);
    const emu::Step& step = exe.steps()[*texld];
    EXPECT_EQ(step.opcode, isa::Opcode::Tex);
    EXPECT_EQ(step.sampler, 1u);
    EXPECT_EQ(step.sources[0].kind, emu::OperandKind::Lanes);
    EXPECT_EQ(step.sources[0].index, emu::slot::kTexCoordFirst + 1);  // t1
    EXPECT_FALSE(emu::alpha_source_texld(lower_or_fail(assemble_or_fail("ps_2_0\nmov oC0, c0\n"))));
}

TEST(AlphaSource, NoneWhereATransparentTexelNeedNotGiveATransparentAlpha) {
    // Added to, or through mad: 0 + c is not 0.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s0\ntexld r0, t0, s0\nadd r0.w, r0.w, c0.x\nmov oC0, r0\n"), std::nullopt);
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmad r0.w, r0.w, c0.x, c0.y\nmov oC0, r0\n"),
              std::nullopt);
    // The last step writing the register writes other channels (its mul of the texel is not
    // the alpha's).
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s0\ntexld r0, t0, s0\nadd r1.w, r0.w, c0.x\nmul r1.xyz, r0, c1\n"
                              "mov oC0, r1\n"),
              std::nullopt);
    // The texel's red as alpha.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0.xyzx\n"), std::nullopt);
    // The alpha overwritten by a constant after the lookup.
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov r0.w, c0.x\nmov oC0, r0\n"), std::nullopt);
    // An interpolated alpha, no texture.
    EXPECT_EQ(alpha_source_of("dcl t0\nmov oC0, t0\n"), std::nullopt);
    // The sampler read by a second texld too (the gate is the stage's, for every lookup of it).
    EXPECT_EQ(alpha_source_of("dcl t0\ndcl t1\ndcl_2d s0\ntexld r0, t0, s0\ntexld r1, t1, s0\n"
                              "mul r0.w, r0.w, r1.x\nmov oC0, r0\n"),
              std::nullopt);
    // A chain of muls of a register by itself from an input: each step branches in two, and
    // the search gives up within its budget rather than following 2^24 paths.
    std::string chain = "dcl t0\nmov r0, t0\n";
    for (int i = 0; i < 24; ++i) chain += "mul r0, r0, r0\n";
    EXPECT_EQ(alpha_source_of(chain + "mov oC0, r0\n"), std::nullopt);
}

// Texels whose alpha is +0, -0 or NaN on sampler `transparent`, random elsewhere; random colour.
class TransparentOn : public emu::Sampler {
public:
    TransparentOn(unsigned transparent, uint32_t seed) : transparent_(transparent), random_(seed) {}
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        std::uniform_real_distribution<float> value(-2.0f, 2.0f);
        const float alphas[3] = {0.0f, -0.0f, std::numeric_limits<float>::quiet_NaN()};
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            for (unsigned c = 0; c < 3; ++c) texels[c][l] = value(random_);
            texels[3][l] = request.sampler == transparent_ ? alphas[random_() % 3] : value(random_);
        }
    }

private:
    unsigned transparent_;
    std::mt19937 random_;
};

// Random shaders of mov, mul, add, mad and texld: wherever alpha_source_sampler() names a
// sampler, the interpreter's oC0.w saturates to +0 on every lane when that sampler's alpha is
// +-0 or NaN, whatever the inputs, constants and other texels.
TEST(AlphaSource, TheInterpreterAgreesOnRandomShaders) {
    std::mt19937 random(20261204);
    const char* const kOps[] = {"mov", "mul", "mul", "add", "mad", "texld"};
    const char* const kSwizzles[] = {"", ".xxxx", ".yyyy", ".zzzz", ".wwww", ".wzyx"};
    const char* const kMasks[] = {"", ".x", ".w", ".xyz", ".xw", ".yw"};
    const auto source = [&] {
        const unsigned kind = random() % 8;
        std::string s = kind < 5 ? "r" + std::to_string(random() % 4) : kind < 7 ? "c" + std::to_string(random() % 4)
                                                                               : "t" + std::to_string(random() % 2);
        s += kSwizzles[random() % std::size(kSwizzles)];
        return (random() % 4 == 0 ? "-" : "") + s;
    };
    unsigned named = 0;
    for (unsigned round = 0; round < 600; ++round) {
        std::string text = "ps_2_0\ndcl t0\ndcl t1\ndcl_2d s0\ndcl_2d s1\n"
                           "mov r0, t0\nmov r1, t1\nmov r2, c2\nmov r3, t0\n";
        const unsigned count = 2 + random() % 7;
        for (unsigned i = 0; i < count; ++i) {
            const std::string op = kOps[random() % std::size(kOps)];
            const std::string dest = "r" + std::to_string(random() % 4);
            if (op == "texld") {
                text += "texld " + dest + ", t" + std::to_string(random() % 2) + ", s" + std::to_string(random() % 2) + "\n";
                continue;
            }
            text += op + (random() % 5 == 0 ? "_sat " : " ") + dest + kMasks[random() % std::size(kMasks)] + ", " + source();
            if (op != "mov") text += ", " + source();
            if (op == "mad") text += ", " + source();
            text += "\n";
        }
        text += "mov oC0, r" + std::to_string(random() % 4) + "\n";
        const emu::Executable exe = lower_or_fail(assemble_or_fail(text));
        const std::optional<unsigned> sampler = emu::alpha_source_sampler(exe);
        if (!sampler) continue;
        ++named;
        for (uint32_t seed = 1; seed <= 3; ++seed) {
            std::mt19937 values(seed * 7919u + round);
            std::uniform_real_distribution<float> value(-3.0f, 3.0f);
            std::vector<Float4> constants(4);
            for (auto& c : constants)
                for (float& v : c) v = values() % 4 == 0 ? 0.0f : value(values);
            auto batch = std::make_unique<emu::Batch>();
            for (unsigned t = 0; t < 2; ++t)
                for (auto& component : batch->texcoord(t))
                    for (float& v : component) v = value(values);
            TransparentOn texels(*sampler, seed);
            emu::execute(exe, exe.bind_constants(constants), *batch, &texels);
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                const float alpha = batch->render_target(0)[3][l];
                ASSERT_FALSE(alpha > 0.0f) << "lane " << l << ": oC0.w " << alpha << " (s" << *sampler << ")\n" << text;
            }
        }
    }
    // The search names a sampler for a good share of them (a test that could not fail would
    // name none).
    EXPECT_GT(named, 60u) << named;
}

}  // namespace
}  // namespace sm2::test
