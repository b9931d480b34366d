// The HLSL line table (CompileOptions::debug_info, the 'SM2L' comment block of
// sm2/isa/line_table.h): each emitted instruction maps to the HLSL line that produces it, worked
// out by reading the shaders below; the table costs nothing when not asked for (the same bytes
// without it), survives an include, and its reader refuses a truncated block.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/hlsl/compiler.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/line_table.h"

namespace {

using sm2::isa::Opcode;

std::string messages(const sm2::hlsl::CompileResult& result) {
    std::string text;
    for (const auto& d : result.diagnostics) text += sm2::hlsl::format_fxc(d) + "\n";
    return text;
}

// Line by line: a mad (n * 2 - 1), a dp3 (dot), a texld (tex2D), then two mul and the mov into
// oC0 for the return (the output's copy takes the line of the value it copies).
constexpr const char* kLit =
    "sampler2D tex;\n"                                                   // 1
    "float3 light;\n"                                                    // 2
    "float4 tint;\n"                                                     // 3
    "float4 main(float3 n : TEXCOORD0, float2 uv : TEXCOORD1) : COLOR\n"  // 4
    "{\n"                                                                // 5
    "    float3 nn = n * 2 - 1;\n"                                       // 6
    "    float d = dot(nn, light);\n"                                    // 7
    "    float4 c = tex2D(tex, uv);\n"                                   // 8
    "    return c * tint * d;\n"                                         // 9
    "}\n";                                                               // 10

sm2::hlsl::CompileResult compile(const std::string& source, sm2::isa::ShaderType stage, bool debug_info,
                                 const std::string& file = "lit.hlsl") {
    sm2::hlsl::CompileOptions options;
    options.file_name = file;
    options.stage = stage;
    options.debug_info = debug_info;
    return sm2::hlsl::compile(source, options);
}

// (opcode, HLSL line) of each instruction that is not a comment, dcl or def.
std::vector<std::pair<Opcode, uint32_t>> code_lines(const sm2::isa::Program& program, const sm2::isa::LineTable& table) {
    std::vector<std::pair<Opcode, uint32_t>> out;
    const auto ordinals = sm2::isa::instruction_ordinals(program);
    for (size_t k = 0; k < program.instructions.size(); ++k) {
        const auto& ins = program.instructions[k];
        if (ins.opcode == Opcode::Comment) continue;
        const auto* e = table.entry(static_cast<uint32_t>(ordinals[k]));
        if (ins.is_setup()) {
            EXPECT_EQ(e, nullptr) << "a dcl or def has no HLSL line";
            continue;
        }
        EXPECT_NE(e, nullptr) << "instruction " << k;
        out.emplace_back(ins.opcode, e ? e->line : 0);
    }
    return out;
}

TEST(HlslLineTable, EachInstructionMapsToTheLineThatProducesIt) {
    const auto result = compile(kLit, sm2::isa::ShaderType::Pixel, true);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_line_table(*result.program);
    ASSERT_TRUE(found.has_value()) << result.assembly;
    ASSERT_TRUE(found->ok()) << found->error;
    const sm2::isa::LineTable& table = *found->table;
    ASSERT_EQ(table.files, std::vector<std::string>{"lit.hlsl"});
    const std::vector<std::pair<Opcode, uint32_t>> expected = {
        {Opcode::Mad, 6}, {Opcode::Dp3, 7}, {Opcode::Tex, 8}, {Opcode::Mul, 9}, {Opcode::Mul, 9}, {Opcode::Mov, 9}};
    EXPECT_EQ(code_lines(*result.program, table), expected) << result.assembly;
    ASSERT_NE(table.text(0, 7), nullptr);
    EXPECT_EQ(*table.text(0, 7), "    float d = dot(nn, light);");
    EXPECT_EQ(*table.text(0, 9), "    return c * tint * d;");
    EXPECT_EQ(table.text(0, 5), nullptr) << "only lines that produced code are carried";
    // The block comes after the CTAB, before the code.
    ASSERT_GE(result.program->instructions.size(), 2u);
    EXPECT_EQ(result.program->instructions[0].comment.at(0), 0x42415443u);  // 'CTAB'
    EXPECT_EQ(result.program->instructions[1].comment.at(0), sm2::isa::kFourccLineTable);
}

TEST(HlslLineTable, WithoutDebugInfoTheBytesAreTheSameLessTheBlock) {
    const auto plain = compile(kLit, sm2::isa::ShaderType::Pixel, false);
    const auto with = compile(kLit, sm2::isa::ShaderType::Pixel, true);
    ASSERT_TRUE(plain.ok() && with.ok());
    EXPECT_FALSE(sm2::isa::find_line_table(*plain.program).has_value());
    sm2::isa::Program stripped = *with.program;
    std::erase_if(stripped.instructions, [](const sm2::isa::Instruction& ins) {
        return ins.opcode == Opcode::Comment && ins.comment.at(0) == sm2::isa::kFourccLineTable;
    });
    EXPECT_EQ(sm2::isa::encode(stripped), plain.tokens);
    EXPECT_EQ(sm2::isa::encode(*with.program), with.tokens);
    EXPECT_EQ(with.assembly, plain.assembly);
}

TEST(HlslLineTable, DisassemblyRoundTripsTheBlockByteForByte) {
    const auto with = compile(kLit, sm2::isa::ShaderType::Pixel, true);
    ASSERT_TRUE(with.ok());
    const std::string text = sm2::assembler::disassemble(*with.program);
    EXPECT_NE(text.find("// SM2L HLSL line table, "), std::string::npos) << text;
    EXPECT_NE(text.find("//   lit.hlsl:7 (instructions 5):     float d = dot(nn, light);\n"), std::string::npos) << text;
    const auto again = sm2::assembler::assemble(text, {});
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again.tokens, with.tokens);
}

TEST(HlslLineTable, LinesOfAnIncludedFileNameThatFile) {
    const std::filesystem::path dir = std::filesystem::path(SM2_BINARY_DIR) / "hlsl_line_table_test";
    std::filesystem::create_directories(dir);
    const std::string header = (dir / "shade.hlsli").string();
    std::ofstream(header) << "float3 shade(float3 n, float3 l)\n"                       // 1
                             "{\n"                                                      // 2
                             "    return saturate(dot(n, l)) * float3(1, 0.5, 0.25);\n"  // 3
                             "}\n";
    const std::string source =
        "#include \"shade.hlsli\"\n"                                          // 1
        "float4x4 wvp;\n"                                                     // 2
        "float3 light;\n"                                                     // 3
        "struct VsOut { float4 pos : POSITION; float4 col : COLOR0; };\n"     // 4
        "VsOut main(float4 p : POSITION, float3 n : NORMAL)\n"                // 5
        "{\n"                                                                 // 6
        "    VsOut o;\n"                                                      // 7
        "    o.pos = mul(p, wvp);\n"                                          // 8
        "    o.col = float4(shade(n, light), 1);\n"                           // 9
        "    return o;\n"                                                     // 10
        "}\n";
    const auto result = compile(source, sm2::isa::ShaderType::Vertex, true, (dir / "vs.hlsl").string());
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_line_table(*result.program);
    ASSERT_TRUE(found && found->ok());
    const auto& table = *found->table;
    const auto ordinals = sm2::isa::instruction_ordinals(*result.program);
    int dp4 = 0, dp3 = 0;
    for (size_t k = 0; k < result.program->instructions.size(); ++k) {
        const auto& ins = result.program->instructions[k];
        const auto* e = ordinals[k] >= 0 ? table.entry(static_cast<uint32_t>(ordinals[k])) : nullptr;
        if (ins.opcode == Opcode::Dp4) {  // mul(p, wvp): four dp4 on line 8 of vs.hlsl
            ++dp4;
            ASSERT_NE(e, nullptr);
            EXPECT_EQ(table.files.at(e->file), (dir / "vs.hlsl").string());
            EXPECT_EQ(e->line, 8u);
        }
        if (ins.opcode == Opcode::Dp3) {  // dot(n, l): line 3 of the included file
            ++dp3;
            ASSERT_NE(e, nullptr);
            EXPECT_EQ(table.files.at(e->file), header);
            EXPECT_EQ(e->line, 3u);
            ASSERT_NE(table.text(e->file, 3), nullptr);
            EXPECT_EQ(*table.text(e->file, 3), "    return saturate(dot(n, l)) * float3(1, 0.5, 0.25);");
        }
    }
    EXPECT_EQ(dp4, 4) << result.assembly;
    EXPECT_EQ(dp3, 1) << result.assembly;
}

TEST(HlslLineTable, SerializeParseRoundTripAndTruncation) {
    sm2::isa::LineTable table;
    table.files = {"a.hlsl", "common.hlsli"};
    table.lines = {{0, 3, "x = 1;"}, {1, 12, ""}};
    table.entries = {{2, 0, 3, 5}, {4, 1, 12, 1}};
    const auto payload = sm2::isa::serialize_line_table(table);
    const auto parsed = sm2::isa::parse_line_table(payload);
    ASSERT_TRUE(parsed.ok()) << parsed.error;
    EXPECT_EQ(parsed.table->files, table.files);
    ASSERT_EQ(parsed.table->entries.size(), 2u);
    EXPECT_EQ(parsed.table->entries[1].instruction, 4u);
    EXPECT_EQ(parsed.table->entries[1].line, 12u);
    EXPECT_EQ(*parsed.table->text(0, 3), "x = 1;");
    for (size_t size = 0; size < payload.size(); ++size)
        EXPECT_FALSE(sm2::isa::parse_line_table(std::span(payload).first(size)).ok()) << size;
}

}  // namespace
