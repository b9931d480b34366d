// Fuzz target: arbitrary text through the HLSL compiler, as a pixel or a vertex shader (the first
// byte chooses). Properties: no crash, hang or leak; what compiles is deterministic (a second
// compile gives the same tokens) and carries a program, since the assembler validated it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "sm2/hlsl/compiler.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    sm2::hlsl::CompileOptions options;
    options.stage = (data[0] & 1) ? sm2::isa::ShaderType::Vertex : sm2::isa::ShaderType::Pixel;
    const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    const auto first = sm2::hlsl::compile(text, options);
    if (!first.ok()) return 0;
    const auto second = sm2::hlsl::compile(text, options);
    if (!second.ok() || second.tokens != first.tokens || first.tokens.empty()) std::abort();
    return 0;
}
