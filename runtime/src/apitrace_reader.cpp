// apitrace trace files: the Snappy container, the event stream, signatures and values
// (runtime/include/sm2/runtime/apitrace.h, docs/apitrace.md).
#include "sm2/runtime/apitrace.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unordered_map>

#include <snappy.h>

#include "sm2/runtime/file_io.h"

namespace sm2::runtime::apitrace {

namespace {

// Thrown inside the reader, turned into an Error at its public edge.
struct Failure {
    std::string message;
};

// The event stream's byte source: the Snappy container's chunks one at a time, or a bare stream.
class Source {
public:
    // The whole file in memory.
    Source(std::span<const std::byte> file, bool container, const Limits& limits)
        : file_(file), file_size_(file.size()), container_(container), limits_(limits) {
        if (container_) {
            file_pos_ = 2;  // "at"
        } else {
            chunk_ = file_;
        }
    }
    // The container read from a file one chunk at a time; `in` is past "at".
    Source(std::unique_ptr<std::ifstream> in, uint64_t size, const Limits& limits)
        : in_(std::move(in)), file_size_(size), container_(true), limits_(limits) {
        file_pos_ = 2;
    }

    // The next byte; false at the end of the data.
    bool get(uint8_t& byte) {
        if (pos_ == chunk_.size() && !refill()) return false;
        byte = static_cast<uint8_t>(chunk_[pos_++]);
        ++offset_;
        return true;
    }
    uint8_t need() {
        uint8_t b = 0;
        if (!get(b)) fail("unexpected end of the trace");
        return b;
    }
    // Appends `n` bytes to `out` as they arrive (no allocation ahead of the data).
    void read(size_t n, std::vector<std::byte>& out) {
        while (n > 0) {
            if (pos_ == chunk_.size() && !refill()) fail("unexpected end of the trace (" + std::to_string(n) + " bytes missing)");
            const size_t take = std::min(n, chunk_.size() - pos_);
            out.insert(out.end(), chunk_.begin() + static_cast<std::ptrdiff_t>(pos_),
                       chunk_.begin() + static_cast<std::ptrdiff_t>(pos_ + take));
            pos_ += take;
            offset_ += take;
            n -= take;
        }
    }
    void read_raw(void* dst, size_t n) {
        std::vector<std::byte> tmp;
        read(n, tmp);
        std::memcpy(dst, tmp.data(), n);
    }

    [[noreturn]] void fail(const std::string& message) const { throw Failure{message}; }

    uint64_t offset() const { return offset_; }
    std::optional<uint64_t> chunk_offset() const {
        if (!container_) return std::nullopt;
        return chunk_file_offset_;
    }

private:
    // The next non-empty chunk; false at the end of the file. A loop, not recursion: a file of
    // empty chunks must not grow the stack.
    bool refill() {
        if (!container_) return false;
        while (file_pos_ < file_size_) {
            load_chunk();
            if (!chunk_.empty()) return true;
        }
        return false;
    }
    void load_chunk() {
        chunk_file_offset_ = file_pos_;
        if (file_size_ - file_pos_ < 4) fail("truncated chunk length at file offset " + std::to_string(file_pos_));
        uint8_t header[4];
        file_bytes(header, 4);
        const uint32_t length = uint32_t(header[0]) | uint32_t(header[1]) << 8 | uint32_t(header[2]) << 16 | uint32_t(header[3]) << 24;
        if (length > file_size_ - file_pos_)
            fail("chunk at file offset " + std::to_string(chunk_file_offset_) + " declares " + std::to_string(length) +
                 " compressed bytes, the file has " + std::to_string(file_size_ - file_pos_) + " left");
        const char* compressed = nullptr;
        if (in_) {
            compressed_.resize(length);
            file_bytes(compressed_.data(), length);
            compressed = compressed_.data();
        } else {
            compressed = reinterpret_cast<const char*>(file_.data() + file_pos_);
            file_pos_ += length;
        }
        size_t uncompressed = 0;
        if (!snappy::GetUncompressedLength(compressed, length, &uncompressed))
            fail("chunk at file offset " + std::to_string(chunk_file_offset_) + " is not Snappy data");
        // Snappy expands at most 64 bytes per 3-byte copy: a larger claim is a corrupt header.
        if (uncompressed > limits_.max_chunk_bytes || uncompressed > uint64_t{length} * 22 + 64)
            fail("chunk at file offset " + std::to_string(chunk_file_offset_) + " claims " + std::to_string(uncompressed) +
                 " bytes from " + std::to_string(length) + " compressed");
        if (!snappy::IsValidCompressedBuffer(compressed, length))
            fail("chunk at file offset " + std::to_string(chunk_file_offset_) + " is corrupt Snappy data");
        storage_.resize(uncompressed);
        if (uncompressed > 0 && !snappy::RawUncompress(compressed, length, reinterpret_cast<char*>(storage_.data())))
            fail("chunk at file offset " + std::to_string(chunk_file_offset_) + " does not decompress");
        chunk_ = storage_;
        pos_ = 0;
    }

    // `n` bytes of the file at file_pos_ (checked to be there), advancing it.
    void file_bytes(void* dst, size_t n) {
        if (in_) {
            in_->read(static_cast<char*>(dst), static_cast<std::streamsize>(n));
            if (static_cast<size_t>(in_->gcount()) != n) fail("read error at file offset " + std::to_string(file_pos_));
        } else {
            std::memcpy(dst, file_.data() + file_pos_, n);
        }
        file_pos_ += n;
    }

    std::span<const std::byte> file_;
    std::unique_ptr<std::ifstream> in_;
    std::vector<char> compressed_;
    uint64_t file_size_ = 0;
    bool container_;
    const Limits& limits_;
    uint64_t file_pos_ = 0;
    uint64_t chunk_file_offset_ = 0;
    std::vector<std::byte> storage_;
    std::span<const std::byte> chunk_;
    size_t pos_ = 0;
    uint64_t offset_ = 0;
};

enum : uint8_t { kEventEnter = 0, kEventLeave = 1 };
enum : uint8_t { kCallEnd = 0, kCallArg, kCallRet, kCallThread, kCallBacktrace, kCallFlags };
enum : uint8_t {
    kTypeNull = 0, kTypeFalse, kTypeTrue, kTypeSInt, kTypeUInt, kTypeFloat, kTypeDouble, kTypeString,
    kTypeBlob, kTypeEnum, kTypeBitmask, kTypeArray, kTypeStruct, kTypeOpaque, kTypeRepr, kTypeWString,
};

void append_utf8(std::string& out, uint64_t cp) {
    if (cp > 0x10FFFF || (cp >= 0xD800 && cp < 0xE000)) cp = 0xFFFD;
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

}  // namespace

struct Reader::Impl {
    Impl(std::span<const std::byte> data, bool container, Limits l) : limits(l), src(data, container, limits) {}
    Impl(std::unique_ptr<std::ifstream> in, uint64_t size, Limits l) : limits(l), src(std::move(in), size, limits) {}

    Limits limits;
    Source src;
    Header header;
    std::unordered_map<uint64_t, std::shared_ptr<FunctionSig>> functions;
    std::unordered_map<uint64_t, std::shared_ptr<EnumSig>> enums;
    std::unordered_map<uint64_t, std::shared_ptr<BitmaskSig>> bitmasks;
    std::unordered_map<uint64_t, std::shared_ptr<StructSig>> structs;
    std::deque<Call> pending;  // entered, not yet left
    uint64_t next_call_no = 0;
    uint64_t call_bytes = 0;   // blob/string bytes of the call being read
    uint64_t call_values = 0;  // value nodes of the call being read
    std::optional<Error> error;
    bool done = false;

    uint64_t read_uint() {
        uint64_t value = 0;
        for (unsigned shift = 0;; shift += 7) {
            const uint8_t c = src.need();
            if (shift >= 64 || (shift == 63 && (c & 0x7E) != 0)) src.fail("integer longer than 64 bits");
            value |= uint64_t(c & 0x7F) << shift;
            if (!(c & 0x80)) return value;
        }
    }
    void count_bytes(uint64_t n) {
        if (n > limits.max_call_bytes - call_bytes)
            src.fail("a call holds more than " + std::to_string(limits.max_call_bytes) + " bytes of strings and blobs");
        call_bytes += n;
    }
    std::string read_string() {
        const uint64_t n = read_uint();
        count_bytes(n);
        std::vector<std::byte> bytes;
        src.read(static_cast<size_t>(n), bytes);
        return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    int64_t read_sint() {
        const uint8_t type = src.need();
        const uint64_t v = read_uint();
        if (type == kTypeSInt) return static_cast<int64_t>(0 - v);
        if (type == kTypeUInt) return static_cast<int64_t>(v);
        src.fail("enum value of type " + std::to_string(type) + " (expected 3 or 4, an integer)");
    }
    uint64_t count(const char* what) {
        const uint64_t n = read_uint();
        if (n > std::numeric_limits<uint32_t>::max()) src.fail(std::string(what) + " count " + std::to_string(n) + " is too large");
        return n;
    }
    template <class Map>
    void check_room(const Map& map, const char* what) {
        if (map.size() >= limits.max_signatures) src.fail(std::string("more than ") + std::to_string(limits.max_signatures) + " " + what + " signatures");
    }

    std::shared_ptr<const FunctionSig> function_sig() {
        const uint64_t id = read_uint();
        if (auto it = functions.find(id); it != functions.end()) return it->second;
        check_room(functions, "function");
        auto sig = std::make_shared<FunctionSig>();
        sig->id = id;
        sig->name = read_string();
        const uint64_t n = count("argument");
        for (uint64_t i = 0; i < n; ++i) sig->args.push_back(read_string());
        return functions.emplace(id, std::move(sig)).first->second;
    }
    std::shared_ptr<const EnumSig> enum_sig(uint32_t depth) {
        const uint64_t id = read_uint();
        if (auto it = enums.find(id); it != enums.end()) return it->second;
        check_room(enums, "enum");
        auto sig = std::make_shared<EnumSig>();
        sig->id = id;
        if (header.version >= 3) {
            const uint64_t n = count("enum value");
            for (uint64_t i = 0; i < n; ++i) {
                std::string name = read_string();
                sig->values.emplace_back(std::move(name), read_sint());
            }
        } else {
            std::string name = read_string();
            Value v = value(depth + 1);  // nested: an old enum signature holds a value
            sig->values.emplace_back(std::move(name), v.as_int().value_or(0));
        }
        return enums.emplace(id, std::move(sig)).first->second;
    }
    std::shared_ptr<const BitmaskSig> bitmask_sig() {
        const uint64_t id = read_uint();
        if (auto it = bitmasks.find(id); it != bitmasks.end()) return it->second;
        check_room(bitmasks, "bitmask");
        auto sig = std::make_shared<BitmaskSig>();
        sig->id = id;
        const uint64_t n = count("bitmask flag");
        for (uint64_t i = 0; i < n; ++i) {
            std::string name = read_string();
            sig->flags.emplace_back(std::move(name), read_uint());
        }
        return bitmasks.emplace(id, std::move(sig)).first->second;
    }
    std::shared_ptr<const StructSig> struct_sig() {
        const uint64_t id = read_uint();
        if (auto it = structs.find(id); it != structs.end()) return it->second;
        check_room(structs, "struct");
        auto sig = std::make_shared<StructSig>();
        sig->id = id;
        sig->name = read_string();
        const uint64_t n = count("struct member");
        for (uint64_t i = 0; i < n; ++i) sig->members.push_back(read_string());
        return structs.emplace(id, std::move(sig)).first->second;
    }

    Value value(uint32_t depth) {
        if (depth > limits.max_depth) src.fail("values nested deeper than " + std::to_string(limits.max_depth));
        if (++call_values > limits.max_call_values)
            src.fail("a call holds more than " + std::to_string(limits.max_call_values) + " values");
        const uint64_t at = src.offset();
        const uint8_t type = src.need();
        Value v;
        switch (type) {
        case kTypeNull: v.kind = Value::Kind::Null; break;
        case kTypeFalse: v.kind = Value::Kind::Bool; break;
        case kTypeTrue: v.kind = Value::Kind::Bool; v.boolean = true; break;
        case kTypeSInt: v.kind = Value::Kind::SInt; v.sint = static_cast<int64_t>(0 - read_uint()); break;
        case kTypeUInt: v.kind = Value::Kind::UInt; v.uint = read_uint(); break;
        case kTypeFloat: {
            float f = 0;
            src.read_raw(&f, sizeof f);
            v.kind = Value::Kind::Float;
            v.real = f;
            break;
        }
        case kTypeDouble:
            v.kind = Value::Kind::Double;
            src.read_raw(&v.real, sizeof v.real);
            break;
        case kTypeString: v.kind = Value::Kind::String; v.text = read_string(); break;
        case kTypeBlob: {
            v.kind = Value::Kind::Blob;
            const uint64_t n = read_uint();
            count_bytes(n);
            src.read(static_cast<size_t>(n), v.bytes);
            break;
        }
        case kTypeEnum:
            v.kind = Value::Kind::Enum;
            v.enum_sig = enum_sig(depth);
            if (header.version >= 3) {
                v.sint = read_sint();
            } else {
                v.sint = v.enum_sig->values.empty() ? 0 : v.enum_sig->values.front().second;
            }
            break;
        case kTypeBitmask:
            v.kind = Value::Kind::Bitmask;
            v.bitmask_sig = bitmask_sig();
            v.uint = read_uint();
            break;
        case kTypeArray: {
            v.kind = Value::Kind::Array;
            const uint64_t n = count("array element");
            // Every element takes at least one byte: grow as they arrive, never ahead.
            for (uint64_t i = 0; i < n; ++i) v.items.push_back(value(depth + 1));
            break;
        }
        case kTypeStruct:
            v.kind = Value::Kind::Struct;
            v.struct_sig = struct_sig();
            for (size_t i = 0; i < v.struct_sig->members.size(); ++i) v.items.push_back(value(depth + 1));
            break;
        case kTypeOpaque: v.kind = Value::Kind::Pointer; v.uint = read_uint(); break;
        case kTypeRepr:
            v.kind = Value::Kind::Repr;
            v.items.push_back(value(depth + 1));
            v.items.push_back(value(depth + 1));
            break;
        case kTypeWString: {
            v.kind = Value::Kind::WString;
            const uint64_t n = count("wide string");
            for (uint64_t i = 0; i < n; ++i) {
                count_bytes(1);
                append_utf8(v.text, read_uint());
            }
            break;
        }
        default:
            throw Failure{"unknown value type " + std::to_string(type) + " at byte " + std::to_string(at)};
        }
        return v;
    }

    // Reads call details into `call` up to the terminator.
    void details(Call& call) {
        for (;;) {
            const uint8_t d = src.need();
            switch (d) {
            case kCallEnd: return;
            case kCallArg: {
                const uint64_t index = read_uint();
                const size_t limit = call.sig ? std::max<size_t>(call.sig->args.size(), 64) : 64;
                if (index >= limit) src.fail("argument index " + std::to_string(index) + " of " + (call.sig ? call.sig->name : std::string("?")) + " is out of range");
                Value v = value(0);
                if (index >= call.args.size()) call.args.resize(static_cast<size_t>(index) + 1);
                call.args[static_cast<size_t>(index)] = std::move(v);
                break;
            }
            case kCallRet: call.ret = value(0); break;
            case kCallThread: call.thread = read_uint(); break;
            case kCallBacktrace: {
                const uint64_t n = count("backtrace frame");
                for (uint64_t i = 0; i < n; ++i) backtrace_frame();
                break;
            }
            case kCallFlags: call.fake = (read_uint() & 1) != 0; break;
            default: src.fail("unknown call detail " + std::to_string(d));
            }
        }
    }
    // Backtraces are read and dropped; a frame's details come with its first occurrence.
    std::unordered_map<uint64_t, bool> frames;
    void backtrace_frame() {
        const uint64_t id = read_uint();
        if (frames.count(id)) return;
        check_room(frames, "backtrace frame");
        frames.emplace(id, true);
        for (;;) {
            const uint8_t d = src.need();
            if (d == 0) return;
            if (d >= 1 && d <= 3) {
                (void)read_string();
            } else if (d == 4 || d == 5) {
                (void)read_uint();
            } else {
                src.fail("unknown backtrace detail " + std::to_string(d));
            }
        }
    }

    void read_header() {
        header.version = read_uint();
        if (header.version > kMaxVersion)
            src.fail("trace format version " + std::to_string(header.version) + " (this reader knows up to " + std::to_string(kMaxVersion) + ")");
        header.semantic_version = header.version;
        if (header.version >= 6) {
            header.semantic_version = read_uint();
            if (header.semantic_version > header.version) src.fail("semantic version " + std::to_string(header.semantic_version) + " above the format version");
            for (size_t n = 0;; ++n) {
                call_bytes = 0;
                std::string name = read_string();
                if (name.empty()) break;
                if (n >= 4096) src.fail("more than 4096 header properties");
                header.properties[name] = read_string();
            }
        }
        call_bytes = 0;
    }

    std::optional<Call> next() {
        while (!done) {
            uint8_t event = 0;
            const uint64_t at = src.offset();
            if (!src.get(event)) {
                done = true;
                break;
            }
            call_bytes = 0;
            call_values = 0;
            if (event == kEventEnter) {
                Call call;
                if (header.version >= 4) call.thread = read_uint();
                call.sig = function_sig();
                call.number = next_call_no++;
                if (pending.size() >= limits.max_pending_calls)
                    src.fail("more than " + std::to_string(limits.max_pending_calls) + " calls entered without leaving");
                pending.push_back(std::move(call));
                details(pending.back());
            } else if (event == kEventLeave) {
                const uint64_t no = read_uint();
                auto it = std::find_if(pending.begin(), pending.end(), [&](const Call& c) { return c.number == no; });
                if (it == pending.end()) src.fail("leave event for call " + std::to_string(no) + ", which has not entered");
                Call call = std::move(*it);
                pending.erase(it);
                details(call);
                return call;
            } else {
                throw Failure{"unknown event " + std::to_string(event) + " at byte " + std::to_string(at)};
            }
        }
        if (!pending.empty()) {
            Call call = std::move(pending.front());
            pending.pop_front();
            call.incomplete = true;
            return call;
        }
        return std::nullopt;
    }

    Error make_error(const Failure& f) const { return Error{src.offset(), src.chunk_offset(), f.message}; }
};

Reader::Reader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Reader::~Reader() = default;

std::unique_ptr<Reader> Reader::open(std::span<const std::byte> data, std::optional<Error>& error,
                                     bool accept_uncompressed, Limits limits) {
    error.reset();
    const bool container = data.size() >= 2 && data[0] == std::byte{'a'} && data[1] == std::byte{'t'};
    if (!container && !accept_uncompressed) {
        std::string what = "not an apitrace file in the Snappy container (it starts with \"at\")";
        if (data.size() >= 2 && data[0] == std::byte{0x1f} && data[1] == std::byte{0x8b})
            what = "a gzip-compressed apitrace file (only the Snappy container, apitrace's default since 2011, is read)";
        error = Error{0, std::nullopt, what};
        return nullptr;
    }
    return start(std::make_unique<Impl>(data, container, limits), error);
}

std::unique_ptr<Reader> Reader::open_file(const std::string& path, std::optional<Error>& error, Limits limits) {
    error.reset();
    std::string why;
    if (!check_input_file(path, std::numeric_limits<uint64_t>::max(), why)) {
        error = Error{0, std::nullopt, why, true};
        return nullptr;
    }
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    auto in = std::make_unique<std::ifstream>(path, std::ios::binary);
    if (ec || !*in) {
        error = Error{0, std::nullopt, path + ": cannot open", true};
        return nullptr;
    }
    char magic[2] = {};
    in->read(magic, 2);
    if (in->gcount() != 2 || magic[0] != 'a' || magic[1] != 't') {
        const std::byte bytes[2] = {std::byte(static_cast<uint8_t>(magic[0])), std::byte(static_cast<uint8_t>(magic[1]))};
        return open(std::span<const std::byte>(bytes, static_cast<size_t>(in->gcount())), error, false, limits);
    }
    return start(std::make_unique<Impl>(std::move(in), size, limits), error);
}

std::unique_ptr<Reader> Reader::start(std::unique_ptr<Impl> impl, std::optional<Error>& error) {
    try {
        impl->read_header();
    } catch (const Failure& f) {
        error = impl->make_error(f);
        return nullptr;
    }
    return std::unique_ptr<Reader>(new Reader(std::move(impl)));
}

const Header& Reader::header() const { return impl_->header; }
const std::optional<Error>& Reader::error() const { return impl_->error; }

std::optional<Call> Reader::next() {
    if (impl_->error) return std::nullopt;
    try {
        return impl_->next();
    } catch (const Failure& f) {
        impl_->error = impl_->make_error(f);
        impl_->done = true;
        impl_->pending.clear();
        return std::nullopt;
    }
}

std::string Error::to_string() const {
    if (io) return message;
    std::string s = "byte " + std::to_string(offset);
    if (file_offset) s += " (chunk at file offset " + std::to_string(*file_offset) + ")";
    return s + ": " + message;
}

std::optional<int64_t> Value::as_int() const {
    switch (kind) {
    case Kind::Bool: return boolean ? 1 : 0;
    case Kind::SInt:
    case Kind::Enum: return sint;
    case Kind::UInt:
    case Kind::Bitmask:
    case Kind::Pointer: return static_cast<int64_t>(uint);
    case Kind::Null: return 0;
    case Kind::Repr: return items.size() == 2 ? items[1].as_int() : std::nullopt;
    default: return std::nullopt;
    }
}

const Value* Value::member(std::string_view name) const {
    if (kind != Kind::Struct || !struct_sig) return nullptr;
    for (size_t i = 0; i < struct_sig->members.size() && i < items.size(); ++i)
        if (struct_sig->members[i] == name) return &items[i];
    return nullptr;
}

const std::vector<std::byte>* Value::blob() const {
    if (kind == Kind::Blob) return &bytes;
    if (kind == Kind::Repr && items.size() == 2) return items[1].blob();
    return nullptr;
}

const Value* Call::arg(std::string_view name) const {
    if (!sig) return nullptr;
    for (size_t i = 0; i < sig->args.size() && i < args.size(); ++i)
        if (sig->args[i] == name) return args[i] ? &*args[i] : nullptr;
    return nullptr;
}

namespace {

void write_value(std::string& out, const Value& v) {
    char buf[64];
    switch (v.kind) {
    case Value::Kind::Null: out += "NULL"; return;
    case Value::Kind::Bool: out += v.boolean ? "true" : "false"; return;
    case Value::Kind::SInt: out += std::to_string(v.sint); return;
    case Value::Kind::UInt: out += std::to_string(v.uint); return;
    case Value::Kind::Float:
        std::snprintf(buf, sizeof buf, "%.7g", v.real);
        out += buf;
        return;
    case Value::Kind::Double:
        std::snprintf(buf, sizeof buf, "%.16g", v.real);
        out += buf;
        return;
    case Value::Kind::WString: out += 'L'; [[fallthrough]];
    case Value::Kind::String:
        out += '"';
        for (const char c : v.text) {
            const auto u = static_cast<unsigned char>(c);
            if (c == '"' || c == '\\') {
                out += '\\';
                out += c;
            } else if (c == '\n') {
                out += "\\n";
            } else if (c == '\r') {
                out += "\\r";
            } else if (c == '\t') {
                out += "\\t";
            } else if (u < 0x20 || u == 0x7F) {
                std::snprintf(buf, sizeof buf, "\\%03o", u);
                out += buf;
            } else {
                out += c;
            }
        }
        out += '"';
        return;
    case Value::Kind::Blob: out += "blob(" + std::to_string(v.bytes.size()) + ")"; return;
    case Value::Kind::Enum:
        for (const auto& [name, value] : v.enum_sig->values) {
            if (value == v.sint) {
                out += name;
                return;
            }
        }
        out += std::to_string(v.sint);
        return;
    case Value::Kind::Bitmask: {
        uint64_t rest = v.uint;
        bool first = true;
        for (const auto& [name, flag] : v.bitmask_sig->flags) {
            if ((flag && (rest & flag) == flag) || (!flag && rest == 0)) {
                if (!first) out += " | ";
                out += name;
                rest &= ~flag;
                first = false;
            }
            if (rest == 0) break;
        }
        if (rest || first) {
            if (!first) out += " | ";
            std::snprintf(buf, sizeof buf, "0x%" PRIx64, rest);
            out += buf;
        }
        return;
    }
    case Value::Kind::Array:
        if (v.items.size() == 1) {
            out += '&';
            write_value(out, v.items[0]);
            return;
        }
        out += '{';
        for (size_t i = 0; i < v.items.size(); ++i) {
            if (i) out += ", ";
            write_value(out, v.items[i]);
        }
        out += '}';
        return;
    case Value::Kind::Struct:
        out += '{';
        for (size_t i = 0; i < v.items.size(); ++i) {
            if (i) out += ", ";
            out += v.struct_sig->members[i];
            out += " = ";
            write_value(out, v.items[i]);
        }
        out += '}';
        return;
    case Value::Kind::Pointer:
        std::snprintf(buf, sizeof buf, "0x%" PRIx64, v.uint);
        out += buf;
        return;
    case Value::Kind::Repr:
        if (!v.items.empty()) write_value(out, v.items[0]);
        return;
    }
}

}  // namespace

std::string to_text(const Value& value) {
    std::string out;
    write_value(out, value);
    return out;
}

std::string to_text(const Call& call) {
    std::string out = std::to_string(call.number) + " " + call.name() + "(";
    for (size_t i = 0; i < call.args.size(); ++i) {
        if (i) out += ", ";
        out += i < call.sig->args.size() ? call.sig->args[i] : "arg" + std::to_string(i);
        out += " = ";
        if (call.args[i]) {
            write_value(out, *call.args[i]);
        } else {
            out += '?';
        }
    }
    out += ')';
    if (call.ret) {
        out += " = ";
        write_value(out, *call.ret);
    }
    if (call.fake || call.incomplete) {
        out += " //";
        if (call.fake) out += " fake";
        if (call.incomplete) out += " incomplete";
    }
    return out;
}

}  // namespace sm2::runtime::apitrace
