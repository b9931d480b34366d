// apitrace trace files (docs/apitrace.md): a streaming reader of the binary format apitrace
// writes (github.com/apitrace/apitrace docs/FORMAT.markdown, versions 0 to 6), in its Snappy
// container ("at", then chunks of u32 length + Snappy-compressed data).
//
// The reader holds one decompressed chunk, the signatures seen so far (functions, enums,
// bitmasks, structs: defined once in the file, referenced by id afterwards) and the calls that
// have entered but not yet left; memory follows the largest call, not the trace. Malformed input
// of any kind becomes an error naming the byte offset, never a crash, a hang or an allocation the
// file's bytes do not back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sm2::runtime::apitrace {

// The newest format version this reader knows (apitrace's TRACE_VERSION).
constexpr uint64_t kMaxVersion = 6;

struct EnumSig {
    uint64_t id = 0;
    std::vector<std::pair<std::string, int64_t>> values;  // name, value
};

struct BitmaskSig {
    uint64_t id = 0;
    std::vector<std::pair<std::string, uint64_t>> flags;  // name, value (a zero flag comes first)
};

struct StructSig {
    uint64_t id = 0;
    std::string name;
    std::vector<std::string> members;
};

struct FunctionSig {
    uint64_t id = 0;
    std::string name;                 // "IDirect3DDevice9::Clear", "memcpy"
    std::vector<std::string> args;    // argument names, in order
};

struct Value {
    enum class Kind : uint8_t {
        Null,     // null pointer
        Bool,     // false/true
        SInt,     // negative integer
        UInt,     // non-negative integer
        Float,
        Double,
        String,   // text (bytes as recorded)
        WString,  // wide string, as UTF-8 in `text`
        Blob,     // bytes
        Enum,     // `sint` with its signature
        Bitmask,  // `uint` with its signature
        Array,    // items
        Struct,   // items, one per member of the signature
        Pointer,  // opaque pointer: `uint` is the address
        Repr,     // items[0] the human form (a shader's disassembly), items[1] the machine form (its bytes)
    };
    Kind kind = Kind::Null;
    bool boolean = false;
    int64_t sint = 0;     // SInt, Enum
    uint64_t uint = 0;    // UInt, Bitmask, Pointer
    double real = 0;      // Float (exactly the float), Double
    std::string text;     // String, WString (UTF-8)
    std::vector<std::byte> bytes;  // Blob
    std::vector<Value> items;      // Array, Struct, Repr
    // Signatures are shared with the reader, so values and calls outlive it.
    std::shared_ptr<const EnumSig> enum_sig;
    std::shared_ptr<const BitmaskSig> bitmask_sig;
    std::shared_ptr<const StructSig> struct_sig;

    // The value as an integer (SInt, UInt, Enum, Bitmask, Pointer, Bool; Repr: its machine form).
    [[nodiscard]] std::optional<int64_t> as_int() const;
    // Struct member by name (nullptr when absent or not a struct).
    [[nodiscard]] const Value* member(std::string_view name) const;
    // The blob of a Blob, or of a Repr's machine form (a shader's bytecode); nullptr otherwise.
    [[nodiscard]] const std::vector<std::byte>* blob() const;
};

struct Call {
    uint64_t number = 0;      // calls are numbered from 0 in the order they enter
    uint64_t thread = 0;
    std::shared_ptr<const FunctionSig> sig;  // never null in a call the reader returns
    std::vector<std::optional<Value>> args;  // by argument index; nullopt: not recorded
    std::optional<Value> ret;
    bool fake = false;        // apitrace's FLAG_FAKE (the memcpy records of uploads)
    bool incomplete = false;  // the file ended before the call left

    [[nodiscard]] const std::string& name() const { return sig->name; }
    // Argument by name (nullptr when the signature has no such argument or it was not recorded).
    [[nodiscard]] const Value* arg(std::string_view name) const;
};

struct Header {
    uint64_t version = 0;
    uint64_t semantic_version = 0;
    std::map<std::string, std::string> properties;  // version 6: "process.name", ...
};

// A malformed or unsupported input: the message names the byte offset.
struct Error {
    uint64_t offset = 0;     // into the decompressed event stream
    std::optional<uint64_t> file_offset;  // the compressed chunk's offset in the file, when in a container
    std::string message;
    bool io = false;         // the file itself could not be read: the message names it, no offset
    [[nodiscard]] std::string to_string() const;  // "byte N (chunk at file offset M): message"
};

struct Limits {
    uint64_t max_chunk_bytes = uint64_t{64} << 20;  // one decompressed chunk (apitrace writes 1 MiB)
    uint64_t max_call_bytes = uint64_t{256} << 20;  // blob and string bytes of one event (enter or leave)
    uint64_t max_call_values = uint64_t{1} << 22;  // value nodes of one event (each ~150 bytes in memory)
    uint32_t max_depth = 64;                         // nesting of arrays, structs and reprs
    uint32_t max_pending_calls = 4096;               // calls entered and not yet left
    uint32_t max_signatures = 1u << 20;              // of each kind
};

class Reader {
public:
    // `data` is the whole file, borrowed for the reader's life: the Snappy container when it
    // starts with "at", else (`accept_uncompressed` only) the bare event stream, as apitrace
    // writes it before compression (tests and fuzzing).
    static std::unique_ptr<Reader> open(std::span<const std::byte> data, std::optional<Error>& error,
                                        bool accept_uncompressed = false, Limits limits = {});
    // The container read from a file one compressed chunk at a time (a regular file: no
    // directory, FIFO or device); the file is never held whole.
    static std::unique_ptr<Reader> open_file(const std::string& path, std::optional<Error>& error, Limits limits = {});
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    [[nodiscard]] const Header& header() const;
    // The next call to leave (apitrace's order: a call is complete when it leaves), or nullopt at
    // the end of the file (then error() says whether the end was clean). Calls still entered at
    // the end come out last, marked incomplete.
    std::optional<Call> next();
    [[nodiscard]] const std::optional<Error>& error() const;

private:
    struct Impl;
    explicit Reader(std::unique_ptr<Impl> impl);
    static std::unique_ptr<Reader> start(std::unique_ptr<Impl> impl, std::optional<Error>& error);
    std::unique_ptr<Impl> impl_;
};

// apitrace dump's text of a value: 42, -1, 0.5, "text", blob(N), D3DFMT_X8R8G8B8, A | B,
// {1, 2}, &{Member = ...} is the caller's (pointers to structs are arrays of one), 0x1234, NULL.
[[nodiscard]] std::string to_text(const Value& value);
// "N Interface::Method(arg = value, ...) = ret" (one line; strings with newlines escaped as \n).
[[nodiscard]] std::string to_text(const Call& call);

}  // namespace sm2::runtime::apitrace
