// SetDeviceLimits: a stream carries the device it needs (the instruction-slot limit), so that it
// replays the same with no side file or flag.
#include <gtest/gtest.h>

#include <string>

#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace sm2::runtime {
namespace {

// A pixel shader of 65 arithmetic slots (one over ps_2_0's 64) as a heredoc.
std::string long_shader(const std::string& name) {
    std::string text = "CreatePixelShader " + name + " asm<<END\nps_2_0\ndef c0, 1, 1, 1, 1\nmov r0, c0\n";
    for (int i = 0; i < 63; ++i) text += "add r0, r0, c0\n";
    return text + "mov oC0, r0\nEND\n";
}

ReplayResult replay_text(const std::string& body, unsigned initial_slots = 0, Device* keep = nullptr) {
    auto parsed = cs::parse_text("sm2cs 1\n" + body);
    EXPECT_TRUE(parsed.ok()) << (parsed.error ? parsed.error->to_string() : "");
    DeviceOptions options;
    options.max_instruction_slots = initial_slots;
    Device device(options);
    ReplayOptions replay_options;
    replay_options.assembler = stream_assembler();
    auto result = replay(keep ? *keep : device, *parsed.stream, replay_options);
    return result;
}

TEST(DeviceLimits, RaiseTheSlotLimitForLaterShaders) {
    // Before SetDeviceLimits the long shader is refused, after it accepted.
    auto r = replay_text(long_shader("a") + "SetDeviceLimits INSTRUCTIONSLOTS 96\n" + long_shader("b"));
    ASSERT_EQ(r.diagnostics.size(), 1u);
    // The 65th arithmetic instruction, `mov oC0, r0`, is assembly line 67 of the heredoc that
    // starts after line 2.
    EXPECT_EQ(r.diagnostics[0].line, 69u);
    EXPECT_EQ(r.diagnostics[0].call, "CreatePixelShader");
    EXPECT_NE(r.diagnostics[0].message.find("slot"), std::string::npos) << r.diagnostics[0].message;
    EXPECT_EQ(r.calls, 3u);
    EXPECT_EQ(r.refused, 1u);
}

TEST(DeviceLimits, TheStreamOverridesTheInitialValueBothWays) {
    Device device;
    EXPECT_EQ(device.max_instruction_slots(), 0u);
    EXPECT_TRUE(device.set_max_instruction_slots(512).ok);
    EXPECT_EQ(device.max_instruction_slots(), 512u);
    // Initial 96 (sm2 --max-slots 96), lowered back to the profile's by the stream.
    auto r = replay_text("SetDeviceLimits INSTRUCTIONSLOTS 0\n" + long_shader("a"), 96);
    EXPECT_EQ(r.refused, 1u);
    EXPECT_TRUE(replay_text(long_shader("a"), 96).ok());
}

TEST(DeviceLimits, BadArgumentsAreRefusedAndChangeNothing) {
    auto r = replay_text("SetDeviceLimits CONSTANTS 512\nSetDeviceLimits INSTRUCTIONSLOTS\n"
                         "SetDeviceLimits INSTRUCTIONSLOTS 70000\nSetDeviceLimits INSTRUCTIONSLOTS 512 FOO\n" +
                         long_shader("a"));
    ASSERT_EQ(r.diagnostics.size(), 5u);
    EXPECT_NE(r.diagnostics[0].message.find("unknown limit 'CONSTANTS' (expected INSTRUCTIONSLOTS)"), std::string::npos)
        << r.diagnostics[0].message;
    EXPECT_NE(r.diagnostics[1].message.find("expects at least 2 arguments"), std::string::npos)
        << r.diagnostics[1].message;
    EXPECT_NE(r.diagnostics[2].message.find("instruction-slot limit 70000 out of range (0 for the profile's, or 1 to 65535)"),
              std::string::npos)
        << r.diagnostics[2].message;
    EXPECT_NE(r.diagnostics[3].message.find("odd number"), std::string::npos) << r.diagnostics[3].message;
    EXPECT_EQ(r.diagnostics[4].call, "CreatePixelShader");  // the limit stayed the profile's
}

TEST(DeviceLimits, SurvivesTheBinaryForm) {
    auto parsed = cs::parse_text("sm2cs 1\nSetDeviceLimits INSTRUCTIONSLOTS 512\n");
    ASSERT_TRUE(parsed.ok());
    auto unpacked = cs::unpack(cs::pack(*parsed.stream));
    ASSERT_TRUE(unpacked.ok());
    EXPECT_EQ(cs::to_text(*unpacked.stream), "sm2cs 1\nSetDeviceLimits INSTRUCTIONSLOTS 512\n");
    ASSERT_TRUE(cs::call_id("SetDeviceLimits").has_value());
    EXPECT_EQ(*cs::call_id("SetDeviceLimits"), *cs::call_id("SaveSurface") + 1);  // appended: ids are stable
}

}  // namespace
}  // namespace sm2::runtime
