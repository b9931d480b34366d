// Shader engine throughput: lanes x executed instructions per second for representative shaders
// in every precision mode and both transcendental modes, in the interpreter and (jit/...) in the
// JIT's compiled code, which runs every mode but fp64 (the reference stays interpreted); and
// (jit/compile/...) the JIT's compile time per routine for the same shaders.
// Reported, never asserted.
//   build/release/bench/shader_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sm2/assembler/assembler.h"
#include "sm2/emu/engine.h"
#include "sm2/emu/jit.h"

namespace {

using namespace sm2;

std::string read_sample(const std::string& name) {
    std::ifstream in(std::string(SM2_SOURCE_DIR) + "/samples/shaders/" + name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A procedural two-colour checkerboard, so the textured shader's figure measures the engine and
// not texture fetch (texture sampling has its own benchmark).
class CheckerSampler final : public emu::Sampler {
public:
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        const auto& uv = *request.coordinates;
        for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane) {
            const bool odd = (static_cast<int>(std::floor(uv[0][lane] * 8)) + static_cast<int>(std::floor(uv[1][lane] * 8))) & 1;
            const float v = odd ? 1.0f : 0.25f;
            texels[0][lane] = v;
            texels[1][lane] = v;
            texels[2][lane] = v;
            texels[3][lane] = 1.0f;
        }
    }
};

struct Mode {
    emu::Precision precision;
    bool pp_fp16;
    emu::Transcendentals transcendentals;
};

constexpr Mode kModes[] = {
    {emu::Precision::Fp32, false, emu::Transcendentals::Exact},
    {emu::Precision::Fp32, false, emu::Transcendentals::Fast},
    {emu::Precision::Fp24, false, emu::Transcendentals::Exact},
    {emu::Precision::Fp24, true, emu::Transcendentals::Exact},  // "fp16": fp24 + _pp in s10e5
    {emu::Precision::Fp64, false, emu::Transcendentals::Exact},
};

const char* mode_label(const Mode& m) {
    if (m.precision == emu::Precision::Fp64) return "fp64";
    if (m.pp_fp16) return "fp16(pp)";
    if (m.precision == emu::Precision::Fp24) return "fp24";
    return m.transcendentals == emu::Transcendentals::Fast ? "fp32/fast" : "fp32";
}

// Times `execute_batch(batch)` on one batch whose inputs vary by lane and component.
template <typename BatchType, typename Execute>
void run(benchmark::State& state, const emu::Executable& executable, Execute&& execute_batch) {
    auto batch = std::make_unique<BatchType>();
    for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
        for (unsigned s = 0; s < emu::slot::kCount; ++s)
            for (unsigned c = 0; c < 4; ++c)
                if (s >= emu::slot::kInputFirst && s < emu::slot::kTexCoordFirst + emu::slot::kTexCoordCount)
                    batch->registers[s][c][lane] = 0.1f * static_cast<float>(lane + c + 1);
    for (auto _ : state) {
        execute_batch(*batch);
        benchmark::DoNotOptimize(batch->registers[emu::slot::kPosition][0][0]);
    }
    const double work = static_cast<double>(executable.executed_instructions()) * emu::kBatchLanes;
    state.counters["lane_instr/s"] = benchmark::Counter(work, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["instr"] = executable.executed_instructions();
}

// The sample shader `file` assembled and lowered; nothing (the benchmark skipped) on an error.
std::optional<emu::Executable> lower_sample(benchmark::State& state, const std::string& file,
                                            const emu::StaticFlowConstants& flow, const emu::LoweringOptions& options) {
    auto assembled = assembler::assemble(read_sample(file));
    if (!assembled.ok()) {
        state.SkipWithError(("cannot assemble " + file).c_str());
        return std::nullopt;
    }
    auto shader = emu::Shader::create(*assembled.program);
    auto lowered = emu::lower(*shader.shader, flow, options);
    if (!lowered.executable) state.SkipWithError(lowered.error.c_str());
    return std::move(lowered.executable);
}

// The application's constant registers for the sample shaders.
emu::ConstantFile sample_constants(const emu::Executable& executable) {
    const std::vector<std::array<float, 4>> app(256, {0.5f, 0.25f, 0.125f, 1.0f});
    return executable.bind_constants(app);
}

// Times one batch a call of `executable` in the interpreter or, with `jit`, compiled (fp64 is
// never compiled: no such benchmark is registered).
void run_engine(benchmark::State& state, const emu::Executable& executable, bool jit, emu::Sampler* sampler,
                const std::string& label) {
    const emu::ConstantFile constants = sample_constants(executable);
    state.SetLabel((jit ? "jit " : "") + label);
    if (!jit) {
        auto execute_batch = [&](auto& batch) { emu::execute(executable, constants, batch, sampler); };
        if (executable.precision() == emu::Precision::Fp64)
            run<emu::ReferenceBatch>(state, executable, execute_batch);
        else
            run<emu::Batch>(state, executable, execute_batch);
        return;
    }
    if (!emu::jit::available()) {
        state.SkipWithError("no JIT in this build");
        return;
    }
    std::string error;
    const auto compiled = emu::jit::compile(executable, &error);
    if (!compiled) {
        state.SkipWithError(error.c_str());
        return;
    }
    run<emu::Batch>(state, executable, [&](emu::Batch& batch) { compiled->run(constants, batch, sampler); });
}

// The lowering options of `mode`.
emu::LoweringOptions lowering_options(const Mode& mode) {
    emu::LoweringOptions options;
    options.precision.precision = mode.precision;
    options.precision.partial_precision_fp16 = mode.pp_fp16;
    options.precision.transcendentals = mode.transcendentals;
    return options;
}

void shader_benchmark(benchmark::State& state, const std::string& file, const Mode& mode,
                      const emu::StaticFlowConstants& flow, bool jit) {
    const auto executable = lower_sample(state, file, flow, lowering_options(mode));
    if (!executable) return;
    CheckerSampler sampler;
    run_engine(state, *executable, jit, &sampler, mode_label(mode));
}

// Independent instances of one transcendental instruction, so the figure is the instruction's
// own cost in each mode; exact vs fast is the ratio in one run. Each instance reads its own
// input component (t0-t7) and writes its own component of r1-r8, and all of them are added
// into oC0: the JIT keeps temporaries in registers, drops what no output reads and computes a
// repeated expression once, which had left its fast kernels almost nothing to do. 32 instances,
// sincos 16 (its results can only go to .x or .y).
std::string transcendental_shader(const std::string& instruction) {
    std::string text =
        "ps_2_0\n"
        "def c0, -0.0000015500992, -0.000021701389, 0.0026041667, 0.00026041668\n"
        "def c1, -0.020833334, -0.125, 1.0, 0.5\n";
    for (int t = 0; t < 8; ++t) text += "dcl t" + std::to_string(t) + "\n";
    for (int r = 1; r <= 8; ++r) text += "mov r" + std::to_string(r) + ", c1.z\n";
    static const char* const kComponents[] = {"x", "y", "z", "w"};
    const bool sincos = instruction == "sincos";
    for (int i = 0; i < (sincos ? 16 : 32); ++i) {
        const std::string src = "t" + std::to_string(sincos ? i / 2 : i / 4) + "." + kComponents[i % 4];
        if (sincos) {
            text += "sincos r" + std::to_string(1 + i / 2) + "." + kComponents[i % 2] + ", " + src + ", c0, c1\n";
            continue;
        }
        const std::string dest = "r" + std::to_string(1 + i / 4) + "." + kComponents[i % 4];
        if (instruction == "pow")
            text += "pow " + dest + ", " + src + ", t" + std::to_string((i / 4 + 1) % 8) + "." + kComponents[(i + 1) % 4] + "\n";
        else
            text += instruction + " " + dest + ", " + src + "\n";
    }
    for (int r = 2; r <= 8; ++r) text += "add r1, r1, r" + std::to_string(r) + "\n";
    return text + "mov oC0, r1\n";
}

void transcendental_benchmark(benchmark::State& state, const std::string& instruction, emu::Transcendentals mode,
                              bool jit) {
    assembler::AssembleOptions no_validation;
    no_validation.validate = false;  // 32 x pow is beyond the 64-slot budget on purpose
    auto assembled = assembler::assemble(transcendental_shader(instruction), no_validation);
    if (!assembled.ok()) {
        state.SkipWithError(("cannot assemble the " + instruction + " shader").c_str());
        return;
    }
    auto shader = emu::Shader::create(*assembled.program);
    emu::LoweringOptions options;
    options.precision.transcendentals = mode;
    options.keep_dead_code = true;
    auto lowered = emu::lower(*shader.shader, {}, options);
    if (!lowered.executable) {
        state.SkipWithError(lowered.error.c_str());
        return;
    }
    run_engine(state, *lowered.executable, jit, nullptr, mode == emu::Transcendentals::Fast ? "fast" : "exact");
}

// The JIT's compile time of one routine: lowering once, then emu::jit::compile() (IR, LLVM's
// passes, machine code) every iteration, its code freed with the routine. The process's
// one-time costs (LLVM's first use, the out-of-line kernels) fall in the warm-up iteration.
void compile_benchmark(benchmark::State& state, const std::string& file, const Mode& mode, const emu::StaticFlowConstants& flow) {
    if (!emu::jit::available()) {
        state.SkipWithError("no JIT in this build");
        return;
    }
    const auto executable = lower_sample(state, file, flow, lowering_options(mode));
    if (!executable) return;
    std::string error;
    if (!emu::jit::compile(*executable, &error)) {
        state.SkipWithError(error.c_str());
        return;
    }
    for (auto _ : state) benchmark::DoNotOptimize(emu::jit::compile(*executable, &error));
    state.SetLabel(std::to_string(executable->steps().size()) + " steps");
}

void register_all() {
    emu::StaticFlowConstants four_lights;
    four_lights.integers[0] = {4, 16, 2, 0};
    const emu::StaticFlowConstants none;
    for (const Mode& mode : kModes) {
        if (mode.precision == emu::Precision::Fp64) continue;
        const std::string label = mode_label(mode);
        for (const char* file : {"phong_lights.vs.asm", "textured_phong.ps.asm", "alu64.ps.asm"})
            benchmark::RegisterBenchmark((std::string("jit/compile/") + file + "/" + label).c_str(),
                                         [mode, file, four_lights, none](benchmark::State& s) {
                                             compile_benchmark(s, file, mode, std::string(file) == "phong_lights.vs.asm" ? four_lights : none);
                                         })
                ->Unit(benchmark::kMillisecond);
    }
    for (const bool jit : {false, true}) {
        const std::string engine = jit ? "jit/" : "";
        for (const char* instruction : {"exp", "log", "pow", "sincos"})
            for (const auto mode : {emu::Transcendentals::Exact, emu::Transcendentals::Fast})
                benchmark::RegisterBenchmark(
                    (engine + "transcendental/" + instruction + (mode == emu::Transcendentals::Fast ? "/fast" : "/exact")).c_str(),
                    [instruction = std::string(instruction), mode, jit](benchmark::State& s) {
                        transcendental_benchmark(s, instruction, mode, jit);
                    });
        for (const Mode& mode : kModes) {
            if (jit && mode.precision == emu::Precision::Fp64) continue;
            const std::string label = mode_label(mode);
            benchmark::RegisterBenchmark((engine + "phong_4_lights_vs/" + label).c_str(),
                                         [mode, four_lights, jit](benchmark::State& s) {
                                             shader_benchmark(s, "phong_lights.vs.asm", mode, four_lights, jit);
                                         });
            benchmark::RegisterBenchmark((engine + "textured_phong_ps/" + label).c_str(), [mode, none, jit](benchmark::State& s) {
                shader_benchmark(s, "textured_phong.ps.asm", mode, none, jit);
            });
            benchmark::RegisterBenchmark((engine + "alu64_ps/" + label).c_str(), [mode, none, jit](benchmark::State& s) {
                shader_benchmark(s, "alu64.ps.asm", mode, none, jit);
            });
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    register_all();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
