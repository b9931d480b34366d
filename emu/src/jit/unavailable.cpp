// The JIT in a build without LLVM (SM2_JIT=OFF): nothing compiles, callers use the interpreter.
#include "sm2/emu/jit.h"

namespace sm2::emu::jit {

struct CompiledShader::Code {};

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
