// Command streams: recorded D3D9 device calls, in a text form and a binary form that convert
// into each other without loss (docs/command-stream.md). This layer is syntax only: it knows
// the call names and the shapes of argument values; what a call means is the replayer's job.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sm2::runtime::cs {

constexpr uint32_t kFormatVersion = 1;

// How a blob's bytes are written in text; the bytes are the content.
enum class BlobType : uint8_t { U8, U16, U32, I16, I32, F32, F16, Hex };

struct Value {
    enum class Kind : uint8_t {
        Integer,     // 12, -3, 0xFF00FF00
        Float,       // 0.5, 1e-3, inf, nan
        Identifier,  // names, enums, TRUE/FALSE
        String,      // "path"
        Tuple,       // { ... }
        Blob,        // f32[ ... ]
        SideFile,    // @"path": bytes loaded from a file beside the stream
        Heredoc,     // asm<<TAG ... TAG, hlsl<<TAG ... TAG
    };
    enum class Language : uint8_t { Asm, Hlsl };  // a Heredoc's text
    Kind kind = Kind::Integer;
    int64_t integer = 0;          // Integer (-2^31 .. 2^32-1)
    bool hex = false;             // Integer written in hex
    uint32_t float_bits = 0;      // Float: exact bits
    std::string text;             // Identifier, String, SideFile path, Heredoc tag
    std::vector<Value> items;     // Tuple
    BlobType blob_type = BlobType::U8;  // Blob
    std::vector<std::byte> bytes; // Blob, SideFile content, Heredoc text
    Language language = Language::Asm;  // Heredoc

    [[nodiscard]] float as_float() const;
    friend bool operator==(const Value&, const Value&) = default;
};

struct Statement {
    enum class Kind : uint8_t { Call, Comment, Blank };
    Kind kind = Kind::Call;
    std::string name;              // Call: D3D9 call name; Comment: the text after '#'
    std::vector<Value> arguments;  // Call
    std::string trailing_comment;  // Call: a '#' comment on the same line (without '#')
    uint32_t line = 0;             // 1-based line in the text form (0: from binary)
    friend bool operator==(const Statement& a, const Statement& b) {
        return a.kind == b.kind && a.name == b.name && a.arguments == b.arguments &&
               a.trailing_comment == b.trailing_comment;
    }
};

struct Stream {
    uint32_t version = kFormatVersion;
    std::vector<Statement> statements;
};

struct ParseError {
    std::string file;
    uint32_t line = 0;
    uint32_t column = 0;
    size_t byte_offset = 0;  // binary form
    std::string message;
    [[nodiscard]] std::string to_string() const;
};

struct ParseResult {
    std::optional<Stream> stream;
    std::optional<ParseError> error;
    [[nodiscard]] bool ok() const { return stream.has_value(); }
};

// Reads a side file named in the stream: `path` as written, relative to the stream's folder
// `base_dir`, which must resolve inside `root_dir` (runtime/file_io.h resolve_inside: no absolute
// path, no `..` or symbolic link leaving it); a regular file of at most kMaxInputFileBytes.
// nullopt and the reason in `error` when it cannot be read.
using SideFileReader = std::optional<std::vector<std::byte>> (*)(const std::string& root_dir,
                                                                  const std::string& base_dir,
                                                                  const std::string& path, std::string& error);
[[nodiscard]] std::optional<std::vector<std::byte>> read_side_file(const std::string& root_dir,
                                                                   const std::string& base_dir,
                                                                   const std::string& path, std::string& error);

struct TextOptions {
    std::string file_name = "<input>";  // for messages
    std::string base_dir = ".";         // where side files are looked up
    std::string root_dir;               // the folder they must stay inside (empty: base_dir)
    SideFileReader side_files = &read_side_file;
};

[[nodiscard]] ParseResult parse_text(std::string_view text, const TextOptions& options = {});
// The canonical text form.
[[nodiscard]] std::string to_text(const Stream& stream);

[[nodiscard]] std::vector<std::byte> pack(const Stream& stream);
[[nodiscard]] ParseResult unpack(std::span<const std::byte> bytes);
[[nodiscard]] bool looks_packed(std::span<const std::byte> bytes);

// The call vocabulary: D3D9 device call names with stable binary ids (never renumbered).
[[nodiscard]] std::span<const std::string_view> call_names();
[[nodiscard]] std::optional<uint16_t> call_id(std::string_view name);
[[nodiscard]] std::optional<std::string_view> call_name(uint16_t id);

}  // namespace sm2::runtime::cs
