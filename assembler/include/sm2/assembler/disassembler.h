// Program -> assembly text that the assembler accepts again and turns into the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sm2/isa/program.h"

namespace sm2::assembler {

// The whole program: version line, then one statement per line. A comment block of the stream
// (e.g. a compiler's CTAB) is a `comment 0x..., ...` statement carrying its DWORDs (wrapped over
// several lines), after `//` lines that decode it: the constant table's names, types, registers
// and defaults, or the block's FOURCC.
[[nodiscard]] std::string disassemble(const isa::Program& program);

// One statement without a newline: "mov_sat r0.xy, -c[a0.x + 5].yzxw" (a comment block is
// its `comment` directive with every word on the one line).
[[nodiscard]] std::string format_instruction(isa::ShaderVersion version,
                                             const isa::Instruction& instruction);

// The disassembly, checked: the text is assembled again (validation off, source order) and
// every statement, comment blocks included, must come back as the same tokens. Bytecode that
// text cannot express (a `defb` holding 2, a register type the ISA does not have) gives an
// error naming the first statement that does not come back.
struct DisassemblyError {
    uint32_t token_offset = 0;  // the statement's first token in the bytecode
    std::string message;        // "'defb b0, true' assembles to different bytes", ...
};
struct CheckedDisassembly {
    std::string text;                      // always set (what disassemble() gives)
    std::optional<DisassemblyError> error;  // set when the text does not assemble back
};
[[nodiscard]] CheckedDisassembly disassemble_checked(const isa::Program& program);

}  // namespace sm2::assembler
