// Replaying a stream or trace call by call up to a point (sm2 state, sm2 pixel).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/device.h"

namespace sm2::tools {

struct CallWalk {
    std::string file_name;        // for messages
    bool trace = false;           // an apitrace capture: calls numbered from 0 by the trace
    uint64_t first_call = 1;      // the numbers calls can have: first_call..last_call
    uint64_t last_call = 0;
    uint64_t refused = 0;         // calls the device refused (the walk went on)
    [[nodiscard]] std::string range_text() const;  // "calls 1..120" ("no calls" when empty)
};

// The device sm2 state, pixel and debug replay on: every core, the JIT, and no files written
// (a stream's SaveSurface succeeds without writing: looking inside a frame leaves no images in
// the working folder).
[[nodiscard]] runtime::DeviceOptions inspection_device_options();

// Replays `path` (.sm2cs, .sm2cb, or .trace) on `device`. Before each call, `keep_going(call,
// statement)` decides whether it runs; the first `false` ends the replay (a trace is still read
// to its end, to count its calls). Calls are numbered as sm2 replay --stats and --snapshot
// number them: from 1 in streams, the trace's own numbers in traces. nullopt after printing
// "sm2 COMMAND: ..." when the input cannot be read or is malformed.
std::optional<CallWalk> walk_calls(const std::string& path, const std::string& read_root, const char* command,
                                   runtime::Device& device,
                                   const std::function<bool(uint64_t call, const runtime::cs::Statement&)>& keep_going);

}  // namespace sm2::tools
