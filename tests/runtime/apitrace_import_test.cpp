// apitrace D3D9 traces to command streams: the three captures of tests/data/traces, with what
// their reference dumps (`apitrace dump -v`, independent of this code) say about them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <snappy.h>

#include "sm2/runtime/apitrace_import.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/replay.h"
#include "trace_event_writer.h"

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
    // GetDesc + LockRect(READONLY) + UnlockRect, and the Releases that leave an object alive. The
    // read-backs (per frame CreateOffscreenPlainSurface(SYSTEMMEM), GetRenderTargetData and the
    // surface's last Release) are imported.
    EXPECT_EQ(r.report.imported, 153u);
    EXPECT_EQ(r.report.accepted, 21u);
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

// Every call of the three captures is in the stream vocabulary now (device calls, state blocks,
// fixed-function state): nothing is skipped for its kind.
TEST(ApitraceImport, EveryCallKindOfTheCapturesIsImported) {
    struct Expect {
        const char* trace;
        uint64_t imported, accepted, skipped;
        std::vector<std::string> kinds;  // skipped for "not in the stream vocabulary yet"
    };
    const Expect cases[] = {
        {"ff_lit_cube", 91 + 58, 26, 0, {}},  // the 58 fixed-function calls the dump lists, imported
        {"mixed_states", 186 + 41, 41, 0, {}},  // its 22 SetFVF and 19 SetTextureStageState calls too
    };
    for (const auto& e : cases) {
        const ImportResult r = import_file(e.trace);
        ASSERT_FALSE(r.error);
        const auto dump = dump_calls(e.trace);
        EXPECT_EQ(r.report.imported, e.imported) << e.trace << "\n" << r.report.to_string();
        EXPECT_EQ(r.report.accepted, e.accepted) << e.trace;
        EXPECT_EQ(r.report.skipped, e.skipped) << e.trace;
        EXPECT_EQ(r.report.imported + r.report.accepted + r.report.skipped, r.report.calls);
        EXPECT_EQ(r.report.skipped_kinds.size(), e.kinds.size()) << r.report.to_string();
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
    const ImportResult r = import_file("mixed_states");
    std::map<std::string, ImportReport::Skipped> kinds;
    for (const auto& k : r.report.skipped_kinds) kinds[k.call] = k;
    EXPECT_EQ(kinds.count("IDirect3DDevice9::SetFVF"), 0u) << r.report.to_string();
    EXPECT_EQ(kinds.count("IDirect3DDevice9::SetTextureStageState"), 0u) << r.report.to_string();
}

// ff_lit_cube: the fixed-function calls become statements with the values of the reference
// dump; every call but the draws (which need the fixed-function pipeline) replays.
TEST(ApitraceImport, FixedFunctionCallsOfFfLitCubeAreImported) {
    const ImportResult r = import_file("ff_lit_cube");
    ASSERT_FALSE(r.error);
    EXPECT_EQ(r.report.skipped, 0u) << r.report.to_string();
    EXPECT_EQ(r.report.imported, 91u + 58u);  // the 58 fixed-function calls the dump lists
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

    // On the Device: every call runs, the 3 fixed-function draws of each frame included.
    Device device;
    const ReplayResult replayed = replay(device, r.stream);
    for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
    EXPECT_EQ(device.statistics().draws, 3u * 3u);
    EXPECT_EQ(device.fixed_function().fvf, 0x112u);
    EXPECT_EQ(device.fixed_function().enabled_lights, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(device.fixed_function().lights.at(0).direction, (Vector3{-0.5f, -0.6f, 0.7f}));
    // 18 SetTransform(D3DTS_VIEW, {{1, 0, 0, 0}, {0, 0.9486833, -0.3162278, 0}, {-0, 0.3162278,
    // 0.9486833, 0}, {-0, -0, 6.324555, 1}}) (the dump prints 7 digits).
    const Matrix4 view{1, 0, 0, 0, 0, 0.9486833f, -0.3162278f, 0, 0, 0.3162278f, 0.9486833f, 0, 0, 0, 6.324555f, 1};
    for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(device.fixed_function().view[i], view[i], 1e-6) << i;
}

// mixed_states' device calls: one statement per call of each kind the reference dump lists
// (state blocks, clears with rectangle lists, UpdateSurface, ColorFill, StretchRect of
// rectangles, the read-back surfaces), with the dump's arguments.
TEST(ApitraceImport, MixedStatesDeviceCallsBecomeStatements) {
    const ImportResult r = import_file("mixed_states");
    ASSERT_FALSE(r.error);
    const auto dump = dump_calls("mixed_states");
    const auto counts = statement_counts(r.stream);
    const std::pair<const char*, const char*> kinds[] = {
        {"CreateStateBlock", "IDirect3DDevice9::CreateStateBlock"}, {"BeginStateBlock", "IDirect3DDevice9::BeginStateBlock"},
        {"EndStateBlock", "IDirect3DDevice9::EndStateBlock"},       {"Apply", "IDirect3DStateBlock9::Apply"},
        {"Capture", "IDirect3DStateBlock9::Capture"},               {"UpdateSurface", "IDirect3DDevice9::UpdateSurface"},
        {"ColorFill", "IDirect3DDevice9::ColorFill"},               {"StretchRect", "IDirect3DDevice9::StretchRect"},
        {"Clear", "IDirect3DDevice9::Clear"},                       {"GetRenderTargetData", "IDirect3DDevice9::GetRenderTargetData"},
        {"CreateOffscreenPlainSurface", "IDirect3DDevice9::CreateOffscreenPlainSurface"},
    };
    for (const auto& [statement, call] : kinds) EXPECT_EQ(counts.at(statement), dump.at(call).second) << statement;
    // The five SetRenderState calls between BeginStateBlock (4) and EndStateBlock (10) are imported
    // in their place: the replayer records them into the block.
    const std::string text = cs::to_text(r.stream);
    EXPECT_NE(text.find("\nCreateStateBlock sb_3afbb0 ALL\nBeginStateBlock\nSetRenderState SHADEMODE FLAT\n"), std::string::npos);
    EXPECT_NE(text.find("\nSetRenderState DESTBLEND ONE\nEndStateBlock sb_3c8f40\n"), std::string::npos);
    EXPECT_NE(text.find("\nCreateStateBlock sb_3cccb0 PIXELSTATE\n"), std::string::npos);
    // 48 Clear(Count = 2, pRects = {{4, 4, 30, 30}, {34, 34, 60, 60}}, TARGET, 4294918208)
    EXPECT_NE(text.find("\nClear TARGET 0xFFFF4040 1.0 0 { 4 4 30 30 } { 34 34 60 60 }\n"), std::string::npos);
    // 54/58 UpdateSurface of the SYSTEMMEM texture's level 0 into the DEFAULT one's.
    EXPECT_NE(text.find(" 64 64 1 X8R8G8B8 SYSTEMMEM\n"), std::string::npos);
    EXPECT_NE(text.find(" 64 64 1 X8R8G8B8 DEFAULT\n"), std::string::npos);
    EXPECT_NE(text.find(" 0 { 0 0 16 16 } tex_"), std::string::npos);
    EXPECT_NE(text.find(" 0 { 40 8 }\n"), std::string::npos);
    // 73 ColorFill(pRect = {0, 0, 16, 16}, color = 4294967040); 81 StretchRect with both rectangles.
    EXPECT_NE(text.find("\nColorFill rt_3c99d0 { 0 0 16 16 } 0xFFFFFF00\n"), std::string::npos);
    EXPECT_NE(text.find("\nStretchRect rt_3c99d0 { 8 8 32 32 } backbuffer { 192 0 256 64 } LINEAR\n"), std::string::npos);
    EXPECT_NE(text.find("\nStretchRect rt_3c99d0 backbuffer { 128 0 192 64 } POINT\n"), std::string::npos);
    EXPECT_NE(text.find("\nApply sb_3c8f40\n"), std::string::npos);
    EXPECT_NE(text.find("\nCapture sb_3cccb0\n"), std::string::npos);
    EXPECT_NE(text.find("\nRelease sb_3cccb0\n"), std::string::npos);
    auto unpacked = cs::unpack(cs::pack(r.stream));
    ASSERT_TRUE(unpacked.ok());
    EXPECT_EQ(cs::to_text(*unpacked.stream), text);
}

// The frames of mixed_states (all its draws are fixed-function XYZRHW DrawPrimitiveUP) against the
// frames the program read back from Wine's d3d9, pixel class by pixel class:
// * exactly: cell (0,0), three clears with rectangle lists; (2,0), StretchRect POINT of an
//   offscreen render target filled by ColorFill, outside the gouraud triangle drawn into it
//   (vertices (16,2), (30,30), (2,30)); every flat-coloured fixed-function cell: culling (0,1),
//   scissor (2,1), colour write mask (3,1), the cube and volume textures of row 2 (POINT, stage 0
//   SELECTARG1 TEXTURE), the point list (1,3) and the PIXELSTATE state block's MODULATE TFACTOR
//   DIFFUSE quad (3,3);
// * within 1/255: the gouraud-shaded colours, in the triangle of (2,0) and the additive quad of
//   the recorded state block (1,1) (Wine's GL rasterizer interpolates colour in its own fixed
//   point; ours in float, then rounds: 56 and 366 pixels differ by 1);
// * within 1/255 except at most 32 pixels per frame: the wireframe fan (0,3) and the line strip
//   (2,3), whose line pixels follow Wine's GL diamond-exit rule where ours differ at some ends
//   (20 and 31 pixels);
// * (3,0), StretchRect LINEAR of a sub-rectangle: within 3/255 (bilinear weights) where no tap
//   comes within 1.5 texels of the triangle's edges.
TEST(ApitraceImport, MixedStatesFramesMatchWine) {
    const ImportResult imported = import_file("mixed_states");
    ASSERT_FALSE(imported.error);
    std::vector<Surface> frames;
    DeviceOptions options;
    options.output_dir = "frames";  // not written: write_image keeps the surfaces
    options.write_image = [&](const Surface& s, const std::string&) { frames.push_back(s); };
    Device device(options);
    const ReplayResult replayed = replay(device, imported.stream);
    for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
    ASSERT_EQ(frames.size(), 2u);

    // Outward distance of a source texel centre from the triangle (positive: outside).
    const auto outside_by = [](double px, double py) {
        const double v[3][2] = {{16, 2}, {30, 30}, {2, 30}};
        double best = -1e9;
        for (int i = 0; i < 3; ++i) {
            const double* a = v[i];
            const double* b = v[(i + 1) % 3];
            const double* c = v[(i + 2) % 3];
            const double nx = b[1] - a[1], ny = a[0] - b[0], len = std::hypot(nx, ny);
            double d = ((px - a[0]) * nx + (py - a[1]) * ny) / len;
            if (((c[0] - a[0]) * nx + (c[1] - a[1]) * ny) > 0) d = -d;  // orient outward
            best = std::max(best, d);
        }
        return best;
    };
    const auto safe = [&](uint32_t sx, uint32_t sy) { return outside_by(sx + 0.5, sy + 0.5) > 1.5; };

    for (uint32_t f = 0; f < 2; ++f) {
        const Image expected = read_image(trace_path("mixed_states/frame_" + std::to_string(f) + ".png"));
        ASSERT_EQ(expected.width, 256u);
        const auto channel = [](float v) { return static_cast<int>(std::lround(v * 255.0f)); };
        const auto differs = [&](uint32_t x, uint32_t y, int tolerance) {
            const Float4 got = frames[f].read(x, y);
            int worst = 0;
            for (unsigned c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(channel(got[c]) - channel(expected.rgba[(y * 256 + x) * 4 + c])));
            return worst > tolerance;
        };
        uint32_t compared = 0;
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x, ++compared) EXPECT_FALSE(differs(x, y, 0)) << "frame " << f << " " << x << "," << y;
        // (2,0): the whole 32x32 source onto {128 0 192 64}, POINT: texel ((x-128)/2, y/2).
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 128; x < 192; ++x, ++compared)
                EXPECT_FALSE(differs(x, y, safe((x - 128) / 2, y / 2) ? 0 : 1)) << "frame " << f << " " << x << "," << y;
        // The fixed-function cells of rows 1 to 3.
        for (uint32_t cy = 1; cy < 4; ++cy)
            for (uint32_t cx = 0; cx < 4; ++cx) {
                const bool gouraud = cx == 1 && cy == 1, lines = cy == 3 && (cx == 0 || cx == 2);
                uint32_t line_pixels = 0;
                for (uint32_t y = cy * 64; y < cy * 64 + 64; ++y)
                    for (uint32_t x = cx * 64; x < cx * 64 + 64; ++x, ++compared) {
                        if (lines) {
                            line_pixels += differs(x, y, 1) ? 1 : 0;
                            continue;
                        }
                        EXPECT_FALSE(differs(x, y, gouraud ? 1 : 0)) << "frame " << f << " " << x << "," << y;
                    }
                EXPECT_LE(line_pixels, 32u) << "frame " << f << " cell " << cx << "," << cy;
            }
        // (3,0): source {8 8 32 32} onto {192+4f 0 256 64-4f}, LINEAR; outside it the cleared background.
        const uint32_t left = 192 + 4 * f, bottom = 64 - 4 * f, width = 256 - left;
        const auto taps = [](uint32_t d, uint32_t size) {
            const double u = (d + 0.5) * 24.0 / size - 0.5;
            const auto first = static_cast<uint32_t>(std::max(0.0, std::floor(u)));
            return std::pair<uint32_t, uint32_t>{8 + std::min(first, 23u), 8 + std::min(first + 1, 23u)};
        };
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 192; x < 256; ++x) {
                if (x < left || y >= bottom) {
                    ++compared;
                    EXPECT_FALSE(differs(x, y, 0)) << "frame " << f << " " << x << "," << y;
                    continue;
                }
                const auto [x0, x1] = taps(x - left, width);
                const auto [y0, y1] = taps(y, bottom);
                if (!safe(x0, y0) || !safe(x1, y0) || !safe(x0, y1) || !safe(x1, y1)) continue;
                ++compared;
                EXPECT_FALSE(differs(x, y, 3)) << "frame " << f << " " << x << "," << y;
            }
        EXPECT_GT(compared, 4096u * 14) << "frame " << f;
    }
}

// replay_trace: the streamed import replays the same frames as the stream imported whole, with
// no refusal (mixed_states' 38 fixed-function DrawPrimitiveUP draw).
TEST(ApitraceImport, StreamedReplayOfATraceEqualsTheImportedStreams) {
    const auto frames_of = [](auto&& run) {
        std::vector<std::vector<std::byte>> frames;
        DeviceOptions options;
        options.output_dir = "frames";  // not written: write_image keeps the bytes
        options.write_image = [&](const Surface& s, const std::string&) { frames.emplace_back(s.bytes().begin(), s.bytes().end()); };
        Device device(options);
        run(device);
        return frames;
    };
    const ImportResult imported = import_file("mixed_states");
    const auto whole = frames_of([&](Device& device) { (void)replay(device, imported.stream); });
    TraceReplay streamed;
    const auto direct = frames_of([&](Device& device) {
        std::optional<Error> error;
        auto reader = Reader::open_file(trace_path("mixed_states.trace"), error);
        ASSERT_TRUE(reader);
        streamed = replay_trace(*reader, device);
    });
    ASSERT_EQ(whole.size(), 2u);
    EXPECT_EQ(direct, whole);
    EXPECT_FALSE(streamed.error);
    EXPECT_EQ(streamed.import.imported, 227u);
    EXPECT_EQ(streamed.statements, 227u);
    EXPECT_EQ(streamed.refused, 0u);
    EXPECT_TRUE(streamed.refused_kinds.empty());
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

// locks_reset (tests/data/traces/src/locks_reset.c, captured under Wine): a LockBox with a box,
// LockRect of a D16_LOCKABLE depth surface whole and through a rectangle, and Reset to a smaller
// back buffer. Every call is imported or accepted; the statements carry the box, the rectangle
// and only their bytes; the replay draws Wine's two frames exactly and stores the depth values
// Wine read back (depth.txt). Wine refuses to lock its D32F_LOCKABLE surface (D3DERR_INVALIDCALL,
// in depth.txt), so that LockRect is a failed call: accepted, no statement.
TEST(ApitraceImport, PartialVolumeAndDepthUploadsAndResetOfLocksReset) {
    const ImportResult r = import_file("locks_reset");
    ASSERT_FALSE(r.error) << r.error->to_string();
    EXPECT_EQ(r.report.skipped, 0u) << r.report.to_string();
    std::vector<const cs::Statement*> boxes, depth_locks;
    const cs::Statement* reset = nullptr;
    std::string d16;
    for (const auto& st : r.stream.statements) {
        if (st.name == "LockBox") boxes.push_back(&st);
        if (st.name == "CreateDepthStencilSurface" && st.arguments.at(3).text == "D16_LOCKABLE") d16 = st.arguments[0].text;
        if (st.name == "LockRect" && !d16.empty() && st.arguments.at(0).text == d16) depth_locks.push_back(&st);
        if (st.name == "Reset") reset = &st;
    }
    // LockBox vol 0 (whole, 4x4x4 texels of 4 bytes), then LockBox vol 0 { 1 1 1 3 3 2 } with the
    // box's 2x2x1 texels: B G R A of 0xFFFF0000 + x 0x80 + y 0x8000.
    ASSERT_EQ(boxes.size(), 2u);
    ASSERT_EQ(boxes[0]->arguments.size(), 3u);
    EXPECT_EQ(boxes[0]->arguments[2].bytes.size(), 256u);
    ASSERT_EQ(boxes[1]->arguments.size(), 4u);
    std::vector<int64_t> box;
    for (const auto& v : boxes[1]->arguments[2].items) box.push_back(v.integer);
    EXPECT_EQ(box, (std::vector<int64_t>{1, 1, 1, 3, 3, 2}));
    const std::vector<uint8_t> texels{0x00, 0x00, 0xFF, 0xFF, 0x80, 0x00, 0xFF, 0xFF,
                                      0x00, 0x80, 0xFF, 0xFF, 0x80, 0x80, 0xFF, 0xFF};
    ASSERT_EQ(boxes[1]->arguments[3].bytes.size(), texels.size());
    for (size_t i = 0; i < texels.size(); ++i)
        EXPECT_EQ(static_cast<uint8_t>(boxes[1]->arguments[3].bytes[i]), texels[i]) << i;
    // LockRect ds 0 (whole, 4x4 16-bit values) and LockRect ds 0 { 1 2 3 4 } (2x2 values).
    ASSERT_FALSE(d16.empty());
    ASSERT_EQ(depth_locks.size(), 2u);
    EXPECT_EQ(depth_locks[0]->arguments.size(), 3u);
    EXPECT_EQ(depth_locks[0]->arguments.back().bytes.size(), 32u);
    ASSERT_EQ(depth_locks[1]->arguments.size(), 4u);
    std::vector<int64_t> rect;
    for (const auto& v : depth_locks[1]->arguments[2].items) rect.push_back(v.integer);
    EXPECT_EQ(rect, (std::vector<int64_t>{1, 2, 3, 4}));
    EXPECT_EQ(depth_locks[1]->arguments[3].bytes.size(), 8u);
    ASSERT_TRUE(reset);
    EXPECT_EQ(reset->arguments.at(0).integer, 128);
    EXPECT_EQ(reset->arguments.at(1).integer, 96);

    // The depth values, replayed up to the surface's Release: Wine's read-back, row by row.
    std::ifstream depth_txt(trace_path("locks_reset/depth.txt"));
    std::vector<uint32_t> wine_depth;
    std::string line;
    for (int row = 0; row < 4 && std::getline(depth_txt, line); ++row) {
        std::istringstream values(line);
        for (uint32_t v; values >> v;) wine_depth.push_back(v);
    }
    ASSERT_EQ(wine_depth.size(), 16u);
    EXPECT_EQ(wine_depth[2 * 4 + 1], 0xF000u);  // the rectangle's first value
    std::getline(depth_txt, line);
    EXPECT_NE(line.find("LockRect failed, hr=0x8876086c"), std::string::npos) << line;  // D32F_LOCKABLE
    cs::Stream until_release;
    for (const auto& st : r.stream.statements) {
        if (st.name == "Release" && !st.arguments.empty() && st.arguments[0].text == d16) break;
        until_release.statements.push_back(st);
    }
    {
        DeviceOptions options;
        options.output_dir = "frames";  // not written
        options.write_image = [](const Surface&, const std::string&) {};
        Device device(options);
        const ReplayResult replayed = replay(device, until_release);
        for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
        const DepthStencilSurface* ds = device.depth_stencil(d16);
        ASSERT_NE(ds, nullptr);
        for (uint32_t y = 0; y < 4; ++y)
            for (uint32_t x = 0; x < 4; ++x) EXPECT_EQ(ds->stored_depth(x, y), wine_depth[y * 4 + x]) << x << "," << y;
    }

    // The frames: exact. Frame 0's 4x4 block at (8, 8) is slice 1 of the volume, one texel per
    // pixel: the box's texels at (9..10, 9..10), the whole fill's 0x404040 around them.
    std::vector<Surface> frames;
    DeviceOptions options;
    options.output_dir = "frames";  // not written: write_image keeps the surfaces
    options.write_image = [&](const Surface& s, const std::string&) { frames.push_back(s); };
    Device device(options);
    const ReplayResult replayed = replay(device, r.stream);
    for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
    ASSERT_EQ(frames.size(), 2u);
    const auto channel = [](float v) { return static_cast<int>(std::lround(v * 255.0f)); };
    for (uint32_t f = 0; f < 2; ++f) {
        const Image expected = read_image(trace_path("locks_reset/frame_" + std::to_string(f) + ".png"));
        ASSERT_EQ(frames[f].width(), expected.width) << f;
        ASSERT_EQ(frames[f].height(), expected.height) << f;
        EXPECT_EQ(expected.width, f == 0 ? 256u : 128u);
        uint32_t differing = 0;
        for (uint32_t y = 0; y < expected.height; ++y)
            for (uint32_t x = 0; x < expected.width; ++x) {
                const Float4 got = frames[f].read(x, y);
                for (unsigned c = 0; c < 3; ++c)
                    if (channel(got[c]) != channel(expected.rgba[(y * expected.width + x) * 4 + c])) {
                        ++differing;
                        break;
                    }
            }
        EXPECT_EQ(differing, 0u) << "frame " << f;
    }
    const auto rgb = [&](uint32_t x, uint32_t y) {
        const Float4 v = frames[0].read(x, y);
        return static_cast<uint32_t>(channel(v[0]) << 16 | channel(v[1]) << 8 | channel(v[2]));
    };
    EXPECT_EQ(rgb(9, 9), 0xFF0000u);
    EXPECT_EQ(rgb(10, 9), 0xFF0080u);
    EXPECT_EQ(rgb(9, 10), 0xFF8000u);
    EXPECT_EQ(rgb(10, 10), 0xFF8080u);
    EXPECT_EQ(rgb(8, 8), 0x404040u);
    EXPECT_EQ(rgb(11, 11), 0x404040u);
    EXPECT_EQ(rgb(12, 12), 0x000000u);
}

// A hand-made event stream (the format before Snappy, as apitrace_reader_test.cpp writes it):
// what Wine cannot capture. Wine refuses to lock a D32F_LOCKABLE surface, so its uploads are
// built here: LockRect of the whole 2x2 surface (pitch 8) and of the rectangle { 1 0 2 2 }, whose
// copy runs from its first value to its last (12 bytes: 4, a gap of 4, 4), then an upload to a
// D24S8 surface, which D3D9 cannot lock: skipped with the reason; and a render target's upload.
using EventWriter = test::TraceWriter;

TEST(ApitraceImport, LockableDepthUploadsOfAHandMadeTrace) {
    EventWriter w;
    w.uint(6).uint(6).str("");
    w.enter(0, "IDirect3D9::CreateDevice", {"this", "pPresentationParameters", "ppReturnedDeviceInterface"});
    w.arg(0).ptr(0x10).arg(1).one().byte(12).uint(0).str("D3DPRESENT_PARAMETERS").uint(5).str("BackBufferWidth");
    w.str("BackBufferHeight").str("BackBufferFormat").str("EnableAutoDepthStencil").str("AutoDepthStencilFormat");
    w.u(2).u(2).u(21).u(0).u(0).byte(0);  // 2x2 A8R8G8B8, no auto depth
    w.leave(0).arg(2).one().ptr(0x100).byte(0);
    const auto create_ds = [&](uint64_t call, uint64_t format, uint64_t surface) {
        if (call == 1) w.enter(1, "IDirect3DDevice9::CreateDepthStencilSurface", {"this", "Width", "Height", "Format", "ppSurface"});
        else w.enter_again(1);
        w.arg(0).ptr(0x100).arg(1).u(2).arg(2).u(2).arg(3).u(format).byte(0);
        w.leave(call).arg(4).one().ptr(surface).byte(0);
    };
    const auto lock = [&](uint64_t call, uint64_t surface, bool rect, uint64_t bits) {
        if (call == 2) w.enter(2, "IDirect3DSurface9::LockRect", {"this", "pLockedRect", "pRect", "Flags"});
        else w.enter_again(2);
        w.arg(0).ptr(surface).arg(2);
        if (rect) {
            w.one().byte(12).uint(2);
            if (call == 5) w.str("RECT").uint(4).str("left").str("top").str("right").str("bottom");
            w.u(1).u(0).u(2).u(2);
        } else {
            w.byte(0);  // NULL: the whole surface
        }
        w.arg(3).u(0).byte(0);
        w.leave(call).arg(1).one().byte(12).uint(1);
        if (call == 2) w.str("D3DLOCKED_RECT").uint(2).str("Pitch").str("pBits");
        w.u(8).ptr(bits).byte(0);
    };
    const auto copy = [&](uint64_t call, uint64_t dest, std::initializer_list<float> values) {
        if (call == 3) w.enter(3, "memcpy", {"dest", "src", "n"});
        else w.enter_again(3);
        w.arg(0).ptr(dest).arg(1).floats(values).arg(2).u(values.size() * 4).byte(0);
        w.leave(call).byte(0);
    };
    const auto unlock = [&](uint64_t call, uint64_t surface) {
        if (call == 4) w.enter(4, "IDirect3DSurface9::UnlockRect", {"this"});
        else w.enter_again(4);
        w.arg(0).ptr(surface).byte(0);
        w.leave(call).byte(0);
    };
    create_ds(1, 82, 0x200);  // D32F_LOCKABLE
    lock(2, 0x200, false, 0x1000);
    copy(3, 0x1000, {1.0f, 1.0f, 1.0f, 1.0f});
    unlock(4, 0x200);
    lock(5, 0x200, true, 0x2004);
    copy(6, 0x2004, {0.25f, -7.0f, 0.5f});  // -7: the row's pad, not the rectangle's
    unlock(7, 0x200);
    create_ds(8, 75, 0x300);  // D24S8
    lock(9, 0x300, false, 0x3000);
    copy(10, 0x3000, {0.0f, 0.0f, 0.0f, 0.0f});
    // A render target's LockRect: its bytes as they are (here the bits of 4 floats as 4 texels).
    w.enter(11, "IDirect3DDevice9::CreateRenderTarget", {"this", "Width", "Height", "Format", "ppSurface"});
    w.arg(0).ptr(0x100).arg(1).u(2).arg(2).u(2).arg(3).u(21).byte(0);
    w.leave(11).arg(4).one().ptr(0x400).byte(0);
    lock(12, 0x400, false, 0x4000);
    copy(13, 0x4000, {1.0f, 0.25f, 0.5f, 2.0f});

    std::optional<Error> error;
    auto reader = Reader::open(w.out, error, true);
    ASSERT_TRUE(reader) << (error ? error->to_string() : "");
    const ImportResult r = import_d3d9(*reader);
    ASSERT_FALSE(r.error) << r.error->to_string();
    EXPECT_EQ(r.report.calls, 14u);
    EXPECT_EQ(r.report.skipped, 1u) << r.report.to_string();
    ASSERT_EQ(r.report.skipped_kinds.size(), 1u);
    EXPECT_EQ(r.report.skipped_kinds[0].call, "memcpy");
    EXPECT_EQ(r.report.skipped_kinds[0].first, 10u);
    EXPECT_EQ(r.report.skipped_kinds[0].reason, "an upload to a depth surface that is not D16_LOCKABLE or D32F_LOCKABLE");
    std::vector<const cs::Statement*> locks;
    for (const auto& st : r.stream.statements)
        if (st.name == "LockRect") locks.push_back(&st);
    ASSERT_EQ(locks.size(), 3u);
    EXPECT_EQ(locks[0]->arguments.at(0).text, "ds_200");
    EXPECT_EQ(locks[2]->arguments.at(0).text, "rt_400");
    EXPECT_EQ(locks[0]->arguments.back().bytes.size(), 16u);
    ASSERT_EQ(locks[1]->arguments.size(), 4u);
    EXPECT_EQ(locks[1]->arguments[3].bytes.size(), 8u);

    Device device;
    const ReplayResult replayed = replay(device, r.stream);
    for (const auto& d : replayed.diagnostics) ADD_FAILURE() << d.to_string();
    const DepthStencilSurface* ds = device.depth_stencil("ds_200");
    ASSERT_NE(ds, nullptr);
    EXPECT_EQ(ds->depth(0, 0), 1.0f);
    EXPECT_EQ(ds->depth(0, 1), 1.0f);
    EXPECT_EQ(ds->depth(1, 0), 0.25f);
    EXPECT_EQ(ds->depth(1, 1), 0.5f);
    const Surface* rt = device.surface("rt_400");
    ASSERT_NE(rt, nullptr);
    ASSERT_EQ(rt->bytes().size(), 16u);
    for (size_t i = 0; i < 4; ++i) {
        uint32_t texel = 0;
        std::memcpy(&texel, rt->bytes().data() + 4 * i, 4);
        EXPECT_EQ(texel, std::bit_cast<uint32_t>(std::array<float, 4>{1.0f, 0.25f, 0.5f, 2.0f}[i])) << i;
    }
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
