// execute() with a step observer (what sm2 run --trace uses): called once per step, in order,
// with the batch as that step left it.
#include <vector>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

TEST(StepObserver, SeesEveryStepInOrderWithItsResult) {
    const auto exe = lower_or_fail(assemble_or_fail(R"(
        vs_2_0
        dcl_position v0
        add r0, v0, c0
        mul oPos, r0, c1
    )"));
    auto constants = exe.bind_constants(std::vector<std::array<float, 4>>{{2, 2, 2, 2}, {4, 4, 4, 4}});
    auto batch = std::make_unique<emu::Batch>();
    batch->broadcast(batch->input(0), 1, 2, 3, 1);
    std::vector<size_t> seen;
    std::vector<float> r0x, pos_x;
    emu::execute(exe, constants, *batch, nullptr, [&](size_t index, const emu::Step&) {
        seen.push_back(index);
        r0x.push_back(batch->temp(0)[0][0]);
        pos_x.push_back(batch->position()[0][0]);
    });
    ASSERT_EQ(seen, (std::vector<size_t>{0, 1}));
    // after step 0: r0.x = v0.x + c0.x = 1 + 2 = 3, oPos.x still its initial 0
    EXPECT_EQ(r0x[0], 3.0f);
    EXPECT_EQ(pos_x[0], 0.0f);
    // after step 1: oPos.x = r0.x * c1.x = 3 * 4 = 12
    EXPECT_EQ(pos_x[1], 12.0f);
}

}  // namespace
}  // namespace sm2::test
