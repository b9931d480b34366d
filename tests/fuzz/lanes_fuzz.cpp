// Fuzz target: bytes as an `sm2 run --lanes` CSV for a pixel and a vertex shader. Property: every
// input is read or refused with InputError naming file:line; no crash, no hang.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tools/lanes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (const sm2::isa::ShaderVersion version : {sm2::isa::ShaderVersion{sm2::isa::ShaderType::Pixel, 2, 0},
                                                   sm2::isa::ShaderVersion{sm2::isa::ShaderType::Vertex, 2, 0}}) {
        try {
            (void)sm2::tools::parse_lanes_csv(text, "fuzz.csv", version);
        } catch (const sm2::tools::InputError&) {
        }
    }
    return 0;
}
