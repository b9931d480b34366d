// HLSL -> optimized SPIR-V (glslang + SPIRV-Tools); the back end (backend.h) takes it from there.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "sm2/assembler/diagnostics.h"
#include "sm2/hlsl/compiler.h"

namespace sm2::hlsl {

struct SpirvModule {
    std::vector<uint32_t> words;                     // empty on error
    std::vector<assembler::Diagnostic> diagnostics;  // glslang's errors, located
};

// Parses, links and optimizes into one function of straight-line code where the program allows it
// (inlined calls, unrolled loops, folded constants, branches on constants removed, small if/else
// turned into selects). Line information (OpLine) is kept for the back end's diagnostics.
[[nodiscard]] SpirvModule hlsl_to_spirv(std::string_view source, const CompileOptions& options);

}  // namespace sm2::hlsl
