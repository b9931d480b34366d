// The command line's conventions (issue 14): streams that carry their device limits, output
// forms, help, errors a user can act on.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_support.h"

namespace {

using namespace cli_support;
namespace fs = std::filesystem;

const std::string kScenes = std::string(SM2_SOURCE_DIR) + "/samples/scenes/";

// Scene 27 needs a ps_2_x-size device; the stream says so (SetDeviceLimits), no flag needed.
TEST(CliConventions, LongShaderScenesBenchWithNoFlags) {
    auto r = sm2("bench " + kScenes + "27_final_combine.sm2cs --repeat 1 --threads 2");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("194 calls, 1 frames, 19 draws"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(kScenes + "27_final_combine.options"));
    EXPECT_FALSE(fs::exists(kScenes + "26_neon_light.options"));
}

}  // namespace

namespace {

std::string fresh_dir(const std::string& name) {
    const std::string dir = tmp(name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

const std::string kShader = "ps_2_0\nmov oC0, c0\n";
const std::string kTinyScene = "sm2cs 1\n# two frames\nCreateDevice 4 4 A8R8G8B8\nClear TARGET 0xFF00FF00 1 0\n"
                               "Present\n\nPresent\n";

TEST(CliConventions, AsmWritesBinaryOnlyToAFile) {
    const std::string dir = fresh_dir("asm_forms");
    // stdout: text
    auto hex = sm2("asm -", kShader);
    EXPECT_EQ(hex.out, "FFFF0200\n02000001 800F0800 A0E40000\n0000FFFF\n");
    // -o FILE: binary, 5 DWORDs
    ASSERT_EQ(sm2("asm - -o " + dir + "/a.pso", kShader).status, 0);
    EXPECT_EQ(fs::file_size(dir + "/a.pso"), 20u);
    // '-o -' is for text: binary there is refused, hex and c are fine
    auto bin = sm2("asm - -o - --format bin", kShader);
    EXPECT_EQ(bin.status, 2);
    EXPECT_TRUE(bin.out.empty());
    EXPECT_NE(bin.err.find("binary output goes to a file: use -o FILE"), std::string::npos) << bin.err;
    EXPECT_EQ(sm2("asm - -o - --format hex", kShader).out, hex.out);
    // Redirecting the hex into a file named like bytecode is not silent.
    write_file(dir + "/s.asm", kShader);
    std::system((std::string(SM2_TOOL) + " asm " + dir + "/s.asm > " + dir + "/x.bin 2> " + dir + "/x.err").c_str());
    EXPECT_EQ(slurp(dir + "/x.bin"), hex.out);
    EXPECT_NE(slurp(dir + "/x.err").find("x.bin: writing hex words (text) there; for the binary bytecode use -o"),
              std::string::npos)
        << slurp(dir + "/x.err");
    std::system((std::string(SM2_TOOL) + " asm " + dir + "/s.asm > " + dir + "/x.txt 2> " + dir + "/y.err").c_str());
    EXPECT_TRUE(slurp(dir + "/y.err").empty());
}

TEST(CliConventions, CsPackWritesBesideItsInputByDefault) {
    const std::string dir = fresh_dir("pack");
    write_file(dir + "/s.sm2cs", kTinyScene);
    auto r = sm2("cs pack " + dir + "/s.sm2cs");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    ASSERT_TRUE(fs::exists(dir + "/s.sm2cb"));
    EXPECT_EQ(sm2("cs dump " + dir + "/s.sm2cb").out, kTinyScene);
    EXPECT_EQ(sm2("cs pack " + dir + "/s.sm2cs -o -").status, 2);  // binary is not for stdout
    EXPECT_EQ(sm2("cs pack -", kTinyScene).status, 2);              // stdin: -o needed
    EXPECT_EQ(sm2("cs pack " + dir + "/s.sm2cb").status, 2);         // would overwrite its input
}

TEST(CliConventions, ReplayAndBenchNameFp64) {
    for (const char* command : {"replay - -o " , "bench - "}) {
        const std::string dir = fresh_dir("fp64");
        auto r = sm2(std::string(command) + (command[0] == 'r' ? dir : "") + " --precision fp64", kTinyScene);
        EXPECT_EQ(r.status, 2) << command;
        EXPECT_NE(r.err.find("--precision fp64 is the reference of single shaders (sm2 run --precision fp64)"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(dir + "/frame_0000.png"));
    }
}

TEST(CliConventions, HelpCommandAndDidYouMean) {
    auto h = sm2("help asm");
    EXPECT_EQ(h.status, 0);
    EXPECT_NE(h.out.find("--format"), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("Examples:\n  sm2 asm shader.asm"), std::string::npos) << h.out;
    EXPECT_EQ(sm2("asm --help").out, h.out);
    EXPECT_NE(sm2("help cs pack").out.find("writes scene.sm2cb beside it"), std::string::npos);
    EXPECT_NE(sm2("help").out.find("sm2 help COMMAND"), std::string::npos);
    // Every command's help has examples.
    for (const char* c : {"asm", "dis", "validate", "compile", "run", "cs pack", "cs dump", "cs import", "trace dump", "replay", "bench", "pixel", "debug", "diff"}) {
        auto r = sm2(std::string("help ") + c);
        EXPECT_EQ(r.status, 0) << c;
        EXPECT_NE(r.out.find("Examples:\n  sm2 " + std::string(c).substr(0, 2)), std::string::npos) << c << r.out;
    }
    auto typo = sm2("asn x.asm");
    EXPECT_EQ(typo.status, 2);
    EXPECT_NE(typo.err.find("sm2: unknown command 'asn'; did you mean 'asm'?"), std::string::npos) << typo.err;
    EXPECT_NE(sm2("replya s.sm2cs").err.find("did you mean 'replay'?"), std::string::npos);
    EXPECT_NE(sm2("cs pakc s.sm2cs").err.find("unknown command 'cs pakc'; did you mean 'cs pack'?"), std::string::npos);
    auto far = sm2("frobnicate");
    EXPECT_EQ(far.status, 2);
    EXPECT_NE(far.err.find("unknown command 'frobnicate' (sm2 --help lists the commands)"), std::string::npos) << far.err;
    auto bad_help = sm2("help dsi");
    EXPECT_EQ(bad_help.status, 2);
    EXPECT_NE(bad_help.err.find("did you mean 'dis'?"), std::string::npos) << bad_help.err;
}

TEST(CliConventions, ReplayRefusesOldFramesUnlessOverwrite) {
    const std::string dir = fresh_dir("overwrite");
    write_file(dir + "/notes.txt", "not a frame");
    auto first = sm2("replay - -o " + dir, kTinyScene);  // other files are no reason to refuse
    ASSERT_EQ(first.status, 0) << first.err;
    // Per-frame lines name the folder; summary and lines count frames and calls alike.
    EXPECT_NE(first.out.find((fs::path(dir) / "frame_0000.png").string() + ": "), std::string::npos) << first.out;
    EXPECT_NE(first.out.find((fs::path(dir) / "frame_0001.png").string() + ": "), std::string::npos) << first.out;
    EXPECT_NE(first.out.find("2 frames, 4 calls"), std::string::npos) << first.out;
    auto again = sm2("replay - -o " + dir, kTinyScene);
    EXPECT_EQ(again.status, 2);
    EXPECT_NE(again.err.find("already holds 2 frames of an earlier replay (frame_0000.png ... frame_0001.png); use "
                             "--overwrite"),
              std::string::npos)
        << again.err;
    // --overwrite: the old frames go, so a one-frame replay leaves one frame.
    auto one = sm2("replay - -o " + dir + " --overwrite --quiet", "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nPresent\n");
    EXPECT_EQ(one.status, 0) << one.err;
    EXPECT_TRUE(fs::exists(dir + "/frame_0000.png"));
    EXPECT_FALSE(fs::exists(dir + "/frame_0001.png"));
    EXPECT_TRUE(fs::exists(dir + "/notes.txt"));
}

}  // namespace

namespace {

// sm2 run --json: numbers are numbers (the shortest text that reads back to the same float);
// inf/-inf/nan are null there and named in the lane's "nonfinite" object.
TEST(CliConventions, RunJsonHasNumbersAndNamesNonFiniteValues) {
    const std::string shader = "ps_2_0\ndef c1, 0.1, -2.5, 0, 1\nrcp r0.x, c1.z\nmov r0.y, c1.x\nmov r0.z, c1.y\n"
                               "add r0.w, r0.x, -r0.x\nmov oC0, r0\n";
    auto r = sm2("run - --json", shader);
    ASSERT_EQ(r.status, 0) << r.err;
    // rcp(0) = +inf; inf - inf = nan
    EXPECT_EQ(r.out, "{\"shader\":\"ps_2_0\",\"precision\":\"fp32\",\"lanes\":[{\"oC0\":{\"x\":null,\"y\":0.1,"
                     "\"z\":-2.5,\"w\":null},\"nonfinite\":{\"oC0.x\":\"inf\",\"oC0.w\":\"nan\"}}]}\n");
    auto text = sm2("run -", shader);
    EXPECT_EQ(text.out, "oC0 = inf 0.1 -2.5 nan\n");
}

}  // namespace
