// The replayer's draw calls: each form of draw (from buffers, indexed, from user memory) replayed
// onto a Device and its pixels checked against values worked out by hand; refused draws keep
// their line and leave the surfaces alone.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/stream_assembler.h"
#include "runtime/replay_text.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime {
namespace {

// A 4x4 back buffer cleared to opaque black, a pass-through vertex shader, a pixel shader
// writing c0 = (1, 0.5, 0, 1), culling off.
const std::string kSetup =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"                         // 2
    "CreateVertexShader vs asm<<END\n"                     // 3
    "vs_2_0\n"
    "dcl_position v0\n"
    "mov oPos, v0\n"
    "END\n"
    "CreatePixelShader ps asm<<END\n"                      // 8
    "ps_2_0\n"
    "mov oC0, c0\n"
    "END\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"  // 12
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "SetPixelShaderConstantF 0 f32[ 1 0.5 0 1 ]\n"
    "SetRenderState CULLMODE NONE\n"
    "Clear TARGET 0xFF000000 1 0\n"                        // 18
    "BeginScene\n";                                        // 19

// (1, 0.5, 0, 1) in A8R8G8B8: B 0, G round(127.5) = 128, R 255, A 255
const std::vector<uint8_t> kOrange = {0x00, 0x80, 0xFF, 0xFF};
const std::vector<uint8_t> kBlack = {0x00, 0x00, 0x00, 0xFF};

using Outcome = test::ReplayOutcome;
using test::expect_no_diagnostics;

Outcome replay_text(const std::string& body) { return test::replay_stream_text(kSetup + body, "d.sm2cs"); }

// Every pixel of the 4x4 back buffer is `texel`.
std::vector<uint8_t> filled(const std::vector<uint8_t>& texel) {
    std::vector<uint8_t> out;
    for (int i = 0; i < 16; ++i) out.insert(out.end(), texel.begin(), texel.end());
    return out;
}

// The whole viewport as a quad in clip space, z = 0.5.
const std::string kQuadStrip = "-1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5";

TEST(ReplayDraw, DrawPrimitiveUpFillsTheViewport) {
    const Outcome o = replay_text("DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ " + kQuadStrip + " ]\nEndScene\nPresent\n");
    expect_no_diagnostics(o.result);
    EXPECT_EQ(o.pixels, filled(kOrange));
    EXPECT_EQ(o.statistics.draws, 1u);
    EXPECT_EQ(o.statistics.primitives, 2u);
    EXPECT_EQ(o.statistics.vertices_shaded, 4u);
    ASSERT_EQ(o.result.frames.size(), 1u);
    EXPECT_EQ(o.result.frames[0].statistics.draws, 1u);
    EXPECT_EQ(o.result.statistics.primitives, 2u);
}

TEST(ReplayDraw, DrawPrimitiveFromAVertexBuffer) {
    // The left half: x from -1 to 0 covers pixel centres 0 and 1; centre 2 lies on the right
    // edge, which the top-left rule leaves out.
    const Outcome o = replay_text(
        "CreateVertexBuffer vb 72\n"
        "Lock vb 0 f32[ -1 1 0.5   0 1 0.5   -1 -1 0.5     0 1 0.5   0 -1 0.5   -1 -1 0.5 ]\n"
        "SetStreamSource 0 vb 0 12\n"
        "DrawPrimitive TRIANGLELIST 0 2\n");
    expect_no_diagnostics(o.result);
    std::vector<uint8_t> row;
    for (const auto* t : {&kOrange, &kOrange, &kBlack, &kBlack}) row.insert(row.end(), t->begin(), t->end());
    std::vector<uint8_t> expected;
    for (int y = 0; y < 4; ++y) expected.insert(expected.end(), row.begin(), row.end());
    EXPECT_EQ(o.pixels, expected);
    EXPECT_EQ(o.statistics.primitives, 2u);
}

TEST(ReplayDraw, DrawIndexedPrimitiveSharesVertices) {
    const Outcome o = replay_text(
        "CreateVertexBuffer vb 60\n"
        "Lock vb 12 f32[ " + kQuadStrip + " ]\n"  // vertices 1..4 (vertex 0 unused)
        "CreateIndexBuffer ib 12 INDEX16\n"
        "Lock ib 0 u16[ 0 1 2   1 3 2 ]\n"
        "SetStreamSource 0 vb 0 12\n"
        "SetIndices ib\n"
        "DrawIndexedPrimitive TRIANGLELIST 1 0 4 0 2\n");  // base vertex 1
    expect_no_diagnostics(o.result);
    EXPECT_EQ(o.pixels, filled(kOrange));
    EXPECT_EQ(o.statistics.vertices_shaded, 4u);  // 6 indices, 4 distinct vertices
}

TEST(ReplayDraw, DrawIndexedPrimitiveUp) {
    const Outcome o = replay_text("DrawIndexedPrimitiveUP TRIANGLELIST 0 4 2 u32[ 0 1 2 1 3 2 ] INDEX32 f32[ " +
                                  kQuadStrip + " ] 12\n");
    expect_no_diagnostics(o.result);
    EXPECT_EQ(o.pixels, filled(kOrange));
}

TEST(ReplayDraw, RefusedDrawsKeepTheirLineAndTheSurface) {
    const Outcome o = replay_text(
        "CreateVertexBuffer vb 36\n"                       // 20
        "SetStreamSource 0 vb 0 12\n"                      // 21
        "DrawPrimitive TRIANGLELIST 0 2\n"                 // 22: 6 vertices, the buffer holds 3
        "SetVertexShader NULL\n"                           // 23
        "SetRenderState VERTEXBLEND 255\n"                                // 24: TWEENING
        "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ " + kQuadStrip + " ]\n"  // 25: tweening without POSITION1, refused
        "EndScene\n"
        "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ " + kQuadStrip + " ]\n");  // 27: outside the scene
    ASSERT_EQ(o.result.diagnostics.size(), 3u);
    EXPECT_EQ(o.result.diagnostics[0].line, 22u);
    EXPECT_EQ(o.result.diagnostics[0].call, "DrawPrimitive");
    EXPECT_EQ(o.result.diagnostics[1].line, 25u);
    EXPECT_EQ(o.result.diagnostics[1].call, "DrawPrimitiveUP");
    EXPECT_NE(o.result.diagnostics[1].message.find("TWEENING"), std::string::npos)
        << o.result.diagnostics[1].message;
    EXPECT_EQ(o.result.diagnostics[2].line, 27u);
    EXPECT_NE(o.result.diagnostics[2].message.find("BeginScene"), std::string::npos) << o.result.diagnostics[2].message;
    EXPECT_EQ(o.pixels, filled(kBlack));
    EXPECT_EQ(o.statistics.draws, 0u);
}

// Alpha test on the alpha the shader wrote: clamped to [0, 1] where render target 0 clamps
// (A8R8G8B8), as written on float targets (A32B32G32R32F, A16B16G16R16F): 1.5 passes GREATER 255
// and -0.25 passes LESS 0 there, and fails both on the 8-bit target.
bool alpha_test_writes(const std::string& format, const std::string& alpha, const std::string& func,
                       const std::string& ref) {
    const std::string text =
        "sm2cs 1\n"
        "CreateDevice 4 4 A8R8G8B8\n"
        "CreateRenderTarget rt 4 4 " + format + "\n"
        "SetRenderTarget 0 rt\n"
        "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
        "CreatePixelShader ps asm<<END\nps_2_0\nmov oC0, c0\nEND\n"
        "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
        "SetVertexDeclaration decl\nSetVertexShader vs\nSetPixelShader ps\n"
        "SetPixelShaderConstantF 0 f32[ 0.25 0.5 0.75 " + alpha + " ]\n"
        "SetRenderState CULLMODE NONE\n"
        "SetRenderState ALPHATESTENABLE TRUE\n"
        "SetRenderState ALPHAFUNC " + func + "\n"
        "SetRenderState ALPHAREF " + ref + "\n"
        "Clear TARGET 0x00000000 1 0\n"
        "BeginScene\n"
        "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ " + kQuadStrip + " ]\n"
        "EndScene\n";
    auto parsed = cs::parse_text(text);
    EXPECT_TRUE(parsed.ok()) << parsed.error->to_string();
    if (!parsed.ok()) return false;
    Device device;
    ReplayOptions options;
    options.assembler = runtime::stream_assembler();
    const ReplayResult r = replay(device, *parsed.stream, options);
    expect_no_diagnostics(r);
    const Surface* rt = device.surface("rt");
    EXPECT_NE(rt, nullptr);
    if (!rt) return false;
    const Float4 pixel = rt->read(1, 1);
    EXPECT_EQ(pixel, rt->read(2, 3)) << "every pixel alike";
    if (pixel[1] == 0.0f) return false;  // still cleared
    EXPECT_NEAR(pixel[1], 0.5f, 1.0f / 255);  // 128/255 on the 8-bit target
    return true;
}

TEST(ReplayDraw, AlphaTestClampsOnlyWhereTheTargetClamps) {
    for (const char* format : {"A32B32G32R32F", "A16B16G16R16F"}) {
        EXPECT_TRUE(alpha_test_writes(format, "1.5", "GREATER", "255")) << format;
        EXPECT_TRUE(alpha_test_writes(format, "-0.25", "LESS", "0")) << format;
        EXPECT_FALSE(alpha_test_writes(format, "1", "GREATER", "255")) << format;
        EXPECT_FALSE(alpha_test_writes(format, "0", "LESS", "0")) << format;
    }
    // 8-bit UNORM: 1.5 clamps to 1, not greater than 255/255; -0.25 clamps to 0, not less than 0
    EXPECT_FALSE(alpha_test_writes("A8R8G8B8", "1.5", "GREATER", "255"));
    EXPECT_FALSE(alpha_test_writes("A8R8G8B8", "-0.25", "LESS", "0"));
    EXPECT_TRUE(alpha_test_writes("A8R8G8B8", "1.5", "GREATEREQUAL", "255"));
    EXPECT_TRUE(alpha_test_writes("A8R8G8B8", "0.75", "GREATER", "128"));
}

}  // namespace
}  // namespace sm2::runtime
