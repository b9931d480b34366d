// texkill R (ps_2_0): a lane is discarded when any tested component is below zero; discarded
// lanes keep running as helpers.
#include <gtest/gtest.h>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

emu::LaneMask killed_by(std::initializer_list<Float4> per_lane, Dst tested = td(0)) {
    ProgramBuilder p(ShaderType::Pixel);
    p.texkill(tested).op(Opcode::Mov, oC(0), {c(0)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    batch.broadcast(batch.texcoord(0), 1, 1, 1, 1);
    batch.broadcast(batch.temp(2), 1, 1, 1, 1);
    unsigned lane = 0;
    for (const Float4& value : per_lane) {
        batch.set(batch.texcoord(0), lane, value[0], value[1], value[2], value[3]);
        batch.set(batch.temp(2), lane, value[0], value[1], value[2], value[3]);
        ++lane;
    }
    emu::execute(exe, exe.bind_constants(), batch);
    return batch.killed;
}

TEST(Texkill, AnyNegativeComponentKills) {
    EXPECT_EQ(killed_by({{1, 1, 1, 1}, {-1, 1, 1, 1}, {1, -1, 1, 1}, {1, 1, -1, 1}, {1, 1, 1, -1}}), 0b11110u);
}

TEST(Texkill, ZeroNegativeZeroAndNaNDoNotKill) {
    EXPECT_EQ(killed_by({{0, 0, 0, 0}, {-0.0f, -0.0f, -0.0f, -0.0f}, {kNaN, kNaN, kNaN, kNaN}, {-1e-40f, 1, 1, 1}}), 0b1000u);
}

TEST(Texkill, InfinityKillsWhenNegative) {
    EXPECT_EQ(killed_by({{-kInf, 1, 1, 1}, {kInf, kInf, kInf, kInf}}), 0b01u);
}

TEST(Texkill, TempRegistersToo) {
    EXPECT_EQ(killed_by({{1, 1, 1, 1}, {1, -0.5f, 1, 1}}, rd(2)), 0b10u);
}

TEST(Texkill, OnlyTheComponentsOfTheMaskAreTested) {
    // "texkill t0.xyz" (as Wine writes it): w is not tested
    EXPECT_EQ(killed_by({{1, 1, 1, -1}, {1, 1, -1, 1}}, td(0).mask("xyz")), 0b10u);
}

}  // namespace
}  // namespace sm2::test
