// sm2 run: execute one shader over a few lanes and print what it writes.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "io.h"
#include "lanes.h"
#include "violations.h"
#include "sm2/assembler/assembler.h"
#include "sm2/emu/engine.h"
#include "sm2/emu/jit.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/constant_table.h"
#include "sm2/isa/validator.h"
#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/sampler.h"
#include "sm2/runtime/texture_io.h"

namespace sm2::tools {

namespace {

struct RunOptions {
    std::string shader;
    std::vector<std::string> constants, integers, booleans, inputs, textures, sampler_states;
    std::string precision = "fp32";
    std::string transcendentals = "exact";
    std::string lanes_csv;
    unsigned lanes = 1;
    bool json = false;
    bool trace = false;
    std::string engine = kDefaultEngine;
    std::string jit_cache;
};

// Shortest text that reads back to the same value in the run's storage type (float or double).
template <typename Real>
std::string format_number(Real v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    (void)ec;
    return std::string(buf, end);
}

// "c4=1,2,3,4" -> (4, ["1","2","3","4"]) for register letter `letter`.
std::pair<unsigned, std::vector<std::string_view>> register_assignment(const std::string& arg, std::string_view prefix,
                                                                       unsigned count, const char* option) {
    const size_t eq = arg.find('=');
    const std::string what = std::string(option) + " '" + arg + "'";
    if (eq == std::string::npos || arg.compare(0, prefix.size(), prefix) != 0)
        throw UsageError{"expected " + std::string(prefix) + "N=values in " + what};
    const auto index = parse_number<unsigned>(std::string_view(arg).substr(prefix.size(), eq - prefix.size()), what);
    if (index >= count)
        throw UsageError{std::string(prefix) + std::to_string(index) + " is out of range (" + std::string(prefix) +
                         "0.." + std::string(prefix) + std::to_string(count - 1) + ") in " + what};
    auto values = split(std::string_view(arg).substr(eq + 1), ',');
    if (values.empty() || values.size() > 4) throw UsageError{"expected 1 to 4 values in " + what};
    return {index, values};
}

// --const NAME=values names a float constant of the shader's constant table (CTAB); its values
// fill its registers four at a time (a float4x4 takes up to 16). c#=values passes through.
std::vector<std::string> constant_assignments(const isa::Program& program, const std::string& arg) {
    const size_t eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const bool register_form = name.size() > 1 && name[0] == 'c' &&
                               name.find_first_not_of("0123456789", 1) == std::string::npos;
    if (eq == std::string::npos || register_form) return {arg};
    const std::string what = "--const '" + arg + "'";
    const auto table = isa::find_constant_table(program);
    if (!table) throw UsageError{what + ": the shader has no constant table to look '" + name + "' up in"};
    if (!table->ok()) throw InputError{"the shader's constant table: " + table->error};
    const isa::ConstantInfo* constant = isa::find_constant(*table->table, name);
    if (!constant) {
        std::string names;
        for (const isa::ConstantInfo& c : table->table->constants) names += (names.empty() ? "" : ", ") + c.name;
        throw UsageError{what + ": the constant table has no '" + name + "' (it has: " + names + ")"};
    }
    if (constant->register_set != isa::ConstantRegisterSet::Float4)
        throw UsageError{what + ": '" + name + "' lives in " + isa::register_set_prefix(constant->register_set) +
                         std::to_string(constant->register_index) + "; --const sets c# registers"};
    const auto values = split(std::string_view(arg).substr(eq + 1), ',');
    const size_t capacity = 4u * constant->register_count;
    if (values.empty() || values.size() > capacity)
        throw UsageError{"expected 1 to " + std::to_string(capacity) + " values for '" + name + "' (" +
                         isa::constant_type_name(constant->type) + ", " + std::to_string(constant->register_count) +
                         " register" + (constant->register_count == 1 ? "" : "s") + ") in " + what};
    std::vector<std::string> out;
    for (size_t first = 0; first < values.size(); first += 4) {
        std::string assignment = "c" + std::to_string(constant->register_index + first / 4) + "=";
        for (size_t k = first; k < std::min(values.size(), first + 4); ++k)
            assignment += (k == first ? "" : ",") + std::string(values[k]);
        out.push_back(std::move(assignment));
    }
    return out;
}

std::optional<isa::Program> load_program(const std::string& path) {
    std::string error;
    auto bytes = read_input(path, error);
    if (!bytes) throw InputError{error};
    const std::string name = display_name(path);
    if (isa::looks_like_bytecode(*bytes)) {
        auto decoded = isa::decode_bytes(*bytes);
        if (!decoded.ok()) throw InputError{name + ": " + decoded.error->to_string()};
        const auto violations = isa::validate(*decoded.program);
        print_violations(std::cerr, name, *decoded.program, violations);
        if (!violations.empty()) return std::nullopt;
        return std::move(*decoded.program);
    }
    assembler::AssembleOptions options;
    options.file_name = name;
    auto result = assembler::assemble({reinterpret_cast<const char*>(bytes->data()), bytes->size()}, options);
    for (const auto& d : result.diagnostics) std::cerr << d.to_string() << '\n';
    if (!result.ok()) return std::nullopt;
    return std::move(*result.program);
}

std::string output_name(unsigned s) {
    namespace slot = emu::slot;
    if (s == slot::kPosition) return "oPos";
    if (s == slot::kFog) return "oFog";
    if (s == slot::kPointSize) return "oPts";
    if (s == slot::kDepth) return "oDepth";
    if (s >= slot::kColorOutFirst && s < slot::kColorOutFirst + slot::kColorOutCount)
        return "oD" + std::to_string(s - slot::kColorOutFirst);
    if (s >= slot::kTexCoordOutFirst && s < slot::kTexCoordOutFirst + slot::kTexCoordOutCount)
        return "oT" + std::to_string(s - slot::kTexCoordOutFirst);
    if (s >= slot::kRenderTargetFirst && s < slot::kRenderTargetFirst + slot::kRenderTargetCount)
        return "oC" + std::to_string(s - slot::kRenderTargetFirst);
    return "slot" + std::to_string(s);
}

// Per-lane input values: (slot, component) -> value, from --input (all lanes) and --lanes CSV.
struct LaneInputs {
    using Value = LaneValue;
    std::vector<Value> all_lanes;
    std::vector<std::vector<Value>> per_lane;
};

LaneInputs read_inputs(const RunOptions& o, isa::ShaderVersion version) {
    LaneInputs in;
    for (const std::string& arg : o.inputs) {
        const size_t eq = arg.find('=');
        const std::string what = "--input '" + arg + "'";
        if (eq == std::string::npos) throw UsageError{"expected REGISTER=values in " + what};
        const unsigned s = input_slot(version, std::string_view(arg).substr(0, eq), what);
        const auto values = split(std::string_view(arg).substr(eq + 1), ',');
        if (values.size() > 4) throw UsageError{"expected 1 to 4 values in " + what};
        // Components not given keep the input default (0, 0, 0, 1), like a short vertex element.
        for (unsigned c = 0; c < values.size(); ++c)
            in.all_lanes.push_back({s, c, parse_number<double>(values[c], what)});
    }
    if (o.lanes_csv.empty()) return in;
    std::string error;
    const auto bytes = read_input(o.lanes_csv, error);
    if (!bytes) throw InputError{error};
    in.per_lane = parse_lanes_csv({reinterpret_cast<const char*>(bytes->data()), bytes->size()},
                                  display_name(o.lanes_csv), version);
    return in;
}

std::vector<std::string> describe_lines(const emu::Executable& executable) {
    std::vector<std::string> lines;
    std::istringstream in(executable.describe());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The register a step wrote, per lane (or the lanes texkill discarded, or a0 after mova).
template <typename BatchType>
void trace_step(std::ostringstream& out, const emu::Step& step, const BatchType& batch, unsigned count,
                unsigned first_lane) {
    static constexpr char kComponents[] = "xyzw";
    for (unsigned lane = 0; lane < count; ++lane) {
        out << "    lane " << first_lane + lane << ":";
        if (step.opcode == isa::Opcode::TexKill) {
            out << ((batch.killed >> lane) & 1u ? " killed" : " kept");
        } else if (step.dest.address) {
            for (unsigned c = 0; c < 4; ++c)
                if (step.dest.mask & (1u << c)) out << " a0." << kComponents[c] << "=" << batch.address[c][lane];
        } else {
            for (unsigned c = 0; c < 4; ++c)
                if (step.dest.mask & (1u << c))
                    out << " " << kComponents[c] << "=" << format_number(batch.registers[step.dest.slot][c][lane]);
        }
        out << '\n';
    }
}

template <typename BatchType>
int execute_and_print(const emu::Executable& executable, const emu::ConstantFile& constants,
                      const LaneInputs& inputs, unsigned lane_total, const RunOptions& o,
                      emu::Sampler& sampler) {
    using Real = std::remove_reference_t<decltype(std::declval<BatchType&>().registers[0][0][0])>;
    const auto& written = executable.components_written();
    // --json (README, "sm2 run --json"): finite values are JSON numbers, the shortest text that
    // reads back to the same value; inf, -inf and nan, which JSON has no numbers for, are null
    // there and named as strings in the lane's "nonfinite" object ("oC0.y": "inf").
    std::ostringstream text;
    nlohmann::ordered_json json = {{"shader", executable.version().name()}, {"precision", o.precision}};
    nlohmann::ordered_json& json_lanes = json["lanes"] = nlohmann::ordered_json::array();
    static constexpr char kComponents[] = "xyzw";
    // --engine jit: the executable as native code (float batches; --trace, fp64 and a build
    // without the JIT interpret).
    std::shared_ptr<const emu::jit::CompiledShader> compiled;
    if constexpr (std::is_same_v<BatchType, emu::Batch>) {
        if (o.engine == "jit" && !o.trace && emu::jit::available()) {
            // (Read by the JIT at each compilation: jit.h.)
            if (!o.jit_cache.empty()) ::setenv("SM2_JIT_CACHE", o.jit_cache.c_str(), 1);
            std::string error;
            compiled = emu::jit::compile(executable, &error);
            if (!compiled) throw InputError{"--engine jit: " + error};
        }
    }
    for (unsigned first = 0; first < lane_total; first += emu::kBatchLanes) {
        auto batch = std::make_unique<BatchType>();
        const unsigned count = std::min(emu::kBatchLanes, lane_total - first);
        batch->lane_count = count;
        for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane) {
            for (const auto& v : inputs.all_lanes) batch->registers[v.slot][v.component][lane] = static_cast<Real>(v.value);
            const unsigned global = first + lane;
            if (global < inputs.per_lane.size())
                for (const auto& v : inputs.per_lane[global])
                    batch->registers[v.slot][v.component][lane] = static_cast<Real>(v.value);
        }
        if (o.trace) {
            const std::vector<std::string> lines = describe_lines(executable);
            emu::execute(executable, constants, *batch, &sampler, [&](size_t i, const emu::Step& step) {
                text << "#" << i << "  " << (i < lines.size() ? lines[i] : "") << '\n';
                trace_step(text, step, *batch, count, first);
            });
        } else if constexpr (std::is_same_v<BatchType, emu::Batch>) {
            if (compiled) compiled->run(constants, *batch, &sampler);
            else emu::execute(executable, constants, *batch, &sampler);
        } else {
            emu::execute(executable, constants, *batch, &sampler);
        }
        for (unsigned lane = 0; lane < count; ++lane) {
            const unsigned global = first + lane;
            nlohmann::ordered_json lane_json = nlohmann::ordered_json::object(), nonfinite = nlohmann::ordered_json::object();
            const std::string prefix = lane_total > 1 ? "lane " + std::to_string(global) + ": " : "";
            if (batch->killed & (emu::LaneMask{1} << lane)) {
                text << prefix << "killed (texkill)\n";
                lane_json["killed"] = true;
            }
            const bool killed = (batch->killed & (emu::LaneMask{1} << lane)) != 0;
            for (unsigned s = 0; s < emu::kSlotCount && !killed; ++s) {
                if (!emu::is_output_slot(s) || written[s] == 0) continue;
                std::string mask;
                std::string values;
                nlohmann::ordered_json fields = nlohmann::ordered_json::object();
                for (unsigned c = 0; c < 4; ++c) {
                    if (!(written[s] & (1u << c))) continue;
                    const Real value = batch->registers[s][c][lane];
                    mask += kComponents[c];
                    const std::string number = format_number(value);
                    values += (values.empty() ? "" : " ") + number;
                    const std::string component(1, kComponents[c]);
                    if (std::isfinite(value)) {
                        fields[component] = std::strtod(number.c_str(), nullptr);
                    } else {
                        fields[component] = nullptr;
                        nonfinite[output_name(s) + "." + component] = number;
                    }
                }
                text << prefix << output_name(s) << (mask == "xyzw" ? "" : "." + mask) << " = " << values << '\n';
                lane_json[output_name(s)] = std::move(fields);
            }
            if (!nonfinite.empty()) lane_json["nonfinite"] = std::move(nonfinite);
            json_lanes.push_back(std::move(lane_json));
        }
    }
    if (o.json) std::cout << json.dump() << '\n';
    else std::cout << text.str();
    return kOk;
}

// --texture sN=FILE and --sampler-state sN.STATE=VALUE (D3D9 names, e.g. s0.MINFILTER=LINEAR).
struct BoundTextures {
    runtime::TextureSampler sampler;
    std::vector<std::unique_ptr<runtime::Texture>> textures;
};

std::unique_ptr<BoundTextures> bind_textures(const RunOptions& o) {
    auto bound = std::make_unique<BoundTextures>();
    for (const std::string& arg : o.textures) {
        const size_t eq = arg.find('=');
        const std::string what = "--texture '" + arg + "'";
        if (eq == std::string::npos || arg.empty() || arg[0] != 's')
            throw UsageError{"expected sN=FILE in " + what};
        const auto stage = parse_number<unsigned>(std::string_view(arg).substr(1, eq - 1), what);
        if (stage >= runtime::TextureSampler::kStages) throw UsageError{"sampler s" + std::to_string(stage) + " does not exist (s0..s15) in " + what};
        try {
            bound->textures.push_back(std::make_unique<runtime::Texture>(runtime::load_texture(arg.substr(eq + 1))));
        } catch (const runtime::TextureIoError& e) {
            throw InputError{e.what()};
        }
        bound->sampler.set_texture(stage, bound->textures.back().get());
    }
    for (const std::string& arg : o.sampler_states) {
        const std::string what = "--sampler-state '" + arg + "'";
        const size_t dot = arg.find('.'), eq = arg.find('=');
        if (arg.empty() || arg[0] != 's' || dot == std::string::npos || eq == std::string::npos || eq < dot)
            throw UsageError{"expected sN.STATE=VALUE in " + what};
        const auto stage = parse_number<unsigned>(std::string_view(arg).substr(1, dot - 1), what);
        if (stage >= runtime::TextureSampler::kStages) throw UsageError{"sampler s" + std::to_string(stage) + " does not exist (s0..s15) in " + what};
        const std::string_view name = std::string_view(arg).substr(dot + 1, eq - dot - 1);
        const std::string_view text = std::string_view(arg).substr(eq + 1);
        const runtime::StateInfo* info = runtime::find_sampler_state(name);
        if (!info) throw UsageError{"unknown sampler state '" + std::string(name) + "' in " + what};
        uint32_t value = 0;
        switch (info->kind) {
        case runtime::StateValueKind::Enum: {
            auto v = runtime::enum_value(info->family, text);
            if (!v) throw UsageError{"'" + std::string(text) + "' is not a " + std::string(runtime::enum_prefix(info->family)) + "* value in " + what};
            value = *v;
            break;
        }
        case runtime::StateValueKind::Bool:
            if (text == "TRUE" || text == "true" || text == "1") value = 1;
            else if (text == "FALSE" || text == "false" || text == "0") value = 0;
            else throw UsageError{"expected TRUE or FALSE in " + what};
            break;
        case runtime::StateValueKind::Float:
            value = std::bit_cast<uint32_t>(parse_number<float>(text, what));
            break;
        default:
            if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
                auto [end, ec] = std::from_chars(text.data() + 2, text.data() + text.size(), value, 16);
                if (ec != std::errc{} || end != text.data() + text.size()) throw UsageError{"bad number '" + std::string(text) + "' in " + what};
            } else {
                value = parse_number<uint32_t>(text, what);
            }
        }
        bound->sampler.state(stage).set(info->id, value);
    }
    return bound;
}

int run_shader(const RunOptions& o) {
    auto program = load_program(o.shader);
    if (!program) return kInvalidInput;
    const isa::ShaderVersion version = program->version;
    const isa::RegisterFile* const_file = isa::find_register_file(version, "c");
    const unsigned constant_count = const_file ? const_file->count : 0;

    std::vector<std::array<float, 4>> constants(constant_count, {0, 0, 0, 0});
    for (const std::string& named : o.constants) {
        for (const std::string& arg : constant_assignments(*program, named)) {
            auto [index, values] = register_assignment(arg, "c", constant_count, "--const");
            for (unsigned c = 0; c < values.size(); ++c)
                constants[index][c] = parse_number<float>(values[c], "--const '" + named + "'");
        }
    }
    emu::StaticFlowConstants flow;
    for (const std::string& arg : o.integers) {
        auto [index, values] = register_assignment(arg, "i", emu::kIntConstants, "--int");
        for (unsigned c = 0; c < values.size(); ++c) flow.integers[index][c] = parse_number<int32_t>(values[c], "--int '" + arg + "'");
    }
    for (const std::string& arg : o.booleans) {
        auto [index, values] = register_assignment(arg, "b", emu::kBoolConstants, "--bool");
        if (values.size() != 1) throw UsageError{"expected one value in --bool '" + arg + "'"};
        if (values[0] == "true" || values[0] == "1") flow.booleans[index] = true;
        else if (values[0] == "false" || values[0] == "0") flow.booleans[index] = false;
        else throw UsageError{"expected true or false in --bool '" + arg + "'"};
    }
    const LaneInputs inputs = read_inputs(o, version);
    auto textures = bind_textures(o);
    const unsigned lane_total = std::max<unsigned>(o.lanes, static_cast<unsigned>(inputs.per_lane.size()));

    emu::LoweringOptions lowering;
    // fp16 is the ps_2_0 hardware mode: full precision fp24, _pp results rounded to s10e5.
    if (o.precision == "fp24" || o.precision == "fp16") lowering.precision.precision = emu::Precision::Fp24;
    if (o.precision == "fp64") lowering.precision.precision = emu::Precision::Fp64;
    lowering.precision.partial_precision_fp16 = o.precision == "fp16";
    lowering.keep_dead_code = o.trace;  // a trace shows every instruction, used or not
    if (o.transcendentals == "fast") lowering.precision.transcendentals = emu::Transcendentals::Fast;

    auto shader = emu::Shader::create(std::move(*program));
    if (!shader.shader) throw InputError{display_name(o.shader) + ": " + shader.error};
    auto lowered = emu::lower(*shader.shader, flow, lowering);
    if (!lowered.executable) throw InputError{display_name(o.shader) + ": " + lowered.error};
    const emu::ConstantFile bound = lowered.executable->bind_constants(constants);
    if (o.precision == "fp64")
        return execute_and_print<emu::ReferenceBatch>(*lowered.executable, bound, inputs, lane_total, o, textures->sampler);
    return execute_and_print<emu::Batch>(*lowered.executable, bound, inputs, lane_total, o, textures->sampler);
}

}  // namespace

void add_run_command(CLI::App& app, int& status) {
    auto o = std::make_shared<RunOptions>();
    auto* cmd = app.add_subcommand("run", "Execute a vs_2_0/ps_2_0 shader and print every output it writes");
    cmd->add_option("shader", o->shader, "Shader: assembly text or bytecode ('-' for stdin)")->required();
    cmd->add_option("--const", o->constants,
                    "Float constant, e.g. c4=1,2,3,4, or by its constant-table name, e.g. WorldViewProj=1,0,0,0,0,1,"
                    "... (filling its registers four values at a time; repeatable)");
    cmd->add_option("--int", o->integers, "Integer constant, e.g. i0=3,0,1,0 (repeatable)");
    cmd->add_option("--bool", o->booleans, "Boolean constant, e.g. b0=true (repeatable)");
    cmd->add_option("--input", o->inputs,
                    "Input for every lane, e.g. v0=1,2,3 (missing components read 0,0,0,1; repeatable)");
    cmd->add_option("--lanes", o->lanes_csv,
                    "CSV of per-lane inputs: a header like v0.x,v0.y,t0.x then one row per lane "
                    "(pixel shaders: four rows per 2x2 quad)");
    cmd->add_option("--lane-count", o->lanes, "Lanes to run when no CSV gives them (default 1)")
        ->check(CLI::Range(1u, 4096u));
    cmd->add_option("--texture", o->textures,
                    "Texture for a sampler, e.g. s0=wood.png (PNG, TGA, JPEG, EXR, HDR, DDS; repeatable)");
    cmd->add_option("--sampler-state", o->sampler_states,
                    "Sampler state by D3D9 name, e.g. s0.MINFILTER=LINEAR or s0.MIPMAPLODBIAS=0.5 "
                    "(defaults as D3D9: POINT, WRAP; repeatable)");
    cmd->add_option("--precision", o->precision,
                    "fp32 (default), fp24 (ps rounds every result to s16e7), fp16 (fp24 plus _pp "
                    "results rounded to s10e5), fp64 (reference)")
        ->check(CLI::IsMember({"fp32", "fp24", "fp16", "fp64"}));
    cmd->add_option("--transcendentals", o->transcendentals,
                    "exact (correctly rounded exp, log and pow; default) or fast (documented minimum precision)")
        ->check(CLI::IsMember({"exact", "fast"}));
    cmd->add_option("--engine", o->engine,
                    "jit (default where the build has one: native code, the same results) or interpreter (the "
                    "reference); --trace and fp64 always interpret")
        ->check(CLI::IsMember({"interpreter", "jit"}));
    cmd->add_option("--jit-cache", o->jit_cache,
                    "Folder where the JIT keeps the machine code it compiles (as replay's --jit-cache; "
                    "SM2_JIT_CACHE names it too)");
    cmd->add_flag("--json", o->json, "Print JSON instead of text");
    cmd->add_flag("--trace", o->trace,
                  "Print every executed instruction (after flow control is resolved) with the "
                  "register it wrote, per lane, before the outputs (text only)");
    cmd->callback([o, &status] {
        try {
            status = run_shader(*o);
        } catch (const InputError& e) {
            std::cerr << "sm2 run: " << e.message << '\n';
            status = kInvalidInput;
        } catch (const UsageError& e) {
            std::cerr << "sm2 run: " << e.message << '\n';
            status = kBadUsage;
        }
    });
}

}  // namespace sm2::tools
