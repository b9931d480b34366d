// Backward liveness over (register slot, component) pairs plus the four components of a0.
#include "dead_code.h"

#include <bitset>

#include "sm2/emu/batch.h"
#include "sm2/isa/program.h"

namespace sm2::emu {

namespace {

constexpr unsigned kAddressBit = slot::kCount * 4;  // a0.x .. a0.w follow the slots
using Live = std::bitset<slot::kCount * 4 + 4>;

unsigned dest_bit(const StepDest& dest, unsigned component) {
    return dest.address ? kAddressBit + component : dest.slot * 4u + component;
}

}  // namespace

bool is_component_wise(isa::Opcode opcode) {
    const auto* info = isa::find_opcode(opcode);
    return opcode == isa::Opcode::Mova ||
           (info != nullptr && info->category == isa::Category::ComponentWise);
}

void remove_dead_steps(std::vector<Step>& steps, uint32_t outputs_read) {
    Live live;
    for (unsigned s = slot::kPosition; s < slot::kCount; ++s)
        if ((outputs_read >> (s - slot::kPosition)) & 1u)
            for (unsigned c = 0; c < 4; ++c) live.set(s * 4 + c);

    std::vector<bool> keep(steps.size(), false);
    for (size_t i = steps.size(); i-- > 0;) {
        Step& step = steps[i];
        const bool side_effect = step.opcode == isa::Opcode::TexKill;
        uint8_t live_mask = 0;
        if (!side_effect)
            for (unsigned c = 0; c < 4; ++c)
                if (((step.dest.mask >> c) & 1u) && live.test(dest_bit(step.dest, c)))
                    live_mask = static_cast<uint8_t>(live_mask | (1u << c));
        if (!side_effect && live_mask == 0) continue;
        keep[i] = true;
        if (!side_effect) {
            step.dest.mask = live_mask;
            if (is_component_wise(step.opcode))
                for (auto& source : step.sources) source.channels = live_mask;
            for (unsigned c = 0; c < 4; ++c)
                if ((live_mask >> c) & 1u) live.reset(dest_bit(step.dest, c));
        }
        for (unsigned k = 0; k < step.source_count; ++k) {
            const StepSource& source = step.sources[k];
            if (source.kind == OperandKind::RelativeConstant)
                live.set(kAddressBit + source.address_component);
            if (source.kind != OperandKind::Lanes) continue;
            for (unsigned c = 0; c < 4; ++c)
                if ((source.channels >> c) & 1u)
                    live.set(source.index * 4u + isa::swizzle_component(source.swizzle, static_cast<int>(c)));
        }
    }
    size_t out = 0;
    for (size_t i = 0; i < steps.size(); ++i)
        if (keep[i]) steps[out++] = steps[i];
    steps.resize(out);
}

}  // namespace sm2::emu
