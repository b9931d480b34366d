// Precision modes: a property of the engine, chosen when a shader is lowered, never scattered
// casts. Each step of an executable carries the rounding its result gets (numerics.h applies it).
#pragma once

#include <cstdint>

namespace sm2::emu {

enum class Precision : uint8_t {
    Fp32,  // IEEE single for every result (default)
    Fp24,  // pixel shaders round every result to s16e7, as ps_2_0 hardware does; vs stay fp32
    Fp64,  // reference: IEEE double everywhere, no rounding (needs a ReferenceBatch)
};

// How exp/expp, log/logp, pow (and lit's power) and sincos are computed.
enum class Transcendentals : uint8_t {
    Exact,  // the C library in the storage precision (default)
    Fast,   // branch-free approximations at the documented minimum precisions, which the
            // compiler vectorizes; fp32/fp24 only (the fp64 reference is always exact)
};

struct PrecisionOptions {
    Precision precision = Precision::Fp32;
    Transcendentals transcendentals = Transcendentals::Exact;
    // Round the results of _pp instructions to s10e5 (IEEE half), as the docs permit.
    // Ignored in Fp64 mode.
    bool partial_precision_fp16 = false;
};

// What happens to one step's result before it is stored.
enum class ResultRounding : uint8_t { None, Fp24, Fp16 };

}  // namespace sm2::emu
