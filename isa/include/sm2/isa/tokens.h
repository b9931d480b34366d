// The token codec: one 32-bit token at a time, bit for bit as bytecode.md lays them out.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sm2/isa/program.h"

namespace sm2::isa::tokens {

constexpr uint32_t kEnd = 0x0000FFFFu;
constexpr uint32_t kParameterBit = 0x80000000u;

// --- instruction token -----------------------------------------------------------------
struct InstructionToken {
    uint16_t opcode = 0;
    uint8_t control = 0;   // bits 16..23
    uint8_t length = 0;    // bits 24..27
    bool predicated = false;  // bit 28
    bool reserved = false;    // bit 29
    bool coissue = false;     // bit 30
    bool high_bit = false;    // bit 31 (must be 0)
};
[[nodiscard]] constexpr uint32_t encode_instruction(uint16_t opcode, uint8_t control,
                                                    uint8_t length, bool predicated = false) {
    return opcode | (static_cast<uint32_t>(control) << 16) |
           (static_cast<uint32_t>(length & 0xF) << 24) | (predicated ? 0x10000000u : 0u);
}
[[nodiscard]] constexpr InstructionToken decode_instruction(uint32_t t) {
    return {static_cast<uint16_t>(t & 0xFFFF), static_cast<uint8_t>((t >> 16) & 0xFF),
            static_cast<uint8_t>((t >> 24) & 0xF), (t & 0x10000000u) != 0,
            (t & 0x20000000u) != 0, (t & 0x40000000u) != 0, (t & 0x80000000u) != 0};
}

// --- comment token ---------------------------------------------------------------------
[[nodiscard]] constexpr uint32_t encode_comment(uint32_t size_in_dwords) {
    return 0xFFFEu | ((size_in_dwords & 0x7FFFu) << 16);
}
[[nodiscard]] constexpr bool is_comment(uint32_t t) {
    return (t & 0xFFFFu) == 0xFFFEu && (t & 0x80000000u) == 0;
}
[[nodiscard]] constexpr uint32_t comment_size(uint32_t t) { return (t >> 16) & 0x7FFFu; }

// --- register type split across bits 28..30 and 11..12 ---------------------------------
[[nodiscard]] constexpr uint32_t encode_register_type(RegisterType type) {
    const auto t = static_cast<uint32_t>(type);
    return ((t & 7u) << 28) | ((t & 0x18u) << 8);
}
[[nodiscard]] constexpr uint8_t decode_register_type(uint32_t token) {
    return static_cast<uint8_t>(((token >> 28) & 7u) | ((token >> 8) & 0x18u));
}

// --- parameter tokens --------------------------------------------------------------------
// Encoders assume well-formed parameters (numbers fit their fields).
[[nodiscard]] uint32_t encode_destination(const DestinationParameter& d);
[[nodiscard]] uint32_t encode_source(const SourceParameter& s);  // the base token only
[[nodiscard]] uint32_t encode_relative(const RelativeAddress& r);

// Decoders check every field and say what is wrong; nullopt + message on failure.
struct DecodeFailure {
    std::string message;
};
[[nodiscard]] std::optional<DestinationParameter> decode_destination(uint32_t token,
                                                                     std::string* error);
// The relative flag is returned separately: the caller reads the extra token.
[[nodiscard]] std::optional<SourceParameter> decode_source(uint32_t token, bool* relative,
                                                           std::string* error);
[[nodiscard]] std::optional<RelativeAddress> decode_relative(uint32_t token, std::string* error);

// --- dcl usage/type token ------------------------------------------------------------------
[[nodiscard]] uint32_t encode_declaration(const Declaration& d);
[[nodiscard]] std::optional<Declaration> decode_declaration(uint32_t token, std::string* error);

}  // namespace sm2::isa::tokens
