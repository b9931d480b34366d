// Shader text in a command stream (asm<<END heredocs, text side files) goes through the
// assembler; the runtime does not link it (DESIGN.md: the runtime uses isa and emu only), so
// whoever replays hands this adaptor in as ReplayOptions::assembler: the sm2 tool, the tests,
// the fuzz target, a program that embeds sm2emu. Header-only for that reason: a program that
// includes it links sm2emu::assembler as well as sm2emu::runtime (or sm2emu::sm2emu, both).
//
//   sm2::runtime::ReplayOptions options;
//   options.assembler = sm2::runtime::stream_assembler();
#pragma once

#include <string_view>
#include <utility>

#include "sm2/assembler/assembler.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime {

// Heredoc shaders are validated here, against the device's instruction-slot limit the replayer
// passes in (SetDeviceLimits, DeviceOptions::max_instruction_slots, sm2 --max-slots), so a
// violation keeps its line inside the heredoc. A failure reports the first error.
inline ShaderAssembler stream_assembler() {
    return [](std::string_view text, unsigned max_instruction_slots) {
        assembler::AssembleOptions options;
        options.validation.max_instruction_slots = max_instruction_slots;
        auto assembled = assembler::assemble(text, options);
        AssembledShader out;
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

}  // namespace sm2::runtime
