// Fixed-function state (fixed_function.h, docs/fixed-function.md): D3D9's defaults, the stream
// calls that set it (SetFVF, SetTransform, MultiplyTransform, SetMaterial, SetLight, LightEnable,
// SetTextureStageState) and their refusals, the FVF's vertex layout, and the text/binary round trip.
// Expected values: D3D9's documentation (defaults, FVF layout, MultiplyTransform order) and hand
// arithmetic; the FVF strides also match the strides the ff_lit_cube capture passed SetStreamSource.
#include "sm2/runtime/fixed_function.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace sm2::runtime {
namespace {

// D3DDECLUSAGE / D3DDECLTYPE values the layouts use.
constexpr uint8_t kPosition = 0, kBlendWeight = 1, kBlendIndices = 2, kNormal = 3, kTexCoord = 5, kPositionT = 9,
                  kColor = 10;
constexpr auto F1 = static_cast<uint8_t>(DeclType::FLOAT1), F2 = static_cast<uint8_t>(DeclType::FLOAT2),
               F3 = static_cast<uint8_t>(DeclType::FLOAT3), F4 = static_cast<uint8_t>(DeclType::FLOAT4),
               Color = static_cast<uint8_t>(DeclType::D3DCOLOR), UByte4 = static_cast<uint8_t>(DeclType::UBYTE4);

VertexElement element(uint16_t offset, uint8_t type, uint8_t usage, uint8_t index = 0) {
    return VertexElement{0, offset, type, 0, usage, index};
}

TEST(FvfLayout, ElementsFollowD3D9sOrderAndSizes) {
    // D3DFVF_XYZ | D3DFVF_NORMAL | D3DFVF_TEX1 = 0x112: 12 + 12 + 8 = 32 bytes, the stride
    // ff_lit_cube's capture gives SetStreamSource for its cube.
    FvfLayout cube = fvf_layout(0x112);
    ASSERT_TRUE(cube.error.empty()) << cube.error;
    EXPECT_EQ(cube.elements, (std::vector<VertexElement>{element(0, F3, kPosition), element(12, F3, kNormal),
                                                         element(24, F2, kTexCoord, 0)}));
    EXPECT_EQ(cube.stride, 32u);
    // D3DFVF_XYZ | D3DFVF_DIFFUSE = 0x42: 16 bytes, the capture's background quad.
    EXPECT_EQ(fvf_layout(0x42).stride, 16u);
    // XYZRHW | DIFFUSE | SPECULAR | TEX2 | TEXCOORDSIZE3(1) (1 << 18): 16 + 4 + 4 + 8 + 12.
    FvfLayout t = fvf_layout(0x004 | 0x040 | 0x080 | 0x200 | (1u << 18));
    ASSERT_TRUE(t.error.empty()) << t.error;
    EXPECT_EQ(t.elements, (std::vector<VertexElement>{element(0, F4, kPositionT), element(16, Color, kColor, 0),
                                                      element(20, Color, kColor, 1), element(24, F2, kTexCoord, 0),
                                                      element(32, F3, kTexCoord, 1)}));
    EXPECT_EQ(t.stride, 44u);
    // XYZB3 | LASTBETA_UBYTE4: two weights, then the indices in the last beta.
    FvfLayout blend = fvf_layout(0x00A | 0x1000);
    EXPECT_EQ(blend.elements, (std::vector<VertexElement>{element(0, F3, kPosition), element(12, F2, kBlendWeight),
                                                          element(20, UByte4, kBlendIndices)}));
    // TEXCOORDSIZE1(0) = 3 << 16, TEXCOORDSIZE4(0) = 2 << 16.
    EXPECT_EQ(fvf_layout(0x002 | 0x100 | (3u << 16)).elements.back(), element(12, F1, kTexCoord));
    EXPECT_EQ(fvf_layout(0x4002 | 0x100 | (2u << 16)).elements,
              (std::vector<VertexElement>{element(0, F4, kPosition), element(16, F4, kTexCoord)}));
}

TEST(FvfLayout, RefusesWhatIsNotAnFvf) {
    EXPECT_NE(fvf_layout(0x0900).error, "");          // TEX9
    EXPECT_NE(fvf_layout(0x4004).error, "");          // position bits of no D3DFVF position type
    EXPECT_NE(fvf_layout(0x002 | 0x1000).error, "");  // LASTBETA without XYZBn
    EXPECT_NE(fvf_layout(0x00A | 0x1000 | 0x8000).error, "");
    // XYZB5 holds 5 betas: 4 weights and the indices with LASTBETA, refused without.
    EXPECT_NE(fvf_layout(0x00E).error, "");
    EXPECT_EQ(fvf_layout(0x00E | 0x8000).elements,
              (std::vector<VertexElement>{element(0, F3, kPosition), element(12, F4, kBlendWeight),
                                          element(28, Color, kBlendIndices)}));
    EXPECT_NE(fvf_layout(0x002 | 0x2000).error, "");  // a bit D3DFVF does not define
    EXPECT_EQ(fvf_layout(0x002 | 0x0800).stride, 12u + 8 * 8);  // TEX8, the most
}

TEST(FixedFunctionNames, FlagWordsAsNamesReadBackToTheSameValue) {
    EXPECT_EQ(flag_names(EnumFamily::TextureArg, 0x12), (std::vector<std::string>{"TEXTURE", "COMPLEMENT"}));
    EXPECT_EQ(flag_names(EnumFamily::TextureArg, 0x00), (std::vector<std::string>{"DIFFUSE"}));
    EXPECT_EQ(flag_names(EnumFamily::TextureArg, 0x33), (std::vector<std::string>{"TFACTOR", "COMPLEMENT", "ALPHAREPLICATE"}));
    EXPECT_EQ(flag_names(EnumFamily::TextureArg, 0x07), (std::vector<std::string>{"7"}));  // no selector 7
    EXPECT_EQ(flag_names(EnumFamily::TexCoordIndex, 0x10001), (std::vector<std::string>{"CAMERASPACENORMAL", "1"}));
    EXPECT_EQ(flag_names(EnumFamily::TextureTransform, 0x103), (std::vector<std::string>{"COUNT3", "PROJECTED"}));
    EXPECT_EQ(flag_names(EnumFamily::Fvf, 0x112), (std::vector<std::string>{"XYZ", "TEX1", "NORMAL"}));
    EXPECT_EQ(flag_names(EnumFamily::Fvf, 0x004 | 0x040 | 0x200 | (1u << 18)),
              (std::vector<std::string>{"XYZRHW", "TEX2", "TEXCOORDSIZE3_1", "DIFFUSE"}));
    EXPECT_EQ(enum_value(EnumFamily::Fvf, "D3DFVF_TEXCOORDSIZE1_7"), 3u << 30);
    EXPECT_EQ(enum_value(EnumFamily::TextureOp, "MODULATE2X"), 5u);
    EXPECT_EQ(enum_value(EnumFamily::TextureOp, "D3DTOP_LERP"), 26u);
    EXPECT_EQ(transform_state_value("WORLDMATRIX255"), 511u);
    EXPECT_EQ(transform_state_value("D3DTS_TEXTURE7"), 23u);
    EXPECT_EQ(transform_state_value("WORLDMATRIX256"), std::nullopt);
    EXPECT_EQ(transform_state_value("WORLDMATRIX01"), std::nullopt);
    EXPECT_EQ(transform_state_name(257), "WORLD1");
    EXPECT_EQ(transform_state_name(300), "WORLDMATRIX44");
}

// A Device fed through the replayer, as `sm2 replay` does.
class FixedFunctionReplay : public ::testing::Test {
protected:
    ReplayResult run(const std::string& body) {
        cs::TextOptions text;
        text.file_name = "ff.sm2cs";
        auto parsed = cs::parse_text("sm2cs 1\n" + body, text);
        EXPECT_TRUE(parsed.ok()) << parsed.error->to_string();
        if (!parsed.ok()) return {};
        ReplayOptions options;
        options.file_name = "ff.sm2cs";
        options.assembler = runtime::stream_assembler();
        return replay(device_, *parsed.stream, options);
    }
    void ok(const std::string& body) {
        for (const auto& d : run(body).diagnostics) ADD_FAILURE() << d.to_string();
    }
    std::vector<std::string> refusals(const std::string& body) {
        std::vector<std::string> out;
        for (const auto& d : run(body).diagnostics) out.push_back(d.to_string());
        return out;
    }
    const FixedFunctionState& state() const { return device_.fixed_function(); }
    Device device_;
};

TEST_F(FixedFunctionReplay, DefaultsAreD3D9s) {
    // D3DTEXTURESTAGESTATETYPE: stage 0 COLOROP MODULATE, ALPHAOP SELECTARG1, later stages DISABLE;
    // ARG1 TEXTURE, ARG2 CURRENT, TEXCOORDINDEX the stage's own number.
    for (uint32_t stage = 0; stage < kMaxTextureStages; ++stage) {
        const auto& s = state().stages[stage];
        EXPECT_EQ(s[kTssColorOp], stage == 0 ? 4u : 1u) << stage;
        EXPECT_EQ(s[kTssAlphaOp], stage == 0 ? 2u : 1u) << stage;
        EXPECT_EQ(s[kTssColorArg1], 2u);
        EXPECT_EQ(s[kTssColorArg2], 1u);
        EXPECT_EQ(s[kTssAlphaArg1], 2u);
        EXPECT_EQ(s[kTssAlphaArg2], 1u);
        EXPECT_EQ(s[kTssTexCoordIndex], stage);
        EXPECT_EQ(s[kTssTextureTransformFlags], 0u);
        EXPECT_EQ(s[kTssResultArg], 1u);
    }
    EXPECT_EQ(state().fvf, 0u);
    EXPECT_EQ(state().view, identity_matrix());
    EXPECT_EQ(state().world[0], identity_matrix());
    EXPECT_EQ(state().material, Material{});
    EXPECT_TRUE(state().enabled_lights.empty());
}

TEST_F(FixedFunctionReplay, TransformsAreSetAndMultipliedInD3D9sOrder) {
    // VIEW = translation (1, 2, 3); MultiplyTransform VIEW by scale 2 is scale x translation
    // (pMatrix times State): the translation row stays (1, 2, 3, 1). The other order would give
    // (2, 4, 6, 1).
    ok("SetTransform VIEW f32[ 1 0 0 0  0 1 0 0  0 0 1 0  1 2 3 1 ]\n"
       "MultiplyTransform VIEW f32[ 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1 ]\n"
       "SetTransform WORLDMATRIX3 f32[ 1 2 3 4  5 6 7 8  9 10 11 12  13 14 15 16 ]\n"
       "SetTransform D3DTS_TEXTURE2 f32[ 0 1 0 0  1 0 0 0  0 0 1 0  0 0 0 1 ]\n");
    EXPECT_EQ(state().view, (Matrix4{2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}));
    EXPECT_EQ(state().world[3], (Matrix4{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}));
    EXPECT_EQ(state().texture[2], (Matrix4{0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
    EXPECT_EQ(state().projection, identity_matrix());

    const auto refused = refusals("SetTransform WORLDMATRIX256 f32[ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1 ]\n"
                                  "SetTransform VIEW f32[ 1 2 3 ]\n"
                                  "MultiplyTransform PROJECTION u8[ 1 2 3 4 ]\n");
    ASSERT_EQ(refused.size(), 3u);
    EXPECT_NE(refused[0].find("ff.sm2cs:2: D3DERR_INVALIDCALL: SetTransform: argument 1 (transform state): unknown name 'WORLDMATRIX256'"),
              std::string::npos) << refused[0];
    EXPECT_NE(refused[1].find("argument 2 (matrix): 3 floats, a matrix has 16"), std::string::npos) << refused[1];
    EXPECT_NE(refused[2].find("argument 2 (matrix): 1 floats, a matrix has 16"), std::string::npos) << refused[2];
    EXPECT_EQ(state().view, (Matrix4{2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}));
}

TEST_F(FixedFunctionReplay, MaterialAndLightsAreStoredAndEnabledUpToEight) {
    // ff_lit_cube's calls 20, 23 and 24 (the reference dump's values).
    ok("SetMaterial { 1 1 1 1 } { 0.5 0.5 0.5 1 } { 0.5 0.5 0.5 1 } { 0 0 0 0 } 20\n"
       "SetLight 1 POINT { 0.2 0.4 1 1 } { 0 0 0 0 } { 0 0 0 0 } { -2.5 1 -2.5 } { 0 0 0 } 10 0 0.2 0.15 0 0 0\n"
       "LightEnable 1 TRUE\n");
    EXPECT_EQ(state().material, (Material{{1, 1, 1, 1}, {0.5f, 0.5f, 0.5f, 1}, {0.5f, 0.5f, 0.5f, 1}, {0, 0, 0, 0}, 20}));
    const Light& point = state().lights.at(1);
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_EQ(point.diffuse, (ColorValue{0.2f, 0.4f, 1, 1}));
    EXPECT_EQ(point.position, (Vector3{-2.5f, 1, -2.5f}));
    EXPECT_EQ(point.range, 10.0f);
    EXPECT_EQ(point.attenuation0, 0.2f);
    EXPECT_EQ(point.attenuation1, 0.15f);
    EXPECT_EQ(state().enabled_lights, (std::vector<uint32_t>{1}));

    // LightEnable of an index no SetLight named makes D3D9's default light: directional, white
    // diffuse (alpha 0), direction (0, 0, 1).
    ok("LightEnable 1000 TRUE\n");
    const Light& made = state().lights.at(1000);
    EXPECT_EQ(made.type, LightType::Directional);
    EXPECT_EQ(made.diffuse, (ColorValue{1, 1, 1, 0}));
    EXPECT_EQ(made.direction, (Vector3{0, 0, 1}));
    EXPECT_EQ(made.specular, ColorValue{});

    // Enabling twice is one light; the ninth at once is refused; disabling frees a place.
    ok("LightEnable 1 TRUE\nLightEnable 2 TRUE\nLightEnable 3 TRUE\nLightEnable 4 TRUE\nLightEnable 5 TRUE\n"
       "LightEnable 6 TRUE\nLightEnable 7 TRUE\n");
    EXPECT_EQ(state().enabled_lights.size(), 8u);
    auto refused = refusals("LightEnable 8 TRUE\n");
    ASSERT_EQ(refused.size(), 1u);
    EXPECT_EQ(refused[0], "ff.sm2cs:2: D3DERR_INVALIDCALL: LightEnable: light 8: 8 lights are enabled already (MaxActiveLights)");
    ok("LightEnable 1000 FALSE\nLightEnable 8 TRUE\n");
    EXPECT_FALSE(state().light_enabled(1000));
    EXPECT_TRUE(state().light_enabled(8));

    refused = refusals("SetLight 0 AREA { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 0 0 0 0 0 0 0\n"
                       "SetLight 0 SPOT { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } -1 0 0 0 0 0 0\n"
                       "SetLight 0 SPOT { 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 1 0 0 0 0 0 0\n"
                       "SetMaterial { 1 1 1 1 } { 1 1 1 1 } { 1 1 1 1 } 0 20\n");
    ASSERT_EQ(refused.size(), 4u);
    EXPECT_NE(refused[0].find("argument 2 (type): unknown name 'AREA' (expected one of POINT, SPOT, DIRECTIONAL)"),
              std::string::npos) << refused[0];
    EXPECT_NE(refused[1].find("SetLight: a point or spot light's range"), std::string::npos) << refused[1];
    EXPECT_NE(refused[2].find("argument 3 (diffuse): expected 4 numbers { r g b a }, got 3"), std::string::npos) << refused[2];
    EXPECT_NE(refused[3].find("argument 4 (emissive): expected a tuple { r g b a }, got an integer 0"), std::string::npos)
        << refused[3];
    EXPECT_EQ(state().lights.count(0), 0u);
}

TEST_F(FixedFunctionReplay, TextureStageStatesTakeNamesTuplesAndNumbers) {
    ok("SetTextureStageState 0 COLOROP MODULATE2X\n"
       "SetTextureStageState 0 COLORARG1 { TEXTURE COMPLEMENT }\n"
       "SetTextureStageState 1 ALPHAARG2 { TFACTOR ALPHAREPLICATE }\n"
       "SetTextureStageState 2 TEXCOORDINDEX { CAMERASPACENORMAL 1 }\n"
       "SetTextureStageState 3 TEXTURETRANSFORMFLAGS { COUNT3 PROJECTED }\n"
       "SetTextureStageState 4 BUMPENVMAT01 0.25\n"
       "SetTextureStageState 5 CONSTANT 0x80FF0000\n"
       "SetTextureStageState 7 D3DTSS_RESULTARG TEMP\n"
       "SetTextureStageState 6 TEXCOORDINDEX 3\n");
    EXPECT_EQ(state().stages[0][kTssColorOp], 5u);
    EXPECT_EQ(state().stages[0][kTssColorArg1], 0x12u);
    EXPECT_EQ(state().stages[1][kTssAlphaArg2], 0x23u);
    EXPECT_EQ(state().stages[2][kTssTexCoordIndex], 0x10001u);
    EXPECT_EQ(state().stages[3][kTssTextureTransformFlags], 0x103u);
    float bump = 0;
    std::memcpy(&bump, &state().stages[4][kTssBumpEnvMat01], 4);
    EXPECT_EQ(bump, 0.25f);
    EXPECT_EQ(state().stages[5][kTssConstant], 0x80FF0000u);
    EXPECT_EQ(state().stages[7][kTssResultArg], 5u);
    EXPECT_EQ(state().stages[6][kTssTexCoordIndex], 3u);

    const auto refused = refusals("SetTextureStageState 8 COLOROP DISABLE\n"
                                  "SetTextureStageState 0 COLOROP SPARKLE\n"
                                  "SetTextureStageState 0 TEXTURESIZE 1\n"
                                  "SetTextureStageState 0 COLOROP 4\n");
    ASSERT_EQ(refused.size(), 4u);
    EXPECT_EQ(refused[0], "ff.sm2cs:2: D3DERR_INVALIDCALL: SetTextureStageState: stage 8 out of range (0 to 7)");
    EXPECT_NE(refused[1].find("unknown name 'SPARKLE' (expected one of DISABLE, SELECTARG1,"), std::string::npos) << refused[1];
    EXPECT_NE(refused[2].find("argument 2 (state): unknown texture stage state 'TEXTURESIZE'"), std::string::npos) << refused[2];
    EXPECT_NE(refused[3].find("argument 3 (COLOROP value): expected a name of DISABLE"), std::string::npos) << refused[3];
    EXPECT_EQ(state().stages[0][kTssColorOp], 5u);
}

// SetFVF binds the FVF's layout as the declaration, so a vertex shader reads an FVF buffer:
// XYZ | DIFFUSE vertices (16 bytes each) with the colour 0xFF00FF00 reach oD0 as (0, 1, 0, 1).
TEST_F(FixedFunctionReplay, SetFvfFeedsAShaderDraw) {
    ok("CreateDevice 4 4 A8R8G8B8\n"
       "CreateVertexShader vs asm<<END\n"
       "vs_2_0\n"
       "dcl_position v0\n"
       "dcl_color v1\n"
       "mov oPos, v0\n"
       "mov oD0, v1\n"
       "END\n"
       "CreateVertexBuffer vb 64\n"
       "Lock vb 0 u32[ 0xBF800000 0x3F800000 0x3F000000 0xFF00FF00  0x3F800000 0x3F800000 0x3F000000 0xFF00FF00\n"
       "               0xBF800000 0xBF800000 0x3F000000 0xFF00FF00  0x3F800000 0xBF800000 0x3F000000 0xFF00FF00 ]\n"
       "SetFVF { XYZ DIFFUSE }\n"
       "SetVertexShader vs\n"
       "SetStreamSource 0 vb 0 16\n"
       "SetRenderState CULLMODE NONE\n"
       "BeginScene\n"
       "DrawPrimitive TRIANGLESTRIP 0 2\n"
       "EndScene\n");
    EXPECT_EQ(state().fvf, 0x42u);
    const Surface* back = device_.surface("backbuffer");
    ASSERT_NE(back, nullptr);
    for (size_t i = 0; i < back->bytes().size(); i += 4) {
        const auto* px = reinterpret_cast<const uint8_t*>(back->bytes().data()) + i;
        EXPECT_EQ(px[0], 0x00);  // B
        EXPECT_EQ(px[1], 0xFF);  // G
        EXPECT_EQ(px[2], 0x00);  // R
    }
    // A declaration replaces the FVF (GetFVF would answer 0); a bad FVF changes nothing.
    ok("CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\nSetVertexDeclaration decl\n");
    EXPECT_EQ(state().fvf, 0u);
    const auto refused = refusals("SetFVF 0x900\nSetFVF { XYZ GLITTER }\n");
    ASSERT_EQ(refused.size(), 2u);
    EXPECT_EQ(refused[0], "ff.sm2cs:2: D3DERR_INVALIDCALL: SetFVF: TEX9 (at most TEX8)");
    EXPECT_NE(refused[1].find("SetFVF: argument 1 (fvf): item 2: unknown name 'GLITTER' (expected one of XYZ, XYZRHW,"), std::string::npos) << refused[1];
    EXPECT_EQ(state().fvf, 0u);
}

// Canonical text of every new call survives text -> binary -> text byte for byte.
TEST(FixedFunctionStream, CallsRoundTripThroughTheBinaryForm) {
    const std::string text =
        "sm2cs 1\n"
        "SetFVF { XYZ NORMAL TEX1 }\n"
        "SetFVF 0x00000112\n"
        "SetTransform WORLDMATRIX7 f32[\n  1.0 0.0 0.0 0.0 0.0 1.0 0.0 0.0\n  0.0 0.0 1.0 0.0 0.5 -2.0 3.25 1.0\n]\n"
        "MultiplyTransform VIEW f32[\n  2.0 0.0 0.0 0.0 0.0 2.0 0.0 0.0\n  0.0 0.0 2.0 0.0 0.0 0.0 0.0 1.0\n]\n"
        "SetMaterial { 1.0 1.0 1.0 1.0 } { 0.5 0.5 0.5 1.0 } { 0.5 0.5 0.5 1.0 } { 0.0 0.0 0.0 0.0 } 20.0\n"
        "SetLight 0 DIRECTIONAL { 0.8 0.8 0.7 1.0 } { 0.5 0.5 0.5 1.0 } { 0.0 0.0 0.0 0.0 } { 0.0 0.0 0.0 } "
        "{ -0.5 -0.6 0.7 } 0.0 0.0 0.0 0.0 0.0 0.0 0.0\n"
        "LightEnable 0 TRUE\n"
        "SetTextureStageState 0 COLORARG1 { TEXTURE ALPHAREPLICATE }\n"
        "SetTextureStageState 1 TEXCOORDINDEX { SPHEREMAP 0 }\n";
    auto parsed = cs::parse_text(text);
    ASSERT_TRUE(parsed.ok()) << parsed.error->to_string();
    EXPECT_EQ(cs::to_text(*parsed.stream), text);
    auto unpacked = cs::unpack(cs::pack(*parsed.stream));
    ASSERT_TRUE(unpacked.ok());
    EXPECT_EQ(cs::to_text(*unpacked.stream), text);
    // Binary ids are appended, never renumbered: the fixed-function calls after the device calls
    // (ColorFill 49 ... SetGammaRamp 61).
    EXPECT_EQ(cs::call_id("SetDeviceLimits"), 48u);
    EXPECT_EQ(cs::call_id("SetGammaRamp"), 61u);
    EXPECT_EQ(cs::call_id("SetFVF"), 62u);
    EXPECT_EQ(cs::call_id("SetTextureStageState"), 68u);
}

}  // namespace
}  // namespace sm2::runtime
