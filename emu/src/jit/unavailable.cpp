// The JIT in a build without LLVM (SM2_JIT=OFF): nothing compiles, callers use the interpreter.
#include <stdexcept>

#include "sm2/emu/jit.h"

namespace sm2::emu::jit {

struct CompiledShader::Code {};

CompiledShader::CompiledShader(std::shared_ptr<Code> code, uintptr_t entry, unsigned constant_count, size_t step_count,
                               double compile_seconds)
    : code_(std::move(code)),
      entry_(entry),
      constant_count_(constant_count),
      step_count_(step_count),
      compile_seconds_(compile_seconds) {}

CompiledShader::~CompiledShader() = default;

void CompiledShader::run(const ConstantFile&, Batch&, Sampler*) const {
    throw std::logic_error("sm2 was built without the JIT (SM2_JIT=OFF)");
}

bool available() { return false; }

namespace {
const char* const kNoJit = "jit: sm2 was built without the JIT (SM2_JIT=OFF: no LLVM 14 / clang++-14)";
}  // namespace

std::shared_ptr<const CompiledShader> compile(const Executable&, std::string* error) {
    if (error != nullptr) *error = kNoJit;
    return nullptr;
}

std::vector<std::shared_ptr<const CompiledShader>> compile_all(std::span<const Executable* const>, std::string* error) {
    if (error != nullptr) *error = kNoJit;
    return {};
}

}  // namespace sm2::emu::jit
