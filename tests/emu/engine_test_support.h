// Helpers shared by the engine and conformance tests: lower a program (failing the test on an
// error), and run one instruction with constant operands.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "emu/program_builder.h"
#include "sm2/assembler/assembler.h"
#include "sm2/emu/engine.h"

namespace sm2::test {

using emu::Float4;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kFltMax = std::numeric_limits<float>::max();

inline emu::Executable lower_or_fail(const isa::Program& program, const emu::StaticFlowConstants& flow = {},
                                     const emu::LoweringOptions& options = {}) {
    auto shader = emu::Shader::create(program);
    EXPECT_TRUE(shader.shader.has_value()) << shader.error;
    if (!shader.shader) return emu::Executable({}, emu::Precision::Fp32, 0, {}, {}, 0);
    auto lowered = emu::lower(*shader.shader, flow, options);
    EXPECT_TRUE(lowered.executable.has_value()) << lowered.error;
    if (!lowered.executable) return emu::Executable({}, emu::Precision::Fp32, 0, {}, {}, 0);
    return std::move(*lowered.executable);
}

// Assembly text -> Program (without validation, so tests can state any program).
inline isa::Program assemble_or_fail(std::string_view text) {
    assembler::AssembleOptions options;
    options.validate = false;
    auto result = assembler::assemble(text, options);
    EXPECT_TRUE(result.ok()) << text;
    for (const auto& d : result.diagnostics) ADD_FAILURE() << d.to_string();
    return result.program.value_or(isa::Program{});
}

inline std::string lowering_error(const isa::Program& program, const emu::StaticFlowConstants& flow = {},
                                  const emu::LoweringOptions& options = {}) {
    auto shader = emu::Shader::create(program);
    if (!shader.shader) return shader.error;
    auto lowered = emu::lower(*shader.shader, flow, options);
    return lowered.executable ? std::string() : lowered.error;
}

template <typename Register>
Float4 lane_value(const Register& reg, unsigned lane = 0) {
    return {static_cast<float>(reg[0][lane]), static_cast<float>(reg[1][lane]),
            static_cast<float>(reg[2][lane]), static_cast<float>(reg[3][lane])};
}

// Bitwise equality, so that -0 differs from +0 and NaN equals NaN.
inline bool same_bits(float a, float b) {
    if (std::isnan(a) && std::isnan(b)) return true;
    uint32_t x, y;
    std::memcpy(&x, &a, 4);
    std::memcpy(&y, &b, 4);
    return x == y;
}

#define EXPECT_FLOAT4_EQ(actual, ex, ey, ez, ew)                                  \
    do {                                                                         \
        const ::sm2::emu::Float4 value_ = (actual);                              \
        const ::sm2::emu::Float4 expected_{ex, ey, ez, ew};                      \
        for (int k_ = 0; k_ < 4; ++k_)                                           \
            EXPECT_TRUE(::sm2::test::same_bits(value_[k_], expected_[k_]))       \
                << "component " << "xyzw"[k_] << ": got " << value_[k_]          \
                << ", expected " << expected_[k_];                               \
    } while (0)

#define EXPECT_FLOAT4_NEAR(actual, ex, ey, ez, ew, tolerance)                     \
    do {                                                                         \
        const ::sm2::emu::Float4 value_ = (actual);                              \
        const ::sm2::emu::Float4 expected_{ex, ey, ez, ew};                      \
        for (int k_ = 0; k_ < 4; ++k_)                                           \
            EXPECT_NEAR(value_[k_], expected_[k_], tolerance) << "component " << "xyzw"[k_]; \
    } while (0)

// The value r0 holds after one instruction. Sources are usually constants c0..c3 whose values
// are `constants`; r0 starts as `initial` (9, 9, 9, 9 by default) in every lane so write masks
// show. Without an explicit `shader`, the instruction runs in every shader type whose 2.0
// profile allows it (the opcode table says which), and in the default fp32 mode all of them must
// give the same bits; with `shader`, or another precision, it runs in that type (vertex by
// default) only.
struct OneInstruction {
    std::optional<ShaderType> shader;
    emu::PrecisionOptions precision{};
    Float4 initial{9.0f, 9.0f, 9.0f, 9.0f};
};

inline Float4 run_instruction_in(ShaderType type, Opcode opcode, Dst destination, std::initializer_list<Src> sources,
                                 const std::vector<Float4>& constants, const OneInstruction& how) {
    ProgramBuilder p(type);
    p.op(opcode, destination, sources);
    emu::LoweringOptions options;
    options.keep_dead_code = true;
    options.precision = how.precision;
    const emu::Executable exe = lower_or_fail(p.program(), {}, options);
    const emu::ConstantFile file = exe.bind_constants(constants);
    emu::Batch batch;
    batch.broadcast(batch.temp(0), how.initial[0], how.initial[1], how.initial[2], how.initial[3]);
    emu::execute(exe, file, batch);
    const Float4 first = lane_value(batch.temp(0), 0);
    // Constant operands: every lane computes the same value.
    for (unsigned lane = 1; lane < emu::kBatchLanes; ++lane) {
        const Float4 other = lane_value(batch.temp(0), lane);
        for (int k = 0; k < 4; ++k) EXPECT_TRUE(same_bits(first[k], other[k])) << "lane " << lane;
    }
    return first;
}

inline Float4 run_instruction(Opcode opcode, Dst destination, std::initializer_list<Src> sources,
                              const std::vector<Float4>& constants, const OneInstruction& how = {}) {
    if (how.shader) return run_instruction_in(*how.shader, opcode, destination, sources, constants, how);
    const isa::OpcodeInfo* row = isa::find_opcode(opcode);
    const bool in_vs = row && row->allowed_in({ShaderType::Vertex, 2, 0});
    const bool in_ps = row && row->allowed_in({ShaderType::Pixel, 2, 0});
    const emu::PrecisionOptions fp32{};
    const bool default_mode = how.precision.precision == fp32.precision &&
                              how.precision.transcendentals == fp32.transcendentals &&
                              !how.precision.partial_precision_fp16;
    if (!in_ps || (!default_mode && in_vs))
        return run_instruction_in(ShaderType::Vertex, opcode, destination, sources, constants, how);
    const Float4 pixel = run_instruction_in(ShaderType::Pixel, opcode, destination, sources, constants, how);
    if (in_vs) {
        const Float4 vertex = run_instruction_in(ShaderType::Vertex, opcode, destination, sources, constants, how);
        for (int k = 0; k < 4; ++k)
            EXPECT_TRUE(same_bits(vertex[k], pixel[k]))
                << "vs and ps differ in component " << k << ": " << vertex[k] << " vs " << pixel[k];
    }
    return pixel;
}

}  // namespace sm2::test
