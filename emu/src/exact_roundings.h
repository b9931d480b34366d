// Roundings that cannot change a value, dropped from a lowered step list.
#pragma once

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "sm2/emu/executable.h"

namespace sm2::emu {

// Clears the rounding (fp24, fp16) of the steps whose every result channel is one of their
// sources' values, sign aside (mov, abs, min, max, cmp's chosen operands; saturated or not),
// where each such value is known to be representable in the step's format already: a result
// of an earlier step rounded to that format (or to fp16, whose values fp24 holds too), a def'd
// constant that is, or 0. Rounding such a value gives its own bits back (numerics.h's
// roundings keep NaN payloads, infinities and signed zeros), so both engines compute the same
// bits with fewer operations; the JIT's compile of an fp24 routine shrinks with them.
// `defs`: the shader's def'd float constants (index, value); other constants are unknown.
void drop_exact_roundings(std::vector<Step>& steps, std::span<const std::pair<unsigned, std::array<float, 4>>> defs);

}  // namespace sm2::emu
