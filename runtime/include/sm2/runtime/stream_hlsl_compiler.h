// HLSL shader text in a command stream (hlsl<<END heredocs) goes through the HLSL compiler
// (sm2/hlsl/compiler.h: glslang, SPIRV-Tools and sm2's back end); the runtime does not link it,
// so whoever replays hands this adaptor in as ReplayOptions::hlsl_compiler: the sm2 tool, the
// tests. Header-only for that reason: a program that includes it links sm2_hlsl as well.
//
//   sm2::runtime::ReplayOptions options;
//   options.hlsl_compiler = sm2::runtime::stream_hlsl_compiler();
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include "sm2/hlsl/compiler.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime {

// Entry point `main`, profile vs_2_0 or ps_2_0 from the call (CreateVertexShader,
// CreatePixelShader). The compiler checks the profile's limits and the device's instruction-slot
// limit the replayer passes in (SetDeviceLimits, DeviceOptions::max_instruction_slots, sm2
// --max-slots), as for assembly heredocs. A failure reports the first error, at its line in the
// HLSL text. The program carries the HLSL line table (a comment block,
// sm2/isa/line_table.h) so that sm2 debug can step by HLSL line.
inline ShaderCompiler stream_hlsl_compiler() {
    return [](std::string_view source, isa::ShaderType stage, unsigned max_instruction_slots) {
        hlsl::CompileOptions options;
        options.max_instruction_slots = max_instruction_slots;
        options.file_name = "hlsl";
        options.stage = stage;
        options.debug_info = true;  // the line table, for sm2 debug (a comment block: runs the same)
        auto compiled = hlsl::compile(source, options);
        AssembledShader out;
        for (const auto& d : compiled.diagnostics)
            if (d.severity == assembler::Severity::Error) {
                out.error = d.message;
                out.line = d.line;
                return out;
            }
        if (!compiled.program) {
            out.error = "the HLSL does not compile";
            return out;
        }
        out.program = std::move(compiled.program);
        return out;
    };
}

}  // namespace sm2::runtime
