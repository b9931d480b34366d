// Fuzz target: arbitrary bytes as an apitrace trace, in the Snappy container when they start with
// "at", else as the bare event stream (where mutations reach the signatures and values).
// Then the D3D9 importer on the same bytes (sm2 cs import), whole and streamed (sm2 replay).
// Properties: never a crash, a hang or an allocation the input does not back; every call read
// prints; an error names a byte inside the data read; a bare stream yields at most one call per
// two bytes (an enter and a leave event take at least that).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "sm2/runtime/apitrace.h"
#include "sm2/runtime/apitrace_import.h"

using namespace sm2::runtime::apitrace;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    const bool container = size >= 2 && data[0] == 'a' && data[1] == 't';
    std::optional<Error> error;
    auto reader = Reader::open(bytes, error, true);
    if (!reader) {
        if (!error || error->message.empty()) std::abort();
        if (!container && error->offset > size) std::abort();
        return 0;
    }
    size_t calls = 0;
    while (auto call = reader->next()) {
        ++calls;
        if (!call->sig) std::abort();
        (void)to_text(*call);
        for (const auto& arg : call->args)
            if (arg) {
                (void)arg->as_int();
                (void)arg->blob();
                (void)arg->member("x");
            }
    }
    if (reader->error()) {
        if (reader->error()->message.empty()) std::abort();
        if (!container && reader->error()->offset > size) std::abort();
    }
    if (!container && calls > size / 2 + 1) std::abort();
    if (reader->next()) std::abort();  // the end stays the end

    // The importer on the same bytes: every call is imported, accepted or skipped, and the stream
    // it makes prints and packs.
    auto again = Reader::open(bytes, error, true);
    if (!again) std::abort();
    const ImportResult imported = import_d3d9(*again);
    const ImportReport& report = imported.report;
    if (report.calls != calls || report.imported + report.accepted + report.skipped != report.calls) std::abort();
    (void)report.to_string();
    (void)sm2::runtime::cs::to_text(imported.stream);
    (void)sm2::runtime::cs::pack(imported.stream);
    // Streamed (sm2 replay APP.trace): the same statements, one call at a time.
    auto streamed_reader = Reader::open(bytes, error, true);
    if (!streamed_reader) std::abort();
    size_t streamed = 0;
    const ImportResult by_call = import_d3d9(*streamed_reader, [&](const sm2::runtime::cs::Statement&, uint64_t) { ++streamed; });
    if (streamed != imported.stream.statements.size() || !by_call.stream.statements.empty()) std::abort();
    return 0;
}
