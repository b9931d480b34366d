// The lane kernels of the steps: what one step does to the lanes of a batch, written once.
// The interpreter (interpreter.cpp) calls these templates for every step; the JIT
// (jit/kernels.cpp, compiled to LLVM bitcode at build time) instantiates the float versions
// as extern "C" functions that the generated code calls with the step's fields as constants,
// so both run the same source for every rule (fetch with swizzle and negate, each opcode's
// lane loop, saturate and rounding on store, mova, texkill, texld).
//
// Every loop runs over all kBatchLanes lanes with a fixed trip count so that it vectorizes.
// A step reads all its sources into scratch vectors before it writes anything, which makes
// `mul r0, r0.yzxw, r0` well defined.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "numerics.h"
#include "sm2/emu/batch.h"
#include "sm2/emu/executable.h"
#include "sm2/emu/sampler.h"
#include "sm2/isa/program.h"

namespace sm2::emu::kernels {

namespace num = numerics;
using isa::Opcode;

constexpr unsigned N = kBatchLanes;
template <typename Real>
using Lanes = std::array<Real, kBatchLanes>;
// Four components of all lanes: a fetched source or a result before it is stored.
template <typename Real>
using Vector = std::array<Lanes<Real>, 4>;
using ConstantRegister = std::array<float, 4>;
using Texels = std::array<FloatLanes, 4>;

constexpr bool has(unsigned mask, unsigned c) { return ((mask >> c) & 1u) != 0; }
// The component a source's swizzle reads for result channel c.
constexpr unsigned component(unsigned swizzle, unsigned c) {
    return isa::swizzle_component(static_cast<uint8_t>(swizzle), static_cast<int>(c));
}

// The arithmetic steps: each has a compute<Real, Opcode::X, fast>() below. The JIT names its
// kernels after this list (sm2_k_X, and sm2_k_X_fast for the transcendental ones).
#define SM2_ARITHMETIC_STEPS(X)                                                                     \
    X(Mov) X(Abs) X(Frc) X(Sgn) X(Add) X(Sub) X(Mul) X(Min) X(Max) X(Slt) X(Sge) X(Mad) X(Cmp)     \
    X(Lrp) X(Dp3) X(Dp4) X(Dp2Add) X(Rcp) X(Rsq) X(Exp) X(ExpP) X(Log) X(LogP) X(Pow) X(Lit)      \
    X(Dst) X(Crs) X(Nrm) X(SinCos)

// The steps whose result depends on Transcendentals (exact or fast).
constexpr bool transcendental(Opcode op) {
    return op == Opcode::Exp || op == Opcode::ExpP || op == Opcode::Log || op == Opcode::LogP ||
           op == Opcode::Pow || op == Opcode::Lit || op == Opcode::SinCos;
}

// --- fetch: one source into a scratch vector, channels of s.channels only ---------------------

// A register of the batch (or, in compiled code, a temporary kept out of it: jit/compiler.cpp).
template <typename Real>
inline void fetch_register(Vector<Real>& dst, const Vector<Real>& reg, unsigned swizzle, bool negate,
                           unsigned channels) {
    for (unsigned c = 0; c < 4; ++c) {
        if (!has(channels, c)) continue;
        const Lanes<Real>& in = reg[component(swizzle, c)];
        Lanes<Real>& out = dst[c];
        if (negate)
            for (unsigned l = 0; l < N; ++l) out[l] = -in[l];
        else
            out = in;
    }
}

// Whether fetch_register() copies the register as it is: every channel it fetches read from
// its own component, not negated. The JIT then hands the step's kernel the register itself,
// not a copy (jit/compiler.cpp).
constexpr bool fetch_is_copy(unsigned swizzle, bool negate, unsigned channels) {
    if (negate) return false;
    for (unsigned c = 0; c < 4; ++c)
        if (has(channels, c) && component(swizzle, c) != c) return false;
    return true;
}

template <typename Real>
inline void fetch_lanes(Vector<Real>& dst, const BasicBatch<Real>& batch, unsigned slot, unsigned swizzle,
                        bool negate, unsigned channels) {
    fetch_register(dst, batch.registers[slot], swizzle, negate, channels);
}

template <typename Real>
inline void fetch_constant(Vector<Real>& dst, const ConstantRegister& value, unsigned swizzle, bool negate,
                           unsigned channels) {
    for (unsigned c = 0; c < 4; ++c) {
        if (!has(channels, c)) continue;
        const Real v = static_cast<Real>(value[component(swizzle, c)]);
        dst[c].fill(negate ? -v : v);
    }
}

template <typename Real>
inline void fetch_zero(Vector<Real>& dst, bool negate, unsigned channels) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(channels, c)) dst[c].fill(negate ? -Real(0) : Real(0));
}

// c[a0.? + index]: chosen per lane; out-of-range reads return (0,0,0,0) (docs, "Address
// Register"). `count` is the size of the constant file. Every lane loads (register 0 when its
// own is out of range) and selects: no branch, so the loop vectorizes.
template <typename Real>
inline void fetch_relative(Vector<Real>& dst, const BasicBatch<Real>& batch, const ConstantRegister* constants,
                           int64_t count, unsigned index, unsigned address_component, unsigned swizzle,
                           bool negate, unsigned channels) {
    if (count <= 0) {
        fetch_zero(dst, negate, channels);
        return;
    }
    const auto& address = batch.address[address_component];
    for (unsigned c = 0; c < 4; ++c) {
        if (!has(channels, c)) continue;
        const unsigned read = component(swizzle, c);
        Lanes<Real>& out = dst[c];
        for (unsigned l = 0; l < N; ++l) {
            const int64_t i = int64_t{address[l]} + index;
            const bool inside = i >= 0 && i < count;
            const Real loaded = static_cast<Real>(constants[inside ? static_cast<size_t>(i) : 0][read]);
            const Real v = inside ? loaded : Real(0);
            out[l] = negate ? -v : v;
        }
    }
}

template <typename Real>
inline void fetch(Vector<Real>& dst, const StepSource& s, const BasicBatch<Real>& batch,
                  const ConstantRegister* constants, int64_t count) {
    switch (s.kind) {
    case OperandKind::Lanes: fetch_lanes(dst, batch, s.index, s.swizzle, s.negate, s.channels); break;
    case OperandKind::Constant: fetch_constant(dst, constants[s.index], s.swizzle, s.negate, s.channels); break;
    case OperandKind::RelativeConstant:
        fetch_relative(dst, batch, constants, count, s.index, s.address_component, s.swizzle, s.negate, s.channels);
        break;
    case OperandKind::Zero: fetch_zero(dst, s.negate, s.channels); break;
    }
}

// --- the arithmetic of each step -------------------------------------------------------------

// The fast transcendentals exist for float storage only; the fp64 reference is exact.
template <typename Real, bool fast>
inline Real exp2(Real x) {
    if constexpr (fast && std::is_same_v<Real, float>) return num::fast::exp2(x);
    else return num::exp2(x);
}
template <typename Real, bool fast>
inline Real log2(Real x) {
    if constexpr (fast && std::is_same_v<Real, float>) return num::fast::log2(x);
    else return num::log2(x);
}
template <typename Real, bool fast>
inline Real pow(Real base, Real exponent) {
    if constexpr (fast && std::is_same_v<Real, float>) return num::fast::pow(base, exponent);
    else return num::pow(base, exponent);
}

// result[c][l] = f(a[c][l], ...) for every channel of the mask.
template <typename Real, typename F>
inline void unary(Vector<Real>& result, const Vector<Real>& a, unsigned mask, F f) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(mask, c))
            for (unsigned l = 0; l < N; ++l) result[c][l] = f(a[c][l]);
}
template <typename Real, typename F>
inline void binary(Vector<Real>& result, const Vector<Real>& a, const Vector<Real>& b, unsigned mask, F f) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(mask, c))
            for (unsigned l = 0; l < N; ++l) result[c][l] = f(a[c][l], b[c][l]);
}
template <typename Real, typename F>
inline void ternary(Vector<Real>& result, const Vector<Real>& a, const Vector<Real>& b, const Vector<Real>& c3,
                    unsigned mask, F f) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(mask, c))
            for (unsigned l = 0; l < N; ++l) result[c][l] = f(a[c][l], b[c][l], c3[c][l]);
}
// A scalar instruction's result: one value per lane, replicated into the channels of `mask`.
template <typename Real>
inline void replicate(Vector<Real>& result, unsigned mask, const Lanes<Real>& value) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(mask, c)) result[c] = value;
}
// Scalar instructions: one value per lane from channel 0 of the sources, replicated.
template <typename Real, typename F>
inline void scalar(Vector<Real>& result, unsigned mask, F f) {
    Lanes<Real> value;
    for (unsigned l = 0; l < N; ++l) value[l] = f(l);
    replicate(result, mask, value);
}

// pow's first way, for a batch whose exponent b.x is one integer n in [1, 256] on every lane
// (n = num::uniform_integer_exponent(b.x), not 0): the same correctly rounded result as
// pow_float() by repeated squaring, a few multiplications instead of its two series (specular
// exponents are such constants). Fast mode takes it too: it is cheaper than fast's log2 and exp2
// and more accurate (fast mode had made lighting shaders slower than exact: docs/numerics.md).
// False, with `result` untouched, where a lane's rounding is not certain (pow_float_integer()):
// the series decide.
inline bool pow_by_squaring(Vector<float>& result, const Vector<float>& a, unsigned n, unsigned mask) {
    FloatLanes value;
    if (!num::pow_float_integer(a[0], n, value)) return false;
    replicate(result, mask, value);
    return true;
}

// The result channels of step `op` (those of `mask`, or all that the instruction defines) from
// the fetched sources a, b, c3.
template <typename Real, Opcode op, bool fast>
inline void compute(Vector<Real>& result, const Vector<Real>& a, const Vector<Real>& b, const Vector<Real>& c3,
                    unsigned mask) {
    if constexpr (op == Opcode::Mov) {
        unary(result, a, mask, [](Real x) { return x; });
    } else if constexpr (op == Opcode::Abs) {
        unary(result, a, mask, [](Real x) { return std::fabs(x); });
    } else if constexpr (op == Opcode::Frc) {
        unary(result, a, mask, [](Real x) { return num::frc(x); });
    } else if constexpr (op == Opcode::Sgn) {
        unary(result, a, mask, [](Real x) { return num::sgn(x); });
    } else if constexpr (op == Opcode::Add) {
        binary(result, a, b, mask, [](Real x, Real y) { return x + y; });
    } else if constexpr (op == Opcode::Sub) {
        binary(result, a, b, mask, [](Real x, Real y) { return x - y; });
    } else if constexpr (op == Opcode::Mul) {
        binary(result, a, b, mask, [](Real x, Real y) { return num::mul(x, y); });
    } else if constexpr (op == Opcode::Min) {
        binary(result, a, b, mask, [](Real x, Real y) { return num::min(x, y); });
    } else if constexpr (op == Opcode::Max) {
        binary(result, a, b, mask, [](Real x, Real y) { return num::max(x, y); });
    } else if constexpr (op == Opcode::Slt) {
        binary(result, a, b, mask, [](Real x, Real y) { return num::slt(x, y); });
    } else if constexpr (op == Opcode::Sge) {
        binary(result, a, b, mask, [](Real x, Real y) { return num::sge(x, y); });
    } else if constexpr (op == Opcode::Mad) {
        ternary(result, a, b, c3, mask, [](Real x, Real y, Real z) { return num::mad(x, y, z); });
    } else if constexpr (op == Opcode::Cmp) {
        ternary(result, a, b, c3, mask, [](Real x, Real y, Real z) { return num::cmp(x, y, z); });
    } else if constexpr (op == Opcode::Lrp) {
        // t * (a - b) + b
        ternary(result, a, b, c3, mask, [](Real t, Real x, Real y) { return num::mad(t, x - y, y); });
    } else if constexpr (op == Opcode::Dp3) {
        scalar(result, mask, [&](unsigned l) {
            return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) + num::mul(a[2][l], b[2][l]);
        });
    } else if constexpr (op == Opcode::Dp4) {
        scalar(result, mask, [&](unsigned l) {
            return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) + num::mul(a[2][l], b[2][l]) +
                   num::mul(a[3][l], b[3][l]);
        });
    } else if constexpr (op == Opcode::Dp2Add) {
        scalar(result, mask,
               [&](unsigned l) { return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) + c3[0][l]; });
    } else if constexpr (op == Opcode::Rcp) {
        scalar(result, mask, [&](unsigned l) { return num::rcp(a[0][l]); });
    } else if constexpr (op == Opcode::Rsq) {
        scalar(result, mask, [&](unsigned l) { return num::rsq(a[0][l]); });
    } else if constexpr (op == Opcode::Exp || op == Opcode::ExpP) {
        scalar(result, mask, [&](unsigned l) { return exp2<Real, fast>(a[0][l]); });
    } else if constexpr (op == Opcode::Log || op == Opcode::LogP) {
        scalar(result, mask, [&](unsigned l) { return log2<Real, fast>(a[0][l]); });
    } else if constexpr (op == Opcode::Pow) {
        if constexpr (std::is_same_v<Real, float>) {
            if (const unsigned n = num::uniform_integer_exponent(b[0]); n != 0)
                if (pow_by_squaring(result, a, n, mask)) return;
        }
        // A compiler barrier: without it clang 14 carries the exponent's first load (the test
        // above) into this lane loop as a loop-carried value and leaves the loop scalar (the
        // native exact pow 4x slower, scene 27 1.5x). A function call between the two would do
        // the same but needs a symbol the native kernels' levels would share (CMakeLists.txt).
        asm volatile("" ::: "memory");
        scalar(result, mask, [&](unsigned l) { return pow<Real, fast>(a[0][l], b[0][l]); });
    } else if constexpr (op == Opcode::Lit) {
        for (unsigned l = 0; l < N; ++l) {
            const Real x = a[0][l], y = a[1][l], power = num::lit_power_clamp(a[3][l]);
            const Real specular = pow<Real, fast>(y, power);
            result[0][l] = Real(1);
            result[1][l] = x > Real(0) ? x : Real(0);
            result[2][l] = x > Real(0) && y > Real(0) ? specular : Real(0);
            result[3][l] = Real(1);
        }
    } else if constexpr (op == Opcode::Dst) {
        for (unsigned l = 0; l < N; ++l) {
            result[0][l] = Real(1);
            result[1][l] = num::mul(a[1][l], b[1][l]);
            result[2][l] = a[2][l];
            result[3][l] = b[3][l];
        }
    } else if constexpr (op == Opcode::Crs) {
        for (unsigned l = 0; l < N; ++l) {
            result[0][l] = num::mul(a[1][l], b[2][l]) - num::mul(a[2][l], b[1][l]);
            result[1][l] = num::mul(a[2][l], b[0][l]) - num::mul(a[0][l], b[2][l]);
            result[2][l] = num::mul(a[0][l], b[1][l]) - num::mul(a[1][l], b[0][l]);
        }
    } else if constexpr (op == Opcode::Nrm) {
        for (unsigned l = 0; l < N; ++l) {
            const Real f = num::nrm_factor(num::mul(a[0][l], a[0][l]) + num::mul(a[1][l], a[1][l]) +
                                           num::mul(a[2][l], a[2][l]));
            for (unsigned c = 0; c < 4; ++c) result[c][l] = num::mul(a[c][l], f);
        }
    } else if constexpr (op == Opcode::SinCos) {
        // x = cos, y = sin
        if constexpr (fast && std::is_same_v<Real, float>) {
            for (unsigned l = 0; l < N; ++l) num::fast::sincos(a[0][l], result[1][l], result[0][l]);
        } else {
            for (unsigned l = 0; l < N; ++l) {
                result[0][l] = std::cos(a[0][l]);
                result[1][l] = std::sin(a[0][l]);
            }
        }
    } else {
        static_assert(op == Opcode::Mov, "no kernel for this opcode");
    }
}

// --- the steps that write no lane register -----------------------------------------------------

// mova: a0 components of the mask from the fetched source.
template <typename Real>
inline void mova(BasicBatch<Real>& batch, const Vector<Real>& a, unsigned mask) {
    for (unsigned c = 0; c < 4; ++c)
        if (has(mask, c))
            for (unsigned l = 0; l < N; ++l) batch.address[c][l] = num::mova_round(a[c][l]);
}

// Whether a run stops after a texkill (see BasicBatch::stop_when_all_killed).
template <typename Real>
inline bool stop_after_texkill(const BasicBatch<Real>& batch) {
    return batch.stop_when_all_killed && (batch.killed & kAllLanes) == kAllLanes;
}

// texkill: lanes whose tested components (bit c of `tested`) hold a value below zero.
template <typename Real>
inline void texkill(BasicBatch<Real>& batch, const Vector<Real>& a, unsigned tested) {
    LaneMask killed = 0;
    for (unsigned l = 0; l < N; ++l) {
        const Real inf = num::kInfinity<Real>;  // untested channels never kill
        const bool kills = num::kills(has(tested, 0) ? a[0][l] : inf, has(tested, 1) ? a[1][l] : inf,
                                      has(tested, 2) ? a[2][l] : inf, has(tested, 3) ? a[3][l] : inf);
        killed |= LaneMask{kills} << l;  // (no branch: the loop vectorizes)
    }
    batch.killed |= killed & kAllLanes;
}

// --- texld ------------------------------------------------------------------------------------

// The request a texld step hands its Sampler, and what an unbound stage returns. Called by the
// interpreter directly, and by the JIT's sampling callback.
inline void sample_texels(Sampler* sampler, unsigned sampler_index, unsigned variant, unsigned lane_count,
                          LaneMask killed, const Texels& coordinates, Texels& texels) {
    if (sampler == nullptr) {
        // No sampler: what D3D9 samples from an unbound stage, (0, 0, 0, 1).
        for (unsigned c = 0; c < 4; ++c) texels[c].fill(c == 3 ? 1.0f : 0.0f);
        return;
    }
    TextureRequest request;
    request.sampler = sampler_index;
    request.variant = static_cast<TextureVariant>(variant);
    request.coordinates = &coordinates;
    request.quad_count = (lane_count + kQuadLanes - 1) / kQuadLanes;
    request.helper_lanes = killed;
    sampler->sample(request, texels);
}

// texld: the coordinates (all four components of the fetched source) as floats, the texels
// back in the storage type. `sample(coordinates, texels, lane_count, killed)` fetches them.
template <typename Real, typename Sample>
inline void texture(Vector<Real>& result, const Vector<Real>& a, const BasicBatch<Real>& batch, Sample&& sample) {
    alignas(64) Texels coordinates;
    alignas(64) Texels texels;
    // NaN made canonical here too: a value the JIT keeps in a temporary may hold any NaN
    // (store_register), and the sign of a NaN coordinate picks a cube face.
    for (unsigned c = 0; c < 4; ++c)
        for (unsigned l = 0; l < N; ++l) coordinates[c][l] = num::canonical_nan(static_cast<float>(a[c][l]));
    sample(coordinates, texels, batch.lane_count, batch.killed);
    for (unsigned c = 0; c < 4; ++c)
        for (unsigned l = 0; l < N; ++l) result[c][l] = static_cast<Real>(texels[c][l]);
}

// --- store ------------------------------------------------------------------------------------

// The result channels of the mask, saturated (_sat), rounded to the precision mode and, where
// `canonical`, with NaN made canonical (numerics.h), into the destination slot.
// The interpreter stores every result canonical (the debugger and traces show its registers).
// The JIT does not on the temporaries it keeps to itself: no rule reads the payload or sign of
// a NaN but a cube lookup's face choice, whose coordinates texture() makes canonical, so an
// intermediate NaN's bits never reach a result, and every value that leaves the compiled code
// (outputs, a0) is stored canonical. JitDifferential checks it with NaN payloads everywhere and
// a sampler whose texels hash the coordinates' bits.
template <typename Real>
inline void store_register(Vector<Real>& reg, Vector<Real>& r, unsigned mask, bool saturate, ResultRounding rounding,
                           bool canonical) {
    for (unsigned c = 0; c < 4; ++c) {
        if (!has(mask, c)) continue;
        Lanes<Real>& v = r[c];
        if (saturate)
            for (unsigned l = 0; l < N; ++l) v[l] = num::saturate(v[l]);
        // One loop per rounding, so each stays a plain vectorizable loop.
        if (rounding == ResultRounding::Fp24)
            for (unsigned l = 0; l < N; ++l) v[l] = num::round_result(v[l], ResultRounding::Fp24);
        else if (rounding == ResultRounding::Fp16)
            for (unsigned l = 0; l < N; ++l) v[l] = num::round_result(v[l], ResultRounding::Fp16);
        if (canonical && !saturate)  // (a saturated value is never NaN)
            for (unsigned l = 0; l < N; ++l) v[l] = num::canonical_nan(v[l]);
        reg[c] = v;
    }
}

template <typename Real>
inline void store(BasicBatch<Real>& batch, unsigned slot, Vector<Real>& r, unsigned mask, bool saturate,
                  ResultRounding rounding) {
    store_register(batch.registers[slot], r, mask, saturate, rounding, true);
}

}  // namespace sm2::emu::kernels
