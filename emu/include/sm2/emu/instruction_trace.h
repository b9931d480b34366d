// Runs an executable one source instruction at a time (sm2 debug): the steps lowering made from
// one instruction of the Program (Step::origin; an m4x4 is four dp4 steps, a loop's body comes
// back once per iteration) are grouped, and after the group the registers it wrote are read
// back from the batch. It is execute() with a StepObserver: the values are the interpreter's.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/emu/engine.h"

namespace sm2::emu {

// Register names of lane slots: "r3", "v0", "t1", "oPos", "oC0".
[[nodiscard]] std::string slot_name(unsigned slot);

// One register an instruction wrote, as the instruction left it: all four components (not only
// those of `mask`) in every lane of the batch.
struct InstructionWrite {
    uint16_t slot = 0;      // lane slot (unused when `address`)
    bool address = false;   // a0 (mova), its integer components stored as floats
    uint8_t mask = 0;       // components the instruction wrote (bit c = component c)
    std::array<std::array<float, 4>, kBatchLanes> lanes{};
};

// One run of one source instruction.
struct InstructionTrace {
    uint32_t instruction = 0;  // index in Program::instructions (Step::origin)
    bool texkill = false;      // a texkill: `killed` is Batch::killed after it
    LaneMask killed = 0;
    std::vector<InstructionWrite> writes;  // in the order first written
};

// execute(executable, constants, batch, sampler) with every step observed and grouped into runs
// of consecutive steps with the same origin (a loop's next iteration of a one-instruction body
// starts a new run: it writes again what the run wrote).
[[nodiscard]] std::vector<InstructionTrace> trace_instructions(const Executable& executable, const ConstantFile& constants,
                                                               Batch& batch, Sampler* sampler);

}  // namespace sm2::emu
