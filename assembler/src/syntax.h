// Pieces of the assembly syntax shared by the parser and the disassembler, so that what one
// prints the other reads: usage names, swizzle / write-mask letters, number literals.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "sm2/isa/program.h"

namespace sm2::assembler::syntax {

// dcl usage suffixes (bytecode.md §7.1), indexed by D3DDECLUSAGE value.
[[nodiscard]] std::string_view usage_name(isa::DeclUsage usage);
[[nodiscard]] std::optional<isa::DeclUsage> find_usage(std::string_view lower_name);

// Sampler texture types: "2d", "cube", "volume", "1d"; "" for Unknown.
[[nodiscard]] std::string_view texture_type_name(isa::TextureType type);
[[nodiscard]] std::optional<isa::TextureType> find_texture_type(std::string_view lower_name);

// Component letter -> 0..3 (x/r, y/g, z/b, w/a, any case); -1 if not a component letter.
[[nodiscard]] int component_index(char c);

// ".xy" style swizzle text (letters only, no dot) -> swizzle byte; the last letter repeats.
[[nodiscard]] std::optional<uint8_t> parse_swizzle(std::string_view letters);
// Write mask letters in x, y, z, w order without repeats -> mask bits.
[[nodiscard]] std::optional<uint8_t> parse_write_mask(std::string_view letters);

// Shortest letters that parse_swizzle maps back to `swizzle` ("" for identity .xyzw).
[[nodiscard]] std::string format_swizzle(uint8_t swizzle);
// "xz" for 0b0101; "" for the full mask.
[[nodiscard]] std::string format_write_mask(uint8_t mask);

// "0x..." (the lexer's hex number form).
[[nodiscard]] bool is_hex_literal(std::string_view text);
// 0x and 1 to 8 hex digits -> the 32-bit value, or nullopt with *error set.
[[nodiscard]] std::optional<uint32_t> parse_hex_dword(std::string_view text, std::string* error);

// def literals. Accepted: [+-]digits[.digits][e[+-]digits][f], [+-].digits..., and the raw
// IEEE-754 bit pattern 0xHHHHHHHH (extension; used for NaN and infinity). Decimal text is read
// as a double and then rounded to float, as Wine's atof-then-cast does.
// Returns the float's bit pattern, or nullopt with *error set.
[[nodiscard]] std::optional<uint32_t> parse_float_literal(bool negative, std::string_view text,
                                                          std::string* error);
// The shortest text that parse_float_literal reads back to exactly `bits` (fixed notation, no
// exponent, so Wine reads it too; NaN / infinity as 0xHHHHHHHH).
[[nodiscard]] std::string format_float_literal(uint32_t bits);

// ASCII lower case.
[[nodiscard]] std::string to_lower(std::string_view s);

}  // namespace sm2::assembler::syntax
