// The replayer: executes a command stream (cs::Stream) one statement at a time on a Device
// (docs/command-stream.md, "Calls"). It turns each call's arguments into the Device method's
// parameters: enums by name with or without their D3D prefix (d3d9_names), formats by name,
// render/sampler state values typed by their state, vertex elements as tuples, blobs and side
// files as bytes, shaders from assembly heredocs, side files or bytecode blobs.
//
// A call whose arguments have the wrong shape, or that the Device refuses, becomes a diagnostic
// with the statement's line ("file:line: D3DERR_INVALIDCALL: Call: message"); the device is left
// as it was and the replay goes on with the next statement.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/isa/program.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/device.h"

namespace sm2::runtime {

// Shader assembly text -> program, validated against `max_instruction_slots` (0: the profile's;
// the device's limit when the shader is created, SetDeviceLimits). The runtime does not depend
// on the assembler (DESIGN.md: runtime uses isa and emu only), so whoever replays hands one in:
// sm2/runtime/stream_assembler.h.
struct AssembledShader {
    std::optional<isa::Program> program;
    std::string error;  // the first error, when there is no program
    uint32_t line = 0;  // its 1-based line in the assembly text (0: none)
};
using ShaderAssembler = std::function<AssembledShader(std::string_view text, unsigned max_instruction_slots)>;
// HLSL source (entry point main) -> program for `stage` (vs_2_0/ps_2_0), for hlsl<<TAG heredocs;
// the runtime does not link the HLSL compiler (glslang), so whoever replays hands one in:
// sm2/runtime/stream_hlsl_compiler.h. `line` in the answer is the line in the HLSL text.
using ShaderCompiler =
    std::function<AssembledShader(std::string_view source, isa::ShaderType stage, unsigned max_instruction_slots)>;

struct ReplayDiagnostic {
    std::string file;
    uint32_t line = 0;       // 1-based line in the text form; 0 for a binary stream
    size_t record = 0;       // 1-based record (statement) number, for binary streams
    std::string call;        // "SetRenderState"
    std::string message;     // without the call name
    CallError code = CallError::InvalidCall;
    // "file:line: D3DERR_INVALIDCALL: Call: message" ("file: record N: ..." without a line;
    // D3DERR_OUTOFVIDEOMEMORY or E_OUTOFMEMORY for resources over the memory limit)
    [[nodiscard]] std::string to_string() const;
};

// One frame: the statements from the end of the previous Present (or the start) up to and
// including this Present.
struct FrameStats {
    double seconds = 0;
    size_t calls = 0;              // calls executed (refused ones included)
    DrawStatistics statistics{};   // what the frame's draws did
};

struct ReplayOptions {
    std::string file_name = "<input>";  // for diagnostics
    std::string base_dir = ".";         // LoadTexture paths are relative to it (the stream's folder)
    // LoadTexture paths must resolve inside this folder (empty: base_dir): no absolute paths, no
    // `..` or symbolic link leaving it (file_io.h resolve_inside). SaveSurface paths likewise
    // stay inside DeviceOptions::output_dir.
    std::string root_dir;
    ShaderAssembler assembler;          // empty: asm heredocs are refused
    ShaderCompiler hlsl_compiler;       // empty: hlsl heredocs are refused
    // Called after each statement with (statements done, total) during replay(); may be empty.
    std::function<void(size_t, size_t)> progress;
    // replay() records each draw's work in ReplayResult::draws (sm2 replay --stats); off, it
    // costs one test per call.
    bool per_draw_statistics = false;
    // Called after each call, accepted or refused, with its call number: 1-based as
    // ReplayResult::calls counts them for replay(), the trace's own number for replay_trace().
    // Returning false stops the replay there (no later call runs). May be empty (sm2 replay
    // --snapshot, sm2 state); per call, never per pixel.
    std::function<bool(const cs::Statement& statement, uint64_t call, bool accepted)> after_call;
};

// One draw call's work (ReplayOptions::per_draw_statistics).
struct DrawRecord {
    size_t call = 0;     // 1-based, counting calls as ReplayResult::calls does
    uint32_t line = 0;   // the statement's line in the text form (0: binary)
    size_t record = 0;   // 1-based statement number
    std::string name;    // "DrawIndexedPrimitive"
    size_t frame = 0;    // the frame it draws into (Presents before it)
    double seconds = 0;  // the call's wall time
    DrawStatistics statistics{};
};

struct ReplayResult {
    std::vector<ReplayDiagnostic> diagnostics;
    std::vector<FrameStats> frames;  // one per Present that succeeded
    size_t calls = 0;                // calls executed (comments and blank lines are not calls)
    size_t refused = 0;              // calls that became diagnostics
    double seconds = 0;              // the whole replay
    DrawStatistics statistics{};     // what the replay's draws did (the device's counters' growth)
    std::vector<DrawRecord> draws;   // ReplayOptions::per_draw_statistics: each draw, in order
    [[nodiscard]] bool ok() const { return diagnostics.empty(); }
};

class Replayer {
public:
    explicit Replayer(Device& device, ReplayOptions options = {});

    // Executes one statement (comments and blank lines do nothing). Returns false and records a
    // diagnostic when the call was refused; the device is then unchanged.
    bool execute(const cs::Statement& statement, size_t record = 0);
    // Executes every statement in order, timing frames at each Present.
    ReplayResult replay(const cs::Stream& stream);

    [[nodiscard]] const std::vector<ReplayDiagnostic>& diagnostics() const { return diagnostics_; }
    // Drops the diagnostics kept so far (a long streamed replay reads each one as it comes).
    void clear_diagnostics() { diagnostics_.clear(); }
    [[nodiscard]] Device& device() { return device_; }

private:
    Device& device_;
    ReplayOptions options_;
    std::vector<ReplayDiagnostic> diagnostics_;
};

// Replays `stream` on `device` with a fresh Replayer.
ReplayResult replay(Device& device, const cs::Stream& stream, const ReplayOptions& options = {});

}  // namespace sm2::runtime
