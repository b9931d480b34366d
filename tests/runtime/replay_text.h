// Test helper: a command stream given as text, replayed on a fresh Device; what the draw tests
// look at afterwards (the replay's result, the back buffer's bytes, the device's statistics).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace sm2::runtime::test {

struct ReplayOutcome {
    ReplayResult result;
    std::vector<uint8_t> pixels;  // back buffer bytes (B G R A per pixel for A8R8G8B8)
    DrawStatistics statistics;
};

// `text` parsed as the stream file `file_name` (parse errors fail the test) and replayed.
inline ReplayOutcome replay_stream_text(const std::string& text, const std::string& file_name) {
    cs::TextOptions options_text;
    options_text.file_name = file_name;
    auto parsed = cs::parse_text(text, options_text);
    EXPECT_TRUE(parsed.ok()) << parsed.error->to_string();
    ReplayOutcome out;
    if (!parsed.ok()) return out;
    Device device;
    ReplayOptions options;
    options.file_name = file_name;
    options.assembler = runtime::stream_assembler();
    out.result = replay(device, *parsed.stream, options);
    const Surface* back = device.surface("backbuffer");
    out.pixels.resize(back->bytes().size());
    std::memcpy(out.pixels.data(), back->bytes().data(), out.pixels.size());
    out.statistics = device.statistics();
    return out;
}

// Every diagnostic of the replay is a test failure.
inline void expect_no_diagnostics(const ReplayResult& r) {
    for (const auto& d : r.diagnostics) ADD_FAILURE() << d.to_string();
}

}  // namespace sm2::runtime::test
