// The interpreter: runs the steps of an Executable over a batch of lanes. Every step fetches
// its sources into small structure-of-arrays scratch registers (swizzle and negate applied,
// constants broadcast), computes the result channels in loops over all kBatchLanes lanes (fixed
// trip count: the compiler vectorizes them), then saturates, rounds to the precision mode and
// stores the masked channels. Reading every source before writing makes `mul r0, r0.yzxw, r0`
// well defined.
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "numerics.h"
#include "sm2/emu/engine.h"

namespace sm2::emu {

namespace {

namespace num = numerics;
using isa::Opcode;

template <typename Real>
class Interpreter {
public:
    using Lanes = typename BasicBatch<Real>::Lanes;
    using Vector = std::array<Lanes, 4>;
    static constexpr unsigned N = kBatchLanes;

    Interpreter(const ConstantFile& constants, BasicBatch<Real>& batch, Sampler* sampler, Transcendentals transcendentals)
        : constants_(constants), batch_(batch), sampler_(sampler),
          fast_(std::is_same_v<Real, float> && transcendentals == Transcendentals::Fast) {}

    void run(std::span<const Step> steps) {
        for (const Step& step : steps) run_step(step);
    }
    void run(std::span<const Step> steps, const StepObserver& observer) {
        for (size_t i = 0; i < steps.size(); ++i) {
            run_step(steps[i]);
            observer(i, steps[i]);
        }
    }

private:
    static bool has(uint8_t mask, unsigned c) { return (mask >> c) & 1u; }

    // The fast transcendentals exist for float storage only; the fp64 reference is exact.
    static Real fast_exp2(Real x) {
        if constexpr (std::is_same_v<Real, float>) return num::fast::exp2(x);
        else return num::exp2(x);
    }
    static Real fast_log2(Real x) {
        if constexpr (std::is_same_v<Real, float>) return num::fast::log2(x);
        else return num::log2(x);
    }
    static Real fast_pow(Real base, Real exponent) {
        if constexpr (std::is_same_v<Real, float>) return num::fast::pow(base, exponent);
        else return num::pow(base, exponent);
    }
    static void fast_sincos(Real x, Real& sine, Real& cosine) {
        if constexpr (std::is_same_v<Real, float>) {
            num::fast::sincos(x, sine, cosine);
        } else {
            sine = std::sin(x);
            cosine = std::cos(x);
        }
    }

    template <typename Pow>
    void lit(Pow power_function) {
        const Vector& a = src_[0];
        for (unsigned l = 0; l < N; ++l) {
            const Real x = a[0][l], y = a[1][l], power = num::lit_power_clamp(a[3][l]);
            const Real specular = power_function(y, power);
            result_[0][l] = Real(1);
            result_[1][l] = x > Real(0) ? x : Real(0);
            result_[2][l] = x > Real(0) && y > Real(0) ? specular : Real(0);
            result_[3][l] = Real(1);
        }
    }

    void fetch(const StepSource& s, Vector& out) const {
        for (unsigned c = 0; c < 4; ++c) {
            if (!has(s.channels, c)) continue;
            const unsigned component = isa::swizzle_component(s.swizzle, static_cast<int>(c));
            Lanes& dst = out[c];
            switch (s.kind) {
            case OperandKind::Lanes: {
                const Lanes& in = batch_.registers[s.index][component];
                if (s.negate)
                    for (unsigned l = 0; l < N; ++l) dst[l] = -in[l];
                else
                    dst = in;
                break;
            }
            case OperandKind::Constant: {
                const Real v = static_cast<Real>(constants_.registers[s.index][component]);
                dst.fill(s.negate ? -v : v);
                break;
            }
            case OperandKind::RelativeConstant: {
                // Out-of-range relative reads return (0,0,0,0) (docs, "Address Register").
                const auto& address = batch_.address[s.address_component];
                const int64_t count = static_cast<int64_t>(constants_.registers.size());
                for (unsigned l = 0; l < N; ++l) {
                    const int64_t index = int64_t{address[l]} + s.index;
                    const Real v = index >= 0 && index < count
                                       ? static_cast<Real>(constants_.registers[static_cast<size_t>(index)][component])
                                       : Real(0);
                    dst[l] = s.negate ? -v : v;
                }
                break;
            }
            case OperandKind::Zero:
                dst.fill(s.negate ? -Real(0) : Real(0));
                break;
            }
        }
    }

    // result[c][l] = f(a[c][l]) for every channel of the mask.
    template <typename F>
    void unary(uint8_t mask, F f) {
        for (unsigned c = 0; c < 4; ++c)
            if (has(mask, c))
                for (unsigned l = 0; l < N; ++l) result_[c][l] = f(src_[0][c][l]);
    }
    template <typename F>
    void binary(uint8_t mask, F f) {
        for (unsigned c = 0; c < 4; ++c)
            if (has(mask, c))
                for (unsigned l = 0; l < N; ++l) result_[c][l] = f(src_[0][c][l], src_[1][c][l]);
    }
    template <typename F>
    void ternary(uint8_t mask, F f) {
        for (unsigned c = 0; c < 4; ++c)
            if (has(mask, c))
                for (unsigned l = 0; l < N; ++l)
                    result_[c][l] = f(src_[0][c][l], src_[1][c][l], src_[2][c][l]);
    }
    // Scalar instructions: one value from channel 0 of the fetched sources, replicated.
    template <typename F>
    void scalar(uint8_t mask, F f) {
        Lanes value;
        for (unsigned l = 0; l < N; ++l) value[l] = f(l);
        for (unsigned c = 0; c < 4; ++c)
            if (has(mask, c)) result_[c] = value;
    }

    void run_step(const Step& step) {
        for (unsigned k = 0; k < step.source_count; ++k) fetch(step.sources[k], src_[k]);
        const uint8_t mask = step.dest.mask;
        const Vector& a = src_[0];
        const Vector& b = src_[1];
        const Vector& c3 = src_[2];
        switch (step.opcode) {
        case Opcode::Mov: unary(mask, [](Real x) { return x; }); break;
        case Opcode::Abs: unary(mask, [](Real x) { return std::fabs(x); }); break;
        case Opcode::Frc: unary(mask, [](Real x) { return num::frc(x); }); break;
        case Opcode::Sgn: unary(mask, [](Real x) { return num::sgn(x); }); break;
        case Opcode::Add: binary(mask, [](Real x, Real y) { return x + y; }); break;
        case Opcode::Sub: binary(mask, [](Real x, Real y) { return x - y; }); break;
        case Opcode::Mul: binary(mask, [](Real x, Real y) { return num::mul(x, y); }); break;
        case Opcode::Min: binary(mask, [](Real x, Real y) { return num::min(x, y); }); break;
        case Opcode::Max: binary(mask, [](Real x, Real y) { return num::max(x, y); }); break;
        case Opcode::Slt: binary(mask, [](Real x, Real y) { return num::slt(x, y); }); break;
        case Opcode::Sge: binary(mask, [](Real x, Real y) { return num::sge(x, y); }); break;
        case Opcode::Mad: ternary(mask, [](Real x, Real y, Real z) { return num::mad(x, y, z); }); break;
        case Opcode::Cmp: ternary(mask, [](Real x, Real y, Real z) { return num::cmp(x, y, z); }); break;
        case Opcode::Lrp:
            // t * (a - b) + b
            ternary(mask, [](Real t, Real x, Real y) { return num::mad(t, x - y, y); });
            break;
        case Opcode::Dp3:
            scalar(mask, [&](unsigned l) {
                return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) + num::mul(a[2][l], b[2][l]);
            });
            break;
        case Opcode::Dp4:
            scalar(mask, [&](unsigned l) {
                return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) +
                       num::mul(a[2][l], b[2][l]) + num::mul(a[3][l], b[3][l]);
            });
            break;
        case Opcode::Dp2Add:
            scalar(mask, [&](unsigned l) {
                return num::mul(a[0][l], b[0][l]) + num::mul(a[1][l], b[1][l]) + c3[0][l];
            });
            break;
        case Opcode::Rcp: scalar(mask, [&](unsigned l) { return num::rcp(a[0][l]); }); break;
        case Opcode::Rsq: scalar(mask, [&](unsigned l) { return num::rsq(a[0][l]); }); break;
        case Opcode::Exp:
        case Opcode::ExpP:
            if (fast_) scalar(mask, [&](unsigned l) { return fast_exp2(a[0][l]); });
            else scalar(mask, [&](unsigned l) { return num::exp2(a[0][l]); });
            break;
        case Opcode::Log:
        case Opcode::LogP:
            if (fast_) scalar(mask, [&](unsigned l) { return fast_log2(a[0][l]); });
            else scalar(mask, [&](unsigned l) { return num::log2(a[0][l]); });
            break;
        case Opcode::Pow:
            if (fast_) scalar(mask, [&](unsigned l) { return fast_pow(a[0][l], b[0][l]); });
            else scalar(mask, [&](unsigned l) { return num::pow(a[0][l], b[0][l]); });
            break;
        case Opcode::Lit:
            if (fast_) lit([](Real y, Real p) { return fast_pow(y, p); });
            else lit([](Real y, Real p) { return num::pow(y, p); });
            break;
        case Opcode::Dst:
            for (unsigned l = 0; l < N; ++l) {
                result_[0][l] = Real(1);
                result_[1][l] = num::mul(a[1][l], b[1][l]);
                result_[2][l] = a[2][l];
                result_[3][l] = b[3][l];
            }
            break;
        case Opcode::Crs:
            for (unsigned l = 0; l < N; ++l) {
                result_[0][l] = num::mul(a[1][l], b[2][l]) - num::mul(a[2][l], b[1][l]);
                result_[1][l] = num::mul(a[2][l], b[0][l]) - num::mul(a[0][l], b[2][l]);
                result_[2][l] = num::mul(a[0][l], b[1][l]) - num::mul(a[1][l], b[0][l]);
            }
            break;
        case Opcode::Nrm:
            for (unsigned l = 0; l < N; ++l) {
                const Real f = num::nrm_factor(num::mul(a[0][l], a[0][l]) + num::mul(a[1][l], a[1][l]) +
                                               num::mul(a[2][l], a[2][l]));
                for (unsigned c = 0; c < 4; ++c) result_[c][l] = num::mul(a[c][l], f);
            }
            break;
        case Opcode::SinCos:
            if (fast_) {
                for (unsigned l = 0; l < N; ++l) fast_sincos(a[0][l], result_[1][l], result_[0][l]);
            } else {
                for (unsigned l = 0; l < N; ++l) {
                    result_[0][l] = std::cos(a[0][l]);
                    result_[1][l] = std::sin(a[0][l]);
                }
            }
            break;
        case Opcode::Mova:
            for (unsigned c = 0; c < 4; ++c)
                if (has(mask, c))
                    for (unsigned l = 0; l < N; ++l) batch_.address[c][l] = num::mova_round(a[c][l]);
            return;
        case Opcode::TexKill: {
            const uint8_t tested = step.sources[0].channels;
            LaneMask killed = 0;
            for (unsigned l = 0; l < N; ++l) {
                const Real inf = num::kInfinity<Real>;  // untested channels never kill
                if (num::kills(has(tested, 0) ? a[0][l] : inf, has(tested, 1) ? a[1][l] : inf,
                               has(tested, 2) ? a[2][l] : inf, has(tested, 3) ? a[3][l] : inf))
                    killed |= LaneMask{1} << l;
            }
            batch_.killed |= killed & kAllLanes;
            return;
        }
        case Opcode::Tex: sample(step); break;
        default: return;  // lowering emits nothing else
        }
        store(step.dest);
    }

    void sample(const Step& step) {
        std::array<FloatLanes, 4> coordinates;
        std::array<FloatLanes, 4> texels;
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < N; ++l) coordinates[c][l] = static_cast<float>(src_[0][c][l]);
        if (sampler_ == nullptr) {
            // No sampler: what D3D9 samples from an unbound stage, (0, 0, 0, 1).
            for (unsigned c = 0; c < 4; ++c) texels[c].fill(c == 3 ? 1.0f : 0.0f);
        } else {
            TextureRequest request;
            request.sampler = step.sampler;
            request.variant = static_cast<TextureVariant>(step.control);
            request.coordinates = &coordinates;
            request.quad_count = (batch_.lane_count + kQuadLanes - 1) / kQuadLanes;
            request.helper_lanes = batch_.killed;
            sampler_->sample(request, texels);
        }
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < N; ++l) result_[c][l] = static_cast<Real>(texels[c][l]);
    }

    void store(const StepDest& dest) {
        for (unsigned c = 0; c < 4; ++c) {
            if (!has(dest.mask, c)) continue;
            Lanes& out = batch_.registers[dest.slot][c];
            Lanes& r = result_[c];
            if (dest.saturate)
                for (unsigned l = 0; l < N; ++l) r[l] = num::saturate(r[l]);
            // One loop per rounding, so each stays a plain vectorizable loop.
            if (dest.rounding == ResultRounding::Fp24)
                for (unsigned l = 0; l < N; ++l) r[l] = num::round_result(r[l], ResultRounding::Fp24);
            else if (dest.rounding == ResultRounding::Fp16)
                for (unsigned l = 0; l < N; ++l) r[l] = num::round_result(r[l], ResultRounding::Fp16);
            out = r;
        }
    }

    const ConstantFile& constants_;
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
