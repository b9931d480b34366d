// Uniform steps (uniform_steps.cpp): the prelude's run, which bind_constants() calls.
#pragma once

#include "sm2/emu/batch.h"
#include "sm2/emu/executable.h"

namespace sm2::emu {

// Appends the derived constants of `prelude` to `file` (whose first registers are the
// application's and the defs'): its steps run by the interpreter over one batch, each snapshot
// taken from lane 0 once the steps before it have run.
void bind_derived_constants(const UniformPrelude& prelude, Transcendentals transcendentals, ConstantFile& file);

// The interpreter over `steps` (interpreter.cpp): no sampler, no observer.
void execute_steps(std::span<const Step> steps, const ConstantFile& constants, Batch& batch,
                   Transcendentals transcendentals);

}  // namespace sm2::emu
