// The replayer: every call of docs/command-stream.md's vocabulary applied to a Device and its
// effect checked (resources, states, constants, surface bytes, files), and every bad-input path
// reported with its line while the device stays usable. Draws are in replay_draw_test.cpp.
#include "sm2/runtime/replay.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/image_io.h"

namespace sm2::runtime {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> bytes_of(const Surface* s) {
    std::vector<uint8_t> out;
    if (!s) return out;
    out.resize(s->bytes().size());
    std::memcpy(out.data(), s->bytes().data(), out.size());
    return out;
}

// Each test gets a folder of its own (tests run in parallel processes) used as the Device's
// output folder and as the stream's folder for side files and LoadTexture.
class Replay : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("sm2_replay_" + std::to_string(getpid()));
        fs::create_directories(dir_);
        DeviceOptions options;
        options.output_dir = dir_.string();
        device_ = std::make_unique<Device>(options);
        replayer_ = std::make_unique<Replayer>(*device_, replay_options());
    }
    void TearDown() override {
        replayer_.reset();
        device_.reset();
        fs::remove_all(dir_);
    }

    [[nodiscard]] ReplayOptions replay_options() const {
        ReplayOptions options;
        options.file_name = "t.sm2cs";
        options.base_dir = dir_.string();
        options.assembler = runtime::stream_assembler();
        return options;
    }

    // Parses "sm2cs 1\n" + body (so the body's first line is line 2) and replays it.
    ReplayResult run(const std::string& body) {
        cs::TextOptions text;
        text.file_name = "t.sm2cs";
        text.base_dir = dir_.string();
        auto parsed = cs::parse_text("sm2cs 1\n" + body, text);
        EXPECT_TRUE(parsed.ok()) << parsed.error->to_string();
        if (!parsed.ok()) return {};
        return replayer_->replay(*parsed.stream);
    }
    // Replays and expects no diagnostics.
    ReplayResult ok(const std::string& body) {
        ReplayResult r = run(body);
        for (const auto& d : r.diagnostics) ADD_FAILURE() << d.to_string();
        return r;
    }
    // Replays and expects exactly these diagnostics.
    void refused(const std::string& body, const std::vector<std::string>& expected) {
        const ReplayResult r = run(body);
        std::vector<std::string> got;
        for (const auto& d : r.diagnostics) got.push_back(d.to_string());
        EXPECT_EQ(got, expected);
        EXPECT_EQ(r.refused, expected.size());
    }
    // Replays one bad call and expects one diagnostic on line 2 containing `fragment`.
    void refused_with(const std::string& call, const std::string& fragment) {
        const ReplayResult r = run(call + "\n");
        ASSERT_EQ(r.diagnostics.size(), 1u) << call;
        const std::string text = r.diagnostics[0].to_string();
        EXPECT_EQ(text.rfind("t.sm2cs:2: D3DERR_INVALIDCALL: ", 0), 0u) << text;
        EXPECT_NE(text.find(fragment), std::string::npos) << text;
    }
    void write_file(const std::string& name, const void* data, size_t size) const {
        std::ofstream(dir_ / name, std::ios::binary).write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }

    Device& device() { return *device_; }

private:
    fs::path dir_;
    std::unique_ptr<Device> device_;
    std::unique_ptr<Replayer> replayer_;
};

// ---------------------------------------------------------------------------------------------
// Resources

TEST_F(Replay, CreateDeviceMakesTheBackBufferAndAutomaticDepth) {
    ok("CreateDevice 8 4 A8R8G8B8 D24S8\n");
    const Surface* back = device().surface("backbuffer");
    ASSERT_NE(back, nullptr);
    EXPECT_EQ(back->width(), 8u);
    EXPECT_EQ(back->height(), 4u);
    EXPECT_EQ(back->format(), Format::A8R8G8B8);
    EXPECT_NE(device().depth_stencil("autodepth"), nullptr);
    EXPECT_EQ(device().render_state().z_enable, ZBufferType::True);
    EXPECT_EQ(device().viewport(), (Viewport{0, 0, 8, 4, 0.0f, 1.0f}));
}

TEST_F(Replay, CreateDeviceAcceptsPrefixedFormats) {
    ok("CreateDevice 2 2 D3DFMT_X8R8G8B8\n");
    EXPECT_EQ(device().surface("backbuffer")->format(), Format::X8R8G8B8);
    EXPECT_FALSE(device().has_resource("autodepth"));
}

TEST_F(Replay, CreateEveryKindOfResource) {
    ok("CreateVertexBuffer vb 36\n"
       "CreateIndexBuffer ib 12 INDEX16\n"
       "CreateIndexBuffer ib32 12 D3DFMT_INDEX32\n"
       "CreateTexture tex 16 8 0 A8R8G8B8\n"
       "CreateTexture rtt 4 4 1 A8R8G8B8 RENDERTARGET\n"
       "CreateTexture rtt2 4 4 1 R5G6B5 D3DUSAGE_RENDERTARGET\n"
       "CreateCubeTexture cube 4 1 L8\n"
       "CreateCubeTexture cubert 4 1 A8R8G8B8 RENDERTARGET\n"
       "CreateVolumeTexture vol 4 2 2 1 L8\n"
       "CreateRenderTarget rt 5 3 A16B16G16R16F\n"
       "CreateDepthStencilSurface ds 5 3 D16\n"
       "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 D3DCOLOR DEFAULT COLOR 0 }\n");
    for (const char* name : {"vb", "ib", "ib32", "tex", "rtt", "rtt2", "cube", "cubert", "vol", "rt", "ds", "decl"})
        EXPECT_TRUE(device().has_resource(name)) << name;
    EXPECT_EQ(device().surface("tex")->width(), 16u);
    EXPECT_EQ(device().surface("tex")->height(), 8u);
    EXPECT_EQ(device().surface("rt")->format(), Format::A16B16G16R16F);
    EXPECT_EQ(device().surface("vol")->depth(), 2u);
    EXPECT_EQ(device().depth_stencil("ds")->width(), 5u);
}

TEST_F(Replay, LockRectWritesTheLevelBytesAsGiven) {
    ok("CreateTexture t 2 1 1 A8R8G8B8\n"
       "LockRect t 0 u32[ 0xFF102030 0x80FFFFFF ]\n");
    // u32 little-endian: 0xFF102030 -> 30 20 10 FF (B G R A)
    EXPECT_EQ(bytes_of(device().surface("t")), (std::vector<uint8_t>{0x30, 0x20, 0x10, 0xFF, 0xFF, 0xFF, 0xFF, 0x80}));
    const Float4 texel = device().surface("t")->read(0, 0);
    EXPECT_FLOAT_EQ(texel[0], 16.0f / 255);
    EXPECT_FLOAT_EQ(texel[1], 32.0f / 255);
    EXPECT_FLOAT_EQ(texel[2], 48.0f / 255);
    EXPECT_FLOAT_EQ(texel[3], 1.0f);
}

TEST_F(Replay, LockRectOnCubeFacesByName) {
    ok("CreateCubeTexture c 2 1 L8\n"
       "LockRect c POSITIVE_X 0 u8[ 1 2 3 4 ]\n"
       "LockRect c D3DCUBEMAP_FACE_NEGATIVE_Z 0 u8[ 9 9 9 9 ]\n"
       "LockRect c 3 0 u8[ 7 7 7 7 ]\n");
    // surface() is face 0 (POSITIVE_X): the other faces' data did not land there.
    EXPECT_EQ(bytes_of(device().surface("c")), (std::vector<uint8_t>{1, 2, 3, 4}));
    refused_with("LockRect c UP 0 u8[ 1 2 3 4 ]", "unknown cube face 'UP'");
    refused_with("LockRect c 6 0 u8[ 1 2 3 4 ]", "face 6 out of range");
    EXPECT_EQ(bytes_of(device().surface("c")), (std::vector<uint8_t>{1, 2, 3, 4}));
}

TEST_F(Replay, LockBoxWritesEverySlice) {
    ok("CreateVolumeTexture v 2 2 2 1 L8\n"
       "LockBox v 0 u8[ 1 2 3 4 5 6 7 8 ]\n");
    EXPECT_EQ(bytes_of(device().surface("v")), (std::vector<uint8_t>{1, 2, 3, 4, 5, 6, 7, 8}));
    refused_with("LockBox v 0 u8[ 1 2 3 ]", "3 bytes given, the level holds 8");
}

TEST_F(Replay, LockTakesBlobsAndSideFiles) {
    const uint8_t data[4] = {0xDE, 0xAD, 0xBE, 0xEF};
    write_file("data.bin", data, sizeof data);
    ok("CreateVertexBuffer vb 10\n"
       "Lock vb 0 f32[ 1 ]\n"
       "Lock vb 6 @\"data.bin\"\n");
    refused_with("Lock vb 8 @\"data.bin\"", "4 bytes at offset 8 do not fit in 'vb' (10 bytes)");
    refused_with("Lock vb 0 12", "argument 3 (data): expected a blob");
}

TEST_F(Replay, LoadTextureReadsAFileBesideTheStream) {
    Image image;
    image.width = 2;
    image.height = 1;
    image.rgba = {1, 0, 0, 1, 0, 0, 1, 1};
    write_image(image, path("tex.png"));
    ok("LoadTexture t \"tex.png\"\n"
       "LoadTexture t2 \"tex.png\" GENERATEMIPS\n");
    const Surface* s = device().surface("t");
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->width(), 2u);
    EXPECT_EQ(s->read(0, 0), (Float4{1, 0, 0, 1}));
    EXPECT_EQ(s->read(1, 0), (Float4{0, 0, 1, 1}));
    EXPECT_TRUE(device().has_resource("t2"));
    refused_with("LoadTexture t3 \"missing.png\"", "LoadTexture: ");
    refused_with("LoadTexture t4 \"tex.png\" MIPS", "expected GENERATEMIPS");
    EXPECT_FALSE(device().has_resource("t3"));
}

TEST_F(Replay, GenerateMipSubLevelsAndRelease) {
    ok("CreateTexture t 4 4 0 A8R8G8B8\n"
       "GenerateMipSubLevels t\n"
       "CreateRenderTarget rt 4 4 A8R8G8B8\n");
    refused_with("GenerateMipSubLevels rt", "'rt' is not a texture");
    ok("Release t\n");
    EXPECT_FALSE(device().has_resource("t"));
    ok("CreateVertexBuffer t 4\n");  // the handle may be reused
    EXPECT_TRUE(device().has_resource("t"));
    refused_with("Release t_never", "no resource named 't_never'");
}

// ---------------------------------------------------------------------------------------------
// Shaders

constexpr uint32_t kPsMovC0[] = {0xFFFF0200, 0x02000001, 0x800F0800, 0xA0E40000, 0x0000FFFF};  // mov oC0, c0

TEST_F(Replay, ShadersFromHeredocBlobAndSideFiles) {
    write_file("ps.bin", kPsMovC0, sizeof kPsMovC0);
    const std::string vs_text = "vs_2_0\ndcl_position v0\nmov oPos, v0\n";
    write_file("vs.asm", vs_text.data(), vs_text.size());
    ok("CreateVertexShader vs asm<<END\n"
       "vs_2_0\n"
       "dcl_position v0\n"
       "mov oPos, v0\n"
       "END\n"
       "CreatePixelShader ps u32[ 0xFFFF0200 0x02000001 0x800F0800 0xA0E40000 0x0000FFFF ]\n"
       "CreatePixelShader ps_file @\"ps.bin\"\n"
       "CreateVertexShader vs_file @\"vs.asm\"\n"
       "SetVertexShader vs\n"
       "SetPixelShader ps_file\n"
       "SetVertexShader NULL\n"
       "SetPixelShader NULL\n");
    for (const char* name : {"vs", "ps", "ps_file", "vs_file"}) EXPECT_TRUE(device().has_resource(name)) << name;
}

TEST_F(Replay, ShaderOfTheWrongType) {
    refused_with("CreateVertexShader v u32[ 0xFFFF0200 0x02000001 0x800F0800 0xA0E40000 0x0000FFFF ]",
                 "CreateVertexShader: the program is a pixel shader");
    EXPECT_FALSE(device().has_resource("v"));
    ok("CreateVertexShader vs asm<<END\nvs_2_0\nmov oPos, c0\nEND\n");
    refused_with("SetPixelShader vs", "SetPixelShader: 'vs' is not a pixel shader");
}

TEST_F(Replay, BadAssemblyNamesTheLineInsideTheHeredoc) {
    const ReplayResult r = run("CreateDevice 2 2 A8R8G8B8\n"      // line 2
                               "CreateVertexShader vs asm<<END\n"  // line 3
                               "vs_2_0\n"                          // line 4: assembly line 1
                               "frobnicate r0, r1\n"               // line 5: assembly line 2
                               "END\n"
                               "Clear TARGET 0xFF0000FF 1 0\n");
    ASSERT_EQ(r.diagnostics.size(), 1u);
    const std::string text = r.diagnostics[0].to_string();
    EXPECT_EQ(text.rfind("t.sm2cs:5: D3DERR_INVALIDCALL: CreateVertexShader: assembly line 2: ", 0), 0u) << text;
    EXPECT_FALSE(device().has_resource("vs"));
    // The replay went on: the Clear after it ran.
    EXPECT_EQ(bytes_of(device().surface("backbuffer"))[0], 0xFF);
}

TEST_F(Replay, BadBytecodeAndMissingAssembler) {
    refused_with("CreatePixelShader p u32[ 0xFFFF0200 0x05000001 0x0000FFFF ]", "argument 2 (shader): bytecode token");
    refused_with("CreatePixelShader p u8[ 1 2 3 ]", "3 bytes is not a whole number of tokens");
    refused_with("CreatePixelShader p \"ps.asm\"", "expected asm<<TAG or hlsl<<TAG text, a side file or a u32[] blob");

    Replayer bare(device());  // no assembler given
    cs::Statement st;
    st.name = "CreatePixelShader";
    st.line = 9;
    cs::Value name;
    name.kind = cs::Value::Kind::Identifier;
    name.text = "p";
    cs::Value text;
    text.kind = cs::Value::Kind::Heredoc;
    text.text = "END";
    const std::string asm_text = "ps_2_0\nmov oC0, c0\n";
    for (char c : asm_text) text.bytes.push_back(static_cast<std::byte>(c));
    st.arguments = {name, text};
    EXPECT_FALSE(bare.execute(st));
    ASSERT_EQ(bare.diagnostics().size(), 1u);
    EXPECT_EQ(bare.diagnostics()[0].to_string(),
              "<input>:9: D3DERR_INVALIDCALL: CreatePixelShader: argument 2 (shader): no assembler is available to "
              "this replay for shader text");
    EXPECT_FALSE(device().has_resource("p"));
}

// ---------------------------------------------------------------------------------------------
// Bindings

TEST_F(Replay, BindingsAcceptTheRightKindAndNull) {
    ok("CreateDevice 4 4 A8R8G8B8\n"
       "CreateVertexBuffer vb 48\n"
       "CreateIndexBuffer ib 12 INDEX16\n"
       "CreateTexture tex 4 4 1 A8R8G8B8\n"
       "CreateDepthStencilSurface ds 4 4 D24S8\n"
       "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
       "SetVertexDeclaration decl\n"
       "SetStreamSource 0 vb 0 12\n"
       "SetStreamSource 15 vb 12 12\n"
       "SetIndices ib\n"
       "SetTexture 0 tex\n"
       "SetTexture 15 tex\n"
       "SetDepthStencilSurface ds\n"
       "SetVertexDeclaration NULL\n"
       "SetStreamSource 0 NULL 0 0\n"
       "SetIndices NULL\n"
       "SetTexture 0 NULL\n"
       "SetDepthStencilSurface NULL\n");
    refused_with("SetStreamSource 0 vb 0 0", "SetStreamSource: stride 0");
    refused_with("SetStreamSource 16 vb 0 12", "stream 16 out of range");
    refused_with("SetIndices vb", "'vb' is not a index buffer");
    refused_with("SetTexture 0 ds", "'ds' is not a texture");
    refused_with("SetTexture 16 tex", "stage 16 out of range");
    refused_with("SetDepthStencilSurface tex", "'tex' is not a depth-stencil surface");
    refused_with("SetVertexDeclaration vb", "'vb' is not a vertex declaration");
    refused_with("SetTexture 0 nowhere", "SetTexture: no resource named 'nowhere'");
}

TEST_F(Replay, SetRenderTargetResetsViewportAndScissor) {
    ok("CreateDevice 8 8 A8R8G8B8\n"
       "CreateRenderTarget rt 4 2 A8R8G8B8\n"
       "CreateTexture rtt 4 4 1 A8R8G8B8 RENDERTARGET\n"
       "SetViewport 1 1 2 2 0 1\n"
       "SetRenderTarget 0 rt\n");
    EXPECT_EQ(device().viewport(), (Viewport{0, 0, 4, 2, 0.0f, 1.0f}));
    EXPECT_EQ(device().scissor_rect(), (PixelRect{0, 0, 4, 2}));
    ok("SetRenderTarget 1 rtt\nSetRenderTarget 1 NULL\n");
    refused_with("SetRenderTarget 0 NULL", "render target 0 cannot be NULL");
    refused_with("SetRenderTarget 4 rt", "index 4 out of range");
    EXPECT_EQ(device().viewport(), (Viewport{0, 0, 4, 2, 0.0f, 1.0f}));
}

// ---------------------------------------------------------------------------------------------
// States and constants

TEST_F(Replay, RenderStateValuesTakeTheTypeOfTheirState) {
    ok("SetRenderState CULLMODE NONE\n"
       "SetRenderState D3DRS_ZFUNC D3DCMP_GREATER\n"
       "SetRenderState FOGSTART 0.5\n"
       "SetRenderState FOGEND 2\n"
       "SetRenderState ALPHAREF 0x80\n"
       "SetRenderState ALPHABLENDENABLE TRUE\n"
       "SetRenderState ZWRITEENABLE FALSE\n"
       "SetRenderState FOGCOLOR 0xFF808080\n"
       "SetRenderState STENCILMASK 0x0F\n"
       "SetRenderState COLORWRITEENABLE { RED ALPHA }\n"
       "SetRenderState COLORWRITEENABLE1 GREEN\n"
       "SetRenderState COLORWRITEENABLE2 0x5\n"
       "SetRenderState SRCBLEND SRCALPHA\n");
    const RenderState& rs = device().render_state();
    EXPECT_EQ(rs.cull_mode, CullMode::None);
    EXPECT_EQ(rs.z_func, CompareFunc::Greater);
    EXPECT_EQ(rs.fog_start, 0.5f);
    EXPECT_EQ(rs.fog_end, 2.0f);
    EXPECT_EQ(rs.alpha_ref, 128u);
    EXPECT_TRUE(rs.alpha_blend_enable);
    EXPECT_FALSE(rs.z_write_enable);
    EXPECT_EQ(rs.fog_color, 0xFF808080u);
    EXPECT_EQ(rs.stencil_mask, 0x0Fu);
    EXPECT_EQ(rs.color_write_enable[0], 9u);  // RED 1 | ALPHA 8
    EXPECT_EQ(rs.color_write_enable[1], 2u);
    EXPECT_EQ(rs.color_write_enable[2], 5u);
    EXPECT_EQ(rs.src_blend, Blend::SrcAlpha);
}

TEST_F(Replay, BadRenderStateValuesLeaveTheStateAlone) {
    ok("SetRenderState CULLMODE CW\n");
    refused_with("SetRenderState CULLMODE SIDEWAYS",
                 "argument 2 (CULLMODE value): unknown name 'SIDEWAYS' (expected one of NONE, CW, CCW)");
    refused_with("SetRenderState CULLMODE 1", "expected a name of NONE, CW, CCW, got an integer 1");
    refused_with("SetRenderState ALPHABLENDENABLE 1", "expected TRUE or FALSE, got an integer 1");
    refused_with("SetRenderState FOGSTART NONE", "expected a number, got a name 'NONE'");
    refused_with("SetRenderState ALPHAREF 0.5", "expected an integer, got a float");
    refused_with("SetRenderState FROBNICATE TRUE", "argument 1 (state): unknown render state 'FROBNICATE'");
    refused_with("SetRenderState COLORWRITEENABLE { RED PURPLE }", "unknown name 'PURPLE'");
    EXPECT_EQ(device().render_state().cull_mode, CullMode::CW);
    EXPECT_EQ(device().render_state().color_write_enable[0], 0xFu);
}

TEST_F(Replay, SamplerStates) {
    ok("SetSamplerState 1 ADDRESSU CLAMP\n"
       "SetSamplerState 1 D3DSAMP_MAGFILTER D3DTEXF_LINEAR\n"
       "SetSamplerState 1 MIPMAPLODBIAS -1.5\n"
       "SetSamplerState 1 BORDERCOLOR 0xFF00FF00\n"
       "SetSamplerState 1 SRGBTEXTURE TRUE\n"
       "SetSamplerState 15 MAXANISOTROPY 4\n");
    const SamplerState& s = device().sampler_state(1);
    EXPECT_EQ(s.address_u, TextureAddress::Clamp);
    EXPECT_EQ(s.address_v, TextureAddress::Wrap);
    EXPECT_EQ(s.mag_filter, TextureFilter::Linear);
    EXPECT_EQ(s.mip_lod_bias, -1.5f);
    EXPECT_EQ(s.border_color, 0xFF00FF00u);
    EXPECT_TRUE(s.srgb_texture);
    EXPECT_EQ(device().sampler_state(15).max_anisotropy, 4u);
    EXPECT_EQ(device().sampler_state(0), SamplerState{});
    refused_with("SetSamplerState 16 ADDRESSU CLAMP", "sampler 16 out of range");
    refused_with("SetSamplerState 0 ADDRESSU LINEAR", "unknown name 'LINEAR'");
    refused_with("SetSamplerState 0 CULLMODE NONE", "unknown sampler state 'CULLMODE'");
    EXPECT_EQ(device().sampler_state(0), SamplerState{});
}

TEST_F(Replay, ShaderConstants) {
    ok("SetVertexShaderConstantF 3 f32[ 1 2 3 4 5 6 7 8 ]\n"
       "SetPixelShaderConstantF 223 f32[ -1 0.5 inf 0 ]\n"
       "SetVertexShaderConstantI 2 i32[ -1 0 5 7 ]\n"
       "SetPixelShaderConstantI 15 i32[ 255 1 2 3 ]\n"
       "SetVertexShaderConstantB 0 u32[ 1 0 7 ]\n"
       "SetPixelShaderConstantB 14 u32[ 1 0 ]\n");
    EXPECT_EQ(device().vertex_shader_constant_f(3), (std::array<float, 4>{1, 2, 3, 4}));
    EXPECT_EQ(device().vertex_shader_constant_f(4), (std::array<float, 4>{5, 6, 7, 8}));
    EXPECT_EQ(device().pixel_shader_constant_f(223)[0], -1.0f);
    EXPECT_EQ(device().pixel_shader_constant_f(223)[1], 0.5f);
    EXPECT_TRUE(std::isinf(device().pixel_shader_constant_f(223)[2]));
    EXPECT_EQ(device().vertex_shader_flow_constants().integers[2], (emu::Int4{-1, 0, 5, 7}));
    EXPECT_EQ(device().pixel_shader_flow_constants().integers[15], (emu::Int4{255, 1, 2, 3}));
    const auto& vb = device().vertex_shader_flow_constants().booleans;
    EXPECT_TRUE(vb[0]);
    EXPECT_FALSE(vb[1]);
    EXPECT_TRUE(vb[2]);  // any non-zero BOOL is TRUE
    EXPECT_TRUE(device().pixel_shader_flow_constants().booleans[14]);
    EXPECT_FALSE(device().pixel_shader_flow_constants().booleans[15]);

    refused_with("SetVertexShaderConstantF 255 f32[ 9 9 9 9 9 9 9 9 ]", "registers 255..257 exceed 256");
    refused_with("SetPixelShaderConstantF 224 f32[ 9 9 9 9 ]", "registers 224..225 exceed 224");
    refused_with("SetVertexShaderConstantF 0 f32[ 9 9 9 ]", "3 floats is not a whole number of registers");
    refused_with("SetVertexShaderConstantF 0 u8[ 1 2 3 ]", "3 bytes is not a whole number of 32-bit values");
    refused_with("SetVertexShaderConstantI 16 i32[ 1 1 1 1 ]", "registers 16..17 exceed 16");
    refused_with("SetPixelShaderConstantB 15 u32[ 1 1 ]", "registers 15..17 exceed 16");
    refused_with("SetVertexShaderConstantF -1 f32[ 9 9 9 9 ]", "-1 is not an unsigned 32-bit integer");
    EXPECT_EQ(device().vertex_shader_constant_f(0), (std::array<float, 4>{0, 0, 0, 0}));
    EXPECT_EQ(device().vertex_shader_constant_f(255), (std::array<float, 4>{0, 0, 0, 0}));
    EXPECT_FALSE(device().pixel_shader_flow_constants().booleans[15]);
}

TEST_F(Replay, ViewportScissorAndClipPlanesOneByOneOrAsTuples) {
    ok("CreateDevice 8 8 A8R8G8B8\n"
       "SetViewport 1 2 3 4 0.25 0.75\n");
    EXPECT_EQ(device().viewport(), (Viewport{1, 2, 3, 4, 0.25f, 0.75f}));
    ok("SetViewport { 0 0 8 8 0 1 }\n"
       "SetScissorRect 1 2 5 6\n");
    EXPECT_EQ(device().viewport(), (Viewport{0, 0, 8, 8, 0.0f, 1.0f}));
    EXPECT_EQ(device().scissor_rect(), (PixelRect{1, 2, 5, 6}));
    ok("SetScissorRect { 0 0 4 4 }\n"
       "SetClipPlane 2 1 0 -1 0.5\n"
       "SetClipPlane 5 { 0 1 0 -2 }\n");
    EXPECT_EQ(device().scissor_rect(), (PixelRect{0, 0, 4, 4}));
    EXPECT_EQ(device().clip_plane(2), (Vec4{1, 0, -1, 0.5f}));
    EXPECT_EQ(device().clip_plane(5), (Vec4{0, 1, 0, -2}));
    refused_with("SetViewport 0 0 9 8 0 1", "the viewport does not fit the render target");
    refused_with("SetViewport 0 0 8 8 0 2", "MinZ/MaxZ outside [0, 1]");
    refused_with("SetViewport 1 2 3", "expects 6 numbers (x y width height min_z max_z), got 3");
    refused_with("SetScissorRect 5 0 1 1", "malformed rectangle");
    refused_with("SetClipPlane 6 0 0 0 0", "index 6 out of range");
    EXPECT_EQ(device().viewport(), (Viewport{0, 0, 8, 8, 0.0f, 1.0f}));
    EXPECT_EQ(device().scissor_rect(), (PixelRect{0, 0, 4, 4}));
}

// ---------------------------------------------------------------------------------------------
// Frames

TEST_F(Replay, ClearWritesTheColourInTheTargetFormat) {
    ok("CreateDevice 4 2 A8R8G8B8\n"
       "Clear TARGET 0xFF336699 1 0\n");
    const auto bytes = bytes_of(device().surface("backbuffer"));
    ASSERT_EQ(bytes.size(), 4u * 2u * 4u);
    for (size_t i = 0; i < bytes.size(); i += 4) {
        EXPECT_EQ(bytes[i + 0], 0x99);  // B
        EXPECT_EQ(bytes[i + 1], 0x66);  // G
        EXPECT_EQ(bytes[i + 2], 0x33);  // R
        EXPECT_EQ(bytes[i + 3], 0xFF);  // A
    }
    // R5G6B5: red 0xFF -> 31 << 11 = 0xF800, stored little-endian
    ok("CreateRenderTarget rt 1 1 R5G6B5\n"
       "SetRenderTarget 0 rt\n"
       "Clear D3DCLEAR_TARGET 0xFFFF0000 1 0\n");
    EXPECT_EQ(bytes_of(device().surface("rt")), (std::vector<uint8_t>{0x00, 0xF8}));
}

TEST_F(Replay, ClearFlagsAsTupleAndNumber) {
    ok("CreateDevice 2 2 A8R8G8B8 D16\n"
       "Clear { TARGET ZBUFFER } 0x00000000 0.5 0\n");
    // D16: round(0.5 * 65535) = round(32767.5) = 32768 (halves up)
    EXPECT_EQ(device().depth_stencil("autodepth")->stored_depth(1, 1), 32768u);
    EXPECT_EQ(bytes_of(device().surface("backbuffer"))[3], 0x00);
    ok("CreateDepthStencilSurface ds 2 2 D24S8\n"
       "SetDepthStencilSurface ds\n"
       "Clear 6 0 0.25 7\n");  // ZBUFFER | STENCIL
    const DepthStencilSurface* ds = device().depth_stencil("ds");
    EXPECT_EQ(ds->stencil(0, 1), 7u);
    // D24: round(0.25 * (2^24 - 1)) = round(4194303.75) = 4194304
    EXPECT_EQ(ds->stored_depth(0, 1), 4194304u);
    refused_with("Clear { TARGET DEPTH } 0 1 0", "unknown name 'DEPTH'");
    refused_with("Clear {} 0 1 0", "an empty tuple clears nothing");
    refused_with("Clear 8 0 1 0", "flags 8 are not D3DCLEAR_TARGET/ZBUFFER/STENCIL");
    refused_with("Clear ZBUFFER 0 1.5 0", "z outside [0, 1]");
    refused_with("Clear TARGET 0 1", "expects at least 4 arguments (flags color z stencil [{ x1 y1 x2 y2 }...]), got 3");
}

TEST_F(Replay, PresentCountsAndWritesFramesAndTimesThem) {
    const ReplayResult r = ok("CreateDevice 2 1 A8R8G8B8\n"
                              "BeginScene\n"
                              "Clear TARGET 0xFF00FF00 1 0\n"
                              "EndScene\n"
                              "Present\n"
                              "# a comment is not a call\n"
                              "Clear TARGET 0x80FF0000 1 0\n"
                              "Present\n"
                              "Clear TARGET 0 1 0\n");
    EXPECT_EQ(device().frames_presented(), 2u);
    EXPECT_EQ(r.calls, 8u);
    ASSERT_EQ(r.frames.size(), 2u);
    EXPECT_EQ(r.frames[0].calls, 5u);
    EXPECT_EQ(r.frames[1].calls, 2u);
    EXPECT_GE(r.frames[0].seconds, 0.0);
    EXPECT_GE(r.seconds, r.frames[0].seconds + r.frames[1].seconds);
    EXPECT_EQ(r.statistics.draws, 0u);
    const Image f0 = read_image(path("frame_0000.png"));
    const Image f1 = read_image(path("frame_0001.png"));
    EXPECT_EQ(f0.rgba, (std::vector<float>{0, 1, 0, 1, 0, 1, 0, 1}));
    EXPECT_FLOAT_EQ(f1.rgba[0], 1.0f);
    EXPECT_FLOAT_EQ(f1.rgba[3], 128.0f / 255);
    EXPECT_FALSE(fs::exists(path("frame_0002.png")));
}

TEST_F(Replay, SceneAndPresentErrors) {
    refused_with("Present", "Present: no device (CreateDevice) and so no back buffer");
    refused_with("EndScene", "EndScene: without BeginScene");
    ok("BeginScene\n");
    refused_with("BeginScene", "already inside BeginScene/EndScene");
    refused_with("Present 1", "Present: expects 0 arguments (no arguments), got 1");
    EXPECT_EQ(device().frames_presented(), 0u);
}

TEST_F(Replay, SaveSurfaceWritesRelativeToTheOutputFolder) {
    ok("CreateRenderTarget rt 1 1 A8R8G8B8\n"
       "SetRenderTarget 0 rt\n"
       "Clear TARGET 0xFF0000FF 1 0\n"
       "SaveSurface rt \"saved.png\"\n"
       "SaveSurface rt \"sub/../also.exr\"\n");
    EXPECT_EQ(read_image(path("saved.png")).rgba, (std::vector<float>{0, 0, 1, 1}));
    EXPECT_EQ(read_image(path("also.exr")).rgba, (std::vector<float>{0, 0, 1, 1}));
    refused_with("SaveSurface rt \"x.unknown\"", "SaveSurface: ");
    refused_with("SaveSurface nothing \"n.png\"", "'nothing' is not a surface or texture");
    refused_with("SaveSurface rt saved2", "argument 2 (file): expected a string");
}

// SaveSurface of a depth/stencil surface: depth as float (.exr), stencil as the integer value in
// an 8-bit .png. Clear to z 0.25 (exact in D24: round(0.25 * (2^24-1)) / (2^24-1) is 0.25 to
// float precision) and stencil 7.
TEST_F(Replay, SaveSurfaceWritesDepthAndStencil) {
    ok("CreateDepthStencilSurface ds 2 1 D24S8\n"
       "CreateRenderTarget rt 2 1 A8R8G8B8\n"
       "SetRenderTarget 0 rt\n"
       "SetDepthStencilSurface ds\n"
       "Clear { ZBUFFER STENCIL } 0 0.25 7\n"
       "SaveSurface ds \"depth.exr\"\n"
       "SaveSurface ds \"stencil.png\"\n");
    const Image depth = read_image(path("depth.exr"));
    ASSERT_EQ(depth.rgba.size(), 8u);
    for (unsigned i = 0; i < 2; ++i)
        EXPECT_NEAR(depth.rgba[i * 4], 0.25f, 1e-7f);
    EXPECT_EQ(depth.rgba[3], 1.0f);
    const Image stencil = read_image(path("stencil.png"));
    ASSERT_EQ(stencil.rgba.size(), 8u);
    EXPECT_EQ(std::lround(stencil.rgba[0] * 255.0f), 7);
    EXPECT_EQ(std::lround(stencil.rgba[4] * 255.0f), 7);
    ok("CreateDepthStencilSurface d16 1 1 D16\n");
    refused_with("SaveSurface d16 \"s.png\"", "'d16' has no stencil");
    refused_with("SaveSurface ds \"d.dds\"", "depth to .exr or .raw, stencil to .png or .tga");
    refused_with("SaveSurface ds \"d.exr\" 1", "'ds' has no level 1 face 0");
}

// SaveSurface's level and face: level 1 (2x1) of a 4x2 texture filled with known bytes, and a
// cube face by name.
TEST_F(Replay, SaveSurfaceWritesALevelAndAFace) {
    ok("CreateTexture t 4 2 2 A8R8G8B8\n"
       "LockRect t 1 u32[ 0xFF336699 0x80FF0000 ]\n"
       "CreateCubeTexture c 1 1 A8R8G8B8\n"
       "LockRect c NEGATIVE_Y 0 u32[ 0xFF00FF00 ]\n"
       "SaveSurface t \"level1.png\" 1\n"
       "SaveSurface c \"face3.png\" 0 NEGATIVE_Y\n"
       "SaveSurface c \"face0.png\" 0 0\n");
    const Image level = read_image(path("level1.png"));
    ASSERT_EQ(level.width, 2u);
    ASSERT_EQ(level.height, 1u);
    const std::vector<float> expected{0x33 / 255.0f, 0x66 / 255.0f, 0x99 / 255.0f, 1.0f,
                                      1.0f, 0.0f, 0.0f, 0x80 / 255.0f};
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(level.rgba[i], expected[i], 1e-6f) << i;
    EXPECT_EQ(read_image(path("face3.png")).rgba, (std::vector<float>{0, 1, 0, 1}));
    EXPECT_EQ(read_image(path("face0.png")).rgba, (std::vector<float>{0, 0, 0, 0}));
    refused_with("SaveSurface t \"x.png\" 2", "'t' has no level 2 face 0");
    refused_with("SaveSurface t \"x.png\" 0 1", "'t' has no level 0 face 1");
    ok("CreateRenderTarget rt 1 1 A8R8G8B8\n");
    refused_with("SaveSurface rt \"x.png\" 1", "'rt' has no level 1 face 0");
}

// SaveSurface writes inside the output folder only: absolute paths, `..` out of it and symbolic
// links leading out are refused with the call's line, and nothing is written.
TEST_F(Replay, SaveSurfaceStaysInsideTheOutputFolder) {
    ok("CreateRenderTarget rt 1 1 A8R8G8B8\n");
    const fs::path outside = fs::path(path("")).parent_path().parent_path() /
                             ("sm2_outside_" + std::to_string(getpid()));
    fs::create_directories(outside);
    fs::create_directory_symlink(outside, path("link"));
    refused_with("SaveSurface rt \"" + (outside / "abs.png").string() + "\"", "is an absolute path");
    refused_with("SaveSurface rt \"../escape.png\"", "outside");
    refused_with("SaveSurface rt \"link/escape.png\"", "outside");
    EXPECT_FALSE(fs::exists(outside / "abs.png"));
    EXPECT_FALSE(fs::exists(fs::path(path("")).parent_path().parent_path() / "escape.png"));
    EXPECT_FALSE(fs::exists(outside / "escape.png"));
    fs::remove_all(outside);
}

// LoadTexture reads inside the stream's folder (or the wider read root) only.
TEST_F(Replay, LoadTextureStaysInsideTheReadRoot) {
    Image image;
    image.width = image.height = 1;
    image.rgba = {0, 1, 0, 1};
    const fs::path sibling = fs::path(path("")).parent_path().parent_path() /
                             ("sm2_sibling_" + std::to_string(getpid()));
    fs::create_directories(sibling);
    write_image(image, (sibling / "tex.png").string());
    fs::create_symlink(sibling / "tex.png", path("link.png"));
    const std::string up = "../" + sibling.filename().string() + "/tex.png";
    refused_with("LoadTexture a \"/etc/passwd\"", "argument 2 (file): '/etc/passwd' is an absolute path");
    refused_with("LoadTexture b \"" + up + "\"", "outside");
    refused_with("LoadTexture c \"link.png\"", "outside");
    EXPECT_FALSE(device().has_resource("a") || device().has_resource("b") || device().has_resource("c"));

    // --read-root widens the root to the parent folder: the same paths load.
    Device wide_device;
    ReplayOptions options = replay_options();
    options.root_dir = sibling.parent_path().string();
    Replayer wide(wide_device, options);
    auto parsed = cs::parse_text("sm2cs 1\nLoadTexture b \"" + up + "\"\nLoadTexture c \"link.png\"\n");
    ASSERT_TRUE(parsed.ok());
    const ReplayResult r = wide.replay(*parsed.stream);
    EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].to_string());
    ASSERT_NE(wide_device.surface("b"), nullptr);
    EXPECT_EQ(wide_device.surface("c")->read(0, 0), (Float4{0, 1, 0, 1}));
    fs::remove_all(sibling);
}

// Side files likewise: the parse error names the line and column of the '@'.
TEST_F(Replay, SideFilesStayInsideTheStreamsFolder) {
    cs::TextOptions text;
    text.file_name = "t.sm2cs";
    text.base_dir = path("");
    auto absolute = cs::parse_text("sm2cs 1\nLock vb 0 @\"/etc/passwd\"\n", text);
    ASSERT_FALSE(absolute.ok());
    EXPECT_EQ(absolute.error->to_string(),
              "t.sm2cs:2:11: error: cannot read side file '/etc/passwd': '/etc/passwd' is an absolute path; streams "
              "may name files only relative to their folder");
    auto up = cs::parse_text("sm2cs 1\nCreateVertexBuffer vb 4\n\nLock vb 0 @\"../../etc/passwd\"\n", text);
    ASSERT_FALSE(up.ok());
    EXPECT_EQ(up.error->line, 4u);
    EXPECT_NE(up.error->message.find("outside"), std::string::npos) << up.error->message;
    // A folder and a FIFO are refused at once (a FIFO with no writer would block a plain open).
    fs::create_directory(path("folder"));
    ASSERT_EQ(mkfifo(path("fifo").c_str(), 0600), 0);
    auto folder = cs::parse_text("sm2cs 1\nLock vb 0 @\"folder\"\n", text);
    ASSERT_FALSE(folder.ok());
    EXPECT_EQ(folder.error->message, "cannot read side file 'folder': is a directory");
    auto fifo = cs::parse_text("sm2cs 1\nLock vb 0 @\"fifo\"\n", text);
    ASSERT_FALSE(fifo.ok());
    EXPECT_EQ(fifo.error->message, "cannot read side file 'fifo': is a FIFO (named pipe), not a regular file");
    refused_with("LoadTexture t \"fifo\"", "is a FIFO");
    refused_with("LoadTexture t \"folder\"", "is a directory");
}

// Resources count against DeviceOptions::memory_limit: past it a creation is refused with
// D3DERR_OUTOFVIDEOMEMORY before anything is allocated, the replay goes on, Release gives back.
TEST(ReplayMemory, ResourcesPastTheLimitAreOutOfVideoMemory) {
    DeviceOptions options;
    options.memory_limit = 1 << 20;  // 1 MiB
    Device device(options);
    ReplayOptions replay_options;
    replay_options.file_name = "m.sm2cs";
    auto parsed = cs::parse_text(
        "sm2cs 1\n"
        "CreateTexture big 1024 1024 1 A8R8G8B8\n"       // 4 MiB: refused
        "CreateTexture t 256 256 1 A8R8G8B8\n"           // 256 KiB
        "CreateVertexBuffer vb 600000\n"
        "CreateRenderTarget rt 256 256 A8R8G8B8\n"       // 256 KiB more: refused
        "Release vb\n"
        "CreateRenderTarget rt 256 256 A8R8G8B8\n"       // fits now
        "CreateVolumeTexture v 512 512 512 1 A32B32G32R32F\n"  // 2 GiB: refused, not allocated
        "CreateCubeTexture c 4096 0 A32B32G32R32F\n");  // 6 faces x 341 MiB: refused
    ASSERT_TRUE(parsed.ok());
    const ReplayResult r = replay(device, *parsed.stream, replay_options);
    ASSERT_EQ(r.diagnostics.size(), 4u);
    EXPECT_EQ(r.diagnostics[0].to_string(),
              "m.sm2cs:2: D3DERR_OUTOFVIDEOMEMORY: CreateTexture: 'big' needs 4194304 bytes; 0 of the 1048576-byte "
              "memory limit are in use");
    EXPECT_EQ(r.diagnostics[1].to_string(),
              "m.sm2cs:5: D3DERR_OUTOFVIDEOMEMORY: CreateRenderTarget: 'rt' needs 262144 bytes; 862144 of the "
              "1048576-byte memory limit are in use");
    EXPECT_EQ(r.diagnostics[2].line, 8u);
    EXPECT_EQ(r.diagnostics[2].code, CallError::OutOfVideoMemory);
    EXPECT_EQ(r.diagnostics[3].line, 9u);
    EXPECT_EQ(r.diagnostics[3].code, CallError::OutOfVideoMemory);
    EXPECT_FALSE(device.has_resource("big"));
    EXPECT_TRUE(device.has_resource("rt"));
    EXPECT_EQ(device.memory_used(), 2u * 256 * 256 * 4);
}

// A draw of the largest vertex count D3D9 allows (MaxPrimitiveCount triangles) needs gigabytes of
// working memory: refused with E_OUTOFMEMORY against the memory limit, before any allocation.
TEST(ReplayMemory, DrawsPastTheLimitAreOutOfMemory) {
    DeviceOptions options;
    options.memory_limit = uint64_t{1} << 30;
    Device device(options);
    ReplayOptions replay_options;
    replay_options.file_name = "d.sm2cs";
    replay_options.assembler = runtime::stream_assembler();
    auto parsed = cs::parse_text(
        "sm2cs 1\n"
        "CreateDevice 4 4 A8R8G8B8\n"
        "CreateVertexBuffer vb 48\n"
        "CreateVertexDeclaration decl { 0 0 FLOAT4 DEFAULT POSITION 0 }\n"
        "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
        "SetVertexDeclaration decl\n"
        "SetVertexShader vs\n"
        "SetStreamSource 0 vb 0 16\n"
        "BeginScene\n"
        "DrawPrimitive TRIANGLELIST 0 5592405\n"
        "DrawPrimitiveUP TRIANGLELIST 5592405 16 f32[ 0 0 0 1 ]\n"
        "DrawPrimitive TRIANGLELIST 0 1\n"
        "EndScene\n");
    ASSERT_TRUE(parsed.ok()) << parsed.error->to_string();
    const ReplayResult r = replay(device, *parsed.stream, replay_options);
    ASSERT_EQ(r.diagnostics.size(), 2u);
    EXPECT_EQ(r.diagnostics[0].to_string(),
              "d.sm2cs:14: E_OUTOFMEMORY: DrawPrimitive: 16777215 vertices need about 4294967040 bytes of working "
              "memory, more than the 1073741824-byte memory limit");
    EXPECT_EQ(r.diagnostics[1].line, 15u);
    EXPECT_EQ(r.diagnostics[1].code, CallError::OutOfMemory);
    EXPECT_EQ(device.statistics().draws, 1u);  // the small draw after them ran
}

// ---------------------------------------------------------------------------------------------
// StretchRect

TEST_F(Replay, StretchRectPointDoublesEachTexel) {
    ok("CreateRenderTarget src 2 1 A8R8G8B8\n"
       "LockRect src 0 u32[ 0xFF0000FF 0xFFFF0000 ]\n"
       "CreateRenderTarget dst 4 2 A8R8G8B8\n"
       "StretchRect src dst POINT\n");
    // destination column x samples source texel floor((x + 1/2) * 2 / 4): 0, 0, 1, 1
    const std::vector<uint8_t> blue = {0xFF, 0, 0, 0xFF}, red = {0, 0, 0xFF, 0xFF};
    std::vector<uint8_t> row;
    for (const auto* t : {&blue, &blue, &red, &red}) row.insert(row.end(), t->begin(), t->end());
    std::vector<uint8_t> expected = row;
    expected.insert(expected.end(), row.begin(), row.end());
    EXPECT_EQ(bytes_of(device().surface("dst")), expected);
}

TEST_F(Replay, StretchRectLinearHalvesByAveragingTwoByTwo) {
    // Source L8 4x2; destination 2x1: pixel x samples at u = 2x + 1, v = 1: the average of a 2x2 block.
    ok("CreateTexture src 4 2 1 L8\n"
       "LockRect src 0 u8[ 0 100 200 100   100 0 100 52 ]\n"
       "CreateRenderTarget dst 2 1 A8R8G8B8\n"
       "StretchRect src dst LINEAR\n");
    // (0 + 100 + 100 + 0) / 4 = 50; (200 + 100 + 100 + 52) / 4 = 113; L8 reads alpha 1
    EXPECT_EQ(bytes_of(device().surface("dst")), (std::vector<uint8_t>{50, 50, 50, 255, 113, 113, 113, 255}));
}

TEST_F(Replay, StretchRectConvertsFormats) {
    ok("CreateRenderTarget src 1 1 A8R8G8B8\n"
       "LockRect src 0 u32[ 0x80FF8000 ]\n"
       "CreateRenderTarget f 1 1 A32B32G32R32F\n"
       "CreateTexture rgb 1 1 1 R5G6B5 RENDERTARGET\n"
       "StretchRect src f\n"
       "StretchRect src rgb D3DTEXF_LINEAR\n");
    EXPECT_EQ(device().surface("f")->read(0, 0), (Float4{1.0f, 128.0f / 255, 0.0f, 128.0f / 255}));
    // R5G6B5: r 31, g round(128/255 * 63) = round(31.62) = 32, b 0 -> 0xF800 | 32 << 5 = 0xFC00
    EXPECT_EQ(bytes_of(device().surface("rgb")), (std::vector<uint8_t>{0x00, 0xFC}));
}

TEST_F(Replay, StretchRectErrors) {
    ok("CreateRenderTarget rt 2 2 A8R8G8B8\n"
       "CreateRenderTarget rt2 2 2 A8R8G8B8\n"
       "CreateTexture tex 2 2 1 A8R8G8B8\n"
       "CreateDepthStencilSurface ds 2 2 D16\n"
       "SetRenderTarget 0 rt2\n"
       "Clear TARGET 0xFF112233 1 0\n");
    refused_with("StretchRect rt rt", "source and destination are the same surface");
    refused_with("StretchRect rt tex", "'tex' is not a render target");
    refused_with("StretchRect ds rt", "'ds' is not a render target or 2D texture");
    refused_with("StretchRect rt rt2 ANISOTROPIC", "filter 3 is not NONE, POINT or LINEAR");
    refused_with("StretchRect rt rt2 BLURRY", "unknown name 'BLURRY'");
    refused_with("StretchRect missing rt2", "no resource named 'missing'");
    const std::vector<uint8_t> texel = {0x33, 0x22, 0x11, 0xFF};
    std::vector<uint8_t> expected;
    for (int i = 0; i < 4; ++i) expected.insert(expected.end(), texel.begin(), texel.end());
    EXPECT_EQ(bytes_of(device().surface("rt2")), expected);
}

// ---------------------------------------------------------------------------------------------
// Shapes of arguments, and diagnostics

TEST_F(Replay, DiagnosticsNameFileLineCallAndGoOn) {
    refused("CreateDevice 2 2 A8R8G8B8\n"      // 2
            "CreateVertexBuffer vb0\n"         // 3
            "CreateVertexBuffer vb1 \"12\"\n"  // 4
            "CreateVertexBuffer vb2 -4\n"      // 5
            "CreateVertexBuffer vb3 16\n"      // 6
            "CreateVertexBuffer vb3 16\n"      // 7
            "CreateTexture t 4 4 1 A8R8G8B9\n" // 8
            "CreateTexture t 4 4 1 A8R8G8B8 SHINY\n"    // 9
            "Clear TARGET 0xFF0000FF 1 0\n",   // 10
            {
                "t.sm2cs:3: D3DERR_INVALIDCALL: CreateVertexBuffer: expects 2 arguments (name length), got 1",
                "t.sm2cs:4: D3DERR_INVALIDCALL: CreateVertexBuffer: argument 2 (length): expected an integer, got a "
                "string \"12\"",
                "t.sm2cs:5: D3DERR_INVALIDCALL: CreateVertexBuffer: argument 2 (length): -4 is not an unsigned 32-bit "
                "integer",
                "t.sm2cs:7: D3DERR_INVALIDCALL: CreateVertexBuffer: a resource named 'vb3' already exists",
                "t.sm2cs:8: D3DERR_INVALIDCALL: CreateTexture: argument 5 (format): unknown format 'A8R8G8B9'",
                "t.sm2cs:9: D3DERR_INVALIDCALL: CreateTexture: argument 6 (usage or pool): expected RENDERTARGET, "
                "DYNAMIC or a pool (DEFAULT, MANAGED, SYSTEMMEM, SCRATCH), got a name 'SHINY'",
            });
    EXPECT_TRUE(device().has_resource("vb3"));
    EXPECT_FALSE(device().has_resource("vb0"));
    EXPECT_FALSE(device().has_resource("t"));
    EXPECT_EQ(bytes_of(device().surface("backbuffer"))[2], 0x00);  // R of 0xFF0000FF
    EXPECT_EQ(bytes_of(device().surface("backbuffer"))[0], 0xFF);  // B
}

TEST_F(Replay, VertexDeclarationTuples) {
    ok("CreateVertexDeclaration d { 0 0 D3DDECLTYPE_FLOAT3 D3DDECLMETHOD_DEFAULT D3DDECLUSAGE_POSITION 0 } "
       "{ 1 0 FLOAT2 DEFAULT TEXCOORD 3 }\n");
    EXPECT_TRUE(device().has_resource("d"));
    refused_with("CreateVertexDeclaration e { 0 0 FLOAT5 DEFAULT POSITION 0 }",
                 "argument 2 (element 1): field 3 (type): unknown name 'FLOAT5'");
    refused_with("CreateVertexDeclaration e { 0 0 FLOAT3 DEFAULT POSITION }",
                 "argument 2 (element 1): a vertex element has 6 fields (stream offset type method usage usage_index), "
                 "got 5");
    refused_with("CreateVertexDeclaration e { 0 70000 FLOAT3 DEFAULT POSITION 0 }",
                 "argument 2 (element 1): field 2 (offset): 70000 is out of range (0 to 65535)");
    refused_with("CreateVertexDeclaration e { 0 0 FLOAT3 DEFAULT POSITION 0 } 12",
                 "argument 3 (element 2): expected a tuple");
    refused_with("CreateVertexDeclaration e", "CreateVertexDeclaration: ");
    refused_with("CreateVertexDeclaration e { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 FLOAT3 DEFAULT POSITION 0 }",
                 "CreateVertexDeclaration: ");
    EXPECT_FALSE(device().has_resource("e"));
}

TEST_F(Replay, EnumArgumentsOfDrawsAreCheckedBeforeTheDevice) {
    ok("CreateDevice 2 2 A8R8G8B8\n");
    refused_with("DrawPrimitive TRIANGLEBLOB 0 1",
                 "argument 1 (primitive type): unknown name 'TRIANGLEBLOB' (expected one of POINTLIST, LINELIST, "
                 "LINESTRIP, TRIANGLELIST, TRIANGLESTRIP, TRIANGLEFAN)");
    refused_with("DrawPrimitive 4 0 1", "argument 1 (primitive type): expected a name, got an integer 4");
    refused_with("DrawIndexedPrimitive TRIANGLELIST 0x80000000 0 3 0 1", "2147483648 is not a signed 32-bit integer");
    refused_with("DrawIndexedPrimitiveUP TRIANGLELIST 0 3 1 u16[ 0 1 2 ] A8R8G8B8 f32[ 0 ] 4",
                 "argument 6 (index format): expected INDEX16 or INDEX32, got 'A8R8G8B8'");
    refused_with("DrawPrimitiveUP TRIANGLELIST 1 12", "expects 4 arguments");
}

TEST_F(Replay, UnknownCallsAndBinaryStreamsUseRecordNumbers) {
    Replayer replayer(device(), replay_options());
    cs::Statement st;
    st.name = "Frobnicate";
    st.line = 7;
    EXPECT_FALSE(replayer.execute(st));
    ASSERT_EQ(replayer.diagnostics().size(), 1u);
    EXPECT_EQ(replayer.diagnostics()[0].to_string(), "t.sm2cs:7: D3DERR_INVALIDCALL: Frobnicate: unknown call");

    // A binary stream has no lines: diagnostics count records (comments included).
    auto parsed = cs::parse_text("sm2cs 1\n# one\nCreateDevice 2 2 A8R8G8B8\nRelease nothing\n");
    ASSERT_TRUE(parsed.ok());
    auto unpacked = cs::unpack(cs::pack(*parsed.stream));
    ASSERT_TRUE(unpacked.ok());
    ReplayOptions options;
    options.file_name = "t.sm2cb";
    const ReplayResult r = replay(device(), *unpacked.stream, options);
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics[0].to_string(), "t.sm2cb: record 3: D3DERR_INVALIDCALL: Release: no resource named 'nothing'");
    EXPECT_EQ(r.calls, 2u);
    EXPECT_EQ(r.refused, 1u);
}

TEST_F(Replay, TheDeviceStaysUsableAfterEveryKindOfError) {
    const ReplayResult r = run("CreateDevice 2 1 A8R8G8B8\n"
                               "SetRenderState CULLMODE\n"
                               "SetTexture 0 ghost\n"
                               "SetVertexShaderConstantF 300 f32[ 1 1 1 1 ]\n"
                               "CreatePixelShader p asm<<END\nps_2_0\nmov oC0, v9\nEND\n"
                               "LockRect backbuffer 0 u8[ 1 ]\n"
                               "Clear TARGET 0xFF00FF00 1 0\n"
                               "Present\n");
    EXPECT_EQ(r.diagnostics.size(), 5u);
    EXPECT_EQ(r.frames.size(), 1u);
    EXPECT_EQ(device().frames_presented(), 1u);
    EXPECT_EQ(bytes_of(device().surface("backbuffer")), (std::vector<uint8_t>{0, 0xFF, 0, 0xFF, 0, 0xFF, 0, 0xFF}));
}

}  // namespace
}  // namespace sm2::runtime
