// Random executables for differential tests: step lists with every opcode the interpreter runs,
// random swizzles, negates, masks, saturate and rounding and every operand kind, and batches and
// constant files full of special values (NaN with payloads, +-inf, +-0, denormals, huge, tiny,
// halves, the fp24 and fp16 limits). Shared by the JIT's tests (the JIT against the
// interpreter) and the engine's (a lowering pass against the steps it rewrites).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/emu/executable.h"

namespace sm2::test::random_executables {

using emu::OperandKind;
using emu::ResultRounding;
using emu::Step;
using emu::StepSource;
using isa::Opcode;
using isa::ShaderType;
using Random = std::mt19937_64;

inline unsigned pick(Random& random, unsigned count) { return static_cast<unsigned>(random() % count); }
inline bool chance(Random& random, unsigned percent) { return pick(random, 100) < percent; }

// A float from a mix meant to hit every special case of the numeric policy.
inline float special_float(Random& random) {
    const unsigned kind = pick(random, 24);
    const bool negative = chance(random, 50);
    float value = 0;
    switch (kind) {
    case 0: value = 0.0f; break;
    case 1: value = std::numeric_limits<float>::infinity(); break;
    case 2:  // quiet NaN with a random payload
        value = std::bit_cast<float>(0x7FC00000u | static_cast<uint32_t>(random() & 0x3FFFFFu));
        break;
    case 3: value = std::bit_cast<float>(static_cast<uint32_t>(random() & 0x7FFFFFu) | 1u); break;  // denormal
    case 4: value = std::bit_cast<float>(0x7F000000u | static_cast<uint32_t>(random() & 0x7FFFFFu)); break;  // huge
    case 5: value = std::bit_cast<float>(0x00800000u | static_cast<uint32_t>(random() & 0x7FFFFFu)); break;  // tiny
    case 6: value = 1.0f; break;
    case 7: value = static_cast<float>(pick(random, 64)) * 0.5f; break;  // integers and halves
    case 8: value = static_cast<float>(pick(random, 8)) * 0.25f; break;
    case 9:  // fp24 / fp16 rounding boundaries, largest floats below an integer
        value = std::nextafter(static_cast<float>(pick(random, 4)), 0.0f);
        break;
    case 10: value = 65504.0f + static_cast<float>(pick(random, 32)); break;
    case 11: value = std::bit_cast<float>(static_cast<uint32_t>(random() & 0xFFFFFFFFu)); break;  // any bits
    case 12: value = 127.9961f + static_cast<float>(pick(random, 3)) - 1.0f; break;  // lit's power clamp
    case 13: value = std::ldexp(1.0f, static_cast<int>(pick(random, 60)) - 72); break;  // near fp24's floor
    default: {
        // ordinary values over a wide range of magnitudes
        std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
        value = std::ldexp(mantissa(random), static_cast<int>(pick(random, 40)) - 20);
        break;
    }
    }
    return negative ? -value : value;
}

// --- random executables ---------------------------------------------------------------------

inline constexpr Opcode kOpcodes[] = {
    Opcode::Mov,    Opcode::Abs, Opcode::Frc, Opcode::Sgn, Opcode::Add,    Opcode::Sub,  Opcode::Mul,     Opcode::Min,
    Opcode::Max,    Opcode::Slt, Opcode::Sge, Opcode::Mad, Opcode::Cmp,    Opcode::Lrp,  Opcode::Dp3,     Opcode::Dp4,
    Opcode::Dp2Add, Opcode::Rcp, Opcode::Rsq, Opcode::Exp, Opcode::ExpP,   Opcode::Log,  Opcode::LogP,    Opcode::Pow,
    Opcode::Lit,    Opcode::Dst, Opcode::Crs, Opcode::Nrm, Opcode::SinCos, Opcode::Mova, Opcode::TexKill, Opcode::Tex,
};

// Which modes a random executable is built for.
enum class Rounding { Fp32, Fp24, Fp16 };

struct Mode {
    Rounding rounding;
    emu::Transcendentals transcendentals;
};

inline const char* mode_name(const Mode& mode) {
    static const char* const names[3][2] = {{"fp32", "fp32/fast"}, {"fp24", "fp24/fast"}, {"fp16", "fp16/fast"}};
    return names[static_cast<int>(mode.rounding)][mode.transcendentals == emu::Transcendentals::Fast];
}

class ProgramGenerator {
public:
    ProgramGenerator(Random& random, Mode mode, unsigned constant_count)
        : random_(random), mode_(mode), constant_count_(constant_count) {}

    // No relatively addressed constant (hoist_uniform_steps() leaves those executables alone),
    // and sources that are constants or the temporaries r0-r5 more often, so that chains of
    // uniform steps form.
    void favour_uniform_steps() { favour_uniform_ = true; }

    emu::Executable generate(unsigned step_count) {
        const bool pixel = mode_.rounding != Rounding::Fp32 || chance(random_, 50);
        std::vector<Step> steps;
        for (unsigned i = 0; i < step_count; ++i) steps.push_back(step(pixel, i));
        // Compiled code keeps the temporaries out of the batch, so only outputs are compared:
        // half the executables end by copying r0..r11 into the output slots, which makes every
        // temporary's last value a result (the others keep the outputs they wrote themselves).
        if (chance(random_, 50))
            for (unsigned t = 0; t < 12; ++t) {
                Step copy;
                copy.origin = step_count + t;
                copy.opcode = Opcode::Mov;
                copy.dest.slot = static_cast<uint16_t>(emu::slot::kPosition + t);
                copy.source_count = 1;
                copy.sources[0].kind = OperandKind::Lanes;
                copy.sources[0].index = static_cast<uint16_t>(emu::slot::kTempFirst + t);
                copy.sources[0].swizzle = 0xE4;
                copy.sources[0].channels = 0xF;
                steps.push_back(copy);
            }
        const auto precision = mode_.rounding == Rounding::Fp24 ? emu::Precision::Fp24 : emu::Precision::Fp32;
        const auto executed = static_cast<uint32_t>(steps.size());
        return emu::Executable(isa::ShaderVersion{pixel ? ShaderType::Pixel : ShaderType::Vertex, 2, 0}, precision,
                               constant_count_, std::move(steps), {}, executed, mode_.transcendentals);
    }

private:
    uint8_t nonzero_mask() { return static_cast<uint8_t>(1 + pick(random_, 15)); }

    StepSource source(uint8_t channels) {
        StepSource s;
        s.channels = channels;
        s.swizzle = static_cast<uint8_t>(chance(random_, 30) ? 0xE4 : pick(random_, 256));
        s.negate = chance(random_, 30);
        const unsigned kind = pick(random_, 100);
        if (favour_uniform_) {
            s.kind = kind < 40 ? OperandKind::Constant : kind < 45 ? OperandKind::Zero : OperandKind::Lanes;
            if (s.kind == OperandKind::Constant) s.index = static_cast<uint16_t>(pick(random_, constant_count_));
            if (s.kind == OperandKind::Lanes)
                s.index = static_cast<uint16_t>(kind < 85 ? emu::slot::kTempFirst + pick(random_, 6)
                                                          : pick(random_, emu::slot::kCount));
            return s;
        }
        if (kind < 55) {
            s.kind = OperandKind::Lanes;
            s.index = static_cast<uint16_t>(pick(random_, emu::slot::kCount));
        } else if (kind < 80) {
            s.kind = OperandKind::Constant;
            s.index = static_cast<uint16_t>(pick(random_, constant_count_));
        } else if (kind < 95) {
            s.kind = OperandKind::RelativeConstant;
            s.index = static_cast<uint16_t>(pick(random_, constant_count_ + 8));
            s.address_component = static_cast<uint8_t>(pick(random_, 4));
        } else {
            s.kind = OperandKind::Zero;
        }
        return s;
    }

    // A destination slot the lowering could write: a temp or an output.
    uint16_t dest_slot() {
        if (favour_uniform_ && chance(random_, 70))
            return static_cast<uint16_t>(emu::slot::kTempFirst + pick(random_, 6));
        if (chance(random_, 70)) return static_cast<uint16_t>(emu::slot::kTempFirst + pick(random_, 12));
        return static_cast<uint16_t>(emu::slot::kPosition + pick(random_, emu::slot::kCount - emu::slot::kPosition));
    }

    ResultRounding rounding() {
        switch (mode_.rounding) {
        case Rounding::Fp32: return ResultRounding::None;
        case Rounding::Fp24: return chance(random_, 20) ? ResultRounding::Fp16 : ResultRounding::Fp24;  // _pp
        case Rounding::Fp16: return ResultRounding::Fp16;
        }
        return ResultRounding::None;
    }

    Step step(bool pixel, unsigned index) {
        Step step;
        step.origin = index;
        step.opcode = kOpcodes[pick(random_, std::size(kOpcodes))];
        // a0 is read early and often: a third of the vertex steps that are not mova are mova.
        if (!pixel && chance(random_, 8)) step.opcode = Opcode::Mova;
        step.dest.slot = dest_slot();
        step.dest.mask = nonzero_mask();
        step.dest.saturate = chance(random_, 25);
        step.dest.rounding = rounding();
        // Which channels each source is read for, as lowering computes them.
        std::array<uint8_t, 3> channels{step.dest.mask, step.dest.mask, step.dest.mask};
        unsigned count = 1;
        switch (step.opcode) {
        case Opcode::Mov:
        case Opcode::Abs:
        case Opcode::Frc:
        case Opcode::Sgn: count = 1; break;
        case Opcode::Add:
        case Opcode::Sub:
        case Opcode::Mul:
        case Opcode::Min:
        case Opcode::Max:
        case Opcode::Slt:
        case Opcode::Sge: count = 2; break;
        case Opcode::Mad:
        case Opcode::Cmp:
        case Opcode::Lrp: count = 3; break;
        case Opcode::Dp3:
            count = 2;
            channels = {0x7, 0x7, 0};
            break;
        case Opcode::Dp4:
            count = 2;
            channels = {0xF, 0xF, 0};
            break;
        case Opcode::Dp2Add:
            count = 3;
            channels = {0x3, 0x3, 0x1};
            break;
        case Opcode::Rcp:
        case Opcode::Rsq:
        case Opcode::Exp:
        case Opcode::ExpP:
        case Opcode::Log:
        case Opcode::LogP:
            count = 1;
            channels = {0x1, 0x1, 0x1};
            break;
        case Opcode::Pow:
            count = 2;
            channels = {0x1, 0x1, 0x1};
            break;
        case Opcode::Lit:
        case Opcode::Nrm:
            count = 1;
            channels = {0xF, 0xF, 0xF};
            break;
        case Opcode::Dst:
        case Opcode::Crs:
            count = 2;
            channels = {0xF, 0xF, 0xF};
            break;
        case Opcode::SinCos:
            count = 1;
            channels = {0x1, 0, 0};
            break;
        case Opcode::Mova:
            count = 1;
            step.dest = {};
            step.dest.mask = nonzero_mask();
            step.dest.address = true;
            channels = {step.dest.mask, 0, 0};
            break;
        case Opcode::TexKill:
            count = 1;
            step.dest = {};
            step.dest.mask = 0;
            channels = {nonzero_mask(), 0, 0};
            break;
        case Opcode::Tex:
            count = 1;
            channels = {0xF, 0, 0};
            step.sampler = static_cast<uint8_t>(pick(random_, 16));
            step.control = static_cast<uint8_t>(pick(random_, 3));
            step.dest.slot = static_cast<uint16_t>(emu::slot::kTempFirst + pick(random_, 12));
            break;
        default: break;
        }
        if (step.opcode == Opcode::Crs)
            step.dest.mask = static_cast<uint8_t>((step.dest.mask & 0x7) ? step.dest.mask & 0x7 : 0x1);
        if (step.opcode == Opcode::SinCos)
            step.dest.mask = static_cast<uint8_t>((step.dest.mask & 0x3) ? step.dest.mask & 0x3 : 0x2);
        if (step.opcode == Opcode::Mova) channels[0] = step.dest.mask;
        step.source_count = static_cast<uint8_t>(count);
        for (unsigned k = 0; k < count; ++k) step.sources[k] = source(channels[k]);
        return step;
    }

    Random& random_;
    Mode mode_;
    unsigned constant_count_;
    bool favour_uniform_ = false;
};

// --- batches ---------------------------------------------------------------------------------

inline void randomize(emu::Batch& batch, Random& random, unsigned constant_count) {
    for (auto& reg : batch.registers)
        for (auto& component : reg)
            for (float& value : component) value = special_float(random);
    for (auto& component : batch.address)
        for (int32_t& a : component) {
            const unsigned kind = pick(random, 10);
            a = kind == 0   ? std::numeric_limits<int32_t>::min()
                : kind == 1 ? std::numeric_limits<int32_t>::max()
                : kind == 2 ? -(1 << 30)  // mova of NaN
                            : static_cast<int32_t>(pick(random, constant_count + 16)) - 8;
        }
    batch.killed = static_cast<emu::LaneMask>(chance(random, 50) ? random() & emu::kAllLanes : 0);
    batch.lane_count = chance(random, 70) ? emu::kBatchLanes : 1 + pick(random, emu::kBatchLanes);
}

inline emu::ConstantFile random_constants(Random& random, unsigned count) {
    emu::ConstantFile constants;
    // Sometimes larger than the executable's count: relative reads may reach past it.
    constants.registers.resize(count + (chance(random, 50) ? pick(random, 8) : 0));
    for (auto& reg : constants.registers)
        for (float& value : reg) value = special_float(random);
    return constants;
}

}  // namespace sm2::test::random_executables
