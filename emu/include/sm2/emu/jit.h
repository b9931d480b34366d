// The JIT: an Executable compiled to one native function (LLVM ORC) that runs its steps over a
// Batch exactly as the interpreter does: the same kernels (the lane loops of every step are
// compiled from the interpreter's own source, step_kernels.h), so every register, a0 and the
// killed mask come out bit-identical, special values included.
//
//   std::string error;
//   auto compiled = jit::compile(executable, &error);   // once per executable
//   if (compiled) compiled->run(constants, batch, &sampler); else execute(executable, ...);
//
// A compiled shader keeps constants as a run-time argument, so one compilation serves every draw
// of its executable. Any number of threads may run it at once, each with its own Batch.
// Only float executables (fp32, fp24, fp16 rounding) compile; the fp64 reference mode stays in
// the interpreter. Compiling costs milliseconds (a few for a short shader, 50-150 ms for 50
// steps): worth it for an executable that runs many batches.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/emu/executable.h"
#include "sm2/emu/sampler.h"

namespace sm2::emu::jit {

// True when the engine was built with LLVM (CMake option SM2_JIT) and the host target could be
// set up; compile() returns null otherwise.
[[nodiscard]] bool available();

class CompiledShader {
public:
    struct Code;  // the machine code of the shaders compiled together (opaque), freed with the last
    // The compiled function, (Batch*, constant registers, constant count, Sampler*, texld callback),
    // and the callback's signature (the module's sample_callback: Sampler::sample).
    using SampleFunction = void (*)(void* sampler, unsigned sampler_index, unsigned variant, unsigned lane_count,
                                    uint32_t killed, const float* coordinates, float* texels);
    using Entry = void (*)(void* batch, const float* constants, int64_t constant_count, void* sampler,
                           SampleFunction sample);
    // (made by compile() and compile_all())
    CompiledShader(std::shared_ptr<Code> code, Entry entry, SampleFunction sample, unsigned constant_count,
                   size_t step_count, double compile_seconds, bool from_cache = false)
        : code_(std::move(code)), entry_(entry), sample_(sample), constant_count_(constant_count),
          step_count_(step_count), compile_seconds_(compile_seconds), from_cache_(from_cache) {}
    ~CompiledShader() = default;
    CompiledShader(const CompiledShader&) = delete;
    CompiledShader& operator=(const CompiledShader&) = delete;

    // What execute() does for the executable it was compiled from: every step over all lanes of
    // `batch`, with the same outputs, a0 and killed lanes. The temporaries r# stay in the
    // compiled code's registers: the batch's temps keep what they held (a temp the shader reads
    // before writing it, which the validator refuses, starts as the batch holds it).
    // `sampler` may be null (texld then reads (0,0,0,1)); an exception it throws reaches the
    // caller. std::invalid_argument when the constant file is smaller than the executable's
    // constant count.
    // (Inline, the compiled function called directly: through the module's forwarder it was two
    // calls and a guarded static a batch, 2% of scene 13's profile.)
    void run(const ConstantFile& constants, Batch& batch, Sampler* sampler = nullptr) const {
        if (constants.registers.size() < constant_count_) too_few_constants(constants.registers.size());
        const float* registers = constants.registers.empty() ? nullptr : constants.registers.front().data();
        entry_(&batch, registers, static_cast<int64_t>(constants.registers.size()), sampler, sample_);
    }

    // Wall time the compilation took (kernels, code generation, optimization, machine code); for
    // shaders compiled together by compile_all(), the time of the whole group.
    [[nodiscard]] double compile_seconds() const { return compile_seconds_; }
    [[nodiscard]] size_t step_count() const { return step_count_; }
    // Whether the machine code came from the JIT cache (SM2_JIT_CACHE, below) instead of LLVM's
    // optimizer and code generator.
    [[nodiscard]] bool from_cache() const { return from_cache_; }

private:
    [[noreturn, gnu::cold, gnu::noinline]] void too_few_constants(size_t registers) const {
        throw std::invalid_argument("the constant file has " + std::to_string(registers) +
                                    " registers, the executable reads up to " + std::to_string(constant_count_) +
                                    " (use Executable::bind_constants)");
    }

    std::shared_ptr<Code> code_;
    Entry entry_;
    SampleFunction sample_;
    unsigned constant_count_;
    size_t step_count_;
    double compile_seconds_;
    bool from_cache_;
};

// Compiles `executable` for the host CPU. Null on failure (fp64 executable, no JIT in this
// build, an LLVM error), with the reason in *error when given. Thread-safe.
[[nodiscard]] std::shared_ptr<const CompiledShader> compile(const Executable& executable,
                                                            std::string* error = nullptr);

// The JIT cache: where the environment variable SM2_JIT_CACHE names a directory (made if
// missing), compile() and compile_all() keep each group's machine code there under a hash of
// everything it is made from (the shaders' IR before optimization, the JIT module's build (its
// code and kernels), LLVM's version, the host CPU and its features), and a later compilation of the
// same group, in this process or another, loads it instead of running LLVM's optimizer and code
// generator: the same machine code, so the same results. A file that does not hold what it
// should (its checksum) is compiled again and replaced. Nothing is read or written anywhere
// when the variable is unset or empty. The folder's files are machine code this process runs:
// name only a folder that others cannot write (as for the module SM2EMU_JIT names).

// Several executables at once (a pipeline's vertex and pixel shaders, a cache warming up): one
// LLVM module, so the fixed cost of a compilation is paid once. One compiled shader per
// executable, in order; empty on failure (with the reason in *error).
[[nodiscard]] std::vector<std::shared_ptr<const CompiledShader>> compile_all(
    std::span<const Executable* const> executables, std::string* error = nullptr);

}  // namespace sm2::emu::jit
