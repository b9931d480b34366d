// Draws without shaders: the fixed-function vertex and pixel programs generated from the state
// (runtime/src/fixed_function_programs.cpp, docs/fixed-function.md). Every expected pixel is worked
// out by hand from D3D9's documented rules: XYZRHW coordinates are render-target pixels (centres
// at integers), World x View x Projection transforms row vectors, the texture operations'
// formulas of D3DTEXTUREOP, and the target's UNORM conversion (round to nearest).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "fixed_function_programs.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"
#include "runtime/replay_text.h"

namespace sm2::runtime {
namespace {

// A 4x4 back buffer cleared to opaque black, culling off, no shaders.
const std::string kSetup =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "SetRenderState CULLMODE NONE\n"
    "Clear TARGET 0xFF000000 1 0\n"
    "BeginScene\n";

using Outcome = test::ReplayOutcome;
using test::expect_no_diagnostics;

Outcome replay_text(const std::string& body) { return test::replay_stream_text(kSetup + body, "ff.sm2cs"); }

// The A8R8G8B8 pixel (x, y) as 0xAARRGGBB.
uint32_t pixel(const Outcome& o, unsigned x, unsigned y) {
    uint32_t v = 0;
    std::memcpy(&v, o.pixels.data() + (y * 4 + x) * 4, 4);
    return v;
}

// Vertex data as a u32 blob: floats by their bits, colours as D3DCOLOR words.
struct Words {
    std::vector<uint32_t> words;
    Words& f(std::initializer_list<float> values) {
        for (float v : values) words.push_back(std::bit_cast<uint32_t>(v));
        return *this;
    }
    Words& color(uint32_t argb) {
        words.push_back(argb);
        return *this;
    }
    [[nodiscard]] std::string blob() const {
        std::string out = "u32[";
        for (uint32_t w : words) out += ' ' + std::to_string(w);
        return out + " ]";
    }
};

// An XYZRHW | DIFFUSE quad (triangle strip) from (x0, y0) to (x1, y1) in pixels.
std::string rhw_quad(float x0, float y0, float x1, float y1, uint32_t diffuse, float rhw = 1.0f) {
    Words w;
    w.f({x0, y0, 0.5f, rhw}).color(diffuse).f({x1, y0, 0.5f, rhw}).color(diffuse);
    w.f({x0, y1, 0.5f, rhw}).color(diffuse).f({x1, y1, 0.5f, rhw}).color(diffuse);
    return "SetFVF { XYZRHW DIFFUSE }\nDrawPrimitiveUP TRIANGLESTRIP 2 20 " + w.blob() + "\n";
}

TEST(FixedFunctionDraw, XyzrhwVertexCoversExactlyItsPixel) {
    // The square [1.5, 2.5) x [0.5, 1.5) holds one pixel centre, (2, 1); with rhw 0.25 (w = 4)
    // it must land in the same place (the program multiplies by w, the viewport divides).
    for (float rhw : {1.0f, 0.25f}) {
        const Outcome o = replay_text(rhw_quad(1.5f, 0.5f, 2.5f, 1.5f, 0xFF00FF00u, rhw));
        expect_no_diagnostics(o.result);
        for (unsigned y = 0; y < 4; ++y)
            for (unsigned x = 0; x < 4; ++x)
                EXPECT_EQ(pixel(o, x, y), x == 2 && y == 1 ? 0xFF00FF00u : 0xFF000000u) << x << "," << y << " rhw " << rhw;
    }
}

TEST(FixedFunctionDraw, XyzrhwHonoursTheViewportOrigin) {
    // Pre-transformed x, y are render-target pixels whatever the viewport: with the viewport at
    // (2, 2) the square around centre (1, 1) still lands on pixel (1, 1)... and is clipped away
    // outside the viewport, so only a square inside it shows: centre (3, 2).
    const Outcome o = replay_text("SetViewport 2 2 2 2 0 1\n" + rhw_quad(2.5f, 1.5f, 3.5f, 2.5f, 0xFF0000FFu));
    expect_no_diagnostics(o.result);
    for (unsigned y = 0; y < 4; ++y)
        for (unsigned x = 0; x < 4; ++x)
            EXPECT_EQ(pixel(o, x, y), x == 3 && y == 2 ? 0xFF0000FFu : 0xFF000000u) << x << "," << y;
}

TEST(FixedFunctionDraw, WorldViewProjectionTransformXyzPositions) {
    // A quad over the left half of clip space, x in [-1, 0]; WORLD translates x by +0.5 and
    // PROJECTION scales y by 0.5: x in [-0.5, 0.5] -> pixels x 1..2, y in [-0.5, 0.5] -> rows 1..2.
    // No DIFFUSE in the vertex: D3D9's default diffuse, opaque white.
    Words w;
    w.f({-1, 1, 0.5f}).f({0, 1, 0.5f}).f({-1, -1, 0.5f}).f({0, -1, 0.5f});
    const Outcome o = replay_text(
        "SetRenderState LIGHTING FALSE\n"
        "SetTransform WORLD f32[ 1 0 0 0  0 1 0 0  0 0 1 0  0.5 0 0 1 ]\n"
        "SetTransform PROJECTION f32[ 1 0 0 0  0 0.5 0 0  0 0 1 0  0 0 0 1 ]\n"
        "SetFVF XYZ\nDrawPrimitiveUP TRIANGLESTRIP 2 12 " + w.blob() + "\n");
    expect_no_diagnostics(o.result);
    for (unsigned y = 0; y < 4; ++y)
        for (unsigned x = 0; x < 4; ++x) {
            const bool inside = x >= 1 && x <= 2 && y >= 1 && y <= 2;
            EXPECT_EQ(pixel(o, x, y), inside ? 0xFFFFFFFFu : 0xFF000000u) << x << "," << y;
        }
}

// A full-target XYZ | NORMAL quad at z = 0.5 (identity transforms) with one normal for all four
// vertices, so that every vertex gets the same lit colour and the pixels show it exactly.
std::string lit_quad(float nx, float ny, float nz) {
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}})
        w.f({x, y, 0.5f, nx, ny, nz});
    return "SetFVF { XYZ NORMAL }\nDrawPrimitiveUP TRIANGLESTRIP 2 24 " + w.blob() + "\n";
}

TEST(FixedFunctionDraw, DirectionalLightOnAKnownNormal) {
    // Light: directional, diffuse (1, 0.5, 0.25), shining along +z, so L (towards the light) =
    // (0, 0, -1); N = (0, 0.6, -0.8): N.L = 0.8. Material diffuse 0.8 (no vertex colour, so
    // COLORVERTEX falls back to the material), ambient 0.5; AMBIENT 0x202020 (32/255).
    // colour = Ca Ga + Cd Ld N.L = 0.5 * 0.12549 + 0.8 * 0.8 * (1, 0.5, 0.25)
    //        = (0.70275, 0.38275, 0.22275) -> (179.2, 97.6, 56.8) -> (0xB3, 0x62, 0x39); alpha Cd.a = 1.
    const Outcome o = replay_text(
        "SetRenderState AMBIENT 0x00202020\n"
        "SetMaterial { 0.8 0.8 0.8 1 } { 0.5 0.5 0.5 1 } { 0 0 0 0 } { 0 0 0 0 } 0\n"
        "SetLight 0 DIRECTIONAL { 1 0.5 0.25 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 0 0 0 0 0 0 0\n"
        "LightEnable 0 TRUE\n" + lit_quad(0, 0.6f, -0.8f));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 1, 2), 0xFFB36239u);
    // Facing away (N.L < 0): only the ambient term, 0.0627 -> 16 (0x10).
    const Outcome away = replay_text(
        "SetRenderState AMBIENT 0x00202020\n"
        "SetMaterial { 0.8 0.8 0.8 1 } { 0.5 0.5 0.5 1 } { 0 0 0 0 } { 0 0 0 0 } 0\n"
        "SetLight 0 DIRECTIONAL { 1 0.5 0.25 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 0 0 0 0 0 0 0\n"
        "LightEnable 0 TRUE\n" + lit_quad(0, 0, 1));
    expect_no_diagnostics(away.result);
    EXPECT_EQ(pixel(away, 1, 2), 0xFF101010u);
}

TEST(FixedFunctionDraw, SpecularHighlightWithALocalViewer) {
    // Directional light along +z (L = (0, 0, -1)), N = (0, 0, -1), the eye at the origin: from
    // each corner (+-1, +-1, 0.5) the eye direction is (-+1, -+1, -0.5) / 1.5, H = norm(E + L) =
    // norm(-+0.6667, -+0.6667, -1.3333), N.H = 1.3333 / 1.63299 = 0.81650; Power 2: 0.66667;
    // light specular 1, material specular 0.6: 0.4 -> 102 (0x66) with SPECULARENABLE (material
    // diffuse and ambient 0, so the specular is all there is).
    // LOCALVIEWER off: the eye infinitely far down -z, E = (0, 0, -1), H = norm(E + L). The light
    // shining along (-0.6, 0, 0.8), L = (0.6, 0, -0.8), N = (0.6, 0, -0.8): N.L = 1,
    // H = norm(0.6, 0, -1.8) = (0.31623, 0, -0.94868), N.H = 0.94868, N.H^2 = 0.9,
    // 0.6 * 0.9 = 0.54 -> 137.7 -> 0x8A, the same at every vertex (with the local viewer it would
    // differ per vertex). With E = (0, 0, +1) (the highlight on the far side; what this code did
    // before ff_lighting.trace showed Wine's highlight) N.H^2 = 0.1: 0x0F.
    const auto highlight = [](const char* local_viewer, const char* direction, float nx, float nz) {
        const Outcome o = replay_text(
            std::string("SetRenderState SPECULARENABLE TRUE\nSetRenderState LOCALVIEWER ") + local_viewer +
            "\nSetMaterial { 0 0 0 1 } { 0 0 0 0 } { 0.6 0.6 0.6 1 } { 0 0 0 0 } 2\n"
            "SetLight 0 DIRECTIONAL { 0 0 0 0 } { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 } " + direction +
            " 0 0 0 0 0 0 0\nLightEnable 0 TRUE\n" + lit_quad(nx, 0, nz));
        expect_no_diagnostics(o.result);
        return pixel(o, 1, 1);
    };
    EXPECT_EQ(highlight("TRUE", "{ 0 0 1 }", 0, -1), 0xFF666666u);
    EXPECT_EQ(highlight("FALSE", "{ -0.6 0 0.8 }", 0.6f, -0.8f), 0xFF8A8A8Au);
}

TEST(FixedFunctionDraw, PointLightAttenuationAndRange) {
    // Point light at (0, 0, -2); the quad's corners (+-1, +-1, 0.5) are all d = sqrt(8.25) =
    // 2.87228 from it, N = (0, 0, -1): N.L = 2.5 / d = 0.87039; Atten = 1 / (0.5 + 0.25 d) =
    // 0.82097; white light and material: 0.71456 -> 182.2 -> 182 (0xB6).
    const std::string material = "SetMaterial { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 0 } 0\n";
    const auto light = [](const char* range) {
        return std::string("SetLight 3 POINT { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 -2 } { 0 0 0 } ") + range +
               " 0 0.5 0.25 0 0 0\nLightEnable 3 TRUE\n";
    };
    const Outcome in_range = replay_text(material + light("10") + lit_quad(0, 0, -1));
    expect_no_diagnostics(in_range.result);
    EXPECT_EQ(pixel(in_range, 2, 1), 0xFFB6B6B6u);
    // Range 2.8 < d: no light at all.
    const Outcome beyond = replay_text(material + light("2.8") + lit_quad(0, 0, -1));
    expect_no_diagnostics(beyond.result);
    EXPECT_EQ(pixel(beyond, 2, 1), 0xFF000000u);
}

TEST(FixedFunctionDraw, SpotLightPenumbra) {
    // The point light of PointLightAttenuationAndRange as a spot shining along +z, theta =
    // 0.902054 (cos(theta/2) = 0.9), phi = 1.287002 (cos(phi/2) = 0.8): rho = L . (0, 0, -1) =
    // 0.87039 lies in the penumbra, x = (0.87039 - 0.8) / 0.1 = 0.70391. Falloff 1: 0.87039 *
    // 0.82097 * 0.70391 = 0.50297 -> 128.26 -> 0x80; falloff 2: 0.35403 -> 90.28 -> 0x5A.
    const auto spot = [](const char* falloff, const char* phi) {
        return "SetMaterial { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 0 } 0\n"
               "SetLight 0 SPOT { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 -2 } { 0 0 1 } 10 " +
               std::string(falloff) + " 0.5 0.25 0 0.902054 " + phi + "\nLightEnable 0 TRUE\n" + lit_quad(0, 0, -1);
    };
    const Outcome linear = replay_text(spot("1", "1.287002"));
    expect_no_diagnostics(linear.result);
    EXPECT_EQ(pixel(linear, 1, 1), 0xFF808080u);
    const Outcome squared = replay_text(spot("2", "1.287002"));
    expect_no_diagnostics(squared.result);
    EXPECT_EQ(pixel(squared, 1, 1), 0xFF5A5A5Au);
    // phi = theta: no penumbra, rho = 0.87039 < cos(theta/2) = 0.9 is outside: black.
    const Outcome outside = replay_text(spot("1", "0.902054"));
    expect_no_diagnostics(outside.result);
    EXPECT_EQ(pixel(outside, 1, 1), 0xFF000000u);
}

TEST(FixedFunctionDraw, GeneratedTextureCoordinates) {
    // A 2x1 texture, POINT: u < 0.5 reads the left texel (red), u >= 0.5 the right (green), with
    // WRAP addressing. Stage 0 SELECTARG1 TEXTURE with TEXCOORDINDEX generating u from camera
    // space (identity transforms, LIGHTING off, the vertex has no texture coordinates).
    const auto u_of = [](const std::string& tci, const std::string& body) {
        const Outcome o = replay_text(
            "CreateTexture tex 2 1 1 A8R8G8B8\nLockRect tex 0 u8[ 0 0 255 255  0 255 0 255 ]\nSetTexture 0 tex\n"
            "SetSamplerState 0 MINFILTER POINT\nSetSamplerState 0 MAGFILTER POINT\n"
            "SetRenderState LIGHTING FALSE\nSetRenderState LOCALVIEWER FALSE\n"
            "SetTextureStageState 0 COLOROP SELECTARG1\nSetTextureStageState 0 TEXCOORDINDEX " + tci + "\n" + body);
        expect_no_diagnostics(o.result);
        return o;
    };
    constexpr uint32_t kRed = 0xFFFF0000u, kGreen = 0xFF00FF00u;
    // CAMERASPACENORMAL: u = n.x: 0.8 -> green, 0.2 -> red.
    EXPECT_EQ(pixel(u_of("{ CAMERASPACENORMAL 0 }", lit_quad(0.8f, 0, -0.6f)), 1, 1), kGreen);
    EXPECT_EQ(pixel(u_of("{ CAMERASPACENORMAL 0 }", lit_quad(0.2f, 0, -0.98f)), 1, 1), kRed);
    // CAMERASPACEPOSITION: u = x, from -1 (left edge) to 1: pixel column 3 (x = 0.75) green,
    // column 0 (x = -0.75, wrapped to 0.25) red.
    const Outcome position = u_of("{ CAMERASPACEPOSITION 0 }", lit_quad(0, 0, -1));
    EXPECT_EQ(pixel(position, 3, 1), kGreen);
    EXPECT_EQ(pixel(position, 0, 1), kRed);
    // CAMERASPACEREFLECTIONVECTOR, LOCALVIEWER off: I = (0, 0, 1), N = (0.6, 0, -0.8): N.I = -0.8,
    // R = I + 1.6 N = (0.96, 0, -0.28) -> green; N = (-0.6, 0, -0.8): R.x = -0.96 -> 0.04 -> red.
    EXPECT_EQ(pixel(u_of("{ CAMERASPACEREFLECTIONVECTOR 0 }", lit_quad(0.6f, 0, -0.8f)), 2, 2), kGreen);
    EXPECT_EQ(pixel(u_of("{ CAMERASPACEREFLECTIONVECTOR 0 }", lit_quad(-0.6f, 0, -0.8f)), 2, 2), kRed);
}

TEST(FixedFunctionDraw, VertexFogFactorAtAKnownDepth) {
    // Camera-space z = 0.25 everywhere (identity transforms), white vertices, FOGCOLOR blue.
    // LINEAR start 0, end 1: f = (1 - 0.25) / 1 = 0.75: R = G = 0.75 -> 191.25 -> 0xBF, B = 1.
    // EXP density 2: f = e^-0.5 = 0.60653 -> 154.67 -> 0x9B. EXP2: e^-0.25 = 0.77880 -> 198.6 -> 0xC7.
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}}) w.f({x, y, 0.25f});
    const auto fogged = [&](const char* mode) {
        const Outcome o = replay_text(std::string("SetRenderState LIGHTING FALSE\nSetRenderState FOGENABLE TRUE\n"
                                                  "SetRenderState FOGCOLOR 0xFF0000FF\nSetRenderState FOGSTART 0\n"
                                                  "SetRenderState FOGEND 1\nSetRenderState FOGDENSITY 2\n"
                                                  "SetRenderState FOGVERTEXMODE ") +
                                      mode + "\nSetFVF XYZ\nDrawPrimitiveUP TRIANGLESTRIP 2 12 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return pixel(o, 2, 2);
    };
    EXPECT_EQ(fogged("LINEAR"), 0xFFBFBFFFu);
    EXPECT_EQ(fogged("EXP"), 0xFF9B9BFFu);
    EXPECT_EQ(fogged("EXP2"), 0xFFC7C7FFu);
}

// A full-target XYZ quad at z = `z` (identity transforms) of format `fvf`, every vertex
// carrying the same `attributes` after its position, so that every pixel shows the same value.
std::string uniform_quad(const std::string& fvf, std::initializer_list<float> attributes, float z = 0.5f) {
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}}) w.f({x, y, z}).f(attributes);
    return "SetFVF " + fvf + "\nDrawPrimitiveUP TRIANGLESTRIP 2 " + std::to_string(4 * (3 + attributes.size())) + " " +
           w.blob() + "\n";
}

// A 4x1 texture, POINT filtered, on stage 0 (SELECTARG1 TEXTURE, LIGHTING off): u in [0, 0.25)
// reads red, [0.25, 0.5) green, [0.5, 0.75) blue, [0.75, 1) white (WRAP outside).
const std::string kFourTexels =
    "CreateTexture tex 4 1 1 A8R8G8B8\n"
    "LockRect tex 0 u8[ 0 0 255 255  0 255 0 255  255 0 0 255  255 255 255 255 ]\nSetTexture 0 tex\n"
    "SetSamplerState 0 MINFILTER POINT\nSetSamplerState 0 MAGFILTER POINT\n"
    "SetRenderState LIGHTING FALSE\nSetTextureStageState 0 COLOROP SELECTARG1\n";
constexpr uint32_t kTexel0 = 0xFFFF0000u, kTexel1 = 0xFF00FF00u, kTexel2 = 0xFF0000FFu, kTexel3 = 0xFFFFFFFFu;

TEST(FixedFunctionDraw, TextureTransformOfTwoComponentCoordinates) {
    // D3D9 extends (u, v) to (u, v, 1, 0) for the TEXTURE0 matrix, so the third row translates
    // a 2D coordinate and the fourth does nothing: row 3 = (0.5, 0, 1, 0), row 4 = (0.1, 0, 0, 1):
    // u = 0.25 + 0.5 = 0.75 -> white (the fourth row would give 0.35, green; both 0.85, white).
    const std::string matrix = "SetTransform TEXTURE0 f32[ 1 0 0 0  0 1 0 0  0.5 0 1 0  0.1 0 0 1 ]\n";
    const std::string quad = uniform_quad("{ XYZ TEX1 }", {0.25f, 0.0f});
    const Outcome transformed = replay_text(kFourTexels + matrix + "SetTextureStageState 0 TEXTURETRANSFORMFLAGS COUNT2\n" + quad);
    expect_no_diagnostics(transformed.result);
    EXPECT_EQ(pixel(transformed, 1, 1), kTexel3);
    // DISABLE (the default): the matrix is ignored, u = 0.25 -> green.
    const Outcome untransformed = replay_text(kFourTexels + matrix + quad);
    expect_no_diagnostics(untransformed.result);
    EXPECT_EQ(pixel(untransformed, 1, 1), kTexel1);
}

TEST(FixedFunctionDraw, TextureTransformOfOneComponentCoordinates) {
    // A 1-component coordinate is extended to (u, 1, 0, 0): the second row translates it.
    // Row 2 = (0.5, 1, 0, 0): u = 0.25 + 0.5 = 0.75 -> white (a row-4 translation, 0, would leave
    // 0.25, green).
    const Outcome o = replay_text(kFourTexels + "SetTransform TEXTURE0 f32[ 1 0 0 0  0.5 1 0 0  0 0 1 0  0 0 0 1 ]\n"
                                  "SetTextureStageState 0 TEXTURETRANSFORMFLAGS COUNT1\n" +
                                  uniform_quad("{ XYZ TEX1 TEXCOORDSIZE1_0 }", {0.25f}));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 2, 2), kTexel3);
}

TEST(FixedFunctionDraw, ProjectedTextureCoordinates) {
    // D3DTTFF_PROJECTED divides by the last of the COUNTn components. (u, v, q) = (0.3, 0, 0.5)
    // under COUNT3 PROJECTED (identity matrix): u / q = 0.6 -> blue; COUNT3 alone: 0.3 -> green.
    const std::string quad = uniform_quad("{ XYZ TEX1 TEXCOORDSIZE3_0 }", {0.3f, 0.0f, 0.5f});
    const Outcome projected =
        replay_text(kFourTexels + "SetTextureStageState 0 TEXTURETRANSFORMFLAGS { COUNT3 PROJECTED }\n" + quad);
    expect_no_diagnostics(projected.result);
    EXPECT_EQ(pixel(projected, 1, 2), kTexel2);
    const Outcome plain = replay_text(kFourTexels + "SetTextureStageState 0 TEXTURETRANSFORMFLAGS COUNT3\n" + quad);
    expect_no_diagnostics(plain.result);
    EXPECT_EQ(pixel(plain, 1, 2), kTexel1);
    // A 2D coordinate (0.3, 0) -> (0.3, 0, 1, 0) with row 3 = (0, 0, 2, 0): (0.3, 0, 2), projected
    // 0.15 -> red.
    const Outcome from_2d = replay_text(kFourTexels + "SetTransform TEXTURE0 f32[ 1 0 0 0  0 1 0 0  0 0 2 0  0 0 0 1 ]\n"
                                        "SetTextureStageState 0 TEXTURETRANSFORMFLAGS { COUNT3 PROJECTED }\n" +
                                        uniform_quad("{ XYZ TEX1 }", {0.3f, 0.0f}));
    expect_no_diagnostics(from_2d.result);
    EXPECT_EQ(pixel(from_2d, 1, 2), kTexel0);
    // XYZRHW vertices are not transformed, but PROJECTED still divides by the set's last
    // component: (0.3, 0, 0.5) -> 0.6, blue.
    Words rhw;
    for (auto [x, y] : {std::pair{-0.5f, -0.5f}, {3.5f, -0.5f}, {-0.5f, 3.5f}, {3.5f, 3.5f}})
        rhw.f({x, y, 0.5f, 1.0f, 0.3f, 0.0f, 0.5f});
    const Outcome pretransformed = replay_text(kFourTexels + "SetTextureStageState 0 TEXTURETRANSFORMFLAGS { COUNT3 PROJECTED }\n"
                                               "SetFVF { XYZRHW TEX1 TEXCOORDSIZE3_0 }\nDrawPrimitiveUP TRIANGLESTRIP 2 28 " +
                                               rhw.blob() + "\n");
    expect_no_diagnostics(pretransformed.result);
    EXPECT_EQ(pixel(pretransformed, 2, 1), kTexel2);
}

TEST(FixedFunctionDraw, TransformedGeneratedCoordinates) {
    // CAMERASPACEPOSITION (x, y, z, 1) through TEXTURE0 = a scale of x by 0 and a translation of
    // 0.6 in the fourth row: u = 0.6 everywhere -> blue.
    const Outcome o = replay_text(kFourTexels + "SetTransform TEXTURE0 f32[ 0 0 0 0  0 1 0 0  0 0 1 0  0.6 0 0 1 ]\n"
                                  "SetTextureStageState 0 TEXCOORDINDEX { CAMERASPACEPOSITION 0 }\n"
                                  "SetTextureStageState 0 TEXTURETRANSFORMFLAGS COUNT2\n" +
                                  uniform_quad("XYZ", {}));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 0, 0), kTexel2);
    EXPECT_EQ(pixel(o, 3, 3), kTexel2);
}

TEST(FixedFunctionDraw, SphereMapTextureCoordinates) {
    // A 2x2 texture: top-left red, top-right green, bottom-left blue, bottom-right white.
    // LOCALVIEWER off, I = (0, 0, 1); N = (0.48, 0.6, -0.64): N.I = -0.64, R = I - 2 (N.I) N =
    // (0.6144, 0.768, 0.1808); m = 2 |(Rx, Ry, Rz - 1)| = 2 sqrt(0.37749 + 0.58982 + 0.67109) =
    // 2.56; u = Rx / m + 0.5 = 0.74, v = -Ry / m + 0.5 = 0.2: the top-right texel, green. (Wine's
    // Rz + 1 gives (0.70, 0.75) and OpenGL's +Ry / m gives v = 0.8: both bottom-right, white.)
    const Outcome o = replay_text(
        "CreateTexture tex 2 2 1 A8R8G8B8\n"
        "LockRect tex 0 u8[ 0 0 255 255  0 255 0 255  255 0 0 255  255 255 255 255 ]\nSetTexture 0 tex\n"
        "SetSamplerState 0 MINFILTER POINT\nSetSamplerState 0 MAGFILTER POINT\n"
        "SetRenderState LIGHTING FALSE\nSetRenderState LOCALVIEWER FALSE\n"
        "SetTextureStageState 0 COLOROP SELECTARG1\nSetTextureStageState 0 TEXCOORDINDEX { SPHEREMAP 0 }\n" +
        lit_quad(0.48f, 0.6f, -0.64f));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 1, 1), 0xFF00FF00u);
    // N = (0.28, 0, -0.96), nearly facing the eye: R = (0.5376, 0, -0.8432), m = 2 sqrt(0.28901
    // + 3.39737) = 3.84, u = 0.64 -> the 4x1 texture's third texel, blue (Rz + 1 would give m =
    // 1.12, u = 0.98, white).
    const Outcome facing = replay_text(kFourTexels + "SetRenderState LOCALVIEWER FALSE\n"
                                       "SetTextureStageState 0 TEXCOORDINDEX { SPHEREMAP 0 }\n" +
                                       lit_quad(0.28f, 0, -0.96f));
    expect_no_diagnostics(facing.result);
    EXPECT_EQ(pixel(facing, 2, 2), kTexel2);
}

TEST(FixedFunctionDraw, RangeFogUsesTheDistanceFromTheEye) {
    // Corners (+-1, +-1, 0.25): RANGEFOGENABLE's distance sqrt(2.0625) = 1.43614 at every vertex;
    // LINEAR 0..2: f = (2 - 1.43614) / 2 = 0.28193 -> R = G = 71.9 -> 0x48, B (FOGCOLOR blue) 0xFF.
    // Without range fog d = z = 0.25: f = 0.875 -> 223.1 -> 0xDF.
    const auto fogged = [](const char* range) {
        const Outcome o = replay_text(std::string("SetRenderState LIGHTING FALSE\nSetRenderState FOGENABLE TRUE\n"
                                                  "SetRenderState FOGCOLOR 0xFF0000FF\nSetRenderState FOGSTART 0\n"
                                                  "SetRenderState FOGEND 2\nSetRenderState FOGVERTEXMODE LINEAR\n"
                                                  "SetRenderState RANGEFOGENABLE ") +
                                      range + "\n" + uniform_quad("XYZ", {}, 0.25f));
        expect_no_diagnostics(o.result);
        return pixel(o, 2, 1);
    };
    EXPECT_EQ(fogged("TRUE"), 0xFF4848FFu);
    EXPECT_EQ(fogged("FALSE"), 0xFFDFDFFFu);
}

TEST(FixedFunctionDraw, TableFogOfAFixedFunctionDraw) {
    // FOGTABLEMODE: the merger's per-pixel factor of the depth (z = 0.25 with identity
    // transforms), for fixed-function draws as for shaders: EXP density 2: e^-0.5 = 0.60653 ->
    // 154.67 -> 0x9B.
    const Outcome o = replay_text(
        "SetRenderState LIGHTING FALSE\nSetRenderState FOGENABLE TRUE\nSetRenderState FOGCOLOR 0xFF0000FF\n"
        "SetRenderState FOGDENSITY 2\nSetRenderState FOGTABLEMODE EXP\n" + uniform_quad("XYZ", {}, 0.25f));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 1, 1), 0xFF9B9BFFu);
}

TEST(FixedFunctionDraw, TableFogUnderAPerspectiveProjectionIsWFog) {
    // D3D9 "Eye-Relative vs. Z-based Depth": with a perspective projection table fog is of the
    // eye-space depth (w), FOGSTART/FOGEND in camera units (what ff_fog_texgen.trace's cell 7
    // shows Wine doing). A quad at camera z = 4 filling the view of a projection with near 1, far
    // 10 (_33 = 10/9, _34 = 1, _43 = -10/9): LINEAR start 2, end 7: f = (7 - 4) / 5 = 0.6, white
    // fogged towards blue: (0.6, 0.6, 1) -> (153, 153, 255). Of the depth z/w = 0.8333 instead,
    // f = 1.23 would clamp to 1: white.
    Words w;
    for (auto [x, y] : {std::pair{-4.0f, 4.0f}, {4.0f, 4.0f}, {-4.0f, -4.0f}, {4.0f, -4.0f}}) w.f({x, y, 4.0f});
    const std::string fog =
        "SetRenderState LIGHTING FALSE\nSetRenderState FOGENABLE TRUE\nSetRenderState FOGCOLOR 0xFF0000FF\n"
        "SetRenderState FOGSTART 2\nSetRenderState FOGEND 7\nSetRenderState FOGTABLEMODE LINEAR\n";
    const std::string quad = "SetFVF XYZ\nDrawPrimitiveUP TRIANGLESTRIP 2 12 " + w.blob() + "\n";
    const Outcome o = replay_text(fog +
        "SetTransform PROJECTION f32[ 1 0 0 0  0 1 0 0  0 0 1.1111111 1  0 0 -1.1111111 0 ]\n" + quad);
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 1, 1), 0xFF9999FFu);
    EXPECT_EQ(pixel(o, 3, 0), 0xFF9999FFu);
    // An orthographic projection (fourth column (0, 0, 0, 1)) keeps the fog of the depth: the quad
    // through x/4, y/4, z/8: depth 0.5 < FOGSTART 2, no fog at all.
    const Outcome ortho = replay_text(fog +
        "SetTransform PROJECTION f32[ 0.25 0 0 0  0 0.25 0 0  0 0 0.125 0  0 0 0 1 ]\n" + quad);
    expect_no_diagnostics(ortho.result);
    EXPECT_EQ(pixel(ortho, 1, 1), 0xFFFFFFFFu);
}

// The columns (0..3) of row 1 that a blended draw covers, as a 4-character mask ("0110").
std::string covered_columns(const Outcome& o) {
    std::string mask;
    for (unsigned x = 0; x < 4; ++x) mask += pixel(o, x, 1) == 0xFF000000u ? '0' : '1';
    return mask;
}

// A quad over the left half of clip space (x in [-1, 0]) of format `fvf`, every vertex with the
// same `attributes` (blend weights, indices) after its position; lighting off, white.
std::string left_half_quad(const std::string& fvf, const Words& attributes) {
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {0.0f, 1.0f}, {-1.0f, -1.0f}, {0.0f, -1.0f}}) {
        w.f({x, y, 0.5f});
        w.words.insert(w.words.end(), attributes.words.begin(), attributes.words.end());
    }
    return "SetRenderState LIGHTING FALSE\nSetFVF " + fvf + "\nDrawPrimitiveUP TRIANGLESTRIP 2 " +
           std::to_string(4 * (3 + attributes.words.size())) + " " + w.blob() + "\n";
}

TEST(FixedFunctionDraw, VertexBlendingWithOneWeight) {
    // VERTEXBLEND 1WEIGHTS: p' = w p WORLD + (1 - w) p WORLD1. WORLD translates x by 2, WORLD1 is
    // the identity, w = 0.25: x + 0.5, so the quad spans [-0.5, 0.5]: pixel columns 1 and 2
    // (centres at -0.75, -0.25, 0.25, 0.75). The weights the other way round (0.75 to WORLD)
    // would give [0.5, 1.5], column 3; no blending, WORLD alone, nothing on screen.
    const std::string translate2 = "SetTransform WORLD f32[ 1 0 0 0  0 1 0 0  0 0 1 0  2 0 0 1 ]\n";
    const std::string quad = left_half_quad("{ XYZB1 }", Words().f({0.25f}));
    const Outcome blended = replay_text(translate2 + "SetRenderState VERTEXBLEND 1\n" + quad);
    expect_no_diagnostics(blended.result);
    EXPECT_EQ(covered_columns(blended), "0110");
    const Outcome unblended = replay_text(translate2 + quad);
    expect_no_diagnostics(unblended.result);
    EXPECT_EQ(covered_columns(unblended), "0000");
}

TEST(FixedFunctionDraw, IndexedVertexBlending) {
    // INDEXEDVERTEXBLENDENABLE with one weight: the vertex's indices (5, 2) pick WORLDMATRIX(5)
    // (x + 2) for w = 0.25 and WORLDMATRIX(2) (identity) for 0.75: x + 0.5, columns 1 and 2 as in
    // VertexBlendingWithOneWeight. The indices are the bytes in memory order, for UBYTE4 and for
    // D3DCOLOR alike (a D3DCOLOR word 0x00000205 holds bytes 5, 2, 0, 0; read as (R, G, B) it
    // would give indices (0, 2, 5): WORLD, x - 2, for w: x - 0.5, column 0).
    const std::string state = "SetTransform WORLDMATRIX5 f32[ 1 0 0 0  0 1 0 0  0 0 1 0  2 0 0 1 ]\n"
                              "SetTransform WORLD f32[ 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1 ]\n"
                              "SetRenderState VERTEXBLEND 1\nSetRenderState INDEXEDVERTEXBLENDENABLE TRUE\n";
    for (const char* fvf : {"{ XYZB2 LASTBETA_UBYTE4 }", "{ XYZB2 LASTBETA_D3DCOLOR }"}) {
        const Outcome o = replay_text(state + left_half_quad(fvf, Words().f({0.25f}).color(0x00000205u)));
        expect_no_diagnostics(o.result);
        EXPECT_EQ(covered_columns(o), "0110") << fvf;
    }
}

TEST(FixedFunctionDraw, BlendedNormalsUseEachMatrixsInverseTranspose) {
    // Directional light along +z (L = (0, 0, -1)), white, material diffuse 1; n = (0, 0, -1).
    // WORLD identity, WORLD1 scales z by 2, whose inverse transpose scales it by 0.5; w = 0.5:
    // N = 0.5 (0, 0, -1) + 0.5 (0, 0, -0.5) = (0, 0, -0.75), N.L = 0.75 -> 191.25 -> 0xBF (WORLD1
    // itself would give (0, 0, -1.5), 255). NORMALIZENORMALS: N = (0, 0, -1) -> 0xFF.
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}})
        w.f({x, y, 0.25f, 0.5f, 0.0f, 0.0f, -1.0f});
    const auto lit = [&](const char* normalize) {
        const Outcome o = replay_text(
            std::string("SetMaterial { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 0 } 0\n"
                        "SetLight 0 DIRECTIONAL { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 0 0 0 0 0 0 0\n"
                        "LightEnable 0 TRUE\nSetTransform WORLD1 f32[ 1 0 0 0  0 1 0 0  0 0 2 0  0 0 0 1 ]\n"
                        "SetRenderState VERTEXBLEND 1\nSetRenderState NORMALIZENORMALS ") +
            normalize + "\nSetFVF { XYZB1 NORMAL }\nDrawPrimitiveUP TRIANGLESTRIP 2 28 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return pixel(o, 1, 1);
    };
    EXPECT_EQ(lit("FALSE"), 0xFFBFBFBFu);
    EXPECT_EQ(lit("TRUE"), 0xFFFFFFFFu);
}

TEST(FixedFunctionDraw, TweeningBlendsTheTwoPositions) {
    // VERTEXBLEND TWEENING (D3D9 "Vertex Tweening"): POSITION0 (1 - TWEENFACTOR) + POSITION1
    // TWEENFACTOR. POSITION0 spans x in [-1, 0], POSITION1 the same quad moved by 2, [1, 2];
    // TWEENFACTOR 0.25: x + 0.5, [-0.5, 0.5], columns 1 and 2 (centres -0.75, -0.25, 0.25, 0.75).
    // 0: POSITION0, columns 0 and 1; 1: POSITION1, off screen. The factor the other way round
    // (0.75 to POSITION1) would give [0.5, 1.5], column 3.
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {0.0f, 1.0f}, {-1.0f, -1.0f}, {0.0f, -1.0f}})
        w.f({x, y, 0.5f, x + 2.0f, y, 0.5f});
    const auto tweened = [&](const char* factor) {
        const Outcome o = replay_text(
            std::string("CreateVertexDeclaration tween { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 FLOAT3 DEFAULT POSITION 1 }\n"
                        "SetVertexDeclaration tween\nSetRenderState LIGHTING FALSE\n"
                        "SetRenderState VERTEXBLEND 255\nSetRenderState TWEENFACTOR ") +
            factor + "\nDrawPrimitiveUP TRIANGLESTRIP 2 24 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return covered_columns(o);
    };
    EXPECT_EQ(tweened("0.25"), "0110");
    EXPECT_EQ(tweened("0"), "1100");
    EXPECT_EQ(tweened("1"), "0000");
}

TEST(FixedFunctionDraw, TweeningBlendsTheTwoNormals) {
    // Directional light along +z (L = (0, 0, -1)), white, material diffuse 1. NORMAL0 (0, 0, -1),
    // NORMAL1 (1, 0, 0), TWEENFACTOR 0.25: N = (0.25, 0, -0.75), N.L = 0.75 -> 191.25 -> 0xBF
    // (the factor the other way round: 0.25 -> 0x40). NORMALIZENORMALS: 0.75 / sqrt(0.625) =
    // 0.94868 -> 241.91 -> 0xF2. Without NORMAL1 in the declaration NORMAL0 is used as it is: 0xFF.
    const std::string light =
        "SetMaterial { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 0 } 0\n"
        "SetLight 0 DIRECTIONAL { 1 1 1 1 } { 0 0 0 0 } { 0 0 0 0 } { 0 0 0 } { 0 0 1 } 0 0 0 0 0 0 0\n"
        "LightEnable 0 TRUE\nSetRenderState VERTEXBLEND 255\nSetRenderState TWEENFACTOR 0.25\n"
        "CreateVertexDeclaration both { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 FLOAT3 DEFAULT NORMAL 0 }"
        " { 0 24 FLOAT3 DEFAULT POSITION 1 } { 0 36 FLOAT3 DEFAULT NORMAL 1 }\n"
        "CreateVertexDeclaration one { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 FLOAT3 DEFAULT NORMAL 0 }"
        " { 0 24 FLOAT3 DEFAULT POSITION 1 }\n";
    Words w;
    for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}})
        w.f({x, y, 0.25f, 0.0f, 0.0f, -1.0f, x, y, 0.25f, 1.0f, 0.0f, 0.0f});
    const auto lit = [&](const char* declaration, const char* normalize) {
        const Outcome o = replay_text(light + "SetVertexDeclaration " + declaration +
                                      "\nSetRenderState NORMALIZENORMALS " + normalize +
                                      "\nDrawPrimitiveUP TRIANGLESTRIP 2 48 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return pixel(o, 1, 1);
    };
    EXPECT_EQ(lit("both", "FALSE"), 0xFFBFBFBFu);
    EXPECT_EQ(lit("both", "TRUE"), 0xFFF2F2F2u);
    EXPECT_EQ(lit("one", "FALSE"), 0xFFFFFFFFu);
}

// The 4x4 target as 16 characters, '1' where a pixel is not the clear colour.
std::string coverage(const Outcome& o) {
    std::string mask;
    for (unsigned y = 0; y < 4; ++y)
        for (unsigned x = 0; x < 4; ++x) mask += pixel(o, x, y) == 0xFF000000u ? '0' : '1';
    return mask;
}

TEST(FixedFunctionDraw, PointSizeFromTheVertex) {
    // XYZRHW | PSIZE | DIFFUSE point at pixel centre (2, 2), PSIZE 3: the square [0.5, 3.5]^2
    // holds the centres 1..3 in both directions. Without PSIZE, POINTSIZE (1): pixel (2, 2) only.
    Words with;
    with.f({2, 2, 0.5f, 1, 3}).color(0xFFFFFFFFu);
    const Outcome sized = replay_text("SetFVF { XYZRHW PSIZE DIFFUSE }\nDrawPrimitiveUP POINTLIST 1 24 " + with.blob() + "\n");
    expect_no_diagnostics(sized.result);
    EXPECT_EQ(coverage(sized), "0000" "0111" "0111" "0111");
    Words without;
    without.f({2, 2, 0.5f, 1}).color(0xFFFFFFFFu);
    const Outcome plain = replay_text("SetFVF { XYZRHW DIFFUSE }\nDrawPrimitiveUP POINTLIST 1 20 " + without.blob() + "\n");
    expect_no_diagnostics(plain.result);
    EXPECT_EQ(coverage(plain), "0000" "0000" "0010" "0000");
}

TEST(FixedFunctionDraw, PointScaleWithTheDistanceFromTheEye) {
    // An XYZ point at (0.5, 0, 0.5) (identity transforms: pixel centre (3, 2)), POINTSIZE 0.53033,
    // POINTSCALEENABLE with A = B = 0, C = 1: De = |(0.5, 0, 0.5)| = 0.70711, size = Vh Si
    // sqrt(1 / (C De^2)) = 4 * 0.53033 / 0.70711 = 3: [1.5, 4.5] x [0.5, 3.5], columns 2..3, rows
    // 1..3. (De = z, 0.5, would give 4.24: columns 1..3, rows 0..3.) Unscaled, 0.53033 is raised
    // to POINTSIZE_MIN (1): pixel (3, 2) only.
    Words w;
    w.f({0.5f, 0, 0.5f});
    const std::string draw = "SetRenderState LIGHTING FALSE\nSetRenderState POINTSIZE 0.53033\n"
                             "SetRenderState POINTSCALE_A 0\nSetRenderState POINTSCALE_B 0\n"
                             "SetRenderState POINTSCALE_C 1\nSetFVF XYZ\nDrawPrimitiveUP POINTLIST 1 12 " + w.blob() + "\n";
    const Outcome scaled = replay_text("SetRenderState POINTSCALEENABLE TRUE\n" + draw);
    expect_no_diagnostics(scaled.result);
    EXPECT_EQ(coverage(scaled), "0000" "0011" "0011" "0011");
    const Outcome unscaled = replay_text(draw);
    expect_no_diagnostics(unscaled.result);
    EXPECT_EQ(coverage(unscaled), "0000" "0000" "0001" "0000");
}

TEST(FixedFunctionDraw, PointSpriteTextureCoordinates) {
    // POINTSPRITEENABLE: t0 runs from (0, 0) at the sprite's top-left to (1, 1) at its
    // bottom-right, so a 4-pixel sprite over the whole target shows a 2x2 texture's quadrants
    // (POINT filtered): red, green / blue, white; the vertex has no texture coordinates.
    Words w;
    w.f({2, 2, 0.5f, 1, 4}).color(0xFFFFFFFFu);
    const Outcome o = replay_text(
        "CreateTexture tex 2 2 1 A8R8G8B8\n"
        "LockRect tex 0 u8[ 0 0 255 255  0 255 0 255  255 0 0 255  255 255 255 255 ]\nSetTexture 0 tex\n"
        "SetSamplerState 0 MINFILTER POINT\nSetSamplerState 0 MAGFILTER POINT\n"
        "SetRenderState POINTSPRITEENABLE TRUE\nSetTextureStageState 0 COLOROP SELECTARG1\n"
        "SetFVF { XYZRHW PSIZE DIFFUSE }\nDrawPrimitiveUP POINTLIST 1 24 " + w.blob() + "\n");
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 0, 0), 0xFFFF0000u);
    EXPECT_EQ(pixel(o, 3, 0), 0xFF00FF00u);
    EXPECT_EQ(pixel(o, 0, 3), 0xFF0000FFu);
    EXPECT_EQ(pixel(o, 3, 3), 0xFFFFFFFFu);
}

TEST(FixedFunctionDraw, BumpEnvironmentMapPerturbsTheNextStage) {
    // Stage 0 BUMPENVMAP with a 1x1 A8R8G8B8 "du dv" texture: R = 128 (du = 0.50196), G = 64
    // (dv = 0.25098), B = 128 (luminance 0.50196); stage 1 SELECTARG1 TEXTURE on the 4x1 stripes
    // (red, green, blue, white) at u = 0.1 from TEX2's second set. BUMPENVMAT00 = 0.5, BUMPENVMAT10
    // = 1 (M01 = M11 = 0): u' = 0.1 + 0.5 du + 1 dv = 0.1 + 0.25098 + 0.25098 = 0.60196 -> blue
    // (without dv, 0.35: green; no bump: red). BUMPENVMAPLUMINANCE, LSCALE 1, LOFFSET 0: blue times
    // 0.50196 -> 128 (0x80); alpha keeps stage 0's (SELECTARG1 TEXTURE, 0xFF).
    Words w;
    for (auto [x, y] : {std::pair{-0.5f, -0.5f}, {3.5f, -0.5f}, {-0.5f, 3.5f}, {3.5f, 3.5f}})
        w.f({x, y, 0.5f, 1.0f, 0.5f, 0.5f, 0.1f, 0.5f});
    const auto bumped = [&](const char* op) {
        const Outcome o = replay_text(
            "CreateTexture dudv 1 1 1 A8R8G8B8\nLockRect dudv 0 u8[ 128 64 128 255 ]\nSetTexture 0 dudv\n"
            "CreateTexture stripes 4 1 1 A8R8G8B8\n"
            "LockRect stripes 0 u8[ 0 0 255 255  0 255 0 255  255 0 0 255  255 255 255 255 ]\nSetTexture 1 stripes\n"
            "SetSamplerState 1 MINFILTER POINT\nSetSamplerState 1 MAGFILTER POINT\n"
            "SetTextureStageState 0 COLOROP " + std::string(op) + "\n"
            "SetTextureStageState 0 BUMPENVMAT00 0.5\nSetTextureStageState 0 BUMPENVMAT10 1\n"
            "SetTextureStageState 0 BUMPENVLSCALE 1\nSetTextureStageState 0 BUMPENVLOFFSET 0\n"
            "SetTextureStageState 1 COLOROP SELECTARG1\n"
            "SetFVF { XYZRHW TEX2 }\nDrawPrimitiveUP TRIANGLESTRIP 2 32 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return pixel(o, 1, 2);
    };
    EXPECT_EQ(bumped("BUMPENVMAP"), 0xFF0000FFu);
    EXPECT_EQ(bumped("BUMPENVMAPLUMINANCE"), 0xFF000080u);
    EXPECT_EQ(bumped("SELECTARG2"), 0xFFFF0000u);  // stage 0 not a bump stage: u = 0.1, red
}

TEST(FixedFunctionDraw, PremodulateModulatesWithTheNextStagesTexture) {
    // Stage 0 PREMODULATE (colour and alpha) of DIFFUSE (0x80, 0x40, 0xFF), alpha 0x80: its result
    // is ARG1, which stage 1 multiplies by its texture, (0xFF, 0x80, 0x40), alpha 0x80, before its
    // operations (SELECTARG2 CURRENT, which does not read TEXTURE itself): R 128 * 255/255 = 128
    // (0x80); G 64 * 128/255 = 32.125 -> 0x20; B 255 * 64/255 = 64 (0x40); A 128 * 128/255 =
    // 64.25 -> 0x40. Stage 1 disabled (no next stage), no texture on stage 1 (TEXTURE is 1) or
    // SELECTARG1 instead: the diffuse colour. ALPHAOP SELECTARG1: the alpha stays 0x80.
    Words w;
    for (auto [x, y] : {std::pair{-0.5f, -0.5f}, {3.5f, -0.5f}, {-0.5f, 3.5f}, {3.5f, 3.5f}})
        w.f({x, y, 0.5f, 1.0f}).color(0x808040FFu).f({0.5f, 0.5f});
    const auto drawn = [&](const std::string& state) {
        const Outcome o = replay_text(
            "CreateTexture tex 1 1 1 A8R8G8B8\nLockRect tex 0 u8[ 64 128 255 128 ]\n"
            "SetTextureStageState 0 COLOROP PREMODULATE\nSetTextureStageState 0 COLORARG1 DIFFUSE\n"
            "SetTextureStageState 0 ALPHAOP PREMODULATE\nSetTextureStageState 0 ALPHAARG1 DIFFUSE\n"
            "SetTextureStageState 1 COLOROP SELECTARG2\nSetTextureStageState 1 COLORARG2 CURRENT\n"
            "SetTextureStageState 1 ALPHAOP SELECTARG2\nSetTextureStageState 1 ALPHAARG2 CURRENT\n"
            "SetTextureStageState 1 TEXCOORDINDEX 0\n" + state +
            "SetFVF { XYZRHW DIFFUSE TEX1 }\nDrawPrimitiveUP TRIANGLESTRIP 2 28 " + w.blob() + "\n");
        expect_no_diagnostics(o.result);
        return pixel(o, 2, 1);
    };
    EXPECT_EQ(drawn("SetTexture 1 tex\n"), 0x40802040u);
    EXPECT_EQ(drawn("SetTexture 1 tex\nSetTextureStageState 0 ALPHAOP SELECTARG1\n"), 0x80802040u);
    EXPECT_EQ(drawn("SetTexture 1 tex\nSetTextureStageState 1 COLOROP DISABLE\n"), 0x808040FFu);
    EXPECT_EQ(drawn(""), 0x808040FFu);
    EXPECT_EQ(drawn("SetTexture 1 tex\nSetTextureStageState 0 COLOROP SELECTARG1\n"
                    "SetTextureStageState 0 ALPHAOP SELECTARG1\n"),
              0x808040FFu);
    // RESULTARG TEMP: the stage's result, TEMP, is what stage 1's texture multiplies.
    EXPECT_EQ(drawn("SetTexture 1 tex\nSetTextureStageState 0 RESULTARG TEMP\n"
                    "SetTextureStageState 1 COLORARG2 TEMP\nSetTextureStageState 1 ALPHAARG2 TEMP\n"),
              0x40802040u);
}

// Stage 0 = OP(arg1 TFACTOR, arg2 DIFFUSE) over the whole target; the colour at pixel (0, 0).
uint32_t stage0(const std::string& color_op, uint32_t tfactor, uint32_t diffuse, const std::string& extra = "") {
    const Outcome o = replay_text("SetRenderState TEXTUREFACTOR " + std::to_string(tfactor) +
                                  "\nSetTextureStageState 0 COLOROP " + color_op +
                                  "\nSetTextureStageState 0 COLORARG1 TFACTOR\nSetTextureStageState 0 COLORARG2 DIFFUSE\n" +
                                  extra + rhw_quad(-0.5f, -0.5f, 3.5f, 3.5f, diffuse));
    expect_no_diagnostics(o.result);
    return pixel(o, 0, 0);
}

TEST(FixedFunctionDraw, TextureStageOperations) {
    // TFACTOR (0x60, 0xC0, 0x20) = (96, 192, 32)/255, diffuse (0xC0, 0xC0, 0x80) = (192, 192, 128)/255.
    // Alpha: stage 0's default ALPHAOP SELECTARG1 of TEXTURE, no texture: opaque white, 0xFF.
    const uint32_t tf = 0xFF60C020u, dif = 0xFFC0C080u;
    // MODULATE2X: 2 a1 a2: R 2*96*192/255^2 = 0.56693 -> 144.57 -> 145 (0x91); G 1.134 -> clamped 255;
    // B 2*32*128/255^2 = 0.12598 -> 32.12 -> 32.
    EXPECT_EQ(stage0("MODULATE2X", tf, dif), 0xFF91FF20u);
    // MODULATE: R 96*192/255 = 72.28 -> 72 (0x48); G 192*192/255 = 144.56 -> 145; B 32*128/255 = 16.06 -> 16.
    EXPECT_EQ(stage0("MODULATE", tf, dif), 0xFF489110u);
    // MODULATE4X: R 289.1 -> 255; G -> 255; B 64.25 -> 64.
    EXPECT_EQ(stage0("MODULATE4X", tf, dif), 0xFFFFFF40u);
    // ADD: R 288 -> 255; G 384 -> 255; B 160 (0xA0).
    EXPECT_EQ(stage0("ADD", tf, dif), 0xFFFFFFA0u);
    // SUBTRACT a1 - a2: R -96 -> 0; G 0; B -96 -> 0.
    EXPECT_EQ(stage0("SUBTRACT", tf, dif), 0xFF000000u);
    // ADDSIGNED a1 + a2 - 0.5: R (288 - 127.5) = 160.5 -> 161 (0xA1)? 96+192 = 288/255 = 1.12941 - 0.5
    // = 0.62941 -> 160.5 -> round half to even or up: the float is 160.50000x, so 161 (0xA1); G
    // 384/255 - 0.5 = 1.00588 -> 255; B 160/255 - 0.5 = 0.12745 -> 32.5 -> the float 32.49999 -> 32.
    const uint32_t signed_sum = stage0("ADDSIGNED", tf, dif);
    EXPECT_EQ(signed_sum >> 8 & 0xFF, 0xFFu);
    EXPECT_NEAR(static_cast<int>(signed_sum >> 16 & 0xFF), 160.5, 0.5);
    EXPECT_NEAR(static_cast<int>(signed_sum & 0xFF), 32.5, 0.5);
    // SELECTARG2: the diffuse colour.
    EXPECT_EQ(stage0("SELECTARG2", tf, dif), 0xFFC0C080u);
    // ADDSMOOTH a1 + a2 - a1 a2: R (96 + 192 - 72.28) = 215.72 -> 216 (0xD8); G 255 (384 - 144.56
    // = 239.44 -> 239 (0xEF)); B 32 + 128 - 16.06 = 143.94 -> 144 (0x90).
    EXPECT_EQ(stage0("ADDSMOOTH", tf, dif), 0xFFD8EF90u);
    // BLENDFACTORALPHA with TFACTOR alpha 0x40 (64/255 = 0.25098): a1 0.25098 + a2 0.74902:
    // R 96*0.25098 + 192*0.74902 = 167.91 -> 168 (0xA8); G 192; B 32*.25098 + 128*.74902 = 103.91 -> 104 (0x68).
    EXPECT_EQ(stage0("BLENDFACTORALPHA", 0x4060C020u, dif), 0xFFA8C068u);
}

TEST(FixedFunctionDraw, ArgumentModifiers) {
    // COLORARG1 { TFACTOR COMPLEMENT } with SELECTARG1: 1 - (96, 192, 32)/255 = (159, 63, 223).
    EXPECT_EQ(stage0("SELECTARG1", 0xFF60C020u, 0xFFFFFFFFu, "SetTextureStageState 0 COLORARG1 { TFACTOR COMPLEMENT }\n"),
              0xFF9F3FDFu);
    // { TFACTOR ALPHAREPLICATE }: TFACTOR's alpha 0x40 in every colour channel.
    EXPECT_EQ(stage0("SELECTARG1", 0x4060C020u, 0xFFFFFFFFu,
                     "SetTextureStageState 0 COLORARG1 { TFACTOR ALPHAREPLICATE }\n"),
              0xFF404040u);
}

TEST(FixedFunctionDraw, SecondStageAndTempResult) {
    // Stage 0 writes TFACTOR into TEMP (RESULTARG TEMP), so CURRENT stays the diffuse colour;
    // stage 1 MODULATEs TEMP and CURRENT: (0x80/255) * (0xFF, 0x80, 0x00)/255 = (128, 64.25, 0) -> (0x80, 0x40, 0).
    const Outcome o = replay_text(
        "SetRenderState TEXTUREFACTOR 0xFF808080\n"
        "SetTextureStageState 0 COLOROP SELECTARG1\nSetTextureStageState 0 COLORARG1 TFACTOR\n"
        "SetTextureStageState 0 RESULTARG TEMP\n"
        "SetTextureStageState 1 COLOROP MODULATE\nSetTextureStageState 1 COLORARG1 TEMP\n"
        "SetTextureStageState 1 COLORARG2 CURRENT\n" +
        rhw_quad(-0.5f, -0.5f, 3.5f, 3.5f, 0xFFFF8000u));
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 1, 1), 0xFF804000u);
}

TEST(FixedFunctionDraw, SpecularIsAddedWhenEnabled) {
    // XYZRHW | DIFFUSE | SPECULAR: diffuse (0x40, 0x40, 0x40) + specular (0x20, 0xF0, 0) =
    // (0x60, 0xFF clamped, 0x40) with SPECULARENABLE; the diffuse alone without.
    Words w;
    for (auto [x, y] : {std::pair{-0.5f, -0.5f}, {3.5f, -0.5f}, {-0.5f, 3.5f}, {3.5f, 3.5f}})
        w.f({x, y, 0.5f, 1.0f}).color(0xFF404040u).color(0x0020F000u);
    const std::string draw = "SetFVF { XYZRHW DIFFUSE SPECULAR }\nDrawPrimitiveUP TRIANGLESTRIP 2 24 " + w.blob() + "\n";
    const Outcome on = replay_text("SetRenderState SPECULARENABLE TRUE\n" + draw);
    expect_no_diagnostics(on.result);
    EXPECT_EQ(pixel(on, 2, 2), 0xFF60FF40u);
    const Outcome off = replay_text(draw);
    expect_no_diagnostics(off.result);
    EXPECT_EQ(pixel(off, 2, 2), 0xFF404040u);
}

TEST(FixedFunctionDraw, TextureSelectedByTheStage) {
    // A 1x1 A8R8G8B8 texture (B G R A bytes 0x10 0x20 0x30 0x80): SELECTARG1 TEXTURE shows it,
    // alpha too (the default ALPHAOP SELECTARG1 TEXTURE); the vertex carries TEX1 coordinates.
    Words w;
    for (auto [x, y] : {std::pair{-0.5f, -0.5f}, {3.5f, -0.5f}, {-0.5f, 3.5f}, {3.5f, 3.5f}})
        w.f({x, y, 0.5f, 1.0f, 0.5f, 0.5f});
    const Outcome o = replay_text(
        "CreateTexture tex 1 1 1 A8R8G8B8\nLockRect tex 0 u8[ 16 32 48 128 ]\nSetTexture 0 tex\n"
        "SetTextureStageState 0 COLOROP SELECTARG1\n"
        "SetFVF { XYZRHW TEX1 }\nDrawPrimitiveUP TRIANGLESTRIP 2 24 " + w.blob() + "\n");
    expect_no_diagnostics(o.result);
    EXPECT_EQ(pixel(o, 3, 0), 0x80302010u);
}

TEST(FixedFunctionDraw, ProgramsAreCachedByState) {
    // The same state twice: the second draw builds no pipeline; a new TFACTOR value is a
    // constant, not a new program.
    const std::string quad = rhw_quad(-0.5f, -0.5f, 3.5f, 3.5f, 0xFF808080u);
    const Outcome once = replay_text(quad);
    const Outcome twice = replay_text(quad + "SetRenderState TEXTUREFACTOR 0xFF102030\n" + quad);
    expect_no_diagnostics(twice.result);
    EXPECT_EQ(twice.statistics.pipelines_built, once.statistics.pipelines_built);
    EXPECT_EQ(twice.statistics.draws, 2u);
}

TEST(FixedFunctionDraw, BadStageValuesAreRefused) {
    // The stream parser refuses unknown names; values set through the API reach the generator,
    // which refuses them with a message rather than building a program.
    const std::array<std::optional<isa::TextureType>, kMaxTextureStages> none{};
    const auto refusal = [&](unsigned stage, uint32_t type, uint32_t value) {
        FixedFunctionState ff;
        ff.stages[1][kTssColorOp] = kTopModulate;
        EXPECT_FALSE(ff.set_texture_stage_state(stage, type, value));
        const auto generated = fixed_function_pixel_program(ff, RenderState{}, none);
        EXPECT_FALSE(generated.program);
        return generated.error;
    };
    EXPECT_EQ(refusal(0, kTssColorOp, 99), "texture stage 0 COLOROP 99 is not a D3DTEXTUREOP");
    EXPECT_EQ(refusal(1, kTssAlphaOp, 27), "texture stage 1 ALPHAOP 27 is not a D3DTEXTUREOP");
    EXPECT_EQ(refusal(1, kTssAlphaOp, 22), "texture stage 1 ALPHAOP BUMPENVMAP/BUMPENVMAPLUMINANCE is a colour operation only");
    EXPECT_EQ(refusal(0, kTssColorArg1, 7), "texture stage 0: 7 is not a D3DTA argument");
    EXPECT_EQ(refusal(0, kTssResultArg, kTaTexture), "texture stage 0: RESULTARG must be CURRENT or TEMP");
    // The default state builds.
    EXPECT_TRUE(fixed_function_pixel_program(FixedFunctionState{}, RenderState{}, none).program);
}

TEST(FixedFunctionStateBlocks, TypesCaptureTheirFixedFunctionStates) {
    // D3D9's lists: PIXELSTATE holds every texture stage state; VERTEXSTATE the stage states
    // TEXCOORDINDEX and TEXTURETRANSFORMFLAGS, the lights and the FVF; ALL adds the transforms
    // and the material.
    Device device;
    const Matrix4 scale2{2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    Material red;
    red.diffuse = {1, 0, 0, 1};
    Light point;
    point.type = LightType::Point;
    point.range = 10;
    const auto set_all = [&](bool changed) {
        ASSERT_TRUE(device.set_texture_stage_state(0, kTssColorOp, changed ? 5u : kTopModulate));  // MODULATE2X
        ASSERT_TRUE(device.set_texture_stage_state(0, kTssTexCoordIndex, changed ? 3u : 0u));
        ASSERT_TRUE(device.set_transform(kTransformView, changed ? scale2 : identity_matrix()));
        ASSERT_TRUE(device.set_material(changed ? red : Material{}));
        ASSERT_TRUE(device.set_light(2, changed ? point : Light{}));
    };
    set_all(true);
    for (const char* name : {"all", "pixel", "vertex"})
        ASSERT_TRUE(device.create_state_block(name, std::string(name) == "all"     ? StateBlockType::All
                                                    : std::string(name) == "pixel" ? StateBlockType::PixelState
                                                                                   : StateBlockType::VertexState));
    const auto& ff = device.fixed_function();
    struct Expect {
        const char* block;
        bool color_op, tci, view, material, light;
    };
    for (const Expect& e : {Expect{"all", true, true, true, true, true}, Expect{"pixel", true, true, false, false, false},
                            Expect{"vertex", false, true, false, false, true}}) {
        set_all(false);
        ASSERT_TRUE(device.apply_state_block(e.block));
        EXPECT_EQ(ff.stages[0][kTssColorOp], e.color_op ? 5u : kTopModulate) << e.block;
        EXPECT_EQ(ff.stages[0][kTssTexCoordIndex], e.tci ? 3u : 0u) << e.block;
        EXPECT_EQ(ff.view, e.view ? scale2 : identity_matrix()) << e.block;
        EXPECT_EQ(ff.material, e.material ? red : Material{}) << e.block;
        EXPECT_EQ(ff.lights.at(2), e.light ? point : Light{}) << e.block;
    }
    // A recorded block holds only what was set while recording.
    set_all(false);
    ASSERT_TRUE(device.begin_state_block());
    ASSERT_TRUE(device.set_texture_stage_state(1, kTssColorArg1, kTaDiffuse));
    ASSERT_TRUE(device.set_transform(kTransformProjection, scale2));
    ASSERT_TRUE(device.end_state_block("recorded"));
    EXPECT_EQ(ff.stages[1][kTssColorArg1], kTaTexture);  // EndStateBlock gives the state back
    EXPECT_EQ(ff.projection, identity_matrix());
    set_all(true);
    ASSERT_TRUE(device.apply_state_block("recorded"));
    EXPECT_EQ(ff.stages[1][kTssColorArg1], kTaDiffuse);
    EXPECT_EQ(ff.projection, scale2);
    EXPECT_EQ(ff.stages[0][kTssColorOp], 5u);  // not recorded: left as set
    EXPECT_EQ(ff.view, scale2);
}

}  // namespace
}  // namespace sm2::runtime
