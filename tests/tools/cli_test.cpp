// The sm2 command line, run as a user would: output, files written and exit status
// (0 ok, 1 invalid input, 2 bad usage).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct Run {
    int status = -1;
    std::string out;
    std::string err;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// ctest runs each test in its own process, in parallel: the pid keeps their files apart.
std::string tmp(const std::string& name) {
    return std::string(SM2_TEST_TMP) + "/" + std::to_string(getpid()) + "_" + name;
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Runs `sm2 ARGS` with optional stdin text; captures stdout, stderr and the exit status.
Run sm2(const std::string& args, const std::string& stdin_text = "") {
    static int counter = 0;
    const std::string base = tmp("run" + std::to_string(counter++));
    write_file(base + ".in", stdin_text);
    const std::string cmd = std::string(SM2_TOOL) + " " + args + " <" + base + ".in >" + base +
                            ".out 2>" + base + ".err";
    const int raw = std::system(cmd.c_str());
    Run r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    return r;
}

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

}  // namespace
