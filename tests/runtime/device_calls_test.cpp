// The device calls of issue 10 through the stream vocabulary: Clear with rectangles, ColorFill,
// StretchRect/UpdateSurface with rectangles, pools and their rules, partial LockRect,
// SetSoftwareVertexProcessing, SetNPatchMode and state blocks. Expected values are the D3D9
// rules worked by hand (each test says which), and the text form survives the binary form.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/device.h"
#include "sm2/runtime/device_inspection.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace sm2::runtime {
namespace {

class DeviceCalls : public ::testing::Test {
protected:
    // Replays "sm2cs 1\n" + body; the body's first line is line 2.
    std::vector<std::string> run(const std::string& body) {
        cs::TextOptions text;
        text.file_name = "t.sm2cs";
        auto parsed = cs::parse_text("sm2cs 1\n" + body, text);
        EXPECT_TRUE(parsed.ok()) << parsed.error->to_string();
        if (!parsed.ok()) return {"parse error"};
        ReplayOptions options;
        options.file_name = "t.sm2cs";
        options.assembler = stream_assembler();
        Replayer replayer(device, options);
        const ReplayResult r = replayer.replay(*parsed.stream);
        std::vector<std::string> messages;
        for (const auto& d : r.diagnostics) messages.push_back(d.to_string());
        return messages;
    }
    void ok(const std::string& body) {
        for (const auto& m : run(body)) ADD_FAILURE() << m;
    }
    // One call refused with a message containing `fragment`.
    void refused_with(const std::string& call, const std::string& fragment) {
        const auto messages = run(call + "\n");
        ASSERT_EQ(messages.size(), 1u) << call;
        EXPECT_NE(messages[0].find(fragment), std::string::npos) << messages[0];
        EXPECT_EQ(messages[0].rfind("t.sm2cs:2: D3DERR_INVALIDCALL: ", 0), 0u) << messages[0];
    }
    // The 32-bit texel at (x, y) of a named A8R8G8B8/X8R8G8B8 surface (level 0).
    uint32_t texel(const std::string& name, uint32_t x, uint32_t y) {
        const Surface* s = device.surface(name);
        EXPECT_NE(s, nullptr) << name;
        if (!s) return 0;
        uint32_t v = 0;
        std::memcpy(&v, s->bytes().data() + y * s->row_pitch() + x * 4, 4);
        return v;
    }

    Device device;
};

// IDirect3DDevice9::Clear: "Coordinates are clipped to the bounds of the viewport rectangle"; the
// scissor rectangle clips too when SCISSORTESTENABLE is TRUE (as the rectangle-less clear does).
TEST_F(DeviceCalls, ClearRectanglesAreClippedToTheViewportAndScissor) {
    ok("CreateDevice 8 8 A8R8G8B8\n"
       "Clear TARGET 0xFF000000 1 0\n"
       "SetViewport 1 1 6 6 0 1\n"
       "Clear TARGET 0xFFFF0000 1 0 { 0 0 3 3 } { 5 5 20 20 } { 4 0 3 8 }\n");
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const bool red = (x >= 1 && x < 3 && y >= 1 && y < 3) || (x >= 5 && x < 7 && y >= 5 && y < 7);
            EXPECT_EQ(texel("backbuffer", x, y), red ? 0xFFFF0000u : 0xFF000000u) << x << "," << y;
        }
    ok("SetScissorRect 0 0 2 8\n"
       "SetRenderState SCISSORTESTENABLE TRUE\n"
       "Clear TARGET 0xFF00FF00 1 0 { 0 0 8 8 }\n");
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const bool green = x == 1 && y >= 1 && y < 7;
            if (green) EXPECT_EQ(texel("backbuffer", x, y), 0xFF00FF00u) << x << "," << y;
            else EXPECT_NE(texel("backbuffer", x, y), 0xFF00FF00u) << x << "," << y;
        }
    refused_with("Clear TARGET 0xFF00FF00 1 0 { 0 0 8 }", "a rectangle has 4 numbers");
    refused_with("Clear TARGET 0xFF00FF00 1 0 7", "expected a rectangle");
}

// IDirect3DDevice9::ColorFill: a render target, a render-target texture or a DEFAULT-pool
// off-screen plain surface, whole or a rectangle inside it.
TEST_F(DeviceCalls, ColorFillWritesTheRectangleOfDefaultPoolSurfaces) {
    ok("CreateRenderTarget rt 4 4 A8R8G8B8\n"
       "CreateOffscreenPlainSurface plain 4 4 A8R8G8B8 DEFAULT\n"
       "ColorFill rt 0xFF0000FF\n"
       "ColorFill rt { 1 1 3 2 } 0xFFFFFFFF\n"
       "ColorFill plain { 0 0 1 1 } 0x80102030\n");
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x)
            EXPECT_EQ(texel("rt", x, y), (y == 1 && (x == 1 || x == 2)) ? 0xFFFFFFFFu : 0xFF0000FFu) << x << "," << y;
    EXPECT_EQ(texel("plain", 0, 0), 0x80102030u);
    EXPECT_EQ(texel("plain", 1, 0), 0u);
    ok("CreateTexture managed 4 4 1 A8R8G8B8\n"
       "CreateOffscreenPlainSurface sys 4 4 A8R8G8B8 SYSTEMMEM\n");
    refused_with("ColorFill managed 0xFFFFFFFF", "is not a render target or a DEFAULT-pool off-screen plain surface");
    refused_with("ColorFill sys 0xFFFFFFFF", "is not a render target or a DEFAULT-pool off-screen plain surface");
    refused_with("ColorFill rt { 2 2 5 3 } 0xFFFFFFFF", "rectangle {2 2 5 3} is not inside the 4x4 surface");
}

// IDirect3DDevice9::UpdateSurface: SYSTEMMEM source, DEFAULT destination, same format, no
// stretching; NULL source rectangle = the whole surface, NULL point = (0, 0).
TEST_F(DeviceCalls, UpdateSurfaceCopiesSystemMemoryRectanglesToDefaultPool) {
    ok("CreateTexture sys 4 2 1 A8R8G8B8 SYSTEMMEM\n"
       "CreateTexture def 4 2 1 A8R8G8B8 DEFAULT\n"
       "LockRect sys 0 u32[ 1 2 3 4 5 6 7 8 ]\n"
       "UpdateSurface sys 0 NULL def 0 NULL\n");
    for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(texel("def", i % 4, i / 4), i + 1);
    // Texels (1,0)..(2,1) of the source to (0,0) of the destination.
    ok("UpdateSurface sys 0 { 1 0 3 2 } def 0 { 0 0 }\n");
    EXPECT_EQ(texel("def", 0, 0), 2u);
    EXPECT_EQ(texel("def", 1, 0), 3u);
    EXPECT_EQ(texel("def", 0, 1), 6u);
    EXPECT_EQ(texel("def", 1, 1), 7u);
    EXPECT_EQ(texel("def", 2, 0), 3u);  // untouched
    ok("CreateTexture managed 4 2 1 A8R8G8B8\n"
       "CreateTexture small 2 2 1 A8R8G8B8 DEFAULT\n"
       "CreateTexture other 4 2 1 X8R8G8B8 DEFAULT\n");
    refused_with("UpdateSurface managed 0 NULL def 0 NULL", "the source 'managed' is in the MANAGED pool, not SYSTEMMEM");
    refused_with("UpdateSurface sys 0 NULL sys 0 NULL", "the destination 'sys' is in the SYSTEMMEM pool, not DEFAULT");
    refused_with("UpdateSurface sys 0 NULL small 0 NULL", "does not fit the destination");
    refused_with("UpdateSurface sys 0 { 0 0 2 2 } def 0 { 3 0 }", "does not fit the destination");
    refused_with("UpdateSurface sys 0 NULL other 0 NULL", "formats differ");
    refused_with("UpdateSurface sys 1 NULL def 0 NULL", "has no 2D surface at level 1");
}

// IDirect3DDevice9::UpdateTexture: every destination level from the SYSTEMMEM level of its size.
TEST_F(DeviceCalls, UpdateTextureCopiesTheLevelsOfTheDestinationsSizes) {
    ok("CreateTexture sys 4 4 3 A8R8G8B8 SYSTEMMEM\n"
       "CreateTexture def 2 2 2 A8R8G8B8 DEFAULT\n"
       "LockRect sys 1 u32[ 10 11 12 13 ]\n"
       "LockRect sys 2 u32[ 20 ]\n"
       "UpdateTexture sys def\n");
    EXPECT_EQ(texel("def", 0, 0), 10u);
    EXPECT_EQ(texel("def", 1, 1), 13u);
    refused_with("UpdateTexture def sys", "the source is in the DEFAULT pool, not SYSTEMMEM");
}

// Pools: a DEFAULT texture is locked only with DYNAMIC usage; SYSTEMMEM and SCRATCH ones are not
// sampled; RENDERTARGET needs DEFAULT; off-screen plain surfaces are never MANAGED and never
// render targets.
TEST_F(DeviceCalls, PoolsDecideWhatCanBeLockedSampledAndRenderedTo) {
    ok("CreateDevice 4 4 A8R8G8B8\n"
       "CreateTexture def 2 1 1 A8R8G8B8 DEFAULT\n"
       "CreateTexture dyn 2 1 1 A8R8G8B8 DYNAMIC DEFAULT\n"
       "CreateTexture sys 2 1 1 A8R8G8B8 D3DPOOL_SYSTEMMEM\n"
       "CreateTexture scratch 2 1 1 A8R8G8B8 SCRATCH\n"
       "CreateCubeTexture cube 2 1 A8R8G8B8 SYSTEMMEM\n"
       "CreateVolumeTexture vol 2 2 2 1 A8R8G8B8 SCRATCH\n"
       "LockRect dyn 0 u32[ 1 2 ]\n"
       "LockRect sys 0 u32[ 1 2 ]\n"
       "LockRect scratch 0 u32[ 1 2 ]\n"
       "SetTexture 0 def\n"
       "SetTexture 1 dyn\n"
       "CreateOffscreenPlainSurface plain 4 4 A8R8G8B8 SYSTEMMEM\n"
       "LockRect plain 0 { 0 0 1 1 } u32[ 7 ]\n");
    EXPECT_EQ(texel("plain", 0, 0), 7u);
    refused_with("LockRect def 0 u32[ 1 2 ]", "'def' is a DEFAULT-pool texture without DYNAMIC usage");
    refused_with("SetTexture 0 sys", "'sys' is in the SYSTEMMEM pool, which the device cannot sample");
    refused_with("SetTexture 0 scratch", "in the SCRATCH pool");
    refused_with("CreateTexture rtm 2 2 1 A8R8G8B8 RENDERTARGET MANAGED", "must be in the DEFAULT pool, not MANAGED");
    refused_with("CreateTexture dm 2 2 1 A8R8G8B8 DYNAMIC", "a DYNAMIC texture cannot be in the MANAGED pool");
    refused_with("CreateTexture x 2 2 1 A8R8G8B8 SHINY", "expected RENDERTARGET, DYNAMIC or a pool");
    refused_with("CreateOffscreenPlainSurface m 4 4 A8R8G8B8 MANAGED", "the MANAGED pool is not DEFAULT, SYSTEMMEM or SCRATCH");
    refused_with("SetRenderTarget 0 plain", "'plain' is not a render target");
    refused_with("StretchRect backbuffer plain", "'plain' is not a render target");
}

// LockRect of a rectangle: the rectangle's rows, tightly packed, land inside the level.
TEST_F(DeviceCalls, LockRectOfARectangleWritesOnlyThatRectangle) {
    ok("CreateTexture t 4 3 1 A8R8G8B8\n"
       "LockRect t 0 { 1 1 3 3 } u32[ 0xA 0xB 0xC 0xD ]\n"
       "CreateCubeTexture c 2 1 A8R8G8B8\n"
       "LockRect c NEGATIVE_Y 0 { 1 0 2 1 } u32[ 0xE ]\n");
    EXPECT_EQ(texel("t", 1, 1), 0xAu);
    EXPECT_EQ(texel("t", 2, 1), 0xBu);
    EXPECT_EQ(texel("t", 1, 2), 0xCu);
    EXPECT_EQ(texel("t", 2, 2), 0xDu);
    EXPECT_EQ(texel("t", 0, 1), 0u);
    EXPECT_EQ(texel("t", 3, 2), 0u);
    refused_with("LockRect t 0 { 3 0 5 1 } u32[ 1 2 ]", "is not inside the 4x3 level");
    refused_with("LockRect t 0 { 0 0 2 1 } u32[ 1 ]", "4 bytes given, the rectangle holds 8");
}

// StretchRect between rectangles: POINT maps destination pixel centres into the source
// rectangle, texel floor((x + 1/2) * 2 / 4) = x / 2, so each source texel fills 2x2 pixels.
TEST_F(DeviceCalls, StretchRectScalesASourceRectangleIntoADestinationRectangle) {
    ok("CreateRenderTarget src 4 4 A8R8G8B8\n"
       "CreateRenderTarget dst 8 8 A8R8G8B8\n"
       "LockRect src 0 u32[ 0xFF000001 0xFF000002 0xFF000003 0xFF000004  0xFF000005 0xFF000006 0xFF000007 0xFF000008\n"
       "                    0xFF000009 0xFF00000A 0xFF00000B 0xFF00000C  0xFF00000D 0xFF00000E 0xFF00000F 0xFF000010 ]\n"
       "StretchRect src { 2 1 4 3 } dst { 4 4 8 8 } POINT\n");
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const uint32_t expected = (x >= 4 && y >= 4) ? 0xFF000000u | (1 + (2 + (x - 4) / 2) + 4 * (1 + (y - 4) / 2)) : 0u;
            EXPECT_EQ(texel("dst", x, y), expected) << x << "," << y;
        }
    ok("StretchRect src dst { 0 0 1 1 }\n");  // whole source, filter NONE: texel (2, 2) of the 4x4
    EXPECT_EQ(texel("dst", 0, 0), 0xFF00000Bu);
    refused_with("StretchRect src { 0 0 5 1 } dst", "the source rectangle is not inside 'src'");
    refused_with("StretchRect src dst { 6 6 9 9 } LINEAR", "the destination rectangle is not inside 'dst'");
    refused_with("StretchRect src dst POINT LINEAR", "unexpected");
}

TEST_F(DeviceCalls, SoftwareVertexProcessingIsAcceptedAndNPatchesRefused) {
    ok("SetSoftwareVertexProcessing TRUE\nSetSoftwareVertexProcessing FALSE\nSetNPatchMode 0\n");
    refused_with("SetNPatchMode 4", "N-patches (4.000000 segments) are not drawn by sm2emu");
}

// SetGammaRamp: Present writes the frame through the ramp, level v -> ramp[v] / 65535; here
// ramp[v] = (255 - v) * 257 inverts each channel (0x40 -> 0xBF). The back buffer keeps its values.
TEST_F(DeviceCalls, GammaRampAppliesToPresentedFramesOnly) {
    std::vector<Surface> frames;
    DeviceOptions options;
    options.output_dir = "frames";  // not written: write_image keeps the surfaces
    options.write_image = [&](const Surface& s, const std::string&) { frames.push_back(s); };
    Device gamma_device(options);
    std::string ramp;
    for (int i = 0; i < 768; ++i) ramp += " " + std::to_string((255 - i % 256) * 257);
    const auto parsed = cs::parse_text("sm2cs 1\nCreateDevice 2 1 X8R8G8B8\nClear TARGET 0xFF4080C0 1 0\nPresent\n"
                                       "SetGammaRamp 0 u16[" + ramp + " ]\nPresent\nSetGammaRamp 1 u16[" + ramp + " ]\n"
                                       "SetGammaRamp 0 u16[ 1 2 ]\n");
    ASSERT_TRUE(parsed.ok());
    const ReplayResult r = replay(gamma_device, *parsed.stream);
    ASSERT_EQ(r.diagnostics.size(), 2u);
    EXPECT_NE(r.diagnostics[0].message.find("swap chain 1 does not exist"), std::string::npos);
    EXPECT_NE(r.diagnostics[1].message.find("4 bytes; a D3DGAMMARAMP is 768 WORDs"), std::string::npos);
    ASSERT_EQ(frames.size(), 2u);
    uint32_t first = 0, second = 0, back = 0;
    std::memcpy(&first, frames[0].bytes().data(), 4);
    std::memcpy(&second, frames[1].bytes().data(), 4);
    std::memcpy(&back, gamma_device.surface("backbuffer")->bytes().data(), 4);
    EXPECT_EQ(first & 0xFFFFFFu, 0x4080C0u);
    EXPECT_EQ(second & 0xFFFFFFu, 0xBF7F3Fu);
    EXPECT_EQ(back & 0xFFFFFFu, 0x4080C0u);
}

// State blocks, with the lists of "Saving Pixel/Vertex/All Device States with a StateBlock":
// SRCBLEND is pixel state, CULLMODE vertex state, textures and the viewport are in ALL only.
TEST_F(DeviceCalls, PredefinedStateBlocksHoldTheirTypesStates) {
    ok("CreateDevice 8 8 A8R8G8B8\n"
       "CreateTexture tex 2 2 1 A8R8G8B8\n"
       "SetRenderState SRCBLEND ZERO\n"
       "SetRenderState CULLMODE NONE\n"
       "SetRenderState FOGSTART 0.25\n"
       "SetTexture 0 tex\n"
       "SetSamplerState 0 MINFILTER LINEAR\n"
       "SetViewport 1 1 4 4 0 1\n"
       "SetVertexShaderConstantF 2 f32[ 1 2 3 4 ]\n"
       "SetPixelShaderConstantF 1 f32[ 5 6 7 8 ]\n"
       "CreateStateBlock px PIXELSTATE\n"
       "CreateStateBlock vx D3DSBT_VERTEXSTATE\n"
       "CreateStateBlock all ALL\n"
       // Everything changed after the captures.
       "SetRenderState SRCBLEND ONE\n"
       "SetRenderState CULLMODE CW\n"
       "SetRenderState FOGSTART 0.5\n"
       "SetTexture 0 NULL\n"
       "SetSamplerState 0 MINFILTER POINT\n"
       "SetViewport 0 0 8 8 0 1\n"
       "SetVertexShaderConstantF 2 f32[ 0 0 0 0 ]\n"
       "SetPixelShaderConstantF 1 f32[ 0 0 0 0 ]\n"
       "Apply px\n");
    EXPECT_EQ(device.render_state().src_blend, Blend::Zero);
    EXPECT_EQ(device.render_state().cull_mode, CullMode::CW);  // vertex state: not in px
    EXPECT_EQ(device.render_state().fog_start, 0.25f);         // both pixel and vertex state
    EXPECT_EQ(device.sampler_state(0).min_filter, TextureFilter::Linear);
    EXPECT_EQ(device.pixel_shader_constant_f(1)[2], 7.0f);
    EXPECT_EQ(device.vertex_shader_constant_f(2)[0], 0.0f);
    EXPECT_EQ(device.viewport(), (Viewport{0, 0, 8, 8, 0.0f, 1.0f}));
    ok("SetRenderState SRCBLEND ONE\nSetRenderState FOGSTART 0.5\nApply vx\n");
    EXPECT_EQ(device.render_state().cull_mode, CullMode::None);
    EXPECT_EQ(device.render_state().src_blend, Blend::One);  // pixel state: not in vx
    EXPECT_EQ(device.render_state().fog_start, 0.25f);
    EXPECT_EQ(device.vertex_shader_constant_f(2)[1], 2.0f);
    ok("SetRenderState CULLMODE CCW\nSetViewport 0 0 8 8 0 1\nApply all\n");
    EXPECT_EQ(device.render_state().cull_mode, CullMode::None);
    EXPECT_EQ(device.viewport(), (Viewport{1, 1, 4, 4, 0.0f, 1.0f}));
    // The texture is bound again: releasing its name leaves the block's reference alive.
    ok("SetTexture 0 NULL\nRelease tex\nApply all\nSetRenderState ZENABLE FALSE\n");
    refused_with("Apply nothing", "'nothing' is not a state block");
    refused_with("CreateStateBlock bad STENCIL", "unknown name 'STENCIL'");
}

// BeginStateBlock/EndStateBlock: the calls in between go into the block, not the device
// ("records each state change"); Apply sets only those; Capture re-reads only those.
TEST_F(DeviceCalls, RecordedStateBlocksHoldOnlyTheStatesSetWhileRecording) {
    ok("CreateDevice 8 8 A8R8G8B8\n"
       "SetRenderState ZFUNC GREATER\n"
       "BeginStateBlock\n"
       "SetRenderState SHADEMODE FLAT\n"
       "SetRenderState CULLMODE NONE\n"
       "SetRenderState ALPHABLENDENABLE TRUE\n"
       "SetRenderState SRCBLEND ONE\n"
       "SetRenderState DESTBLEND ONE\n"
       "SetPixelShaderConstantF 3 f32[ 1 1 1 1 ]\n"
       "EndStateBlock additive\n");
    // The device did not take the recorded states.
    EXPECT_EQ(device.render_state().shade_mode, ShadeMode::Gouraud);
    EXPECT_EQ(device.render_state().cull_mode, CullMode::CCW);
    EXPECT_FALSE(device.render_state().alpha_blend_enable);
    EXPECT_EQ(device.render_state().dest_blend, Blend::Zero);
    EXPECT_EQ(device.pixel_shader_constant_f(3)[0], 0.0f);
    ok("SetRenderState ZFUNC LESS\nApply additive\n");
    EXPECT_EQ(device.render_state().shade_mode, ShadeMode::Flat);
    EXPECT_EQ(device.render_state().cull_mode, CullMode::None);
    EXPECT_TRUE(device.render_state().alpha_blend_enable);
    EXPECT_EQ(device.render_state().src_blend, Blend::One);
    EXPECT_EQ(device.render_state().dest_blend, Blend::One);
    EXPECT_EQ(device.pixel_shader_constant_f(3)[3], 1.0f);
    EXPECT_EQ(device.render_state().z_func, CompareFunc::Less);  // not recorded: untouched
    // Capture re-reads the block's states only.
    ok("SetRenderState CULLMODE CW\nSetRenderState ZFUNC ALWAYS\nCapture additive\n"
       "SetRenderState CULLMODE CCW\nSetRenderState ZFUNC NEVER\nApply additive\n");
    EXPECT_EQ(device.render_state().cull_mode, CullMode::CW);
    EXPECT_EQ(device.render_state().z_func, CompareFunc::Never);
    refused_with("EndStateBlock again", "without BeginStateBlock");
    ok("BeginStateBlock\n");
    refused_with("BeginStateBlock", "already being recorded");
    ok("EndStateBlock empty\n");
}

// A stream with every new call survives the binary form: dump(pack(text)) == text.
// LockRect of a lockable depth surface ("only lockable formats": D16_LOCKABLE, D32F_LOCKABLE)
// writes the values as stored: D16_LOCKABLE z * 65535 as a 16-bit integer, D32F_LOCKABLE the
// float. A D32F surface left at 1.0 but for x 0..1 at 0.25, then a quad at z 0.5 with ZFUNC
// LESS: 0.5 < 0.25 fails (x 0, 1 stay black), 0.5 < 1 passes (x 2, 3 red, depth 0.5 written).
TEST_F(DeviceCalls, LockRectWritesLockableDepthSurfaces) {
    std::string quad = "u32[";
    for (int i = 0; i < 4; ++i) {  // strip corners (0,0) (4,0) (0,1) (4,1), rhw 1
        for (float v : {i % 2 ? 4.0f : 0.0f, i / 2 ? 1.0f : 0.0f, 0.5f, 1.0f}) quad += ' ' + std::to_string(std::bit_cast<uint32_t>(v));
        quad += " 4294901760";  // diffuse 0xFFFF0000
    }
    quad += " ]";
    ok("CreateDevice 4 1 A8R8G8B8\n"
       "CreateDepthStencilSurface z 4 1 D32F_LOCKABLE\n"
       "SetDepthStencilSurface z\n"
       "LockRect z 0 f32[ 1 1 1 1 ]\n"
       "LockRect z 0 { 0 0 2 1 } f32[ 0.25 0.25 ]\n"
       "SetRenderState ZENABLE TRUE\n"
       "SetRenderState ZFUNC LESS\n"
       "Clear TARGET 0xFF000000 1 0\n"
       "SetFVF { XYZRHW DIFFUSE }\n"
       "BeginScene\n"
       "DrawPrimitiveUP TRIANGLESTRIP 2 20 " + quad + "\n"
       "EndScene\n");
    const DepthStencilSurface* z = device.depth_stencil("z");
    ASSERT_NE(z, nullptr);
    for (uint32_t x = 0; x < 4; ++x) {
        EXPECT_EQ(texel("backbuffer", x, 0), x < 2 ? 0xFF000000u : 0xFFFF0000u) << x;
        EXPECT_EQ(z->depth(x, 0), x < 2 ? 0.25f : 0.5f) << x;
    }
    ok("CreateDepthStencilSurface d 2 2 D16_LOCKABLE\n"
       "LockRect d 0 u16[ 0 65535 0 0 ]\n"
       "LockRect d 0 { 1 1 2 2 } u16[ 32768 ]\n");
    const DepthStencilSurface* d = device.depth_stencil("d");
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->depth(1, 0), 1.0f);
    EXPECT_EQ(d->stored_depth(1, 1), 32768u);
    EXPECT_EQ(d->depth(1, 1), 32768.0f / 65535.0f);
    EXPECT_EQ(d->depth(0, 1), 0.0f);
    ok("CreateDepthStencilSurface ds 2 2 D24S8\n");
    refused_with("LockRect ds 0 u32[ 0 0 0 0 ]", "only D16_LOCKABLE and D32F_LOCKABLE ones can be locked");
    refused_with("LockRect d 0 u16[ 0 0 0 ]", "6 bytes given, the surface holds 8");
    refused_with("LockRect d 0 { 1 1 3 2 } u16[ 0 0 ]", "is not inside the 2x2 surface");
    refused_with("LockRect d 1 u16[ 0 0 0 0 ]", "a depth surface has one level");
}

// LockBox with a D3DBOX (right, bottom, back exclusive) writes only the box's texels: in a 2x2x2
// A8R8G8B8 volume filled with 1..8 (texel x + 2y + 4z holds x + 2y + 4z + 1), the box
// { 1 0 1 2 2 2 } is texels (1,0,1) and (1,1,1), bytes 5*4 and 7*4.
TEST_F(DeviceCalls, LockBoxOfABoxWritesOnlyThatBox) {
    ok("CreateVolumeTexture v 2 2 2 1 A8R8G8B8\n"
       "LockBox v 0 u32[ 1 2 3 4 5 6 7 8 ]\n"
       "LockBox v 0 { 1 0 1 2 2 2 } u32[ 0xAA 0xBB ]\n");
    const Surface* level = device.surface("v");
    ASSERT_NE(level, nullptr);
    ASSERT_EQ(level->bytes().size(), 32u);
    std::vector<uint32_t> texels(8);
    std::memcpy(texels.data(), level->bytes().data(), 32);
    EXPECT_EQ(texels, (std::vector<uint32_t>{1, 2, 3, 4, 5, 0xAA, 7, 0xBB}));
    refused_with("LockBox v 0 { 1 0 1 3 2 2 } u32[ 0 0 ]", "box {1 0 1 3 2 2} is not inside the 2x2x2 level");
    refused_with("LockBox v 0 { 0 0 0 1 1 1 } u32[ 0 0 ]", "8 bytes given, the box holds 4");
    refused_with("LockBox v 0 { 0 0 0 1 1 } u32[ 0 ]", "a box has 6 numbers");
}

// IDirect3DDevice9::Reset: refused (D3DERR_INVALIDCALL) while a DEFAULT-pool resource is alive
// (here a render target, then a DEFAULT texture), the replay going on; once they are released
// the back buffer and automatic depth surface are 6x2 (and D16), every state and binding is
// back to its default (ZENABLE TRUE with an automatic depth surface, CULLMODE CCW, MINFILTER
// POINT, constants 0, no texture, the new back buffer as render target 0), and viewport and
// scissor rectangle cover 6x2. MANAGED resources live on.
TEST_F(DeviceCalls, ResetRecreatesTheBackBufferAndRestoresDefaults) {
    ok("CreateDevice 4 4 A8R8G8B8 D24S8\n"
       "CreateRenderTarget rt 2 2 A8R8G8B8\n"
       "CreateTexture def 2 2 1 A8R8G8B8 RENDERTARGET\n"
       "CreateTexture tex 2 2 1 A8R8G8B8\n"
       "SetTexture 0 tex\n"
       "SetRenderState CULLMODE NONE\n"
       "SetRenderState ZENABLE FALSE\n"
       "SetSamplerState 0 MINFILTER LINEAR\n"
       "SetPixelShaderConstantF 1 f32[ 1 2 3 4 ]\n"
       "SetViewport 1 1 2 2 0 1\n");
    refused_with("Reset 6 2 X8R8G8B8 D16", "Reset: DEFAULT-pool resources are not released: 'def', 'rt'");
    ok("Release rt\n");
    refused_with("Reset 6 2 X8R8G8B8 D16", "Reset: DEFAULT-pool resources are not released: 'def'");
    EXPECT_EQ(device.viewport(), (Viewport{1, 1, 2, 2, 0.0f, 1.0f}));  // refused: nothing changed
    ok("Release def\nReset 6 2 X8R8G8B8 D16\n");
    const Surface* back = device.surface("backbuffer");
    ASSERT_NE(back, nullptr);
    EXPECT_EQ(back->width(), 6u);
    EXPECT_EQ(back->height(), 2u);
    EXPECT_EQ(back->format(), Format::X8R8G8B8);
    const DepthStencilSurface* depth = device.depth_stencil("autodepth");
    ASSERT_NE(depth, nullptr);
    EXPECT_EQ(depth->format(), Format::D16);
    EXPECT_EQ(depth->width(), 6u);
    EXPECT_EQ(device.viewport(), (Viewport{0, 0, 6, 2, 0.0f, 1.0f}));
    EXPECT_EQ(device.scissor_rect(), (PixelRect{0, 0, 6, 2}));
    EXPECT_EQ(device.render_state().cull_mode, CullMode::CCW);
    EXPECT_EQ(device.render_state().z_enable, ZBufferType::True);
    EXPECT_EQ(device.sampler_state(0).min_filter, TextureFilter::Point);
    EXPECT_EQ(device.pixel_shader_constant_f(1)[0], 0.0f);
    const DeviceInspection state = device.inspect();
    EXPECT_FALSE(state.textures[0].has_value());
    EXPECT_EQ(state.render_targets[0], back);
    EXPECT_EQ(state.depth_stencil, depth);
    EXPECT_TRUE(device.has_resource("tex"));
    ok("Reset 2 2 A8R8G8B8\n");  // no automatic depth surface: ZENABLE FALSE
    EXPECT_FALSE(device.has_resource("autodepth"));
    EXPECT_EQ(device.render_state().z_enable, ZBufferType::False);
    refused_with("Reset 0 2 A8R8G8B8", "Reset: back buffer size 0x2 is out of range");
    refused_with("Reset 2 2 A8R8G8B8 A8R8G8B8", "Reset: A8R8G8B8 is not a depth format");
    EXPECT_EQ(device.surface("backbuffer")->width(), 2u);
}

// Reset before CreateDevice has no device to reset.
TEST_F(DeviceCalls, ResetWithoutADeviceIsRefused) {
    refused_with("Reset 2 2 A8R8G8B8", "Reset: no device (CreateDevice)");
}

TEST_F(DeviceCalls, NewCallsRoundTripThroughTheBinaryForm) {
    const std::string text =
        "sm2cs 1\n"
        "CreateTexture sys 4 4 1 A8R8G8B8 DYNAMIC SYSTEMMEM\n"
        "CreateOffscreenPlainSurface plain 4 4 X8R8G8B8 SCRATCH\n"
        "Clear TARGET 0xFF102030 1.0 0 { 0 0 2 2 } { 3 3 4 4 }\n"
        "ColorFill rt { 0 0 16 16 } 0xFFFFFF00\n"
        "UpdateSurface sys 0 { 0 0 16 16 } def 0 { 40 8 }\n"
        "UpdateSurface sys 0 NULL def 0 NULL\n"
        "UpdateTexture sys def\n"
        "StretchRect rt { 8 8 32 32 } backbuffer { 192 0 256 64 } LINEAR\n"
        "GetRenderTargetData backbuffer plain\n"
        "LockRect t POSITIVE_Z 0 { 1 1 2 2 } u32[ 0xFFFFFFFF ]\n"
        "SetSoftwareVertexProcessing TRUE\n"
        "SetNPatchMode 0.0\n"
        "CreateStateBlock sb ALL\n"
        "BeginStateBlock\n"
        "EndStateBlock sb2\n"
        "Capture sb\n"
        "Apply sb2\n"
        "SetGammaRamp 0 u16[ 0 1 2 ]\n"
        "LockBox v 0 { 1 0 1 2 2 2 } u32[ 0x000000AA 0x000000BB ]\n"
        "SaveSurface c \"f.png\" 1 NEGATIVE_Y\n"
        "SaveSurface ds \"d.exr\"\n"
        "Reset 640 480 X8R8G8B8 D24S8\n";
    auto parsed = cs::parse_text(text);
    ASSERT_TRUE(parsed.ok()) << parsed.error->to_string();
    EXPECT_EQ(cs::to_text(*parsed.stream), text);
    auto unpacked = cs::unpack(cs::pack(*parsed.stream));
    ASSERT_TRUE(unpacked.ok()) << unpacked.error->to_string();
    EXPECT_EQ(cs::to_text(*unpacked.stream), text);
}

}  // namespace
}  // namespace sm2::runtime
