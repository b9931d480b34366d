// The arithmetic kernels of kernels.cpp compiled ahead of time, once per x86-64 level
// (emu/CMakeLists.txt), for the kernels the JIT calls out of line rather than inlines
// (compiler.cpp's call_shared): the same source and flags as the bitcode, so the same results,
// and no process spends its first routines' compile on them.
#pragma once

#include <cstddef>

namespace sm2::emu::jit {

// sm2_k_<Opcode>[_fast](result, a, b, c, mask): kernels.cpp's arithmetic kernels.
using ArithmeticKernel = void (*)(float* result, const float* a, const float* b, const float* c, unsigned mask);

struct NativeKernel {
    const char* name;  // the kernel's name in the bitcode, e.g. "sm2_k_Exp"
    ArithmeticKernel function;
};

}  // namespace sm2::emu::jit

// One table per level, each in the namespace its object was compiled with (SM2_KERNEL_INSTANCE).
#define SM2_NATIVE_KERNEL_TABLE(level)                                    \
    namespace level {                                                     \
    extern const sm2::emu::jit::NativeKernel native_kernels[];            \
    extern const std::size_t native_kernel_count;                         \
    }
SM2_NATIVE_KERNEL_TABLE(sm2_kernels_x86_64)
SM2_NATIVE_KERNEL_TABLE(sm2_kernels_x86_64_v3)
SM2_NATIVE_KERNEL_TABLE(sm2_kernels_x86_64_v4)
#undef SM2_NATIVE_KERNEL_TABLE
