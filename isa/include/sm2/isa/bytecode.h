// Whole-stream decode and encode. Decoding untrusted bytes never crashes: every malformed
// stream is an error naming the offending token index.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::isa {

struct DecodeError {
    size_t token_index = 0;  // index of the offending DWORD (byte offset = 4 * token_index)
    std::string message;
    [[nodiscard]] std::string to_string() const;  // "token 7 (byte 0x1c): message"
};

struct DecodeResult {
    std::optional<Program> program;
    std::optional<DecodeError> error;
    [[nodiscard]] bool ok() const { return program.has_value(); }
};

// Tokens -> Program. Checks: version token, known opcodes, instruction lengths against the
// operand walk, reserved bits, bit 31 of parameter tokens, relative-address tokens, END.
[[nodiscard]] DecodeResult decode(std::span<const uint32_t> tokens);
// Little-endian bytes -> Program; the size must be a multiple of 4.
[[nodiscard]] DecodeResult decode_bytes(std::span<const std::byte> bytes);

// Program -> tokens (version ... END). Instruction lengths are computed from the operands.
[[nodiscard]] std::vector<uint32_t> encode(const Program& program);
// Little-endian bytes.
[[nodiscard]] std::vector<std::byte> to_bytes(std::span<const uint32_t> tokens);

// True when `bytes` starts with a shader version token (tells bytecode from assembly text).
[[nodiscard]] bool looks_like_bytecode(std::span<const std::byte> bytes);

}  // namespace sm2::isa
