// Draws whose transparent batches are not shaded (draw.cpp's outside_cull): a volume drawn
// source-over, addressed BORDER with a transparent BORDERCOLOR, its texture coordinate running
// beyond the volume. Where the lookups of a batch all lie outside, the batch writes nothing, so
// the draw need not run its shader; against the reference paths (per-lane sampler and merger,
// the interpreter, which shade every batch) the image, the depth and the counts are the same.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace sm2::runtime {
namespace {

struct Drawn {
    std::vector<uint8_t> pixels;  // the back buffer's bytes (B G R A)
    std::vector<uint32_t> depth;  // stored depth per pixel (none without a depth buffer)
    DrawStatistics statistics;
};

constexpr uint32_t kWidth = 32, kHeight = 8;

// A 32x8 target; a 4x4x4 A8R8G8B8 volume, every texel (0x20, 0x40, 0x60) with alpha 0x80;
// u = 2 x + 0.5 over the screen's x in [-1, 1], v = w = 0.5. The volume's box in u is
// [-1/4, 5/4) (a texel of margin): columns 0-9 and 22-31 look it up outside. `depth`: with a D24S8 buffer cleared to 1, ZFUNC ALWAYS.
// `lookup`: the pixel shader's instructions.
Drawn draw(const std::string& states, bool depth, bool reference,
           const std::string& lookup = "texld r0, t0, s0\nmov oC0, r0\n") {
    std::string words;
    for (int i = 0; i < 64; ++i) words += " 2151694368";  // 0x80402060: A 0x80, R 0x40, G 0x20, B 0x60
    const std::string text = "sm2cs 1\n"
                             "CreateDevice 32 8 A8R8G8B8" + std::string(depth ? " D24S8" : "") + "\n"
                             "CreateVolumeTexture vol 4 4 4 1 A8R8G8B8\n"
                             "LockBox vol 0 u32[" + words + " ]\n"
                             "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
                             "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nmad oT0, v0, c0, c1\nEND\n"
                             "CreatePixelShader ps asm<<END\nps_2_0\ndcl t0.xyz\ndcl_volume s0\n" + lookup + "END\n"
                             "SetVertexDeclaration decl\n"
                             "SetVertexShader vs\n"
                             "SetPixelShader ps\n"
                             "SetVertexShaderConstantF 0 f32[ 2 0 0 0   0.5 0.5 0.5 1 ]\n"
                             "SetTexture 0 vol\n"
                             "SetSamplerState 0 ADDRESSU BORDER\n"
                             "SetSamplerState 0 BORDERCOLOR 0x00FF0000\n"
                             "SetSamplerState 0 MAGFILTER LINEAR\n"
                             "SetSamplerState 0 MINFILTER LINEAR\n"
                             "SetRenderState CULLMODE NONE\n"
                             "SetRenderState ALPHABLENDENABLE TRUE\n"
                             "SetRenderState SRCBLEND SRCALPHA\n"
                             "SetRenderState DESTBLEND INVSRCALPHA\n"
                             "SetRenderState ZFUNC ALWAYS\n" +
                             states +
                             "Clear { TARGET" + std::string(depth ? " ZBUFFER" : "") + " } 0xFF000080 1 0\n"
                             "BeginScene\n"
                             "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
                             "EndScene\n"
                             "Present\n";
    cs::TextOptions text_options;
    text_options.file_name = "outside.sm2cs";
    auto parsed = cs::parse_text(text, text_options);
    EXPECT_TRUE(parsed.ok()) << (parsed.error ? parsed.error->to_string() : "");
    Drawn out;
    if (!parsed.ok()) return out;
    DeviceOptions options;
    options.threads = reference ? 1 : 2;
    options.reference_paths = reference;
    options.engine = reference ? DeviceOptions::Engine::Interpreter : DeviceOptions::Engine::Jit;
    Device device(options);
    ReplayOptions replay_options;
    replay_options.file_name = "outside.sm2cs";
    replay_options.assembler = stream_assembler();
    const ReplayResult result = replay(device, *parsed.stream, replay_options);
    for (const auto& d : result.diagnostics) ADD_FAILURE() << d.to_string();
    const Surface* back = device.surface("backbuffer");
    out.pixels.assign(reinterpret_cast<const uint8_t*>(back->bytes().data()),
                      reinterpret_cast<const uint8_t*>(back->bytes().data()) + back->bytes().size());
    if (const DepthStencilSurface* ds = device.depth_stencil("autodepth"))
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) out.depth.push_back(ds->stored_depth(x, y));
    out.statistics = device.statistics();
    return out;
}

void expect_same_as_reference(const Drawn& drawn, const Drawn& reference) {
    EXPECT_TRUE(drawn.pixels == reference.pixels);
    EXPECT_TRUE(drawn.depth == reference.depth);
    EXPECT_EQ(drawn.statistics.pixels_rasterized, reference.statistics.pixels_rasterized);
    EXPECT_EQ(drawn.statistics.pixels_shaded, reference.statistics.pixels_shaded);
    EXPECT_EQ(drawn.statistics.pixels_killed, reference.statistics.pixels_killed);
    EXPECT_EQ(drawn.statistics.pixels_written, reference.statistics.pixels_written);
    EXPECT_EQ(reference.statistics.pixels_outside_texture, 0u);  // the reference shades every batch
}

// The back buffer's pixel (x, y) as B G R A.
std::vector<uint8_t> pixel(const Drawn& d, uint32_t x, uint32_t y) {
    const size_t at = (static_cast<size_t>(y) * kWidth + x) * 4;
    return {d.pixels.begin() + static_cast<std::ptrdiff_t>(at), d.pixels.begin() + static_cast<std::ptrdiff_t>(at + 4)};
}

// Early depth (no alpha test, no texkill): the depth test runs and writes before the shader, so
// the batches outside are not shaded. Which batches those are depends on how the rasterizer
// groups each triangle's quads by four; at most the 20 columns outside, at least half of them.
// Their pixels keep the clear colour (alpha +0 blends to the destination), their depth is the
// quad's 0.5 as everywhere else.
TEST(OutsideCull, BatchesOutsideTheVolumeAreNotShadedAndChangeNothingElse) {
    const Drawn drawn = draw("", true, false), reference = draw("", true, true);
    EXPECT_GE(drawn.statistics.pixels_outside_texture, 80u);
    EXPECT_LE(drawn.statistics.pixels_outside_texture, 160u);
    expect_same_as_reference(drawn, reference);
    EXPECT_EQ(drawn.statistics.pixels_shaded, kWidth * kHeight);
    const std::vector<uint8_t> clear = {0x80, 0x00, 0x00, 0xFF};
    EXPECT_EQ(pixel(drawn, 0, 0), clear);
    EXPECT_EQ(pixel(drawn, 31, 7), clear);
    // Column 16 (u = 0.5625) blends the texel at alpha 0x80 / 255 over the clear colour.
    EXPECT_NE(pixel(drawn, 16, 3), clear);
    ASSERT_EQ(drawn.depth.size(), size_t{kWidth * kHeight});
    for (uint32_t i = 0; i < kWidth * kHeight; ++i) ASSERT_EQ(drawn.depth[i], drawn.depth[16]) << i;
    EXPECT_NE(drawn.depth[0], 0xFFFFFFu);  // not the clear's 1
}

// An alpha test runs after the shader, before the depth test: the depth written depends on the
// shader's alpha, so every batch is shaded. ALWAYS passes the transparent pixels: depth 0.5 is
// written on every column.
TEST(OutsideCull, AnAlphaTestShadesEveryBatch) {
    const std::string always = "SetRenderState ALPHATESTENABLE TRUE\nSetRenderState ALPHAFUNC ALWAYS\n";
    const Drawn drawn = draw(always, true, false), reference = draw(always, true, true);
    EXPECT_EQ(drawn.statistics.pixels_outside_texture, 0u);
    expect_same_as_reference(drawn, reference);
    for (uint32_t i = 0; i < kWidth * kHeight; ++i) ASSERT_EQ(drawn.depth[i], drawn.depth[16]) << i;
    EXPECT_NE(drawn.depth[0], 0xFFFFFFu);
    // Without a depth buffer, NEVER drops every pixel: none is written, which a batch skipped
    // before the test would have counted.
    const std::string never = "SetRenderState ALPHATESTENABLE TRUE\nSetRenderState ALPHAFUNC NEVER\n";
    const Drawn dropped = draw(never, false, false), dropped_reference = draw(never, false, true);
    EXPECT_EQ(dropped.statistics.pixels_outside_texture, 0u);
    EXPECT_EQ(dropped.statistics.pixels_written, 0u);
    expect_same_as_reference(dropped, dropped_reference);
}

// An opaque BORDERCOLOR, or a coordinate the shader computes: every batch is shaded.
TEST(OutsideCull, OnlyTransparentBordersAndInterpolatedCoordinates) {
    const Drawn opaque = draw("SetSamplerState 0 BORDERCOLOR 0x01FF0000\n", true, false);
    EXPECT_EQ(opaque.statistics.pixels_outside_texture, 0u);
    expect_same_as_reference(opaque, draw("SetSamplerState 0 BORDERCOLOR 0x01FF0000\n", true, true));
    // Without BORDER on u (CLAMP), no axis of the box: the clamped lookups read the volume.
    const Drawn clamped = draw("SetSamplerState 0 ADDRESSU CLAMP\n", true, false);
    EXPECT_EQ(clamped.statistics.pixels_outside_texture, 0u);
    EXPECT_NE(pixel(clamped, 0, 0), (std::vector<uint8_t>{0x80, 0x00, 0x00, 0xFF}));
    // The coordinate through a temporary: the draw does not follow it.
    const std::string copied = "mov r1.xyz, t0\nmov r1.w, c0.x\ntexld r0, r1, s0\nmov oC0, r0\n";
    const Drawn computed = draw("", true, false, copied);
    EXPECT_EQ(computed.statistics.pixels_outside_texture, 0u);
    expect_same_as_reference(computed, draw("", true, true, copied));
}

}  // namespace
}  // namespace sm2::runtime
