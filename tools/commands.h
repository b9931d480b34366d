// Each subcommand of `sm2` registers itself on the app and runs from a callback that stores its
// exit status. Exit statuses: 0 ok, 1 invalid input, 2 bad usage.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace sm2::tools {

enum ExitStatus : int { kOk = 0, kInvalidInput = 1, kBadUsage = 2 };

// The engine `run`, `replay` and `bench` use without --engine: native code where the build has
// the JIT (the interpreter otherwise; both give the same bytes).
inline constexpr const char* kDefaultEngine = "jit";

// The positional STREAM argument of the commands that replay a stream or capture (`replay`,
// `state`, `pixel`, `debug`), required, with its one help text.
inline CLI::Option* add_stream_argument(CLI::App& cmd, std::string& stream) {
    return cmd
        .add_option("stream", stream,
                    "Command stream, text (.sm2cs) or binary (.sm2cb), '-' for stdin; or an apitrace capture (.trace), "
                    "imported as it replays")
        ->required();
}

// Shader text and bytecode: `asm`, `dis`, `validate`.
void add_shader_commands(CLI::App& app, int& status);

// Shader execution: `run`.
void add_run_command(CLI::App& app, int& status);

// Command streams: `cs pack`, `cs dump`.
void add_stream_commands(CLI::App& app, int& status);

// apitrace trace files: `trace dump`.
void add_trace_commands(CLI::App& app, int& status);

// Image comparison: `diff`.
void add_diff_command(CLI::App& app, int& status);

// Command-stream replay on the Device: `replay`, `bench`.
void add_replay_commands(CLI::App& app, int& status);

// The device state after one call: `state`.
void add_state_command(CLI::App& app, int& status);

// One pixel's history in a frame: `pixel`.
void add_pixel_command(CLI::App& app, int& status);

// A draw's pixel or vertex shader stepped one source instruction at a time: `debug`.
void add_debug_command(CLI::App& app, int& status);

}  // namespace sm2::tools
