#include "sm2/hlsl/compiler.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "backend.h"
#include "frontend.h"
#include "sm2/assembler/assembler.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/line_table.h"

namespace sm2::hlsl {

namespace {

// Where a diagnostic came from: glslang (parse, link), the back end, or the assembler's validator.
enum class Stage { FrontEnd, BackEnd, Validation };

struct FxcCodeRule {
    Stage stage;
    const char* fragment;  // in the message (glslang's wording or ours)
    uint32_t code;
};

// fxc's numbers for the same errors, first match wins; docs/hlsl.md lists them.
constexpr FxcCodeRule kFxcCodes[] = {
    {Stage::FrontEnd, "undeclared identifier", 3004},
    {Stage::FrontEnd, "unknown variable", 3004},  // glslang's wording
    {Stage::FrontEnd, "redefinition", 3003},
    {Stage::FrontEnd, "no matching overloaded function", 3013},
    {Stage::FrontEnd, "cannot convert", 3017},
    {Stage::FrontEnd, "not convertible", 3017},
    {Stage::FrontEnd, "include", 1507},  // fxc: failed to open source file
    {Stage::FrontEnd, "entry point", 3501},
    {Stage::BackEnd, "temporary registers", 4505},  // fxc: maximum temp register index exceeded
    {Stage::BackEnd, "constant registers", 4550},
    {Stage::Validation, "arithmetic instruction slot", 5608},
    {Stage::Validation, "instruction slot", 5609},
};

// Anything else: a syntax or semantic error (X3000), or an expression the profile cannot express
// (X4532, "cannot map expression to ps_2_0 instruction set").
uint32_t fxc_code(Stage stage, std::string message) {
    std::transform(message.begin(), message.end(), message.begin(),
                   [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
    for (const auto& rule : kFxcCodes)
        if (rule.stage == stage && message.find(rule.fragment) != std::string::npos) return rule.code;
    return stage == Stage::FrontEnd ? 3000 : 4532;
}

void add_diagnostics(std::vector<Diagnostic>& out, Stage stage, const std::vector<assembler::Diagnostic>& found) {
    for (const auto& d : found) {
        Diagnostic coded;
        static_cast<assembler::Diagnostic&>(coded) = d;
        coded.fxc_code = fxc_code(stage, d.message);
        out.push_back(std::move(coded));
    }
}

std::vector<std::string> split_lines(std::string_view text) {
    std::vector<std::string> lines;
    for (size_t start = 0; start < text.size();) {
        size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string line(text.substr(start, end - start));
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(std::move(line));
        start = end + 1;
    }
    return lines;
}

// Each code instruction's HLSL file and line (the back end's line_origin of the assembly line it
// was assembled from), and the text of those lines: the main file's from `source`, an included
// file's read again from disk (no text when it cannot be). A dcl or def has no line.
isa::LineTable build_line_table(const isa::Program& program, const AssemblyOutput& assembly, std::string_view source,
                                const CompileOptions& options) {
    constexpr size_t kMaxLineText = 256;  // longer lines are cut: the block must stay under 32767 DWORDs
    isa::LineTable table;
    std::map<std::string, uint32_t> file_index;
    std::map<uint32_t, std::vector<std::string>> file_lines;
    std::set<std::pair<uint32_t, uint32_t>> lines_used;
    const auto ordinals = isa::instruction_ordinals(program);
    for (size_t k = 0; k < program.instructions.size(); ++k) {
        const auto& ins = program.instructions[k];
        if (ins.opcode == isa::Opcode::Comment || ins.is_setup()) continue;
        const uint32_t text_line = ins.location.line;
        if (text_line < 1 || text_line > assembly.line_origin.size() || assembly.line_origin[text_line - 1].line == 0)
            continue;
        const std::string& file = assembly.line_file[text_line - 1];
        auto [it, added] = file_index.emplace(file, static_cast<uint32_t>(table.files.size()));
        if (added) {
            table.files.push_back(file);
            if (file == options.file_name) {
                file_lines[it->second] = split_lines(source);
            } else {
                std::ifstream in(file, std::ios::binary);
                std::stringstream text;
                if (in) text << in.rdbuf();
                file_lines[it->second] = split_lines(text.str());
            }
        }
        const isa::SourceLocation origin = assembly.line_origin[text_line - 1];
        table.entries.push_back({static_cast<uint32_t>(ordinals[k]), it->second, origin.line, origin.column});
        lines_used.insert({it->second, origin.line});
    }
    for (const auto& [file, line] : lines_used) {
        const auto& lines = file_lines[file];
        if (line > lines.size()) continue;
        std::string text = lines[line - 1];
        if (text.size() > kMaxLineText) text = text.substr(0, kMaxLineText - 3) + "...";
        table.lines.push_back({file, line, std::move(text)});
    }
    return table;
}

// The program with the line table's comment block after its leading comment blocks (the CTAB);
// left as it is when the table does not fit in one comment block (32767 DWORDs).
void add_line_table(isa::Program& program, std::vector<uint32_t>& tokens, const isa::LineTable& table) {
    isa::Instruction block;
    block.opcode = isa::Opcode::Comment;
    block.comment = isa::serialize_line_table(table);
    if (block.comment.size() > 0x7FFF) return;
    size_t at = 0;
    while (at < program.instructions.size() && program.instructions[at].opcode == isa::Opcode::Comment) ++at;
    std::vector<isa::Instruction> instructions = program.instructions;
    instructions.insert(instructions.begin() + static_cast<long>(at), std::move(block));
    const isa::Program with_table{program.version, instructions};
    std::vector<uint32_t> encoded = isa::encode(with_table);
    auto decoded = isa::decode(encoded);  // token offsets recomputed
    if (!decoded.ok() || decoded.program->instructions.size() != instructions.size()) return;
    for (size_t k = 0; k < instructions.size(); ++k) decoded.program->instructions[k].location = instructions[k].location;
    program = std::move(*decoded.program);
    tokens = std::move(encoded);
}

}  // namespace

std::string format_fxc(const Diagnostic& d) {
    std::string text = d.file;
    if (d.line > 0) text += "(" + std::to_string(d.line) + "," + std::to_string(d.column) + ")";
    const char* severity = d.severity == assembler::Severity::Error     ? "error"
                           : d.severity == assembler::Severity::Warning ? "warning"
                                                                        : "note";
    char code[16];
    std::snprintf(code, sizeof code, "X%04u", d.fxc_code);
    return text + ": " + severity + " " + code + ": " + d.message;
}

std::optional<isa::ShaderType> parse_profile(std::string_view profile) {
    if (profile == "vs_2_0") return isa::ShaderType::Vertex;
    if (profile == "ps_2_0") return isa::ShaderType::Pixel;
    return std::nullopt;
}

CompileResult compile(std::string_view source, const CompileOptions& options) {
    CompileResult result;
    SpirvModule spirv = hlsl_to_spirv(source, options);
    add_diagnostics(result.diagnostics, Stage::FrontEnd, spirv.diagnostics);
    if (spirv.words.empty()) return result;
    AssemblyOutput assembly = spirv_to_assembly(spirv.words, source, options);
    add_diagnostics(result.diagnostics, Stage::BackEnd, assembly.diagnostics);
    if (assembly.text.empty()) return result;

    // The assembler encodes and validates (profile limits: slots, read ports, dependent reads...);
    // its findings are moved to the HLSL line the instruction came from.
    assembler::AssembleOptions assemble_options;
    assemble_options.file_name = options.file_name;
    assemble_options.validation.max_instruction_slots = options.max_instruction_slots;
    auto assembled = assembler::assemble(assembly.text, assemble_options);
    std::vector<std::string> lines;
    for (size_t start = 0; start < assembly.text.size();) {
        const size_t end = assembly.text.find('\n', start);
        lines.push_back(assembly.text.substr(start, end - start));
        start = end == std::string::npos ? assembly.text.size() : end + 1;
    }
    std::vector<assembler::Diagnostic> validation;
    for (auto d : assembled.diagnostics) {
        const uint32_t line = d.line;
        const std::string statement = line >= 1 && line <= lines.size() ? lines[line - 1] : std::string();
        const isa::SourceLocation origin =
            line >= 1 && line <= assembly.origin.size() ? assembly.origin[line - 1] : isa::SourceLocation{1, 1};
        d.file = options.file_name;
        d.line = origin.line;
        d.column = origin.column;
        if (!statement.empty()) d.message += " (in the generated `" + statement + "`)";
        validation.push_back(std::move(d));
    }
    add_diagnostics(result.diagnostics, Stage::Validation, validation);
    if (!assembled.ok()) return result;
    result.program = std::move(assembled.program);
    result.tokens = std::move(assembled.tokens);
    if (options.debug_info)
        add_line_table(*result.program, result.tokens, build_line_table(*result.program, assembly, source, options));
    result.assembly = std::move(assembly.text);
    return result;
}

}  // namespace sm2::hlsl
