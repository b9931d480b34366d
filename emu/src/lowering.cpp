// Lowering: a Shader plus the static flow constants of one draw -> a straight list of steps.
// `if b#` blocks are taken or dropped, `rep`/`loop` bodies are repeated (aL takes its value for
// each copy, so c[aL + n] becomes a fixed constant), `call`/`callnz` bodies are inlined, matrix
// macros become dot products, steps no output needs are removed (dead_code.cpp), and so are
// roundings that cannot change a value (exact_roundings.cpp).
#include <string>

#include "dead_code.h"
#include "exact_roundings.h"
#include "numerics.h"
#include "sm2/emu/engine.h"

namespace sm2::emu {

using isa::Opcode;
using isa::RegisterType;

namespace {

// Why a loop/rep integer constant is outside its documented range ("" when it is fine). rep
// reads only the count.
std::string loop_constant_error(const Int4& c, bool is_loop) {
    if (c[0] < 0 || c[0] > 255) return "the iteration count (x) must be in 0..255";
    if (!is_loop) return {};
    if (c[1] < 0 || c[1] > 255) return "the start value of aL (y) must be in 0..255";
    if (c[2] < -128 || c[2] > 127) return "the step of aL (z) must be in -128..127";
    if (c[3] != 0) return "the unused component (w) must be 0";
    return {};
}


// vs_2_0 allows one level of calls; vs_2_x up to 4. Deeper (or recursive) calls are refused
// rather than followed forever.
constexpr int kMaxCallDepth = 4;

unsigned documented_constant_count(isa::ShaderVersion version) {
    if (const auto* file = isa::find_register_file(version, RegisterType::Const, 0)) return file->count;
    return 256;
}

class Lowerer {
public:
    Lowerer(const Shader& shader, const StaticFlowConstants& flow, const LoweringOptions& options)
        : shader_(shader), code_(shader.program().instructions), flow_(flow), options_(options),
          pixel_(shader.version().is_pixel()),
          constant_count_(options.constant_count ? options.constant_count
                                                 : documented_constant_count(shader.version())) {}

    LowerResult run() {
        const auto flow = walk(0, shader_.main_end(), std::nullopt, 0);
        if (!flow) return {std::nullopt, error_};
        if (!options_.keep_dead_code) remove_dead_steps(steps_, options_.outputs_read);
        std::vector<std::pair<unsigned, std::array<float, 4>>> defs;
        for (const auto& [index, value] : shader_.definitions().floats) defs.emplace_back(index, value);
        drop_exact_roundings(steps_, defs);
        const Precision precision = options_.precision.precision;
        const Transcendentals transcendentals =
            precision == Precision::Fp64 ? Transcendentals::Exact : options_.precision.transcendentals;
        Executable executable(shader_.version(), precision, constant_count_, std::move(steps_), std::move(defs),
                              executed_, transcendentals);
        if (options_.hoist_uniform_steps && !options_.keep_dead_code)
            return {hoist_uniform_steps(executable, options_.outputs_read), {}};
        return {std::move(executable), {}};
    }

private:
    enum class Flow { Continue, Returned };
    using AddressValue = std::optional<int64_t>;  // aL inside a loop body (64-bit: no overflow)

    bool fail(size_t at, const std::string& what) {
        const auto* info = code_[at].info();
        error_ = "instruction " + std::to_string(at) + " (" +
                 std::string(info ? info->mnemonic : "?") + "): " + what;
        return false;
    }

    // Counts one executed instruction against the limit.
    bool count(size_t at) {
        if (++executed_ <= options_.max_executed_instructions) return true;
        return fail(at, "executed-instruction limit of " +
                            std::to_string(options_.max_executed_instructions) +
                            " exceeded (loops and calls unrolled for these b#/i# values)");
    }

    bool condition(const isa::SourceParameter& b) const {
        const bool value = flow_.booleans[b.index];
        return b.modifier == isa::SourceModifier::Not ? !value : value;
    }

    std::optional<Flow> walk(size_t begin, size_t end, AddressValue loop_counter, int call_depth) {
        for (size_t i = begin; i < end; ++i) {
            const isa::Instruction& ins = code_[i];
            switch (ins.opcode) {
            case Opcode::Comment: case Opcode::Dcl: case Opcode::Def: case Opcode::DefI:
            case Opcode::DefB:
                continue;
            case Opcode::Nop:
                if (!count(i)) return std::nullopt;
                continue;
            case Opcode::If: {
                if (!count(i)) return std::nullopt;
                const size_t middle = shader_.partner(i);  // else or endif
                const bool has_else = code_[middle].opcode == Opcode::Else;
                const size_t endif = has_else ? shader_.partner(middle) : middle;
                std::optional<Flow> taken = Flow::Continue;
                if (condition(ins.sources[0])) {
                    taken = walk(i + 1, middle, loop_counter, call_depth);
                } else if (has_else) {
                    if (!count(middle)) return std::nullopt;
                    taken = walk(middle + 1, endif, loop_counter, call_depth);
                }
                if (!taken || *taken == Flow::Returned) return taken;
                if (!count(endif)) return std::nullopt;
                i = endif;
                continue;
            }
            case Opcode::Rep:
            case Opcode::Loop: {
                if (!count(i)) return std::nullopt;
                const size_t end_block = shader_.partner(i);
                const bool is_loop = ins.opcode == Opcode::Loop;
                const unsigned int_register = ins.sources[is_loop ? 1 : 0].index;
                const Int4& counts = flow_.integers[int_register];
                // Documented ranges of the integer constant (instructions.md §12.1; validator rule
                // 20, which needs the draw's values): count and start 0..255, step -128..127, w 0.
                if (const std::string bad = loop_constant_error(counts, is_loop); !bad.empty()) {
                    fail(i, "i" + std::to_string(int_register) + " = (" + std::to_string(counts[0]) + ", " +
                                std::to_string(counts[1]) + ", " + std::to_string(counts[2]) + ", " +
                                std::to_string(counts[3]) + "): " + bad);
                    return std::nullopt;
                }
                // i#.x iterations (0 skips the body); loop: aL starts at i#.y, steps by i#.z.
                const int32_t iterations = counts[0] > 0 ? counts[0] : 0;
                int64_t counter = counts[1];
                for (int32_t k = 0; k < iterations; ++k) {
                    const auto inner = walk(i + 1, end_block, is_loop ? AddressValue(counter) : loop_counter,
                                            call_depth);
                    if (!inner || *inner == Flow::Returned) return inner;
                    if (!count(end_block)) return std::nullopt;
                    counter += counts[2];
                }
                i = end_block;
                continue;
            }
            case Opcode::Call:
            case Opcode::CallNz: {
                if (!count(i)) return std::nullopt;
                if (ins.sources.size() < (ins.opcode == Opcode::CallNz ? 2u : 1u)) {
                    fail(i, "missing operand");
                    return std::nullopt;
                }
                if (ins.opcode == Opcode::CallNz && !condition(ins.sources[1])) continue;
                const auto label = shader_.label_position(ins.sources[0].index);
                if (!label) {
                    fail(i, "calls l" + std::to_string(ins.sources[0].index) + ", which is not defined");
                    return std::nullopt;
                }
                if (call_depth >= kMaxCallDepth) {
                    fail(i, "calls nest deeper than " + std::to_string(kMaxCallDepth));
                    return std::nullopt;
                }
                size_t routine_end = *label + 1;
                while (routine_end < code_.size() && code_[routine_end].opcode != Opcode::Label) ++routine_end;
                if (!walk(*label + 1, routine_end, loop_counter, call_depth + 1)) return std::nullopt;
                continue;
            }
            case Opcode::Ret:
                if (!count(i)) return std::nullopt;
                return Flow::Returned;
            case Opcode::Else: case Opcode::EndIf: case Opcode::EndRep: case Opcode::EndLoop:
            case Opcode::Label:
                fail(i, "reached outside its block");
                return std::nullopt;
            default:
                if (!count(i) || !emit(i, loop_counter)) return std::nullopt;
                continue;
            }
        }
        return Flow::Continue;
    }

    std::optional<StepSource> source(size_t at, const isa::SourceParameter& p, AddressValue loop_counter,
                                     uint8_t channels) {
        StepSource s;
        s.swizzle = p.swizzle;
        s.channels = channels;
        if (p.modifier == isa::SourceModifier::Negate) {
            s.negate = true;
        } else if (p.modifier != isa::SourceModifier::None) {
            fail(at, "source modifier not available in vs_2_0/ps_2_0");
            return std::nullopt;
        }
        if (p.type == RegisterType::Const) {
            int64_t index = p.index;
            if (p.relative && p.relative->type == RegisterType::Loop) {
                if (!loop_counter) {
                    fail(at, "c[aL + n] used outside a loop");
                    return std::nullopt;
                }
                index += *loop_counter;
            } else if (p.relative) {
                s.kind = OperandKind::RelativeConstant;
                s.index = p.index;
                s.address_component = isa::swizzle_component(p.relative->swizzle, 0);
                return s;
            }
            const bool inside = index >= 0 && index < static_cast<int64_t>(constant_count_);
            s.kind = inside ? OperandKind::Constant : OperandKind::Zero;
            s.index = static_cast<uint16_t>(inside ? index : 0);
            return s;
        }
        if (p.relative) {
            fail(at, "relative addressing is only available on constants");
            return std::nullopt;
        }
        const auto lane_slot = register_slot(shader_.version().type, p.type, p.index);
        if (!lane_slot) {
            fail(at, "source register cannot be read here");
            return std::nullopt;
        }
        s.kind = OperandKind::Lanes;
        s.index = static_cast<uint16_t>(*lane_slot);
        return s;
    }

    bool emit(size_t at, AddressValue loop_counter) {
        const isa::Instruction& ins = code_[at];
        const isa::OpcodeInfo* info = ins.info();
        if (!info || !info->allowed_in(shader_.version()))
            return fail(at, "not available in " + shader_.version().name());
        Step step;
        step.opcode = ins.opcode;
        step.control = ins.control;
        step.origin = static_cast<uint32_t>(at);

        if (ins.opcode == Opcode::TexKill) {
            // The tested register sits in the destination token; its mask names the
            // components tested (.xyzw normally; Wine writes .xyz for "texkill t0.xyz").
            if (!ins.dest) return fail(at, "missing operand");
            isa::SourceParameter tested;
            tested.type = ins.dest->type;
            tested.index = ins.dest->index;
            auto s = source(at, tested, loop_counter, ins.dest->write_mask);
            if (!s) return false;
            step.sources[0] = *s;
            step.source_count = 1;
            step.dest.mask = 0;
            steps_.push_back(step);
            return true;
        }

        if (!ins.dest) return fail(at, "missing destination");
        const isa::DestinationParameter& d = *ins.dest;
        if (d.shift != 0) return fail(at, "result shift not available in vs_2_0/ps_2_0");
        step.dest.mask = d.write_mask;
        step.dest.saturate = d.saturate;
        step.dest.rounding = numerics::result_rounding(options_.precision, pixel_, d.partial_precision);
        // "mov a0.x, r0.x" (the vs_1_1 way, still encoded by the assemblers for vs_2_0): the
        // docs say it rounds to nearest like mova, so it becomes a mova.
        if (ins.opcode == Opcode::Mov && d.type == RegisterType::Address && !pixel_) {
            step.opcode = Opcode::Mova;
            info = isa::find_opcode(Opcode::Mova);
        }
        if (step.opcode == Opcode::Mova) {
            if (d.type != RegisterType::Address) return fail(at, "mova writes a0");
            step.dest.address = true;
            step.dest.rounding = ResultRounding::None;
        } else {
            const auto dest_slot = register_slot(shader_.version().type, d.type, d.index);
            if (!dest_slot) return fail(at, "destination register cannot be written here");
            step.dest.slot = static_cast<uint16_t>(*dest_slot);
        }

        // Which result channels each source is read for.
        std::array<uint8_t, 3> channels{d.write_mask, d.write_mask, d.write_mask};
        size_t source_count = info->num_sources;
        switch (step.opcode == Opcode::Mova ? isa::Category::Special : info->category) {
        case isa::Category::ComponentWise:
            if (ins.opcode == Opcode::Sgn) source_count = 1;  // src1, src2 are scratch temps
            break;
        case isa::Category::DotProduct:
            if (ins.opcode == Opcode::Dp3) channels = {0x7, 0x7, 0};
            if (ins.opcode == Opcode::Dp4) channels = {0xF, 0xF, 0};
            if (ins.opcode == Opcode::Dp2Add) channels = {0x3, 0x3, 0x1};
            break;
        case isa::Category::Scalar:
            channels = {0x1, 0x1, 0x1};
            break;
        case isa::Category::Matrix:
            return emit_matrix(at, step, *info, loop_counter);
        case isa::Category::Special:
            channels = {0xF, 0xF, 0xF};
            if (ins.opcode == Opcode::SinCos) {
                // Exact sin/cos: the D3DSINCOSCONST operands are not needed.
                source_count = 1;
                channels = {0x1, 0, 0};
            }
            if (step.opcode == Opcode::Mova) channels = {d.write_mask, 0, 0};
            break;
        case isa::Category::Texture:
            channels = {0xF, 0, 0};
            source_count = 1;
            if (ins.sources.size() < 2 || ins.sources[1].type != RegisterType::Sampler)
                return fail(at, "texld needs a sampler");
            if (ins.sources[1].index >= 16) return fail(at, "sampler register out of range");
            step.sampler = static_cast<uint8_t>(ins.sources[1].index);
            break;
        default:
            return fail(at, "not executable");
        }
        // crs never writes w; sincos writes x (cos) and y (sin) and leaves z and w untouched
        // (SM2 leaves z undefined; untouched is one of the legal choices).
        if (ins.opcode == Opcode::Crs) step.dest.mask &= 0x7;
        if (ins.opcode == Opcode::SinCos) step.dest.mask &= 0x3;
        if (ins.sources.size() < source_count) return fail(at, "missing source operand");
        for (size_t k = 0; k < source_count; ++k) {
            auto s = source(at, ins.sources[k], loop_counter, channels[k]);
            if (!s) return false;
            step.sources[k] = *s;
        }
        step.source_count = static_cast<uint8_t>(source_count);
        steps_.push_back(step);
        return true;
    }

    // m4x4 d, s0, s1 == dp4 d.x, s0, s1 ; dp4 d.y, s0, s1+1 ; ... (instructions.md §8). Rows
    // outside the write mask are not computed.
    bool emit_matrix(size_t at, const Step& base, const isa::OpcodeInfo& info, AddressValue loop_counter) {
        const isa::Instruction& ins = code_[at];
        if (ins.sources.size() < 2) return fail(at, "missing source operand");
        const uint8_t row_channels = info.matrix_columns == 4 ? 0xF : 0x7;
        for (unsigned row = 0; row < info.matrix_rows; ++row) {
            if (!((base.dest.mask >> row) & 1u)) continue;
            Step step = base;
            step.opcode = info.matrix_columns == 4 ? Opcode::Dp4 : Opcode::Dp3;
            step.dest.mask = static_cast<uint8_t>(1u << row);
            isa::SourceParameter row_register = ins.sources[1];
            row_register.index = static_cast<uint16_t>(row_register.index + row);
            auto vector = source(at, ins.sources[0], loop_counter, row_channels);
            auto matrix_row = source(at, row_register, loop_counter, row_channels);
            if (!vector || !matrix_row) return false;
            step.sources[0] = *vector;
            step.sources[1] = *matrix_row;
            step.source_count = 2;
            steps_.push_back(step);
        }
        return true;
    }

    const Shader& shader_;
    const std::vector<isa::Instruction>& code_;
    StaticFlowConstants flow_;
    LoweringOptions options_;
    bool pixel_;
    unsigned constant_count_;
    std::vector<Step> steps_;
    uint32_t executed_ = 0;
    std::string error_;
};

}  // namespace

LowerResult lower(const Shader& shader, const StaticFlowConstants& flow, const LoweringOptions& options) {
    return Lowerer(shader, shader.effective_flow(flow), options).run();
}

}  // namespace sm2::emu
