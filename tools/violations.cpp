#include "violations.h"

#include "sm2/assembler/disassembler.h"

namespace sm2::tools {

void print_violations(std::ostream& out, const std::string& name, const isa::Program& program,
                      const std::vector<isa::Violation>& violations) {
    for (const auto& v : violations) {
        out << name;
        const bool located = v.instruction < program.instructions.size();
        if (located) {
            const auto& ins = program.instructions[v.instruction];
            out << ": token " << ins.token_offset << " (byte 0x" << std::hex << ins.token_offset * 4 << std::dec << ")";
        }
        out << ": error: [" << isa::rule_name(v.rule) << "] " << v.message << '\n';
        if (located)
            out << "    " << assembler::format_instruction(program.version, program.instructions[v.instruction]) << '\n';
    }
}

}  // namespace sm2::tools
