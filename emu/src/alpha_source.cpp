#include "sm2/emu/alpha_source.h"

#include <algorithm>
#include <span>

#include "sm2/emu/batch.h"
#include "sm2/isa/program.h"

namespace sm2::emu {
namespace {

using isa::Opcode;

// Follows the value of `component` of `slot`, as the steps before `before` leave it, back to the
// texld that made it (its index in `texld`). `budget` bounds the search: a chain of muls whose
// two sources are registers would branch at every step.
bool from_texture_alpha(std::span<const Step> steps, unsigned slot, unsigned component, size_t before,
                        size_t& texld, unsigned& budget) {
    if (budget == 0) return false;
    --budget;
    for (size_t i = before; i-- > 0;) {
        const Step& step = steps[i];
        if (step.opcode == Opcode::TexKill || step.dest.address) continue;  // no lane register written
        if (step.dest.slot != slot || !(step.dest.mask >> component & 1u)) continue;
        // Step i wrote the value.
        const auto source_of = [&](unsigned k, unsigned& source_slot, unsigned& source_component) {
            const StepSource& s = step.sources[k];
            if (s.kind != OperandKind::Lanes) return false;
            source_slot = s.index;
            source_component = isa::swizzle_component(s.swizzle, static_cast<int>(component));
            return true;
        };
        unsigned source_slot = 0, source_component = 0;
        switch (step.opcode) {
        case Opcode::Tex:
            // Result channel c is the texel's channel c.
            if (component != 3) return false;
            texld = i;
            return true;
        case Opcode::Mov:
            return source_of(0, source_slot, source_component) &&
                   from_texture_alpha(steps, source_slot, source_component, i, texld, budget);
        case Opcode::Mul:
            for (unsigned k = 0; k < 2; ++k)
                if (source_of(k, source_slot, source_component) &&
                    from_texture_alpha(steps, source_slot, source_component, i, texld, budget))
                    return true;
            return false;
        default: return false;
        }
    }
    return false;  // never written: an input register
}

}  // namespace

std::optional<size_t> alpha_source_texld(const Executable& pixel_shader) {
    const std::span<const Step> steps = pixel_shader.steps();
    size_t texld = 0;
    unsigned budget = 256;
    if (!from_texture_alpha(steps, slot::kRenderTargetFirst, 3, steps.size(), texld, budget)) return std::nullopt;
    const unsigned sampler = steps[texld].sampler;
    const auto reads = std::count_if(steps.begin(), steps.end(), [&](const Step& step) {
        return step.opcode == Opcode::Tex && step.sampler == sampler;
    });
    if (reads != 1) return std::nullopt;
    return texld;
}

std::optional<unsigned> alpha_source_sampler(const Executable& pixel_shader) {
    const std::optional<size_t> texld = alpha_source_texld(pixel_shader);
    if (!texld) return std::nullopt;
    return pixel_shader.steps()[*texld].sampler;
}

}  // namespace sm2::emu
