// HLSL source -> vs_2_0/ps_2_0 bytecode: glslang's HLSL front end to SPIR-V, SPIRV-Tools'
// optimizer, then sm2's own back end from SPIR-V to SM2 assembly, which the assembler encodes and
// validates against the profile's limits (docs/hlsl.md lists what is supported).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sm2/assembler/diagnostics.h"
#include "sm2/isa/program.h"
#include "sm2/isa/version.h"

namespace sm2::hlsl {

struct CompileOptions {
    std::string file_name = "<input>";  // used in diagnostics and to resolve #include "..."
    std::string entry_point = "main";
    isa::ShaderType stage = isa::ShaderType::Pixel;  // vs_2_0 or ps_2_0
    std::vector<std::pair<std::string, std::string>> defines;  // -D NAME=VALUE (value may be empty)
    std::vector<std::string> include_dirs;                       // -I DIR, searched after the file's folder
    // Adds the HLSL line table (sm2/isa/line_table.h, a comment block 'SM2L' after the CTAB):
    // each instruction's HLSL file and line, with those lines' text (sm2 compile --debug-info,
    // always for a command stream's hlsl<<TAG shaders). Off, the bytes do not change.
    bool debug_info = false;
    // A device's instruction-slot limit below the profile's (SetDeviceLimits, --max-slots); 0
    // keeps the profile's. Exceeding it is a located error, as in the assembler.
    unsigned max_instruction_slots = 0;
};

// A located diagnostic with the number fxc would give it (X3000 is printed as "X3000"); the
// mapping from our messages to fxc's numbers is in docs/hlsl.md ("Errors").
struct Diagnostic : assembler::Diagnostic {
    uint32_t fxc_code = 0;
};

struct CompileResult {
    std::optional<isa::Program> program;  // set when there were no errors
    std::vector<uint32_t> tokens;         // the bytecode, version .. END, with the CTAB comment
    std::string assembly;                 // the SM2 assembly the back end produced (empty on error;
                                          // without the line table's comment block)
    std::vector<Diagnostic> diagnostics;  // located at the HLSL source
    [[nodiscard]] bool ok() const { return program.has_value(); }
};

// Never throws; every problem (syntax, unsupported construct, profile limit) becomes a diagnostic.
[[nodiscard]] CompileResult compile(std::string_view source, const CompileOptions& options);

// fxc's form: "file(line,col): error X3000: message" (no position: "file: error X3000: message").
[[nodiscard]] std::string format_fxc(const Diagnostic& diagnostic);

// The profile name as -T spells it ("vs_2_0", "ps_2_0"); nullopt for any other.
[[nodiscard]] std::optional<isa::ShaderType> parse_profile(std::string_view profile);

}  // namespace sm2::hlsl
