// Uniform steps: the arithmetic whose every source is the same on all lanes, done once per draw.
//
// Shaders often compute from constants alone: a light direction normalized in the pixel shader
// (bench_1024's `add r5.xyz, c0, c1; nrm r6.xyz, r5`), a colour scaled by a factor. Each batch
// would compute the same value on every lane. Such a step moves to the executable's prelude,
// which bind_constants() runs once with the interpreter; a step that reads one of its
// temporaries reads a derived constant instead (the temporary as the prelude left it at that
// point). Both engines fetch a constant and a temporary the same way (swizzle, negate, no
// rounding on the way in), and every arithmetic kernel is a function of its sources alone, so
// the bits are those of the per-lane computation.
#include "uniform_steps.h"

#include <map>
#include <memory>
#include <utility>

#include "dead_code.h"
#include "sm2/emu/engine.h"
#include "step_kernels.h"

namespace sm2::emu {

namespace {

// The steps whose result is a function of their sources alone (no lane, texture, a0 or kill).
bool arithmetic(isa::Opcode opcode) {
    switch (opcode) {
#define SM2_ARITHMETIC_CASE(name) case isa::Opcode::name:
        SM2_ARITHMETIC_STEPS(SM2_ARITHMETIC_CASE)
#undef SM2_ARITHMETIC_CASE
        return true;
    default: return false;
    }
}

// The components of its register that source k of `step` reads (bit c = component c) for the
// result channels the step writes: lowering marks the sources of nrm, crs, lit and dst read for
// all four channels, though their kernels take fewer components (nrm's w only for a w result).
uint8_t components_read(const Step& step, unsigned k) {
    const StepSource& source = step.sources[k];
    uint8_t channels = source.channels;
    switch (step.opcode) {
    case isa::Opcode::Nrm: channels &= static_cast<uint8_t>(0x7 | (step.dest.mask & 0x8)); break;
    case isa::Opcode::Crs: channels &= 0x7; break;
    case isa::Opcode::Lit: channels &= 0xB; break;                       // x, y, w
    case isa::Opcode::Dst: channels &= k == 0 ? 0x6 : 0xA; break;       // a.yz, b.yw
    default: break;
    }
    uint8_t read = 0;
    for (unsigned c = 0; c < 4; ++c)
        if ((channels >> c) & 1u)
            read = static_cast<uint8_t>(read | 1u << isa::swizzle_component(source.swizzle, static_cast<int>(c)));
    return read;
}

}  // namespace

Executable hoist_uniform_steps(const Executable& executable, uint32_t outputs_read) {
    if (executable.precision() == Precision::Fp64 || !executable.prelude().steps.empty()) return executable;
    std::vector<Step> steps(executable.steps().begin(), executable.steps().end());
    for (const Step& step : steps)
        for (unsigned k = 0; k < step.source_count; ++k)
            if (step.sources[k].kind == OperandKind::RelativeConstant) return executable;

    UniformPrelude prelude;
    // Per temporary, the components whose value a uniform step wrote (and nothing since).
    std::array<uint8_t, slot::kTempCount> uniform{};
    const auto uniform_source = [&](const Step& step, unsigned k) {
        const StepSource& source = step.sources[k];
        switch (source.kind) {
        case OperandKind::Constant:
        case OperandKind::Zero: return true;
        case OperandKind::Lanes:
            return is_temp_slot(source.index) && (components_read(step, k) & ~uniform[source.index - slot::kTempFirst]) == 0;
        case OperandKind::RelativeConstant: return false;
        }
        return false;
    };
    std::map<std::pair<uint16_t, uint32_t>, uint16_t> derived;  // (slot, after) -> constant register
    const unsigned first_derived = executable.application_constant_count();
    for (Step& step : steps) {
        const bool writes_temp = step.opcode != isa::Opcode::TexKill && !step.dest.address && is_temp_slot(step.dest.slot);
        bool sources_uniform = true;
        for (unsigned k = 0; k < step.source_count; ++k) sources_uniform = sources_uniform && uniform_source(step, k);
        if (writes_temp && sources_uniform && arithmetic(step.opcode)) {
            prelude.steps.push_back(step);
            uniform[step.dest.slot - slot::kTempFirst] |= step.dest.mask;
            continue;
        }
        for (unsigned k = 0; k < step.source_count; ++k) {
            StepSource& source = step.sources[k];
            if (source.kind != OperandKind::Lanes || !is_temp_slot(source.index) || components_read(step, k) == 0 ||
                !uniform_source(step, k))
                continue;
            const auto key = std::make_pair(source.index, static_cast<uint32_t>(prelude.steps.size()));
            auto [at, added] = derived.emplace(key, static_cast<uint16_t>(first_derived + prelude.snapshots.size()));
            if (added) prelude.snapshots.push_back({key.first, key.second});
            source.kind = OperandKind::Constant;
            source.index = at->second;
        }
        if (writes_temp) uniform[step.dest.slot - slot::kTempFirst] &= static_cast<uint8_t>(~step.dest.mask);
    }
    if (prelude.snapshots.empty()) return executable;
    // The prelude ends with its last snapshot; the uniform steps left in `steps` are those a
    // step reads together with a lane value (a register half uniform): dead-code removal keeps
    // exactly those.
    prelude.steps.resize(prelude.snapshots.back().after);
    remove_dead_steps(steps, outputs_read);
    return Executable(executable.version(), executable.precision(), first_derived, std::move(steps), executable.defs(),
                      executable.executed_instructions(), executable.transcendentals(), std::move(prelude));
}

void bind_derived_constants(const UniformPrelude& prelude, Transcendentals transcendentals, ConstantFile& file) {
    if (prelude.snapshots.empty()) return;
    // (A batch is 19 KB: not on the stack of whatever thread binds.)
    const auto batch = std::make_unique<Batch>();
    uint32_t done = 0;
    for (const UniformSnapshot& snapshot : prelude.snapshots) {
        // (The prelude reads the application's registers only, which the appends leave.)
        execute_steps(std::span<const Step>(prelude.steps).subspan(done, snapshot.after - done), file, *batch,
                      transcendentals);
        done = snapshot.after;
        const Batch::Register& value = batch->registers[snapshot.slot];
        file.registers.push_back({value[0][0], value[1][0], value[2][0], value[3][0]});
    }
}

}  // namespace sm2::emu
