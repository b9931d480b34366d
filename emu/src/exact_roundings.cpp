// Roundings that cannot change a value (exact_roundings.h).
#include "exact_roundings.h"

#include <algorithm>
#include <bit>

#include "numerics.h"
#include "sm2/isa/program.h"

namespace sm2::emu {

namespace {

// What a value is known to be representable in, ordered: fp16's values are fp24 values too
// (10 fraction bits, exponents 2^-24 to 2^15, all within fp24's 16 bits and 2^-62 to 2^63).
enum class Known : uint8_t { Nothing, Fp24, Fp16 };

Known known_after(ResultRounding rounding) {
    switch (rounding) {
    case ResultRounding::Fp24: return Known::Fp24;
    case ResultRounding::Fp16: return Known::Fp16;
    case ResultRounding::None: break;
    }
    return Known::Nothing;
}

bool survives(Known known, ResultRounding rounding) { return known >= known_after(rounding); }

bool same_bits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

Known known_value(float v) {
    if (same_bits(numerics::round_to_fp16(v), v)) return Known::Fp16;
    if (same_bits(numerics::round_to_fp24(v), v)) return Known::Fp24;
    return Known::Nothing;
}

// The sources whose values a result channel takes as they are (sign aside), in
// step_kernels.h's compute(): cmp's first source is only compared.
std::span<const StepSource> selected_sources(const Step& step) {
    const std::span<const StepSource> all(step.sources.data(), step.source_count);
    switch (step.opcode) {
    case isa::Opcode::Mov:
    case isa::Opcode::Abs:
    case isa::Opcode::Min:
    case isa::Opcode::Max: return all;
    case isa::Opcode::Cmp: return all.subspan(1);
    default: return {};
    }
}

}  // namespace

void drop_exact_roundings(std::vector<Step>& steps, std::span<const std::pair<unsigned, std::array<float, 4>>> defs) {
    std::vector<std::array<Known, 4>> constants;
    for (const auto& [index, value] : defs) {
        if (index >= constants.size()) constants.resize(index + 1, {});
        for (unsigned c = 0; c < 4; ++c) constants[index][c] = known_value(value[c]);
    }
    std::array<std::array<Known, 4>, kSlotCount> slots{};
    auto known = [&](const StepSource& source, unsigned component) {
        switch (source.kind) {
        case OperandKind::Lanes: return slots[source.index][component];
        case OperandKind::Constant:
            return source.index < constants.size() ? constants[source.index][component] : Known::Nothing;
        case OperandKind::Zero: return Known::Fp16;
        case OperandKind::RelativeConstant: break;
        }
        return Known::Nothing;
    };
    for (Step& step : steps) {
        if (step.dest.address || step.dest.mask == 0) continue;  // mova, texkill: no slot written
        const std::span<const StepSource> selected = selected_sources(step);
        const Known rounded = known_after(step.dest.rounding);
        // Per channel, what the result is known to be: what its rounding makes it, or what the
        // source value it takes is (saturated too: 0, 1 or the value).
        std::array<Known, 4> result{};
        bool exact = !selected.empty() && step.dest.rounding != ResultRounding::None;
        for (unsigned c = 0; c < 4; ++c) {
            if (!(step.dest.mask >> c & 1u)) continue;
            Known taken = selected.empty() ? Known::Nothing : Known::Fp16;
            for (const StepSource& source : selected)
                if (source.channels >> c & 1u)
                    taken = std::min(taken, known(source, isa::swizzle_component(source.swizzle, static_cast<int>(c))));
            exact = exact && survives(taken, step.dest.rounding);
            result[c] = std::max(taken, rounded);
        }
        if (exact) step.dest.rounding = ResultRounding::None;
        for (unsigned c = 0; c < 4; ++c)
            if (step.dest.mask >> c & 1u) slots[step.dest.slot][c] = result[c];
    }
}

}  // namespace sm2::emu
