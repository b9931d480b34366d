// Fuzz target: untrusted bytes through the decoder, the validator and the disassembler.
// Property: whatever decodes re-encodes to exactly the input bytes, and disassembles either to
// text that assembles back to the same statements or to an error naming one.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/validator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    auto result = sm2::isa::decode_bytes(bytes);
    if (!result.ok()) return 0;
    const auto tokens = sm2::isa::encode(*result.program);
    const auto again = sm2::isa::to_bytes(tokens);
    if (again.size() != size || !std::equal(again.begin(), again.end(), bytes.begin()))
        std::abort();  // decode/encode is not the identity
    (void)sm2::isa::validate(*result.program);
    const auto checked = sm2::assembler::disassemble_checked(*result.program);
    if (checked.error && checked.error->message.empty()) std::abort();  // an error must say what
    return 0;
}
