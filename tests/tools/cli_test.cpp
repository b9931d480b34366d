// The sm2 command line, run as a user would: output, files written and exit status
// (0 ok, 1 invalid input, 2 bad usage).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <cmath>
#include <filesystem>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_support.h"

namespace {

// Running sm2 (Run, sm2, tmp, slurp, write_file): tests/tools/cli_support.h.
using namespace cli_support;

const std::string kExampleA = std::string(SM2_SOURCE_DIR) + "/tests/assembler/corpus/example_a_ps.asm";

TEST(Cli, AsmPrintsHexOnStdoutByDefault) {
    auto r = sm2("asm " + kExampleA);
    ASSERT_EQ(r.status, 0) << r.err;
    // bytecode.md §13 example A, one statement per line
    EXPECT_EQ(r.out,
              "FFFF0200\n"
              "0200001F 80000000 B0030000\n"
              "0200001F 80000000 B00F0001\n"
              "0200001F 80000000 900F0000\n"
              "0200001F 90000000 A00F0800\n"
              "0200001F 98000000 A00F0801\n"
              "05000051 A00F0000 3F000000 3F800000 00000000 3E800000\n"
              "03000042 800F0000 B0E40000 A0E40800\n"
              "03010042 802F0001 B0E40001 A0E40801\n"
              "03000005 802F0000 80E40000 90E40000\n"
              "04000012 801F0002 A0000000 80E40000 80E40001\n"
              "02000001 80080002 A0550000\n"
              "02000001 800F0800 80E40002\n"
              "0000FFFF\n");
}

TEST(Cli, AsmBinaryFileThenDisThenAsmAgainIsIdentical) {
    const std::string bin = tmp("a.bin"), text = tmp("a.dis.asm"), bin2 = tmp("a2.bin");
    ASSERT_EQ(sm2("asm " + kExampleA + " -o " + bin).status, 0);
    const std::string bytes = slurp(bin);
    ASSERT_EQ(bytes.size(), 46u * 4u);  // example A has 46 tokens
    EXPECT_EQ(static_cast<unsigned char>(bytes[3]), 0xFF);  // version token, little-endian
    EXPECT_EQ(static_cast<unsigned char>(bytes[2]), 0xFF);
    ASSERT_EQ(sm2("dis " + bin + " -o " + text).status, 0);
    ASSERT_EQ(sm2("asm " + text + " -o " + bin2).status, 0);
    EXPECT_EQ(slurp(bin2), bytes);
}

TEST(Cli, AsmKeepsTheSourceOrderUnlessWineOrder) {
    const std::string text = "ps_2_0\ndef c0, 1, 1, 1, 1\ndcl t0\nmov oC0, c0\n";
    auto source = sm2("asm -", text);
    ASSERT_EQ(source.status, 0) << source.err;
    EXPECT_EQ(source.out,
              "FFFF0200\n05000051 A00F0000 3F800000 3F800000 3F800000 3F800000\n0200001F 80000000 B00F0000\n"
              "02000001 800F0800 A0E40000\n0000FFFF\n");
    auto wine = sm2("asm - --wine-order", text);
    ASSERT_EQ(wine.status, 0) << wine.err;
    EXPECT_EQ(wine.out,
              "FFFF0200\n0200001F 80000000 B00F0000\n05000051 A00F0000 3F800000 3F800000 3F800000 3F800000\n"
              "02000001 800F0800 A0E40000\n0000FFFF\n");
}

// fxc output (SDL's YUV pixel shader, tests/assembler/compiled): the constant table is decoded
// into comments and the text assembles back to the same file.
TEST(Cli, DisOfCompilerOutputDecodesTheTableAndReassemblesIdentically) {
    const std::string blob = std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/decoder/fxc_ps_yuv_ctab.bin";
    const std::string text = tmp("yuv.asm"), again = tmp("yuv.bin");
    auto dis = sm2("dis " + blob + " -o " + text);
    ASSERT_EQ(dis.status, 0) << dis.err;
    const std::string listing = slurp(text);
    EXPECT_NE(listing.find("// CTAB constant table, 97 DWORDs: target ps_2_0, creator \"Microsoft (R) HLSL Shader "
                           "Compiler 10.1\""),
              std::string::npos)
        << listing;
    EXPECT_NE(listing.find("//   Yoffset                 float4     c0        1\n"), std::string::npos) << listing;
    EXPECT_NE(listing.find("//   theSampler+theTextureY  texture2D  s0        1\n"), std::string::npos) << listing;
    EXPECT_NE(listing.find("\ncomment 0x42415443, 0x0000001c, "), std::string::npos) << listing;
    ASSERT_EQ(sm2("asm " + text + " -o " + again).status, 0);
    EXPECT_EQ(slurp(again), slurp(blob));
}

TEST(Cli, AsmReadsStdinAndWritesCArray) {
    auto r = sm2("asm - --format c --name g_ps", "ps_2_0\nmov oC0, c0\n");
    ASSERT_EQ(r.status, 0) << r.err;
    // mov oC0, c0 = 02000001 800F0800 A0E40000
    EXPECT_NE(r.out.find("const unsigned int g_ps[5] = {"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0xFFFF0200, 0x02000001, 0x800F0800, 0xA0E40000, 0x0000FFFF"),
              std::string::npos) << r.out;
}

TEST(Cli, DisAcceptsHexWords) {
    auto r = sm2("dis -", "FFFF0200 02000001 800F0800 A0E40000 0000FFFF\n");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("ps_2_0"), std::string::npos);
    EXPECT_NE(r.out.find("mov oC0, c0"), std::string::npos) << r.out;
}

TEST(Cli, SyntaxErrorsGiveFileLineColumnAndStatus1) {
    const std::string path = tmp("bad.asm");
    write_file(path, "ps_2_0\nmov oC0, c0\nfrobnicate r0, r1\n");
    auto r = sm2("asm " + path);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(path + ":3:1: error:"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(Cli, BadBytecodeNamesTheToken) {
    // instruction length 5 runs past the end of a 4-token stream
    auto r = sm2("dis -", "FFFE0200 05000001 800F0000 0000FFFF");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("token 1 (byte 0x4)"), std::string::npos) << r.err;
}

TEST(Cli, GarbageIsNotBytecode) {
    auto r = sm2("dis -", "hello");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("not shader bytecode"), std::string::npos) << r.err;
}

TEST(Cli, MissingFileIsInvalidInput) {
    auto r = sm2("asm /nonexistent/file.asm");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
}

TEST(Cli, BadUsageIsStatus2) {
    EXPECT_EQ(sm2("").status, 2);                          // no subcommand
    EXPECT_EQ(sm2("asm").status, 2);                       // missing input
    EXPECT_EQ(sm2("asm x.asm --format pdf").status, 2);    // unknown format
    EXPECT_EQ(sm2("frobnicate").status, 2);                // unknown subcommand
}

TEST(Cli, HelpIsStatus0) {
    auto r = sm2("asm --help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("--format"), std::string::npos);
}

TEST(Cli, ValidateReportsRuleAndLocation) {
    const std::string path = tmp("invalid.asm");
    // ps_2_0 has no r12 (r0..r11)
    write_file(path, "ps_2_0\nmov r12, c0\nmov oC0, r12\n");
    auto r = sm2("validate " + path);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(path + ":2:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("r12"), std::string::npos) << r.err;
}

TEST(Cli, ValidateAcceptsEverySample) {
    for (const char* name : {"gouraud.vs", "gouraud.ps", "phong_lights.vs", "lake.vs",
                             "textured_phong.ps"}) {
        auto r = sm2("validate " + std::string(SM2_SOURCE_DIR) + "/samples/shaders/" + name + ".asm");
        EXPECT_EQ(r.status, 0) << name << ": " << r.err;
    }
}

TEST(Cli, CommandStreamPackThenDumpIsIdentical) {
    const std::string text = std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/command_stream/triangle.sm2cs";
    const std::string packed = tmp("triangle.sm2cb");
    ASSERT_EQ(sm2("cs pack " + text + " -o " + packed).status, 0);
    EXPECT_EQ(slurp(packed).substr(0, 4), "SM2C");
    auto r = sm2("cs dump " + packed);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, slurp(text));
}

TEST(Cli, CommandStreamErrorsNameTheLine) {
    auto r = sm2("cs dump -", "sm2cs 1\nPresent\nDrawPrimitive TRIANGLELIST 0 1x\n");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("<stdin>:3:30: error: not a number '1x'"), std::string::npos) << r.err;
    EXPECT_EQ(sm2("cs").status, 2);  // needs pack or dump
}

const std::string kSamples = std::string(SM2_SOURCE_DIR) + "/samples/shaders/";

TEST(CliRun, VertexShaderOutputs) {
    // identity matrix in c0..c3: oPos = v0 with w from the (0,0,0,1) default fill
    auto r = sm2("run " + kSamples + "gouraud.vs.asm --input v0=1,2,3 --input v1=0.5,0.25,1,1 "
                 "--const c0=1,0,0,0 --const c1=0,1,0,0 --const c2=0,0,1,0 --const c3=0,0,0,1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "oPos = 1 2 3 1\noD0 = 0.5 0.25 1 1\n");
}

// fxc output (burgerlib's vsstaticpositiondx9, tests/assembler/compiled): the constant table puts
// float4x4 ViewProjectionMatrix in c0..c3; oPos = (dot(v, c0), .., dot(v, c3)) with v = (v0.xyz, 1).
TEST(CliRun, ConstantsByTheirConstantTableName) {
    const std::string blob = std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/decoder/fxc_vs_matrix_ctab.bin";
    auto r = sm2("run " + blob + " --input v0=1,2,3 --input v1=0.5,0.25 "
                 "--const ViewProjectionMatrix=2,0,0,0,0,3,0,0,0,0,4,0,1,1,1,1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "oPos = 2 6 12 7\noT0.xy = 0.5 0.25\n");  // the shader writes oT0.xy only
    // Fewer values fill the first registers; c# still works beside names.
    auto partial = sm2("run " + blob + " --input v0=1,2,3 --const ViewProjectionMatrix=1,1,1,1 --const c3=0,0,0,1");
    ASSERT_EQ(partial.status, 0) << partial.err;
    EXPECT_EQ(partial.out.substr(0, 15), "oPos = 7 0 0 1\n");
    auto unknown = sm2("run " + blob + " --input v0=1,2,3 --const World=1");
    EXPECT_EQ(unknown.status, 2);
    EXPECT_NE(unknown.err.find("the constant table has no 'World' (it has: ViewProjectionMatrix)"), std::string::npos)
        << unknown.err;
    auto too_many = sm2("run " + blob + " --input v0=1,2,3 --const ViewProjectionMatrix=" + std::string(33, ',') + "1");
    EXPECT_EQ(too_many.status, 2);
    EXPECT_NE(too_many.err.find("expected 1 to 16 values for 'ViewProjectionMatrix' (float4x4, 4 registers)"),
              std::string::npos)
        << too_many.err;
    // A shader without a table.
    auto none = sm2("run " + kSamples + "gouraud.vs.asm --input v0=1,2,3 --const Matrix=1");
    EXPECT_EQ(none.status, 2);
    EXPECT_NE(none.err.find("the shader has no constant table to look 'Matrix' up in"), std::string::npos) << none.err;
}

TEST(Cli, ValidatePrintsFxcStyleSlotCounts) {
    // fxc's listing of this blob ends "approximately 12 instruction slots used (3 texture, 9 arithmetic)".
    auto r = sm2("validate " + std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/decoder/fxc_ps_yuv_ctab.bin");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(": valid ps_2_0, approximately 12 instruction slots used (3 texture, 9 arithmetic)\n"),
              std::string::npos)
        << r.out;
    auto vs = sm2("validate -", "vs_2_0\ndcl_position v0\nm4x4 oPos, v0, c0\n");
    ASSERT_EQ(vs.status, 0) << vs.err;
    EXPECT_EQ(vs.out, "<stdin>: valid vs_2_0, approximately 4 instruction slots used\n");
}

TEST(CliRun, PrecisionModesRoundAsSpecified) {
    const std::string shader = tmp("mul.asm");
    write_file(shader, "ps_2_0\nmul r0, c0, c1\nmov oC0, r0\n");
    const std::string consts = " --const c0=1,3,0.1,1 --const c1=0.3333333333,0.3333333333,1,1";
    // fp32: 1/3 = 0x3EAAAAAB prints as 0.33333334; 3 * (1/3) rounds to exactly 1
    EXPECT_EQ(sm2("run " + shader + consts).out, "oC0 = 0.33333334 1 0.1 1\n");
    // fp24 (s16e7): 1/3 = 1.0101010101010101|0101.. x 2^-2 rounds down to 0.333332061767578125;
    // 0.1 = 1.1001100110011001|1001.. x 2^-4 rounds up to 0.100000381469726562
    EXPECT_EQ(sm2("run " + shader + consts + " --precision fp24").out, "oC0 = 0.33333206 1 0.10000038 1\n");
    const std::string pp = tmp("mul_pp.asm");
    write_file(pp, "ps_2_0\nmul_pp r0, c0, c1\nmov oC0, r0\n");
    // fp16 for _pp: half(1/3) = 0x3555 = 0.333251953125, half(0.1) = 0x2E66 = 0.0999755859375
    EXPECT_EQ(sm2("run " + pp + consts + " --precision fp16").out, "oC0 = 0.33325195 1 0.099975586 1\n");
}

TEST(CliRun, BothEnginesGiveTheHandComputedValues) {
    const std::string shader = tmp("engines.asm");
    write_file(shader, "ps_2_0\nmul r0, c0, c1\nrcp r1.x, c1.x\nmov r0.w, r1.x\nmov oC0, r0\n");
    const std::string consts = " --const c0=1,3,0.1,1 --const c1=0.3333333333,0.3333333333,1,1";
    // mul as in PrecisionModesRoundAsSpecified; rcp(0x3EAAAAAB = 0.333333343) = 2.99999991, which
    // rounds to 3 (the float below 3 is 2.99999976)
    for (const char* engine : {"interpreter", "jit"})
        EXPECT_EQ(sm2("run " + shader + consts + " --engine " + engine).out, "oC0 = 0.33333334 1 0.1 3\n")
            << engine;
    EXPECT_EQ(sm2("run " + shader + " --engine tape").status, 2);
}

TEST(CliRun, LanesFromCsvAndTexkillAsJson) {
    const std::string shader = tmp("kill.asm"), lanes = tmp("kill.csv");
    write_file(shader, "ps_2_0\ndcl t0\ntexkill t0\nmov oC0, t0\n");
    write_file(lanes, "t0.x,t0.y,t0.z,t0.w\n1,2,3,4\n-1,0,0,0\n");
    auto r = sm2("run " + shader + " --lanes " + lanes + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "{\"shader\":\"ps_2_0\",\"precision\":\"fp32\",\"lanes\":"
                     "[{\"oC0\":{\"x\":1.0,\"y\":2.0,\"z\":3.0,\"w\":4.0}},{\"killed\":true}]}\n");
}

TEST(CliRun, TracePrintsEveryStepWithWhatItWrote) {
    const std::string shader = tmp("trace.asm"), lanes = tmp("trace.csv");
    write_file(shader, "ps_2_0\ndcl t0\ntexkill t0\nmov oC0, t0\n");
    write_file(lanes, "t0.x,t0.y,t0.z,t0.w\n1,2,3,4\n-1,0,0,0\n");
    auto r = sm2("run " + shader + " --lanes " + lanes + " --trace");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out,
              "#0  texkill t0\n"
              "    lane 0: kept\n"
              "    lane 1: killed\n"  // -1 < 0 in x
              "#1  mov oC0, t0\n"
              "    lane 0: x=1 y=2 z=3 w=4\n"
              "    lane 1: x=-1 y=0 z=0 w=0\n"
              "lane 0: oC0 = 1 2 3 4\n"
              "lane 1: killed (texkill)\n");
}

TEST(CliRun, StaticFlowConstantsFromTheCommandLine) {
    const std::string shader = tmp("flow.asm");
    // rep i0 adds c0 i0.x times; if b0 adds c1 once more
    write_file(shader, "vs_2_0\ndcl_position v0\nmov r0, v0\nrep i0\nadd r0, r0, c0\nendrep\n"
                       "if b0\nadd r0, r0, c1\nendif\nmov oPos, r0\n");
    auto r = sm2("run " + shader + " --const c0=1,0,0,0 --const c1=0,10,0,0 --int i0=3,0,0,0 --bool b0=true");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "oPos = 3 10 0 1\n");  // (0,0,0,1) + 3 * (1,0,0,0) + (0,10,0,0)
    EXPECT_EQ(sm2("run " + shader + " --const c0=1,0,0,0 --int i0=0,0,0,0").out, "oPos = 0 0 0 1\n");
}

TEST(CliRun, TexturesAndSamplerStates) {
    // A 2x2 TGA, 32 bpp BGRA, top-left origin: red green / blue white.
    const std::string image = tmp("quad.tga");
    const unsigned char tga[] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 32, 0x28,
                                 0, 0, 255, 255, 0, 255, 0, 255, 255, 0, 0, 255, 255, 255, 255, 255};
    write_file(image, std::string(reinterpret_cast<const char*>(tga), sizeof tga));
    const std::string shader = tmp("tex.asm");
    write_file(shader, "ps_2_0\ndcl t0.xy\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\n");
    // POINT (the default): (0.75, 0.25) is the centre of texel (1, 0), green
    EXPECT_EQ(sm2("run " + shader + " --texture s0=" + image + " --input t0=0.75,0.25").out, "oC0 = 0 1 0 1\n");
    // LINEAR at the centre: equal weights, (red + green + blue + white) / 4
    EXPECT_EQ(sm2("run " + shader + " --texture s0=" + image +
                  " --input t0=0.5,0.5 --sampler-state s0.MAGFILTER=LINEAR").out,
              "oC0 = 0.5 0.5 0.5 1\n");
    // WRAP (default) vs CLAMP at u = 1.25: wraps to texel 0 (red), clamps to texel 1 (green)
    EXPECT_EQ(sm2("run " + shader + " --texture s0=" + image + " --input t0=1.25,0.25").out, "oC0 = 1 0 0 1\n");
    EXPECT_EQ(sm2("run " + shader + " --texture s0=" + image +
                  " --input t0=1.25,0.25 --sampler-state s0.ADDRESSU=CLAMP").out,
              "oC0 = 0 1 0 1\n");
    auto missing = sm2("run " + shader + " --texture s0=/nonexistent.png");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("cannot open"), std::string::npos) << missing.err;
    // Malformed option values are usage errors (2), like every other
    auto bad = sm2("run " + shader + " --sampler-state s0.MAGFILTER=BILINEAR");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("not a D3DTEXF_* value"), std::string::npos) << bad.err;
    EXPECT_EQ(sm2("run " + shader + " --texture s16=" + image).status, 2);
}

TEST(CliRun, MalformedOptionsAreStatus2BadFilesStatus1) {
    const std::string shader = kSamples + "gouraud.ps.asm";
    struct Case {
        std::string args;
        std::string message;
    };
    const Case cases[] = {
        {"--input q0=1", "unknown input register 'q0'"},
        {"--input v2=1", "does not exist in ps_2_0"},
        {"--input v0=1,x", "bad number 'x'"},
        {"--input v0=1,2,3,4,5", "1 to 4 values"},
        {"--const c32=1", "out of range (c0..c31)"},
        {"--const c0", "expected cN=values"},
        {"--bool b0=maybe", "true or false"},
        {"--texture x0=a.png", "expected sN=FILE"},
        {"--sampler-state s0.NOSUCH=1", "unknown sampler state 'NOSUCH'"},
    };
    for (const Case& c : cases) {
        auto r = sm2("run " + shader + " " + c.args);
        EXPECT_EQ(r.status, 2) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    }
    auto missing = sm2("run " + shader + " --lanes /nonexistent.csv");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("cannot open"), std::string::npos) << missing.err;
    const std::string csv = tmp("bad.csv");
    write_file(csv, "v0.x,v0.q\n1,2\n");
    EXPECT_NE(sm2("run " + shader + " --lanes " + csv).err.find("component must be x, y, z or w"), std::string::npos);
    write_file(csv, "v0.x,v0.y\n1\n");
    EXPECT_NE(sm2("run " + shader + " --lanes " + csv).err.find(":2: 1 values for 2 columns"), std::string::npos);
    EXPECT_EQ(sm2("run " + shader + " --precision fp8").status, 2);
    const std::string invalid = tmp("invalid_run.asm");
    write_file(invalid, "ps_2_0\nmov r0, c0\n");  // never writes oC0
    auto r = sm2("run " + invalid);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("[outputs]"), std::string::npos) << r.err;
}


// ---------------------------------------------------------------------------------------------
// sm2 replay, sm2 bench, sm2 diff

std::string make_dir(const std::string& name) {
    const std::string dir = tmp(name);
    std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
    return dir;
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// Writes two 2x2 images and a 1x1 one through sm2 replay (SaveSurface), independently of Clear:
// a.png all opaque black, b.png the same but pixel (1,1) red 0x80, c.png 1x1.
std::string make_images() {
    const std::string dir = make_dir("images");
    write_file(dir + "/images.sm2cs",
               "sm2cs 1\n"
               "CreateRenderTarget a 2 2 A8R8G8B8\n"
               "LockRect a 0 u32[ 0xFF000000 0xFF000000 0xFF000000 0xFF000000 ]\n"
               "SaveSurface a \"a.png\"\n"
               "CreateRenderTarget b 2 2 A8R8G8B8\n"
               "LockRect b 0 u32[ 0xFF000000 0xFF000000 0xFF000000 0xFF800000 ]\n"
               "SaveSurface b \"b.png\"\n"
               "CreateRenderTarget c 1 1 A8R8G8B8\n"
               "SaveSurface c \"c.png\"\n");
    auto r = sm2("replay " + dir + "/images.sm2cs -o " + dir);
    EXPECT_EQ(r.status, 0) << r.err;
    return dir;
}

TEST(CliReplay, ClearAndPresentWriteTheClearedFrame) {
    const std::string dir = make_dir("replay_clear");
    const std::string stream = dir + "/clear.sm2cs";
    write_file(stream,
               "sm2cs 1\n"
               "CreateDevice 2 2 A8R8G8B8\n"
               "Clear TARGET 0xFF336699 1 0\n"
               "Present\n"
               "CreateRenderTarget ref 2 2 A8R8G8B8\n"
               "LockRect ref 0 u32[ 0xFF336699 0xFF336699 0xFF336699 0xFF336699 ]\n"
               "SaveSurface ref \"ref.png\"\n"
               "LockRect ref 0 u32[ 0xFF336699 0xFF336699 0xFF336699 0xFF33669A ]\n"
               "SaveSurface ref \"off_by_one.png\"\n");
    auto r = sm2("replay " + stream + " -o " + dir + "/out");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(exists(dir + "/out/frame_0000.png"));
    EXPECT_FALSE(exists(dir + "/out/frame_0001.png"));
    EXPECT_NE(r.out.find("frame_0000.png: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("1 frames, 8 calls"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0 draws"), std::string::npos) << r.out;
    // The frame holds exactly the bytes written by hand, and not one more or less blue.
    EXPECT_EQ(sm2("diff " + dir + "/out/frame_0000.png " + dir + "/out/ref.png").status, 0);
    EXPECT_EQ(sm2("diff " + dir + "/out/frame_0000.png " + dir + "/out/off_by_one.png").status, 2);  // FAILURE
    // --quiet keeps only the summary
    auto q = sm2("replay " + stream + " -o " + dir + "/out2 --quiet --threads 3");
    EXPECT_EQ(q.status, 0) << q.err;
    EXPECT_EQ(q.out.find("frame_0000.png"), std::string::npos) << q.out;
    EXPECT_NE(q.out.find("1 frames"), std::string::npos) << q.out;
    EXPECT_TRUE(q.err.empty()) << q.err;  // no progress: stderr is not a terminal
}

TEST(CliReplay, BenchNamesItsEngineAndCompilesOnlyInTheFirstRun) {
    const std::string scene = std::string(SM2_SOURCE_DIR) + "/samples/scenes/14_textured_phong.sm2cs";
    auto jit = sm2("bench " + scene + " --repeat 2 --threads 1");
    ASSERT_EQ(jit.status, 0) << jit.err;
    EXPECT_NE(jit.out.find("engine: jit"), std::string::npos) << jit.out;
    EXPECT_NE(jit.out.find("later runs compiled 0"), std::string::npos) << jit.out;
    auto interpreted = sm2("bench " + scene + " --repeat 1 --threads 1 --engine interpreter");
    ASSERT_EQ(interpreted.status, 0) << interpreted.err;
    EXPECT_NE(interpreted.out.find("engine: interpreter"), std::string::npos) << interpreted.out;
}

// --jit-cache DIR: the first run compiles and fills the folder, a second process loads every
// routine from it, and both replays write the same frame.
TEST(CliReplay, JitCacheFolderServesALaterProcess) {
    const std::string scene = std::string(SM2_SOURCE_DIR) + "/samples/scenes/14_textured_phong.sm2cs";
    const std::string dir = make_dir("jit_cache");
    const std::string cache = dir + "/cache";
    auto cold = sm2("bench " + scene + " --repeat 1 --threads 1 --jit-cache " + cache);
    ASSERT_EQ(cold.status, 0) << cold.err;
    if (cold.out.find("not in this build") != std::string::npos) GTEST_SKIP() << "built without the JIT";
    EXPECT_EQ(cold.out.find("loaded from the JIT cache"), std::string::npos) << cold.out;
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(cache)) files += entry.path().extension() == ".sm2jit";
    EXPECT_GT(files, 0u);
    auto warm = sm2("bench " + scene + " --repeat 1 --threads 1 --jit-cache " + cache);
    ASSERT_EQ(warm.status, 0) << warm.err;
    // "N routines compiled in the first run (N loaded from the JIT cache)": every one.
    std::smatch counts;
    const std::regex pattern("(\\d+) routines compiled in the first run \\((\\d+) loaded from the JIT cache\\)");
    ASSERT_TRUE(std::regex_search(warm.out, counts, pattern)) << warm.out;
    EXPECT_EQ(counts[1].str(), counts[2].str()) << warm.out;
    EXPECT_NE(counts[1].str(), "0") << warm.out;
    ASSERT_EQ(sm2("replay " + scene + " -o " + dir + "/a --quiet --threads 1").status, 0);
    ASSERT_EQ(sm2("replay " + scene + " -o " + dir + "/b --quiet --threads 1 --jit-cache " + cache).status, 0);
    EXPECT_EQ(sm2("diff " + dir + "/a/frame_0000.png " + dir + "/b/frame_0000.png").status, 0);
}

TEST(CliReplay, RefusedCallsExit1WithFileLineAfterFinishingTheStream) {
    const std::string dir = make_dir("replay_bad");
    const std::string stream = dir + "/bad.sm2cs";
    write_file(stream,
               "sm2cs 1\n"
               "CreateDevice 2 2 A8R8G8B8\n"
               "CreateVertexBuffer vb\n"
               "SetRenderState CULLMODE SIDEWAYS\n"
               "Present\n");
    auto r = sm2("replay " + stream + " -o " + dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(stream + ":3: D3DERR_INVALIDCALL: CreateVertexBuffer: expects 2 arguments"),
              std::string::npos) << r.err;
    EXPECT_NE(r.err.find(stream + ":4: D3DERR_INVALIDCALL: SetRenderState: "), std::string::npos) << r.err;
    EXPECT_TRUE(exists(dir + "/frame_0000.png"));  // the Present after the errors still ran

    // A stream that does not parse stops with file:line:column.
    auto p = sm2("replay - -o " + dir, "sm2cs 1\nPresent\nFrobnicate\n");
    EXPECT_EQ(p.status, 1);
    EXPECT_NE(p.err.find("<stdin>:3:1: error: unknown call 'Frobnicate'"), std::string::npos) << p.err;
    EXPECT_EQ(sm2("replay /nonexistent/s.sm2cs -o " + dir).status, 1);
}

// A pixel shader of 65 arithmetic slots (one over ps_2_0's 64) in a heredoc: refused by default
// with its line inside the heredoc, accepted with --max-slots (a ps_2_x-size device).
TEST(CliReplay, MaxSlotsReachesHeredocShaders) {
    const std::string dir = make_dir("replay_slots");
    const std::string stream = dir + "/long.sm2cs";
    std::string text = "sm2cs 1\nCreateDevice 2 2 A8R8G8B8\nCreatePixelShader ps asm<<END\nps_2_0\ndef c0, 1, 1, 1, 1\nmov r0, c0\n";
    for (int i = 0; i < 63; ++i) text += "add r0, r0, c0\n";
    text += "mov oC0, r0\nEND\nPresent\n";
    write_file(stream, text);
    auto refused = sm2("replay " + stream + " -o " + dir + "/a --quiet");
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.err.find("CreatePixelShader"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("slot"), std::string::npos) << refused.err;
    auto accepted = sm2("replay " + stream + " -o " + dir + "/b --quiet --max-slots 96");
    EXPECT_EQ(accepted.status, 0) << accepted.err;
}

TEST(CliReplay, SampleScenesReplayWithoutDiagnostics) {
    const std::string dir = make_dir("replay_scenes");
    const std::string scenes = std::string(SM2_SOURCE_DIR) + "/samples/scenes/";
    for (const char* name : {"01_gouraud_triangle", "02_shared_edges_stencil", "09_lake", "12_cube_map"}) {
        auto r = sm2("replay " + scenes + name + ".sm2cs -o " + dir + "/" + name + " --quiet");
        EXPECT_EQ(r.status, 0) << name << ": " << r.err;
        EXPECT_TRUE(r.err.empty()) << name << ": " << r.err;
        EXPECT_TRUE(exists(dir + "/" + name + "/frame_0000.png")) << name;
    }
}

TEST(CliReplay, BinaryStreamsReplayToo) {
    const std::string dir = make_dir("replay_binary");
    write_file(dir + "/s.sm2cs", "sm2cs 1\nCreateDevice 1 1 A8R8G8B8\nPresent\nPresent\n");
    ASSERT_EQ(sm2("cs pack " + dir + "/s.sm2cs -o " + dir + "/s.sm2cb").status, 0);
    auto r = sm2("replay " + dir + "/s.sm2cb -o " + dir + "/out");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(exists(dir + "/out/frame_0001.png"));
}

// A captured scene with side files and heredocs, packed to the binary form (which carries the
// side files' bytes) and replayed from a folder without them, draws the same frames.
TEST(CliReplay, PackedSceneReplaysToTheSameFrames) {
    const std::string dir = make_dir("replay_packed");
    const std::string scene = std::string(SM2_SOURCE_DIR) + "/samples/scenes/14_textured_phong.sm2cs";
    ASSERT_EQ(sm2("cs pack " + scene + " -o " + dir + "/scene.sm2cb").status, 0);
    auto text = sm2("replay " + scene + " -o " + dir + "/text --quiet");
    ASSERT_EQ(text.status, 0) << text.err;
    auto binary = sm2("replay " + dir + "/scene.sm2cb -o " + dir + "/binary --quiet");
    ASSERT_EQ(binary.status, 0) << binary.err;
    EXPECT_EQ(sm2("diff " + dir + "/text/frame_0000.png " + dir + "/binary/frame_0000.png").status, 0);
}

TEST(CliReplay, BadArgumentsAreStatus2) {
    EXPECT_EQ(sm2("replay").status, 2);                         // no stream
    EXPECT_EQ(sm2("replay s.sm2cs").status, 2);                 // no -o
    EXPECT_EQ(sm2("replay s.sm2cs -o out --threads 0").status, 2);
    EXPECT_EQ(sm2("replay s.sm2cs -o out --frobnicate").status, 2);
    EXPECT_EQ(sm2("bench").status, 2);
    EXPECT_EQ(sm2("bench s.sm2cs --repeat 0").status, 2);
    EXPECT_EQ(sm2("bench s.sm2cs --repeat x").status, 2);
    EXPECT_EQ(sm2("diff a.png").status, 2);
    // Range errors say what is wrong in a few words (CLI11's own printed DBL_MAX in full).
    const auto negative = sm2("diff a.png b.png --tolerance -1");
    EXPECT_EQ(negative.status, 2);
    EXPECT_NE(negative.err.find("'-1' is negative: give 0 or more"), std::string::npos) << negative.err;
    EXPECT_LT(negative.err.size(), 200u) << negative.err;
    const auto zero_scale = sm2("diff a.png b.png --heatmap-scale 0");
    EXPECT_EQ(zero_scale.status, 2);
    EXPECT_NE(zero_scale.err.find("'0' is not positive"), std::string::npos) << zero_scale.err;
    auto help = sm2("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* command : {"replay", "bench", "diff"}) EXPECT_NE(help.out.find(command), std::string::npos) << command;
}

// A stream without Present (the d3d9ref translator's bench_1024) has no frame rate: bench says so
// and gives runs per second instead of "0.000".
TEST(CliBench, AStreamWithoutPresentHasNoFrameRate) {
    const std::string dir = make_dir("bench_no_present");
    write_file(dir + "/b.sm2cs", "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nClear TARGET 0xFF000000 1 0\n");
    auto r = sm2("bench " + dir + "/b.sm2cs --repeat 3");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("0 frames"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("frames/s: - (the stream presents no frame: runs/s "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("frames/s: 0"), std::string::npos) << r.out;
}

TEST(CliBench, ReportsRatesOfTheMedianRun) {
    const std::string dir = make_dir("bench");
    write_file(dir + "/b.sm2cs",
               "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nClear TARGET 0xFF000000 1 0\nPresent\nPresent\nPresent\n");
    auto r = sm2("bench " + dir + "/b.sm2cs --repeat 3 --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("5 calls, 3 frames, 0 draws"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3 runs, 2 threads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("frames/s: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("pixels shaded/s: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("vertices/s: "), std::string::npos) << r.out;
    // in memory: no frames written anywhere
    EXPECT_FALSE(exists("frame_0000.png"));
    EXPECT_FALSE(exists(dir + "/frame_0000.png"));
    auto bad = sm2("bench -", "sm2cs 1\nPresent\n");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.err.find("<stdin>:2: D3DERR_INVALIDCALL: Present:"), std::string::npos) << bad.err;
}

// --compare against golden frames written by hand: a 2x2 clear to 0xFF336699, and the same with
// blue one step up (0x9A) at pixel (1,1): an error of 1/255 in channel B there.
TEST(CliReplay, CompareChecksEachFrameAgainstGoldenFrames) {
    const std::string dir = make_dir("replay_compare");
    write_file(dir + "/clear.sm2cs", "sm2cs 1\nCreateDevice 2 2 A8R8G8B8\nClear TARGET 0xFF336699 1 0\nPresent\nPresent\n");
    write_file(dir + "/golden.sm2cs",
               "sm2cs 1\n"
               "CreateRenderTarget ref 2 2 A8R8G8B8\n"
               "LockRect ref 0 u32[ 0xFF336699 0xFF336699 0xFF336699 0xFF336699 ]\n"
               "SaveSurface ref \"exact/frame_0000.png\"\n"
               "SaveSurface ref \"exact/frame_0001.png\"\n"
               "SaveSurface ref \"off/frame_0000.png\"\n"
               "LockRect ref 0 u32[ 0xFF336699 0xFF336699 0xFF336699 0xFF33669A ]\n"
               "SaveSurface ref \"off/frame_0001.png\"\n"
               "SaveSurface ref \"short/frame_0000.png\"\n"
               "SaveSurface ref \"long/frame_0000.png\"\n"
               "SaveSurface ref \"long/frame_0001.png\"\n"
               "SaveSurface ref \"long/frame_0002.png\"\n");
    for (const char* sub : {"exact", "off", "short", "long"}) std::filesystem::create_directories(dir + "/g/" + sub);
    auto golden = sm2("replay " + dir + "/golden.sm2cs -o " + dir + "/g");
    ASSERT_EQ(golden.status, 0) << golden.err;
    const std::string replay = "replay " + dir + "/clear.sm2cs --quiet --overwrite -o " + dir + "/out --compare " + dir;
    auto pass = sm2(replay + "/g/exact");
    EXPECT_EQ(pass.status, 0) << pass.out << pass.err;
    EXPECT_NE(pass.out.find("compare frame_0001.png: PASS, max error 0,"), std::string::npos) << pass.out;
    EXPECT_NE(pass.out.find("2 frames compared with " + dir + "/g/exact: PASS\n"), std::string::npos) << pass.out;
    auto fail = sm2(replay + "/g/off");
    EXPECT_EQ(fail.status, 2) << fail.out << fail.err;
    EXPECT_NE(fail.out.find("compare frame_0000.png: PASS"), std::string::npos) << fail.out;
    EXPECT_NE(fail.out.find("compare frame_0001.png: FAILURE, max error 0.00392157 at (1, 1) B, PSNR "),
              std::string::npos) << fail.out;  // 1/255
    EXPECT_EQ(sm2(replay + "/g/off --fail 0.004").status, 0);
    EXPECT_EQ(sm2(replay + "/g/off --fail 0.004 --warn 0.001").status, 1);
    // a frame the golden folder lacks, and a golden frame the replay did not write
    auto short_golden = sm2(replay + "/g/short");
    EXPECT_EQ(short_golden.status, 4);
    EXPECT_NE(short_golden.out.find("compare frame_0001.png: UNREADABLE: "), std::string::npos) << short_golden.out;
    auto long_golden = sm2(replay + "/g/long");
    EXPECT_EQ(long_golden.status, 4);
    EXPECT_NE(long_golden.out.find("compare frame_0002.png: UNREADABLE: in " + dir + "/g/long, not written by the replay (2 frames)"),
              std::string::npos) << long_golden.out;
    EXPECT_EQ(sm2(replay + "/nonexistent").status, 4);
    // a golden frame number past any integer is a frame the replay did not write
    std::filesystem::copy(dir + "/g/exact", dir + "/g/huge");
    write_file(dir + "/g/huge/frame_99999999999999999999999.png", "x");
    auto huge = sm2(replay + "/g/huge");
    EXPECT_EQ(huge.status, 4) << huge.out << huge.err;
    EXPECT_NE(huge.out.find("compare frame_99999999999999999999999.png: UNREADABLE: in "), std::string::npos) << huge.out;
}

// A sample scene against its own earlier replay: every frame passes.
TEST(CliReplay, CompareSampleSceneWithItsOwnFrames) {
    const std::string dir = make_dir("replay_compare_scene");
    const std::string scene = std::string(SM2_SOURCE_DIR) + "/samples/scenes/02_shared_edges_stencil.sm2cs";
    ASSERT_EQ(sm2("replay " + scene + " -o " + dir + "/golden --quiet").status, 0);
    auto r = sm2("replay " + scene + " -o " + dir + "/again --quiet --threads 1 --compare " + dir + "/golden");
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("frame_0000.png: PASS, max error 0, PSNR inf dB"), std::string::npos) << r.out;
}

// Three full-screen draws (a 4x4 target, two triangles covering each pixel once): a solid colour
// (16 pixels rasterized, shaded, written), a shader whose texkill discards every pixel (16
// killed, none written), and alpha test NEVER (16 shaded, none written). Calls 15, 17, 21 on
// lines 31, 33, 37.
const char* const kStatsScene =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateVertexBuffer vb 48\n"
    "Lock vb 0 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs asm<<END\n"
    "vs_2_0\n"
    "dcl_position v0\n"
    "mov oPos, v0\n"
    "END\n"
    "CreatePixelShader solid asm<<END\n"
    "ps_2_0\n"
    "def c0, 1, 0, 0, 1\n"
    "mov oC0, c0\n"
    "END\n"
    "CreatePixelShader kill asm<<END\n"
    "ps_2_0\n"
    "def c0, 1, 0, 0, 1\n"
    "def c1, -1, -1, -1, -1\n"
    "mov r0, c1\n"
    "texkill r0\n"
    "mov oC0, c0\n"
    "END\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetStreamSource 0 vb 0 12\n"
    "SetRenderState CULLMODE NONE\n"
    "Clear TARGET 0xFF000000 1 0\n"
    "BeginScene\n"
    "SetPixelShader solid\n"
    "DrawPrimitive TRIANGLESTRIP 0 2\n"
    "SetPixelShader kill\n"
    "DrawPrimitive TRIANGLESTRIP 0 2\n"
    "SetPixelShader solid\n"
    "SetRenderState ALPHATESTENABLE TRUE\n"
    "SetRenderState ALPHAFUNC NEVER\n"
    "DrawPrimitive TRIANGLESTRIP 0 2\n"
    "EndScene\n"
    "Present\n";

TEST(CliReplay, StatsCountEachDrawsPixels) {
    const std::string dir = make_dir("replay_stats");
    write_file(dir + "/s.sm2cs", kStatsScene);
    auto r = sm2("replay " + dir + "/s.sm2cs -o " + dir + "/out --quiet --stats json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["calls"], 23);
    ASSERT_EQ(j["draws"].size(), 3u);
    const struct {
        int call, line, killed, written;
    } expected[] = {{15, 31, 0, 16}, {17, 33, 16, 0}, {21, 37, 0, 0}};
    for (size_t i = 0; i < 3; ++i) {
        const auto& d = j["draws"][i];
        EXPECT_EQ(d["call"], expected[i].call) << i;
        EXPECT_EQ(d["line"], expected[i].line) << i;
        EXPECT_EQ(d["name"], "DrawPrimitive") << i;
        EXPECT_EQ(d["frame"], 0) << i;
        EXPECT_EQ(d["pixels_rasterized"], 16) << i;
        EXPECT_EQ(d["pixels_shaded"], 16) << i;
        EXPECT_EQ(d["pixels_killed"], expected[i].killed) << i;
        EXPECT_EQ(d["pixels_written"], expected[i].written) << i;
        EXPECT_EQ(d["vertices_shaded"], 4) << i;
        EXPECT_EQ(d["primitives"], 2) << i;
        EXPECT_GE(d["seconds"].get<double>(), 0.0) << i;
    }
    EXPECT_EQ(j["total"]["pixels_written"], 16);
    EXPECT_EQ(j["total"]["pixels_killed"], 16);
    auto table = sm2("replay " + dir + "/s.sm2cs -o " + dir + "/out --overwrite --quiet --stats table");
    ASSERT_EQ(table.status, 0) << table.err;
    EXPECT_NE(table.out.find("     17      33      0          16          16          16           0         4          2"),
              std::string::npos) << table.out;
    EXPECT_NE(table.out.find("  total                         48          48          16          16        12          6"),
              std::string::npos) << table.out;
    EXPECT_NE(table.out.find("1 frames, 23 calls"), std::string::npos) << table.out;
    EXPECT_EQ(sm2("replay " + dir + "/s.sm2cs -o " + dir + "/out --overwrite --stats csv").status, 2);
}

TEST(CliBench, JsonReport) {
    const std::string dir = make_dir("bench_json");
    write_file(dir + "/b.sm2cs",
               "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nClear TARGET 0xFF000000 1 0\nPresent\nPresent\nPresent\n");
    auto r = sm2("bench " + dir + "/b.sm2cs --repeat 3 --threads 2 --json --engine interpreter");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["calls"], 5);
    EXPECT_EQ(j["frames"], 3);
    EXPECT_EQ(j["draws"], 0);
    EXPECT_EQ(j["runs"], 3);
    EXPECT_EQ(j["threads"], 2);
    EXPECT_EQ(j["engine"], "interpreter");
    ASSERT_EQ(j["run_seconds"].size(), 3u);
    EXPECT_GT(j["median_seconds"].get<double>(), 0.0);
    EXPECT_LE(j["best_seconds"].get<double>(), j["median_seconds"].get<double>());
    EXPECT_NEAR(j["frames_per_second"].get<double>(), 3.0 / j["median_seconds"].get<double>(), 1e-6);
    EXPECT_EQ(j["refused_calls"], 0);
}

TEST(CliDiff, IdenticalImagesPass) {
    const std::string dir = make_images();
    auto r = sm2("diff " + dir + "/a.png " + dir + "/a.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("size: 2x2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("max abs error: 0\n"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("worst pixel"), std::string::npos) << r.out;  // none
    EXPECT_NE(r.out.find("PSNR: inf dB"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("differing pixels: 0 of 4"), std::string::npos) << r.out;
    EXPECT_TRUE(r.out.ends_with("\nPASS\n")) << r.out;
}

TEST(CliDiff, DifferingImagesFailWithMetricsAndHeatmap) {
    const std::string dir = make_images();
    auto r = sm2("diff " + dir + "/a.png " + dir + "/b.png --heatmap " + dir + "/heat.png");
    EXPECT_EQ(r.status, 2) << r.err;  // FAILURE
    // one channel of 16 (red of pixel (1,1)) differs by 128/255, read back as the float
    // 0.50196081; mean 0.50196081 / 16 = 0.03137255 (0.0313726 in 6 digits);
    // RMS = sqrt((128/255)^2 / 16) = 0.50196081 / 4 = 0.1254902; PSNR = 20 log10(1 / RMS) = 18.0278 dB
    EXPECT_NE(r.out.find("max abs error: 0.501961\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("worst pixel: (1, 1) channel R\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("mean abs error: 0.0313726\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("RMS error: 0.12549\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("PSNR: 18.0278 dB"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("warning pixels: 1 of 4 (25%) over 0\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("differing pixels: 1 of 4 (25%) over 0\n"), std::string::npos) << r.out;
    EXPECT_TRUE(r.out.ends_with("\nFAILURE\n")) << r.out;
    EXPECT_TRUE(exists(dir + "/heat.png"));
    // The heat map (worst pixel full red by default) is itself an image sm2 diff reads.
    auto h = sm2("diff " + dir + "/heat.png " + dir + "/a.png");
    EXPECT_NE(h.out.find("max abs error: 1\n"), std::string::npos) << h.out;  // red channel 1 against 0
    EXPECT_NE(h.out.find("worst pixel: (1, 1) channel R\n"), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("differing pixels: 1 of 4"), std::string::npos) << h.out;
    // No heat map unless asked.
    EXPECT_EQ(sm2("diff " + dir + "/a.png " + dir + "/b.png").status, 2);
    EXPECT_FALSE(exists(dir + "/diff.png"));
}

// idiff's thresholds on the one differing channel (0.50196 = 128/255) of 4 pixels.
TEST(CliDiff, ThresholdsGiveIdiffsVerdicts) {
    const std::string dir = make_images();
    const std::string pair = "diff " + dir + "/a.png " + dir + "/b.png ";
    // Over the warn threshold only: WARNING.
    auto warn = sm2(pair + "--fail 0.51 --warn 0.1");
    EXPECT_EQ(warn.status, 1) << warn.out;
    EXPECT_TRUE(warn.out.ends_with("\nWARNING\n")) << warn.out;
    EXPECT_NE(warn.out.find("differing pixels: 0 of 4 (0%) over 0.51\n"), std::string::npos) << warn.out;
    // Under both: PASS (--tolerance, the older name of --fail, sets --warn too).
    EXPECT_EQ(sm2(pair + "--fail 0.51").status, 0);
    EXPECT_EQ(sm2(pair + "--tolerance 0.51").status, 0);
    // An error equal to the threshold is allowed: 128/255 read back is 0.501960813999176.
    EXPECT_EQ(sm2(pair + "--fail 0.50196082").status, 0);
    // 1 failing pixel of 4 is 25%: --failpercent 25 allows it (a WARNING), 24 does not.
    EXPECT_EQ(sm2(pair + "--failpercent 25").status, 1);
    EXPECT_EQ(sm2(pair + "--failpercent 24").status, 2);
    // --hardfail fails whatever the percentage allows.
    EXPECT_EQ(sm2(pair + "--failpercent 50 --hardfail 0.5").status, 2);
    EXPECT_EQ(sm2(pair + "--failpercent 50 --hardfail 0.51").status, 1);
    // --fail and --tolerance are one setting.
    EXPECT_EQ(sm2(pair + "--fail 0.1 --tolerance 0.2").status, 2);
    EXPECT_EQ(sm2(pair + "--failpercent 101").status, 2);
}

TEST(CliDiff, JsonReport) {
    const std::string dir = make_images();
    auto r = sm2("diff " + dir + "/a.png " + dir + "/b.png --json --fail 0.6 --warn 0.5");
    EXPECT_EQ(r.status, 1) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["a"], dir + "/a.png");
    EXPECT_EQ(j["verdict"], "WARNING");
    EXPECT_EQ(j["status"], 1);
    EXPECT_EQ(j["width"], 2);
    EXPECT_NEAR(j["max_error"].get<double>(), 128.0 / 255.0, 1e-7);
    EXPECT_EQ(j["worst_pixel"]["x"], 1);
    EXPECT_EQ(j["worst_pixel"]["y"], 1);
    EXPECT_EQ(j["worst_pixel"]["channel"], "R");
    EXPECT_NEAR(j["rms_error"].get<double>(), 128.0 / 255.0 / 4.0, 1e-7);
    EXPECT_NEAR(j["psnr_db"].get<double>(), 20.0 * std::log10(4.0 * 255.0 / 128.0), 1e-5);
    EXPECT_EQ(j["warning_pixels"], 1);
    EXPECT_EQ(j["failing_pixels"], 0);
    auto same = nlohmann::json::parse(sm2("diff " + dir + "/a.png " + dir + "/a.png --json").out);
    EXPECT_TRUE(same["psnr_db"].is_null());  // infinite
    EXPECT_EQ(same["verdict"], "PASS");
}

TEST(CliDiff, SizeMismatchIs3AndUnreadableFilesAre4) {
    const std::string dir = make_images();
    auto r = sm2("diff " + dir + "/a.png " + dir + "/c.png");
    EXPECT_EQ(r.status, 3);
    EXPECT_NE(r.err.find("sm2 diff: image sizes differ: 2x2 and 1x1"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "SIZE MISMATCH\n");
    auto m = sm2("diff " + dir + "/a.png " + dir + "/missing.png");
    EXPECT_EQ(m.status, 4);
    EXPECT_NE(m.err.find("missing.png"), std::string::npos) << m.err;
    write_file(dir + "/text.png", "not a PNG");
    EXPECT_EQ(sm2("diff " + dir + "/text.png " + dir + "/a.png").status, 4);
    EXPECT_EQ(sm2("diff " + dir + " " + dir + "/a.png").status, 4);  // a folder against a file
}

// Folders are matched by name: a.png equal, b.png failing (c.png against the 2x2 a.png: sizes),
// d.png only on one side.
TEST(CliDiff, FoldersMatchedByNameWithJsonAndHtml) {
    const std::string dir = make_images();
    const std::string left = make_dir("diff_left"), right = make_dir("diff_right");
    std::filesystem::copy_file(dir + "/a.png", left + "/a.png");
    std::filesystem::copy_file(dir + "/a.png", right + "/a.png");
    std::filesystem::copy_file(dir + "/a.png", left + "/b.png");
    std::filesystem::copy_file(dir + "/b.png", right + "/b.png");
    write_file(left + "/notes.txt", "not an image: ignored");
    auto r = sm2("diff " + left + " " + right + " --html " + dir + "/report.html");
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_NE(r.out.find("a.png: PASS, max error 0, PSNR inf dB, 0 of 4 pixels failing\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("b.png: FAILURE, max error 0.501961 at (1, 1) R, PSNR 18.0278 dB, 1 of 4 pixels failing\n"),
              std::string::npos) << r.out;
    EXPECT_NE(r.out.find("2 images: 1 pass, 0 warning, 1 failure, 0 size mismatch, 0 unreadable or missing\nFAILURE\n"),
              std::string::npos) << r.out;
    const std::string html = slurp(dir + "/report.html");
    EXPECT_NE(html.find("<td>b.png</td><td class=\"FAILURE\">FAILURE</td>"), std::string::npos) << html;
    // thumbnails of A and B for both rows, a heat map for the differing one: 5 PNGs
    size_t images = 0;
    for (size_t at = html.find("data:image/png;base64,iVBORw0KGgo"); at != std::string::npos;
         at = html.find("data:image/png;base64,iVBORw0KGgo", at + 1))
        ++images;
    EXPECT_EQ(images, 5u) << html;

    std::filesystem::copy_file(dir + "/c.png", left + "/c.png");
    std::filesystem::copy_file(dir + "/a.png", right + "/c.png");
    std::filesystem::copy_file(dir + "/a.png", right + "/d.png");
    auto j = sm2("diff " + left + " " + right + " --json");
    EXPECT_EQ(j.status, 4);  // the worst: d.png is missing on the left
    const auto json = nlohmann::json::parse(j.out);
    ASSERT_EQ(json["images"].size(), 4u);
    EXPECT_EQ(json["images"][2]["name"], "c.png");
    EXPECT_EQ(json["images"][2]["verdict"], "SIZE MISMATCH");
    EXPECT_EQ(json["images"][2]["status"], 3);
    EXPECT_EQ(json["images"][3]["error"], "only in " + right);
    EXPECT_EQ(json["verdict"], "UNREADABLE");
    // a heat map names one image: refused for folders
    EXPECT_EQ(sm2("diff " + left + " " + right + " --heatmap " + dir + "/h.png").status, 2);
    EXPECT_FALSE(exists(dir + "/h.png"));
}

// File names need not be UTF-8; JSON text must be: the byte 0xFF becomes U+FFFD.
TEST(CliDiff, JsonOfFoldersWithNamesThatAreNotUtf8) {
    const std::string dir = make_images();
    const std::string left = make_dir("diff_utf_left"), right = make_dir("diff_utf_right");
    std::filesystem::copy_file(dir + "/a.png", left + "/bad\xff.png");
    std::filesystem::copy_file(dir + "/a.png", right + "/bad\xff.png");
    auto r = sm2("diff " + left + " " + right + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["images"].size(), 1u);
    EXPECT_EQ(j["images"][0]["name"], "bad\xef\xbf\xbd.png");
    EXPECT_EQ(j["images"][0]["verdict"], "PASS");
}

TEST(CliDiff, StdinAndNanTolerance) {
    const std::string dir = make_images();
    // '-' reads one of the two images from stdin (any format: PNG here)
    auto same = sm2("diff - " + dir + "/b.png", slurp(dir + "/b.png"));
    EXPECT_EQ(same.status, 0) << same.err;
    EXPECT_NE(same.out.find("differing pixels: 0 of 4"), std::string::npos) << same.out;
    auto differs = sm2("diff " + dir + "/a.png -", slurp(dir + "/b.png"));
    EXPECT_EQ(differs.status, 2) << differs.err;
    EXPECT_NE(differs.out.find("differing pixels: 1 of 4"), std::string::npos) << differs.out;
    EXPECT_EQ(sm2("diff - -", slurp(dir + "/b.png")).status, 2);
    // NaN would make every comparison false, so every pixel "equal": refused as bad usage
    auto nan = sm2("diff " + dir + "/a.png " + dir + "/b.png --tolerance nan");
    EXPECT_EQ(nan.status, 2);
    EXPECT_NE(nan.err.find("'nan' is not a number"), std::string::npos) << nan.err;
    EXPECT_EQ(sm2("diff " + dir + "/a.png " + dir + "/b.png --fail nan").status, 2);
    EXPECT_EQ(sm2("diff " + dir + "/a.png " + dir + "/b.png --heatmap-scale nan").status, 2);
}

// Files that are not regular files, as the input of every command: a clear message and status 1,
// never an abort or a hang (ctest's timeout would catch one).
TEST(CliBadFiles, DirectoriesDevicesAndFifosAreRefused) {
    const std::string dir = make_dir("badfiles");
    const std::string fifo = dir + "/fifo";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const std::string shader = kSamples + "gouraud.ps.asm";
    const std::string texture_shader = tmp("tex_bad.asm");
    write_file(texture_shader, "ps_2_0\ndcl t0.xy\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\n");
    struct Case {
        std::string args;
        std::string message;
    };
    const Case cases[] = {
        {"asm " + dir, dir + ": is a directory"},
        {"dis " + dir, dir + ": is a directory"},
        {"validate /dev/zero", "/dev/zero: is a character device, not a regular file"},
        {"cs pack " + fifo + " -o " + dir + "/x.sm2cb", fifo + ": is a FIFO (named pipe), not a regular file"},
        {"cs dump " + dir, dir + ": is a directory"},
        {"trace dump " + dir, dir + ": is a directory"},
        {"trace dump /dev/zero", "/dev/zero: is a character device"},
        {"trace dump " + fifo, fifo + ": is a FIFO"},
        {"replay /dev/zero -o " + dir + "/out", "/dev/zero: is a character device"},
        {"bench " + fifo, fifo + ": is a FIFO"},
        {"run " + fifo, fifo + ": is a FIFO"},
        {"run " + shader + " --lanes /dev/zero", "/dev/zero: is a character device"},
        {"run " + shader + " --lanes " + fifo, fifo + ": is a FIFO"},
        {"run " + texture_shader + " --texture s0=/dev/zero", "/dev/zero: is a character device"},
        {"run " + texture_shader + " --texture s0=" + fifo, fifo + ": is a FIFO"},
        {"run " + texture_shader + " --texture s0=" + dir, dir + ": is a directory"},
    };
    for (const Case& c : cases) {
        auto r = sm2(c.args);
        EXPECT_EQ(r.status, 1) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    }
    // sm2 diff: a file it cannot read is status 4 (idiff's); a folder goes with a folder only.
    const std::string png = dir + "/x.png";
    write_file(png, "not a PNG");
    const Case diff_cases[] = {
        {"diff " + dir + " " + fifo, dir + " is a folder and " + fifo + " is not"},
        {"diff /dev/zero " + dir, dir + " is a folder and /dev/zero is not"},
        {"diff /dev/zero " + png, "/dev/zero: is a character device"},
        {"diff " + fifo + " " + png, fifo + ": is a FIFO"},
    };
    for (const Case& c : diff_cases) {
        auto r = sm2(c.args);
        EXPECT_EQ(r.status, 4) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    }
    // stdin that never ends (/dev/zero) stops at the input size limit
    const std::string cmd = std::string(SM2_TOOL) + " asm - </dev/zero >/dev/null 2>" + dir + "/err";
    const int raw = std::system(cmd.c_str());
    EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1);
    EXPECT_NE(slurp(dir + "/err").find("<stdin>: larger than the 268435456-byte limit"), std::string::npos);
    // Side files and LoadTexture of a stream likewise (the line is named)
    const std::string stream = dir + "/s.sm2cs";
    write_file(stream, "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nLoadTexture t \"fifo\"\n");
    auto load = sm2("replay " + stream + " -o " + dir + "/out");
    EXPECT_EQ(load.status, 1);
    EXPECT_NE(load.err.find("s.sm2cs:3: D3DERR_INVALIDCALL: LoadTexture: " + fifo + ": is a FIFO"), std::string::npos)
        << load.err;
    write_file(stream, "sm2cs 1\nCreateVertexBuffer vb 4\nLock vb 0 @\"fifo\"\n");
    auto side = sm2("cs dump " + stream);
    EXPECT_EQ(side.status, 1);
    EXPECT_NE(side.err.find("s.sm2cs:3:11: error: cannot read side file 'fifo': is a FIFO"), std::string::npos)
        << side.err;
}

// Paths in streams stay inside the stream's folder (reads) and -o DIR (writes); --read-root widens
// the read side.
TEST(CliReplay, StreamPathsStayInsideTheirFolders) {
    const std::string dir = make_dir("paths");
    std::system(("mkdir -p " + dir + "/streams " + dir + "/shared " + dir + "/out").c_str());
    write_file(dir + "/shared/data.bin", std::string(4, '\x01'));
    const std::string stream = dir + "/streams/s.sm2cs";
    write_file(stream, "sm2cs 1\nCreateVertexBuffer vb 4\nLock vb 0 @\"../shared/data.bin\"\n");
    auto narrow = sm2("cs dump " + stream);
    EXPECT_EQ(narrow.status, 1);
    EXPECT_NE(narrow.err.find("s.sm2cs:3:11: error: cannot read side file '../shared/data.bin'"), std::string::npos)
        << narrow.err;
    auto wide = sm2("replay " + stream + " -o " + dir + "/out --read-root " + dir);
    EXPECT_EQ(wide.status, 0) << wide.err;
    write_file(stream, "sm2cs 1\nCreateRenderTarget rt 1 1 A8R8G8B8\nSaveSurface rt \"../escape.png\"\n"
                       "SaveSurface rt \"/tmp/escape.png\"\nSaveSurface rt \"inside.png\"\n");
    auto save = sm2("replay " + stream + " -o " + dir + "/out");
    EXPECT_EQ(save.status, 1);
    EXPECT_NE(save.err.find("s.sm2cs:3: D3DERR_INVALIDCALL: SaveSurface: '../escape.png' resolves to"),
              std::string::npos)
        << save.err;
    EXPECT_NE(save.err.find("s.sm2cs:4: D3DERR_INVALIDCALL: SaveSurface: '/tmp/escape.png' is an absolute path"),
              std::string::npos)
        << save.err;
    EXPECT_FALSE(exists(dir + "/escape.png"));
    EXPECT_TRUE(exists(dir + "/out/inside.png"));
}

// --memory-limit: resources past it are refused with D3DERR_OUTOFVIDEOMEMORY, the replay goes on.
TEST(CliReplay, MemoryLimitRefusesLargeResources) {
    const std::string dir = make_dir("memory");
    write_file(dir + "/m.sm2cs", "sm2cs 1\nCreateTexture big 2048 2048 1 A32B32G32R32F\n"
                                 "CreateTexture small 256 256 1 A8R8G8B8\n");
    auto r = sm2("replay " + dir + "/m.sm2cs -o " + dir + "/out --memory-limit 32");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("m.sm2cs:2: D3DERR_OUTOFVIDEOMEMORY: CreateTexture: 'big' needs 67108864 bytes; 0 of the "
                         "33554432-byte memory limit are in use"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("1 of 2 calls refused"), std::string::npos) << r.err;
    EXPECT_EQ(sm2("replay " + dir + "/m.sm2cs -o " + dir + "/out --memory-limit 65").status, 0);
    EXPECT_EQ(sm2("replay " + dir + "/m.sm2cs -o " + dir + "/out --memory-limit 0").status, 2);
}

TEST(Cli, AsmCArrayNameMustBeACIdentifier) {
    auto ok = sm2("asm - --format c --name g_ps2", "ps_2_0\nmov oC0, c0\n");
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_EQ(ok.out.rfind("const unsigned int g_ps2[", 0), 0u) << ok.out;
    for (const char* bad : {"'x[1]; int evil'", "2abc", "int", "a-b", "''"}) {
        auto r = sm2(std::string("asm - --format c --name ") + bad, "ps_2_0\nmov oC0, c0\n");
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_EQ(r.out, "") << bad;
    }
}

// sm2 run of bytecode that fails validation names the token, like sm2 validate.
TEST(CliRun, BytecodeValidationErrorsNameTheToken) {
    const std::string text = tmp("unlocated.asm"), bin = tmp("unlocated.bin");
    write_file(text, "ps_2_0\ntexld r0, t0, s0\nmov oC0, r0\n");
    ASSERT_EQ(sm2("asm " + text + " --no-validate -o " + bin).status, 0);
    auto r = sm2("run " + bin);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(bin + ": token 1 (byte 0x4): error: [input-declared] texld: t0 is read but not declared\n"
                               "    texld r0, t0, s0\n"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err, sm2("validate " + bin).err);
}

// sm2 dis writes only text that assembles back to the same bytes; otherwise a located error.
TEST(Cli, DisRefusesBytecodeTextCannotExpress) {
    // defb b0 holding 2 ("true" would reassemble to 1)
    auto defb = sm2("dis -", "FFFF0200 0200002F E00F0800 00000002 02000001 800F0800 A0E40000 0000FFFF\n");
    EXPECT_EQ(defb.status, 1);
    EXPECT_EQ(defb.out, "");
    EXPECT_NE(defb.err.find("<stdin>: token 1 (byte 0x4): error: 'defb b0, true' assembles to different bytes"),
              std::string::npos)
        << defb.err;
    // register type 8 in a vertex shader (no such register there): printed ?8:0, which does not parse
    auto unknown = sm2("dis -", "FFFE0200 02000001 800F0000 80E40800 0000FFFF\n");
    EXPECT_EQ(unknown.status, 1);
    EXPECT_NE(unknown.err.find("<stdin>: token 1 (byte 0x4): error: 'mov r0, ?8:0' does not assemble"),
              std::string::npos)
        << unknown.err;
    auto fine = sm2("dis -", "FFFF0200 0200002F E00F0800 00000001 02000001 800F0800 A0E40000 0000FFFF\n");
    EXPECT_EQ(fine.status, 0) << fine.err;
    EXPECT_EQ(fine.out, "ps_2_0\ndefb b0, true\nmov oC0, c0\n");
}

}  // namespace
