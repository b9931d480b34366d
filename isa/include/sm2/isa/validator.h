// The validator: every documented limit and rule of vs_2_0 / ps_2_0
// (registers-and-limits.md §10), each violation naming its rule and instruction.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::isa {

// Stable identifiers of the checks, in the order of the checklist.
enum class Rule : uint8_t {
    Structure,          // 1: stream shape (version, lengths, reserved bits)
    OpcodeVersion,      // 2: opcode allowed in this version
    Operands,           // 3: operand count, register types, register index ranges
    SetupFirst,         // 4: dcl/def before the first executable instruction
    InputDeclared,      // 5: inputs read are declared, components read are declared
    SamplerDeclared,    // 6: samplers used are declared with a known type
    TempInitialized,    // 7: no temp component read before written
    AddressRegister,    // 8: a0 written before used; aL only inside loops
    RelativeAddressing, // 9: only on c#, index a0.c / aL
    SourceModifiers,    // 10
    DestModifiers,      // 11
    Swizzle,            // 12
    WriteMask,          // 13
    ReadPorts,          // 14
    InstructionOperands,// 15: instruction-specific operand rules
    SlotBudget,         // 16
    DependentReads,     // 17
    FlowControl,        // 18
    Outputs,            // 19
};

[[nodiscard]] std::string_view rule_name(Rule rule);  // "read-ports", "slot-budget", ...

struct Violation {
    Rule rule;
    std::string message;          // what is wrong, naming the instruction ("texld r0, ...")
    size_t instruction = SIZE_MAX;  // index into Program::instructions; SIZE_MAX = whole program
    SourceLocation location;      // copied from the instruction when it came from text
};

struct ValidationOptions {
    // Maximum instruction slots override (e.g. a ps_2_x-size limit for long shaders);
    // 0 keeps the profile's limits.
    unsigned max_instruction_slots = 0;
};

[[nodiscard]] std::vector<Violation> validate(const Program& program,
                                              const ValidationOptions& options = {});

// Instruction slots by budget (registers-and-limits.md): what the slot-budget rule counts.
struct SlotCount {
    unsigned total = 0;
    unsigned arithmetic = 0;  // everything but texture instructions (vs: all of them)
    unsigned texture = 0;     // texld*, texkill
};
// The slots of one statement (none for dcl, def* and comment blocks).
[[nodiscard]] SlotCount instruction_slots(ShaderVersion version, const Instruction& instruction);
[[nodiscard]] SlotCount count_slots(const Program& program);
// fxc's summary line: "approximately 12 instruction slots used (3 texture, 9 arithmetic)"; the
// part in parentheses only when texture slots are used, "slot" for one.
[[nodiscard]] std::string slot_summary(const SlotCount& slots);

}  // namespace sm2::isa
