#include "sm2/emu/instruction_trace.h"

#include <algorithm>

namespace sm2::emu {

namespace {

bool same_register(const InstructionWrite& w, const StepDest& dest) {
    return w.address == dest.address && (w.address || w.slot == dest.slot);
}

// Whether `step` begins a new run of an instruction: another origin, or the same instruction
// again (a loop's next iteration), which writes a component this run already wrote (the steps
// of one matrix macro write disjoint components of one register).
bool starts_run(const std::vector<InstructionTrace>& trace, const Step& step) {
    if (trace.empty() || trace.back().instruction != step.origin) return true;
    const InstructionTrace& current = trace.back();
    if (step.opcode == isa::Opcode::TexKill) return current.texkill;
    return std::any_of(current.writes.begin(), current.writes.end(), [&](const InstructionWrite& w) {
        return same_register(w, step.dest) && (w.mask & step.dest.mask) != 0;
    });
}

}  // namespace

std::vector<InstructionTrace> trace_instructions(const Executable& executable, const ConstantFile& constants,
                                                 Batch& batch, Sampler* sampler) {
    std::vector<InstructionTrace> trace;
    execute(executable, constants, batch, sampler, [&](size_t, const Step& step) {
        if (starts_run(trace, step)) trace.push_back(InstructionTrace{step.origin, false, 0, {}});
        InstructionTrace& current = trace.back();
        if (step.opcode == isa::Opcode::TexKill) {
            current.texkill = true;
            current.killed = batch.killed;
            return;
        }
        // Read after every step, so the entry ends with the value the instruction's last step left.
        auto it = std::find_if(current.writes.begin(), current.writes.end(),
                               [&](const InstructionWrite& w) { return same_register(w, step.dest); });
        if (it == current.writes.end()) {
            current.writes.push_back(InstructionWrite{step.dest.slot, step.dest.address, 0, {}});
            it = current.writes.end() - 1;
        }
        it->mask |= step.dest.mask;
        for (unsigned lane = 0; lane < kBatchLanes; ++lane)
            for (unsigned c = 0; c < 4; ++c)
                it->lanes[lane][c] = step.dest.address ? static_cast<float>(batch.address[c][lane])
                                                       : batch.registers[step.dest.slot][c][lane];
    });
    return trace;
}

}  // namespace sm2::emu
