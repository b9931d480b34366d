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

}  // namespace
