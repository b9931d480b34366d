// The HLSL line table: for each instruction the compiler emitted, the HLSL file and line it came
// from. sm2's HLSL compiler writes it, when asked (`sm2 compile --debug-info`, and always for a
// command stream's hlsl<<TAG shaders), as a comment block with the private FOURCC 'SM2L', as fxc
// /Zi writes its 'DBUG' block; sm2 debug reads it to step by HLSL line. A comment block is
// ignored by the device and by every other reader, so the shader runs the same with or without.
//
// Payload (DWORDs, little-endian; a string is its byte length then its bytes, zero-padded to a
// whole DWORD):
//   'SM2L', version (1),
//   file count, each file name (a string),
//   source line count, each: file index, line (1-based), the line's text (a string, no newline),
//   entry count, each: instruction, file index, line, column.
// `instruction` counts the program's instructions other than comments (dcl and def included),
// from 0, so that the table stays valid wherever comment blocks are added or removed.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::isa {

constexpr uint32_t kFourccLineTable = 0x4C324D53;  // 'S' 'M' '2' 'L', little-endian
constexpr uint32_t kLineTableVersion = 1;

struct LineTable {
    struct SourceLine {
        uint32_t file = 0;  // index into files
        uint32_t line = 0;  // 1-based
        std::string text;   // the line as written, without its newline
    };
    struct Entry {
        uint32_t instruction = 0;  // ordinal among the program's non-comment instructions
        uint32_t file = 0;
        uint32_t line = 0;
        uint32_t column = 0;
    };
    std::vector<std::string> files;
    std::vector<SourceLine> lines;
    std::vector<Entry> entries;  // ascending by instruction; at most one per instruction

    // The entry of a non-comment instruction ordinal; nullptr when it has none.
    [[nodiscard]] const Entry* entry(uint32_t instruction) const;
    // The text of a file's line ("" when the table does not carry it).
    [[nodiscard]] const std::string* text(uint32_t file, uint32_t line) const;
};

struct LineTableResult {
    std::optional<LineTable> table;
    std::string error;  // set when table is not
    [[nodiscard]] bool ok() const { return table.has_value(); }
};

[[nodiscard]] std::vector<uint32_t> serialize_line_table(const LineTable& table);
// The payload of a comment block (FOURCC first); every count and string is bounds-checked.
[[nodiscard]] LineTableResult parse_line_table(std::span<const uint32_t> payload);
// The first 'SM2L' comment block of the program, parsed; nullopt when there is none.
[[nodiscard]] std::optional<LineTableResult> find_line_table(const Program& program);
// For each of program.instructions, its ordinal among the non-comment ones (a comment: -1).
[[nodiscard]] std::vector<int64_t> instruction_ordinals(const Program& program);

}  // namespace sm2::isa
