// sm2 trace dump on the real captures of tests/data/traces: the first 30 calls of each trace as
// `apitrace dump -v` (Debian's apitrace 11.1) printed them, and the errors of broken files.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"

namespace {

using cli_support::slurp;
using cli_support::sm2;
using cli_support::tmp;
using cli_support::write_file;

const std::string kTraces = std::string(SM2_SOURCE_DIR) + "/tests/data/traces/";

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The reference dump's call records, multi-line strings joined with "\n" as sm2 writes them.
std::vector<std::string> reference(const std::string& name) {
    const std::regex start(R"(^\d+ [A-Za-z_][A-Za-z0-9_:]*\()");
    std::vector<std::string> records;
    for (const auto& line : lines_of(slurp(kTraces + name + ".dump.txt"))) {
        if (std::regex_search(line, start)) {
            records.push_back(line);
        } else if (!records.empty() && !line.empty() && line.rfind("//", 0) != 0) {
            records.back() += "\\n" + line;
        }
    }
    return records;
}

TEST(CliTrace, DumpMatchesTheReferenceForTheFirst30CallsOfEachTrace) {
    for (const char* name : {"ff_lit_cube", "shader_scene", "mixed_states"}) {
        auto r = sm2("trace dump " + kTraces + name + ".trace");
        ASSERT_EQ(r.status, 0) << name << r.err;
        EXPECT_EQ(r.err, "");
        auto lines = lines_of(r.out);
        // The header's properties first, as apitrace dump prints them.
        ASSERT_GE(lines.size(), 32u);
        EXPECT_EQ(lines[0].rfind("// process.commandLine = \"", 0), 0u) << lines[0];
        EXPECT_EQ(lines[1], "// process.name = \"Z:\\\\tmp\\\\d3d9-traces-build\\\\run_" + std::string(name) + "\\\\" +
                                name + ".exe\"");
        const auto ref = reference(name);
        ASSERT_GE(ref.size(), 30u);
        for (size_t i = 0; i < 30; ++i) {
            const std::string& line = lines[2 + i];
            // number and name ...
            EXPECT_EQ(line.substr(0, line.find('(')), ref[i].substr(0, ref[i].find('('))) << name;
            EXPECT_EQ(line.rfind(std::to_string(i) + " ", 0), 0u) << line;
            // ... and every argument and the return value.
            EXPECT_EQ(line, ref[i]) << name << " call " << i;
        }
    }
}

TEST(CliTrace, DumpValuesOfShaderScene) {
    auto r = sm2("trace dump " + kTraces + "shader_scene.trace");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 2u + 174u);  // properties, then every call apitrace dump lists
    EXPECT_EQ(lines[2], "0 Direct3DCreate9(SDKVersion = 32) = 0x34f290");
    EXPECT_EQ(lines[2 + 13], "13 memcpy(dest = 0x3b6e10, src = blob(432), n = 432) // fake");
    EXPECT_EQ(lines[2 + 27],
              "27 IDirect3DDevice9::Clear(this = 0x34f900, Count = 0, pRects = NULL, Flags = D3DCLEAR_TARGET, "
              "Color = 4279246912, Z = 1, Stencil = 0) = D3D_OK");
    EXPECT_EQ(lines[2 + 7],
              "7 IDirect3DDevice9::CreatePixelShader(this = 0x34f900, pFunction = \"ps_2_0\\nmov oC0.xyzw, c0.xyzw\\n\", "
              "ppShader = &0x3b5940) = D3D_OK");
    EXPECT_EQ(lines.back().rfind("173 ", 0), 0u) << lines.back();
    // -o writes the same text to a file.
    const std::string out = tmp("shader_scene.txt");
    auto to_file = sm2("trace dump " + kTraces + "shader_scene.trace -o " + out);
    ASSERT_EQ(to_file.status, 0) << to_file.err;
    EXPECT_EQ(to_file.out, "");
    EXPECT_EQ(slurp(out), r.out);
    // stdin.
    auto piped = sm2("trace dump -", slurp(kTraces + "shader_scene.trace"));
    EXPECT_EQ(piped.status, 0) << piped.err;
    EXPECT_EQ(piped.out, r.out);
}

TEST(CliTrace, BrokenTracesNameTheByte) {
    const std::string data = slurp(kTraces + "shader_scene.trace");
    // Cut inside the first chunk: its declared length runs past the end.
    const std::string cut = tmp("cut.trace");
    write_file(cut, data.substr(0, 4000));
    auto r = sm2("trace dump " + cut);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("sm2 trace dump: " + cut + ": byte 0 (chunk at file offset 2): chunk at file offset 2 declares "),
              std::string::npos) << r.err;
    // Not a trace.
    const std::string text = tmp("not.trace");
    write_file(text, "sm2cs 1\nPresent\n");
    auto t = sm2("trace dump " + text);
    EXPECT_EQ(t.status, 1);
    EXPECT_NE(t.err.find(text + ": byte 0: not an apitrace file in the Snappy container"), std::string::npos) << t.err;
    // A missing file; a usage error.
    auto missing = sm2("trace dump " + tmp("nothing.trace"));
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("nothing.trace"), std::string::npos) << missing.err;
    EXPECT_EQ(sm2("trace dump").status, 2);
}

// sm2 cs import of shader_scene: the report, then a replay with no refusal whose two frames are
// the program's own read-backs (Wine 8.0 d3d9 on llvmpipe) within 2/255: the stencil, colour-write
// and clear results are exact, the differences (at most 2/255, 27086 and 28785 pixels) are in the
// bilinear sampling of the render target and the alpha blending, where the two rasterizers round
// differently.
TEST(CliTrace, ImportShaderSceneReplaysToTheCapturedFrames) {
    const std::string stream = tmp("shader_scene.sm2cs");
    auto r = sm2("cs import " + kTraces + "shader_scene.trace -o " + stream);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "sm2 cs import: " + kTraces + "shader_scene.trace: imported 153, accepted 21, skipped 0 of 174 calls\n");
    const std::string text = slurp(stream);
    EXPECT_EQ(text.rfind("sm2cs 1\n# imported from shader_scene.trace by sm2 cs import: 153 of 174 calls\n"
                         "CreateDevice 256 256 X8R8G8B8 D24S8\nCreateVertexShader vs_3b0710 u32[", 0), 0u) << text.substr(0, 300);
    // The binary form holds the same stream.
    const std::string packed = tmp("shader_scene.sm2cb");
    ASSERT_EQ(sm2("cs import " + kTraces + "shader_scene.trace --quiet -o " + packed).status, 0);
    EXPECT_EQ(sm2("cs dump " + packed).out, text);
    // On stdout without -o.
    EXPECT_EQ(sm2("cs import --quiet " + kTraces + "shader_scene.trace").out, text);

    const std::string dir = tmp("shader_scene_frames");
    auto replay = sm2("replay " + stream + " -o " + dir + " --quiet");
    ASSERT_EQ(replay.status, 0) << replay.err;
    EXPECT_EQ(replay.err, "");
    for (int i = 0; i < 2; ++i) {
        const std::string ours = dir + "/frame_000" + std::to_string(i) + ".png";
        const std::string theirs = kTraces + "shader_scene/frame_" + std::to_string(i) + ".png";
        auto d = sm2("diff " + ours + " " + theirs + " --tolerance 0.0079");  // 2/255 = 0.00784
        EXPECT_EQ(d.status, 0) << d.out << d.err;
        EXPECT_NE(d.out.find("size: 256x256"), std::string::npos) << d.out;
    }
}

// sm2 replay APP.trace imports the capture as it replays it. shader_scene: no refusal, both
// frames within 2/255 of the program's read-backs, as through cs import. mixed_states: its 38
// fixed-function DrawPrimitiveUP draw, no call is refused.
TEST(CliTrace, ReplayOfATraceImportsItAsItGoes) {
    const std::string dir = tmp("shader_scene_direct");
    auto r = sm2("replay " + kTraces + "shader_scene.trace -o " + dir + " --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("2 frames, 153 calls in "), std::string::npos) << r.out;
    for (int i = 0; i < 2; ++i) {
        auto d = sm2("diff " + dir + "/frame_000" + std::to_string(i) + ".png " + kTraces + "shader_scene/frame_" +
                     std::to_string(i) + ".png --tolerance 0.0079");
        EXPECT_EQ(d.status, 0) << d.out << d.err;
    }
    const std::string mixed = tmp("mixed_states_direct");
    auto m = sm2("replay " + kTraces + "mixed_states.trace -o " + mixed + " --quiet");
    EXPECT_EQ(m.status, 0) << m.err;
    EXPECT_NE(m.out.find("2 frames, 227 calls in "), std::string::npos) << m.out;
    EXPECT_NE(m.out.find(": 38 draws, "), std::string::npos) << m.out;
    EXPECT_EQ(m.err, "");
    // Against Wine's frames: at most 0.15% of the pixels differ by more than 1/255 (measured 71
    // and 78), all in the StretchRect LINEAR cell and at line ends (ApitraceImport.
    // MixedStatesFramesMatchWine checks them class by class).
    for (int i = 0; i < 2; ++i) {
        auto d = sm2("diff " + mixed + "/frame_000" + std::to_string(i) + ".png " + kTraces + "mixed_states/frame_" +
                     std::to_string(i) + ".png --fail 0.004 --failpercent 0.15");
        EXPECT_LE(d.status, 1) << d.out << d.err;
    }
    EXPECT_TRUE(std::filesystem::exists(mixed + "/frame_0001.png"));
    // A broken trace stops with the reader's error after the calls before it.
    const std::string cut = tmp("cut_replay.trace");
    write_file(cut, slurp(kTraces + "ff_lit_cube.trace").substr(0, 100));
    auto bad = sm2("replay " + cut + " -o " + tmp("cut_replay"));
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.err.find("byte 0 (chunk at file offset 2)"), std::string::npos) << bad.err;
}

// The acceptance check of the fixed-function pipeline: sm2 replay ff_lit_cube.trace (a lit,
// textured, alpha-tested, fogged cube, a smaller one, a vertex-coloured floor) draws all 9
// draws with no refusal, and each frame is within 2/255 of Wine's read-back except at most 4
// pixels (0.0061%): measured 1, 0 and 1, each on the alpha-test edge of a hole, where the
// LINEAR-filtered texture alpha is within a rounding of ALPHAREF 128 and Wine filters in 8-bit
// fixed point (../shared/d3d9ref/README.md) where we filter in float.
TEST(CliTrace, FixedFunctionLitCubeMatchesWine) {
    const std::string dir = tmp("ff_lit_cube_frames");
    auto r = sm2("replay " + kTraces + "ff_lit_cube.trace -o " + dir + " --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("3 frames, 149 calls in "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(": 9 draws, "), std::string::npos) << r.out;
    for (int i = 0; i < 3; ++i) {
        const std::string ours = dir + "/frame_000" + std::to_string(i) + ".png";
        const std::string theirs = kTraces + "ff_lit_cube/frame_" + std::to_string(i) + ".png";
        auto d = sm2("diff " + ours + " " + theirs + " --fail 0.0079 --failpercent 0.0062");
        EXPECT_LE(d.status, 1) << d.out << d.err;
        EXPECT_NE(d.out.find("size: 256x256"), std::string::npos) << d.out;
    }
}

TEST(CliTrace, ImportReportsEachSkippedKindOnce) {
    // ff_lit_cube and mixed_states: every call is in the vocabulary now (the 58 and 41
    // fixed-function calls, the device calls and state blocks included), so nothing is skipped.
    auto ff = sm2("cs import " + kTraces + "ff_lit_cube.trace -o " + tmp("ff.sm2cs"));
    ASSERT_EQ(ff.status, 0) << ff.err;
    EXPECT_NE(ff.err.find("imported 149, accepted 26, skipped 0 of 175 calls\n"), std::string::npos) << ff.err;
    auto r = sm2("cs import " + kTraces + "mixed_states.trace -o " + tmp("mixed.sm2cs"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("imported 227, accepted 41, skipped 0 of 268 calls\n"), std::string::npos) << r.err;
    // A broken trace: exit 1, the byte named, nothing written.
    const std::string cut = tmp("cut_import.trace");
    write_file(cut, slurp(kTraces + "ff_lit_cube.trace").substr(0, 100));
    const std::string out = tmp("cut_import.sm2cs");
    auto bad = sm2("cs import " + cut + " -o " + out);
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.err.find("sm2 cs import: " + cut + ": byte 0 (chunk at file offset 2): chunk at file offset 2 declares "),
              std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
