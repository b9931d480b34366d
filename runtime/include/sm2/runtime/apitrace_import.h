// apitrace D3D9 traces to command streams (docs/apitrace.md "Import"): the calls the stream
// vocabulary has become statements, objects named by the pointers the trace recorded; calls
// that only query or read back are accepted with no statement; every other kind of call is
// skipped and reported once, with the number of its first call.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sm2/runtime/apitrace.h"
#include "sm2/runtime/command_stream.h"

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

}  // namespace sm2::runtime::apitrace
