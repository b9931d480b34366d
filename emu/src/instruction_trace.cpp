#include "sm2/emu/instruction_trace.h"

#include <algorithm>

namespace sm2::emu {

std::vector<InstructionTrace> trace_instructions(const Executable& executable, const ConstantFile& constants,
                                                 Batch& batch, Sampler* sampler) {
    std::vector<InstructionTrace> trace;
    execute(executable, constants, batch, sampler, [&](size_t index, const Step& step) {
        if (index == 0 || trace.empty() || trace.back().instruction != step.origin)
            trace.push_back(InstructionTrace{step.origin, false, 0, {}});
        InstructionTrace& current = trace.back();
        if (step.opcode == isa::Opcode::TexKill) {
            current.texkill = true;
            current.killed = batch.killed;
            return;
        }
        // Read after every step, so the entry ends with the value the instruction's last step left.
        auto it = std::find_if(current.writes.begin(), current.writes.end(), [&](const InstructionWrite& w) {
            return w.address == step.dest.address && (w.address || w.slot == step.dest.slot);
        });
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
