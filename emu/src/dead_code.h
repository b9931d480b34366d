// Dead-code removal over a lowered step list.
#pragma once

#include <cstdint>
#include <vector>

#include "sm2/emu/executable.h"

namespace sm2::emu {

// True for steps whose sources are read per result channel (their `channels` follow the mask).
[[nodiscard]] bool is_component_wise(isa::Opcode opcode);

// Walks the steps backwards keeping only those whose results some output (bit s -
// slot::kPosition of `outputs_read`) or a texkill depends on. Write masks shrink to the
// channels that are read later.
void remove_dead_steps(std::vector<Step>& steps, uint32_t outputs_read);

}  // namespace sm2::emu
