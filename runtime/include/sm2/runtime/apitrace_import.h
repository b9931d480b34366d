// apitrace D3D9 traces to command streams (docs/apitrace.md "Import"): the calls the stream
// vocabulary has become statements, objects named by the pointers the trace recorded; calls
// that only query or read back are accepted with no statement; every other kind of call is
// skipped and reported once, with the number of its first call.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sm2/runtime/apitrace.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime::apitrace {

struct ImportReport {
    struct Skipped {
        std::string call;      // "IDirect3DDevice9::SetFVF"
        uint64_t first = 0;    // number of its first skipped call
        uint64_t count = 0;    // how many were skipped
        std::string reason;    // why the first one was
    };
    uint64_t calls = 0;        // calls read from the trace
    uint64_t imported = 0;     // calls that became a statement (a memcpy upload counts here)
    uint64_t accepted = 0;     // calls with nothing to replay: queries, read-backs, Lock/Unlock
                               // bookkeeping, AddRef/Release of a live object, failed calls
    uint64_t skipped = 0;      // calls the stream vocabulary cannot express yet
    std::vector<Skipped> skipped_kinds;  // one per call name, in order of first appearance

    // "imported 120, accepted 40, skipped 14 of 174 calls" and one line per skipped kind:
    // "  IDirect3DDevice9::SetFVF: 3 calls skipped from call 12: not in the stream vocabulary".
    [[nodiscard]] std::string to_string() const;
};

struct ImportResult {
    cs::Stream stream;
    ImportReport report;
    std::optional<Error> error;  // the trace was malformed at this byte (the stream holds the calls before)
};

// Reads `reader` to its end.
[[nodiscard]] ImportResult import_d3d9(Reader& reader);
// Streaming: each statement goes to `sink` with the number of the call it came from as soon as
// that call is translated; nothing accumulates (ImportResult::stream stays empty), so memory
// follows the largest call, not the trace.
using StatementSink = std::function<void(const cs::Statement& statement, uint64_t call)>;
[[nodiscard]] ImportResult import_d3d9(Reader& reader, const StatementSink& sink);

// `sm2 replay APP.trace`: the trace imported and replayed on `device` one call at a time. Calls
// the device refuses are counted per statement kind, each kind with its first call number and
// message, and the replay goes on.
struct TraceReplay {
    struct Refused {
        std::string call;      // the statement: "DrawPrimitiveUP"
        uint64_t first = 0;    // trace call number of the first refused one
        uint64_t count = 0;
        std::string message;   // the first one's diagnostic, without the call name
        CallError code = CallError::InvalidCall;
    };
    ImportReport import;
    std::optional<Error> error;        // the trace was malformed here (the calls before ran)
    uint64_t statements = 0;           // statements executed
    uint64_t refused = 0;              // of them refused by the device
    std::vector<Refused> refused_kinds;
    // "  DrawPrimitiveUP: 44 calls refused from call 66: D3DERR_INVALIDCALL: no vertex
    // declaration is set", one line per kind.
    [[nodiscard]] std::string refusals_to_string() const;
};
[[nodiscard]] TraceReplay replay_trace(Reader& reader, Device& device, const ReplayOptions& options = {});

}  // namespace sm2::runtime::apitrace
