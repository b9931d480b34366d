// The JIT against the interpreter: random executables (every opcode the interpreter runs, random
// swizzles, negates, masks, saturate and rounding, every operand kind, mova then relative reads,
// texkill, texld) and the sample shaders, on random batches full of special values (NaN with
// payloads, +-inf, +-0, denormals, huge, tiny, halves). Every register component of every lane,
// a0, the killed mask and every texture request must be the same bits.
// Compile times and the speed of both on the sample shaders are printed, not asserted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "emu/src/dead_code.h"
#include "emu/src/numerics.h"
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "emu/engine_test_support.h"
#include "emu/random_executables.h"
#include "sm2/emu/jit.h"
#ifdef SM2_TEST_NATIVE_KERNELS
#include <cmath>
#include <span>

#include "emu/src/jit/native_kernels.h"
#include "emu/src/step_kernels.h"
#endif

namespace sm2::test {
namespace {

using emu::OperandKind;
using emu::ResultRounding;
using emu::Step;
using emu::StepSource;
using namespace random_executables;

// --- a sampler that records what it is asked ---------------------------------------------------

struct Request {
    unsigned sampler;
    emu::TextureVariant variant;
    unsigned quad_count;
    emu::LaneMask helper_lanes;
    std::array<emu::FloatLanes, 4> coordinates;
};

bool same_bits(const Request& a, const Request& b) {
    return a.sampler == b.sampler && a.variant == b.variant && a.quad_count == b.quad_count &&
           a.helper_lanes == b.helper_lanes && std::memcmp(&a.coordinates, &b.coordinates, sizeof(a.coordinates)) == 0;
}

class RecordingSampler final : public emu::Sampler {
public:
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override {
        requests.push_back(
            {request.sampler, request.variant, request.quad_count, request.helper_lanes, *request.coordinates});
        // A deterministic function of the coordinate bits, the component and the sampler; now
        // and then a special value.
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                uint64_t h = std::bit_cast<uint32_t>((*request.coordinates)[c][l]) * 0x9E3779B97F4A7C15ull;
                h ^= (h >> 29) + c * 0x632BE59BD9B4E019ull + request.sampler * 0x85EBCA77C2B2AE63ull +
                     static_cast<uint64_t>(request.variant);
                h *= 0xBF58476D1CE4E5B9ull;
                h ^= h >> 31;
                const unsigned kind = static_cast<unsigned>(h % 16);
                const float unit = static_cast<float>((h >> 8) & 0xFFFFFF) * 0x1p-24f;
                texels[c][l] = kind == 0   ? std::numeric_limits<float>::quiet_NaN()
                               : kind == 1 ? -std::numeric_limits<float>::infinity()
                               : kind == 2 ? -unit
                               : kind == 3 ? unit * 1e30f
                                           : unit;
            }
    }
    std::vector<Request> requests;
};

// --- comparing runs ----------------------------------------------------------------------------

// Compares every bit of a run's results: every register but the temporaries (compiled code
// keeps them to itself), a0 and the killed lanes; describes the first differences.
::testing::AssertionResult same_batches(const emu::Batch& interpreter, const emu::Batch& jit) {
    std::ostringstream differences;
    int shown = 0;
    for (unsigned s = emu::slot::kTempFirst + emu::slot::kTempCount; s < emu::slot::kCount; ++s)
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                const uint32_t a = std::bit_cast<uint32_t>(interpreter.registers[s][c][l]);
                const uint32_t b = std::bit_cast<uint32_t>(jit.registers[s][c][l]);
                if (a != b && shown++ < 8)
                    differences << "slot " << s << " component " << c << " lane " << l << ": interpreter "
                                << interpreter.registers[s][c][l] << " (0x" << std::hex << a << "), jit "
                                << jit.registers[s][c][l] << " (0x" << b << std::dec << ")\n";
            }
    for (unsigned c = 0; c < 4; ++c)
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            if (interpreter.address[c][l] != jit.address[c][l] && shown++ < 8)
                differences << "a0 component " << c << " lane " << l << ": interpreter " << interpreter.address[c][l]
                            << ", jit " << jit.address[c][l] << "\n";
    if (interpreter.killed != jit.killed && shown++ < 8)
        differences << "killed: interpreter 0x" << std::hex << interpreter.killed << ", jit 0x" << jit.killed
                    << std::dec << "\n";
    if (interpreter.lane_count != jit.lane_count) differences << "lane_count changed\n", ++shown;
    if (shown == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << shown << " differences:\n" << differences.str();
}

::testing::AssertionResult same_requests(const RecordingSampler& interpreter, const RecordingSampler& jit) {
    if (interpreter.requests.size() != jit.requests.size())
        return ::testing::AssertionFailure()
               << interpreter.requests.size() << " texture requests from the interpreter, " << jit.requests.size()
               << " from the jit";
    for (size_t i = 0; i < jit.requests.size(); ++i)
        if (!same_bits(interpreter.requests[i], jit.requests[i]))
            return ::testing::AssertionFailure() << "texture request " << i << " differs";
    return ::testing::AssertionSuccess();
}

// Runs `executable` on `batches` random batches in both engines.
::testing::AssertionResult run_both(const emu::Executable& executable, const emu::jit::CompiledShader& compiled,
                                    const emu::ConstantFile& constants, Random& random, unsigned batches) {
    for (unsigned b = 0; b < batches; ++b) {
        auto input = std::make_unique<emu::Batch>();
        randomize(*input, random, static_cast<unsigned>(constants.registers.size()));
        input->stop_when_all_killed = b % 2 == 1;  // both engines stop at a texkill that kills every lane
        auto by_interpreter = std::make_unique<emu::Batch>(*input);
        auto by_jit = std::make_unique<emu::Batch>(*input);
        RecordingSampler interpreter_sampler, jit_sampler;
        emu::Sampler* const interpreter_sampler_or_null = b == 1 ? nullptr : &interpreter_sampler;
        emu::Sampler* const jit_sampler_or_null = b == 1 ? nullptr : &jit_sampler;
        emu::execute(executable, constants, *by_interpreter, interpreter_sampler_or_null);
        compiled.run(constants, *by_jit, jit_sampler_or_null);
        if (auto same = same_batches(*by_interpreter, *by_jit); !same) return same << "(batch " << b << ")";
        if (auto same = same_requests(interpreter_sampler, jit_sampler); !same) return same;
    }
    return ::testing::AssertionSuccess();
}

std::string listing(const emu::Executable& executable) {
    std::string text = executable.describe();
    return text.size() > 20000 ? text.substr(0, 20000) + "..." : text;
}

// --- the tests --------------------------------------------------------------------------------

TEST(Jit, Available) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    std::string error;
    const auto compiled = emu::jit::compile(
        emu::Executable(isa::ShaderVersion{ShaderType::Vertex, 2, 0}, emu::Precision::Fp64, 0, {}, {}, 0), &error);
    EXPECT_EQ(compiled, nullptr);
    EXPECT_NE(error.find("fp64"), std::string::npos) << error;
}

struct DifferentialTotals {
    unsigned programs = 0;
    unsigned steps = 0;
    double compile_seconds = 0;
};

// `groups` x `per_group` random programs of min_steps..max_steps steps; each group is compiled
// as one module (compile_all), each program run on `batches` random batches by both engines.
void differential(const Mode& mode, uint64_t seed, unsigned groups, unsigned per_group, unsigned min_steps,
                  unsigned max_steps, unsigned batches, DifferentialTotals& totals) {
    Random random(seed);
    for (unsigned g = 0; g < groups; ++g) {
        std::vector<emu::Executable> executables;
        std::vector<emu::ConstantFile> constants;
        for (unsigned p = 0; p < per_group; ++p) {
            const unsigned constant_count = 8 + pick(random, 64);
            ProgramGenerator generator(random, mode, constant_count);
            executables.push_back(generator.generate(min_steps + pick(random, max_steps - min_steps + 1)));
            constants.push_back(random_constants(random, constant_count));
            totals.steps += static_cast<unsigned>(executables.back().steps().size());
        }
        std::vector<const emu::Executable*> pointers;
        for (const auto& executable : executables) pointers.push_back(&executable);
        std::string error;
        const auto compiled = emu::jit::compile_all(pointers, &error);
        ASSERT_EQ(compiled.size(), executables.size()) << error;
        totals.programs += per_group;
        totals.compile_seconds += compiled.front()->compile_seconds();
        for (unsigned p = 0; p < per_group; ++p)
            ASSERT_TRUE(run_both(executables[p], *compiled[p], constants[p], random, batches))
                << mode_name(mode) << ", seed " << seed << ", group " << g << ", program " << p << ":\n"
                << listing(executables[p]);
    }
}

class JitDifferential : public ::testing::TestWithParam<Mode> {};

TEST_P(JitDifferential, RandomExecutablesAreBitIdentical) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    const Mode mode = GetParam();
    DifferentialTotals totals;
    const uint64_t seed =
        0x5EED0000u + static_cast<uint64_t>(mode.rounding) * 2 + (mode.transcendentals == emu::Transcendentals::Fast);
    // Many short programs (every opcode next to every other, 25 to a module), a few long ones
    // (long chains of results feeding each other, a0 set and read many times).
    differential(mode, seed, 14, 25, 1, 4, 3, totals);
    differential(mode, seed + 100, 1, 2, 60, 150, 8, totals);
    std::printf(
        "[ jit      ] %-9s %u random programs, %u steps: all identical; compile %.2f ms per program "
        "(%.0f us per step)\n",
        mode_name(mode), totals.programs, totals.steps, 1e3 * totals.compile_seconds / totals.programs,
        1e6 * totals.compile_seconds / totals.steps);
}

INSTANTIATE_TEST_SUITE_P(Modes, JitDifferential,
                         ::testing::Values(Mode{Rounding::Fp32, emu::Transcendentals::Exact},
                                           Mode{Rounding::Fp32, emu::Transcendentals::Fast},
                                           Mode{Rounding::Fp24, emu::Transcendentals::Exact},
                                           Mode{Rounding::Fp24, emu::Transcendentals::Fast},
                                           Mode{Rounding::Fp16, emu::Transcendentals::Exact},
                                           Mode{Rounding::Fp16, emu::Transcendentals::Fast}),
                         [](const ::testing::TestParamInfo<Mode>& param_info) {
                             std::string name = mode_name(param_info.param);
                             std::replace(name.begin(), name.end(), '/', '_');
                             return name;
                         });

// hoist_uniform_steps() against the executable as generated: the hoisted one, its prelude run
// by bind_constants(), gives the same bits in the interpreter and in compiled code as the
// original in the interpreter (outputs, killed lanes, texture requests).
TEST_P(JitDifferential, HoistedUniformStepsGiveTheSameBits) {
    const Mode mode = GetParam();
    Random random(0x4015700u + static_cast<uint64_t>(mode.rounding) * 2 +
                  (mode.transcendentals == emu::Transcendentals::Fast));
    unsigned hoisted_steps = 0, snapshots = 0, programs = 0;
    for (unsigned p = 0; p < 200; ++p) {
        const unsigned constant_count = 8 + pick(random, 24);
        ProgramGenerator generator(random, mode, constant_count);
        generator.favour_uniform_steps();
        // Without its dead steps, as lowering leaves every executable (the hoisted one loses
        // them too: a mova or texld no output depends on).
        const emu::Executable generated = generator.generate(4 + pick(random, 28));
        std::vector<Step> live(generated.steps().begin(), generated.steps().end());
        emu::remove_dead_steps(live, ~0u);
        const emu::Executable original(generated.version(), generated.precision(), constant_count, std::move(live), {},
                                       generated.executed_instructions(), generated.transcendentals());
        const emu::Executable hoisted = emu::hoist_uniform_steps(original);
        if (hoisted.prelude().snapshots.empty()) continue;
        ++programs;
        hoisted_steps += static_cast<unsigned>(hoisted.prelude().steps.size());
        snapshots += static_cast<unsigned>(hoisted.prelude().snapshots.size());
        const emu::ConstantFile application = random_constants(random, constant_count);
        const emu::ConstantFile bound = hoisted.bind_constants(std::span(application.registers).first(constant_count));
        ASSERT_EQ(bound.registers.size(), hoisted.constant_count());
        std::shared_ptr<const emu::jit::CompiledShader> compiled;
        std::string error;
        if (emu::jit::available()) {
            compiled = emu::jit::compile(hoisted, &error);
            ASSERT_NE(compiled, nullptr) << error;
        }
        for (unsigned b = 0; b < 3; ++b) {
            auto input = std::make_unique<emu::Batch>();
            randomize(*input, random, constant_count);
            auto by_original = std::make_unique<emu::Batch>(*input);
            auto by_hoisted = std::make_unique<emu::Batch>(*input);
            RecordingSampler original_sampler, hoisted_sampler;
            emu::execute(original, application, *by_original, &original_sampler);
            emu::execute(hoisted, bound, *by_hoisted, &hoisted_sampler);
            ASSERT_TRUE(same_batches(*by_original, *by_hoisted))
                << mode_name(mode) << " program " << p << " batch " << b << ":\n" << listing(original) << "hoisted:\n" << listing(hoisted);
            ASSERT_TRUE(same_requests(original_sampler, hoisted_sampler)) << "program " << p;
            if (compiled) {
                auto by_jit = std::make_unique<emu::Batch>(*input);
                RecordingSampler jit_sampler;
                compiled->run(bound, *by_jit, &jit_sampler);
                ASSERT_TRUE(same_batches(*by_original, *by_jit)) << mode_name(mode) << " program " << p << " batch " << b << " (jit)";
                ASSERT_TRUE(same_requests(original_sampler, jit_sampler)) << "program " << p << " (jit)";
            }
        }
    }
    std::printf("[ uniform  ] %-9s %u programs hoisted %u steps into %u derived constants\n", mode_name(mode), programs,
                hoisted_steps, snapshots);
    EXPECT_GE(programs, 40u);
    EXPECT_GE(hoisted_steps, 3 * programs);
}

// --- the sample shaders -----------------------------------------------------------------------

std::vector<std::filesystem::path> sample_shaders() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SM2_SOURCE_DIR) + "/samples/shaders"))
        if (entry.path().extension() == ".asm") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

struct SampleMode {
    const char* name;
    emu::PrecisionOptions precision;
};

constexpr SampleMode kSampleModes[] = {
    {"fp32", {emu::Precision::Fp32, emu::Transcendentals::Exact, false}},
    {"fp32/fast", {emu::Precision::Fp32, emu::Transcendentals::Fast, false}},
    {"fp24", {emu::Precision::Fp24, emu::Transcendentals::Exact, false}},
    {"fp24/fast", {emu::Precision::Fp24, emu::Transcendentals::Fast, false}},
    {"fp16(pp)", {emu::Precision::Fp24, emu::Transcendentals::Exact, true}},
};

// Inputs as a draw would give them (moderate values), now and then a special one.
void realistic_inputs(emu::Batch& batch, Random& random) {
    std::uniform_real_distribution<float> value(-2.0f, 2.0f);
    for (unsigned s = emu::slot::kInputFirst; s < emu::slot::kTexCoordFirst + emu::slot::kTexCoordCount; ++s)
        for (auto& component : batch.registers[s])
            for (float& v : component) v = chance(random, 3) ? special_float(random) : value(random);
}

TEST(Jit, SampleShadersAreBitIdentical) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    Random random(0x5A3B1E);
    unsigned checked = 0;
    for (const auto& file : sample_shaders()) {
        const isa::Program program = assemble_or_fail(read_text(file));
        for (const SampleMode& mode : kSampleModes) {
            emu::LoweringOptions options;
            options.precision = mode.precision;
            const emu::Executable executable = lower_or_fail(program, {}, options);
            std::string error;
            const auto compiled = emu::jit::compile(executable, &error);
            ASSERT_NE(compiled, nullptr) << error;
            std::vector<Float4> application(256);
            for (auto& reg : application)
                for (float& v : reg)
                    v = chance(random, 5) ? special_float(random)
                                          : std::uniform_real_distribution<float>(-1, 1)(random);
            const emu::ConstantFile constants = executable.bind_constants(application);
            for (unsigned b = 0; b < 32; ++b) {
                auto input = std::make_unique<emu::Batch>();
                if (b < 16)
                    realistic_inputs(*input, random);
                else
                    randomize(*input, random, static_cast<unsigned>(constants.registers.size()));
                auto by_interpreter = std::make_unique<emu::Batch>(*input);
                auto by_jit = std::make_unique<emu::Batch>(*input);
                RecordingSampler interpreter_sampler, jit_sampler;
                emu::execute(executable, constants, *by_interpreter, &interpreter_sampler);
                compiled->run(constants, *by_jit, &jit_sampler);
                ASSERT_TRUE(same_batches(*by_interpreter, *by_jit))
                    << file.filename() << " " << mode.name << " batch " << b;
                ASSERT_TRUE(same_requests(interpreter_sampler, jit_sampler)) << file.filename() << " " << mode.name;
            }
            std::printf("[ jit      ] %-22s %-9s %3zu steps: identical, compiled in %.2f ms\n",
                        file.filename().string().c_str(), mode.name, executable.steps().size(),
                        1e3 * compiled->compile_seconds());
            ++checked;
        }
    }
    EXPECT_GT(checked, 0u);
}

// An exception from the Sampler reaches the caller of run(), as it does through execute().
TEST(Jit, SamplerExceptionsPassThrough) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    class ThrowingSampler final : public emu::Sampler {
    public:
        void sample(const emu::TextureRequest&, std::array<emu::FloatLanes, 4>&) override {
            throw std::runtime_error("no texture");
        }
    };
    Step tex;
    tex.opcode = Opcode::Tex;
    tex.source_count = 1;
    tex.sources[0].kind = OperandKind::Lanes;
    tex.sources[0].index = static_cast<uint16_t>(emu::slot::kTexCoordFirst);
    const emu::Executable executable(isa::ShaderVersion{ShaderType::Pixel, 2, 0}, emu::Precision::Fp32, 0, {tex}, {},
                                     1);
    const auto compiled = emu::jit::compile(executable);
    ASSERT_NE(compiled, nullptr);
    ThrowingSampler sampler;
    emu::Batch batch;
    EXPECT_THROW(emu::execute(executable, {}, batch, &sampler), std::runtime_error);
    EXPECT_THROW(compiled->run({}, batch, &sampler), std::runtime_error);
    // and the compiled code still runs afterwards
    RecordingSampler recording;
    compiled->run({}, batch, &recording);
    EXPECT_EQ(recording.requests.size(), 1u);
}

// Several threads compile and run at once (one LLJIT per process).
TEST(Jit, ThreadsCompileAndRunAtOnce) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    constexpr unsigned kThreads = 4;
    std::vector<std::string> failures(kThreads);
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < kThreads; ++t)
        threads.emplace_back([t, &failures] {
            Random random(0xC0FFEE + t);
            for (unsigned p = 0; p < 6; ++p) {
                ProgramGenerator generator(random, Mode{Rounding::Fp32, emu::Transcendentals::Exact}, 16);
                const emu::Executable executable = generator.generate(12);
                std::string error;
                const auto compiled = emu::jit::compile(executable, &error);
                if (!compiled) {
                    failures[t] = error;
                    return;
                }
                const emu::ConstantFile constants = random_constants(random, 16);
                if (auto same = run_both(executable, *compiled, constants, random, 2); !same) {
                    failures[t] = same.message();
                    return;
                }
            }
        });
    for (auto& thread : threads) thread.join();
    for (const auto& failure : failures) EXPECT_EQ(failure, "");
}

// The JIT cache (SM2_JIT_CACHE, jit.h): a group compiled again while its code lives shares it;
// freed, it loads from the directory; a file whose bytes changed is not loaded but compiled
// again and replaced. Every compiled shader runs bit-identical to the interpreter.
TEST(Jit, CacheServesTheSameCodeAndRefusesChangedFiles) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    const std::filesystem::path directory =
        std::filesystem::temp_directory_path() / ("sm2_jit_cache_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(directory);
    ASSERT_EQ(::setenv("SM2_JIT_CACHE", directory.c_str(), 1), 0);
    Random random(20261203);
    ProgramGenerator generator(random, Mode{Rounding::Fp32, emu::Transcendentals::Exact}, 16);
    const emu::Executable executable = generator.generate(16);
    const emu::ConstantFile constants = random_constants(random, 16);
    const auto compile_and_check = [&](bool expect_from_cache, const char* what) {
        std::string error;
        auto compiled = emu::jit::compile(executable, &error);
        EXPECT_NE(compiled, nullptr) << what << ": " << error;
        if (!compiled) return compiled;
        EXPECT_EQ(compiled->from_cache(), expect_from_cache) << what;
        const auto same = run_both(executable, *compiled, constants, random, 2);
        EXPECT_TRUE(same) << what << ": " << same.message();
        return compiled;
    };
    const auto cache_files = [&] {
        std::vector<std::filesystem::path> files;
        for (const auto& entry : std::filesystem::directory_iterator(directory))
            if (entry.path().extension() == ".sm2jit") files.push_back(entry.path());
        return files;
    };
    {
        const auto first = compile_and_check(false, "first compilation");
        ASSERT_TRUE(std::filesystem::is_directory(directory));
        EXPECT_FALSE(cache_files().empty());
        const auto again = compile_and_check(true, "again while the first lives");
        ASSERT_TRUE(first && again);
    }
    compile_and_check(true, "from the directory");
    // Every file changed in one byte: its checksum's first (bytes 8-27 of the file, after the
    // 8-byte tag), so that it no longer matches the object.
    for (const auto& file : cache_files()) {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(8);
        const char byte = static_cast<char>(f.get());
        f.seekp(8);
        f.put(static_cast<char>(byte ^ 0x5A));
    }
    compile_and_check(false, "after the files changed");
    compile_and_check(true, "from the replaced files");
    // A file cut short is no more loaded than a changed one.
    for (const auto& file : cache_files()) std::filesystem::resize_file(file, 12);
    compile_and_check(false, "after the files were cut short");
    ASSERT_EQ(::unsetenv("SM2_JIT_CACHE"), 0);
    compile_and_check(false, "without the cache");
    std::filesystem::remove_all(directory);
}

// A shader of one step, pow(x, c0.z or -c0.z) with c0 def'd, its z `exponent` (negated in the
// def where the source negates it, so the step reads `exponent`): a pixel shader's oC0.mask =
// pow(t0.x, ...), a vertex shader's oT0.mask = pow(v0.x, ...).
emu::Executable pow_by_def(ShaderType type, float exponent, bool negate, bool fast, uint8_t mask) {
    Step pow;
    pow.opcode = Opcode::Pow;
    const bool pixel = type == ShaderType::Pixel;
    pow.dest.slot = static_cast<uint16_t>(pixel ? emu::slot::kRenderTargetFirst : emu::slot::kTexCoordOutFirst);
    pow.dest.mask = mask;
    pow.source_count = 2;
    pow.sources[0].kind = OperandKind::Lanes;
    pow.sources[0].index = static_cast<uint16_t>(pixel ? emu::slot::kTexCoordFirst : emu::slot::kInputFirst);
    pow.sources[0].swizzle = 0x00;  // .xxxx
    pow.sources[0].channels = 0x1;
    pow.sources[1].kind = OperandKind::Constant;
    pow.sources[1].index = 0;
    pow.sources[1].swizzle = 0xAA;  // .zzzz
    pow.sources[1].negate = negate;
    pow.sources[1].channels = 0x1;
    const float def_z = negate ? -exponent : exponent;
    return emu::Executable(isa::ShaderVersion{type, 2, 0}, emu::Precision::Fp32, 1, {pow},
                           {{0, {7.0f, 3.0f, def_z, 2.0f}}}, 1,
                           fast ? emu::Transcendentals::Fast : emu::Transcendentals::Exact);
}

// pow with a def'd exponent, which the JIT splits in pixel routines (jit/compiler.cpp's
// emit_pow): the squarings inline for an integer in [1, 256], the kernel out of line for the
// batches they leave undecided, the kernel alone for every other exponent (and in vertex
// routines, for every exponent). The bases include exact squaring ties ((1 + 2^-12)^2 lies
// halfway between two floats) and NaN, so the out-of-line block runs, which the test checks;
// every output is the interpreter's bits.
TEST(Jit, PowWithADefdExponentIsTheInterpretersBits) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    const float exponents[] = {1.0f, 2.0f, 3.0f, 5.0f, 32.0f, 255.0f, 256.0f, 257.0f, 0.5f, -2.0f, 0.0f, 2.5f,
                               std::numeric_limits<float>::quiet_NaN()};
    Random random(41);
    std::uniform_real_distribution<float> ordinary(0.01f, 1.5f);
    unsigned decided_batches = 0, undecided_batches = 0;
    for (const ShaderType type : {ShaderType::Pixel, ShaderType::Vertex})
        for (const float exponent : exponents)
            for (const bool fast : {false, true})
                for (const bool negate : {false, true}) {
                    const emu::Executable executable =
                        pow_by_def(type, exponent, negate, fast, static_cast<uint8_t>(1 + pick(random, 15)));
                    std::string error;
                    const auto compiled = emu::jit::compile(executable, &error);
                    ASSERT_NE(compiled, nullptr) << error;
                    const emu::ConstantFile constants = executable.bind_constants();
                    for (unsigned b = 0; b < 24; ++b) {
                        auto input = std::make_unique<emu::Batch>();
                        randomize(*input, random, 1);
                        input->killed = 0;
                        input->lane_count = emu::kBatchLanes;
                        // A third of the batches ordinary finite values (the squarings decide them), a
                        // third with one lane a squaring tie, a third with special values (NaN among them).
                        emu::FloatLanes& bases = input->registers[executable.steps()[0].sources[0].index][0];
                        for (float& base : bases) base = b % 3 == 2 ? special_float(random) : ordinary(random);
                        const float tie = 1.0f + static_cast<float>(1 + pick(random, 64)) * 0x1p-12f;
                        if (b % 3 == 1) bases[pick(random, emu::kBatchLanes)] = tie;
                        emu::FloatLanes squared;
                        if (exponent == std::trunc(exponent) && exponent >= 1.0f && exponent <= 256.0f)
                            ++(emu::numerics::pow_float_integer(bases, static_cast<unsigned>(exponent), squared)
                                   ? decided_batches
                                   : undecided_batches);
                        auto by_interpreter = std::make_unique<emu::Batch>(*input);
                        auto by_jit = std::make_unique<emu::Batch>(*input);
                        emu::execute(executable, constants, *by_interpreter, nullptr);
                        compiled->run(constants, *by_jit, nullptr);
                        ASSERT_TRUE(same_batches(*by_interpreter, *by_jit))
                            << (type == ShaderType::Pixel ? "pixel" : "vertex") << " routine, exponent " << exponent
                            << (negate ? " (a negated def)" : "") << (fast ? " (fast)" : "") << ", batch " << b;
                    }
                }
    // Both blocks ran: every integer exponent's batches of ordinary values are decided inline.
    EXPECT_GT(undecided_batches, 20u);
    EXPECT_LT(undecided_batches, decided_batches);
}

#ifdef SM2_TEST_NATIVE_KERNELS
// The interpreter's kernel of `op` (step_kernels.h, compiled by this build's compiler) in the
// native kernels' form.
template <Opcode op, bool fast>
void interpreter_kernel(float* result, const float* a, const float* b, const float* c, unsigned mask) {
    using Vector = emu::kernels::Vector<float>;
    emu::kernels::compute<float, op, fast>(*reinterpret_cast<Vector*>(result), *reinterpret_cast<const Vector*>(a),
                                           *reinterpret_cast<const Vector*>(b), *reinterpret_cast<const Vector*>(c),
                                           mask);
}

// Every x86-64 level's native kernels (what the JIT calls out of line: native_kernels.h) on
// random special values and masks: each channel the mask writes is the interpreter's bits (any
// NaN for a NaN: the store canonicalizes it). Levels this CPU lacks are skipped.
TEST(Jit, NativeKernelsOfEveryLevelAreTheInterpretersBits) {
    struct Reference {
        const char* name;
        emu::jit::ArithmeticKernel function;
    };
    static constexpr Reference kReferences[] = {
#define SM2_REFERENCE(name)                                            \
    {"sm2_k_" #name, &interpreter_kernel<Opcode::name, false>},        \
        {"sm2_k_" #name "_fast", &interpreter_kernel<Opcode::name, true>},
        SM2_ARITHMETIC_STEPS(SM2_REFERENCE)
#undef SM2_REFERENCE
    };
    struct Level {
        const char* name;
        bool runs;
        std::span<const emu::jit::NativeKernel> kernels;
    };
    __builtin_cpu_init();
    const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                    __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
                    __builtin_cpu_supports("avx512cd");
    const Level levels[] = {
        {"x86-64", true, {sm2_kernels_x86_64::native_kernels, sm2_kernels_x86_64::native_kernel_count}},
        {"x86-64-v3", v3, {sm2_kernels_x86_64_v3::native_kernels, sm2_kernels_x86_64_v3::native_kernel_count}},
        {"x86-64-v4", v4, {sm2_kernels_x86_64_v4::native_kernels, sm2_kernels_x86_64_v4::native_kernel_count}},
    };
    using Vector = emu::kernels::Vector<float>;
    Random random(29);
    for (const Level& level : levels) {
        ASSERT_EQ(level.kernels.size(), std::size(kReferences)) << level.name;
        if (!level.runs) {
            std::printf("[ jit      ] native kernels for %s: not run on this CPU\n", level.name);
            continue;
        }
        for (size_t k = 0; k < level.kernels.size(); ++k) {
            const emu::jit::NativeKernel& kernel = level.kernels[k];
            ASSERT_STREQ(kernel.name, kReferences[k].name) << level.name;
            for (unsigned round = 0; round < 64; ++round) {
                Vector sources[3];
                for (Vector& source : sources)
                    for (auto& component : source)
                        for (float& value : component) value = special_float(random);
                const unsigned mask = 1 + pick(random, 15);
                Vector native{};
                Vector reference{};
                kernel.function(native[0].data(), sources[0][0].data(), sources[1][0].data(), sources[2][0].data(),
                                mask);
                kReferences[k].function(reference[0].data(), sources[0][0].data(), sources[1][0].data(),
                                        sources[2][0].data(), mask);
                for (unsigned c = 0; c < 4; ++c) {
                    if ((mask & (1u << c)) == 0) continue;
                    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                        const float got = native[c][l];
                        const float want = reference[c][l];
                        if (std::isnan(got) && std::isnan(want)) continue;
                        ASSERT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(want))
                            << level.name << " " << kernel.name << ", mask " << mask << ", channel " << c << ", lane "
                            << l << ": " << got << " against the interpreter's " << want << " (sources "
                            << sources[0][c][l] << ", " << sources[1][c][l] << ", " << sources[2][c][l] << ")";
                    }
                }
            }
        }
    }
}
#endif

// The time per batch of the interpreter and of the compiled code on the longer sample shaders
// (printed, not asserted; the best of several rounds, one thread).
TEST(Jit, SampleShaderSpeed) {
    if (!emu::jit::available()) GTEST_SKIP() << "built without the JIT";
    Random random(7);
    for (const auto& file : sample_shaders()) {
        const isa::Program program = assemble_or_fail(read_text(file));
        for (const SampleMode& mode : {kSampleModes[0], kSampleModes[1], kSampleModes[2]}) {
            emu::LoweringOptions options;
            options.precision = mode.precision;
            const emu::Executable executable = lower_or_fail(program, {}, options);
            if (executable.steps().size() < 10) continue;
            const auto compiled = emu::jit::compile(executable);
            ASSERT_NE(compiled, nullptr);
            const emu::ConstantFile constants =
                executable.bind_constants(std::vector<Float4>(256, Float4{0.5f, 0.25f, 0.125f, 1.0f}));
            auto input = std::make_unique<emu::Batch>();
            realistic_inputs(*input, random);
            auto batch = std::make_unique<emu::Batch>(*input);
            RecordingSampler sampler;
            auto time = [&](auto&& run) {
                using Clock = std::chrono::steady_clock;
                constexpr int kRuns = 100;
                double best = std::numeric_limits<double>::infinity();
                for (int round = 0; round < 7; ++round) {
                    *batch = *input;
                    const auto start = Clock::now();
                    for (int i = 0; i < kRuns; ++i) run();
                    best =
                        std::min(best, std::chrono::duration<double, std::nano>(Clock::now() - start).count() / kRuns);
                    sampler.requests.clear();
                }
                return best;
            };
            const double interpreted = time([&] { emu::execute(executable, constants, *batch, &sampler); });
            const double jitted = time([&] { compiled->run(constants, *batch, &sampler); });
            std::printf(
                "[ jit      ] %-22s %-9s %3zu steps: interpreter %7.0f ns/batch, jit %6.0f ns/batch (x%.1f), "
                "compiled in %.1f ms\n",
                file.filename().string().c_str(), mode.name, executable.steps().size(), interpreted, jitted,
                interpreted / jitted, 1e3 * compiled->compile_seconds());
        }
    }
}

}  // namespace
}  // namespace sm2::test
