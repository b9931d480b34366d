// Program -> assembly text that the assembler accepts again and turns into the same bytes.
#pragma once

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

}  // namespace sm2::assembler
