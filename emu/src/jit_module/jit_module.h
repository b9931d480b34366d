// The JIT as a module loaded on first use.
//
// LLVM is one shared library of ~100 MB whose 366,000 relocations and static constructors cost
// every process that links it ~20 ms at start-up: `sm2 asm` must not pay for them. So the JIT
// (emu/src/jit/compiler.cpp and its kernels, the only code that calls LLVM) is built as the
// module sm2emu_jit.so, and sm2_emu holds a forwarder (loader.cpp) that implements jit.h by
// dlopen()ing it on the first jit::available() or jit::compile(). The module exports one
// symbol, a table of the jit.h functions as compiled inside it (hidden visibility: its copies
// and the forwarder's never meet). kAbiVersion changes whenever the table does.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sm2/emu/jit.h"

namespace sm2::emu::jit::module {

constexpr uint32_t kAbiVersion = 2;  // 2: CompiledShader holds its callback and runs inline

struct Functions {
    uint32_t abi_version;
    uint32_t size;  // sizeof(Functions)
    bool (*available)();
    std::shared_ptr<const CompiledShader> (*compile)(const Executable& executable, std::string* error);
    std::vector<std::shared_ptr<const CompiledShader>> (*compile_all)(std::span<const Executable* const> executables,
                                                                      std::string* error);
};

}  // namespace sm2::emu::jit::module

extern "C" const sm2::emu::jit::module::Functions* sm2emu_jit_v1();
