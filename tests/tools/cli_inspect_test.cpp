// sm2 replay --snapshot and sm2 state: on small streams written here, on the sample scenes and
// on the apitrace capture shader_scene.trace, with expected values from the streams' own calls
// (a Clear's colour, depth and stencil; the value a SetRenderState set).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.h"

namespace {

using Result = cli_support::Run;
using cli_support::sm2;
using cli_support::tmp;
using cli_support::write_file;

const std::string kSource = SM2_SOURCE_DIR;
const std::string kScene01 = kSource + "/samples/scenes/01_gouraud_triangle.sm2cs";
const std::string kShaderTrace = "/work/shared/traces/shader_scene.trace";

// An uncompressed 32-bit TGA of one colour (8-bit channels), written by hand so that the
// expected image does not come from the code under test.
void write_tga(const std::string& path, unsigned width, unsigned height, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    std::vector<uint8_t> bytes(18, 0);
    bytes[2] = 2;  // uncompressed true colour
    bytes[12] = static_cast<uint8_t>(width & 0xFF);
    bytes[13] = static_cast<uint8_t>(width >> 8);
    bytes[14] = static_cast<uint8_t>(height & 0xFF);
    bytes[15] = static_cast<uint8_t>(height >> 8);
    bytes[16] = 32;
    bytes[17] = 0x28;  // top-left origin, 8 alpha bits
    for (unsigned i = 0; i < width * height; ++i) bytes.insert(bytes.end(), {b, g, r, a});
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
}

// sm2 diff A B --json: the max error, or -1 when the comparison did not run.
double max_error(const std::string& a, const std::string& b) {
    const Result r = sm2("diff " + a + " " + b + " --json");
    const auto j = nlohmann::json::parse(r.out, nullptr, false);
    if (j.is_discarded() || !j.contains("max_error") || !j["max_error"].is_number()) return -1.0;
    return j["max_error"].get<double>();
}

std::vector<std::string> files_in(const std::string& folder) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(folder)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string fresh_folder(const std::string& name) {
    const std::string dir = tmp(name);
    std::filesystem::remove_all(dir);
    return dir;
}

// Calls: 1 CreateDevice, 2 Clear, 3 Present.
const std::string kClearStream =
    "sm2cs 1\n"
    "CreateDevice 4 3 A8R8G8B8 D24S8\n"
    "Clear { TARGET ZBUFFER STENCIL } 0xFF336699 0.25 7\n"
    "Present\n";

TEST(CliSnapshot, AfterAClearTheImagesHoldItsColourDepthAndStencil) {
    const std::string stream = tmp("clear.sm2cs"), dir = fresh_folder("snap_clear");
    write_file(stream, kClearStream);
    const Result r = sm2("replay " + stream + " -o " + dir + " --snapshot 2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("snapshots: 1 call, 3 images"), std::string::npos) << r.out;
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"call_000002_frame_0_depth.exr", "call_000002_frame_0_rt0.png",
                                                       "call_000002_frame_0_stencil.png", "frame_0000.png"}));
    const std::string colour = tmp("clear_colour.tga"), depth = tmp("clear_depth.tga"), stencil = tmp("clear_stencil.tga"),
                      other = tmp("clear_other.tga");
    write_tga(colour, 4, 3, 0x33, 0x66, 0x99, 0xFF);
    write_tga(depth, 4, 3, 64, 64, 64, 255);   // 64/255 = 0.25098: within 0.001 of 0.25
    write_tga(stencil, 4, 3, 7, 7, 7, 255);    // stencil 7 as 7/255
    write_tga(other, 4, 3, 0x33, 0x66, 0x98, 0xFF);
    EXPECT_EQ(max_error(dir + "/call_000002_frame_0_rt0.png", colour), 0.0);
    EXPECT_GT(max_error(dir + "/call_000002_frame_0_rt0.png", other), 0.0);  // the comparison can fail
    const double depth_error = max_error(dir + "/call_000002_frame_0_depth.exr", depth);
    EXPECT_GE(depth_error, 0.0);
    EXPECT_LT(depth_error, 0.001);
    EXPECT_EQ(max_error(dir + "/call_000002_frame_0_stencil.png", stencil), 0.0);
}

TEST(CliSnapshot, BeforeTheClearTheTargetIsStillBlack) {
    const std::string stream = tmp("clear_before.sm2cs"), dir = fresh_folder("snap_before");
    write_file(stream, kClearStream);
    const Result r = sm2("replay " + stream + " -o " + dir + " --snapshot 1");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string black = tmp("black.tga");
    write_tga(black, 4, 3, 0, 0, 0, 0);
    EXPECT_EQ(max_error(dir + "/call_000001_frame_0_rt0.png", black), 0.0);
}

TEST(CliSnapshot, DrawsAndFramesOfASampleScene) {
    // Scene 01: call 17 is its one DrawPrimitive, call 19 its Present.
    const std::string dir = fresh_folder("snap_scene01");
    const Result r = sm2("replay " + kScene01 + " -o " + dir + " --snapshot '*/draw,frame' -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"call_000017_frame_0_rt0.png", "call_000019_frame_0_rt0.png",
                                                       "frame_0000.png"}));
    // After the only draw and after Present the target holds the frame.
    EXPECT_EQ(max_error(dir + "/call_000017_frame_0_rt0.png", dir + "/frame_0000.png"), 0.0);
    EXPECT_EQ(max_error(dir + "/call_000019_frame_0_rt0.png", dir + "/frame_0000.png"), 0.0);
}

TEST(CliSnapshot, RangesStepsAndLists) {
    const std::string dir = fresh_folder("snap_steps");
    const Result r = sm2("replay " + kScene01 + " -o " + dir + " --snapshot '1-19/9 15' -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"call_000001_frame_0_rt0.png", "call_000010_frame_0_rt0.png",
                                                       "call_000015_frame_0_rt0.png", "call_000019_frame_0_rt0.png",
                                                       "frame_0000.png"}));
    // Call 15 is the scene's Clear TARGET 0xFF202020.
    const std::string grey = tmp("grey.tga");
    write_tga(grey, 256, 256, 0x20, 0x20, 0x20, 0xFF);
    EXPECT_EQ(max_error(dir + "/call_000015_frame_0_rt0.png", grey), 0.0);
    const std::string open_dir = fresh_folder("snap_open");
    const Result open = sm2("replay " + kScene01 + " -o " + open_dir + " --snapshot 18- -q");
    ASSERT_EQ(open.status, 0) << open.err;
    EXPECT_EQ(files_in(open_dir), (std::vector<std::string>{"call_000018_frame_0_rt0.png", "call_000019_frame_0_rt0.png",
                                                            "frame_0000.png"}));
}

TEST(CliSnapshot, ATraceAfterItsClearAndAtItsFrames) {
    // shader_scene.trace call 27: Clear(TARGET, 0xFF102040) into the 128x128 render-target texture.
    const std::string dir = fresh_folder("snap_trace");
    const Result r = sm2("replay " + kShaderTrace + " -o " + dir + " --snapshot '27,frame' -q");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string blue = tmp("trace_clear.tga");
    write_tga(blue, 128, 128, 0x10, 0x20, 0x40, 0xFF);
    EXPECT_EQ(max_error(dir + "/call_000027_frame_0_rt0.png", blue), 0.0);
    // Its Presents are calls 88 and 153; their snapshots are the frames.
    EXPECT_EQ(max_error(dir + "/call_000088_frame_0_rt0.png", dir + "/frame_0000.png"), 0.0);
    EXPECT_EQ(max_error(dir + "/call_000153_frame_1_rt0.png", dir + "/frame_0001.png"), 0.0);
    EXPECT_TRUE(std::filesystem::exists(dir + "/call_000088_frame_0_depth.exr"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/call_000088_frame_0_stencil.png"));
}

TEST(CliSnapshot, BadCallSetsAreLocated) {
    struct Case {
        const char* set;
        const char* message;
    };
    for (const Case& c : {Case{"1-x", "column 3: expected a call number after '-'"},
                          Case{"5-2", "column 4: the range ends (2) before it starts (5)"},
                          Case{"*/0", "a step must be at least 1"},
                          Case{"10,fbo", "column 4: expected a call number"},
                          Case{"3/", "column 3: expected a step"},
                          Case{"12a", "column 3: expected ','"},
                          Case{"@/nonexistent/file", "cannot read the call-set file"}}) {
        const Result r = sm2("replay " + kScene01 + " -o " + tmp("snap_bad") + " --overwrite --snapshot '" + c.set + "'");
        EXPECT_EQ(r.status, 2) << c.set;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.set << ": " << r.err;
        EXPECT_NE(r.err.find(std::string("call set '") + c.set + "'"), std::string::npos) << r.err;
    }
    const Result none = sm2("replay " + kScene01 + " -o " + fresh_folder("snap_none") + " --snapshot 500");
    EXPECT_EQ(none.status, 1);
    EXPECT_NE(none.err.find("selects none of the 19 calls"), std::string::npos) << none.err;
}

TEST(CliSnapshot, CallSetFromAFile) {
    const std::string list = tmp("calls.txt"), dir = fresh_folder("snap_file");
    write_file(list, "15\n17\n");
    const Result r = sm2("replay " + kScene01 + " -o " + dir + " --snapshot @" + list + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"call_000015_frame_0_rt0.png", "call_000017_frame_0_rt0.png",
                                                       "frame_0000.png"}));
}

// ---------------------------------------------------------------------------------------------
// sm2 state

// Calls: 1 CreateDevice, 2 SetRenderState, 3 SetSamplerState, 4 SetPixelShaderConstantF,
// 5 SetScissorRect, 6 SetRenderState.
const std::string kStateStream =
    "sm2cs 1\n"
    "CreateDevice 64 32 A8R8G8B8 D24S8\n"
    "SetRenderState CULLMODE NONE\n"
    "SetSamplerState 2 MINFILTER LINEAR\n"
    "SetPixelShaderConstantF 5 f32[ 0.5 -2 0 1 ]\n"
    "SetScissorRect 1 2 30 20\n"
    "SetRenderState CULLMODE CW\n";

nlohmann::json state_json(const std::string& stream, int call) {
    const Result r = sm2("state " + stream + " --call " + std::to_string(call) + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out, nullptr, false);
}

TEST(CliState, EachCallShowsWhatItSet) {
    const std::string stream = tmp("state.sm2cs");
    write_file(stream, kStateStream);
    const auto first = state_json(stream, 1);
    EXPECT_TRUE(first["render_states"].empty()) << first.dump();
    EXPECT_EQ(first["render_targets"]["0"]["width"], 64);
    EXPECT_EQ(first["render_targets"]["0"]["format"], "A8R8G8B8");
    EXPECT_EQ(first["depth_stencil"]["format"], "D24S8");
    const auto second = state_json(stream, 2);
    EXPECT_EQ(second["render_states"]["CULLMODE"]["value"], "NONE");
    EXPECT_EQ(second["render_states"]["CULLMODE"]["default"], "CCW");
    EXPECT_EQ(second["render_states"].size(), 1u) << second.dump();
    EXPECT_TRUE(second["sampler_states"].empty());
    const auto fourth = state_json(stream, 4);
    EXPECT_EQ(fourth["sampler_states"]["2"]["MINFILTER"]["value"], "LINEAR");
    EXPECT_EQ(fourth["pixel_shader_constants"]["c5"], nlohmann::json::array({0.5, -2.0, 0.0, 1.0}));
    EXPECT_EQ(fourth["scissor_rect"]["right"], 64);
    const auto last = state_json(stream, 6);
    EXPECT_EQ(last["scissor_rect"], (nlohmann::json{{"left", 1}, {"top", 2}, {"right", 30}, {"bottom", 20}}));
    EXPECT_EQ(last["render_states"]["CULLMODE"]["value"], "CW");
    const Result text = sm2("state " + stream + " --call 6");
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("  CULLMODE = CW (default CCW)\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("    MINFILTER = LINEAR (default POINT)\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("  c5 = (0.5, -2, 0, 1)\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("scissor rect: left 1, top 2, right 30, bottom 20\n"), std::string::npos) << text.out;
}

TEST(CliState, ASampleSceneAtItsDraw) {
    const auto j = state_json(kScene01, 17);
    EXPECT_EQ(j["streams"]["0"]["name"], "vb_pos");
    EXPECT_EQ(j["streams"]["0"]["stride"], 12);
    EXPECT_EQ(j["streams"]["1"]["stride"], 4);
    EXPECT_EQ(j["streams"]["1"]["bytes"], 12);
    EXPECT_EQ(j["vertex_declaration"]["elements"][1]["type"], "D3DCOLOR");
    EXPECT_EQ(j["vertex_shader_constants"]["c3"], nlohmann::json::array({0.0, 0.0, 0.0, 1.0}));
    EXPECT_NE(j["vertex_shader"]["disassembly"].get<std::string>().find("m4x4 oPos, v0, c0"), std::string::npos);
    EXPECT_NE(j["pixel_shader"]["disassembly"].get<std::string>().find("mov oC0, v0"), std::string::npos);
    EXPECT_EQ(j["in_scene"], true);
}

TEST(CliState, ATraceAfterItsStencilStates) {
    // shader_scene.trace calls 54..58: COLORWRITEENABLE 0, STENCILENABLE TRUE, STENCILFUNC ALWAYS,
    // STENCILREF 1, STENCILMASK 255 (call 22 set ZENABLE FALSE on a device with auto depth).
    const auto before = state_json(kShaderTrace, 53);
    EXPECT_FALSE(before["render_states"].contains("COLORWRITEENABLE")) << before.dump();
    EXPECT_EQ(before["render_states"]["ZENABLE"]["value"], "FALSE");
    EXPECT_EQ(before["render_states"]["ZENABLE"]["default"], "TRUE");
    const auto after = state_json(kShaderTrace, 58);
    EXPECT_EQ(after["render_states"]["COLORWRITEENABLE"]["dword"], 0);
    EXPECT_EQ(after["render_states"]["STENCILENABLE"]["value"], "TRUE");
    EXPECT_EQ(after["render_states"]["STENCILREF"]["value"], "1");
    EXPECT_EQ(after["render_states"]["STENCILMASK"]["dword"], 255);
    EXPECT_FALSE(after["render_states"].contains("STENCILFUNC"));  // ALWAYS is its default
    EXPECT_EQ(after["depth_stencil"]["format"], "D24S8");
    EXPECT_EQ(after["frame"], 0);
}

TEST(CliState, CallsOutOfRangeAreRefused) {
    const Result zero = sm2("state " + kScene01 + " --call 0");
    EXPECT_EQ(zero.status, 1);
    EXPECT_NE(zero.err.find("--call 0: out of range: " + kScene01 + " has calls 1..19"), std::string::npos) << zero.err;
    const Result past = sm2("state " + kScene01 + " --call 20");
    EXPECT_EQ(past.status, 1);
    EXPECT_NE(past.err.find("has calls 1..19"), std::string::npos) << past.err;
    const Result trace = sm2("state " + kShaderTrace + " --call 100000");
    EXPECT_EQ(trace.status, 1);
    EXPECT_NE(trace.err.find("out of range"), std::string::npos) << trace.err;
    const Result missing = sm2("state " + tmp("no_such.sm2cs") + " --call 1");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("sm2 state"), std::string::npos) << missing.err;
}

// ---------------------------------------------------------------------------------------------
// sm2 pixel

// A 4x4 target cleared to (0, 0, 128/255, 1), then three full-screen quads (triangle strips:
// primitive 0 the top-left half, x + y < 4 at pixel centres, primitive 1 the bottom-right):
//   call 11: oC0 = (1, 0, 0, 1), no blending                       -> (1, 0, 0, 1)
//   call 16: oC0 = (0, 0.5, 0, 1), blend ONE + ONE                  -> (1, 128/255, 0, 1)
//   call 23: oC0 = (0, 0, 1, 0.25), scissor (0,0)-(2,2), alpha GREATER 128/255: pixels inside
//            the scissor fail the alpha test, those outside are scissored; nothing changes.
const std::string kTwoQuads =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
    "CreatePixelShader ps asm<<END\nps_2_0\nmov oC0, c0\nEND\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "Clear TARGET 0xFF000080 1 0\n"
    "BeginScene\n"
    "SetPixelShaderConstantF 0 f32[ 1 0 0 1 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
    "SetRenderState ALPHABLENDENABLE TRUE\n"
    "SetRenderState SRCBLEND ONE\n"
    "SetRenderState DESTBLEND ONE\n"
    "SetPixelShaderConstantF 0 f32[ 0 0.5 0 1 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
    "SetScissorRect 0 0 2 2\n"
    "SetRenderState SCISSORTESTENABLE TRUE\n"
    "SetRenderState ALPHATESTENABLE TRUE\n"
    "SetRenderState ALPHAFUNC GREATER\n"
    "SetRenderState ALPHAREF 128\n"
    "SetPixelShaderConstantF 0 f32[ 0 0 1 0.25 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
    "EndScene\n"
    "Present\n";

void expect_colour(const nlohmann::json& c, double r, double g, double b, double a, const std::string& what) {
    ASSERT_TRUE(c.is_array() && c.size() == 4) << what << ": " << c.dump();
    EXPECT_NEAR(c[0].get<double>(), r, 1e-6) << what;
    EXPECT_NEAR(c[1].get<double>(), g, 1e-6) << what;
    EXPECT_NEAR(c[2].get<double>(), b, 1e-6) << what;
    EXPECT_NEAR(c[3].get<double>(), a, 1e-6) << what;
}

nlohmann::json pixel_json(const std::string& stream, int frame, const std::string& xy) {
    const Result r = sm2("pixel " + stream + " --frame " + std::to_string(frame) + " --pixel " + xy + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out, nullptr, false);
}

TEST(CliPixel, TwoQuadsBlendedByHand) {
    const std::string stream = tmp("two_quads.sm2cs");
    write_file(stream, kTwoQuads);
    const double half = 128.0 / 255.0;
    for (const auto& [xy, primitive] : {std::pair{std::string("3,2"), 1}, std::pair{std::string("0,1"), 0}}) {
        const auto j = pixel_json(stream, 0, xy);
        ASSERT_EQ(j["draws"].size(), 3u) << j.dump();
        const auto& first = j["draws"][0]["fragments"];
        EXPECT_EQ(j["draws"][0]["call"], 11);
        ASSERT_EQ(first.size(), 1u);
        EXPECT_EQ(first[0]["primitive"], primitive) << xy;
        expect_colour(first[0]["shader_color"], 1, 0, 0, 1, xy + " call 11 shader");
        expect_colour(first[0]["before"]["color"], 0, 0, half, 1, xy + " call 11 before (the clear)");
        expect_colour(first[0]["after"]["color"], 1, 0, 0, 1, xy + " call 11 after");
        EXPECT_EQ(first[0]["written"], true);
        const auto& second = j["draws"][1]["fragments"][0];
        EXPECT_EQ(j["draws"][1]["call"], 16);
        expect_colour(second["shader_color"], 0, 0.5, 0, 1, xy + " call 16 shader");
        expect_colour(second["before"]["color"], 1, 0, 0, 1, xy + " call 16 before");
        expect_colour(second["after"]["color"], 1, half, 0, 1, xy + " call 16 after: red + 0.5 green");
        const auto& third = j["draws"][2]["fragments"][0];
        EXPECT_EQ(j["draws"][2]["call"], 23);
        EXPECT_EQ(third["written"], false);
        expect_colour(third["after"]["color"], 1, half, 0, 1, xy + " call 23 after: unchanged");
        if (xy == "3,2") {  // outside the scissor rectangle
            EXPECT_EQ(third["scissor"], "fail");
            EXPECT_EQ(third["shaded"], false);
            EXPECT_TRUE(third["alpha_test"].is_null());
        } else {  // inside: shaded, alpha 0.25 is not GREATER than 128/255
            EXPECT_EQ(third["scissor"], "pass");
            expect_colour(third["shader_color"], 0, 0, 1, 0.25, xy + " call 23 shader");
            EXPECT_EQ(third["alpha_test"], "fail");
        }
        expect_colour(j["final"], 1, half, 0, 1, xy + " final");
        EXPECT_EQ(j["consistent"], true);
    }
    // The frame itself: every pixel (1, 128/255, 0, 1), as the history ends.
    const std::string dir = fresh_folder("pixel_frame"), expected = tmp("pixel_frame.tga");
    ASSERT_EQ(sm2("replay " + stream + " -o " + dir + " -q").status, 0);
    write_tga(expected, 4, 4, 255, 128, 0, 255);
    EXPECT_EQ(max_error(dir + "/frame_0000.png", expected), 0.0);
}

TEST(CliPixel, TextNamesEachTest) {
    const std::string stream = tmp("two_quads_text.sm2cs");
    write_file(stream, kTwoQuads);
    const Result r = sm2("pixel " + stream + " --frame 0 --pixel 3,2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("3 draws covered it"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("call 16 DrawPrimitiveUP, primitive 1:\n  shader: oC0 (0, 0.5, 0, 1)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("tests: scissor fail"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("final: (1, 0.501961, 0, 1)"), std::string::npos) << r.out;
}

// A transparent volume slice (scene 13's shader): the texel (r, g, b, a) = (15, 12, 9, 0) / 15 of
// a 1x1x1 A4R4G4B4 volume, its alpha times 0.5, blended SRCALPHA / INVSRCALPHA onto the clear
// (0, 0, 128/255, 1); depth cleared to 1, the quad at z 0.5, ZFUNC ALWAYS, ZWRITE on. `middle`
// runs between the lookup and the output (c1 = 0.5). Where nothing in it reads the colour, the
// draw lets the sampler leave the colour of lookups transparent on every lane
// (TextureSampler::set_alpha_gate): nothing is written.
std::string transparent_slice(const std::string& middle) {
    return "sm2cs 1\n"
           "CreateDevice 4 4 A8R8G8B8 D24S8\n"
           "CreateVolumeTexture vol 1 1 1 1 A4R4G4B4\n"
           "LockBox vol 0 u16[ 4041 ]\n"  // 0x0FC9
           "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
           "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nmov oT0, c0\nEND\n"
           "CreatePixelShader ps asm<<END\nps_2_0\ndef c1, 0.5, 0.5, 0.5, 0.5\ndcl t0.xyz\ndcl_volume s0\n"
           "texld r0, t0, s0\n" + middle + "mul r0.w, r0.w, c0.x\nmov oC0, r0\nEND\n"
           "SetVertexDeclaration decl\n"
           "SetVertexShader vs\n"
           "SetPixelShader ps\n"
           "SetTexture 0 vol\n"
           "SetSamplerState 0 MAGFILTER LINEAR\n"
           "SetSamplerState 0 MINFILTER LINEAR\n"
           "SetRenderState ALPHABLENDENABLE TRUE\n"
           "SetRenderState SRCBLEND SRCALPHA\n"
           "SetRenderState DESTBLEND INVSRCALPHA\n"
           "SetRenderState ZFUNC ALWAYS\n"
           "SetVertexShaderConstantF 0 f32[ 0.5 0.5 0.5 1 ]\n"
           "SetPixelShaderConstantF 0 f32[ 0.5 0 0 0 ]\n"
           "Clear { TARGET ZBUFFER } 0xFF000080 1 0\n"
           "BeginScene\n"
           "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
           "EndScene\n"
           "Present\n";
}

// Gated: the history still shows the colour the shader computed.
TEST(CliPixel, TransparentLookupsKeepTheirColourInTheHistory) {
    const std::string stream = tmp("transparent_slice.sm2cs");
    write_file(stream, transparent_slice(""));
    const double half = 128.0 / 255.0;
    const auto j = pixel_json(stream, 0, "1,2");
    ASSERT_EQ(j["draws"].size(), 1u) << j.dump();
    const auto& fragment = j["draws"][0]["fragments"][0];
    expect_colour(fragment["shader_color"], 1, 12.0 / 15.0, 9.0 / 15.0, 0, "shader");
    expect_colour(fragment["before"]["color"], 0, 0, half, 1, "before (the clear)");
    expect_colour(fragment["after"]["color"], 0, 0, half, 1, "after: unchanged");
    expect_colour(j["final"], 0, 0, half, 1, "final");
    EXPECT_EQ(j["consistent"], true);
}

// The alpha gate's exclusions: the texel's colour decides a texkill or oDepth, so a transparent
// lookup must still return it. With texkill on colour - 0.5 (>= 0.1 in every channel): not
// killed, so the depth 0.5 is written (a lookup gated to colour 0 would kill it). With oDepth =
// red: 1 with the real colour (ZFUNC ALWAYS writes it), where a gated lookup would write 0.
TEST(CliPixel, TransparentLookupsKeepTheColourThatDecidesTexkillAndDepth) {
    const double half = 128.0 / 255.0;
    const std::string killed = tmp("transparent_slice_texkill.sm2cs");
    write_file(killed, transparent_slice("sub r1.xyz, r0, c1\nmov r1.w, c1.w\ntexkill r1\n"));
    const auto k = pixel_json(killed, 0, "1,2");
    ASSERT_EQ(k["draws"].size(), 1u) << k.dump();
    const auto& kf = k["draws"][0]["fragments"][0];
    EXPECT_EQ(kf["texkill"], "pass");
    EXPECT_NEAR(kf["after"]["depth"].get<double>(), 0.5, 1e-6);
    expect_colour(kf["after"]["color"], 0, 0, half, 1, "texkill: colour unchanged");
    EXPECT_EQ(k["consistent"], true);
    const std::string depth = tmp("transparent_slice_odepth.sm2cs");
    write_file(depth, transparent_slice("mov oDepth, r0.x\n"));
    const auto d = pixel_json(depth, 0, "1,2");
    ASSERT_EQ(d["draws"].size(), 1u) << d.dump();
    const auto& df = d["draws"][0]["fragments"][0];
    EXPECT_NEAR(df["after"]["depth"].get<double>(), 1.0, 1e-6);
    EXPECT_EQ(d["consistent"], true);
}

TEST(CliPixel, ShaderSceneTraceStencilAndBlend) {
    // shader_scene.trace frame 0, pixel (128, 128): call 49 draws the textured quad; call 64 writes
    // stencil 1 with colour writes off (COLORWRITEENABLE 0, calls 54..58); call 73 blends a
    // yellow quad (alpha 0.6) where the stencil is set; call 76's stencil test fails.
    const auto j = pixel_json(kShaderTrace, 0, "128,128");
    ASSERT_EQ(j["draws"].size(), 4u) << j.dump();
    EXPECT_EQ(j["draws"][0]["call"], 49);
    EXPECT_EQ(j["draws"][1]["call"], 64);
    const auto& stencil = j["draws"][1]["fragments"][0];
    EXPECT_EQ(stencil["before"]["stencil"], 0);
    EXPECT_EQ(stencil["after"]["stencil"], 1);
    EXPECT_EQ(stencil["before"]["color"], stencil["after"]["color"]);  // colour writes off
    const auto& blended = j["draws"][2]["fragments"][0];
    EXPECT_EQ(j["draws"][2]["call"], 73);
    expect_colour(blended["shader_color"], 1, 0.9f, 0.1f, 0.6f, "call 73 shader");
    // SRCALPHA / INVSRCALPHA: 0.6 * src + 0.4 * dst, in 8 bits, within one step.
    for (int c = 0; c < 3; ++c) {
        const double src = blended["shader_color"][c].get<double>(), dst = blended["before"]["color"][c].get<double>();
        EXPECT_NEAR(blended["after"]["color"][c].get<double>(), 0.6 * src + 0.4 * dst, 1.0 / 255.0) << c;
    }
    const auto& failed = j["draws"][3]["fragments"][0];
    EXPECT_EQ(failed["depth_stencil"], "fail");
    EXPECT_EQ(failed["written"], false);
    EXPECT_EQ(j["final"], failed["after"]["color"]);
    EXPECT_EQ(j["consistent"], true);
}

TEST(CliPixel, EveryPixelOfASceneEndsAtItsFrame) {
    // Scene 01 (one triangle over a grey clear): on the triangle, the history's last value is the
    // frame's; off it, no draw covered the pixel and the final value is the clear colour.
    const auto on = pixel_json(kScene01, 0, "128,100");
    ASSERT_EQ(on["draws"].size(), 1u) << on.dump();
    EXPECT_EQ(on["draws"][0]["call"], 17);
    EXPECT_EQ(on["final"], on["draws"][0]["fragments"][0]["after"]["color"]);
    expect_colour(on["draws"][0]["fragments"][0]["before"]["color"], 0x20 / 255.0, 0x20 / 255.0, 0x20 / 255.0, 1, "clear");
    const auto off = pixel_json(kScene01, 0, "2,2");
    EXPECT_TRUE(off["draws"].empty());
    expect_colour(off["final"], 0x20 / 255.0, 0x20 / 255.0, 0x20 / 255.0, 1, "clear only");
}

// Texkill and a late depth test (a shader with texkill tests depth after it runs), on a depth
// buffer cleared to 0.25 with ZFUNC LESS; calls 12, 14 and 16 draw full-screen quads:
//   call 12: c1 = (-1, 0, 0, 0): texkill discards; nothing is written
//   call 14: depth 0.5, not less than 0.25: the depth test fails
//   call 16: depth 0.1: passes, writes green and depth 0.1
const std::string kKillAndDepth =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8 D24S8\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
    "CreatePixelShader ps asm<<END\nps_2_0\nmov r0, c1\ntexkill r0\nmov oC0, c0\nEND\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "Clear { TARGET ZBUFFER } 0xFF000000 0.25 0\n"
    "SetRenderState ZFUNC LESS\n"
    "BeginScene\n"
    "SetPixelShaderConstantF 0 f32[ 1 1 1 1   -1 0 0 0 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.1   1 1 0.1   -1 -1 0.1   1 -1 0.1 ]\n"
    "SetPixelShaderConstantF 0 f32[ 1 0 0 1   1 1 1 1 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
    "SetPixelShaderConstantF 0 f32[ 0 1 0 1   1 1 1 1 ]\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.1   1 1 0.1   -1 -1 0.1   1 -1 0.1 ]\n"
    "EndScene\n"
    "Present\n";

TEST(CliPixel, TexkillAndALateDepthTest) {
    const std::string stream = tmp("kill_depth.sm2cs");
    write_file(stream, kKillAndDepth);
    const auto j = pixel_json(stream, 0, "1,1");
    ASSERT_EQ(j["draws"].size(), 3u) << j.dump();
    const auto& killed = j["draws"][0]["fragments"][0];
    EXPECT_EQ(j["draws"][0]["call"], 12);
    EXPECT_EQ(killed["texkill"], "fail");
    EXPECT_TRUE(killed["depth_stencil"].is_null());
    EXPECT_EQ(killed["written"], false);
    EXPECT_NEAR(killed["after"]["depth"].get<double>(), 0.25, 1e-6);
    const auto& hidden = j["draws"][1]["fragments"][0];
    EXPECT_EQ(hidden["texkill"], "pass");
    EXPECT_EQ(hidden["early_depth_stencil"], false);
    EXPECT_EQ(hidden["depth_stencil"], "fail");
    EXPECT_NEAR(hidden["depth"].get<double>(), 0.5, 1e-6);
    expect_colour(hidden["after"]["color"], 0, 0, 0, 1, "call 14 after: the clear");
    const auto& drawn = j["draws"][2]["fragments"][0];
    EXPECT_EQ(drawn["depth_stencil"], "pass");
    EXPECT_EQ(drawn["written"], true);
    EXPECT_NEAR(drawn["after"]["depth"].get<double>(), 0.1, 1e-6);
    expect_colour(drawn["after"]["color"], 0, 1, 0, 1, "call 16 after");
    expect_colour(j["final"], 0, 1, 0, 1, "final");
}

TEST(CliPixel, BadInputIsRefused) {
    const Result outside = sm2("pixel " + kScene01 + " --frame 0 --pixel 256,3");
    EXPECT_EQ(outside.status, 1);
    EXPECT_NE(outside.err.find("--pixel 256,3: outside the 256x256 back buffer"), std::string::npos) << outside.err;
    const Result frame = sm2("pixel " + kScene01 + " --frame 1 --pixel 3,3");
    EXPECT_EQ(frame.status, 1);
    EXPECT_NE(frame.err.find("--frame 1: out of range: " + kScene01 + " presents 1 frame"), std::string::npos) << frame.err;
    for (const char* bad : {"3", "3,", ",3", "a,b", "1,2,3", "-1,2"}) {
        const Result r = sm2("pixel " + kScene01 + " --frame 0 --pixel '" + bad + "'");
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_NE(r.err.find("expected X,Y"), std::string::npos) << bad << ": " << r.err;
    }
    const Result trace = sm2("pixel " + kShaderTrace + " --frame 7 --pixel 1,1");
    EXPECT_EQ(trace.status, 1);
    EXPECT_NE(trace.err.find("presents 2 frames"), std::string::npos) << trace.err;
}

// The binary form: the same calls, numbers and results as the text form.
TEST(CliInspect, BinaryStreamsAsText) {
    const std::string binary = tmp("scene01.sm2cb");
    ASSERT_EQ(sm2("cs pack " + kScene01 + " -o " + binary).status, 0);
    const std::string text_dir = fresh_folder("bin_text"), binary_dir = fresh_folder("bin_binary");
    ASSERT_EQ(sm2("replay " + kScene01 + " -o " + text_dir + " --snapshot '*/draw' -q").status, 0);
    const Result r = sm2("replay " + binary + " -o " + binary_dir + " --snapshot '*/draw' -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(files_in(binary_dir), files_in(text_dir));
    EXPECT_EQ(max_error(binary_dir + "/call_000017_frame_0_rt0.png", text_dir + "/call_000017_frame_0_rt0.png"), 0.0);
    auto without_file = [](nlohmann::json j) {
        j.erase("file");
        return j;
    };
    EXPECT_EQ(without_file(state_json(binary, 17)), without_file(state_json(kScene01, 17)));
    EXPECT_EQ(without_file(pixel_json(binary, 0, "128,100")), without_file(pixel_json(kScene01, 0, "128,100")));
}

}  // namespace
