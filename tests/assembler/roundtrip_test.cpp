// assemble -> disassemble -> assemble gives the same bytes; decode -> disassemble -> assemble too.
#include <bit>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "helpers.h"
#include "sm2/isa/opcodes.h"
#include "sm2/isa/tokens.h"

namespace sm2::assembler::test {
namespace {

std::vector<std::filesystem::path> asm_files(const char* folder) {
    std::vector<std::filesystem::path> files;
    const std::filesystem::path dir = std::filesystem::path(SM2_SOURCE_DIR) / folder;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        if (entry.path().extension() == ".asm") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::filesystem::path> corpus_files() { return asm_files("tests/assembler/corpus"); }

std::string read_file(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// Checks the round trip of one text and returns its tokens.
Tokens check_round_trip(const std::string& text) {
    const AssembleResult first = assemble_unvalidated(text);
    EXPECT_TRUE(first.ok()) << text << "\n" << diagnostics_text(first);
    if (!first.ok()) return {};
    const std::string printed = disassemble(*first.program);
    const AssembleResult second = assemble_unvalidated(printed);
    EXPECT_TRUE(second.ok()) << printed << "\n" << diagnostics_text(second);
    if (!second.ok()) return {};
    EXPECT_EQ(hex(second.tokens), hex(first.tokens)) << "printed:\n" << printed;
    // The decoder's view of the bytes prints the same text.
    const isa::DecodeResult decoded = isa::decode(first.tokens);
    EXPECT_TRUE(decoded.ok()) << (decoded.error ? decoded.error->to_string() : "");
    if (decoded.ok()) {
        EXPECT_EQ(disassemble(*decoded.program), printed);
    }
    // Printing is stable: text of the reassembled program is the same.
    EXPECT_EQ(disassemble(*second.program), printed);
    return first.tokens;
}

TEST(RoundTrip, Corpus) {
    const auto files = corpus_files();
    ASSERT_GE(files.size(), 7u);
    for (const auto& f : files) {
        SCOPED_TRACE(f.filename().string());
        check_round_trip(read_file(f));
    }
}

// The sample scenes' shaders assemble, pass the validator and round-trip.
TEST(RoundTrip, SampleShaders) {
    for (const auto& f : asm_files("samples/shaders")) {
        SCOPED_TRACE(f.filename().string());
        const std::string text = read_file(f);
        const AssembleResult validated = assemble(text);
        EXPECT_TRUE(validated.ok()) << diagnostics_text(validated);
        check_round_trip(text);
    }
}

TEST(RoundTrip, InlinePrograms) {
    const char* programs[] = {
        "vs_2_0\nmov r0, c[a0.x]\nmov r0, c[a0.xy + 3]\nmov r0, c[a0.wzyx + 1].y\nmov r0, c[aL]\n",
        "vs_2_0\ndef c0, -0.0, 0.1, 0.2, 0.3\ndef c1, 3.4028235e38, 1.17549435e-38, 1e-45, -1e-40\n",
        "vs_2_0\ndef c0, 0x7FC00000, 0xFF800000, 0x7F800000, 0xFFFFFFFF\n",
        "vs_2_0\ndefi i0, -2147483648, 2147483647, -1, 0\n",
        "ps_2_0\ndcl_centroid_pp t0.xw\ndcl_pp v1.y\nmov_sat_pp r0.yzw, -t0.yzxw\n",
        "ps_2_0\nsincos r0.x, r1.z\nsincos r0.y, r1.w, c0, c1\n",
        "vs_2_0\nlabel l2047\nret\ncall l2047\ncallnz l5, !b15\nif !b3\nendif\n",
        "ps_2_0\ndcl s0\ndcl_1d s1\ndcl_2d s2\ndcl_cube s3\ndcl_volume s4\n",
    };
    for (const char* p : programs) {
        SCOPED_TRACE(p);
        check_round_trip(p);
    }
}

isa::Instruction mov(isa::SourceParameter src, uint8_t mask = isa::kMaskAll) {
    isa::Instruction ins;
    ins.opcode = isa::Opcode::Mov;
    isa::DestinationParameter d;
    d.write_mask = mask;
    ins.dest = d;
    ins.sources.push_back(src);
    return ins;
}

// Every swizzle, every write mask and every address swizzle prints in a form that reads back.
TEST(RoundTrip, AllSwizzlesMasksAndAddressComponents) {
    isa::Program program;
    program.version = {isa::ShaderType::Vertex, 2, 0};
    for (int s = 0; s < 256; ++s) {
        isa::SourceParameter src;
        src.type = isa::RegisterType::Temp;
        src.index = 1;
        src.swizzle = static_cast<uint8_t>(s);
        program.instructions.push_back(mov(src));
        isa::SourceParameter rel;
        rel.type = isa::RegisterType::Const;
        rel.index = static_cast<uint16_t>(s);
        rel.swizzle = static_cast<uint8_t>(255 - s);
        rel.relative = isa::RelativeAddress{isa::RegisterType::Address, static_cast<uint8_t>(s)};
        program.instructions.push_back(mov(rel));
    }
    for (uint8_t m = 1; m < 16; ++m) {
        isa::SourceParameter src;
        program.instructions.push_back(mov(src, m));
    }
    const Tokens expected = isa::encode(program);
    const std::string text = disassemble(program);
    const AssembleResult r = assemble_unvalidated(text);
    ASSERT_TRUE(r.ok()) << diagnostics_text(r);
    EXPECT_EQ(r.tokens, expected);
}

// def floats: the shortest decimal that reads back to the same bits, for many bit patterns.
TEST(RoundTrip, DefFloatBitPatterns) {
    std::vector<uint32_t> patterns = {0x00000000, 0x80000000, 0x3F800000, 0xBF800000, 0x00000001,
                                      0x80000001, 0x007FFFFF, 0x00800000, 0x7F7FFFFF, 0xFF7FFFFF,
                                      0x7F800000, 0xFF800000, 0x7FC00000, 0xFFC00001, 0x7F800001,
                                      0x3DCCCCCD, 0x3EAAAAAB, 0x4B800001, 0x5F000000, 0x33D6BF95};
    std::mt19937 rng(12345);
    for (int i = 0; i < 20000; ++i) patterns.push_back(rng());
    // Every exponent with random mantissas, so tiny and huge magnitudes are well covered.
    for (uint32_t e = 0; e < 256; ++e)
        for (int k = 0; k < 8; ++k) patterns.push_back((e << 23) | (rng() & 0x807FFFFF));
    isa::Program program;
    program.version = {isa::ShaderType::Vertex, 2, 0};
    for (size_t i = 0; i < patterns.size(); i += 4) {
        isa::Instruction def;
        def.opcode = isa::Opcode::Def;
        isa::DestinationParameter d;
        d.type = isa::RegisterType::Const;
        d.index = static_cast<uint16_t>((i / 4) % 2048);
        def.dest = d;
        for (size_t k = 0; k < 4; ++k)
            def.constant_bits[k] = i + k < patterns.size() ? patterns[i + k] : 0;
        program.instructions.push_back(def);
    }
    const Tokens expected = isa::encode(program);
    const std::string text = disassemble(program);
    const AssembleResult r = assemble_unvalidated(text);
    ASSERT_TRUE(r.ok()) << diagnostics_text(r);
    ASSERT_EQ(r.tokens.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_EQ(r.tokens[i], expected[i]) << "token " << i;
    // Finite values print without exponent or hex (Wine reads them too).
    for (uint32_t bits : patterns) {
        isa::Program one;
        one.version = program.version;
        isa::Instruction def = program.instructions[0];
        def.constant_bits = {bits, 0, 0, 0};
        const std::string line = format_instruction(one.version, def);
        const float f = std::bit_cast<float>(bits);
        if (f - f == 0.0f) {
            EXPECT_EQ(line.find_first_of("eEx", 4), std::string::npos) << line;
        }
    }
}

TEST(Disassembler, Formatting) {
    const isa::ShaderVersion vs{isa::ShaderType::Vertex, 2, 0};
    const AssembleResult r = assemble_unvalidated(
        "vs_2_0\n"
        "mov_sat r0.xy, -c[a0.x + 5].yzxw\n"
        "mov r0, r1.xyyy\n"
        "mov r0, r1.xxxx\n"
        "mov r0, r1.xyzw\n"
        "mov r0, r1.xyww\n"
        "mov r0, c10[aL]\n"
        "mov r0, c[a0]\n"
        "def c0, 0.5, -0, 1024, 0.1\n"
        "def c1, 0x7FC00000, 1e39, 0, 0\n"
        "mov oFog, r0.x\n"
        "if !b2\n");
    ASSERT_TRUE(r.ok()) << diagnostics_text(r);
    EXPECT_EQ(disassemble(*r.program),
              "vs_2_0\n"
              "mov_sat r0.xy, -c[a0.x + 5].yzxw\n"
              "mov r0, r1.xy\n"
              "mov r0, r1.x\n"
              "mov r0, r1\n"
              "mov r0, r1.xyw\n"
              "mov r0, c[aL + 10]\n"
              "mov r0, c[a0]\n"
              "def c0, 0.5, -0, 1024, 0.1\n"
              "def c1, 0x7FC00000, 0x7F800000, 0, 0\n"
              "mov oFog, r0.x\n"
              "if !b2\n");
    const AssembleResult p = assemble_unvalidated(
        "ps_2_0\ndcl_centroid t0.xy\ndcl_2d s0\ndcl s1\ntexldp_pp r0, t0, s0\ntexkill t0.xyz\n"
        "sincos r1.xy, r0.x\nmov oC0, r0\n");
    ASSERT_TRUE(p.ok()) << diagnostics_text(p);
    EXPECT_EQ(disassemble(*p.program),
              "ps_2_0\n"
              "dcl_centroid t0.xy\n"
              "dcl_2d s0\n"
              "dcl s1\n"
              "texldp_pp r0, t0, s0\n"
              "texkill t0.xyz\n"
              "sincos r1.xy, r0.x\n"
              "mov oC0, r0\n");
    (void)vs;
}

TEST(Disassembler, CommentBlocksArePrintedAsDirectivesThatReassemble) {
    // A compiler blob: version, a comment of 3 DWORDs (not a valid CTAB), mov, END.
    const Tokens blob = {0xFFFF0200, isa::tokens::encode_comment(3), 0x42415443, 0x1, 0x2,
                         0x02000001, 0x800F0800, 0xA0E40000, 0x0000FFFF};
    const isa::DecodeResult d = isa::decode(blob);
    ASSERT_TRUE(d.ok()) << d.error->to_string();
    const std::string text = disassemble(*d.program);
    EXPECT_EQ(text,
              "ps_2_0\n"
              "// CTAB constant table, 3 DWORDs, not decoded: the CTAB header at byte offset 0x0 (28 bytes) lies "
              "outside the 8 bytes after 'CTAB'\n"
              "comment 0x42415443, 0x00000001, 0x00000002\n"
              "mov oC0, c0\n");
    EXPECT_EQ(assemble_tokens(text), blob);

    // Other FOURCCs, blocks of any bytes, and empty blocks come back too; long blocks wrap.
    Tokens other = {0xFFFE0200, isa::tokens::encode_comment(0), isa::tokens::encode_comment(2), 0x53455250,
                    0xFFFFFFFF, isa::tokens::encode_comment(10)};
    for (uint32_t k = 0; k < 10; ++k) other.push_back(0x0000FFFE + k);
    other.push_back(0x0000FFFF);
    const isa::DecodeResult o = isa::decode(other);
    ASSERT_TRUE(o.ok()) << o.error->to_string();
    const std::string other_text = disassemble(*o.program);
    EXPECT_EQ(other_text,
              "vs_2_0\n"
              "// empty comment block\n"
              "comment\n"
              "// comment block 'PRES', 2 DWORDs\n"
              "comment 0x53455250, 0xffffffff\n"
              "// comment block, 10 DWORDs\n"
              "comment 0x0000fffe, 0x0000ffff, 0x00010000, 0x00010001, 0x00010002, 0x00010003, 0x00010004, "
              "0x00010005,\n"
              "        0x00010006, 0x00010007\n");
    EXPECT_EQ(assemble_tokens(other_text), other);
}

// disassemble_checked: what the decoder accepts either comes back through text byte for byte or
// is refused at its statement.
TEST(Disassembler, CheckedDisassemblyRoundTripsOrNamesTheStatement) {
    // Every statement of the corpus and of the samples comes back (comment blocks aside).
    auto files = corpus_files();
    for (const auto& f : asm_files("samples/shaders")) files.push_back(f);
    for (const auto& f : files) {
        const AssembleResult r = assemble_unvalidated(read_file(f));
        ASSERT_TRUE(r.ok()) << f;
        const isa::DecodeResult d = isa::decode(r.tokens);
        ASSERT_TRUE(d.ok()) << f;
        const CheckedDisassembly c = disassemble_checked(*d.program);
        EXPECT_FALSE(c.error) << f << ": " << c.error->message;
        EXPECT_EQ(c.text, disassemble(*d.program));
    }
    const Tokens with_comment = {0xFFFF0200, isa::tokens::encode_comment(3), 0x42415443, 0x1, 0x2,
                                 0x02000001, 0x800F0800, 0xA0E40000, 0x0000FFFF};
    EXPECT_FALSE(disassemble_checked(*isa::decode(with_comment).program).error);

    // defb b0 holding 2: "true" would assemble to 1.
    Tokens defb = assemble_tokens("ps_2_0\ndefb b0, true\nmov oC0, c0\n");
    ASSERT_EQ(hex(defb).substr(0, 35), "FFFF0200 0200002F E00F0800 00000001");
    defb[3] = 2;
    const isa::DecodeResult d = isa::decode(defb);
    ASSERT_TRUE(d.ok()) << d.error->to_string();
    const CheckedDisassembly c = disassemble_checked(*d.program);
    ASSERT_TRUE(c.error);
    EXPECT_EQ(c.error->token_offset, 1u);
    EXPECT_EQ(c.error->message.rfind("'defb b0, true' assembles to different bytes", 0), 0u) << c.error->message;

    // A source register type the ISA does not have (20): printed as ?20:0, which does not parse.
    Tokens mov = assemble_tokens("ps_2_0\nmov oC0, c0\nmov oC1, c1\n");
    ASSERT_EQ(mov.size(), 8u);
    mov[6] = (mov[6] & ~(0x70000000u | 0x1800u)) | (4u << 28) | (2u << 11);  // type 20 = 0b10'100
    const isa::DecodeResult u = isa::decode(mov);
    if (u.ok()) {  // the decoder may refuse the type itself, which is just as good
        const CheckedDisassembly cu = disassemble_checked(*u.program);
        ASSERT_TRUE(cu.error);
        EXPECT_EQ(cu.error->token_offset, 4u);
        EXPECT_NE(cu.error->message.find("?20:"), std::string::npos) << cu.error->message;
    }

    // A def after an arithmetic instruction stays there (source order).
    const Tokens late_def = {0xFFFF0200, 0x02000001, 0x800F0800, 0xA0E40000,
                             0x05000051, 0xA00F0000, 0, 0, 0, 0, 0x0000FFFF};
    const isa::DecodeResult l = isa::decode(late_def);
    ASSERT_TRUE(l.ok()) << l.error->to_string();
    const CheckedDisassembly cl = disassemble_checked(*l.program);
    EXPECT_FALSE(cl.error) << cl.error->message;

    // A statement that fails after a multi-line comment block is still named by its offset.
    Tokens after_comment = {0xFFFF0200, isa::tokens::encode_comment(12)};
    for (uint32_t k = 0; k < 12; ++k) after_comment.push_back(k);
    const size_t defb_at = after_comment.size();
    for (uint32_t t : {0x0200002Fu, 0xE00F0800u, 2u, 0x0000FFFFu}) after_comment.push_back(t);
    const isa::DecodeResult a = isa::decode(after_comment);
    ASSERT_TRUE(a.ok()) << a.error->to_string();
    const CheckedDisassembly ca = disassemble_checked(*a.program);
    ASSERT_TRUE(ca.error);
    EXPECT_EQ(ca.error->token_offset, defb_at);
}

TEST(Disassembler, VertexDeclarationsPrintTheirUsage) {
    const AssembleResult r = assemble_unvalidated(
        "vs_2_0\ndcl_position v0\ndcl_texcoord3 v5.xy\ndcl_color1 v10\ndcl_normal12 v15\n");
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(disassemble(*r.program),
              "vs_2_0\ndcl_position v0\ndcl_texcoord3 v5.xy\ndcl_color1 v10\ndcl_normal12 v15\n");
}

}  // namespace
}  // namespace sm2::assembler::test
