// mova a0.mask, s (vs_2_0): a0.c = round to nearest (halves away from zero), seen through
// relative constant reads c[a0.c + n].
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

// mova a0.<component>, c0.<component>; mov r0, c[a0.<component> + 10]; c_k = (k, k, k, k)
float addressed_index(float value, char component = 'x') {
    ProgramBuilder p(ShaderType::Vertex);
    const std::string single(1, component);
    p.op(Opcode::Mova, a0().mask(single), {c(0).swz(single)}).op(Opcode::Mov, oPos(), {c(10).rel_a0(component)});
    const auto exe = lower_or_fail(p.program());
    std::vector<Float4> constants(256);
    for (unsigned k = 1; k < 256; ++k) constants[k] = {static_cast<float>(k), 0, 0, 1};
    constants[0] = {value, value, value, value};
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(constants), batch);
    return batch.position()[0][0] - 10.0f;  // the rounded address
}

TEST(Mova, RoundsToNearest) {
    EXPECT_EQ(addressed_index(0.0f), 0.0f);
    EXPECT_EQ(addressed_index(1.4f), 1.0f);
    EXPECT_EQ(addressed_index(1.6f), 2.0f);
    EXPECT_EQ(addressed_index(-1.4f), -1.0f);
    EXPECT_EQ(addressed_index(-1.6f), -2.0f);
    EXPECT_EQ(addressed_index(7.0f), 7.0f);
}

TEST(Mova, HalvesRoundAwayFromZero) {
    EXPECT_EQ(addressed_index(0.5f), 1.0f);
    EXPECT_EQ(addressed_index(2.5f), 3.0f);
    EXPECT_EQ(addressed_index(-0.5f), -1.0f);
    EXPECT_EQ(addressed_index(-2.5f), -3.0f);
}

TEST(Mova, EveryComponentOfA0) {
    EXPECT_EQ(addressed_index(3.2f, 'y'), 3.0f);
    EXPECT_EQ(addressed_index(4.5f, 'z'), 5.0f);
    EXPECT_EQ(addressed_index(-5.7f, 'w'), -6.0f);
}

TEST(Mova, OutOfRangeReadsZero) {
    // -10.6 -> -11: c[-1] does not exist; 300 -> c310 does not exist; NaN has no address
    EXPECT_EQ(addressed_index(-10.6f), -10.0f);  // x of (0,0,0,0) minus the offset 10
    EXPECT_EQ(addressed_index(300.0f), -10.0f);
    EXPECT_EQ(addressed_index(kNaN), -10.0f);
    EXPECT_EQ(addressed_index(kInf), -10.0f);
}

TEST(Mova, NegatedSwizzledSourceAndSeveralComponents) {
    ProgramBuilder p(ShaderType::Vertex);
    // a0.xz = round(-c0.yyww) = (round(-1.5), _, round(-(-3.5)), _) = (-2, _, 4, _)
    p.op(Opcode::Mova, a0().mask("xz"), {c(0).swz("yyww").neg()})
        .op(Opcode::Add, oPos(), {c(12).rel_a0('x'), c(20).rel_a0('z')});
    const auto exe = lower_or_fail(p.program());
    std::vector<Float4> constants(256);
    for (unsigned k = 1; k < 256; ++k) constants[k] = {static_cast<float>(k), 0, 0, 0};
    constants[0] = {0, 1.5f, 0, -3.5f};
    emu::Batch batch;
    emu::execute(exe, exe.bind_constants(constants), batch);
    EXPECT_EQ(batch.position()[0][3], 10.0f + 24.0f);  // c10 + c24
}

}  // namespace
}  // namespace sm2::test
