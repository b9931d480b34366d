// Fuzz target: arbitrary text through the assembler.
// Property: what assembles, disassembles to text that reassembles to the same tokens.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    sm2::assembler::AssembleOptions options;
    options.validate = false;  // reach the encoder with programs the validator would reject
    auto first = sm2::assembler::assemble(text, options);
    if (!first.ok()) return 0;
    const std::string listing = sm2::assembler::disassemble(*first.program);
    auto second = sm2::assembler::assemble(listing, options);
    if (!second.ok() || second.tokens != first.tokens) std::abort();
    (void)sm2::assembler::assemble(text);  // and once with validation
    return 0;
}
