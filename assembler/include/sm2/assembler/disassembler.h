// Program -> assembly text that the assembler accepts again and turns into the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sm2/isa/program.h"

namespace sm2::assembler {

// The whole program: version line, then one statement per line. Comment blocks of the stream
// (e.g. a compiler's CTAB) are printed as `// comment: N DWORDs` lines, which the assembler
// skips.
[[nodiscard]] std::string disassemble(const isa::Program& program);

// One statement without a newline: "mov_sat r0.xy, -c[a0.x + 5].yzxw".
[[nodiscard]] std::string format_instruction(isa::ShaderVersion version,
                                             const isa::Instruction& instruction);

// The disassembly, checked: the text is assembled again (validation off) and every statement
// must come back as the same tokens. Comment blocks are the exception: they print as
// `// comment: N DWORDs` lines and are dropped. Bytecode that text cannot express (a `defb`
// holding 2, a register type the ISA does not have, statements in an order the assembler does
// not emit) gives an error naming the first statement that does not come back.
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
