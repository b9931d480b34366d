// dcl, def, defi, defb, the source and Wine's statement orders, and the worked examples of bytecode.md §13.
#include <fstream>
#include <sstream>

#include "helpers.h"

namespace sm2::assembler::test {
namespace {

TEST(Dcl, EveryVertexUsage) {
    // bytecode.md §7.1: usage token = 0x80000000 | usage | index << 16.
    const char* names[] = {"position", "blendweight", "blendindices", "normal", "psize",
                           "texcoord", "tangent", "binormal", "tessfactor", "positiont",
                           "color", "fog", "depth", "sample"};
    for (uint32_t usage = 0; usage < 14; ++usage) {
        const std::string text = std::string("dcl_") + names[usage] + " v3";
        EXPECT_EQ(statement_tokens("vs_2_0", text), (Tokens{0x0200001F, 0x80000000u | usage, 0x900F0003}))
            << text;
        const std::string indexed = std::string("dcl_") + names[usage] + "7 v3";
        EXPECT_EQ(statement_tokens("vs_2_0", indexed),
                  (Tokens{0x0200001F, 0x80070000u | usage, 0x900F0003}))
            << indexed;
    }
}

TEST(Dcl, VertexExamples) {
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_position v0")), "0200001F 80000000 900F0000");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_position0 v0")), "0200001F 80000000 900F0000");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_normal12 v15")), "0200001F 800C0003 900F000F");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_texcoord3 v5.xy")), "0200001F 80030005 90030005");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_color1 v10")), "0200001F 8001000A 900F000A");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "dcl_texcoord15 v1")), "0200001F 800F0005 900F0001");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "DCL_TEXCOORD2 V1")), "0200001F 80020005 900F0001");
}

TEST(Dcl, PixelInputs) {
    // bytecode.md §7.2
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl t0")), "0200001F 80000000 B00F0000");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl t0.xy")), "0200001F 80000000 B0030000");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl v1.xyz")), "0200001F 80000000 90070001");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_pp t0")), "0200001F 80000000 B02F0000");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_centroid t1.xy")), "0200001F 80000000 B0430001");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_centroid_pp t7")), "0200001F 80000000 B06F0007");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_pp v0.w")), "0200001F 80000000 90280000");
}

TEST(Dcl, Samplers) {
    // bytecode.md §7.3: texture type in bits 27..30.
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl s0")), "0200001F 80000000 A00F0800");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_1d s0")), "0200001F 88000000 A00F0800");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_2d s0")), "0200001F 90000000 A00F0800");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_cube s1")), "0200001F 98000000 A00F0801");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "dcl_volume s15")), "0200001F A0000000 A00F080F");
}

// Bit patterns of the def literals (IEEE-754 single precision).
TEST(Def, LiteralForms) {
    const std::pair<const char*, uint32_t> literals[] = {
        {"0", 0x00000000},   {"0.0", 0x00000000}, {"-0.0", 0x80000000}, {"-0", 0x80000000},
        {"0.5", 0x3F000000}, {".5", 0x3F000000},  {"-.5", 0xBF000000},  {"-0.5", 0xBF000000},
        {"1", 0x3F800000},   {"1.", 0x3F800000},  {"1.0f", 0x3F800000}, {"1f", 0x3F800000},
        {"1.f", 0x3F800000}, {"-1", 0xBF800000},  {"+2", 0x40000000},   {"0.25", 0x3E800000},
        {"1024", 0x44800000}, {"100.0", 0x42C80000}, {"1.5", 0x3FC00000}, {"2.0F", 0x40000000},
        // exponent forms (extension; Wine rejects them)
        {"1e0", 0x3F800000}, {"2.5e2", 0x437A0000}, {"25E-1", 0x40200000}, {"1e+1", 0x41200000},
        // 2^24 + 1 rounds to even (2^24); the smallest denormal; overflow to infinity
        {"16777217", 0x4B800000},
        {"0.000000000000000000000000000000000000000000001", 0x00000001},
        {"1e39", 0x7F800000},
        {"-1e39", 0xFF800000},
        // raw bit patterns (extension, used by the disassembler for NaN and infinity)
        {"0x7FC00000", 0x7FC00000}, {"0xFF800000", 0xFF800000}, {"0x7f800001", 0x7F800001},
        {"0x1", 0x00000001},
    };
    // 2.5e2 = 250 = 1.953125 * 2^7: exponent 134 = 0x86, fraction 0x7A0000.
    // 25e-1 = 2.5 = 1.25 * 2: 0x40200000. 1e+1 = 10 = 1.25 * 8: 0x41200000.
    for (const auto& [text, bits] : literals) {
        const std::string statement = std::string("def c3, ") + text + ", 0, 0, 0";
        EXPECT_EQ(statement_tokens("vs_2_0", statement),
                  (Tokens{0x05000051, 0xA00F0003, bits, 0, 0, 0}))
            << text;
    }
    // bytecode.md §8 example
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "def c12, 0, -1, -0.5, 1024")),
              "05000051 A00F000C 00000000 BF800000 BF000000 44800000");
    // D3DSINCOSCONST1/2 (bytecode.md §8)
    EXPECT_EQ(hex(statement_tokens("vs_2_0",
                                   "def c0, -1.5500992e-6, -2.1701389e-5, 0.0026041667, 0.00026041668")),
              "05000051 A00F0000 B5D00D01 B7B60B61 3B2AAAAB 39888889");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "def c1, -0.020833334, -0.125, 1.0, 0.5")),
              "05000051 A00F0001 BCAAAAAB BE000000 3F800000 3F000000");
}

TEST(Def, IntegersAndBooleans) {
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defi i0, -1, 1, 10, 0")),
              "05000030 F00F0000 FFFFFFFF 00000001 0000000A 00000000");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defi i15, 255, -128, 127, 2147483647")),
              "05000030 F00F000F 000000FF FFFFFF80 0000007F 7FFFFFFF");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defi i1, -2147483648, 0, 0, 0")),
              "05000030 F00F0001 80000000 00000000 00000000 00000000");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defb b1, false")), "0200002F E00F0801 00000000");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defb b15, true")), "0200002F E00F080F 00000001");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "defb b2, TRUE")), "0200002F E00F0802 00000001");
}

// Microsoft's assemblers keep the source order (fxc writes def before dcl, so do its listings).
TEST(Order, SourceOrderByDefault) {
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\nmov r0, c0\ndef c0, 1, 1, 1, 1\ndcl t0\ndcl_2d s0\n")),
              "FFFF0200 02000001 800F0000 A0E40000 05000051 A00F0000 3F800000 3F800000 3F800000 3F800000 "
              "0200001F 80000000 B00F0000 0200001F 90000000 A00F0800 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\ndcl_cube s3\ndcl v0\n")),
              "FFFF0200 0200001F 98000000 A00F0803 0200001F 80000000 900F0000 0000FFFF");
}

// Wine's order (wine_order): version, input dcl, sampler dcl, def, defb, defi, instructions.
TEST(Order, WineOrderMovesDeclarationsAndDefinitionsToTheTop) {
    constexpr bool kWineOrder = true;
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\nmov r0, c0\ndef c0, 1, 1, 1, 1\ndcl t0\ndcl_2d s0\n", kWineOrder)),
              "FFFF0200 0200001F 80000000 B00F0000 0200001F 90000000 A00F0800 "
              "05000051 A00F0000 3F800000 3F800000 3F800000 3F800000 02000001 800F0000 A0E40000 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("vs_2_0\n"
                                  "defi i0, 1, 0, 0, 0\n"
                                  "mov r0, v1\n"
                                  "defb b0, true\n"
                                  "def c1, 0, 0, 0, 0\n"
                                  "dcl_normal v1\n"
                                  "def c0, 0, 0, 0, 0\n"
                                  "dcl_position v0\n",
                                  kWineOrder)),
              "FFFE0200 0200001F 80000003 900F0001 0200001F 80000000 900F0000 "
              "05000051 A00F0001 00000000 00000000 00000000 00000000 "
              "05000051 A00F0000 00000000 00000000 00000000 00000000 "
              "0200002F E00F0800 00000001 "
              "05000030 F00F0000 00000001 00000000 00000000 00000000 "
              "02000001 800F0000 90E40001 0000FFFF");
    // The sampler group comes after all inputs even when declared first.
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\ndcl_cube s3\ndcl v0\n", kWineOrder)),
              "FFFF0200 0200001F 80000000 900F0000 0200001F 98000000 A00F0803 0000FFFF");
}

// `comment` writes a comment token (size in bits 16..30, 0xFFFE below) and the words as given.
TEST(CommentBlock, WordsAsGivenWhereWritten) {
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\nmov oC0, c0\nCOMMENT 0xA,\n  0xffffffff\ncomment\n")),
              "FFFF0200 02000001 800F0800 A0E40000 0002FFFE 0000000A FFFFFFFF 0000FFFE 0000FFFF");
    // Wine's order moves declarations and definitions, not comment blocks.
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\ncomment 0x1\ndef c0, 0, 0, 0, 0\n", true)),
              "FFFF0200 05000051 A00F0000 00000000 00000000 00000000 00000000 0001FFFE 00000001 0000FFFF");
}

TEST(Version, Forms) {
    EXPECT_EQ(hex(assemble_tokens("vs_2_0\n")), "FFFE0200 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("vs.2.0\n")), "FFFE0200 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("ps_2_0")), "FFFF0200 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("  PS.2.0  // comment\n")), "FFFF0200 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("// leading comment\n; another\n/* block\n */ ps_2_0 nop")),
              "FFFF0200 00000000 0000FFFF");
    EXPECT_EQ(hex(assemble_tokens("\xEF\xBB\xBFvs_2_0\n")), "FFFE0200 0000FFFF");  // UTF-8 BOM
    EXPECT_EQ(hex(assemble_tokens("#define VERSION ps_2_0\nVERSION\n")), "FFFF0200 0000FFFF");
}

TEST(Syntax, CommentsWhitespaceAndStatementLayout) {
    const char* text =
        "vs_2_0 ; comment\n"
        "\t mov\tr0 ,\tr1 // trailing\n"
        "/* a block comment\n spanning lines */ add r0, /* inline */ r0, r1\n"
        "mov r1, r2 mov r2, r3\n"  // Wine needs no newline between statements
        "def c0,\n 1, 2,\n 3, 4\n"  // nor inside one
        "\r\n";
    constexpr bool kWineOrder = true;  // the def moves first, as Wine writes it
    EXPECT_EQ(hex(assemble_tokens(text, kWineOrder)),
              "FFFE0200 05000051 A00F0000 3F800000 40000000 40400000 40800000 "
              "02000001 800F0000 80E40001 03000002 800F0000 80E40000 80E40001 "
              "02000001 800F0001 80E40002 02000001 800F0002 80E40003 0000FFFF");
}

TEST(Preprocessor, DefineUndefLine) {
    const char* text =
        "#define ONE 1.0\n"
        "#define POS oPos\n"
        "#define XFORM m4x4 POS, v0, c0\n"
        "vs_2_0\n"
        "def c4, ONE, 0, 0, ONE\n"
        "XFORM\n"
        "#undef POS\n"
        "#define POS r0\n"
        "mov POS, c4\n";
    EXPECT_EQ(hex(assemble_tokens(text)),
              "FFFE0200 05000051 A00F0004 3F800000 00000000 00000000 3F800000 "
              "03000014 C00F0000 90E40000 A0E40000 02000001 800F0000 A0E40004 0000FFFF");
    // #line changes the reported line (and file).
    const AssembleResult r = assemble_unvalidated("vs_2_0\n#line 100\nnop\nbogus\n#line 7 \"x.vsh\"\nbad\n");
    ASSERT_EQ(r.diagnostics.size(), 2u) << diagnostics_text(r);
    EXPECT_EQ(r.diagnostics[0].to_string(), "<input>:101:1: error: unknown instruction 'bogus'");
    EXPECT_EQ(r.diagnostics[1].to_string(), "x.vsh:7:1: error: unknown instruction 'bad'");
}

// bytecode.md §13: the three worked examples, token for token.
std::string read_corpus(const char* name) {
    std::ifstream f(std::string(SM2_SOURCE_DIR) + "/tests/assembler/corpus/" + name);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

TEST(WorkedExamples, A) {
    const std::string text = read_corpus("example_a_ps.asm");
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(hex(assemble_tokens(text)),
              "FFFF0200 "
              "0200001F 80000000 B0030000 "
              "0200001F 80000000 B00F0001 "
              "0200001F 80000000 900F0000 "
              "0200001F 90000000 A00F0800 "
              "0200001F 98000000 A00F0801 "
              "05000051 A00F0000 3F000000 3F800000 00000000 3E800000 "
              "03000042 800F0000 B0E40000 A0E40800 "
              "03010042 802F0001 B0E40001 A0E40801 "
              "03000005 802F0000 80E40000 90E40000 "
              "04000012 801F0002 A0000000 80E40000 80E40001 "
              "02000001 80080002 A0550000 "
              "02000001 800F0800 80E40002 "
              "0000FFFF");
}

TEST(WorkedExamples, B) {
    const std::string text = read_corpus("example_b_vs.asm");
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(hex(assemble_tokens(text)),
              "FFFE0200 "
              "0200001F 80000000 900F0000 "
              "0200001F 80000003 900F0001 "
              "0200001F 80000005 900F0002 "
              "05000051 A00F0008 3F800000 00000000 3F000000 40000000 "
              "05000051 A00F0009 B5D00D01 B7B60B61 3B2AAAAB 39888889 "
              "05000051 A00F000A BCAAAAAB BE000000 3F800000 3F000000 "
              "03000014 C00F0000 90E40000 A0E40000 "
              "03000008 80010000 90E40001 A0E40004 "
              "0300000B 80010000 80000000 A0550008 "
              "0200002E B0010000 A0FF0008 "
              "04000005 D00F0000 80000000 A0E42005 B0000000 "
              "04000025 80030001 90000002 A0E40009 A0E4000A "
              "02000001 E0030000 80E40001 "
              "02000001 C00F0001 A0000008 "
              "0000FFFF");
}

TEST(WorkedExamples, C) {
    const std::string text = read_corpus("example_c_flow.asm");
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(hex(assemble_tokens(text)),
              "FFFE0200 "
              "0200001F 80000000 900F0000 "
              "0200002F E00F0800 00000001 "
              "05000030 F00F0000 00000004 00000000 00000001 00000000 "
              "02000001 800F0000 90E40000 "
              "0200001B F0E40800 F0E40000 "
              "04000002 800F0000 80E40000 A0E4200A F0E40800 "
              "0000001D "
              "01000028 E0E40800 "
              "01000019 A0E41001 "
              "0000002B "
              "02000001 C00F0000 80E40000 "
              "0000001C "
              "0100001E A0E41001 "
              "03000005 800F0000 80E40000 A0E40002 "
              "0000001C "
              "0000FFFF");
}

TEST(WorkedExamples, PixelSinCosOneSourceForm) {
    EXPECT_EQ(hex(assemble_tokens("ps_2_0\nsincos r0.xy, r1.x\n")),
              "FFFF0200 02000025 80030000 80000001 0000FFFF");
}

}  // namespace
}  // namespace sm2::assembler::test
