// The interpreter: runs the steps of an Executable over a batch of lanes. Every step fetches
// its sources into small structure-of-arrays scratch registers (swizzle and negate applied,
// constants broadcast), computes the result channels in loops over all kBatchLanes lanes (fixed
// trip count: the compiler vectorizes them), then saturates, rounds to the precision mode and
// stores the masked channels. Reading every source before writing makes `mul r0, r0.yzxw, r0`
// well defined. The lane loops themselves are the kernels of step_kernels.h, which the JIT
// (jit/) compiles from the same source.
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "numerics.h"
#include "sm2/emu/engine.h"
#include "step_kernels.h"
#include "uniform_steps.h"

namespace sm2::emu {

namespace {

using isa::Opcode;

// The exact exp, log and pow of floats (and lit's power): numerics.h's series in double of
// fused multiply-adds, cloned for x86-64-v4 and v3, where std::fma is one instruction and the
// lane loops vectorize. The baseline clone, for CPUs without FMA, calls the C library's fma for
// each (the same bits: a fused multiply-add has one result): 4x the unfused series' time.
// (GCC: flatten, so that every kernel is inlined into each clone and compiled for its
// instruction set. Clang refuses flatten beside target_clones, and its clones call pow's and
// lit's kernels as compiled for the baseline: the same bits, the C library's fma.)
#if defined(__clang__)
#define SM2_CLONES_INLINE_ALL
#else
#define SM2_CLONES_INLINE_ALL flatten,
#endif
__attribute__((SM2_CLONES_INLINE_ALL target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void exact_transcendental(Opcode op, kernels::Vector<float>& result, const kernels::Vector<float>& a,
                          const kernels::Vector<float>& b, const kernels::Vector<float>& c, unsigned mask) {
    switch (op) {
    case Opcode::Exp: kernels::compute<float, Opcode::Exp, false>(result, a, b, c, mask); return;
    case Opcode::ExpP: kernels::compute<float, Opcode::ExpP, false>(result, a, b, c, mask); return;
    case Opcode::Log: kernels::compute<float, Opcode::Log, false>(result, a, b, c, mask); return;
    case Opcode::LogP: kernels::compute<float, Opcode::LogP, false>(result, a, b, c, mask); return;
    case Opcode::Pow: kernels::compute<float, Opcode::Pow, false>(result, a, b, c, mask); return;
    case Opcode::Lit: kernels::compute<float, Opcode::Lit, false>(result, a, b, c, mask); return;
    default: return;
    }
}

template <typename Real>
class Interpreter {
public:
    using Vector = kernels::Vector<Real>;

    Interpreter(const ConstantFile& constants, BasicBatch<Real>& batch, Sampler* sampler,
                Transcendentals transcendentals)
        : constants_(constants.registers.data()),
          constant_count_(static_cast<int64_t>(constants.registers.size())), batch_(batch), sampler_(sampler),
          fast_(std::is_same_v<Real, float> && transcendentals == Transcendentals::Fast) {}

    void run(std::span<const Step> steps) {
        for (const Step& step : steps) {
            run_step(step);
            if (step.opcode == Opcode::TexKill && kernels::stop_after_texkill(batch_)) return;
        }
    }
    void run(std::span<const Step> steps, const StepObserver& observer) {
        for (size_t i = 0; i < steps.size(); ++i) {
            run_step(steps[i]);
            observer(i, steps[i]);
            if (steps[i].opcode == Opcode::TexKill && kernels::stop_after_texkill(batch_)) return;
        }
    }

private:
    template <Opcode op>
    void compute(unsigned mask) {
        if constexpr (kernels::transcendental(op)) {
            if (fast_) {
                kernels::compute<Real, op, true>(result_, src_[0], src_[1], src_[2], mask);
                return;
            }
            if constexpr (std::is_same_v<Real, float> && op != Opcode::SinCos) {
                exact_transcendental(op, result_, src_[0], src_[1], src_[2], mask);
                return;
            }
        }
        kernels::compute<Real, op, false>(result_, src_[0], src_[1], src_[2], mask);
    }

    void run_step(const Step& step) {
        for (unsigned k = 0; k < step.source_count; ++k)
            kernels::fetch(src_[k], step.sources[k], batch_, constants_, constant_count_);
        const unsigned mask = step.dest.mask;
        switch (step.opcode) {
#define SM2_STEP_CASE(name) \
        case Opcode::name: compute<Opcode::name>(mask); break;
        SM2_ARITHMETIC_STEPS(SM2_STEP_CASE)
#undef SM2_STEP_CASE
        case Opcode::Mova: kernels::mova(batch_, src_[0], mask); return;
        case Opcode::TexKill: kernels::texkill(batch_, src_[0], step.sources[0].channels); return;
        case Opcode::Tex:
            kernels::texture(result_, src_[0], batch_,
                             [&](const kernels::Texels& coordinates, kernels::Texels& texels, unsigned lane_count,
                                 LaneMask killed) {
                                 kernels::sample_texels(sampler_, step.sampler, step.control, lane_count, killed,
                                                        coordinates, texels);
                             });
            break;
        default: return;  // lowering emits nothing else
        }
        kernels::store(batch_, step.dest.slot, result_, mask, step.dest.saturate, step.dest.rounding);
    }

    const kernels::ConstantRegister* constants_;
    int64_t constant_count_;
    BasicBatch<Real>& batch_;
    Sampler* sampler_;
    bool fast_;
    alignas(64) std::array<Vector, 3> src_{};
    alignas(64) Vector result_{};
};

}  // namespace

namespace {

void check_constants(const Executable& executable, const ConstantFile& constants) {
    if (constants.registers.size() < executable.constant_count())
        throw std::invalid_argument("the constant file has " + std::to_string(constants.registers.size()) +
                                    " registers, the executable reads up to " +
                                    std::to_string(executable.constant_count()) +
                                    " (use Executable::bind_constants)");
}

}  // namespace

void execute_steps(std::span<const Step> steps, const ConstantFile& constants, Batch& batch,
                   Transcendentals transcendentals) {
    Interpreter<float>(constants, batch, nullptr, transcendentals).run(steps);
}

void execute(const Executable& executable, const ConstantFile& constants, Batch& batch, Sampler* sampler) {
    if (executable.precision() == Precision::Fp64)
        throw std::invalid_argument("an fp64 executable runs on a ReferenceBatch");
    check_constants(executable, constants);
    Interpreter<float>(constants, batch, sampler, executable.transcendentals()).run(executable.steps());
}

void execute(const Executable& executable, const ConstantFile& constants, ReferenceBatch& batch,
             Sampler* sampler) {
    check_constants(executable, constants);
    Interpreter<double>(constants, batch, sampler, executable.transcendentals()).run(executable.steps());
}

void execute(const Executable& executable, const ConstantFile& constants, Batch& batch, Sampler* sampler,
             const StepObserver& observer) {
    if (executable.precision() == Precision::Fp64)
        throw std::invalid_argument("an fp64 executable runs on a ReferenceBatch");
    check_constants(executable, constants);
    Interpreter<float>(constants, batch, sampler, executable.transcendentals()).run(executable.steps(), observer);
}

void execute(const Executable& executable, const ConstantFile& constants, ReferenceBatch& batch,
             Sampler* sampler, const StepObserver& observer) {
    check_constants(executable, constants);
    Interpreter<double>(constants, batch, sampler, executable.transcendentals()).run(executable.steps(), observer);
}

}  // namespace sm2::emu
