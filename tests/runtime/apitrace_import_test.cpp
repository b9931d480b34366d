// apitrace D3D9 traces to command streams: the three captures of tests/data/traces, with what
// their reference dumps (`apitrace dump -v`, independent of this code) say about them.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <snappy.h>

#include "sm2/runtime/apitrace_import.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime::apitrace {
namespace {

std::string trace_path(const std::string& name) { return std::string(SM2_SOURCE_DIR) + "/tests/data/traces/" + name; }

ImportResult import_file(const std::string& name) {
    std::optional<Error> error;
    auto reader = Reader::open_file(trace_path(name + ".trace"), error);
    EXPECT_TRUE(reader) << (error ? error->to_string() : "");
    if (!reader) return {};
    return import_d3d9(*reader);
}

// Call name -> (first call number, count), from the reference dump.
std::map<std::string, std::pair<uint64_t, uint64_t>> dump_calls(const std::string& name) {
    std::ifstream in(trace_path(name + ".dump.txt"));
    std::map<std::string, std::pair<uint64_t, uint64_t>> calls;
    const std::regex start(R"(^(\d+) ([A-Za-z_][A-Za-z0-9_:]*)\()");
    std::smatch m;
    for (std::string line; std::getline(in, line);) {
        if (!std::regex_search(line, m, start)) continue;
        auto [it, fresh] = calls.try_emplace(m[2].str(), std::stoull(m[1].str()), 0);
        ++it->second.second;
    }
    return calls;
}

std::map<std::string, size_t> statement_counts(const cs::Stream& stream) {
    std::map<std::string, size_t> counts;
    for (const auto& st : stream.statements)
        if (st.kind == cs::Statement::Kind::Call) ++counts[st.name];
    return counts;
}

// shader_scene: every call is either imported or has nothing to replay; the stream replays on the
// Device with no refusal and presents the program's two frames.
TEST(ApitraceImport, ShaderSceneImportsEveryCallAndReplays) {
    const ImportResult r = import_file("shader_scene");
    ASSERT_FALSE(r.error) << r.error->to_string();
    EXPECT_EQ(r.report.calls, 174u);
    EXPECT_EQ(r.report.skipped, 0u) << r.report.to_string();
    EXPECT_TRUE(r.report.skipped_kinds.empty());
    // Accepted with no statement: Direct3DCreate9, the 2 Lock/Unlock pairs of the vertex buffers
    // (their memcpy is the upload), GetSurfaceLevel, GetRenderTarget, per frame GetBackBuffer +
    // CreateOffscreenPlainSurface(SYSTEMMEM) + GetRenderTargetData + GetDesc + LockRect(READONLY) +
    // UnlockRect, and the Releases that leave an object alive or end a read-back surface.
    EXPECT_EQ(r.report.imported, 147u);
    EXPECT_EQ(r.report.accepted, 27u);
    EXPECT_EQ(r.report.imported + r.report.accepted, 174u);

    // As many statements of each kind as the reference dump has calls.
    const auto dump = dump_calls("shader_scene");
    const auto counts = statement_counts(r.stream);
    for (const char* name : {"SetRenderState", "SetPixelShaderConstantF", "SetSamplerState", "SetVertexShader",
                             "SetVertexDeclaration", "SetPixelShader", "DrawPrimitiveUP", "SetStreamSource", "SetViewport",
                             "SetVertexShaderConstantF", "SetTexture", "SetRenderTarget", "DrawPrimitive", "Clear",
                             "CreateVertexShader", "CreateVertexDeclaration", "CreatePixelShader", "CreateVertexBuffer",
                             "CreateTexture", "BeginScene", "EndScene", "Present"}) {
        EXPECT_EQ(counts.count(name) ? counts.at(name) : 0, dump.at(std::string("IDirect3DDevice9::") + name).second) << name;
    }
    EXPECT_EQ(counts.at("Lock"), dump.at("memcpy").second);  // 2 uploads
    EXPECT_EQ(counts.at("CreateDevice"), 1u);

    // 1 CreateDevice: BackBufferWidth = 256, BackBufferHeight = 256, D3DFMT_X8R8G8B8, auto depth D24S8.
    const cs::Stream& s = r.stream;
    ASSERT_GE(s.statements.size(), 2u);
    EXPECT_EQ(cs::to_text(cs::Stream{1, {s.statements[0]}}), "sm2cs 1\nCreateDevice 256 256 X8R8G8B8 D24S8\n");
    // 2 CreateVertexShader(ppShader = &0x3b0710): the token blob, named by its pointer.
    const auto& vs = s.statements[1];
    EXPECT_EQ(vs.name, "CreateVertexShader");
    EXPECT_EQ(vs.arguments.at(0).text, "vs_3b0710");
    uint32_t version = 0;
    std::memcpy(&version, vs.arguments.at(1).bytes.data(), 4);
    EXPECT_EQ(version, 0xFFFE0200u);
    // 13 memcpy(dest = 0x3b6e10, src = blob(432)) after 12 Lock(this = 0x3b6c50, OffsetToLock = 0):
    // "Lock vb_3b6c50 0" with the 432 bytes.
    const cs::Statement* upload = nullptr;
    for (const auto& st : s.statements)
        if (st.name == "Lock" && !upload) upload = &st;
    ASSERT_TRUE(upload);
    EXPECT_EQ(upload->arguments.at(0).text, "vb_3b6c50");
    EXPECT_EQ(upload->arguments.at(1).integer, 0);
    EXPECT_EQ(upload->arguments.at(2).bytes.size(), 432u);
    // 27 Clear(Flags = D3DCLEAR_TARGET, Color = 4279246912, Z = 1, Stencil = 0) and
    // 25 SetRenderTarget(0, pRenderTarget = 0x3b7560), the level-0 surface of texture 0x3b7220.
    const std::string text = cs::to_text(s);
    EXPECT_NE(text.find("\nClear TARGET 0xFF102040 1.0 0\n"), std::string::npos) << text;  // 4279246912
    // 37 Clear(Flags = D3DCLEAR_TARGET | D3DCLEAR_STENCIL, Color = 4278190080, Z = 1, Stencil = 0)
    EXPECT_NE(text.find("\nClear { TARGET STENCIL } 0xFF000000 1.0 0\n"), std::string::npos);
    EXPECT_NE(text.find("\nSetRenderTarget 0 tex_3b7220\n"), std::string::npos);
    EXPECT_NE(text.find("\nSetRenderTarget 0 backbuffer\n"), std::string::npos);  // 35: 0x344740 from GetRenderTarget
    EXPECT_NE(text.find("\nSetRenderState STENCILFUNC EQUAL\n"), std::string::npos);
    EXPECT_NE(text.find("\nSetSamplerState 0 MINFILTER LINEAR\n"), std::string::npos);

    // The stream replays: no refusal, 2 frames, 10 draws.
    Device device;
    const ReplayResult replayed = replay(device, s);
    for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
    EXPECT_EQ(replayed.frames.size(), 2u);
    EXPECT_EQ(replayed.statistics.draws, 10u);
    // And it survives the binary form unchanged.
    auto unpacked = cs::unpack(cs::pack(s));
    ASSERT_TRUE(unpacked.ok());
    EXPECT_EQ(cs::to_text(*unpacked.stream), text);
}

// mixed_states uses calls the vocabulary lacks (state blocks, UpdateSurface, ColorFill, clears
// with rectangles): each such kind is reported once, with the number of its first call and how
// many there were, as the reference dump lists them. Its 22 SetFVF and 19 SetTextureStageState
// calls (the dump's counts) are imported.
TEST(ApitraceImport, UnsupportedKindsAreReportedOnceWithTheirFirstCall) {
    struct Expect {
        const char* trace;
        uint64_t imported, accepted, skipped;
        std::vector<std::string> kinds;  // skipped for "not in the stream vocabulary yet"
    };
    const Expect cases[] = {
        {"mixed_states", 139 + 41, 50, 79 - 41,
         {"IDirect3DDevice9::CreateStateBlock", "IDirect3DDevice9::BeginStateBlock", "IDirect3DDevice9::EndStateBlock",
          "IDirect3DStateBlock9::Apply", "IDirect3DDevice9::UpdateSurface", "IDirect3DDevice9::ColorFill",
          "IDirect3DStateBlock9::Capture"}},
    };
    for (const auto& e : cases) {
        const ImportResult r = import_file(e.trace);
        ASSERT_FALSE(r.error);
        const auto dump = dump_calls(e.trace);
        EXPECT_EQ(r.report.imported, e.imported) << e.trace << "\n" << r.report.to_string();
        EXPECT_EQ(r.report.accepted, e.accepted) << e.trace;
        EXPECT_EQ(r.report.skipped, e.skipped) << e.trace;
        EXPECT_EQ(r.report.imported + r.report.accepted + r.report.skipped, r.report.calls);
        uint64_t total = 0;
        for (const auto& k : r.report.skipped_kinds) total += k.count;
        EXPECT_EQ(total, r.report.skipped);
        for (const auto& name : e.kinds) {
            auto it = std::find_if(r.report.skipped_kinds.begin(), r.report.skipped_kinds.end(),
                                   [&](const auto& k) { return k.call == name; });
            ASSERT_NE(it, r.report.skipped_kinds.end()) << e.trace << ": " << name;
            EXPECT_EQ(it->first, dump.at(name).first) << name;
            EXPECT_EQ(it->count, dump.at(name).second) << name;
            EXPECT_EQ(it->reason, "not in the stream vocabulary yet") << name;
        }
    }
    // mixed_states: the 5 SetRenderState calls recorded between BeginStateBlock (call 4) and
    // EndStateBlock (call 10) are not applied; Clear with a rectangle list (48 is the first) and
    // StretchRect to a rectangle (80) are skipped with their reason.
    const ImportResult r = import_file("mixed_states");
    std::map<std::string, ImportReport::Skipped> kinds;
    for (const auto& k : r.report.skipped_kinds) kinds[k.call] = k;
    EXPECT_EQ(kinds.at("IDirect3DDevice9::SetRenderState").first, 5u);
    EXPECT_EQ(kinds.at("IDirect3DDevice9::SetRenderState").count, 5u);
    EXPECT_EQ(kinds.at("IDirect3DDevice9::Clear").first, 48u);
    EXPECT_EQ(kinds.at("IDirect3DDevice9::Clear").reason, "Clear with a rectangle list");
    EXPECT_EQ(kinds.at("IDirect3DDevice9::StretchRect").first, 80u);
    EXPECT_EQ(kinds.at("IDirect3DDevice9::StretchRect").reason, "StretchRect of a rectangle");
    EXPECT_EQ(kinds.count("IDirect3DDevice9::SetFVF"), 0u) << r.report.to_string();
    EXPECT_EQ(kinds.count("IDirect3DDevice9::SetTextureStageState"), 0u) << r.report.to_string();
}

// ff_lit_cube: the fixed-function calls become statements with the values of the reference
// dump; every call but the draws (which need the fixed-function pipeline) replays.
TEST(ApitraceImport, FixedFunctionCallsOfFfLitCubeAreImported) {
    const ImportResult r = import_file("ff_lit_cube");
    ASSERT_FALSE(r.error);
    EXPECT_EQ(r.report.skipped, 0u) << r.report.to_string();
    EXPECT_EQ(r.report.imported, 82u + 58u);  // the 58 fixed-function calls the dump lists
    const auto dump = dump_calls("ff_lit_cube");
    const auto counts = statement_counts(r.stream);
    for (const char* name : {"SetTransform", "SetMaterial", "SetLight", "LightEnable", "SetTextureStageState", "SetFVF"})
        EXPECT_EQ(counts.count(name) ? counts.at(name) : 0, dump.at(std::string("IDirect3DDevice9::") + name).second) << name;
    const std::string text = cs::to_text(r.stream);
    for (const char* line : {
             // 20 SetMaterial(Diffuse 1 1 1 1, Ambient 0.5 0.5 0.5 1, Specular 0.5 0.5 0.5 1, Emissive 0, Power 20)
             "\nSetMaterial { 1.0 1.0 1.0 1.0 } { 0.5 0.5 0.5 1.0 } { 0.5 0.5 0.5 1.0 } { 0.0 0.0 0.0 0.0 } 20.0\n",
             // 23 SetLight(1, D3DLIGHT_POINT, Diffuse 0.2 0.4 1 1, Position -2.5 1 -2.5, Range 10, Attenuation0 0.2, Attenuation1 0.15)
             "\nSetLight 1 POINT { 0.2 0.4 1.0 1.0 } { 0.0 0.0 0.0 0.0 } { 0.0 0.0 0.0 0.0 } { -2.5 1.0 -2.5 } { 0.0 0.0 0.0 } "
             "10.0 0.0 0.2 0.15 0.0 0.0 0.0\n",
             "\nLightEnable 0 TRUE\n",                                     // 22
             "\nSetTextureStageState 0 COLORARG1 DIFFUSE\n",               // 50
             "\nSetTextureStageState 0 COLOROP MODULATE\n",                // 60
             "\nSetTextureStageState 0 ALPHAARG1 TEXTURE\n",               // 64
             "\nSetTextureStageState 1 COLOROP DISABLE\n",                 // 66
             "\nSetFVF { XYZ DIFFUSE }\n",                                 // 53
             "\nSetFVF { XYZ TEX1 NORMAL }\n",                             // 68
         })
        EXPECT_NE(text.find(line), std::string::npos) << line;

    // On the Device: the 3 draws of each frame are refused (no vertex shader: the fixed-function
    // pipeline is not emulated yet); nothing else is.
    Device device;
    const ReplayResult replayed = replay(device, r.stream);
    for (const auto& d : replayed.diagnostics)
        EXPECT_TRUE(d.call == "DrawPrimitive" || d.call == "DrawIndexedPrimitive") << d.to_string();
    EXPECT_EQ(replayed.diagnostics.size(), 3u * 3u);
    EXPECT_EQ(device.fixed_function().fvf, 0x112u);
    EXPECT_EQ(device.fixed_function().enabled_lights, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(device.fixed_function().lights.at(0).direction, (Vector3{-0.5f, -0.6f, 0.7f}));
    // 18 SetTransform(D3DTS_VIEW, {{1, 0, 0, 0}, {0, 0.9486833, -0.3162278, 0}, {-0, 0.3162278,
    // 0.9486833, 0}, {-0, -0, 6.324555, 1}}) (the dump prints 7 digits).
    const Matrix4 view{1, 0, 0, 0, 0, 0.9486833f, -0.3162278f, 0, 0, 0.3162278f, 0.9486833f, 0, 0, 0, 6.324555f, 1};
    for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(device.fixed_function().view[i], view[i], 1e-6) << i;
}

// Texture uploads: LockRect/LockBox of whole levels with their memcpy become LockRect/LockBox
// statements with the level's bytes (these captures' pitches are tight: 64x4 = 256, 16x4 = 64,
// 8x4 = 32 with slices of 256), cube faces named.
TEST(ApitraceImport, TextureUploadsBecomeLockRectAndLockBox) {
    // ff_lit_cube 15 IDirect3DTexture9::LockRect(this = 0x3b05e0, Level = 0, Pitch = 256),
    // 16 memcpy(src = blob(16384)): the checkerboard.
    std::optional<Error> error;
    auto reader = Reader::open_file(trace_path("ff_lit_cube.trace"), error);
    ASSERT_TRUE(reader);
    std::vector<std::byte> recorded;
    while (auto c = reader->next())
        if (c->number == 16) recorded = *c->arg("src")->blob();
    ASSERT_EQ(recorded.size(), 16384u);
    const ImportResult ff = import_file("ff_lit_cube");
    const cs::Statement* lock = nullptr;
    for (const auto& st : ff.stream.statements)
        if (st.name == "LockRect") lock = &st;
    ASSERT_TRUE(lock);
    ASSERT_EQ(lock->arguments.size(), 3u);
    EXPECT_EQ(lock->arguments[0].text, "tex_3b05e0");
    EXPECT_EQ(lock->arguments[1].integer, 0);
    EXPECT_EQ(lock->arguments[2].bytes, recorded);

    // mixed_states 17..33: the six faces of cube 0x3c9a40 (16x16 X8R8G8B8), 36 LockBox of volume
    // 0x3cc1d0 (8x8x4 A8R8G8B8).
    const ImportResult ms = import_file("mixed_states");
    std::vector<std::string> faces;
    size_t box_bytes = 0;
    for (const auto& st : ms.stream.statements) {
        if (st.name == "LockRect" && st.arguments.at(0).text == "cube_3c9a40") {
            faces.push_back(st.arguments.at(1).text);
            EXPECT_EQ(st.arguments.at(3).bytes.size(), 1024u);
        }
        if (st.name == "LockBox" && st.arguments.at(0).text == "vol_3cc1d0") box_bytes = st.arguments.at(2).bytes.size();
    }
    EXPECT_EQ(faces, (std::vector<std::string>{"POSITIVE_X", "NEGATIVE_X", "POSITIVE_Y", "NEGATIVE_Y", "POSITIVE_Z",
                                               "NEGATIVE_Z"}));
    EXPECT_EQ(box_bytes, 8u * 8u * 4u * 4u);
}

// A trace cut inside its event stream: the calls before the cut are imported, and the error
// names the byte where the data ended.
TEST(ApitraceImport, TruncatedTraceStopsWithItsError) {
    std::ifstream in(trace_path("shader_scene.trace"), std::ios::binary);
    const std::string file((std::istreambuf_iterator<char>(in)), {});
    std::string raw;
    ASSERT_TRUE(snappy::Uncompress(file.data() + 6, file.size() - 6, &raw));  // one chunk
    raw.resize(9000);
    std::string compressed;
    snappy::Compress(raw.data(), raw.size(), &compressed);
    std::string cut = "at";
    const auto n = static_cast<uint32_t>(compressed.size());
    for (int i = 0; i < 4; ++i) cut += static_cast<char>((n >> (8 * i)) & 0xFF);
    cut += compressed;
    std::vector<std::byte> bytes(cut.size());
    std::memcpy(bytes.data(), cut.data(), cut.size());
    std::optional<Error> error;
    auto reader = Reader::open(bytes, error);
    ASSERT_TRUE(reader) << error->to_string();
    const ImportResult r = import_d3d9(*reader);
    ASSERT_TRUE(r.error);
    // The cut falls inside a string: 19 of its bytes are missing.
    EXPECT_EQ(r.error->to_string(), "byte 9000 (chunk at file offset 2): unexpected end of the trace (19 bytes missing)");
    EXPECT_GT(r.report.calls, 5u);  // the shaders at least
    EXPECT_EQ(r.stream.statements.at(0).name, "CreateDevice");
}

}  // namespace
}  // namespace sm2::runtime::apitrace
