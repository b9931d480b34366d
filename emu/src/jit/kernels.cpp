// The step kernels of step_kernels.h for float batches, as extern "C" functions with plain
// pointer and integer arguments. This file is not compiled into the library: the build turns
// it into LLVM bitcode (clang++-14 -emit-llvm, see emu/CMakeLists.txt) that is embedded in the
// library; the JIT (compiler.cpp) parses it into every module it builds and emits one call per
// kernel and step with the step's fields as constants, then inlines and optimizes it all for
// the host CPU. The interpreter runs the same templates, so both follow one description of
// every rule.
//
// Pointers: `batch` is a Batch (BasicBatch<float>); `dst`, `result`, `a`, `b`, `c` are
// kernels::Vector<float> scratch vectors (4 x kBatchLanes floats); `constants` is the
// ConstantFile's registers (4 floats each). The result is the JIT's own scratch vector, which
// no source overlaps; two sources may be the same register (a source fetched as it is is read
// in place, jit/compiler.cpp's emit_fetch), which __restrict allows for pointers only read.
// Hence __restrict: the lane loops vectorize without overlap checks.
//
// The same file is also compiled to native objects, once per x86-64 level, with
// SM2_KERNEL_INSTANCE naming a namespace of the level's own (emu/CMakeLists.txt): the kernels the
// JIT calls out of line (exact exp, log, pow, lit) run from there, so no process compiles them.
// There the functions are C++ names in that namespace, and the level's table of the arithmetic
// kernels (native_kernels.h) ends the file.
#include <cstdint>
#include <iterator>

#include "step_kernels.h"
#ifdef SM2_KERNEL_INSTANCE
#include "jit/native_kernels.h"
#endif

using sm2::emu::Batch;
using sm2::emu::LaneMask;
using sm2::emu::ResultRounding;
using sm2::isa::Opcode;
namespace k = sm2::emu::kernels;

static_assert(sm2::emu::kBatchLanes == 16, "emu/CMakeLists.txt vectorizes the lane loops at width 16");

namespace {

using Vector = k::Vector<float>;

Vector& vector(float* p) { return *reinterpret_cast<Vector*>(p); }
const Vector& vector(const float* p) { return *reinterpret_cast<const Vector*>(p); }
Batch& batch_of(void* p) { return *static_cast<Batch*>(p); }
const Batch& batch_of(const void* p) { return *static_cast<const Batch*>(p); }
const k::ConstantRegister* constant_registers(const float* p) {
    return reinterpret_cast<const k::ConstantRegister*>(p);
}

}  // namespace

// The sampling callback the JIT passes in: fills `texels` (4 x kBatchLanes) for `coordinates`.
using sm2_sample_fn = void (*)(void* sampler, unsigned sampler_index, unsigned variant, unsigned lane_count,
                               uint32_t killed, const float* coordinates, float* texels);

#ifdef SM2_KERNEL_INSTANCE
namespace SM2_KERNEL_INSTANCE {
#else
extern "C" {
#endif

// `reg`: a register of the batch, or a temporary the compiled code keeps to itself.
void sm2_k_fetch_register(float* __restrict dst, const float* __restrict reg, unsigned swizzle, unsigned negate,
                          unsigned channels) {
    k::fetch_register(vector(dst), vector(reg), swizzle, negate != 0, channels);
}

void sm2_k_fetch_constant(float* __restrict dst, const float* __restrict constants, unsigned index, unsigned swizzle,
                          unsigned negate, unsigned channels) {
    k::fetch_constant(vector(dst), constant_registers(constants)[index], swizzle, negate != 0, channels);
}

void sm2_k_fetch_relative(float* __restrict dst, const void* __restrict batch, const float* __restrict constants,
                          int64_t count, unsigned index, unsigned address_component, unsigned swizzle, unsigned negate,
                          unsigned channels) {
    k::fetch_relative(vector(dst), batch_of(batch), constant_registers(constants), count, index, address_component,
                      swizzle, negate != 0, channels);
}

void sm2_k_fetch_zero(float* __restrict dst, unsigned negate, unsigned channels) {
    k::fetch_zero(vector(dst), negate != 0, channels);
}

// sm2_k_Add(result, a, b, c, mask), sm2_k_Add_fast(...), ... for every arithmetic step.
#define SM2_KERNEL(name)                                                                                     \
    void sm2_k_##name(float* __restrict result, const float* __restrict a, const float* __restrict b,        \
                      const float* __restrict c, unsigned mask) {                                            \
        k::compute<float, Opcode::name, false>(vector(result), vector(a), vector(b), vector(c), mask);       \
    }                                                                                                        \
    void sm2_k_##name##_fast(float* __restrict result, const float* __restrict a, const float* __restrict b, \
                             const float* __restrict c, unsigned mask) {                                     \
        k::compute<float, Opcode::name, true>(vector(result), vector(a), vector(b), vector(c), mask);        \
    }
SM2_ARITHMETIC_STEPS(SM2_KERNEL)
#undef SM2_KERNEL

// 1 where pow_by_squaring() decided the batch for the exponent n (the JIT then skips pow's
// out-of-line series).
unsigned sm2_k_pow_by_squaring(float* __restrict result, const float* __restrict a, unsigned n, unsigned mask) {
    return k::pow_by_squaring(vector(result), vector(a), n, mask) ? 1u : 0u;
}

void sm2_k_mova(void* __restrict batch, const float* __restrict a, unsigned mask) {
    k::mova(batch_of(batch), vector(a), mask);
}

void sm2_k_texkill(void* __restrict batch, const float* __restrict a, unsigned tested) {
    k::texkill(batch_of(batch), vector(a), tested);
}

unsigned sm2_k_stop_after_texkill(const void* __restrict batch) {
    return k::stop_after_texkill(batch_of(batch)) ? 1u : 0u;
}

// (The batch is not __restrict here: the sampler is foreign code.)
void sm2_k_tex(float* __restrict result, const float* __restrict a, const void* batch, unsigned sampler_index,
               unsigned variant, void* sampler, sm2_sample_fn sample) {
    k::texture(vector(result), vector(a), batch_of(batch),
               [&](const k::Texels& coordinates, k::Texels& texels, unsigned lane_count, LaneMask killed) {
                   sample(sampler, sampler_index, variant, lane_count, killed, coordinates[0].data(), texels[0].data());
               });
}

void sm2_k_store_register(float* __restrict reg, float* __restrict result, unsigned mask, unsigned saturate,
                          unsigned rounding, unsigned canonical) {
    k::store_register(vector(reg), vector(result), mask, saturate != 0, static_cast<ResultRounding>(rounding),
                      canonical != 0);
}

}  // extern "C", or the level's namespace

#ifdef SM2_KERNEL_INSTANCE
namespace SM2_KERNEL_INSTANCE {
extern const sm2::emu::jit::NativeKernel native_kernels[] = {
#define SM2_KERNEL_ENTRY(name) {"sm2_k_" #name, &sm2_k_##name}, {"sm2_k_" #name "_fast", &sm2_k_##name##_fast},
    SM2_ARITHMETIC_STEPS(SM2_KERNEL_ENTRY)
#undef SM2_KERNEL_ENTRY
};
extern const std::size_t native_kernel_count = std::size(native_kernels);
}  // namespace SM2_KERNEL_INSTANCE
#endif
