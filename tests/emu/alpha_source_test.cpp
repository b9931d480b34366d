// alpha_source_sampler(): the texld whose alpha the pixel shader's oC0.w follows, so that a
// transparent alpha there (+-0 or NaN) makes oC0.w saturate to +0: through mov and mul alone
// (D3D9's mul: 0 times anything is +0), and only where no other texld reads the same sampler.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sm2::test
