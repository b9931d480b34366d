// Optimized SPIR-V (frontend.h) -> SM2 assembly text. Straight-line code, plus in vs_2_0 the static
// flow control SM2 has: `if b#` for branches on uniform bools, `rep i#` for loops counted by uniform
// ints; anything else gets a located error naming what SM2 (or this back end) lacks.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/assembler/diagnostics.h"
#include "sm2/hlsl/compiler.h"
#include "sm2/isa/program.h"

namespace sm2::hlsl {

struct AssemblyOutput {
    std::string text;                            // "ps_2_0\ndcl ...\n..." (empty on error)
    std::vector<isa::SourceLocation> origin;     // per line of `text` (0-based): the HLSL line/column
    // Per line of `text`, for the line table (CompileOptions::debug_info): the HLSL line of the
    // SPIR-V instruction it came from, or of the nearest one before it that had a line (line 0:
    // a declaration, or none known), and that line's file.
    std::vector<isa::SourceLocation> line_origin;
    std::vector<std::string> line_file;
    std::vector<assembler::Diagnostic> diagnostics;
};

[[nodiscard]] AssemblyOutput spirv_to_assembly(const std::vector<uint32_t>& spirv, std::string_view source,
                                               const CompileOptions& options);

}  // namespace sm2::hlsl
