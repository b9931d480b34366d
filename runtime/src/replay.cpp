// The replayer: command-stream statements -> Device calls (docs/command-stream.md, "Calls").
// Every call has one entry in kCalls: its name, argument counts, usage text and a function that
// converts the arguments and calls the Device. Conversion problems throw ArgumentError, which
// becomes the statement's diagnostic before anything reaches the Device.
#include "sm2/runtime/replay.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstring>
#include <exception>
#include <new>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "sm2/isa/bytecode.h"
#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/formats.h"
#include "sm2/runtime/primitive_assembly.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {

namespace {

using cs::Value;
using Kind = cs::Value::Kind;

struct ArgumentError {
    std::string message;
};

std::string kind_name(Kind kind) {
    switch (kind) {
    case Kind::Integer: return "an integer";
    case Kind::Float: return "a float";
    case Kind::Identifier: return "a name";
    case Kind::String: return "a string";
    case Kind::Tuple: return "a tuple";
    case Kind::Blob: return "a blob";
    case Kind::SideFile: return "a side file";
    case Kind::Heredoc: return "a heredoc";
    }
    return "a value";
}

// "a name 'FOO'", "an integer 12": what the stream wrote, for messages.
std::string describe(const Value& v) {
    switch (v.kind) {
    case Kind::Integer: return kind_name(v.kind) + " " + std::to_string(v.integer);
    case Kind::Identifier: return kind_name(v.kind) + " '" + v.text + "'";
    case Kind::String: return kind_name(v.kind) + " \"" + v.text + "\"";
    default: return kind_name(v.kind);
    }
}

// Every name of an enum family, for "expected one of" messages.
std::string family_names(EnumFamily family) {
    std::string names;
    for (const std::string_view name : enum_names(family)) {
        if (!names.empty()) names += ", ";
        names += name;
    }
    return names;
}

// The arguments of one call, converted on demand; `i` is 0-based, messages count from 1.
class Args {
public:
    explicit Args(std::span<const Value> values) : values_(values) {}

    [[nodiscard]] size_t size() const { return values_.size(); }
    [[nodiscard]] std::span<const Value> values() const { return values_; }
    [[nodiscard]] const Value& at(size_t i) const { return values_[i]; }

    [[noreturn]] void fail(size_t i, std::string_view what, const std::string& why) const {
        throw ArgumentError{"argument " + std::to_string(i + 1) + " (" + std::string(what) + "): " + why};
    }
    [[noreturn]] void wrong_kind(size_t i, std::string_view what, std::string_view expected) const {
        fail(i, what, "expected " + std::string(expected) + ", got " + describe(values_[i]));
    }

    [[nodiscard]] int64_t integer(size_t i, std::string_view what) const {
        const Value& v = values_[i];
        if (v.kind != Kind::Integer) wrong_kind(i, what, "an integer");
        return v.integer;
    }
    [[nodiscard]] uint32_t u32(size_t i, std::string_view what) const {
        const int64_t v = integer(i, what);
        if (v < 0 || v > 0xFFFFFFFFll) fail(i, what, std::to_string(v) + " is not an unsigned 32-bit integer");
        return static_cast<uint32_t>(v);
    }
    [[nodiscard]] int32_t i32(size_t i, std::string_view what) const {
        const int64_t v = integer(i, what);
        if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max())
            fail(i, what, std::to_string(v) + " is not a signed 32-bit integer");
        return static_cast<int32_t>(v);
    }
    [[nodiscard]] float f32(size_t i, std::string_view what) const {
        const Value& v = values_[i];
        if (v.kind != Kind::Float && v.kind != Kind::Integer) wrong_kind(i, what, "a number");
        return v.as_float();
    }
    [[nodiscard]] const std::string& identifier(size_t i, std::string_view what) const {
        const Value& v = values_[i];
        if (v.kind != Kind::Identifier) wrong_kind(i, what, "a name");
        return v.text;
    }
    // A resource handle; NULL (unbind) becomes "".
    [[nodiscard]] std::string binding(size_t i, std::string_view what) const {
        const std::string& name = identifier(i, what);
        return name == "NULL" ? std::string() : name;
    }
    [[nodiscard]] const std::string& string(size_t i, std::string_view what) const {
        const Value& v = values_[i];
        if (v.kind != Kind::String) wrong_kind(i, what, "a string (\"...\")");
        return v.text;
    }
    [[nodiscard]] uint32_t enumeration(size_t i, std::string_view what, EnumFamily family) const {
        const std::string& name = identifier(i, what);
        if (auto value = enum_value(family, name)) return *value;
        fail(i, what, "unknown name '" + name + "' (expected one of " + family_names(family) + ")");
    }
    [[nodiscard]] Format format(size_t i, std::string_view what) const {
        const std::string& name = identifier(i, what);
        if (const FormatInfo* info = find_format(name)) return info->format;
        fail(i, what, "unknown format '" + name + "'");
    }
    // A keyword flag such as RENDERTARGET (with or without `prefix`).
    void flag(size_t i, std::string_view what, std::string_view keyword, std::string_view prefix) const {
        std::string_view name = identifier(i, what);
        if (name.substr(0, prefix.size()) == prefix) name.remove_prefix(prefix.size());
        if (name != keyword) fail(i, what, "expected " + std::string(keyword) + ", got " + describe(values_[i]));
    }
    // Inline bytes: a blob or a side file.
    [[nodiscard]] std::span<const std::byte> bytes(size_t i, std::string_view what) const {
        const Value& v = values_[i];
        if (v.kind != Kind::Blob && v.kind != Kind::SideFile) wrong_kind(i, what, "a blob (TYPE[ ... ]) or a side file (@\"file\")");
        return v.bytes;
    }
    // Bytes as little-endian 32-bit elements (floats, integers, BOOLs).
    template <typename T>
    [[nodiscard]] std::vector<T> words(size_t i, std::string_view what) const {
        static_assert(sizeof(T) == 4);
        const auto data = bytes(i, what);
        if (data.size() % 4 != 0)
            fail(i, what, std::to_string(data.size()) + " bytes is not a whole number of 32-bit values");
        std::vector<T> out(data.size() / 4);
        if (!data.empty()) std::memcpy(out.data(), data.data(), data.size());
        return out;
    }

private:
    std::span<const Value> values_;
};

// A flag word of a bit family: a number, a name, or a tuple of names and numbers, OR-ed
// (COLORWRITEENABLE { RED GREEN }, COLORARG1 { TEXTURE COMPLEMENT }, SetFVF { XYZ NORMAL TEX1 }).
uint32_t flag_word(const Args& args, size_t i, const std::string& what, EnumFamily family) {
    const Value& v = args.at(i);
    if (v.kind == Kind::Integer) return args.u32(i, what);
    if (v.kind == Kind::Identifier) return args.enumeration(i, what, family);
    if (v.kind != Kind::Tuple) args.wrong_kind(i, what, "a name, a tuple of names or a number");
    uint32_t bits = 0;
    for (size_t k = 0; k < v.items.size(); ++k) {
        const Value& item = v.items[k];
        const std::string where = "item " + std::to_string(k + 1) + ": ";
        if (item.kind == Kind::Integer) {
            if (item.integer < 0 || item.integer > 0xFFFFFFFFll)
                args.fail(i, what, where + std::to_string(item.integer) + " is not an unsigned 32-bit integer");
            bits |= static_cast<uint32_t>(item.integer);
        } else if (item.kind == Kind::Identifier) {
            const auto value = enum_value(family, item.text);
            if (!value)
                args.fail(i, what, where + "unknown name '" + item.text + "' (expected one of " + family_names(family) + ")");
            bits |= *value;
        } else {
            args.fail(i, what, where + "expected a name or a number, got " + describe(item));
        }
    }
    return bits;
}

// The DWORD of a render, sampler or texture stage state value, typed by the state
// (docs/command-stream.md).
uint32_t state_value(const Args& args, size_t i, const StateInfo& state) {
    const Value& v = args.at(i);
    const std::string what = std::string(state.name) + " value";
    switch (state.kind) {
    case StateValueKind::Enum:
        if (v.kind != Kind::Identifier)
            args.fail(i, what, "expected a name of " + family_names(state.family) + ", got " + describe(v));
        return args.enumeration(i, what, state.family);
    case StateValueKind::Bool:
        if (v.kind != Kind::Identifier) args.fail(i, what, "expected TRUE or FALSE, got " + describe(v));
        return args.enumeration(i, what, EnumFamily::Bool);
    case StateValueKind::Float:
        return std::bit_cast<uint32_t>(args.f32(i, what));
    case StateValueKind::Bits:
        if (state.family != EnumFamily::Bool) return flag_word(args, i, what, state.family);
        return args.u32(i, what);
    case StateValueKind::Color:
    case StateValueKind::Integer:
        return args.u32(i, what);
    }
    return 0;
}

// D3DCLEAR flags: one name, a tuple of names, or a number.
uint32_t clear_flags(const Args& args, size_t i) {
    const Value& v = args.at(i);
    if (v.kind == Kind::Integer) return args.u32(i, "flags");
    if (v.kind == Kind::Identifier) return args.enumeration(i, "flags", EnumFamily::ClearFlags);
    if (v.kind == Kind::Tuple) {
        if (v.items.empty()) args.fail(i, "flags", "an empty tuple clears nothing");
        uint32_t flags = 0;
        const Args names(v.items);
        for (size_t k = 0; k < names.size(); ++k) flags |= names.enumeration(k, "flags", EnumFamily::ClearFlags);
        return flags;
    }
    args.wrong_kind(i, "flags", "TARGET/ZBUFFER/STENCIL, a tuple of them or a number");
}

uint32_t cube_face(const Args& args, size_t i) {
    const Value& v = args.at(i);
    if (v.kind == Kind::Integer) return args.u32(i, "face");
    if (auto face = enum_value(EnumFamily::CubeFace, args.identifier(i, "face"))) return *face;
    args.fail(i, "face", "unknown cube face '" + args.at(i).text + "' (expected one of " +
                             family_names(EnumFamily::CubeFace) + ")");
}

VertexElement vertex_element(const Args& args, size_t i) {
    const Value& v = args.at(i);
    const std::string what = "element " + std::to_string(i);
    if (v.kind != Kind::Tuple)
        args.wrong_kind(i, what, "a tuple { stream offset type method usage usage_index }");
    if (v.items.size() != 6)
        args.fail(i, what, "a vertex element has 6 fields (stream offset type method usage usage_index), got " +
                               std::to_string(v.items.size()));
    const Args fields(v.items);
    auto narrow = [&](size_t k, std::string_view field, uint32_t max) {
        const uint32_t value = fields.u32(k, field);
        if (value > max)
            fields.fail(k, field, std::to_string(value) + " is out of range (0 to " + std::to_string(max) + ")");
        return value;
    };
    try {
        VertexElement e;
        e.stream = static_cast<uint16_t>(narrow(0, "stream", 0xFFFF));
        e.offset = static_cast<uint16_t>(narrow(1, "offset", 0xFFFF));
        e.type = static_cast<uint8_t>(fields.enumeration(2, "type", EnumFamily::DeclType));
        e.method = static_cast<uint8_t>(fields.enumeration(3, "method", EnumFamily::DeclMethod));
        e.usage = static_cast<uint8_t>(fields.enumeration(4, "usage", EnumFamily::DeclUsage));
        e.usage_index = static_cast<uint8_t>(narrow(5, "usage_index", 0xFF));
        return e;
    } catch (const ArgumentError& inner) {
        // "argument 3 (element 2): field 3 (type): unknown type ..."
        std::string message = inner.message;
        message.replace(0, std::string_view("argument").size(), "field");
        args.fail(i, what, message);
    }
}

// A D3DMATRIX: an f32 blob of 16 floats, row by row.
Matrix4 matrix(const Args& args, size_t i) {
    const std::vector<float> values = args.words<float>(i, "matrix");
    if (values.size() != 16) args.fail(i, "matrix", std::to_string(values.size()) + " floats, a matrix has 16");
    Matrix4 m;
    std::copy(values.begin(), values.end(), m.begin());
    return m;
}

// The numbers of a tuple of exactly `count` of them ({ r g b a }, { x y z }).
std::vector<float> number_tuple(const Args& args, size_t i, std::string_view what, size_t count,
                                std::string_view fields) {
    const Value& v = args.at(i);
    if (v.kind != Kind::Tuple) args.wrong_kind(i, what, "a tuple { " + std::string(fields) + " }");
    if (v.items.size() != count)
        args.fail(i, what, "expected " + std::to_string(count) + " numbers { " + std::string(fields) + " }, got " +
                               std::to_string(v.items.size()));
    const Args items(v.items);
    std::vector<float> out;
    for (size_t k = 0; k < count; ++k) out.push_back(items.f32(k, what));
    return out;
}
ColorValue color_value(const Args& args, size_t i, std::string_view what) {
    const auto c = number_tuple(args, i, what, 4, "r g b a");
    return ColorValue{c[0], c[1], c[2], c[3]};
}
Vector3 vector3(const Args& args, size_t i, std::string_view what) {
    const auto c = number_tuple(args, i, what, 3, "x y z");
    return Vector3{c[0], c[1], c[2]};
}

uint32_t transform_state(const Args& args, size_t i) {
    const std::string& name = args.identifier(i, "transform state");
    if (auto value = transform_state_value(name)) return *value;
    args.fail(i, "transform state",
              "unknown name '" + name + "' (expected one of VIEW, PROJECTION, TEXTURE0..TEXTURE7, WORLD, WORLD1..WORLD3, "
              "WORLDMATRIX0..WORLDMATRIX255)");
}

bool looks_like_bytecode(std::span<const std::byte> bytes) {
    if (bytes.size() < 8 || bytes.size() % 4 != 0) return false;
    uint32_t version = 0;
    std::memcpy(&version, bytes.data(), 4);
    const uint32_t type = version >> 16;
    return type == 0xFFFE || type == 0xFFFF;
}

// The context of one statement: the device, the options, and a line for the diagnostic when a
// call can name a more precise one than its own (an error inside an asm heredoc).
struct Context {
    Device& device;
    const ReplayOptions& options;
    uint32_t line = 0;
    uint32_t diagnostic_line = 0;
};

// The program from an assembler's or compiler's answer, or its first error as the argument's,
// at its line inside the heredoc.
isa::Program translated(Context& c, const Args& args, size_t i, AssembledShader assembled, const std::string& where,
                        const char* what) {
    if (assembled.program) return std::move(*assembled.program);
    std::string message = assembled.error.empty() ? std::string("the ") + what + " has errors" : assembled.error;
    if (assembled.line > 0) {
        message = where + " line " + std::to_string(assembled.line) + ": " + message;
        // A heredoc's text starts on the line after the call's.
        if (args.at(i).kind == Kind::Heredoc && c.line > 0) c.diagnostic_line = c.line + assembled.line;
    } else {
        message = where + ": " + message;
    }
    throw ArgumentError{message};
}

isa::Program assemble_text(Context& c, const Args& args, size_t i, std::string_view text, const std::string& where) {
    if (!c.options.assembler)
        args.fail(i, "shader", "no assembler is available to this replay for shader text");
    return translated(c, args, i, c.options.assembler(text, c.device.max_instruction_slots()), where, "assembly");
}

isa::Program compile_hlsl(Context& c, const Args& args, size_t i, std::string_view source, isa::ShaderType stage) {
    if (!c.options.hlsl_compiler)
        args.fail(i, "shader", "HLSL needs sm2 compile support (no HLSL compiler is available to this replay)");
    return translated(c, args, i, c.options.hlsl_compiler(source, stage, c.device.max_instruction_slots()), "HLSL",
                      "HLSL");
}

isa::Program decode_bytecode(const Args& args, size_t i, std::span<const std::byte> bytes, std::string where) {
    if (!where.empty()) where += ' ';
    if (bytes.size() % 4 != 0)
        args.fail(i, "shader", where + std::to_string(bytes.size()) + " bytes is not a whole number of tokens");
    auto decoded = isa::decode_bytes(bytes);
    if (!decoded.ok()) {
        const std::string why = decoded.error ? decoded.error->to_string() : "not shader bytecode";
        args.fail(i, "shader", where + "bytecode " + why);
    }
    return std::move(*decoded.program);
}

// A shader from an asm or hlsl heredoc, a side file (text or bytecode) or a blob of bytecode.
isa::Program shader_program(Context& c, const Args& args, size_t i, isa::ShaderType stage) {
    const Value& v = args.at(i);
    switch (v.kind) {
    case Kind::Heredoc:
        if (v.language == Value::Language::Hlsl)
            return compile_hlsl(c, args, i, {reinterpret_cast<const char*>(v.bytes.data()), v.bytes.size()}, stage);
        return assemble_text(c, args, i, {reinterpret_cast<const char*>(v.bytes.data()), v.bytes.size()}, "assembly");
    case Kind::SideFile: {
        const std::string where = "\"" + v.text + "\"";
        if (looks_like_bytecode(v.bytes)) return decode_bytecode(args, i, v.bytes, where);
        return assemble_text(c, args, i, {reinterpret_cast<const char*>(v.bytes.data()), v.bytes.size()}, where);
    }
    case Kind::Blob: return decode_bytecode(args, i, v.bytes, "");
    default: break;
    }
    args.wrong_kind(i, "shader", "asm<<TAG or hlsl<<TAG text, a side file or a u32[] blob of bytecode");
}

// A LoadTexture file name, inside the read root (refused otherwise, as argument `i`).
std::string resolve_path(const ReplayOptions& options, const Args& args, size_t i, const std::string& path) {
    std::string error;
    const std::string base = options.base_dir.empty() ? std::string(".") : options.base_dir;
    const auto full = resolve_inside(options.root_dir.empty() ? base : options.root_dir, base, path, error);
    if (!full) args.fail(i, "file", error);
    return *full;
}

// A draw's working memory (its vertex numbers, shaded vertices and primitives: about 256 bytes a
// draw vertex for a vertex shader writing every vs_2_0 output) is checked against the device's
// memory limit before the Device allocates it: E_OUTOFMEMORY, as D3D9 answers, rather than a
// std::bad_alloc or the host's memory exhausted by a one-line draw.
constexpr uint64_t kDrawBytesPerVertex = 256;

std::optional<CallResult> draw_memory(const Context& c, const char* call, uint32_t type, uint32_t primitive_count) {
    const auto pt = primitive_type_from(type);
    const auto vertices = pt ? vertices_for(*pt, primitive_count) : std::nullopt;
    if (!vertices) return std::nullopt;  // not a valid draw: the Device says why
    const uint64_t bytes = uint64_t{*vertices} * kDrawBytesPerVertex;
    if (bytes <= c.device.memory_limit()) return std::nullopt;
    return CallResult::fail(std::string(call) + ": " + std::to_string(*vertices) + " vertices need about " +
                                std::to_string(bytes) + " bytes of working memory, more than the " +
                                std::to_string(c.device.memory_limit()) + "-byte memory limit",
                            CallError::OutOfMemory);
}

// Viewport, scissor rectangle and clip plane take their numbers either one by one or in a tuple.
std::vector<Value> flatten_tuples(std::span<const Value> values) {
    std::vector<Value> out;
    for (const Value& v : values) {
        if (v.kind == Kind::Tuple) out.insert(out.end(), v.items.begin(), v.items.end());
        else out.push_back(v);
    }
    return out;
}

void expect_count(std::span<const Value> values, size_t count, std::string_view usage) {
    if (values.size() != count)
        throw ArgumentError{"expects " + std::to_string(count) + " numbers (" + std::string(usage) + "), got " +
                            std::to_string(values.size())};
}

// A rectangle { left top right bottom } (RECT/D3DRECT), or NULL for the whole surface.
std::optional<PixelRect> optional_rect(const Args& args, size_t i, std::string_view what) {
    const Value& v = args.at(i);
    if (v.kind == Kind::Identifier && v.text == "NULL") return std::nullopt;
    if (v.kind != Kind::Tuple) args.wrong_kind(i, what, "a rectangle { left top right bottom } or NULL");
    if (v.items.size() != 4) args.fail(i, what, "a rectangle has 4 numbers (left top right bottom), got " + std::to_string(v.items.size()));
    const Args n(v.items);
    return PixelRect{n.i32(0, "left"), n.i32(1, "top"), n.i32(2, "right"), n.i32(3, "bottom")};
}

// CreateTexture/CreateCubeTexture/CreateVolumeTexture keywords after the format, in any order:
// RENDERTARGET, DYNAMIC (with or without D3DUSAGE_) and a pool (DEFAULT, MANAGED, SYSTEMMEM,
// SCRATCH, with or without D3DPOOL_).
TextureUsage texture_usage(const Args& args, size_t first) {
    TextureUsage usage;
    for (size_t i = first; i < args.size(); ++i) {
        const std::string_view what = "usage or pool";
        std::string_view name = args.identifier(i, what);
        if (auto pool = enum_value(EnumFamily::Pool, name)) {
            usage.pool = static_cast<Pool>(*pool);
            continue;
        }
        if (name.substr(0, 9) == "D3DUSAGE_") name.remove_prefix(9);
        if (name == "RENDERTARGET") usage.render_target = true;
        else if (name == "DYNAMIC") usage.dynamic = true;
        else args.fail(i, what, "expected RENDERTARGET, DYNAMIC or a pool (" + family_names(EnumFamily::Pool) + "), got " + describe(args.at(i)));
    }
    return usage;
}

using Handler = CallResult (*)(Context&, const Args&);

struct CallSpec {
    std::string_view name;
    size_t min_args, max_args;
    std::string_view usage;
    Handler run;
};

constexpr size_t kMany = std::numeric_limits<size_t>::max();

CallResult create_shader(Context& c, const Args& a, bool vertex) {
    const std::string& name = a.identifier(0, "name");
    isa::Program program = shader_program(c, a, 1, vertex ? isa::ShaderType::Vertex : isa::ShaderType::Pixel);
    return vertex ? c.device.create_vertex_shader(name, std::move(program))
                  : c.device.create_pixel_shader(name, std::move(program));
}

const CallSpec kCalls[] = {
    {"CreateDevice", 3, 4, "width height format [depth_format]",
     [](Context& c, const Args& a) {
         std::optional<Format> depth;
         if (a.size() == 4) depth = a.format(3, "depth_format");
         return c.device.create_device(a.u32(0, "width"), a.u32(1, "height"), a.format(2, "format"), depth);
     }},
    {"Reset", 3, 4, "width height format [depth_format]",
     [](Context& c, const Args& a) {
         std::optional<Format> depth;
         if (a.size() == 4) depth = a.format(3, "depth_format");
         return c.device.reset(a.u32(0, "width"), a.u32(1, "height"), a.format(2, "format"), depth);
     }},
    {"CreateVertexBuffer", 2, 2, "name length",
     [](Context& c, const Args& a) {
         return c.device.create_vertex_buffer(a.identifier(0, "name"), a.u32(1, "length"));
     }},
    {"CreateIndexBuffer", 3, 3, "name length INDEX16|INDEX32",
     [](Context& c, const Args& a) {
         return c.device.create_index_buffer(a.identifier(0, "name"), a.u32(1, "length"), a.format(2, "format"));
     }},
    {"CreateTexture", 5, 8, "name width height levels format [RENDERTARGET] [DYNAMIC] [pool]",
     [](Context& c, const Args& a) {
         const TextureUsage usage = texture_usage(a, 5);
         return c.device.create_texture(a.identifier(0, "name"), a.u32(1, "width"), a.u32(2, "height"),
                                        a.u32(3, "levels"), a.format(4, "format"), usage);
     }},
    {"CreateCubeTexture", 4, 7, "name edge levels format [RENDERTARGET] [DYNAMIC] [pool]",
     [](Context& c, const Args& a) {
         const TextureUsage usage = texture_usage(a, 4);
         return c.device.create_cube_texture(a.identifier(0, "name"), a.u32(1, "edge"), a.u32(2, "levels"),
                                             a.format(3, "format"), usage);
     }},
    {"CreateVolumeTexture", 6, 8, "name width height depth levels format [DYNAMIC] [pool]",
     [](Context& c, const Args& a) {
         const TextureUsage usage = texture_usage(a, 6);
         return c.device.create_volume_texture(a.identifier(0, "name"), a.u32(1, "width"), a.u32(2, "height"),
                                               a.u32(3, "depth"), a.u32(4, "levels"), a.format(5, "format"), usage);
     }},
    {"CreateOffscreenPlainSurface", 5, 5, "name width height format pool",
     [](Context& c, const Args& a) {
         return c.device.create_offscreen_plain_surface(a.identifier(0, "name"), a.u32(1, "width"), a.u32(2, "height"),
                                                        a.format(3, "format"),
                                                        static_cast<Pool>(a.enumeration(4, "pool", EnumFamily::Pool)));
     }},
    {"CreateRenderTarget", 4, 4, "name width height format",
     [](Context& c, const Args& a) {
         return c.device.create_render_target(a.identifier(0, "name"), a.u32(1, "width"), a.u32(2, "height"),
                                              a.format(3, "format"));
     }},
    {"CreateDepthStencilSurface", 4, 4, "name width height format",
     [](Context& c, const Args& a) {
         return c.device.create_depth_stencil_surface(a.identifier(0, "name"), a.u32(1, "width"),
                                                      a.u32(2, "height"), a.format(3, "format"));
     }},
    {"CreateVertexDeclaration", 1, kMany, "name { stream offset type method usage usage_index }...",
     [](Context& c, const Args& a) {
         const std::string& name = a.identifier(0, "name");
         std::vector<VertexElement> elements;
         for (size_t i = 1; i < a.size(); ++i) elements.push_back(vertex_element(a, i));
         return c.device.create_vertex_declaration(name, std::move(elements));
     }},
    {"CreateVertexShader", 2, 2, "name asm<<TAG | @\"file\" | u32[ bytecode ]",
     [](Context& c, const Args& a) { return create_shader(c, a, true); }},
    {"CreatePixelShader", 2, 2, "name asm<<TAG | @\"file\" | u32[ bytecode ]",
     [](Context& c, const Args& a) { return create_shader(c, a, false); }},
    {"Lock", 3, 3, "buffer offset data",
     [](Context& c, const Args& a) {
         return c.device.lock(a.identifier(0, "buffer"), a.u32(1, "offset"), a.bytes(2, "data"));
     }},
    {"LockRect", 3, 5, "texture [face] level [rect] data",
     [](Context& c, const Args& a) {
         // A rectangle is the tuple before the data; a face, the argument after the texture
         // when one more is left.
         const bool rect = a.at(a.size() - 2).kind == Kind::Tuple;
         const bool face = a.size() == (rect ? 5u : 4u);
         if (!face && a.size() == 5) a.fail(3, "rect", "expected a rectangle { left top right bottom }, got " + describe(a.at(3)));
         const std::string& name = a.identifier(0, "texture");
         const uint32_t f = face ? cube_face(a, 1) : 0;
         const uint32_t level = a.u32(face ? 2 : 1, "level");
         if (!rect) return c.device.lock_rect(name, f, level, a.bytes(a.size() - 1, "data"));
         const auto r = optional_rect(a, a.size() - 2, "rect");
         return c.device.lock_rect(name, f, level, *r, a.bytes(a.size() - 1, "data"));
     }},
    {"LockBox", 3, 4, "texture level [{ left top front right bottom back }] data",
     [](Context& c, const Args& a) {
         if (a.size() == 3) return c.device.lock_box(a.identifier(0, "texture"), a.u32(1, "level"), a.bytes(2, "data"));
         const Value& v = a.at(2);
         if (v.kind != Kind::Tuple) a.wrong_kind(2, "box", "a box { left top front right bottom back }");
         if (v.items.size() != 6)
             a.fail(2, "box", "a box has 6 numbers (left top front right bottom back), got " + std::to_string(v.items.size()));
         const Args n(v.items);
         const VolumeBox box{n.u32(0, "left"), n.u32(1, "top"), n.u32(2, "front"), n.u32(3, "right"), n.u32(4, "bottom"), n.u32(5, "back")};
         return c.device.lock_box(a.identifier(0, "texture"), a.u32(1, "level"), box, a.bytes(3, "data"));
     }},
    {"LoadTexture", 2, 3, "name \"file\" [GENERATEMIPS]",
     [](Context& c, const Args& a) {
         if (a.size() == 3) a.flag(2, "option", "GENERATEMIPS", "");
         return c.device.load_texture(a.identifier(0, "name"), resolve_path(c.options, a, 1, a.string(1, "file")),
                                      a.size() == 3);
     }},
    {"GenerateMipSubLevels", 1, 1, "texture",
     [](Context& c, const Args& a) { return c.device.generate_mip_sub_levels(a.identifier(0, "texture")); }},
    {"Release", 1, 1, "name", [](Context& c, const Args& a) { return c.device.release(a.identifier(0, "name")); }},
    {"SetVertexDeclaration", 1, 1, "name|NULL",
     [](Context& c, const Args& a) { return c.device.set_vertex_declaration(a.binding(0, "declaration")); }},
    {"SetVertexShader", 1, 1, "name|NULL",
     [](Context& c, const Args& a) { return c.device.set_vertex_shader(a.binding(0, "shader")); }},
    {"SetPixelShader", 1, 1, "name|NULL",
     [](Context& c, const Args& a) { return c.device.set_pixel_shader(a.binding(0, "shader")); }},
    {"SetIndices", 1, 1, "name|NULL",
     [](Context& c, const Args& a) { return c.device.set_indices(a.binding(0, "index buffer")); }},
    {"SetRenderState", 2, 2, "STATE value",
     [](Context& c, const Args& a) {
         const std::string& name = a.identifier(0, "state");
         const StateInfo* state = find_render_state(name);
         if (!state) a.fail(0, "state", "unknown render state '" + name + "'");
         return c.device.set_render_state(state->id, state_value(a, 1, *state));
     }},
    {"SetSamplerState", 3, 3, "sampler STATE value",
     [](Context& c, const Args& a) {
         const uint32_t sampler = a.u32(0, "sampler");
         const std::string& name = a.identifier(1, "state");
         const StateInfo* state = find_sampler_state(name);
         if (!state) a.fail(1, "state", "unknown sampler state '" + name + "'");
         return c.device.set_sampler_state(sampler, state->id, state_value(a, 2, *state));
     }},
    {"SetTexture", 2, 2, "stage name|NULL",
     [](Context& c, const Args& a) { return c.device.set_texture(a.u32(0, "stage"), a.binding(1, "texture")); }},
    {"SetStreamSource", 4, 4, "stream buffer|NULL offset stride",
     [](Context& c, const Args& a) {
         return c.device.set_stream_source(a.u32(0, "stream"), a.binding(1, "buffer"), a.u32(2, "offset"),
                                           a.u32(3, "stride"));
     }},
    {"SetVertexShaderConstantF", 2, 2, "start f32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_vertex_shader_constant_f(a.u32(0, "start"), a.words<float>(1, "values"));
     }},
    {"SetVertexShaderConstantI", 2, 2, "start i32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_vertex_shader_constant_i(a.u32(0, "start"), a.words<int32_t>(1, "values"));
     }},
    {"SetVertexShaderConstantB", 2, 2, "start u32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_vertex_shader_constant_b(a.u32(0, "start"), a.words<uint32_t>(1, "values"));
     }},
    {"SetPixelShaderConstantF", 2, 2, "start f32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_pixel_shader_constant_f(a.u32(0, "start"), a.words<float>(1, "values"));
     }},
    {"SetPixelShaderConstantI", 2, 2, "start i32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_pixel_shader_constant_i(a.u32(0, "start"), a.words<int32_t>(1, "values"));
     }},
    {"SetPixelShaderConstantB", 2, 2, "start u32[...]",
     [](Context& c, const Args& a) {
         return c.device.set_pixel_shader_constant_b(a.u32(0, "start"), a.words<uint32_t>(1, "values"));
     }},
    {"SetViewport", 1, 6, "x y width height min_z max_z",
     [](Context& c, const Args& args) {
         const std::vector<Value> values = flatten_tuples(args.values());
         expect_count(values, 6, "x y width height min_z max_z");
         const Args a(values);
         return c.device.set_viewport(Viewport{a.u32(0, "x"), a.u32(1, "y"), a.u32(2, "width"), a.u32(3, "height"),
                                               a.f32(4, "min_z"), a.f32(5, "max_z")});
     }},
    {"SetScissorRect", 1, 4, "left top right bottom",
     [](Context& c, const Args& args) {
         const std::vector<Value> values = flatten_tuples(args.values());
         expect_count(values, 4, "left top right bottom");
         const Args a(values);
         return c.device.set_scissor_rect(
             PixelRect{a.i32(0, "left"), a.i32(1, "top"), a.i32(2, "right"), a.i32(3, "bottom")});
     }},
    {"SetClipPlane", 2, 5, "index a b c d",
     [](Context& c, const Args& args) {
         const std::vector<Value> values = flatten_tuples(args.values());
         expect_count(values, 5, "index a b c d");
         const Args a(values);
         return c.device.set_clip_plane(a.u32(0, "index"),
                                        Vec4{a.f32(1, "a"), a.f32(2, "b"), a.f32(3, "c"), a.f32(4, "d")});
     }},
    {"SetRenderTarget", 2, 2, "index surface|NULL",
     [](Context& c, const Args& a) { return c.device.set_render_target(a.u32(0, "index"), a.binding(1, "surface")); }},
    {"SetDepthStencilSurface", 1, 1, "surface|NULL",
     [](Context& c, const Args& a) { return c.device.set_depth_stencil_surface(a.binding(0, "surface")); }},
    {"Clear", 4, kMany, "flags color z stencil [{ x1 y1 x2 y2 }...]",
     [](Context& c, const Args& a) {
         std::vector<PixelRect> rects;
         for (size_t i = 4; i < a.size(); ++i) {
             if (a.at(i).kind != Kind::Tuple) a.wrong_kind(i, "rect", "a rectangle { x1 y1 x2 y2 }");
             rects.push_back(*optional_rect(a, i, "rect"));
         }
         return c.device.clear(clear_flags(a, 0), a.u32(1, "color"), a.f32(2, "z"), a.u32(3, "stencil"), rects);
     }},
    {"BeginScene", 0, 0, "no arguments", [](Context& c, const Args&) { return c.device.begin_scene(); }},
    {"EndScene", 0, 0, "no arguments", [](Context& c, const Args&) { return c.device.end_scene(); }},
    {"DrawPrimitive", 3, 3, "type start_vertex primitive_count",
     [](Context& c, const Args& a) {
         const uint32_t type = a.enumeration(0, "primitive type", EnumFamily::PrimitiveType);
         const uint32_t start = a.u32(1, "start_vertex"), count = a.u32(2, "primitive_count");
         if (auto refused = draw_memory(c, "DrawPrimitive", type, count)) return *refused;
         return c.device.draw_primitive(type, start, count);
     }},
    {"DrawIndexedPrimitive", 6, 6, "type base_vertex min_index num_vertices start_index primitive_count",
     [](Context& c, const Args& a) {
         const uint32_t type = a.enumeration(0, "primitive type", EnumFamily::PrimitiveType);
         const int32_t base_vertex = a.i32(1, "base_vertex");
         const uint32_t min_index = a.u32(2, "min_index"), num_vertices = a.u32(3, "num_vertices");
         const uint32_t start_index = a.u32(4, "start_index"), count = a.u32(5, "primitive_count");
         if (auto refused = draw_memory(c, "DrawIndexedPrimitive", type, count)) return *refused;
         return c.device.draw_indexed_primitive(type, base_vertex, min_index, num_vertices, start_index, count);
     }},
    {"DrawPrimitiveUP", 4, 4, "type primitive_count stride data",
     [](Context& c, const Args& a) {
         const uint32_t type = a.enumeration(0, "primitive type", EnumFamily::PrimitiveType);
         const uint32_t count = a.u32(1, "primitive_count");
         const uint32_t stride = a.u32(2, "stride");
         if (auto refused = draw_memory(c, "DrawPrimitiveUP", type, count)) return *refused;
         return c.device.draw_primitive_up(type, count, a.bytes(3, "data"), stride);
     }},
    {"DrawIndexedPrimitiveUP", 8, 8,
     "type min_index num_vertices primitive_count index_data INDEX16|INDEX32 vertex_data stride",
     [](Context& c, const Args& a) {
         const uint32_t type = a.enumeration(0, "primitive type", EnumFamily::PrimitiveType);
         const uint32_t min_index = a.u32(1, "min_index"), num_vertices = a.u32(2, "num_vertices");
         const uint32_t count = a.u32(3, "primitive_count");
         const auto indices = a.bytes(4, "index_data");
         const Format format = a.format(5, "index format");
         if (format != Format::INDEX16 && format != Format::INDEX32)
             a.fail(5, "index format", "expected INDEX16 or INDEX32, got '" + a.at(5).text + "'");
         const auto vertices = a.bytes(6, "vertex_data");
         if (auto refused = draw_memory(c, "DrawIndexedPrimitiveUP", type, count)) return *refused;
         return c.device.draw_indexed_primitive_up(type, min_index, num_vertices, count, indices, format, vertices,
                                                   a.u32(7, "stride"));
     }},
    {"StretchRect", 2, 5, "source [source_rect] destination [destination_rect] [filter]",
     [](Context& c, const Args& a) {
         // Rectangles are tuples, so each is recognised where it may stand.
         size_t i = 0;
         const std::string& source = a.identifier(i++, "source");
         std::optional<PixelRect> source_rect, destination_rect;
         if (i < a.size() && a.at(i).kind == Kind::Tuple) source_rect = optional_rect(a, i++, "source_rect");
         if (i >= a.size()) throw ArgumentError{"expects a destination after the source"};
         const std::string& destination = a.identifier(i++, "destination");
         if (i < a.size() && a.at(i).kind == Kind::Tuple) destination_rect = optional_rect(a, i++, "destination_rect");
         TextureFilter filter = TextureFilter::None;
         if (i < a.size()) filter = static_cast<TextureFilter>(a.enumeration(i++, "filter", EnumFamily::TextureFilter));
         if (i < a.size()) a.fail(i, "extra", "unexpected " + describe(a.at(i)) + " after the filter");
         return c.device.stretch_rect(source, source_rect, destination, destination_rect, filter);
     }},
    {"ColorFill", 2, 3, "surface [rect] color",
     [](Context& c, const Args& a) {
         const std::optional<PixelRect> rect = a.size() == 3 ? optional_rect(a, 1, "rect") : std::nullopt;
         return c.device.color_fill(a.identifier(0, "surface"), rect, a.u32(a.size() - 1, "color"));
     }},
    {"UpdateSurface", 6, 6, "source source_level source_rect|NULL destination destination_level { x y }|NULL",
     [](Context& c, const Args& a) {
         uint32_t x = 0, y = 0;
         const Value& point = a.at(5);
         if (!(point.kind == Kind::Identifier && point.text == "NULL")) {
             if (point.kind != Kind::Tuple || point.items.size() != 2) a.wrong_kind(5, "destination point", "a point { x y } or NULL");
             const Args xy(point.items);
             x = xy.u32(0, "x");
             y = xy.u32(1, "y");
         }
         return c.device.update_surface(a.identifier(0, "source"), a.u32(1, "source_level"), optional_rect(a, 2, "source_rect"),
                                        a.identifier(3, "destination"), a.u32(4, "destination_level"), x, y);
     }},
    {"UpdateTexture", 2, 2, "source destination",
     [](Context& c, const Args& a) {
         return c.device.update_texture(a.identifier(0, "source"), a.identifier(1, "destination"));
     }},
    {"GetRenderTargetData", 2, 2, "render_target destination",
     [](Context& c, const Args& a) {
         return c.device.get_render_target_data(a.identifier(0, "render_target"), a.identifier(1, "destination"));
     }},
    {"SetSoftwareVertexProcessing", 1, 1, "TRUE|FALSE",
     [](Context& c, const Args& a) {
         return c.device.set_software_vertex_processing(a.enumeration(0, "software", EnumFamily::Bool) != 0);
     }},
    {"SetGammaRamp", 2, 2, "swap_chain u16[ 256 red, 256 green, 256 blue ]",
     [](Context& c, const Args& a) {
         const auto data = a.bytes(1, "ramp");
         if (data.size() != 3 * 256 * 2) a.fail(1, "ramp", std::to_string(data.size()) + " bytes; a D3DGAMMARAMP is 768 WORDs (1536 bytes)");
         std::vector<uint16_t> ramp(3 * 256);
         std::memcpy(ramp.data(), data.data(), data.size());
         return c.device.set_gamma_ramp(a.u32(0, "swap_chain"), ramp);
     }},
    {"SetNPatchMode", 1, 1, "segments",
     [](Context& c, const Args& a) { return c.device.set_npatch_mode(a.f32(0, "segments")); }},
    {"CreateStateBlock", 2, 2, "name ALL|PIXELSTATE|VERTEXSTATE",
     [](Context& c, const Args& a) {
         return c.device.create_state_block(a.identifier(0, "name"),
                                            static_cast<StateBlockType>(a.enumeration(1, "type", EnumFamily::StateBlockType)));
     }},
    {"BeginStateBlock", 0, 0, "no arguments", [](Context& c, const Args&) { return c.device.begin_state_block(); }},
    {"EndStateBlock", 1, 1, "name",
     [](Context& c, const Args& a) { return c.device.end_state_block(a.identifier(0, "name")); }},
    {"Capture", 1, 1, "state_block",
     [](Context& c, const Args& a) { return c.device.capture_state_block(a.identifier(0, "state_block")); }},
    {"Apply", 1, 1, "state_block",
     [](Context& c, const Args& a) { return c.device.apply_state_block(a.identifier(0, "state_block")); }},
    {"Present", 0, 0, "no arguments", [](Context& c, const Args&) { return c.device.present(); }},
    {"SetDeviceLimits", 2, kMany, "NAME value ... (INSTRUCTIONSLOTS n)",
     [](Context& c, const Args& a) {
         if (a.size() % 2 != 0) a.fail(a.size() - 1, "limit", "expects NAME value pairs, got an odd number of arguments");
         for (size_t i = 0; i < a.size(); i += 2) {
             const std::string name = a.identifier(i, "limit name");
             if (name != "INSTRUCTIONSLOTS")
                 a.fail(i, "limit name", "unknown limit '" + name + "' (expected INSTRUCTIONSLOTS)");
             if (auto r = c.device.set_max_instruction_slots(a.u32(i + 1, "INSTRUCTIONSLOTS")); !r.ok) return r;
         }
         return CallResult::success();
     }},
    {"SetFVF", 1, 1, "fvf (a number, a name or a tuple: { XYZ NORMAL TEX1 })",
     [](Context& c, const Args& a) { return c.device.set_fvf(flag_word(a, 0, "fvf", EnumFamily::Fvf)); }},
    {"SetTransform", 2, 2, "STATE f32[ 16 floats ]",
     [](Context& c, const Args& a) { return c.device.set_transform(transform_state(a, 0), matrix(a, 1)); }},
    {"MultiplyTransform", 2, 2, "STATE f32[ 16 floats ]",
     [](Context& c, const Args& a) { return c.device.multiply_transform(transform_state(a, 0), matrix(a, 1)); }},
    {"SetMaterial", 5, 5, "{ diffuse r g b a } { ambient } { specular } { emissive } power",
     [](Context& c, const Args& a) {
         return c.device.set_material(Material{color_value(a, 0, "diffuse"), color_value(a, 1, "ambient"),
                                               color_value(a, 2, "specular"), color_value(a, 3, "emissive"),
                                               a.f32(4, "power")});
     }},
    {"SetLight", 14, 14,
     "index POINT|SPOT|DIRECTIONAL { diffuse } { specular } { ambient } { position x y z } { direction x y z } "
     "range falloff attenuation0 attenuation1 attenuation2 theta phi",
     [](Context& c, const Args& a) {
         Light light;
         light.type = static_cast<LightType>(a.enumeration(1, "type", EnumFamily::LightType));
         light.diffuse = color_value(a, 2, "diffuse");
         light.specular = color_value(a, 3, "specular");
         light.ambient = color_value(a, 4, "ambient");
         light.position = vector3(a, 5, "position");
         light.direction = vector3(a, 6, "direction");
         light.range = a.f32(7, "range");
         light.falloff = a.f32(8, "falloff");
         light.attenuation0 = a.f32(9, "attenuation0");
         light.attenuation1 = a.f32(10, "attenuation1");
         light.attenuation2 = a.f32(11, "attenuation2");
         light.theta = a.f32(12, "theta");
         light.phi = a.f32(13, "phi");
         return c.device.set_light(a.u32(0, "index"), light);
     }},
    {"LightEnable", 2, 2, "index TRUE|FALSE",
     [](Context& c, const Args& a) {
         return c.device.light_enable(a.u32(0, "index"), a.enumeration(1, "enable", EnumFamily::Bool) != 0);
     }},
    {"SetTextureStageState", 3, 3, "stage STATE value",
     [](Context& c, const Args& a) {
         const std::string& name = a.identifier(1, "state");
         const StateInfo* state = find_texture_stage_state(name);
         if (!state) a.fail(1, "state", "unknown texture stage state '" + name + "'");
         return c.device.set_texture_stage_state(a.u32(0, "stage"), state->id, state_value(a, 2, *state));
     }},
    {"SaveSurface", 2, 4, "surface \"file\" [level [face]]",
     [](Context& c, const Args& a) {
         return c.device.save_surface(a.identifier(0, "surface"), a.string(1, "file"), a.size() > 2 ? a.u32(2, "level") : 0,
                                      a.size() > 3 ? cube_face(a, 3) : 0);
     }},
};

const CallSpec* find_call(std::string_view name) {
    for (const CallSpec& spec : kCalls)
        if (spec.name == name) return &spec;
    return nullptr;
}

std::string count_text(const CallSpec& spec) {
    if (spec.min_args == spec.max_args) return std::to_string(spec.min_args);
    if (spec.max_args == kMany) return "at least " + std::to_string(spec.min_args);
    return std::to_string(spec.min_args) + " to " + std::to_string(spec.max_args);
}

DrawStatistics difference(const DrawStatistics& after, const DrawStatistics& before) {
    DrawStatistics d;
    d.draws = after.draws - before.draws;
    d.vertices_shaded = after.vertices_shaded - before.vertices_shaded;
    d.primitives = after.primitives - before.primitives;
    d.pixels_shaded = after.pixels_shaded - before.pixels_shaded;
    d.pixels_rasterized = after.pixels_rasterized - before.pixels_rasterized;
    d.pixels_killed = after.pixels_killed - before.pixels_killed;
    d.pixels_written = after.pixels_written - before.pixels_written;
    d.pixels_outside_texture = after.pixels_outside_texture - before.pixels_outside_texture;
    d.pipelines_built = after.pipelines_built - before.pipelines_built;
    d.pipeline_seconds = after.pipeline_seconds - before.pipeline_seconds;
    d.vertex_seconds = after.vertex_seconds - before.vertex_seconds;
    d.setup_seconds = after.setup_seconds - before.setup_seconds;
    d.pixel_seconds = after.pixel_seconds - before.pixel_seconds;
    d.routines_compiled = after.routines_compiled - before.routines_compiled;
    d.routines_from_cache = after.routines_from_cache - before.routines_from_cache;
    d.compile_seconds = after.compile_seconds - before.compile_seconds;
    return d;
}

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

}  // namespace

std::string ReplayDiagnostic::to_string() const {
    std::string s = file.empty() ? "<input>" : file;
    if (line > 0) s += ":" + std::to_string(line);
    else if (record > 0) s += ": record " + std::to_string(record);
    s += std::string(": ") + call_error_name(code) + ": ";
    if (!call.empty()) s += call + ": ";
    return s + message;
}

Replayer::Replayer(Device& device, ReplayOptions options) : device_(device), options_(std::move(options)) {}

bool Replayer::execute(const cs::Statement& statement, size_t record) {
    if (statement.kind != cs::Statement::Kind::Call) return true;
    Context context{device_, options_, statement.line, statement.line};
    std::string message;
    CallError code = CallError::InvalidCall;
    if (const CallSpec* spec = find_call(statement.name)) {
        const size_t count = statement.arguments.size();
        if (count < spec->min_args || count > spec->max_args) {
            message = "expects " + count_text(*spec) + " argument" + (spec->max_args == 1 ? "" : "s") + " (" +
                      std::string(spec->usage) + "), got " + std::to_string(count);
        } else {
            try {
                const CallResult result = spec->run(context, Args(statement.arguments));
                if (result.ok) return true;
                message = result.error;
                code = result.code;
                // The Device names the call itself; the diagnostic already does.
                const std::string prefix = statement.name + ": ";
                if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
            } catch (const ArgumentError& e) {
                message = e.message;
            } catch (const std::bad_alloc&) {
                // What a call needs beyond the resources (a draw's vertices, say) could not be
                // allocated: E_OUTOFMEMORY, and the replay goes on.
                message = "out of host memory";
                code = CallError::OutOfMemory;
            } catch (const std::exception& e) {
                message = std::string("internal error: ") + e.what();
            }
        }
    } else {
        message = "unknown call";
    }
    diagnostics_.push_back(ReplayDiagnostic{options_.file_name, context.diagnostic_line, record, statement.name,
                                            std::move(message), code});
    return false;
}

ReplayResult Replayer::replay(const cs::Stream& stream) {
    using Clock = std::chrono::steady_clock;
    ReplayResult result;
    const size_t first_diagnostic = diagnostics_.size();
    const DrawStatistics start_stats = device_.statistics();
    const auto start = Clock::now();
    auto frame_start = start;
    DrawStatistics frame_stats = start_stats;
    size_t frame_calls = 0;
    const size_t total = stream.statements.size();
    for (size_t i = 0; i < total; ++i) {
        const cs::Statement& st = stream.statements[i];
        if (st.kind == cs::Statement::Kind::Call) {
            ++result.calls;
            ++frame_calls;
            const DrawStatistics before = options_.per_draw_statistics ? device_.statistics() : DrawStatistics{};
            const auto call_start = options_.per_draw_statistics ? Clock::now() : Clock::time_point{};
            const bool ok = execute(st, i + 1);
            if (!ok) ++result.refused;
            if (options_.per_draw_statistics && ok && device_.statistics().draws != before.draws)
                result.draws.push_back(DrawRecord{result.calls, st.line, i + 1, st.name, result.frames.size(),
                                                  seconds_between(call_start, Clock::now()),
                                                  difference(device_.statistics(), before)});
            if (ok && st.name == "Present") {
                const auto now = Clock::now();
                const DrawStatistics now_stats = device_.statistics();
                result.frames.push_back(FrameStats{seconds_between(frame_start, now), frame_calls,
                                                   difference(now_stats, frame_stats)});
                frame_start = now;
                frame_stats = now_stats;
                frame_calls = 0;
            }
            if (options_.after_call && !options_.after_call(st, result.calls, ok)) break;
        }
        if (options_.progress) options_.progress(i + 1, total);
    }
    result.seconds = seconds_between(start, Clock::now());
    result.statistics = difference(device_.statistics(), start_stats);
    result.diagnostics.assign(diagnostics_.begin() + static_cast<std::ptrdiff_t>(first_diagnostic), diagnostics_.end());
    return result;
}

ReplayResult replay(Device& device, const cs::Stream& stream, const ReplayOptions& options) {
    Replayer replayer(device, options);
    return replayer.replay(stream);
}

}  // namespace sm2::runtime
