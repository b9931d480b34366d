// The JIT module's one exported symbol (jit_module.h): the jit.h functions compiled in it.
#include "jit_module.h"

namespace {

using namespace sm2::emu;

std::shared_ptr<const jit::CompiledShader> compile(const Executable& executable, std::string* error) {
    return jit::compile(executable, error);
}

std::vector<std::shared_ptr<const jit::CompiledShader>> compile_all(std::span<const Executable* const> executables,
                                                                    std::string* error) {
    return jit::compile_all(executables, error);
}

constexpr jit::module::Functions kFunctions{jit::module::kAbiVersion, sizeof(jit::module::Functions),
                                            &jit::available, &compile, &compile_all};

}  // namespace

extern "C" __attribute__((visibility("default"))) const jit::module::Functions* sm2emu_jit_v1() { return &kFunctions; }
