#include "sm2/hlsl/compiler.h"

#include "backend.h"
#include "frontend.h"
#include "sm2/assembler/assembler.h"

namespace sm2::hlsl {

std::optional<isa::ShaderType> parse_profile(std::string_view profile) {
    if (profile == "vs_2_0") return isa::ShaderType::Vertex;
    if (profile == "ps_2_0") return isa::ShaderType::Pixel;
    return std::nullopt;
}

CompileResult compile(std::string_view source, const CompileOptions& options) {
    CompileResult result;
    SpirvModule spirv = hlsl_to_spirv(source, options);
    result.diagnostics = std::move(spirv.diagnostics);
    if (spirv.words.empty()) return result;
    AssemblyOutput assembly = spirv_to_assembly(spirv.words, source, options);
    result.diagnostics.insert(result.diagnostics.end(), assembly.diagnostics.begin(), assembly.diagnostics.end());
    if (assembly.text.empty()) return result;

    // The assembler encodes and validates (profile limits: slots, read ports, dependent reads...);
    // its findings are moved to the HLSL line the instruction came from.
    assembler::AssembleOptions assemble_options;
    assemble_options.file_name = options.file_name;
    auto assembled = assembler::assemble(assembly.text, assemble_options);
    std::vector<std::string> lines;
    for (size_t start = 0; start < assembly.text.size();) {
        const size_t end = assembly.text.find('\n', start);
        lines.push_back(assembly.text.substr(start, end - start));
        start = end == std::string::npos ? assembly.text.size() : end + 1;
    }
    for (auto d : assembled.diagnostics) {
        const uint32_t line = d.line;
        const std::string statement = line >= 1 && line <= lines.size() ? lines[line - 1] : std::string();
        const isa::SourceLocation origin =
            line >= 1 && line <= assembly.origin.size() ? assembly.origin[line - 1] : isa::SourceLocation{1, 1};
        d.file = options.file_name;
        d.line = origin.line;
        d.column = origin.column;
        if (!statement.empty()) d.message += " (in the generated `" + statement + "`)";
        result.diagnostics.push_back(std::move(d));
    }
    if (!assembled.ok()) return result;
    result.program = std::move(assembled.program);
    result.tokens = std::move(assembled.tokens);
    result.assembly = std::move(assembly.text);
    return result;
}

}  // namespace sm2::hlsl
