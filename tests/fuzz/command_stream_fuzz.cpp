// Fuzz target: arbitrary bytes as a command stream, text or binary.
// Properties: text that parses prints canonically and that canonical text is a fixed point;
// binary that unpacks packs back to exactly the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string_view>

#include "sm2/runtime/command_stream.h"

using namespace sm2::runtime::cs;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    if (looks_packed(bytes)) {
        auto r = unpack(bytes);
        if (!r.ok()) return 0;
        const auto again = pack(*r.stream);
        if (again.size() != size || !std::equal(again.begin(), again.end(), bytes.begin())) std::abort();
        (void)to_text(*r.stream);
        return 0;
    }
    TextOptions options;
    options.side_files = nullptr;  // no file access while fuzzing
    auto first = parse_text(std::string_view(reinterpret_cast<const char*>(data), size), options);
    if (!first.ok()) return 0;
    const std::string canonical = to_text(*first.stream);
    auto second = parse_text(canonical, options);
    if (!second.ok() || to_text(*second.stream) != canonical) std::abort();
    auto unpacked = unpack(pack(*second.stream));
    if (!unpacked.ok() || to_text(*unpacked.stream) != canonical) std::abort();
    return 0;
}
