// execute() with a step observer (what sm2 run --trace uses): called once per step, in order,
// with the batch as that step left it.
#include <vector>

#include "emu/engine_test_support.h"
#include "sm2/emu/instruction_trace.h"

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

// trace_instructions (sm2 debug): one run per source instruction executed; values worked out by
// hand. v0 = (1, 2, 3, 1); c0..c3 are the rows (1,0,0,0) (0,1,0,0) (0,0,1,0) (1,1,1,1).
TEST(InstructionTrace, OneRunPerInstructionAndLoopIteration) {
    const auto program = assemble_or_fail(R"(
        vs_2_0
        defi i0, 2, 0, 0, 0
        def c10, 1, 1, 1, 1
        dcl_position v0
        mov r1, v0
        m4x4 r0, v0, c0
        rep i0
          add r1, r1, c10
        endrep
        mov a0.x, c10.x
        mov oPos, r0
    )");
    emu::LoweringOptions options;
    options.keep_dead_code = true;
    const auto exe = lower_or_fail(program, {}, options);
    auto constants = exe.bind_constants(
        std::vector<std::array<float, 4>>{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {1, 1, 1, 1}});
    auto batch = std::make_unique<emu::Batch>();
    batch->broadcast(batch->input(0), 1, 2, 3, 1);
    const auto trace = emu::trace_instructions(exe, constants, *batch, nullptr);
    // Instructions: 0 defi, 1 def, 2 dcl, 3 mov, 4 m4x4, 5 rep, 6 add, 7 endrep, 8 mov a0, 9 mov oPos.
    std::vector<uint32_t> order;
    for (const auto& run : trace) order.push_back(run.instruction);
    ASSERT_EQ(order, (std::vector<uint32_t>{3, 4, 6, 6, 8, 9}));
    // m4x4: one run, r0 written whole: (1, 2, 3, 1 + 2 + 3 + 1).
    ASSERT_EQ(trace[1].writes.size(), 1u);
    EXPECT_EQ(emu::slot_name(trace[1].writes[0].slot), "r0");
    EXPECT_EQ(trace[1].writes[0].mask, 0xF);
    EXPECT_EQ(trace[1].writes[0].lanes[0], (std::array<float, 4>{1, 2, 3, 7}));
    // The loop body, once per iteration: r1 = v0 + 1, then v0 + 2.
    EXPECT_EQ(trace[2].writes[0].lanes[0], (std::array<float, 4>{2, 3, 4, 2}));
    EXPECT_EQ(trace[3].writes[0].lanes[0], (std::array<float, 4>{3, 4, 5, 3}));
    // mova: a0.x = 1, read back as a float.
    ASSERT_EQ(trace[4].writes.size(), 1u);
    EXPECT_TRUE(trace[4].writes[0].address);
    EXPECT_EQ(trace[4].writes[0].mask, 0x1);
    EXPECT_EQ(trace[4].writes[0].lanes[0][0], 1.0f);
    EXPECT_EQ(trace[5].writes[0].lanes[15], (std::array<float, 4>{1, 2, 3, 7}));  // every lane
}

TEST(InstructionTrace, TexkillListsTheLanesItDiscarded) {
    const auto exe = lower_or_fail(assemble_or_fail(R"(
        ps_2_0
        dcl t0
        texkill t0
        mov oC0, t0
    )"));
    auto constants = exe.bind_constants({});
    auto batch = std::make_unique<emu::Batch>();
    batch->broadcast(batch->texcoord(0), 1, 1, 1, 1);
    batch->texcoord(0)[1][2] = -0.5f;  // lane 2: y < 0
    const auto trace = emu::trace_instructions(exe, constants, *batch, nullptr);
    ASSERT_EQ(trace.size(), 2u);
    EXPECT_TRUE(trace[0].texkill);
    EXPECT_EQ(trace[0].killed, emu::LaneMask{1} << 2);
    EXPECT_TRUE(trace[0].writes.empty());
    EXPECT_FALSE(trace[1].texkill);
}

}  // namespace
}  // namespace sm2::test
