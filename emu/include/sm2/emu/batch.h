// The lanes a shader runs over, stored as structure of arrays: every component of every
// register is an array of kBatchLanes values, so one instruction is applied to all lanes in a
// tight loop the compiler can vectorize. Pixel batches hold whole 2x2 quads.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "sm2/emu/executable.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/version.h"

namespace sm2::emu {

// Lanes per batch: 4 quads of pixels, or 16 vertices.
constexpr unsigned kBatchLanes = 16;
constexpr unsigned kQuadLanes = 4;
constexpr unsigned kBatchQuads = kBatchLanes / kQuadLanes;

// One bit per lane (bit l = lane l).
using LaneMask = uint32_t;
static_assert(kBatchLanes <= 32, "LaneMask holds one bit per lane");
constexpr LaneMask kAllLanes = kBatchLanes == 32 ? ~LaneMask{0} : (LaneMask{1} << kBatchLanes) - 1;

// The register files of both profiles mapped onto one flat array of "slots". A slot holds one
// four-component register for every lane. Constants are not slots: they are the same for all
// lanes and live in a ConstantFile.
namespace slot {
constexpr unsigned kTempFirst = 0;          // r0..r31 (ps_2_0 documents 12, Wine encodes 32)
constexpr unsigned kTempCount = 32;
constexpr unsigned kInputFirst = 32;        // v0..v15 (vs), v0..v1 (ps)
constexpr unsigned kInputCount = 16;
constexpr unsigned kTexCoordFirst = 48;     // ps t0..t7
constexpr unsigned kTexCoordCount = 8;
constexpr unsigned kPosition = 56;          // vs oPos
constexpr unsigned kFog = 57;               // vs oFog (x used)
constexpr unsigned kPointSize = 58;         // vs oPts (x used)
constexpr unsigned kColorOutFirst = 59;     // vs oD0, oD1
constexpr unsigned kColorOutCount = 2;
constexpr unsigned kTexCoordOutFirst = 61;  // vs oT0..oT7
constexpr unsigned kTexCoordOutCount = 8;
constexpr unsigned kRenderTargetFirst = 69; // ps oC0..oC3
constexpr unsigned kRenderTargetCount = 4;
constexpr unsigned kDepth = 73;             // ps oDepth (x used)
constexpr unsigned kCount = 74;
}  // namespace slot
static_assert(slot::kCount == kSlotCount, "executable.h and batch.h agree on the slot count");

// The slot of register `type` number `index` in a shader of kind `shader`; nullopt for
// registers that are not per-lane values (constants, samplers, a0, aL, b#, i#, labels).
[[nodiscard]] std::optional<unsigned> register_slot(isa::ShaderType shader, isa::RegisterType type,
                                                    unsigned index);
// True for slots a shader writes as its results (oPos ... oDepth).
[[nodiscard]] constexpr bool is_output_slot(unsigned s) { return s >= slot::kPosition && s < slot::kCount; }
// True for the temporaries' slots (r0 ... r31).
[[nodiscard]] constexpr bool is_temp_slot(unsigned s) {
    return s >= slot::kTempFirst && s < slot::kTempFirst + slot::kTempCount;
}

template <typename Real>
struct BasicBatch {
    using Lanes = std::array<Real, kBatchLanes>;
    using Register = std::array<Lanes, 4>;  // x, y, z, w

    // Lanes in use; the engine always computes all kBatchLanes (unused lanes are harmless).
    unsigned lane_count = kBatchLanes;
    // Pixel shaders: lanes discarded by texkill. They keep executing as helper lanes so the
    // derivatives of their quad stay defined; the output merger drops their writes.
    LaneMask killed = 0;
    // A run may stop at a texkill that leaves every lane killed (both engines check after each
    // texkill): a draw sets it, since the output merger drops killed lanes and nothing else reads
    // a batch's results; the outputs then keep what they held. Off by default (sm2 run, the
    // debugger and pixel history show every output), and reset() leaves it as it is.
    bool stop_when_all_killed = false;
    alignas(64) std::array<Register, slot::kCount> registers{};
    // a0 (vs_2_0: four integer components), set by mova.
    alignas(64) std::array<std::array<int32_t, kBatchLanes>, 4> address{};

    // Initial contents as D3D9 defines them (see reset()).
    BasicBatch() { reset(); }

    // Inputs v#/t# read (0,0,0,1) until the caller stores the components its vertex
    // declaration or interpolators supply ("missing components are (0,0,0,1)"). Outputs start
    // as (0,0,0,1) as well, so components a shader leaves unwritten read "partial 0001" in the
    // next stage. Temps and a0 start at 0 (reading them unwritten is invalid, but defined here).
    // Whole registers copied from two patterns (a per-float fill loop here, left scalar at -O2,
    // was most of the vertex stage's own time: it runs per 16 vertices).
    void reset() {
        Register zero{}, unit_w{};
        unit_w[3].fill(Real(1));
        for (unsigned s = 0; s < slot::kCount; ++s) registers[s] = is_temp_slot(s) ? zero : unit_w;
        address = {};
        killed = 0;
    }

    Register& temp(unsigned r) { return registers[slot::kTempFirst + r]; }
    Register& input(unsigned v) { return registers[slot::kInputFirst + v]; }
    Register& texcoord(unsigned t) { return registers[slot::kTexCoordFirst + t]; }
    Register& position() { return registers[slot::kPosition]; }
    Register& fog() { return registers[slot::kFog]; }
    Register& point_size() { return registers[slot::kPointSize]; }
    Register& color_out(unsigned d) { return registers[slot::kColorOutFirst + d]; }
    Register& texcoord_out(unsigned t) { return registers[slot::kTexCoordOutFirst + t]; }
    Register& render_target(unsigned c) { return registers[slot::kRenderTargetFirst + c]; }
    Register& depth() { return registers[slot::kDepth]; }
    const Register& temp(unsigned r) const { return registers[slot::kTempFirst + r]; }
    const Register& input(unsigned v) const { return registers[slot::kInputFirst + v]; }
    const Register& texcoord(unsigned t) const { return registers[slot::kTexCoordFirst + t]; }
    const Register& position() const { return registers[slot::kPosition]; }
    const Register& fog() const { return registers[slot::kFog]; }
    const Register& point_size() const { return registers[slot::kPointSize]; }
    const Register& color_out(unsigned d) const { return registers[slot::kColorOutFirst + d]; }
    const Register& texcoord_out(unsigned t) const { return registers[slot::kTexCoordOutFirst + t]; }
    const Register& render_target(unsigned c) const { return registers[slot::kRenderTargetFirst + c]; }
    const Register& depth() const { return registers[slot::kDepth]; }

    // Stores one four-component value into one lane of a register.
    void set(Register& reg, unsigned lane, Real x, Real y, Real z, Real w) {
        reg[0][lane] = x; reg[1][lane] = y; reg[2][lane] = z; reg[3][lane] = w;
    }
    // Stores the same value into every lane of a register.
    void broadcast(Register& reg, Real x, Real y, Real z, Real w) {
        reg[0].fill(x); reg[1].fill(y); reg[2].fill(z); reg[3].fill(w);
    }
};

// The engine's batch in fp32, fp24 and fp16 modes.
using Batch = BasicBatch<float>;
// The fp64 reference mode's batch.
using ReferenceBatch = BasicBatch<double>;

}  // namespace sm2::emu
