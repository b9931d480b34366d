// Shader text in a command stream (asm<<END heredocs, text side files) goes through the
// assembler; the runtime does not link it, so whoever replays hands this adaptor in: the sm2
// tool, and the tests and fuzz target that replay streams. Header-only for that reason.
#pragma once

#include <string_view>
#include <utility>

#include "sm2/assembler/assembler.h"
#include "sm2/runtime/replay.h"

namespace sm2::tools {

// Heredoc shaders are validated here, against `max_instruction_slots` (0: the profile's; the
// device's --max-slots), so a violation keeps its line inside the heredoc. A failure reports the
// first error.
inline runtime::ShaderAssembler stream_assembler(unsigned max_instruction_slots = 0) {
    return [max_instruction_slots](std::string_view text) {
        assembler::AssembleOptions options;
        options.validation.max_instruction_slots = max_instruction_slots;
        auto assembled = assembler::assemble(text, options);
        runtime::AssembledShader out;
        if (assembled.program) {
            out.program = std::move(assembled.program);
            return out;
        }
        for (const auto& d : assembled.diagnostics)
            if (d.severity == assembler::Severity::Error) {
                out.error = d.message;
                out.line = d.line;
                break;
            }
        return out;
    };
}

}  // namespace sm2::tools
