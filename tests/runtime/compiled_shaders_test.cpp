// The draw's cache of compiled shaders: the compiled code reads def'd registers as constants of
// its own (jit/compiler.cpp), so two shaders with the same steps and other def values must not
// share it, and each must give the interpreter's bits.
#include <gtest/gtest.h>

#include <bit>
#include <string>

#include "compiled_shaders.h"
#include "sm2/assembler/assembler.h"
#include "sm2/emu/engine.h"

namespace sm2::runtime {
namespace {

emu::Executable lowered(const std::string& text) {
    auto assembled = assembler::assemble(text);
    EXPECT_TRUE(assembled.ok()) << text;
    auto shader = emu::Shader::create(assembled.program.value_or(isa::Program{}));
    EXPECT_TRUE(shader.shader.has_value()) << shader.error;
    auto result = emu::lower(*shader.shader, {}, {});
    EXPECT_TRUE(result.executable.has_value()) << result.error;
    return std::move(*result.executable);
}

std::string shader_with(const std::string& def) {
    return "ps_2_0\n" + def +
           "\ndcl t0\nmul r0, t0, c0\npow r1.x, t0.x, c0.z\nmad r0, r0, c0.y, r1.x\nmov oC0, r0\n";
}

TEST(CompiledShaders, DefValuesArePartOfTheKey) {
    const emu::Executable a = lowered(shader_with("def c0, 2, 0, 32, -1"));
    const emu::Executable b = lowered(shader_with("def c0, 3, 1, 5, 0.5"));
    ASSERT_TRUE(std::ranges::equal(a.steps(), b.steps()));  // only the def values differ
    const CompiledLookup first = compiled_shader(a);
    if (!first.shader) GTEST_SKIP() << "no JIT in this build or on this CPU";
    const CompiledLookup second = compiled_shader(b);
    ASSERT_NE(second.shader, nullptr);
    EXPECT_TRUE(second.compiled_now);
    EXPECT_NE(first.shader, second.shader);
    EXPECT_FALSE(compiled_shader(a).compiled_now);  // the same shader again is found

    for (const emu::Executable* exe : {&a, &b}) {
        const emu::ConstantFile constants = exe->bind_constants();
        const CompiledLookup lookup = compiled_shader(*exe);
        emu::Batch interpreted, compiled;
        const float inputs[] = {0.0f, -0.0f, 0.5f, -1.25f, 2.0f, 1e30f, -1e-30f, 3.0f,
                                0.75f, 1.0f, -2.0f, 0.1f, 7.0f, 0.9f, 1.1f, -0.3f};
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            for (unsigned c = 0; c < 4; ++c) {
                interpreted.texcoord(0)[c][l] = inputs[(l + c) % 16];
                compiled.texcoord(0)[c][l] = inputs[(l + c) % 16];
            }
        emu::execute(*exe, constants, interpreted);
        lookup.shader->run(constants, compiled, nullptr);
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l)
                EXPECT_EQ(std::bit_cast<uint32_t>(interpreted.render_target(0)[c][l]),
                          std::bit_cast<uint32_t>(compiled.render_target(0)[c][l]))
                    << "component " << c << " lane " << l;
    }
    // c0.x = 2 against 3 on lane 2's t0.x = 0.5, and pow(0.5, 32) against pow(0.5, 5):
    // r0.x = 0.5 * 2 * 0 + 0.5^32 for a, 0.5 * 3 * 1 + 0.5^5 for b.
    emu::Batch batch_a, batch_b;
    for (unsigned c = 0; c < 4; ++c) {
        batch_a.texcoord(0)[c].fill(0.5f);
        batch_b.texcoord(0)[c].fill(0.5f);
    }
    compiled_shader(a).shader->run(a.bind_constants(), batch_a, nullptr);
    compiled_shader(b).shader->run(b.bind_constants(), batch_b, nullptr);
    EXPECT_EQ(batch_a.render_target(0)[0][0], 0x1p-32f);
    EXPECT_EQ(batch_b.render_target(0)[0][0], 1.5f + 0x1p-5f);
}

}  // namespace
}  // namespace sm2::runtime
