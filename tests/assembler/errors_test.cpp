// Diagnostics: exact positions and messages, several per run, validator violations, and
// robustness against arbitrary input.
#include <random>

#include "helpers.h"
#include "sm2/isa/validator.h"

namespace sm2::assembler::test {
namespace {

struct Expected {
    uint32_t line;
    uint32_t column;
    const char* message_part;
};

void expect_errors(std::string_view text, const std::vector<Expected>& expected) {
    const AssembleResult r = assemble_unvalidated(text);
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(r.tokens.empty());
    ASSERT_EQ(r.diagnostics.size(), expected.size()) << text << "\n" << diagnostics_text(r);
    for (size_t i = 0; i < expected.size(); ++i) {
        const Diagnostic& d = r.diagnostics[i];
        EXPECT_EQ(d.severity, Severity::Error);
        EXPECT_EQ(d.line, expected[i].line) << d.to_string();
        EXPECT_EQ(d.column, expected[i].column) << d.to_string();
        EXPECT_NE(d.message.find(expected[i].message_part), std::string::npos)
            << d.to_string() << "\nwanted: " << expected[i].message_part;
    }
}

TEST(Errors, SeveralInOneRunWithPositions) {
    expect_errors("vs_2_0\n"
                  "mov r0, r1\n"
                  "foo r0, r1\n"          // 3:1
                  "add r0, r1\n"          // 4:1
                  "mov r0.xq, r1\n"       // 5:8
                  "  mov r0, r12\n"       // 6:11
                  "mov r0, r1 r2\n"       // 7:12
                  "mov r0, c[a0.x - 1]\n"  // 8:16
                  "mov r0, r1\n",
                  {{3, 1, "unknown instruction 'foo'"},
                   {4, 1, "'add' takes 2 source operands, found 1"},
                   {5, 8, "invalid write mask 'xq'"},
                   {6, 11, "register r12 does not exist in vs_2_0 (r0..r11)"},
                   {7, 12, "unexpected 'r2' after the end of the statement"},
                   {8, 16, "negative index offsets are not supported"}});
}

TEST(Errors, FileNameInDiagnostics) {
    AssembleOptions options;
    options.file_name = "shader.vsh";
    options.validate = false;
    const AssembleResult r = assemble("vs_2_0\n\n   bogus r0\n", options);
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics[0].to_string(), "shader.vsh:3:4: error: unknown instruction 'bogus'");
}

TEST(Errors, Version) {
    expect_errors("", {{0, 0, "empty input"}});
    expect_errors("// only a comment\n", {{0, 0, "empty input"}});
    expect_errors("mov r0, r1\n", {{1, 1, "expected the shader version"}});
    expect_errors("\n  vs_3_0\nmov r0, r1\n", {{2, 3, "unsupported shader version 'vs_3_0'"}});
    expect_errors("ps_1_4\n", {{1, 1, "unsupported shader version 'ps_1_4'"}});
    expect_errors("vs_2_0\nvs_2_0\n", {{2, 1, "only once"}});
}

TEST(Errors, Registers) {
    expect_errors("vs_2_0\nmov r0, s0\n", {{2, 9, "register 's0' does not exist in vs_2_0"}});
    expect_errors("ps_2_0\nmov oPos, r0\n", {{2, 5, "register 'oPos' does not exist in ps_2_0"}});
    expect_errors("ps_2_0\nmov r0, r32\n", {{2, 9, "register r32 does not exist in ps_2_0 (r0..r31)"}});
    expect_errors("ps_2_0\nmov r0, c32\n", {{2, 9, "c32 does not exist in ps_2_0"}});
    expect_errors("vs_2_0\nmov r0, c2048\n", {{2, 9, "c2048 does not exist"}});
    expect_errors("vs_2_0\nmov v0, r0\n", {{2, 5, "register 'v0' cannot be written"}});
    expect_errors("vs_2_0\nmov r0, oPos\n", {{2, 9, "register 'oPos' cannot be read"}});
    expect_errors("vs_2_0\nmov r0, 5\n", {{2, 9, "expected a source register, found '5'"}});
    expect_errors("vs_2_0\nmov r0, c\n", {{2, 9, "needs a number"}});
    expect_errors("vs_2_0\nmov r0, r1_bx2\n", {{2, 9, "register modifier '_bx2' is not available"}});
    expect_errors("ps_2_0\nmov r2, 1 - r0\n", {{2, 9, "complement"}});
    expect_errors("vs_2_0\nmov r0, !r1\n", {{2, 9, "'!' applies only to boolean registers"}});
    expect_errors("vs_2_0\nmov -r0, r1\n", {{2, 5, "a destination cannot have a source modifier"}});
    expect_errors("vs_2_0\nmov r0[a0.x], r1\n", {{2, 7, "relative addressing is not allowed here"}});
    expect_errors("vs_2_0\nmov r0, v[a0.x]\n", {{2, 9, "only constant registers (c#) can be relatively addressed"}});
    expect_errors("ps_2_0\nmov r0, c[a0.x]\n", {{2, 11, "relative addressing is not available in ps_2_0"}});
    expect_errors("vs_2_0\nmov r0, c[a0.x + aL]\n", {{2, 18, "only one address register"}});
    expect_errors("vs_2_0\nmov r0, c[aL.x]\n", {{2, 13, "aL takes no swizzle"}});
    expect_errors("vs_2_0\nmov r0, c[a0.x + 1.5]\n", {{2, 18, "whole decimal number"}});
    expect_errors("vs_2_0\nmov r0, c[a0.x\n", {{3, 1, "expected '+' or ']'"}});
    expect_errors("vs_2_0\nmov r0, r1.xyzwx\n", {{2, 12, "invalid swizzle 'xyzwx'"}});
    expect_errors("vs_2_0\nmov r0, r1.\n", {{3, 1, "expected a swizzle after '.'"}});
    expect_errors("vs_2_0\nmov r0.wx, r1\n", {{2, 8, "invalid write mask 'wx'"}});
    expect_errors("vs_2_0\nmov r0.xxyz, r1\n", {{2, 8, "invalid write mask"}});
    expect_errors("ps_2_0\ntexkill c0\n", {{2, 9, "texkill tests a temporary or texture register"}});
}

TEST(Errors, Modifiers) {
    expect_errors("ps_2_0\nadd_x4 r0, r0, r1\n", {{2, 1, "result shift '_x4'"}});
    expect_errors("ps_2_0\nadd_foo r0, r0, r1\n", {{2, 1, "unknown instruction modifier '_foo'"}});
    expect_errors("vs_2_0\nadd_pp r0, r0, r1\n", {{2, 1, "'_pp' is only available in pixel shaders"}});
    expect_errors("vs_2_0\nif_sat b0\n", {{2, 1, "takes no modifiers"}});
    expect_errors("vs_2_0\nmov_ r0, r1\n", {{2, 1, "empty modifier"}});
}

TEST(Errors, Operands) {
    expect_errors("vs_2_0\nmov r0, r1, r2\n", {{2, 1, "'mov' takes 1 source operand, found 2"}});
    // every operand counted, past the four an instruction can have
    expect_errors("vs_2_0\nmov r0, r1, r2, r3, r4, r5, r6, r7\n", {{2, 1, "'mov' takes 1 source operand, found 7"}});
    expect_errors("vs_2_0\nmad r0, r1, r2, r3, r4, r5\n", {{2, 1, "'mad' takes 3 source operands, found 5"}});
    expect_errors("vs_2_0\nsincos r0.xy, r1.x\n", {{2, 1, "'sincos' takes 3 source operands, found 1"}});
    expect_errors("ps_2_0\nsincos r0.xy, r1.x, c0\n", {{2, 1, "'sincos' takes 1 or 3 source operands"}});
    expect_errors("vs_2_0\nret r0\n", {{2, 5, "unexpected 'r0'"}});
    expect_errors("vs_2_0\nmov r0,\n", {{3, 1, "expected a source register, found end of input"}});
}

TEST(Errors, Declarations) {
    expect_errors("vs_2_0\ndcl v0\n", {{2, 1, "needs a usage"}});
    expect_errors("vs_2_0\ndcl_foo v0\n", {{2, 1, "unknown declaration suffix '_foo'"}});
    expect_errors("vs_2_0\ndcl_texcoord16 v0\n", {{2, 1, "usage index 16 is out of range"}});
    expect_errors("vs_2_0\ndcl_position r0\n", {{2, 14, "declares only input registers"}});
    expect_errors("vs_2_0\ndcl_2d v0\n", {{2, 1, "applies only to sampler registers"}});
    expect_errors("ps_2_0\ndcl_texcoord0 t0\n", {{2, 1, "usage semantics are not allowed"}});
    expect_errors("ps_2_0\ndcl_2d s0.x\n", {{2, 8, "sampler declarations take no write mask"}});
    expect_errors("ps_2_0\ndcl_position s0\n", {{2, 1, "texture type"}});
    expect_errors("ps_2_0\ndcl r0\n", {{2, 5, "declares only v#, t# and s#"}});
    expect_errors("ps_2_0\ndcl_2d_cube s0\n", {{2, 1, "more than one texture type"}});
}

TEST(Errors, Definitions) {
    expect_errors("vs_2_0\ndef r0, 1, 2, 3, 4\n", {{2, 5, "def defines a constant register c#"}});
    expect_errors("vs_2_0\ndef c0, 1, 2, 3\n", {{3, 1, "expected ','"}});
    expect_errors("vs_2_0\ndef c0, 1, 2, 3, x\n", {{2, 18, "expected a number, found 'x'"}});
    expect_errors("vs_2_0\ndef c0, 1, 2, 3, 1e\n", {{2, 19, "unexpected 'e'"}});
    expect_errors("vs_2_0\ndef c0.x, 1, 2, 3, 4\n", {{2, 7, "takes no write mask"}});
    expect_errors("vs_2_0\ndef c0, -0x3F800000, 0, 0, 0\n", {{2, 9, "cannot be negated"}});
    expect_errors("vs_2_0\ndef c0, 0x123456789, 0, 0, 0\n", {{2, 9, "1 to 8 hex digits"}});
    expect_errors("vs_2_0\ndefi i0, 1.5, 0, 0, 0\n", {{2, 10, "whole decimal numbers"}});
    expect_errors("vs_2_0\ndefi i0, 4294967296, 0, 0, 0\n", {{2, 10, "does not fit in 32 bits"}});
    expect_errors("vs_2_0\ndefi i0, -2147483649, 0, 0, 0\n", {{2, 11, "does not fit in 32 bits"}});
    expect_errors("vs_2_0\ndefb b0, 1\n", {{2, 10, "expected true or false"}});
    expect_errors("vs_2_0\ndef_sat c0, 1, 2, 3, 4\n", {{2, 1, "takes no modifiers"}});
}

TEST(Errors, CommentBlocks) {
    expect_errors("ps_2_0\ncomment 0x1, 12\n",
                  {{2, 14, "comment words are written 0x and 1 to 8 hex digits, found '12'"}});
    expect_errors("ps_2_0\ncomment 0x123456789\n", {{2, 9, "found '0x123456789'"}});
    expect_errors("ps_2_0\ncomment 0x1 0x2\n", {{2, 13, "unexpected '0x2' after the end of the statement"}});
    expect_errors("ps_2_0\ncomment 0x1,\nmov oC0, c0\n", {{3, 1, "expected a DWORD (0xHHHHHHHH), found 'mov'"}});
    // The size field has 15 bits: 32767 words fit, the 32768th is refused.
    std::string text = "ps_2_0\ncomment 0x0";
    for (int i = 1; i < 0x7FFF; ++i) text += ",0x0";
    const AssembleResult fits = assemble_unvalidated(text);
    ASSERT_TRUE(fits.ok()) << diagnostics_text(fits);
    EXPECT_EQ(fits.tokens[1], 0x7FFFFFFEu);
    EXPECT_EQ(fits.tokens.size(), 2u + 0x7FFF + 1);
    expect_errors(text + ",0x0\n", {{2, 9 + 4 * 0x7FFF, "a comment block holds at most 32767 DWORDs"}});
}

TEST(Errors, Preprocessor) {
    expect_errors("#include \"x.h\"\nvs_2_0\n", {{1, 1, "unsupported preprocessor directive '#include'"}});
    expect_errors("#if 1\nvs_2_0\n#endif\n",
                  {{1, 1, "unsupported preprocessor directive '#if'"},
                   {3, 1, "unsupported preprocessor directive '#endif'"}});
    expect_errors("#define F(x) x\nvs_2_0\n", {{1, 10, "function-like macros are not supported"}});
    expect_errors("#define\nvs_2_0\n", {{1, 2, "#define needs a macro name"}});
    expect_errors("#line x\nvs_2_0\n", {{1, 7, "#line needs a decimal line number"}});
    expect_errors("vs_2_0\nmov r0, r1 # comment\n", {{2, 12, "unexpected character(s) '#'"}});
    // the whole message, said once
    const AssembleResult hash = assemble_unvalidated("vs_2_0\nmov r0, r1 # comment\n");
    ASSERT_EQ(hash.diagnostics.size(), 1u);
    EXPECT_EQ(hash.diagnostics[0].message, "unexpected character(s) '#' after the end of the statement");
    expect_errors("vs_2_0\n/* never closed\nmov r0, r1\n", {{2, 1, "unterminated /* comment"}});
}

TEST(Errors, RecoveryIsPerLine) {
    // One error per bad line; the good lines between them still parse.
    std::string text = "vs_2_0\n";
    for (int i = 0; i < 10; ++i) text += "mov r0, r1\nmov r0, @@@ $$$ r1\n";
    const AssembleResult r = assemble_unvalidated(text);
    ASSERT_EQ(r.diagnostics.size(), 10u) << diagnostics_text(r);
    for (size_t i = 0; i < 10; ++i) {
        EXPECT_EQ(r.diagnostics[i].line, 3 + 2 * i);
        EXPECT_EQ(r.diagnostics[i].column, 9u);
    }
}

TEST(Errors, MaxErrorsStopsReporting) {
    std::string text = "vs_2_0\n";
    for (int i = 0; i < 50; ++i) text += "bogus\n";
    AssembleOptions options;
    options.max_errors = 5;
    const AssembleResult r = assemble(text, options);
    ASSERT_EQ(r.diagnostics.size(), 6u);
    EXPECT_EQ(r.diagnostics[4].line, 6u);
    EXPECT_EQ(r.diagnostics[5].severity, Severity::Note);
    EXPECT_TRUE(has_errors(r.diagnostics));
}

// With validation on, every violation of the isa validator becomes an error at the
// instruction's position, prefixed with the rule name.
TEST(Validation, ViolationsBecomeDiagnostics) {
    const char* programs[] = {
        "vs_2_0\nmov oPos, v0\n",                     // v0 not declared
        "ps_2_0\nmov r0, t0\n  mov oC0, r0\n",        // t0 not declared
        "ps_2_0\ndcl t0\nexpp r0, t0.x\nmov oC0, r0\n",  // expp not in ps_2_0
        "vs_2_0\ndcl_position v0\nmov r0, v0\nmov oPos, r0\n",
    };
    for (const char* text : programs) {
        SCOPED_TRACE(text);
        const AssembleResult unvalidated = assemble_unvalidated(text);
        ASSERT_TRUE(unvalidated.ok()) << diagnostics_text(unvalidated);
        const std::vector<isa::Violation> violations = isa::validate(*unvalidated.program);
        const AssembleResult validated = assemble(text);
        EXPECT_EQ(validated.ok(), violations.empty());
        size_t errors = 0;
        for (const Diagnostic& d : validated.diagnostics)
            if (d.severity == Severity::Error) ++errors;
        EXPECT_EQ(errors, std::min<size_t>(violations.size(), AssembleOptions{}.max_errors))
            << diagnostics_text(validated);
        for (size_t i = 0; i < violations.size() && i < validated.diagnostics.size(); ++i) {
            const isa::Violation& v = violations[i];
            const std::string prefix = "[" + std::string(isa::rule_name(v.rule)) + "] ";
            bool found = false;
            for (const Diagnostic& d : validated.diagnostics)
                found |= d.message == prefix + v.message;
            EXPECT_TRUE(found) << prefix + v.message << "\n" << diagnostics_text(validated);
            if (v.instruction < unvalidated.program->instructions.size()) {
                const auto& at = unvalidated.program->instructions[v.instruction].location;
                bool positioned = false;
                for (const Diagnostic& d : validated.diagnostics)
                    positioned |= d.message == prefix + v.message && d.line == at.line &&
                                  d.column == at.column;
                EXPECT_TRUE(positioned) << diagnostics_text(validated);
            }
        }
    }
}

TEST(Validation, InstructionLocations) {
    const char* text = "ps_2_0\n  mov r0, c0\ndcl t0\n\tdef c0, 1, 1, 1, 1\n";
    const AssembleResult r = assemble_unvalidated(text);
    ASSERT_TRUE(r.ok());
    ASSERT_EQ(r.program->instructions.size(), 3u);
    EXPECT_EQ(r.program->instructions[0].location, (isa::SourceLocation{2, 3}));  // mov
    EXPECT_EQ(r.program->instructions[1].location, (isa::SourceLocation{3, 1}));  // dcl
    EXPECT_EQ(r.program->instructions[2].location, (isa::SourceLocation{4, 2}));  // def
    // Reordered (Wine's order), each statement keeps its own location.
    AssembleOptions wine;
    wine.validate = false;
    wine.wine_order = true;
    const AssembleResult w = assemble(text, wine);
    ASSERT_TRUE(w.ok());
    ASSERT_EQ(w.program->instructions.size(), 3u);
    EXPECT_EQ(w.program->instructions[0].location, (isa::SourceLocation{3, 1}));  // dcl
    EXPECT_EQ(w.program->instructions[1].location, (isa::SourceLocation{4, 2}));  // def
    EXPECT_EQ(w.program->instructions[2].location, (isa::SourceLocation{2, 3}));  // mov
}

// ---- robustness ------------------------------------------------------------------------

TEST(Robustness, RandomBytes) {
    std::mt19937 rng(2024);
    for (int i = 0; i < 3000; ++i) {
        std::string text;
        if (i % 2) text = i % 4 == 1 ? "vs_2_0\n" : "ps_2_0\n";
        const size_t n = rng() % 400;
        for (size_t k = 0; k < n; ++k) text += static_cast<char>(rng() & 0xFF);
        const AssembleResult r = assemble(text);
        if (!r.ok()) {
            EXPECT_TRUE(has_errors(r.diagnostics));
        }
        for (const Diagnostic& d : r.diagnostics) EXPECT_FALSE(d.message.empty());
    }
}

TEST(Robustness, RandomTokenSoup) {
    const char* vocabulary[] = {
        "vs_2_0", "ps_2_0", "vs.2.0", "mov", "add", "sincos", "texld", "texldp_pp", "dcl",
        "dcl_2d", "dcl_position", "dcl_texcoord15", "def", "defi", "defb", "if", "else",
        "endif", "loop", "rep", "call", "callnz", "label", "ret", "mova", "r0", "r31", "c0",
        "c", "c2047", "v0", "t0", "s0", "oC0", "oPos", "oFog", "a0", "aL", "b0", "i0", "l0",
        "true", "false", ",", ".", ".xyzw", ".x", "[", "]", "+", "-", "!", "1", "-0.5", ".5",
        "1e5", "0x7FC00000", "\n", "\n", "\n", "//", ";", "/*", "*/", "#define", "#line", "#undef",
        "X", "#", "_sat", "_pp", "\\\n", "\"", "m4x4", "texkill", "dp2add", "nop",
    };
    std::mt19937 rng(7);
    const size_t count = sizeof vocabulary / sizeof vocabulary[0];
    int assembled = 0;
    for (int i = 0; i < 3000; ++i) {
        std::string text = i % 3 == 0 ? "" : i % 3 == 1 ? "vs_2_0\n" : "ps_2_0\n";
        const size_t n = rng() % 12;
        for (size_t k = 0; k < n; ++k) {
            text += vocabulary[rng() % count];
            text += (rng() % 3) ? " " : "";
        }
        const AssembleResult validated = assemble(text);  // must not crash either
        if (!validated.ok()) {
            EXPECT_TRUE(has_errors(validated.diagnostics)) << text;
        }
        const AssembleResult r = assemble_unvalidated(text);
        if (r.ok()) {
            ++assembled;
            // Whatever assembles also round-trips.
            const AssembleResult again = assemble_unvalidated(disassemble(*r.program));
            ASSERT_TRUE(again.ok()) << text << "\n" << disassemble(*r.program);
            EXPECT_EQ(again.tokens, r.tokens) << text;
        } else {
            EXPECT_TRUE(has_errors(r.diagnostics)) << text;
        }
    }
    EXPECT_GT(assembled, 30);
    std::printf("token soup: %d of 3000 assembled\n", assembled);
}

// Huge inputs end in diagnostics, not crashes or hangs (ctest's timeout catches a hang; speed
// itself is a benchmark's business, not a test's).
TEST(Robustness, HugeInputsAreHandled) {
    // One extremely long line.
    std::string line = "vs_2_0\nmov r0, ";
    for (int i = 0; i < 50000; ++i) line += "r1, ";
    EXPECT_FALSE(assemble(line).ok());
    std::string garbage(2000000, '\x01');
    EXPECT_FALSE(assemble(garbage).ok());
    std::string long_ident = "vs_2_0\nmov r0, r" + std::string(1000000, '9') + "\n";
    EXPECT_FALSE(assemble(long_ident).ok());
    // Many statements.
    std::string many = "vs_2_0\ndcl_position v0\n";
    for (int i = 0; i < 20000; ++i) many += "add r0, r0, c1\n";
    const AssembleResult r = assemble_unvalidated(many);
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.tokens.size(), 1 + 3 + 4 * 20000 + 1u);
    // Exponential macro expansion is cut off.
    std::string macros = "#define A0 r0\n";
    for (int i = 1; i < 40; ++i)
        macros += "#define A" + std::to_string(i) + " A" + std::to_string(i - 1) + " A" +
                  std::to_string(i - 1) + "\n";
    macros += "vs_2_0\nmov r0, A39\n";
    const AssembleResult m = assemble(macros);
    EXPECT_FALSE(m.ok());
    // Self-referencing macros do not loop.
    EXPECT_FALSE(assemble("#define A B\n#define B A\nvs_2_0\nmov r0, A\n").ok());
}

}  // namespace
}  // namespace sm2::assembler::test
