// Fuzz target: arbitrary bytes as a command stream replayed on a Device. Property: whatever the
// stream says, replay ends without a crash, a hang or a sanitizer report; refused calls become
// diagnostics. The Device's memory limit (64 MiB here) refuses what would blow up memory; sizes
// are still capped so each input stays fast (a 4096x4096 target would make one input take
// seconds): streams that create a surface or texture over 128 texels a side, a buffer over 1 MiB,
// or draw more than 16384 primitives, are skipped before replay.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/replay.h"

using namespace sm2;
using namespace sm2::runtime;

namespace {

bool too_costly(const cs::Stream& stream) {
    for (const auto& s : stream.statements) {
        if (s.kind != cs::Statement::Kind::Call) continue;
        const bool buffer = s.name == "CreateVertexBuffer" || s.name == "CreateIndexBuffer";
        const bool surface = !buffer && s.name.rfind("Create", 0) == 0;  // sizes of targets, textures
        const bool draws = s.name.rfind("Draw", 0) == 0;
        const int64_t limit = surface ? 128 : buffer ? (1 << 20) : draws ? 16384 : INT64_MAX;
        for (const auto& v : s.arguments)
            if (v.kind == cs::Value::Kind::Integer && v.integer > limit) return true;
    }
    return stream.statements.size() > 512;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    cs::ParseResult parsed;
    if (cs::looks_packed(bytes)) {
        parsed = cs::unpack(bytes);
    } else {
        cs::TextOptions options;
        options.side_files = nullptr;  // no file access while fuzzing
        parsed = cs::parse_text(std::string_view(reinterpret_cast<const char*>(data), size), options);
    }
    if (!parsed.ok() || too_costly(*parsed.stream)) return 0;
    DeviceOptions device_options;  // no output_dir: Present writes nothing
    device_options.memory_limit = uint64_t{64} << 20;
    Device device(device_options);
    ReplayOptions options;
    options.base_dir = "/nonexistent";  // LoadTexture finds nothing
    options.assembler = runtime::stream_assembler();
    (void)replay(device, *parsed.stream, options);
    return 0;
}
