// apitrace D3D9 traces to command streams (runtime/include/sm2/runtime/apitrace_import.h,
// docs/apitrace.md "Import").
#include "sm2/runtime/apitrace_import.h"

#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/formats.h"

namespace sm2::runtime::apitrace {

namespace {

// Thrown while translating one call: it is skipped for `reason`.
struct Skip {
    std::string reason;
};

constexpr uint32_t kLockReadOnly = 0x10;
constexpr uint32_t kUsageRenderTarget = 0x1;
constexpr uint32_t kUsageDynamic = 0x200;
constexpr int64_t kPoolManaged = 1;

struct Object {
    enum class Kind : uint8_t { Device, Shader, Declaration, VertexBuffer, IndexBuffer, Texture, CubeTexture,
                                VolumeTexture, RenderTarget, DepthStencil, Surface, StateBlock, ReadBack };
    Kind kind = Kind::Device;
    std::string name;          // the stream's handle (Surface: its texture's, or backbuffer/autodepth)
    bool owned = true;         // created by a statement: Release at refcount 0 releases it
    Format format = Format::Unknown;
    uint32_t width = 0, height = 0, depth = 1;
    uint32_t level = 0;        // Surface: the texture level it is
    int32_t face = -1;         // Surface of a cube texture: the face
};

// An open Lock/LockRect/LockBox, waiting for the memcpy of its bytes.
struct Lock {
    uint64_t object = 0;       // the locked object's pointer
    uint64_t offset = 0;       // buffers: OffsetToLock
    uint32_t level = 0;
    int32_t face = -1;
    uint64_t pitch = 0, slice_pitch = 0;
    bool whole = true;         // textures: no sub-rectangle or box
    int64_t left = 0, top = 0, right = 0, bottom = 0;  // LockRect's pRect / LockBox's pBox when not whole
    int64_t front = 0, back = 0;                       // LockBox's pBox when not whole
};

cs::Value ident(std::string_view text) {
    cs::Value v;
    v.kind = cs::Value::Kind::Identifier;
    v.text = std::string(text);
    return v;
}
cs::Value integer(int64_t value, bool hex = false) {
    cs::Value v;
    v.kind = cs::Value::Kind::Integer;
    v.integer = value;
    v.hex = hex;
    return v;
}
cs::Value real(float value) {
    cs::Value v;
    v.kind = cs::Value::Kind::Float;
    v.float_bits = std::bit_cast<uint32_t>(value);
    return v;
}
cs::Value blob(std::vector<std::byte> bytes, cs::BlobType type) {
    cs::Value v;
    v.kind = cs::Value::Kind::Blob;
    v.blob_type = type;
    v.bytes = std::move(bytes);
    return v;
}
cs::Value tuple(std::vector<cs::Value> items) {
    cs::Value v;
    v.kind = cs::Value::Kind::Tuple;
    v.items = std::move(items);
    return v;
}

std::string hex(uint64_t value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%" PRIx64, value);
    return buf;
}

// The method name after "Interface::" ("Clear"), or the whole name.
std::string_view method_of(std::string_view name) {
    const size_t at = name.rfind("::");
    return at == std::string_view::npos ? name : name.substr(at + 2);
}

class Importer {
public:
    explicit Importer(const StatementSink* sink = nullptr) : sink_(sink) {}

    ImportResult run(Reader& reader) {
        while (auto call = reader.next()) {
            ++result_.report.calls;
            translate(*call);
            if (sink_) {
                for (const auto& statement : result_.stream.statements) (*sink_)(statement, call->number);
                result_.stream.statements.clear();
            }
        }
        result_.error = reader.error();
        return std::move(result_);
    }

private:
    // --- arguments ---
    static const Value& arg(const Call& c, std::string_view name) {
        const Value* v = c.arg(name);
        if (!v) throw Skip{"argument " + std::string(name) + " is missing"};
        return *v;
    }
    static int64_t num(const Call& c, std::string_view name) {
        const Value& v = arg(c, name);
        if (auto i = v.as_int()) return *i;
        throw Skip{"argument " + std::string(name) + " is not an integer"};
    }
    static uint32_t u32(const Call& c, std::string_view name) {
        const int64_t v = num(c, name);
        if (v < 0 || v > 0xFFFFFFFFll) throw Skip{"argument " + std::string(name) + " = " + std::to_string(v) + " is out of range"};
        return static_cast<uint32_t>(v);
    }
    // A DWORD recorded signed or unsigned.
    static uint32_t dword(const Call& c, std::string_view name) {
        const int64_t v = num(c, name);
        if (v < std::numeric_limits<int32_t>::min() || v > 0xFFFFFFFFll)
            throw Skip{"argument " + std::string(name) + " = " + std::to_string(v) + " is out of range"};
        return static_cast<uint32_t>(v);
    }
    static float f32(const Value& v, std::string_view what) {
        if (v.kind == Value::Kind::Float || v.kind == Value::Kind::Double) return static_cast<float>(v.real);
        if (auto i = v.as_int()) return static_cast<float>(*i);
        throw Skip{std::string(what) + " is not a number"};
    }
    // The pointee of an output pointer (`ppShader = &0x3b0710`) or a pointer to a struct.
    static const Value& deref(const Call& c, std::string_view name) {
        const Value& v = arg(c, name);
        if (v.kind == Value::Kind::Array && v.items.size() == 1) return v.items[0];
        throw Skip{"argument " + std::string(name) + " was not recorded as a pointer to one value"};
    }
    static uint64_t out_pointer(const Call& c, std::string_view name) {
        const Value& v = deref(c, name);
        if (v.kind != Value::Kind::Pointer) throw Skip{"argument " + std::string(name) + " holds no object"};
        return v.uint;
    }
    static int64_t member(const Value& s, std::string_view name) {
        const Value* m = s.member(name);
        if (!m) throw Skip{"member " + std::string(name) + " is missing"};
        if (auto i = m->as_int()) return *i;
        throw Skip{"member " + std::string(name) + " is not an integer"};
    }
    static float member_f(const Value& s, std::string_view name) {
        const Value* m = s.member(name);
        if (!m) throw Skip{"member " + std::string(name) + " is missing"};
        return f32(*m, name);
    }
    // An optional pointer argument absent: NULL (a given one is recorded as the array of the one
    // struct it points to, which deref reads).
    static bool null_pointer(const Call& c, std::string_view name) {
        const Value& v = arg(c, name);
        return v.kind == Value::Kind::Null || (v.kind == Value::Kind::Pointer && v.uint == 0);
    }
    static uint64_t pointer(const Call& c, std::string_view name) {
        const Value& v = arg(c, name);
        if (v.kind == Value::Kind::Null) return 0;
        if (v.kind == Value::Kind::Pointer) return v.uint;
        throw Skip{"argument " + std::string(name) + " is not a pointer"};
    }

    // --- objects ---
    const Object& object(uint64_t ptr, std::string_view what) const {
        auto it = objects_.find(ptr);
        if (it == objects_.end()) throw Skip{std::string(what) + " 0x" + hex(ptr) + " is not an object the trace created"};
        return it->second;
    }
    const Object& self(const Call& c) const { return object(pointer(c, "this"), "this"); }
    // A binding argument: the object's handle, or NULL.
    cs::Value binding(const Call& c, std::string_view name) const {
        const uint64_t ptr = pointer(c, name);
        if (ptr == 0) return ident("NULL");
        return ident(object(ptr, name).name);
    }
    Object& add(uint64_t ptr, Object::Kind kind, std::string_view prefix) {
        Object& o = objects_[ptr];
        o = Object{};
        o.kind = kind;
        o.name = std::string(prefix) + "_" + hex(ptr);
        return o;
    }
    static std::string_view format_name(int64_t value) {
        const FormatInfo* info = format_info(static_cast<Format>(static_cast<uint32_t>(value)));
        if (!info || value <= 0) throw Skip{"format " + std::to_string(value) + " is not one sm2emu has"};
        return info->name;
    }

    // --- results ---
    void emit(std::string name, std::vector<cs::Value> args) {
        cs::Statement st;
        st.kind = cs::Statement::Kind::Call;
        st.name = std::move(name);
        st.arguments = std::move(args);
        result_.stream.statements.push_back(std::move(st));
        emitted_ = true;
    }
    void skip(const Call& c, const std::string& reason) {
        auto& report = result_.report;
        ++report.skipped;
        for (auto& k : report.skipped_kinds)
            if (k.call == c.name()) {
                ++k.count;
                return;
            }
        report.skipped_kinds.push_back({c.name(), c.number, 1, reason});
    }

    void translate(const Call& c) {
        emitted_ = false;
        const size_t before = result_.stream.statements.size();
        try {
            // A call that failed at capture changed nothing.
            if (c.ret && c.ret->kind == Value::Kind::Enum && static_cast<int32_t>(c.ret->sint) < 0) {
                ++result_.report.accepted;
                return;
            }
            const bool handled = dispatch(c);
            if (!handled) throw Skip{"not in the stream vocabulary yet"};
            if (emitted_) {
                ++result_.report.imported;
            } else {
                ++result_.report.accepted;
            }
        } catch (const Skip& s) {
            // Statements of a call that failed half way are withdrawn.
            result_.stream.statements.resize(before);
            skip(c, s.reason);
        }
    }

    // Returns false for a call it does not know.
    bool dispatch(const Call& c) {
        const std::string& name = c.name();
        const std::string_view method = method_of(name);
        if (name == "Direct3DCreate9" || name == "Direct3DCreate9Ex") return true;
        if (name == "memcpy") return upload(c);
        if (name == "IDirect3D9::CreateDevice") return create_device(c);
        if (name.rfind("IDirect3D9::", 0) == 0) return method != "CreateDeviceEx" && method != "RegisterSoftwareDevice";
        if (method == "AddRef" || method == "QueryInterface") return true;
        if (method == "Release") return release(c);
        if (name.rfind("IDirect3DDevice9::", 0) == 0) return device(c, method);
        if (method == "Lock" || method == "LockRect" || method == "LockBox") return lock(c, method);
        if (method == "Unlock" || method == "UnlockRect" || method == "UnlockBox") {
            const uint64_t ptr = pointer(c, "this");
            std::erase_if(locks_, [&](const auto& entry) { return entry.second.object == ptr; });
            return true;
        }
        if (method == "GetSurfaceLevel" || method == "GetCubeMapSurface") return surface_level(c, method);
        if (name.rfind("IDirect3DStateBlock9::", 0) == 0 && (method == "Capture" || method == "Apply")) {
            emit(std::string(method), {ident(self(c).name)});
            return true;
        }
        if (method == "GenerateMipSubLevels") {
            emit("GenerateMipSubLevels", {ident(self(c).name)});
            return true;
        }
        if (method.rfind("Get", 0) == 0) return true;  // GetDesc, GetLevelCount, ...: queries
        return false;
    }

    // CreateDevice's and Reset's D3DPRESENT_PARAMETERS: width height format [depth_format].
    static std::vector<cs::Value> presentation_args(const Value& pp) {
        const auto width = member(pp, "BackBufferWidth"), height = member(pp, "BackBufferHeight");
        if (width <= 0 || height <= 0) throw Skip{"a back buffer of the window's size (0 in the parameters) is not known"};
        int64_t fmt = member(pp, "BackBufferFormat");
        if (fmt == 0) fmt = static_cast<int64_t>(Format::X8R8G8B8);  // D3DFMT_UNKNOWN in windowed mode: the desktop's
        std::vector<cs::Value> args{integer(width), integer(height), ident(format_name(fmt))};
        if (member(pp, "EnableAutoDepthStencil") != 0) args.push_back(ident(format_name(member(pp, "AutoDepthStencilFormat"))));
        return args;
    }

    bool create_device(const Call& c) {
        std::vector<cs::Value> args = presentation_args(deref(c, "pPresentationParameters"));
        if (device_created_) throw Skip{"a second device"};
        const uint64_t ptr = out_pointer(c, "ppReturnedDeviceInterface");
        emit("CreateDevice", std::move(args));
        device_created_ = true;
        Object& dev = add(ptr, Object::Kind::Device, "device");
        dev.owned = false;
        return true;
    }


    // A surface argument as the stream names it: its handle and, for a texture level, the level.
    struct SurfaceRef {
        std::string name;
        uint32_t level = 0;
    };
    SurfaceRef surface_ref(const Call& c, std::string_view argument) const {
        const uint64_t ptr = pointer(c, argument);
        if (ptr == 0) throw Skip{"argument " + std::string(argument) + " is NULL"};
        const Object& o = object(ptr, argument);
        if (o.kind == Object::Kind::Surface && o.face >= 0) throw Skip{"a cube-map face surface"};
        if (o.kind != Object::Kind::Surface && o.kind != Object::Kind::RenderTarget && o.kind != Object::Kind::ReadBack)
            throw Skip{"argument " + std::string(argument) + " is not a surface"};
        return {o.name, o.kind == Object::Kind::Surface ? o.level : 0};
    }
    // A RECT (left top right bottom) or D3DRECT (x1 y1 x2 y2) as a tuple.
    static cs::Value rect(const Value& r) {
        if (r.member("x1"))
            return tuple({integer(member(r, "x1")), integer(member(r, "y1")), integer(member(r, "x2")), integer(member(r, "y2"))});
        return tuple({integer(member(r, "left")), integer(member(r, "top")), integer(member(r, "right")), integer(member(r, "bottom"))});
    }
    static cs::Value optional_rect(const Call& c, std::string_view argument) {
        if (arg(c, argument).kind == Value::Kind::Null) return ident("NULL");
        return rect(deref(c, argument));
    }

    bool device(const Call& c, std::string_view m) {
        if (m == "BeginStateBlock") {
            emit("BeginStateBlock", {});
            return true;
        }
        if (m == "EndStateBlock" || m == "CreateStateBlock") {
            const uint64_t ptr = out_pointer(c, "ppSB");
            std::vector<cs::Value> args{ident("sb_" + hex(ptr))};
            if (m == "CreateStateBlock") {
                const auto type = enum_name(EnumFamily::StateBlockType, u32(c, "Type"));
                if (type.empty()) throw Skip{"an unknown state block type"};
                args.push_back(ident(type));
            }
            emit(std::string(m), std::move(args));
            add(ptr, Object::Kind::StateBlock, "sb");
            return true;
        }
        if (m == "Reset") {
            emit("Reset", presentation_args(deref(c, "pPresentationParameters")));
            return true;
        }
        if (m == "SetSoftwareVertexProcessing") {
            emit("SetSoftwareVertexProcessing", {ident(u32(c, "bSoftware") ? "TRUE" : "FALSE")});
            return true;
        }
        if (m == "SetGammaRamp") {
            // D3DGAMMARAMP: WORD red[256], green[256], blue[256].
            const Value& ramp = deref(c, "pRamp");
            std::vector<std::byte> bytes;
            for (const char* channel : {"red", "green", "blue"}) {
                const Value* words = ramp.member(channel);
                if (!words || words->kind != Value::Kind::Array || words->items.size() != 256)
                    throw Skip{std::string("pRamp.") + channel + " is not 256 WORDs"};
                for (const Value& w : words->items) {
                    const auto v = w.as_int();
                    if (!v || *v < 0 || *v > 0xFFFF) throw Skip{"a gamma ramp entry is not a WORD"};
                    bytes.push_back(static_cast<std::byte>(*v & 0xFF));
                    bytes.push_back(static_cast<std::byte>(*v >> 8));
                }
            }
            emit("SetGammaRamp", {integer(u32(c, "iSwapChain")), blob(std::move(bytes), cs::BlobType::U16)});
            return true;
        }
        if (m == "SetNPatchMode") {
            emit("SetNPatchMode", {real(f32(arg(c, "nSegments"), "nSegments"))});
            return true;
        }
        if (m == "ColorFill") {
            const SurfaceRef s = surface_ref(c, "pSurface");
            if (s.level != 0) throw Skip{"ColorFill of a texture level other than 0"};
            std::vector<cs::Value> args{ident(s.name)};
            if (arg(c, "pRect").kind != Value::Kind::Null) args.push_back(rect(deref(c, "pRect")));
            args.push_back(integer(dword(c, "color"), true));
            emit("ColorFill", std::move(args));
            return true;
        }
        if (m == "UpdateSurface") {
            const SurfaceRef from = surface_ref(c, "pSourceSurface"), to = surface_ref(c, "pDestinationSurface");
            cs::Value point = ident("NULL");
            if (arg(c, "pDestPoint").kind != Value::Kind::Null) {
                const Value& p = deref(c, "pDestPoint");
                point = tuple({integer(member(p, "x")), integer(member(p, "y"))});
            }
            emit("UpdateSurface", {ident(from.name), integer(from.level), optional_rect(c, "pSourceRect"), ident(to.name),
                                   integer(to.level), std::move(point)});
            return true;
        }
        if (m == "UpdateTexture") {
            emit("UpdateTexture", {binding(c, "pSourceTexture"), binding(c, "pDestinationTexture")});
            return true;
        }
        if (m == "CreateVertexShader" || m == "CreatePixelShader") {
            const bool vs = m == "CreateVertexShader";
            const auto* tokens = arg(c, "pFunction").blob();
            if (!tokens || tokens->empty() || tokens->size() % 4 != 0) throw Skip{"the shader's token blob is missing"};
            const uint64_t ptr = out_pointer(c, "ppShader");
            emit(vs ? "CreateVertexShader" : "CreatePixelShader", {ident((vs ? "vs_" : "ps_") + hex(ptr)), blob(*tokens, cs::BlobType::U32)});
            add(ptr, Object::Kind::Shader, vs ? "vs" : "ps");
            return true;
        }
        if (m == "CreateVertexDeclaration") {
            const Value& elements = arg(c, "pVertexElements");
            if (elements.kind != Value::Kind::Array) throw Skip{"pVertexElements is not an array"};
            const uint64_t ptr = out_pointer(c, "ppDecl");
            std::vector<cs::Value> args{ident("decl_" + hex(ptr))};
            for (const Value& e : elements.items) {
                if (member(e, "Stream") == 0xFF) break;  // D3DDECL_END
                const auto type = enum_name(EnumFamily::DeclType, static_cast<uint32_t>(member(e, "Type")));
                const auto method = enum_name(EnumFamily::DeclMethod, static_cast<uint32_t>(member(e, "Method")));
                const auto usage = enum_name(EnumFamily::DeclUsage, static_cast<uint32_t>(member(e, "Usage")));
                if (type.empty() || method.empty() || usage.empty()) throw Skip{"a vertex element sm2emu does not know"};
                args.push_back(tuple({integer(member(e, "Stream")), integer(member(e, "Offset")), ident(type), ident(method),
                                      ident(usage), integer(member(e, "UsageIndex"))}));
            }
            emit("CreateVertexDeclaration", std::move(args));
            add(ptr, Object::Kind::Declaration, "decl");
            return true;
        }
        if (m == "CreateVertexBuffer" || m == "CreateIndexBuffer") {
            const bool vb = m == "CreateVertexBuffer";
            const uint64_t ptr = out_pointer(c, vb ? "ppVertexBuffer" : "ppIndexBuffer");
            std::vector<cs::Value> args{ident((vb ? "vb_" : "ib_") + hex(ptr)), integer(u32(c, "Length"))};
            if (!vb) {
                const int64_t f = num(c, "Format");
                if (f != 101 && f != 102) throw Skip{"index format " + std::to_string(f)};
                args.push_back(ident(f == 101 ? "INDEX16" : "INDEX32"));
            }
            emit(vb ? "CreateVertexBuffer" : "CreateIndexBuffer", std::move(args));
            add(ptr, vb ? Object::Kind::VertexBuffer : Object::Kind::IndexBuffer, vb ? "vb" : "ib");
            return true;
        }
        if (m == "CreateTexture" || m == "CreateCubeTexture" || m == "CreateVolumeTexture") {
            const bool cube = m == "CreateCubeTexture", volume = m == "CreateVolumeTexture";
            const uint64_t ptr = out_pointer(c, cube ? "ppCubeTexture" : volume ? "ppVolumeTexture" : "ppTexture");
            const std::string prefix = cube ? "cube" : volume ? "vol" : "tex";
            const int64_t format = num(c, "Format");
            const uint32_t w = cube ? u32(c, "EdgeLength") : u32(c, "Width");
            const uint32_t h = cube ? w : u32(c, "Height");
            const uint32_t d = volume ? u32(c, "Depth") : 1;
            std::vector<cs::Value> args{ident(prefix + "_" + hex(ptr)), integer(w)};
            if (!cube) args.push_back(integer(h));
            if (volume) args.push_back(integer(d));
            args.push_back(integer(u32(c, "Levels")));
            args.push_back(ident(format_name(format)));
            const uint32_t usage = u32(c, "Usage");
            if (!volume && (usage & kUsageRenderTarget)) args.push_back(ident("RENDERTARGET"));
            if (usage & kUsageDynamic) args.push_back(ident("DYNAMIC"));
            if (const int64_t pool = num(c, "Pool"); pool != kPoolManaged) {
                const auto pool_name = enum_name(EnumFamily::Pool, static_cast<uint32_t>(pool));
                if (pool_name.empty() || pool < 0) throw Skip{"pool " + std::to_string(pool) + " is not a D3DPOOL"};
                args.push_back(ident(pool_name));
            }
            emit(std::string(m), std::move(args));
            Object& o = add(ptr, cube ? Object::Kind::CubeTexture : volume ? Object::Kind::VolumeTexture : Object::Kind::Texture, prefix);
            o.format = static_cast<Format>(format);
            o.width = w;
            o.height = h;
            o.depth = d;
            return true;
        }
        if (m == "CreateRenderTarget" || m == "CreateDepthStencilSurface") {
            const bool rt = m == "CreateRenderTarget";
            const uint64_t ptr = out_pointer(c, "ppSurface");
            const std::string prefix = rt ? "rt" : "ds";
            emit(std::string(m), {ident(prefix + "_" + hex(ptr)), integer(u32(c, "Width")), integer(u32(c, "Height")),
                     ident(format_name(num(c, "Format")))});
            Object& o = add(ptr, rt ? Object::Kind::RenderTarget : Object::Kind::DepthStencil, prefix);
            o.format = static_cast<Format>(u32(c, "Format"));  // its uploads' texel size
            o.width = u32(c, "Width");
            o.height = u32(c, "Height");
            return true;
        }
        if (m == "CreateOffscreenPlainSurface") {
            const auto pool = enum_name(EnumFamily::Pool, u32(c, "Pool"));
            if (pool.empty()) throw Skip{"an unknown pool"};
            const uint64_t ptr = out_pointer(c, "ppSurface");
            emit("CreateOffscreenPlainSurface", {ident("surf_" + hex(ptr)), integer(u32(c, "Width")), integer(u32(c, "Height")),
                                                 ident(format_name(num(c, "Format"))), ident(pool)});
            add(ptr, Object::Kind::ReadBack, "surf");
            return true;
        }
        if (m == "GetBackBuffer" || m == "GetRenderTarget" || m == "GetDepthStencilSurface") {
            const uint64_t ptr = out_pointer(c, m == "GetBackBuffer" ? "ppBackBuffer" : m == "GetRenderTarget" ? "ppRenderTarget" : "ppZStencilSurface");
            if (!objects_.count(ptr)) {
                // Before any SetRenderTarget/SetDepthStencilSurface, the device's own surfaces.
                Object& o = objects_[ptr];
                o.kind = Object::Kind::Surface;
                o.name = m == "GetDepthStencilSurface" ? "autodepth" : "backbuffer";
                o.owned = false;
            }
            return true;
        }
        if (m == "GetRenderTargetData") {
            // A read-back, executed so that D3D9's rules for it are checked.
            emit("GetRenderTargetData", {ident(surface_ref(c, "pRenderTarget").name), ident(surface_ref(c, "pDestSurface").name)});
            return true;
        }
        if (m == "GetFrontBufferData") return true;  // a read-back of the screen: nothing to replay
        if (m.rfind("Get", 0) == 0 || m == "TestCooperativeLevel" || m == "ValidateDevice" || m == "SetCursorPosition" ||
            m == "ShowCursor" || m == "EvictManagedResources")
            return true;
        if (m == "BeginScene" || m == "EndScene" || m == "Present") {
            emit(std::string(m), {});
            return true;
        }
        if (m == "Clear") {
            std::vector<cs::Value> args{clear_flags(u32(c, "Flags")), integer(dword(c, "Color"), true),
                                        real(f32(arg(c, "Z"), "Z")), integer(u32(c, "Stencil"))};
            const uint32_t count = u32(c, "Count");
            const Value& rects = arg(c, "pRects");
            if (count != 0) {
                // apitrace records the D3DRECT array (one element as a pointer to one struct).
                if (rects.kind != Value::Kind::Array || rects.items.size() != count)
                    throw Skip{"pRects does not hold Count rectangles"};
                for (const Value& r : rects.items) args.push_back(rect(r));
            }
            emit("Clear", std::move(args));
            return true;
        }
        if (m == "SetRenderState" || m == "SetSamplerState") {
            const bool rs = m == "SetRenderState";
            const uint32_t id = u32(c, rs ? "State" : "Type");
            const StateInfo* state = rs ? find_render_state(id) : find_sampler_state(id);
            if (!state) throw Skip{std::string(rs ? "render" : "sampler") + " state " + std::to_string(id) + " is not one sm2emu has"};
            cs::Value v = state_value(*state, dword(c, "Value"));
            if (rs) {
                emit("SetRenderState", {ident(state->name), std::move(v)});
            } else {
                emit("SetSamplerState", {integer(u32(c, "Sampler")), ident(state->name), std::move(v)});
            }
            return true;
        }
        if (m == "SetFVF") {
            emit("SetFVF", {flags(EnumFamily::Fvf, u32(c, "FVF"))});
            return true;
        }
        if (m == "SetTransform" || m == "MultiplyTransform") {
            const uint32_t state = u32(c, "State");
            const std::string name = transform_state_name(state);
            if (name.empty()) throw Skip{"transform state " + std::to_string(state) + " is not one D3D9 has"};
            emit(std::string(m), {ident(name), matrix(deref(c, "pMatrix"))});
            return true;
        }
        if (m == "SetMaterial") {
            const Value& material = deref(c, "pMaterial");
            emit("SetMaterial", {color(material, "Diffuse"), color(material, "Ambient"), color(material, "Specular"),
                                 color(material, "Emissive"), real(member_f(material, "Power"))});
            return true;
        }
        if (m == "SetLight") {
            const Value& light = deref(c, "pLight");
            const auto type = enum_name(EnumFamily::LightType, static_cast<uint32_t>(member(light, "Type")));
            if (type.empty()) throw Skip{"light type " + std::to_string(member(light, "Type")) + " is not one D3D9 has"};
            std::vector<cs::Value> args{integer(u32(c, "Index")), ident(type), color(light, "Diffuse"),
                                        color(light, "Specular"), color(light, "Ambient"), vector(light, "Position"),
                                        vector(light, "Direction")};
            for (const char* field : {"Range", "Falloff", "Attenuation0", "Attenuation1", "Attenuation2", "Theta", "Phi"})
                args.push_back(real(member_f(light, field)));
            emit("SetLight", std::move(args));
            return true;
        }
        if (m == "LightEnable") {
            emit("LightEnable", {integer(u32(c, "Index")), ident(num(c, "Enable") ? "TRUE" : "FALSE")});
            return true;
        }
        if (m == "SetTextureStageState") {
            const uint32_t id = u32(c, "Type");
            const StateInfo* state = find_texture_stage_state(id);
            if (!state) throw Skip{"texture stage state " + std::to_string(id) + " is not one D3D9 has"};
            emit("SetTextureStageState", {integer(u32(c, "Stage")), ident(state->name), state_value(*state, dword(c, "Value"))});
            return true;
        }
        if (m == "SetTexture") {
            emit("SetTexture", {integer(u32(c, "Stage")), binding(c, "pTexture")});
            return true;
        }
        if (m == "SetStreamSource") {
            emit("SetStreamSource", {integer(u32(c, "StreamNumber")), binding(c, "pStreamData"), integer(u32(c, "OffsetInBytes")),
                                     integer(u32(c, "Stride"))});
            return true;
        }
        if (m == "SetIndices") {
            emit("SetIndices", {binding(c, "pIndexData")});
            return true;
        }
        if (m == "SetVertexDeclaration") {
            emit("SetVertexDeclaration", {binding(c, "pDecl")});
            return true;
        }
        if (m == "SetVertexShader" || m == "SetPixelShader") {
            emit(std::string(m), {binding(c, "pShader")});
            return true;
        }
        if (m.rfind("SetVertexShaderConstant", 0) == 0 || m.rfind("SetPixelShaderConstant", 0) == 0) return constants(c, m);
        if (m == "SetViewport") {
            const Value& vp = deref(c, "pViewport");
            emit("SetViewport", {integer(member(vp, "X")), integer(member(vp, "Y")), integer(member(vp, "Width")),
                                 integer(member(vp, "Height")), real(member_f(vp, "MinZ")), real(member_f(vp, "MaxZ"))});
            return true;
        }
        if (m == "SetScissorRect") {
            const Value& r = deref(c, "pRect");
            emit("SetScissorRect", {integer(member(r, "left")), integer(member(r, "top")), integer(member(r, "right")),
                                    integer(member(r, "bottom"))});
            return true;
        }
        if (m == "SetClipPlane") {
            const Value& plane = arg(c, "pPlane");
            if (plane.kind != Value::Kind::Array || plane.items.size() != 4) throw Skip{"pPlane is not 4 floats"};
            emit("SetClipPlane", {integer(u32(c, "Index")), real(f32(plane.items[0], "a")), real(f32(plane.items[1], "b")),
                                  real(f32(plane.items[2], "c")), real(f32(plane.items[3], "d"))});
            return true;
        }
        if (m == "SetRenderTarget" || m == "SetDepthStencilSurface") {
            const bool rt = m == "SetRenderTarget";
            const uint64_t ptr = pointer(c, rt ? "pRenderTarget" : "pNewZStencil");
            cs::Value target = ident("NULL");
            if (ptr != 0) {
                const Object& o = object(ptr, rt ? "pRenderTarget" : "pNewZStencil");
                if (o.kind == Object::Kind::Surface && (o.level != 0 || o.face >= 0))
                    throw Skip{"a render target that is not level 0 of a 2D texture"};
                target = ident(o.name);
            }
            if (rt) {
                emit("SetRenderTarget", {integer(u32(c, "RenderTargetIndex")), std::move(target)});
            } else {
                emit("SetDepthStencilSurface", {std::move(target)});
            }
            return true;
        }
        if (m == "DrawPrimitive") {
            emit("DrawPrimitive", {prim(c), integer(u32(c, "StartVertex")), integer(u32(c, "PrimitiveCount"))});
            return true;
        }
        if (m == "DrawIndexedPrimitive") {
            emit("DrawIndexedPrimitive", {prim(c), integer(num(c, "BaseVertexIndex")), integer(u32(c, "MinVertexIndex")),
                                          integer(u32(c, "NumVertices")), integer(u32(c, "startIndex")),
                                          integer(u32(c, "primCount"))});
            return true;
        }
        if (m == "DrawPrimitiveUP") {
            const Value& data = arg(c, "pVertexStreamZeroData");
            if (!data.blob()) throw Skip{"the vertex data was not recorded"};
            emit("DrawPrimitiveUP", {prim(c), integer(u32(c, "PrimitiveCount")), integer(u32(c, "VertexStreamZeroStride")),
                                     blob(*data.blob(), cs::BlobType::Hex)});
            return true;
        }
        if (m == "DrawIndexedPrimitiveUP") {
            const Value& indices = arg(c, "pIndexData");
            const Value& data = arg(c, "pVertexStreamZeroData");
            if (!data.blob() || !indices.blob()) throw Skip{"the vertex or index data was not recorded"};
            const int64_t f = num(c, "IndexDataFormat");
            if (f != 101 && f != 102) throw Skip{"index format " + std::to_string(f)};
            emit("DrawIndexedPrimitiveUP", {prim(c), integer(u32(c, "MinVertexIndex")), integer(u32(c, "NumVertices")),
                                            integer(u32(c, "PrimitiveCount")), blob(*indices.blob(), cs::BlobType::Hex),
                                            ident(f == 101 ? "INDEX16" : "INDEX32"), blob(*data.blob(), cs::BlobType::Hex),
                                            integer(u32(c, "VertexStreamZeroStride"))});
            return true;
        }
        if (m == "StretchRect") {
            const auto filter = enum_name(EnumFamily::TextureFilter, u32(c, "Filter"));
            if (filter.empty()) throw Skip{"an unknown filter"};
            const SurfaceRef from = surface_ref(c, "pSourceSurface"), to = surface_ref(c, "pDestSurface");
            if (from.level != 0 || to.level != 0) throw Skip{"StretchRect of a texture level other than 0"};
            std::vector<cs::Value> args{ident(from.name)};
            if (arg(c, "pSourceRect").kind != Value::Kind::Null) args.push_back(rect(deref(c, "pSourceRect")));
            args.push_back(ident(to.name));
            if (arg(c, "pDestRect").kind != Value::Kind::Null) args.push_back(rect(deref(c, "pDestRect")));
            args.push_back(ident(filter));
            emit("StretchRect", std::move(args));
            return true;
        }
        return false;
    }

    // A state's DWORD as the stream writes it: names for enums, bools and bit families, floats,
    // hex colours and masks, plain numbers.
    static cs::Value state_value(const StateInfo& state, uint32_t value) {
        switch (state.kind) {
        case StateValueKind::Enum: {
            const auto n = enum_name(state.family, value);
            if (n.empty()) throw Skip{std::string(state.name) + " value " + std::to_string(value) + " has no name in sm2emu"};
            return ident(n);
        }
        case StateValueKind::Bool: return ident(value ? "TRUE" : "FALSE");
        case StateValueKind::Float: return real(std::bit_cast<float>(value));
        case StateValueKind::Bits:
            // Texture-stage flag words as names; masks (COLORWRITEENABLE included) in hex.
            if (state.family != EnumFamily::Bool && state.family != EnumFamily::ColorWrite) return flags(state.family, value);
            return integer(value, true);
        case StateValueKind::Color: return integer(value, true);
        case StateValueKind::Integer: return integer(value);
        }
        return integer(value);
    }
    // NAME, { NAME NAME 1 }, or the number when no name covers it (d3d9_names.h flag_names).
    static cs::Value flags(EnumFamily family, uint32_t value) {
        std::vector<cs::Value> items;
        for (const std::string& name : flag_names(family, value)) {
            if (name[0] >= '0' && name[0] <= '9') items.push_back(integer(std::stoll(name)));
            else items.push_back(ident(name));
        }
        if (items.size() == 1) return std::move(items[0]);
        return tuple(std::move(items));
    }
    // A D3DMATRIX ({m = {{...} x4}}) as an f32 blob, row by row.
    static cs::Value matrix(const Value& m) {
        const Value* rows = m.member("m");
        if (!rows) throw Skip{"the matrix has no member m"};
        std::vector<float> values;
        for (const Value& row : rows->items) {
            if (row.kind == Value::Kind::Array)
                for (const Value& x : row.items) values.push_back(f32(x, "a matrix element"));
            else
                values.push_back(f32(row, "a matrix element"));
        }
        if (values.size() != 16) throw Skip{"the matrix has " + std::to_string(values.size()) + " elements, not 16"};
        std::vector<std::byte> bytes(values.size() * sizeof(float));
        std::memcpy(bytes.data(), values.data(), bytes.size());
        return blob(std::move(bytes), cs::BlobType::F32);
    }
    // A D3DCOLORVALUE / D3DVECTOR member as { r g b a } / { x y z }.
    static cs::Value color(const Value& s, std::string_view name) {
        const Value* v = s.member(name);
        if (!v) throw Skip{"member " + std::string(name) + " is missing"};
        return tuple({real(member_f(*v, "r")), real(member_f(*v, "g")), real(member_f(*v, "b")), real(member_f(*v, "a"))});
    }
    static cs::Value vector(const Value& s, std::string_view name) {
        const Value* v = s.member(name);
        if (!v) throw Skip{"member " + std::string(name) + " is missing"};
        return tuple({real(member_f(*v, "x")), real(member_f(*v, "y")), real(member_f(*v, "z"))});
    }

    // TARGET, { TARGET STENCIL }, or the number when a bit has no name.
    static cs::Value clear_flags(uint32_t flags) {
        std::vector<cs::Value> names;
        for (uint32_t bit = 1; bit != 0 && bit <= flags; bit <<= 1) {
            if (!(flags & bit)) continue;
            const auto n = enum_name(EnumFamily::ClearFlags, bit);
            if (n.empty()) return integer(flags);
            names.push_back(ident(n));
        }
        if (names.size() == 1) return names[0];
        if (names.empty()) return integer(flags);
        return tuple(std::move(names));
    }

    cs::Value prim(const Call& c) const {
        const auto n = enum_name(EnumFamily::PrimitiveType, u32(c, "PrimitiveType"));
        if (n.empty()) throw Skip{"an unknown primitive type"};
        return ident(n);
    }

    bool constants(const Call& c, std::string_view m) {
        const char kind = m.back();  // F, I or B
        if (kind != 'F' && kind != 'I' && kind != 'B') return false;
        const Value& data = arg(c, "pConstantData");
        if (data.kind != Value::Kind::Array) throw Skip{"pConstantData is not an array"};
        std::vector<std::byte> bytes(data.items.size() * 4);
        for (size_t i = 0; i < data.items.size(); ++i) {
            uint32_t word = 0;
            if (kind == 'F') {
                word = std::bit_cast<uint32_t>(f32(data.items[i], "a constant"));
            } else {
                auto v = data.items[i].as_int();
                if (!v) throw Skip{"a constant is not an integer"};
                word = static_cast<uint32_t>(*v);
            }
            std::memcpy(bytes.data() + 4 * i, &word, 4);
        }
        const cs::BlobType type = kind == 'F' ? cs::BlobType::F32 : kind == 'I' ? cs::BlobType::I32 : cs::BlobType::U32;
        emit(std::string(m), {integer(u32(c, "StartRegister")), blob(std::move(bytes), type)});
        return true;
    }

    bool release(const Call& c) {
        const uint64_t ptr = pointer(c, "this");
        auto it = objects_.find(ptr);
        if (it == objects_.end()) return true;  // the IDirect3D9 object, or one whose creation was skipped
        const auto left = c.ret ? c.ret->as_int() : std::nullopt;
        if (left && *left == 0) {
            if (it->second.owned) emit("Release", {ident(it->second.name)});
            objects_.erase(it);
        }
        return true;
    }

    bool surface_level(const Call& c, std::string_view m) {
        const Object& tex = self(c);
        const uint64_t ptr = out_pointer(c, m == "GetSurfaceLevel" ? "ppSurfaceLevel" : "ppCubeMapSurface");
        Object s = tex;
        s.kind = Object::Kind::Surface;
        s.owned = false;
        s.level = u32(c, "Level");
        s.face = m == "GetCubeMapSurface" ? static_cast<int32_t>(u32(c, "FaceType")) : -1;
        objects_[ptr] = s;
        return true;
    }

    bool lock(const Call& c, std::string_view m) {
        const Object& o = self(c);
        const uint32_t flags = u32(c, "Flags");
        if (flags & kLockReadOnly) return true;  // a read-back: no bytes come
        Lock l;
        l.object = pointer(c, "this");
        uint64_t bits = 0;
        if (m == "Lock") {
            l.offset = u32(c, "OffsetToLock");
            bits = out_pointer(c, "ppbData");
        } else if (m == "LockRect") {
            const Value& locked = deref(c, "pLockedRect");
            l.pitch = static_cast<uint64_t>(member(locked, "Pitch"));
            bits = static_cast<uint64_t>(member(locked, "pBits"));
            l.whole = null_pointer(c, "pRect");
            if (!l.whole) {
                const Value& r = deref(c, "pRect");
                l.left = member(r, "left");
                l.top = member(r, "top");
                l.right = member(r, "right");
                l.bottom = member(r, "bottom");
            }
            if (o.kind == Object::Kind::Surface) {
                l.level = o.level;
                l.face = o.face;
            } else if (o.kind == Object::Kind::RenderTarget || o.kind == Object::Kind::DepthStencil) {
                l.level = 0;  // IDirect3DSurface9::LockRect: one level, no face
            } else {
                l.level = u32(c, "Level");
                if (o.kind == Object::Kind::CubeTexture) l.face = static_cast<int32_t>(u32(c, "FaceType"));
            }
        } else {
            const Value& locked = deref(c, "pLockedVolume");
            l.pitch = static_cast<uint64_t>(member(locked, "RowPitch"));
            l.slice_pitch = static_cast<uint64_t>(member(locked, "SlicePitch"));
            bits = static_cast<uint64_t>(member(locked, "pBits"));
            l.whole = null_pointer(c, "pBox");
            if (!l.whole) {
                const Value& b = deref(c, "pBox");
                l.left = member(b, "Left");
                l.top = member(b, "Top");
                l.front = member(b, "Front");
                l.right = member(b, "Right");
                l.bottom = member(b, "Bottom");
                l.back = member(b, "Back");
            }
            l.level = u32(c, "Level");
        }
        locks_[bits] = l;
        return true;
    }

    bool upload(const Call& c) {
        const uint64_t dest = pointer(c, "dest");
        const Value& src = arg(c, "src");
        if (!src.blob()) throw Skip{"the copied bytes were not recorded"};
        const std::vector<std::byte>& bytes = *src.blob();
        // The lock whose memory holds `dest` (the highest start at or below it).
        const Lock* l = nullptr;
        uint64_t start = 0;
        for (const auto& [at, lk] : locks_)
            if (at <= dest && (!l || at > start)) {
                l = &lk;
                start = at;
            }
        if (!l) throw Skip{"a copy to 0x" + hex(dest) + ", which no Lock returned"};
        const Object& o = object(l->object, "the locked object");
        if (o.kind == Object::Kind::VertexBuffer || o.kind == Object::Kind::IndexBuffer) {
            if (dest - start > 0xFFFFFFFFull) throw Skip{"a copy far past its lock"};
            emit("Lock", {ident(o.name), integer(static_cast<int64_t>(l->offset + (dest - start))), blob(bytes, cs::BlobType::Hex)});
            return true;
        }
        if (dest != start) throw Skip{"an upload to part of a texture level"};
        // Texture levels, render targets, and depth surfaces of the two lockable formats (D3D9
        // locks no other; the device stores their values as given).
        const bool depth = o.kind == Object::Kind::DepthStencil;
        const bool texture = o.kind == Object::Kind::Texture || o.kind == Object::Kind::CubeTexture ||
                             o.kind == Object::Kind::VolumeTexture || o.kind == Object::Kind::RenderTarget || depth ||
                             (o.kind == Object::Kind::Surface && o.format != Format::Unknown);
        if (!texture) throw Skip{"an upload to a surface that is not a texture level"};
        if (depth && o.format != Format::D16_LOCKABLE && o.format != Format::D32F_LOCKABLE)
            throw Skip{"an upload to a depth surface that is not D16_LOCKABLE or D32F_LOCKABLE"};
        const FormatInfo* info = format_info(o.format);
        if (!info) throw Skip{"an upload in a format sm2emu does not have"};
        if (l->level >= 32) throw Skip{"level " + std::to_string(l->level) + " does not exist"};
        const bool compressed = info->kind == FormatKind::Compressed;
        if (!l->whole && compressed) throw Skip{"an upload to part of a DXTn level"};
        uint64_t w = std::max<uint64_t>(1, o.width >> l->level), h = std::max<uint64_t>(1, o.height >> l->level);
        if (!l->whole) {
            // The rectangle's texels, rows at the recorded pitch (checked as a level's are below).
            if (l->left < 0 || l->top < 0 || l->right <= l->left || l->bottom <= l->top ||
                static_cast<uint64_t>(l->right) > w || static_cast<uint64_t>(l->bottom) > h)
                throw Skip{"a locked rectangle outside the level"};
            w = static_cast<uint64_t>(l->right - l->left);
            h = static_cast<uint64_t>(l->bottom - l->top);
        }
        uint64_t d = std::max<uint64_t>(1, o.depth >> l->level);
        if (!l->whole && o.kind == Object::Kind::VolumeTexture) {
            if (l->front < 0 || l->back <= l->front || static_cast<uint64_t>(l->back) > d) throw Skip{"a locked box outside the level"};
            d = static_cast<uint64_t>(l->back - l->front);
        }
        const uint64_t row = compressed ? (w + 3) / 4 * info->bytes : w * info->bytes;
        const uint64_t rows = compressed ? (h + 3) / 4 : h;
        const bool volume = o.kind == Object::Kind::VolumeTexture;
        // Pitches come from the trace: bounded by the copy before any arithmetic on them. Only
        // the ones that step are: a box or rectangle one row (slice) deep copies less than a
        // pitch (apitrace records the locked bytes from the first texel to the last).
        const bool rows_step = rows > 1, slices_step = volume && d > 1;
        if ((rows_step && l->pitch > bytes.size()) || (slices_step && l->slice_pitch > bytes.size()) || o.width == 0 ||
            o.height == 0)
            throw Skip{"a pitch larger than the copy"};
        const uint64_t pitch = rows_step ? l->pitch : row;
        const uint64_t slice_pitch = slices_step ? l->slice_pitch : rows * pitch;
        if (pitch < row || (slices_step && slice_pitch < (rows - 1) * pitch + row))
            throw Skip{"a pitch smaller than a row"};
        const uint64_t need = (volume ? (d - 1) * slice_pitch : 0) + (rows - 1) * pitch + row;
        if (bytes.size() < need) throw Skip{"the copy holds " + std::to_string(bytes.size()) + " bytes, the level needs " + std::to_string(need)};
        std::vector<std::byte> tight;
        tight.reserve(static_cast<size_t>(row * rows * (volume ? d : 1)));
        for (uint64_t z = 0; z < (volume ? d : 1); ++z)
            for (uint64_t y = 0; y < rows; ++y) {
                const auto* p = bytes.data() + z * slice_pitch + y * pitch;
                tight.insert(tight.end(), p, p + row);
            }
        std::vector<cs::Value> args{ident(o.name)};
        if (volume) {
            args.push_back(integer(l->level));
            if (!l->whole)
                args.push_back(tuple({integer(l->left), integer(l->top), integer(l->front), integer(l->right),
                                      integer(l->bottom), integer(l->back)}));
            args.push_back(blob(std::move(tight), cs::BlobType::Hex));
            emit("LockBox", std::move(args));
            return true;
        }
        if (l->face >= 0) {
            const auto face = enum_name(EnumFamily::CubeFace, static_cast<uint32_t>(l->face));
            if (face.empty()) throw Skip{"an unknown cube face"};
            args.push_back(ident(face));
        }
        args.push_back(integer(l->level));
        if (!l->whole) args.push_back(tuple({integer(l->left), integer(l->top), integer(l->right), integer(l->bottom)}));
        args.push_back(blob(std::move(tight), cs::BlobType::Hex));
        emit("LockRect", std::move(args));
        return true;
    }

    const StatementSink* sink_ = nullptr;
    ImportResult result_;
    std::unordered_map<uint64_t, Object> objects_;
    std::unordered_map<uint64_t, Lock> locks_;  // by the address the lock returned
    bool device_created_ = false;
    bool emitted_ = false;
};

}  // namespace

ImportResult import_d3d9(Reader& reader) { return Importer().run(reader); }

ImportResult import_d3d9(Reader& reader, const StatementSink& sink) { return Importer(&sink).run(reader); }

TraceReplay replay_trace(Reader& reader, Device& device, const ReplayOptions& options) {
    TraceReplay result;
    Replayer replayer(device, options);
    bool stopped = false;  // after_call asked for no more calls: the rest of the trace is only read
    const ImportResult imported = import_d3d9(reader, [&](const cs::Statement& statement, uint64_t call) {
        if (statement.kind != cs::Statement::Kind::Call || stopped) return;
        ++result.statements;
        const bool accepted = replayer.execute(statement, static_cast<size_t>(call));
        if (options.after_call && !options.after_call(statement, call, accepted)) stopped = true;
        if (accepted) return;
        ++result.refused;
        const ReplayDiagnostic d = replayer.diagnostics().back();
        replayer.clear_diagnostics();
        for (auto& k : result.refused_kinds)
            if (k.call == statement.name) {
                ++k.count;
                return;
            }
        result.refused_kinds.push_back({statement.name, call, 1, d.message, d.code});
    });
    result.import = imported.report;
    result.error = imported.error;
    return result;
}

std::string TraceReplay::refusals_to_string() const {
    std::string s;
    for (const auto& k : refused_kinds)
        s += "  " + k.call + ": " + std::to_string(k.count) + (k.count == 1 ? " call" : " calls") + " refused from call " +
             std::to_string(k.first) + ": " + call_error_name(k.code) + ": " + k.message + "\n";
    return s;
}

std::string ImportReport::to_string() const {
    std::string s = "imported " + std::to_string(imported) + ", accepted " + std::to_string(accepted) + ", skipped " +
                    std::to_string(skipped) + " of " + std::to_string(calls) + " calls\n";
    for (const auto& k : skipped_kinds)
        s += "  " + k.call + ": " + std::to_string(k.count) + (k.count == 1 ? " call" : " calls") + " skipped from call " +
             std::to_string(k.first) + ": " + k.reason + "\n";
    return s;
}

}  // namespace sm2::runtime::apitrace
