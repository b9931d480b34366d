// Texture reads the HLSL compiler emits: texCUBEbias/tex2Dbias as texldb with the bias in the
// coordinate's .w, and independent reads that stay independent under ps_2_0's dependent-read rule
// (a texld into a temp written before counts one level deeper, so the compiler allocates ps_2_0
// temps by their dependent-read level), and temps released after a folded multiply.
#include <gtest/gtest.h>

#include <string>

#include "sm2/hlsl/compiler.h"

namespace {

std::string messages(const sm2::hlsl::CompileResult& result) {
    std::string text;
    for (const auto& d : result.diagnostics) text += sm2::hlsl::format_fxc(d) + "\n";
    return text;
}

sm2::hlsl::CompileResult compile_ps(const char* source) {
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Pixel;
    return sm2::hlsl::compile(source, options);
}

TEST(HlslTextureReads, BiasIsTexldbWithTheBiasInW) {
    const auto result = compile_ps(
        "samplerCUBE env;\n"
        "float4 main(float3 n : TEXCOORD0) : COLOR { return texCUBEbias(env, float4(n, 4)); }\n");
    ASSERT_TRUE(result.ok()) << messages(result);
    // n.xyz and the literal 4 gathered in one temp, then texldb from it.
    EXPECT_NE(result.assembly.find("texldb r"), std::string::npos) << result.assembly;
    EXPECT_NE(result.assembly.find(".xyz, t0"), std::string::npos) << result.assembly;
    EXPECT_NE(result.assembly.find(".w, c"), std::string::npos) << result.assembly;
    const auto two_d = compile_ps(
        "sampler2D s;\n"
        "float4 main(float4 t : TEXCOORD0) : COLOR { return tex2Dbias(s, t); }\n");
    ASSERT_TRUE(two_d.ok()) << messages(two_d);
    EXPECT_NE(two_d.assembly.find("texldb r"), std::string::npos) << two_d.assembly;
}

TEST(HlslTextureReads, FourIndependentReadsAreNotAChainOfFour) {
    // Each coordinate comes from t0 and constants only: every read is of order 1 at most, though
    // the results are used between the reads (ps_2_0 allows order 3). Before the compiler took
    // fresh temps, the fourth read reused r0 and was refused as "a dependent read of order 4".
    const auto result = compile_ps(
        "float3 offsets[4];\nfloat4 frequency;\nfloat4 weights;\nsampler3D noise;\n"
        "float4 main(float3 p : TEXCOORD0) : COLOR {\n"
        "  float t0 = abs(tex3D(noise, p + offsets[0]).x * 2 - 1);\n"
        "  float t1 = abs(tex3D(noise, p * frequency.y + offsets[1]).x * 2 - 1);\n"
        "  float t2 = abs(tex3D(noise, p * frequency.z + offsets[2]).x * 2 - 1);\n"
        "  float t3 = abs(tex3D(noise, p * frequency.w + offsets[3]).x * 2 - 1);\n"
        "  return t0 * weights.x + t1 * weights.y + t2 * weights.z + t3 * weights.w;\n"
        "}\n");
    EXPECT_TRUE(result.ok()) << messages(result) << result.assembly;
}

TEST(HlslTextureReads, TwelveTapsOfADependentBlurStayAtTheSecondLevel) {
    // Scene 20's blur: a centre read, then 12 reads at coordinates scaled by the centre's alpha
    // (order 1 each). Reusing a temp that held a read for the next read's destination or
    // coordinate counts a level more each time; the compiler allocates temps by their level.
    const auto result = compile_ps(
        "float4 offsets[12];\nsampler2D image;\n"
        "float4 main(float4 uv : TEXCOORD0) : COLOR0 {\n"
        "  float4 centre = tex2D(image, uv.xy);\n"
        "  float3 sum = centre.xyz;\n"
        "  float weight = 1;\n"
        "  [unroll] for (int k = 0; k < 12; ++k) {\n"
        "    float4 tap = tex2D(image, (centre.w * offsets[k] + uv).xy);\n"
        "    sum = tap.xyz * tap.w + sum;\n"
        "    weight = weight + tap.w;\n"
        "  }\n"
        "  return float4(sum / weight, centre.w);\n"
        "}\n");
    ASSERT_TRUE(result.ok()) << messages(result);
    // The centre is read straight from t0 (t0.xy of the float4 input needs no copy).
    EXPECT_NE(result.assembly.find("texld r0, t0, s0"), std::string::npos) << result.assembly;
}

// The operands of a multiply folded into an add (mad) were never released when the add was their
// last use, so twelve chained mads ran out of the 12 temps.
TEST(HlslTextureReads, OperandsOfAFoldedMultiplyAreReleased) {
    const auto result = compile_ps(
        "float4 k[12];\n"
        "float4 main(float4 a : TEXCOORD0, float4 b : TEXCOORD1) : COLOR0 {\n"
        "  float4 sum = a;\n"
        "  [unroll] for (int i = 0; i < 12; ++i) {\n"
        "    float4 t = sum * k[i] + b;\n"
        "    sum = t * t.w + sum;\n"
        "  }\n"
        "  return sum;\n"
        "}\n");
    EXPECT_TRUE(result.ok()) << messages(result);
}

}  // namespace
