// The binary form of command streams and the call vocabulary (docs/command-stream.md).
#include <array>
#include <cstring>

#include "sm2/runtime/command_stream.h"

namespace sm2::runtime::cs {

namespace {

// Binary ids are positions in this list plus kFirstCallId: append only, never reorder.
constexpr std::array<std::string_view, 68> kCallNames = {
    "CreateDevice", "CreateVertexBuffer", "CreateIndexBuffer", "CreateTexture",
    "CreateCubeTexture", "CreateVolumeTexture", "CreateRenderTarget",
    "CreateDepthStencilSurface", "CreateVertexDeclaration", "CreateVertexShader",
    "CreatePixelShader", "Lock", "LockRect", "LockBox", "LoadTexture", "GenerateMipSubLevels",
    "Release", "SetVertexDeclaration", "SetVertexShader", "SetPixelShader", "SetRenderState",
    "SetSamplerState", "SetTexture", "SetStreamSource", "SetIndices",
    "SetVertexShaderConstantF", "SetVertexShaderConstantI", "SetVertexShaderConstantB",
    "SetPixelShaderConstantF", "SetPixelShaderConstantI", "SetPixelShaderConstantB",
    "SetViewport", "SetScissorRect", "SetClipPlane", "SetRenderTarget",
    "SetDepthStencilSurface", "Clear", "BeginScene", "EndScene", "DrawPrimitive",
    "DrawIndexedPrimitive", "DrawPrimitiveUP", "DrawIndexedPrimitiveUP", "StretchRect",
    "Present", "SaveSurface", "SetDeviceLimits", "ColorFill", "UpdateSurface", "UpdateTexture",
    "GetRenderTargetData", "CreateOffscreenPlainSurface", "SetSoftwareVertexProcessing", "SetNPatchMode",
    "CreateStateBlock", "BeginStateBlock", "EndStateBlock", "Capture", "Apply", "SetGammaRamp",
    "SetFVF", "SetTransform", "MultiplyTransform", "SetMaterial", "SetLight", "LightEnable",
    "SetTextureStageState", "Reset",
};

constexpr uint16_t kCommentId = 0;
constexpr uint16_t kBlankId = 1;
constexpr uint16_t kFirstCallId = 2;
constexpr char kMagic[4] = {'S', 'M', '2', 'C'};
constexpr int kMaxDepth = 16;

enum Tag : uint8_t {
    kTagInteger = 0, kTagHexInteger = 1, kTagFloat = 2, kTagIdentifier = 3, kTagString = 4,
    kTagTuple = 5, kTagBlob = 6, kTagSideFile = 7, kTagHeredoc = 8,
    kTagHlslHeredoc = 9,  // hlsl<<TAG: as kTagHeredoc, the text is HLSL
};

class Writer {
public:
    std::vector<std::byte> bytes;

    template <typename T>
    void put(T v) {
        const auto* p = reinterpret_cast<const std::byte*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof v);  // little-endian hosts only (x86-64, arm64)
    }
    void put_bytes(const void* data, size_t size) {
        put(static_cast<uint32_t>(size));
        const auto* p = static_cast<const std::byte*>(data);
        bytes.insert(bytes.end(), p, p + size);
    }
    void put_string(const std::string& s) { put_bytes(s.data(), s.size()); }

    void put_value(const Value& v) {
        switch (v.kind) {
        case Value::Kind::Integer:
            put(static_cast<uint8_t>(v.hex ? kTagHexInteger : kTagInteger));
            put(v.integer);
            break;
        case Value::Kind::Float:
            put(static_cast<uint8_t>(kTagFloat));
            put(v.float_bits);
            break;
        case Value::Kind::Identifier:
            put(static_cast<uint8_t>(kTagIdentifier));
            put_string(v.text);
            break;
        case Value::Kind::String:
            put(static_cast<uint8_t>(kTagString));
            put_string(v.text);
            break;
        case Value::Kind::Tuple:
            put(static_cast<uint8_t>(kTagTuple));
            put(static_cast<uint16_t>(v.items.size()));
            for (const Value& item : v.items) put_value(item);
            break;
        case Value::Kind::Blob:
            put(static_cast<uint8_t>(kTagBlob));
            put(static_cast<uint8_t>(v.blob_type));
            put_bytes(v.bytes.data(), v.bytes.size());
            break;
        case Value::Kind::SideFile:
            put(static_cast<uint8_t>(kTagSideFile));
            put_string(v.text);
            put_bytes(v.bytes.data(), v.bytes.size());
            break;
        case Value::Kind::Heredoc:
            put(static_cast<uint8_t>(v.language == Value::Language::Hlsl ? kTagHlslHeredoc : kTagHeredoc));
            put_string(v.text);
            put_bytes(v.bytes.data(), v.bytes.size());
            break;
        }
    }
};

class Reader {
public:
    explicit Reader(std::span<const std::byte> bytes) : bytes_(bytes) {}

    ParseResult run() {
        if (!looks_packed(bytes_)) return fail(0, "not a packed command stream (no SM2C header)");
        pos_ = 4;
        uint32_t version = 0;
        if (!get(version)) return fail(pos_, "truncated header");
        if (version != kFormatVersion)
            return fail(4, "unsupported command-stream version " + std::to_string(version));
        Stream stream;
        stream.version = version;
        while (pos_ < bytes_.size()) {
            const size_t record_start = pos_;
            uint16_t id = 0, argc = 0;
            uint32_t payload = 0;
            if (!get(id) || !get(argc) || !get(payload)) return fail(record_start, "truncated record header");
            if (payload > bytes_.size() - pos_) return fail(record_start, "record runs past the end of the stream");
            const size_t end = pos_ + payload;
            Statement st;
            if (id == kCommentId) {
                st.kind = Statement::Kind::Comment;
                if (argc != 0 || !get_string(st.name)) return fail(record_start, "malformed comment record");
            } else if (id == kBlankId) {
                st.kind = Statement::Kind::Blank;
                if (argc != 0) return fail(record_start, "malformed blank-line record");
            } else {
                auto name = call_name(id);
                if (!name) return fail(record_start, "unknown call id " + std::to_string(id));
                st.name = std::string(*name);
                for (uint16_t i = 0; i < argc; ++i) {
                    Value v;
                    if (!get_value(v, 0, end)) return fail(error_at_, error_);
                    st.arguments.push_back(std::move(v));
                }
                if (!get_string(st.trailing_comment)) return fail(record_start, "malformed trailing comment");
            }
            if (pos_ != end) return fail(record_start, "record length does not match its content");
            stream.statements.push_back(std::move(st));
        }
        return ParseResult{std::move(stream), std::nullopt};
    }

private:
    ParseResult fail(size_t at, std::string message) {
        ParseError e;
        e.file = "<packed>";
        e.byte_offset = at;
        e.message = std::move(message);
        return ParseResult{std::nullopt, e};
    }

    template <typename T>
    bool get(T& v) {
        if (sizeof v > bytes_.size() - pos_) return false;
        std::memcpy(&v, bytes_.data() + pos_, sizeof v);
        pos_ += sizeof v;
        return true;
    }
    bool get_bytes(std::vector<std::byte>& out) {
        uint32_t size = 0;
        if (!get(size) || size > bytes_.size() - pos_) return false;
        out.assign(bytes_.begin() + static_cast<ptrdiff_t>(pos_), bytes_.begin() + static_cast<ptrdiff_t>(pos_ + size));
        pos_ += size;
        return true;
    }
    bool get_string(std::string& out) {
        uint32_t size = 0;
        if (!get(size) || size > bytes_.size() - pos_) return false;
        out.assign(reinterpret_cast<const char*>(bytes_.data() + pos_), size);
        pos_ += size;
        return true;
    }
    bool value_error(size_t at, std::string message) {
        error_at_ = at;
        error_ = std::move(message);
        return false;
    }

    bool get_value(Value& v, int depth, size_t end) {
        const size_t at = pos_;
        uint8_t tag = 0;
        if (pos_ >= end || !get(tag)) return value_error(at, "truncated argument");
        switch (tag) {
        case kTagInteger:
        case kTagHexInteger:
            v.kind = Value::Kind::Integer;
            v.hex = tag == kTagHexInteger;
            if (!get(v.integer)) return value_error(at, "truncated integer");
            if (v.integer < INT32_MIN || v.integer > static_cast<int64_t>(UINT32_MAX))
                return value_error(at, "integer out of 32-bit range");
            return true;
        case kTagFloat:
            v.kind = Value::Kind::Float;
            return get(v.float_bits) || value_error(at, "truncated float");
        case kTagIdentifier:
        case kTagString:
            v.kind = tag == kTagIdentifier ? Value::Kind::Identifier : Value::Kind::String;
            return get_string(v.text) || value_error(at, "truncated text");
        case kTagTuple: {
            if (depth >= kMaxDepth) return value_error(at, "tuples nested too deeply");
            v.kind = Value::Kind::Tuple;
            uint16_t count = 0;
            if (!get(count)) return value_error(at, "truncated tuple");
            for (uint16_t i = 0; i < count; ++i) {
                Value item;
                if (!get_value(item, depth + 1, end)) return false;
                v.items.push_back(std::move(item));
            }
            return true;
        }
        case kTagBlob: {
            v.kind = Value::Kind::Blob;
            uint8_t type = 0;
            if (!get(type) || type > static_cast<uint8_t>(BlobType::Hex)) return value_error(at, "bad blob type");
            v.blob_type = static_cast<BlobType>(type);
            return get_bytes(v.bytes) || value_error(at, "truncated blob");
        }
        case kTagSideFile:
        case kTagHeredoc:
        case kTagHlslHeredoc:
            v.kind = tag == kTagSideFile ? Value::Kind::SideFile : Value::Kind::Heredoc;
            if (tag == kTagHlslHeredoc) v.language = Value::Language::Hlsl;
            return (get_string(v.text) && get_bytes(v.bytes)) || value_error(at, "truncated data");
        default:
            return value_error(at, "unknown argument tag " + std::to_string(tag));
        }
    }

    std::span<const std::byte> bytes_;
    size_t pos_ = 0;
    size_t error_at_ = 0;
    std::string error_;
};

}  // namespace

std::span<const std::string_view> call_names() { return kCallNames; }

std::optional<uint16_t> call_id(std::string_view name) {
    for (size_t i = 0; i < kCallNames.size(); ++i)
        if (kCallNames[i] == name) return static_cast<uint16_t>(i + kFirstCallId);
    return std::nullopt;
}

std::optional<std::string_view> call_name(uint16_t id) {
    if (id < kFirstCallId) return std::nullopt;
    const size_t index = static_cast<size_t>(id - kFirstCallId);
    if (index >= kCallNames.size()) return std::nullopt;
    return kCallNames[index];
}

bool looks_packed(std::span<const std::byte> bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0;
}

std::vector<std::byte> pack(const Stream& stream) {
    Writer w;
    w.bytes.insert(w.bytes.end(), reinterpret_cast<const std::byte*>(kMagic),
                   reinterpret_cast<const std::byte*>(kMagic) + 4);
    w.put(stream.version);
    for (const Statement& st : stream.statements) {
        Writer body;
        uint16_t id = kBlankId;
        uint16_t argc = 0;
        if (st.kind == Statement::Kind::Comment) {
            id = kCommentId;
            body.put_string(st.name);
        } else if (st.kind == Statement::Kind::Call) {
            id = call_id(st.name).value_or(kBlankId);
            argc = static_cast<uint16_t>(st.arguments.size());
            for (const Value& v : st.arguments) body.put_value(v);
            body.put_string(st.trailing_comment);
        }
        w.put(id);
        w.put(argc);
        w.put(static_cast<uint32_t>(body.bytes.size()));
        w.bytes.insert(w.bytes.end(), body.bytes.begin(), body.bytes.end());
    }
    return std::move(w.bytes);
}

ParseResult unpack(std::span<const std::byte> bytes) { return Reader(bytes).run(); }

}  // namespace sm2::runtime::cs
