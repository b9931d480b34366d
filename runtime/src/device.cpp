// The Device: resources, bindings, states, constants, Clear/Present. The draw loop itself is in
// draw.cpp.
#include "sm2/runtime/device.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <utility>

#include "device_internal.h"
#include "state_block.h"
#include "worker_pool.h"
#include "sm2/isa/validator.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/texture_io.h"

namespace sm2::runtime {

namespace {

std::string format_name(Format format) {
    const FormatInfo* info = format_info(format);
    return info ? std::string(info->name) : "format " + std::to_string(static_cast<uint32_t>(format));
}

bool is_render_target_format(Format format) {
    const FormatInfo* info = format_info(format);
    return info && info->render_target && info->kind != FormatKind::Depth;
}

// Bytes of `levels` levels (0: the full chain) of `faces` faces of a texture of this format and
// size, as Texture stores them (DXTn by 4x4 blocks); 0 for an unknown format. The sizes are at
// most D3D9's limits when this is called, so nothing overflows 64 bits.
uint64_t texture_bytes(Format format, uint32_t width, uint32_t height, uint32_t depth, uint32_t faces,
                       uint32_t levels) {
    const FormatInfo* info = format_info(format);
    if (info == nullptr) return 0;
    if (levels == 0) levels = Texture::full_chain(width, height, depth);
    uint64_t total = 0;
    for (uint32_t l = 0; l < levels && l < 32; ++l) {
        const uint64_t w = Texture::level_size(width, l), h = Texture::level_size(height, l),
                       d = Texture::level_size(depth, l);
        total += info->kind == FormatKind::Compressed ? (w + 3) / 4 * ((h + 3) / 4) * d * info->bytes
                                                      : w * h * d * info->bytes;
    }
    return total * faces;
}

bool within(uint32_t size, uint32_t limit) { return size >= 1 && size <= limit; }

// Depth-stencil surfaces keep a 32-bit depth and an 8-bit stencil per pixel.
constexpr uint64_t kDepthStencilBytesPerPixel = 5;

}  // namespace

const char* call_error_name(CallError error) {
    switch (error) {
    case CallError::InvalidCall: return "D3DERR_INVALIDCALL";
    case CallError::OutOfVideoMemory: return "D3DERR_OUTOFVIDEOMEMORY";
    case CallError::OutOfMemory: return "E_OUTOFMEMORY";
    }
    return "D3DERR_INVALIDCALL";
}

namespace {

// The D3D9 defaults of the render states RenderState does not model (the fixed-function and
// tessellation ones state blocks capture): LIGHTING, COLORVERTEX, LOCALVIEWER TRUE,
// DIFFUSEMATERIALSOURCE COLOR1, SPECULARMATERIALSOURCE COLOR2, POSITIONDEGREE CUBIC,
// NORMALDEGREE LINEAR, MIN/MAXTESSELLATIONLEVEL and ADAPTIVETESS_Z 1.0f; the others 0.
std::map<uint32_t, uint32_t> default_other_render_states() {
    return {{137, 1}, {139, 0}, {141, 1}, {142, 1}, {143, 0}, {145, 1}, {146, 2},
                            {147, 0}, {148, 0}, {151, 0}, {163, 0}, {167, 0}, {170, 0}, {172, 3},
                            {173, 1}, {178, 0x3F800000}, {179, 0x3F800000}, {180, 0}, {181, 0},
                            {182, 0x3F800000}, {183, 0}, {184, 0}};
}

}  // namespace

Device::Device(DeviceOptions options) : options_(std::move(options)) {
    vs_f_.assign(kMaxVertexShaderConstantsF, {0.0f, 0.0f, 0.0f, 0.0f});
    ps_f_.assign(kMaxPixelShaderConstantsF, {0.0f, 0.0f, 0.0f, 0.0f});
    if (options_.threads == 0) options_.threads = 1;
    other_render_states_ = default_other_render_states();
    sampler_.set_precision(options_.filter_precision);
    sampler_.set_block_path(!options_.reference_paths);
}

Device::~Device() = default;

std::shared_ptr<Device::Resource> Device::find(const std::string& name) const {
    auto it = resources_.find(name);
    return it == resources_.end() ? nullptr : it->second;
}

CallResult Device::reserve_memory(const std::string& what, uint64_t bytes) const {
    if (bytes <= options_.memory_limit && memory_used_ <= options_.memory_limit - bytes) return {};
    return CallResult::fail(what + " needs " + std::to_string(bytes) + " bytes; " +
                                std::to_string(memory_used_) + " of the " + std::to_string(options_.memory_limit) +
                                "-byte memory limit are in use",
                            CallError::OutOfVideoMemory);
}

CallResult Device::add_resource(const std::string& name, std::shared_ptr<Resource> resource) {
    if (name.empty() || name == "NULL") return CallResult::fail("'" + name + "' is not a usable resource name");
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    Resource& r = *resource;
    uint64_t bytes = r.bytes.size() + r.surface.bytes().size();
    for (uint32_t f = 0; f < r.texture.faces() && r.texture.levels() > 0; ++f)
        for (uint32_t l = 0; l < r.texture.levels(); ++l) bytes += r.texture.surface(l, f).bytes().size();
    if (r.depth) bytes += uint64_t{r.depth->width()} * r.depth->height() * kDepthStencilBytesPerPixel;
    if (auto refused = reserve_memory("'" + name + "'", bytes); !refused) return refused;
    r.memory_bytes = bytes;
    memory_used_ += bytes;
    resources_.emplace(name, std::move(resource));
    return {};
}

Surface* Device::render_target_surface(unsigned index) const {
    const auto& r = render_targets_[index];
    if (!r) return nullptr;
    return r->kind == Resource::Kind::Texture ? &r->texture.surface(0, 0) : &r->surface;
}

// ---------------------------------------------------------------------------------------------
// Resources

namespace {

// CreateDevice's and Reset's checks of the presentation parameters.
std::optional<std::string> back_buffer_error(const char* call, uint32_t width, uint32_t height, Format format) {
    if (width == 0 || height == 0 || width > Texture::kMaxSize2D || height > Texture::kMaxSize2D)
        return std::string(call) + ": back buffer size " + std::to_string(width) + "x" + std::to_string(height) +
               " is out of range";
    if (!is_render_target_format(format)) return std::string(call) + ": " + format_name(format) + " is not a render-target format";
    return std::nullopt;
}

}  // namespace

CallResult Device::reset(uint32_t width, uint32_t height, Format format, std::optional<Format> depth_format) {
    if (!created_) return CallResult::fail("Reset: no device (CreateDevice)");
    if (auto error = back_buffer_error("Reset", width, height, format)) return CallResult::fail(*error);
    if (depth_format && !depth_format_info(*depth_format))
        return CallResult::fail("Reset: " + format_name(*depth_format) + " is not a depth format");
    // D3D9: "all ... resources in D3DPOOL_DEFAULT must be released before calling Reset".
    std::string held;
    for (const auto& [name, r] : resources_) {
        if (r == back_buffer_ || name == "autodepth") continue;
        const bool default_pool = r->kind == Resource::Kind::DepthStencil ||
                                  ((r->kind == Resource::Kind::Texture || r->kind == Resource::Kind::RenderTarget) &&
                                   r->pool_of() == Pool::Default);
        if (default_pool) held += (held.empty() ? "'" : ", '") + name + "'";
    }
    if (!held.empty()) return CallResult::fail("Reset: DEFAULT-pool resources are not released: " + held);
    if (recording_) return CallResult::fail("Reset: inside BeginStateBlock/EndStateBlock");
    // The back buffer and the automatic depth surface go; every state and binding returns to its
    // default; CreateDevice makes the new buffers and the viewport and scissor rectangle covering them.
    for (const char* name : {"backbuffer", "autodepth"})
        if (auto it = resources_.find(name); it != resources_.end()) {
            memory_used_ -= it->second->memory_bytes;
            resources_.erase(it);
        }
    render_state_ = RenderState::defaults(false);
    sampler_states_ = {};
    textures_ = {};
    render_targets_ = {};
    depth_stencil_ = back_buffer_ = declaration_ = vertex_shader_ = pixel_shader_ = indices_ = nullptr;
    streams_ = {};
    std::fill(vs_f_.begin(), vs_f_.end(), std::array<float, 4>{});
    std::fill(ps_f_.begin(), ps_f_.end(), std::array<float, 4>{});
    vs_flow_ = {};
    ps_flow_ = {};
    clip_planes_ = {};
    fixed_function_ = {};
    other_render_states_ = default_other_render_states();
    in_scene_ = false;
    created_ = false;
    CallResult created = create_device(width, height, format, depth_format);
    if (!created.ok && created.error.starts_with("CreateDevice")) created.error.replace(0, 12, "Reset");
    return created;
}

CallResult Device::create_device(uint32_t width, uint32_t height, Format format,
                                 std::optional<Format> depth_format) {
    if (created_) return CallResult::fail("CreateDevice: the device already exists");
    if (auto error = back_buffer_error("CreateDevice", width, height, format)) return CallResult::fail(*error);
    if (resources_.count("backbuffer") || (depth_format && resources_.count("autodepth")))
        return CallResult::fail("CreateDevice: the names 'backbuffer'/'autodepth' are taken");
    const uint64_t back_bytes = texture_bytes(format, width, height, 1, 1, 1);
    const uint64_t depth_bytes = depth_format ? uint64_t{width} * height * kDepthStencilBytesPerPixel : 0;
    if (auto refused = reserve_memory("CreateDevice: the back buffer", back_bytes + depth_bytes); !refused)
        return refused;
    std::shared_ptr<Resource> depth;
    if (depth_format) {
        auto created = DepthStencilSurface::create(*depth_format, width, height);
        if (!created.surface) return CallResult::fail("CreateDevice: " + created.error);
        depth = std::make_shared<Resource>();
        depth->kind = Resource::Kind::DepthStencil;
        depth->depth = std::move(created.surface);
        depth->memory_bytes = depth_bytes;
    }
    auto back = std::make_shared<Resource>();
    back->kind = Resource::Kind::RenderTarget;
    back->surface = Surface(format, width, height);
    back->memory_bytes = back->surface.bytes().size();
    memory_used_ += back->memory_bytes + depth_bytes;
    resources_.emplace("backbuffer", back);
    back_buffer_ = back;
    render_targets_[0] = back;
    if (depth) {
        resources_.emplace("autodepth", depth);
        depth_stencil_ = depth;
        render_state_.z_enable = ZBufferType::True;
    }
    viewport_ = Viewport{0, 0, width, height, 0.0f, 1.0f};
    scissor_ = PixelRect{0, 0, static_cast<int32_t>(width), static_cast<int32_t>(height)};
    created_ = true;
    return {};
}

CallResult Device::create_vertex_buffer(const std::string& name, uint32_t length) {
    if (length == 0 || length > (1u << 30)) return CallResult::fail("CreateVertexBuffer: length " + std::to_string(length) + " is out of range");
    if (auto refused = reserve_memory("CreateVertexBuffer: '" + name + "'", length); !refused) return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::VertexBuffer;
    r->bytes.assign(length, std::byte{0});
    return add_resource(name, std::move(r));
}

CallResult Device::create_index_buffer(const std::string& name, uint32_t length, Format format) {
    if (format != Format::INDEX16 && format != Format::INDEX32)
        return CallResult::fail("CreateIndexBuffer: " + format_name(format) + " is not INDEX16 or INDEX32");
    if (length == 0 || length > (1u << 30)) return CallResult::fail("CreateIndexBuffer: length " + std::to_string(length) + " is out of range");
    if (auto refused = reserve_memory("CreateIndexBuffer: '" + name + "'", length); !refused) return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::IndexBuffer;
    r->bytes.assign(length, std::byte{0});
    r->index_format = format == Format::INDEX16 ? IndexFormat::Index16 : IndexFormat::Index32;
    return add_resource(name, std::move(r));
}

namespace {

// D3D9's usage/pool rules at creation: RENDERTARGET and DYNAMIC resources live in DEFAULT (a
// MANAGED RENDERTARGET or DYNAMIC resource is D3DERR_INVALIDCALL, and so is a SCRATCH one).
std::optional<std::string> usage_error(const char* call, const TextureUsage& usage) {
    const Pool pool = usage.pool.value_or(usage.render_target ? Pool::Default : Pool::Managed);
    if (static_cast<uint32_t>(pool) > 3) return std::string(call) + ": pool " + std::to_string(static_cast<uint32_t>(pool)) + " is not a D3DPOOL";
    if (usage.render_target && pool != Pool::Default)
        return std::string(call) + ": a RENDERTARGET texture must be in the DEFAULT pool, not " + pool_name(pool);
    if (usage.dynamic && (pool == Pool::Managed || pool == Pool::Scratch))
        return std::string(call) + ": a DYNAMIC texture cannot be in the " + pool_name(pool) + " pool";
    return std::nullopt;
}

}  // namespace

const char* pool_name(Pool pool) {
    switch (pool) {
    case Pool::Default: return "DEFAULT";
    case Pool::Managed: return "MANAGED";
    case Pool::SystemMem: return "SYSTEMMEM";
    case Pool::Scratch: return "SCRATCH";
    }
    return "unknown";
}

CallResult Device::create_texture(const std::string& name, uint32_t width, uint32_t height, uint32_t levels,
                                  Format format, bool render_target) {
    return create_texture(name, width, height, levels, format, TextureUsage{render_target, false, std::nullopt});
}

CallResult Device::create_cube_texture(const std::string& name, uint32_t edge, uint32_t levels, Format format,
                                       bool render_target) {
    return create_cube_texture(name, edge, levels, format, TextureUsage{render_target, false, std::nullopt});
}

CallResult Device::create_texture(const std::string& name, uint32_t width, uint32_t height, uint32_t levels,
                                  Format format, TextureUsage usage) {
    const bool render_target = usage.render_target;
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    if (auto error = usage_error("CreateTexture", usage)) return CallResult::fail(*error);
    if (render_target && !is_render_target_format(format))
        return CallResult::fail("CreateTexture: " + format_name(format) + " cannot be a render target");
    if (within(width, Texture::kMaxSize2D) && within(height, Texture::kMaxSize2D))
        if (auto refused = reserve_memory("CreateTexture: '" + name + "'",
                                          texture_bytes(format, width, height, 1, 1, levels));
            !refused)
            return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::Texture;
    r->render_target_usage = render_target;
    r->dynamic_usage = usage.dynamic;
    r->pool = usage.pool.value_or(render_target ? Pool::Default : Pool::Managed);
    try {
        r->texture = Texture::create_2d(format, width, height, levels);
    } catch (const std::bad_alloc&) {
        return CallResult::fail("CreateTexture: out of host memory", CallError::OutOfMemory);
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("CreateTexture: ") + e.what());
    }
    return add_resource(name, std::move(r));
}

CallResult Device::create_cube_texture(const std::string& name, uint32_t edge, uint32_t levels, Format format,
                                       TextureUsage usage) {
    const bool render_target = usage.render_target;
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    if (auto error = usage_error("CreateCubeTexture", usage)) return CallResult::fail(*error);
    if (render_target && !is_render_target_format(format))
        return CallResult::fail("CreateCubeTexture: " + format_name(format) + " cannot be a render target");
    if (within(edge, Texture::kMaxSize2D))
        if (auto refused = reserve_memory("CreateCubeTexture: '" + name + "'",
                                          texture_bytes(format, edge, edge, 1, 6, levels));
            !refused)
            return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::Texture;
    r->render_target_usage = render_target;
    r->dynamic_usage = usage.dynamic;
    r->pool = usage.pool.value_or(render_target ? Pool::Default : Pool::Managed);
    try {
        r->texture = Texture::create_cube(format, edge, levels);
    } catch (const std::bad_alloc&) {
        return CallResult::fail("CreateCubeTexture: out of host memory", CallError::OutOfMemory);
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("CreateCubeTexture: ") + e.what());
    }
    return add_resource(name, std::move(r));
}

CallResult Device::create_volume_texture(const std::string& name, uint32_t width, uint32_t height,
                                         uint32_t depth, uint32_t levels, Format format, TextureUsage usage) {
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    if (usage.render_target) return CallResult::fail("CreateVolumeTexture: a volume texture cannot be a render target");
    if (auto error = usage_error("CreateVolumeTexture", usage)) return CallResult::fail(*error);
    if (within(width, Texture::kMaxSizeVolume) && within(height, Texture::kMaxSizeVolume) &&
        within(depth, Texture::kMaxSizeVolume))
        if (auto refused = reserve_memory("CreateVolumeTexture: '" + name + "'",
                                          texture_bytes(format, width, height, depth, 1, levels));
            !refused)
            return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::Texture;
    r->dynamic_usage = usage.dynamic;
    r->pool = usage.pool.value_or(Pool::Managed);
    try {
        r->texture = Texture::create_volume(format, width, height, depth, levels);
    } catch (const std::bad_alloc&) {
        return CallResult::fail("CreateVolumeTexture: out of host memory", CallError::OutOfMemory);
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("CreateVolumeTexture: ") + e.what());
    }
    return add_resource(name, std::move(r));
}

CallResult Device::create_render_target(const std::string& name, uint32_t width, uint32_t height, Format format) {
    if (width == 0 || height == 0 || width > Texture::kMaxSize2D || height > Texture::kMaxSize2D)
        return CallResult::fail("CreateRenderTarget: size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is out of range");
    if (!is_render_target_format(format))
        return CallResult::fail("CreateRenderTarget: " + format_name(format) + " is not a render-target format");
    if (auto refused = reserve_memory("CreateRenderTarget: '" + name + "'", texture_bytes(format, width, height, 1, 1, 1));
        !refused)
        return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::RenderTarget;
    r->surface = Surface(format, width, height);
    return add_resource(name, std::move(r));
}

CallResult Device::create_offscreen_plain_surface(const std::string& name, uint32_t width, uint32_t height,
                                                 Format format, Pool pool) {
    if (width == 0 || height == 0 || width > Texture::kMaxSize2D || height > Texture::kMaxSize2D)
        return CallResult::fail("CreateOffscreenPlainSurface: size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is out of range");
    const FormatInfo* info = format_info(format);
    if (!info || (info->kind != FormatKind::Color && info->kind != FormatKind::Signed))
        return CallResult::fail("CreateOffscreenPlainSurface: " + format_name(format) + " is not a surface format sm2emu can hold");
    // D3D9 refuses off-screen plain surfaces in the MANAGED pool.
    if (pool != Pool::Default && pool != Pool::SystemMem && pool != Pool::Scratch)
        return CallResult::fail(std::string("CreateOffscreenPlainSurface: the ") + pool_name(pool) +
                                " pool is not DEFAULT, SYSTEMMEM or SCRATCH");
    if (auto refused = reserve_memory("CreateOffscreenPlainSurface: '" + name + "'", texture_bytes(format, width, height, 1, 1, 1));
        !refused)
        return refused;
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::RenderTarget;
    r->offscreen_plain = true;
    r->pool = pool;
    r->surface = Surface(format, width, height);
    return add_resource(name, std::move(r));
}

CallResult Device::create_depth_stencil_surface(const std::string& name, uint32_t width, uint32_t height,
                                                Format format) {
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    if (within(width, Texture::kMaxSize2D) && within(height, Texture::kMaxSize2D))
        if (auto refused = reserve_memory("CreateDepthStencilSurface: '" + name + "'",
                                          uint64_t{width} * height * kDepthStencilBytesPerPixel);
            !refused)
            return refused;
    auto created = DepthStencilSurface::create(format, width, height);
    if (!created.surface) return CallResult::fail("CreateDepthStencilSurface: " + created.error);
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::DepthStencil;
    r->depth = std::move(created.surface);
    return add_resource(name, std::move(r));
}

CallResult Device::create_vertex_declaration(const std::string& name, std::vector<VertexElement> elements) {
    if (elements.empty() || elements.size() > kMaxDeclElements)
        return CallResult::fail("CreateVertexDeclaration: " + std::to_string(elements.size()) +
                                " elements (1 to " + std::to_string(kMaxDeclElements) + " allowed)");
    // Check the elements on their own (types, streams, usages, duplicates): a plan for no inputs.
    auto checked = plan_fetch(elements, {});
    if (!checked.plan) return CallResult::fail("CreateVertexDeclaration: " + checked.error);
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::Declaration;
    r->elements = std::move(elements);
    return add_resource(name, std::move(r));
}

CallResult Device::create_shader(const std::string& name, isa::Program program, isa::ShaderType type) {
    const char* call = type == isa::ShaderType::Vertex ? "CreateVertexShader" : "CreatePixelShader";
    if (program.version.type != type)
        return CallResult::fail(std::string(call) + ": the program is a " +
                                (program.version.is_vertex() ? "vertex" : "pixel") + " shader");
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    isa::ValidationOptions validation;
    validation.max_instruction_slots = options_.max_instruction_slots;
    auto violations = isa::validate(program, validation);
    if (!violations.empty()) return CallResult::fail(std::string(call) + ": " + violations.front().message);
    auto object = std::make_shared<ShaderObject>();
    for (const auto& ins : program.instructions)
        if (ins.opcode == isa::Opcode::TexKill) object->texkill = true;
    if (type == isa::ShaderType::Vertex) object->inputs = shader_inputs(program);
    auto created = emu::Shader::create(std::move(program));
    if (!created.shader) return CallResult::fail(std::string(call) + ": " + created.error);
    object->shader.emplace(std::move(*created.shader));
    auto r = std::make_shared<Resource>();
    r->kind = type == isa::ShaderType::Vertex ? Resource::Kind::VertexShader : Resource::Kind::PixelShader;
    r->shader = std::move(object);
    return add_resource(name, std::move(r));
}

CallResult Device::create_vertex_shader(const std::string& name, isa::Program program) {
    return create_shader(name, std::move(program), isa::ShaderType::Vertex);
}
CallResult Device::create_pixel_shader(const std::string& name, isa::Program program) {
    return create_shader(name, std::move(program), isa::ShaderType::Pixel);
}

CallResult Device::lock(const std::string& buffer, uint32_t offset, std::span<const std::byte> data) {
    auto r = find(buffer);
    if (!r) return CallResult::fail("Lock: no resource named '" + buffer + "'");
    if (r->kind != Resource::Kind::VertexBuffer && r->kind != Resource::Kind::IndexBuffer)
        return CallResult::fail("Lock: '" + buffer + "' is not a vertex or index buffer");
    if (offset > r->bytes.size() || data.size() > r->bytes.size() - offset)
        return CallResult::fail("Lock: " + std::to_string(data.size()) + " bytes at offset " + std::to_string(offset) +
                                " do not fit in '" + buffer + "' (" + std::to_string(r->bytes.size()) + " bytes)");
    std::copy(data.begin(), data.end(), r->bytes.begin() + offset);
    return {};
}

namespace {

// D3D9's lock rule: a DEFAULT-pool texture can be locked only with DYNAMIC usage; MANAGED,
// SYSTEMMEM and SCRATCH ones always. (Render targets and off-screen plain surfaces are locked
// as before: the stream's way to fill them.)
std::optional<std::string> lock_error(const char* call, const std::string& name, const Device::Resource& r) {
    if (r.kind == Device::Resource::Kind::Texture && r.pool == Pool::Default && !r.dynamic_usage)
        return std::string(call) + ": '" + name + "' is a DEFAULT-pool texture without DYNAMIC usage, which cannot be locked";
    return std::nullopt;
}

// LockRect of a lockable depth surface (D16_LOCKABLE: 16-bit unsigned values, D32F_LOCKABLE:
// 32-bit floats, as stored; D3D9 locks no other depth format). `rect` null: the whole surface.
CallResult lock_depth(const std::string& name, DepthStencilSurface& ds, const PixelRect* rect,
                      std::span<const std::byte> data) {
    const Format format = ds.format();
    if (format != Format::D16_LOCKABLE && format != Format::D32F_LOCKABLE)
        return CallResult::fail("LockRect: '" + name + "' is a " + std::string(format_info(format)->name) +
                                " depth surface; only D16_LOCKABLE and D32F_LOCKABLE ones can be locked");
    const PixelRect whole{0, 0, static_cast<int32_t>(ds.width()), static_cast<int32_t>(ds.height())};
    const PixelRect& r = rect ? *rect : whole;
    if (r.left < 0 || r.top < 0 || r.right <= r.left || r.bottom <= r.top ||
        static_cast<uint32_t>(r.right) > ds.width() || static_cast<uint32_t>(r.bottom) > ds.height())
        return CallResult::fail("LockRect: rectangle {" + std::to_string(r.left) + " " + std::to_string(r.top) + " " +
                                std::to_string(r.right) + " " + std::to_string(r.bottom) + "} is not inside the " +
                                std::to_string(ds.width()) + "x" + std::to_string(ds.height()) + " surface");
    const size_t bytes = format == Format::D16_LOCKABLE ? 2 : 4;
    const auto w = static_cast<size_t>(r.right - r.left), h = static_cast<size_t>(r.bottom - r.top);
    if (data.size() != w * h * bytes)
        return CallResult::fail("LockRect: " + std::to_string(data.size()) + " bytes given, the " +
                                (rect ? "rectangle" : "surface") + " holds " + std::to_string(w * h * bytes));
    for (size_t y = 0; y < h; ++y)
        for (size_t x = 0; x < w; ++x) {
            uint32_t value = 0;
            if (bytes == 2) {
                uint16_t v16;
                std::memcpy(&v16, data.data() + (y * w + x) * 2, 2);
                value = v16;
            } else {
                std::memcpy(&value, data.data() + (y * w + x) * 4, 4);
            }
            ds.set_stored_depth(static_cast<uint32_t>(r.left) + static_cast<uint32_t>(x),
                                static_cast<uint32_t>(r.top) + static_cast<uint32_t>(y), value);
        }
    return {};
}

}  // namespace

CallResult Device::lock_rect(const std::string& texture, uint32_t face, uint32_t level,
                             std::span<const std::byte> data) {
    auto r = find(texture);
    if (!r) return CallResult::fail("LockRect: no resource named '" + texture + "'");
    if (auto error = lock_error("LockRect", texture, *r)) return CallResult::fail(*error);
    Surface* target = nullptr;
    if (r->kind == Resource::Kind::DepthStencil) {
        if (face != 0 || level != 0) return CallResult::fail("LockRect: a depth surface has one level");
        return lock_depth(texture, *r->depth, nullptr, data);
    }
    if (r->kind == Resource::Kind::RenderTarget) {
        if (face != 0 || level != 0) return CallResult::fail("LockRect: a render target has one level");
        target = &r->surface;
    } else if (r->kind == Resource::Kind::Texture && r->texture.type() != TextureType::Volume) {
        if (face >= r->texture.faces()) return CallResult::fail("LockRect: face " + std::to_string(face) + " out of range");
        if (level >= r->texture.levels()) return CallResult::fail("LockRect: level " + std::to_string(level) + " out of range");
        target = &r->texture.surface(level, face);
    } else {
        return CallResult::fail("LockRect: '" + texture + "' is not a 2D/cube texture or render target");
    }
    if (data.size() != target->bytes().size())
        return CallResult::fail("LockRect: " + std::to_string(data.size()) + " bytes given, the level holds " +
                                std::to_string(target->bytes().size()));
    std::copy(data.begin(), data.end(), target->bytes().begin());
    return {};
}

CallResult Device::lock_rect(const std::string& texture, uint32_t face, uint32_t level, const PixelRect& rect,
                             std::span<const std::byte> data) {
    auto r = find(texture);
    if (!r) return CallResult::fail("LockRect: no resource named '" + texture + "'");
    if (auto error = lock_error("LockRect", texture, *r)) return CallResult::fail(*error);
    Surface* target = nullptr;
    if (r->kind == Resource::Kind::DepthStencil && face == 0 && level == 0) return lock_depth(texture, *r->depth, &rect, data);
    if (r->kind == Resource::Kind::RenderTarget && face == 0 && level == 0) {
        target = &r->surface;
    } else if (r->kind == Resource::Kind::Texture && r->texture.type() != TextureType::Volume && face < r->texture.faces() &&
               level < r->texture.levels()) {
        target = &r->texture.surface(level, face);
    } else {
        return CallResult::fail("LockRect: '" + texture + "' has no face " + std::to_string(face) + " level " +
                                std::to_string(level) + " of a 2D/cube texture or render target");
    }
    const FormatInfo* info = format_info(target->format());
    if (info->kind == FormatKind::Compressed) return CallResult::fail("LockRect: a rectangle of a DXTn level");
    if (rect.left < 0 || rect.top < 0 || rect.right <= rect.left || rect.bottom <= rect.top ||
        static_cast<uint32_t>(rect.right) > target->width() || static_cast<uint32_t>(rect.bottom) > target->height())
        return CallResult::fail("LockRect: rectangle {" + std::to_string(rect.left) + " " + std::to_string(rect.top) + " " +
                                std::to_string(rect.right) + " " + std::to_string(rect.bottom) + "} is not inside the " +
                                std::to_string(target->width()) + "x" + std::to_string(target->height()) + " level");
    const size_t row = static_cast<size_t>(rect.right - rect.left) * info->bytes;
    const size_t rows = static_cast<size_t>(rect.bottom - rect.top);
    if (data.size() != row * rows)
        return CallResult::fail("LockRect: " + std::to_string(data.size()) + " bytes given, the rectangle holds " +
                                std::to_string(row * rows));
    for (size_t y = 0; y < rows; ++y)
        std::memcpy(target->bytes().data() + (static_cast<size_t>(rect.top) + y) * target->row_pitch() +
                        static_cast<size_t>(rect.left) * info->bytes,
                    data.data() + y * row, row);
    return {};
}

CallResult Device::lock_box(const std::string& texture, uint32_t level, std::span<const std::byte> data) {
    return lock_box(texture, level, nullptr, data);
}

CallResult Device::lock_box(const std::string& texture, uint32_t level, const VolumeBox& box,
                            std::span<const std::byte> data) {
    return lock_box(texture, level, &box, data);
}

CallResult Device::lock_box(const std::string& texture, uint32_t level, const VolumeBox* box,
                            std::span<const std::byte> data) {
    auto r = find(texture);
    if (!r) return CallResult::fail("LockBox: no resource named '" + texture + "'");
    if (r->kind != Resource::Kind::Texture || r->texture.type() != TextureType::Volume)
        return CallResult::fail("LockBox: '" + texture + "' is not a volume texture");
    if (auto error = lock_error("LockBox", texture, *r)) return CallResult::fail(*error);
    if (level >= r->texture.levels()) return CallResult::fail("LockBox: level " + std::to_string(level) + " out of range");
    Surface& target = r->texture.surface(level, 0);
    if (!box) {
        if (data.size() != target.bytes().size())
            return CallResult::fail("LockBox: " + std::to_string(data.size()) + " bytes given, the level holds " +
                                    std::to_string(target.bytes().size()));
        std::copy(data.begin(), data.end(), target.bytes().begin());
        return {};
    }
    const FormatInfo* info = format_info(target.format());
    if (info->kind == FormatKind::Compressed) return CallResult::fail("LockBox: a box of a DXTn level");
    const VolumeBox& b = *box;
    if (b.right <= b.left || b.bottom <= b.top || b.back <= b.front || b.right > target.width() ||
        b.bottom > target.height() || b.back > target.depth())
        return CallResult::fail("LockBox: box {" + std::to_string(b.left) + " " + std::to_string(b.top) + " " +
                                std::to_string(b.front) + " " + std::to_string(b.right) + " " + std::to_string(b.bottom) +
                                " " + std::to_string(b.back) + "} is not inside the " + std::to_string(target.width()) +
                                "x" + std::to_string(target.height()) + "x" + std::to_string(target.depth()) + " level");
    const size_t row = size_t{b.right - b.left} * info->bytes;
    const size_t rows = b.bottom - b.top, slices = b.back - b.front;
    if (data.size() != row * rows * slices)
        return CallResult::fail("LockBox: " + std::to_string(data.size()) + " bytes given, the box holds " +
                                std::to_string(row * rows * slices));
    for (size_t z = 0; z < slices; ++z)
        for (size_t y = 0; y < rows; ++y)
            std::memcpy(target.bytes().data() + (b.front + z) * target.slice_pitch() + (b.top + y) * target.row_pitch() +
                            size_t{b.left} * info->bytes,
                        data.data() + (z * rows + y) * row, row);
    return {};
}

CallResult Device::load_texture(const std::string& name, const std::string& path, bool generate_mips) {
    if (resources_.count(name)) return CallResult::fail("a resource named '" + name + "' already exists");
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::Texture;
    try {
        r->texture = runtime::load_texture(path, TextureLoadOptions{generate_mips});
    } catch (const std::bad_alloc&) {
        return CallResult::fail("LoadTexture: out of host memory", CallError::OutOfMemory);
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("LoadTexture: ") + e.what());
    }
    return add_resource(name, std::move(r));
}

CallResult Device::generate_mip_sub_levels(const std::string& texture) {
    auto r = find(texture);
    if (!r || r->kind != Resource::Kind::Texture)
        return CallResult::fail("GenerateMipSubLevels: '" + texture + "' is not a texture");
    // In place: generate_mips() refuses a format before it writes a texel (a copy to keep the
    // levels on failure cost each call the whole texture).
    try {
        r->texture.generate_mips();
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("GenerateMipSubLevels: ") + e.what());
    }
    return {};
}

CallResult Device::release(const std::string& name) {
    auto it = resources_.find(name);
    if (it == resources_.end()) return CallResult::fail("Release: no resource named '" + name + "'");
    memory_used_ -= std::min(memory_used_, it->second->memory_bytes);
    resources_.erase(it);
    return {};
}

// ---------------------------------------------------------------------------------------------
// Bindings

namespace {

CallResult bind_resource(const std::shared_ptr<Device::Resource>& found, const std::string& name, const char* call,
                Device::Resource::Kind kind, const char* what, std::shared_ptr<Device::Resource>& slot) {
    if (name.empty() || name == "NULL") {
        slot = nullptr;
        return {};
    }
    if (!found) return CallResult::fail(std::string(call) + ": no resource named '" + name + "'");
    if (found->kind != kind) return CallResult::fail(std::string(call) + ": '" + name + "' is not a " + what);
    slot = found;
    return {};
}

}  // namespace

CallResult Device::set_vertex_declaration(const std::string& name) {
    select_binding([](StateSelection& s, uint32_t) { s.declaration = true; }, 0);
    CallResult bound = bind_resource(find(name), name, "SetVertexDeclaration", Resource::Kind::Declaration,
                                     "vertex declaration", declaration_);
    if (bound.ok) fixed_function_.fvf = 0;  // GetFVF answers 0 after a declaration
    return bound;
}
CallResult Device::set_vertex_shader(const std::string& name) {
    select_binding([](StateSelection& s, uint32_t) { s.vertex_shader = true; }, 0);
    return bind_resource(find(name), name, "SetVertexShader", Resource::Kind::VertexShader, "vertex shader", vertex_shader_);
}
CallResult Device::set_pixel_shader(const std::string& name) {
    select_binding([](StateSelection& s, uint32_t) { s.pixel_shader = true; }, 0);
    return bind_resource(find(name), name, "SetPixelShader", Resource::Kind::PixelShader, "pixel shader", pixel_shader_);
}
CallResult Device::set_indices(const std::string& name) {
    select_binding([](StateSelection& s, uint32_t) { s.indices = true; }, 0);
    return bind_resource(find(name), name, "SetIndices", Resource::Kind::IndexBuffer, "index buffer", indices_);
}

CallResult Device::set_stream_source(uint32_t stream, const std::string& buffer, uint32_t offset, uint32_t stride) {
    if (stream >= kMaxVertexStreams) return CallResult::fail("SetStreamSource: stream " + std::to_string(stream) + " out of range");
    std::shared_ptr<Resource> found;
    auto result = bind_resource(find(buffer), buffer, "SetStreamSource", Resource::Kind::VertexBuffer, "vertex buffer", found);
    if (!result) return result;
    if (found && stride == 0) return CallResult::fail("SetStreamSource: stride 0");
    if (found && offset >= found->bytes.size() && offset != 0)
        return CallResult::fail("SetStreamSource: offset " + std::to_string(offset) + " is past the buffer");
    streams_[stream] = StreamBinding{found, offset, stride};
    select_binding([](StateSelection& s, uint32_t i) { s.streams.set(i); }, stream);
    return {};
}

CallResult Device::set_texture(uint32_t stage, const std::string& texture) {
    if (stage >= kMaxSamplers) return CallResult::fail("SetTexture: stage " + std::to_string(stage) + " out of range");
    if (auto r = find(texture); r && r->kind == Resource::Kind::Texture && (r->pool == Pool::SystemMem || r->pool == Pool::Scratch))
        return CallResult::fail("SetTexture: '" + texture + "' is in the " + pool_name(r->pool) +
                                " pool, which the device cannot sample");
    auto result = bind_resource(find(texture), texture, "SetTexture", Resource::Kind::Texture, "texture", textures_[stage]);
    if (result) {
        sampler_.set_texture(stage, textures_[stage] ? &textures_[stage]->texture : nullptr);
        select_binding([](StateSelection& s, uint32_t i) { s.textures.set(i); }, stage);
    }
    return result;
}

CallResult Device::set_render_target(uint32_t index, const std::string& name) {
    if (index >= kMaxRenderTargets) return CallResult::fail("SetRenderTarget: index " + std::to_string(index) + " out of range");
    const bool null = name.empty() || name == "NULL";
    if (null) {
        if (index == 0) return CallResult::fail("SetRenderTarget: render target 0 cannot be NULL");
        render_targets_[index] = nullptr;
        return {};
    }
    auto r = find(name);
    if (!r) return CallResult::fail("SetRenderTarget: no resource named '" + name + "'");
    const Surface* s = nullptr;
    if (r->kind == Resource::Kind::RenderTarget && !r->offscreen_plain) s = &r->surface;
    else if (r->kind == Resource::Kind::Texture && r->render_target_usage && r->texture.type() == TextureType::Texture2D)
        s = &r->texture.surface(0, 0);
    if (!s) return CallResult::fail("SetRenderTarget: '" + name + "' is not a render target");
    render_targets_[index] = r;
    if (index == 0) {
        viewport_ = Viewport{0, 0, s->width(), s->height(), 0.0f, 1.0f};
        scissor_ = PixelRect{0, 0, static_cast<int32_t>(s->width()), static_cast<int32_t>(s->height())};
    }
    return {};
}

CallResult Device::set_depth_stencil_surface(const std::string& name) {
    return bind_resource(find(name), name, "SetDepthStencilSurface", Resource::Kind::DepthStencil, "depth-stencil surface",
                depth_stencil_);
}

// ---------------------------------------------------------------------------------------------
// States and constants

CallResult Device::set_render_state(uint32_t type, uint32_t value) {
    RenderState copy = render_state_;
    auto result = runtime::set_render_state(copy, type, value);
    if (!result.ok) return CallResult::fail("SetRenderState: " + result.error);
    render_state_ = copy;
    if (result.ignored) other_render_states_[type] = value;
    select(type);
    return {};
}

CallResult Device::set_sampler_state(uint32_t sampler, uint32_t type, uint32_t value) {
    if (sampler >= kMaxSamplers) return CallResult::fail("SetSamplerState: sampler " + std::to_string(sampler) + " out of range");
    SamplerState copy = sampler_states_[sampler];
    if (!copy.set(type, value)) return CallResult::fail("SetSamplerState: state " + std::to_string(type) + " does not exist");
    sampler_states_[sampler] = copy;
    sampler_.set_state(sampler, copy);
    select_sampler(sampler, type);
    return {};
}

namespace {

CallResult set_floats(const char* call, std::vector<std::array<float, 4>>& file, uint32_t start,
                      std::span<const float> values) {
    if (values.size() % 4 != 0) return CallResult::fail(std::string(call) + ": " + std::to_string(values.size()) + " floats is not a whole number of registers");
    const size_t count = values.size() / 4;
    if (start > file.size() || count > file.size() - start)
        return CallResult::fail(std::string(call) + ": registers " + std::to_string(start) + ".." +
                                std::to_string(start + count) + " exceed " + std::to_string(file.size()));
    for (size_t i = 0; i < count; ++i)
        for (unsigned c = 0; c < 4; ++c) file[start + i][c] = values[4 * i + c];
    return {};
}

CallResult set_ints(const char* call, emu::StaticFlowConstants& flow, uint32_t start, std::span<const int32_t> values) {
    if (values.size() % 4 != 0) return CallResult::fail(std::string(call) + ": " + std::to_string(values.size()) + " integers is not a whole number of registers");
    const size_t count = values.size() / 4;
    if (start > kMaxConstantsI || count > kMaxConstantsI - start)
        return CallResult::fail(std::string(call) + ": registers " + std::to_string(start) + ".." +
                                std::to_string(start + count) + " exceed 16");
    for (size_t i = 0; i < count; ++i)
        for (unsigned c = 0; c < 4; ++c) flow.integers[start + i][c] = values[4 * i + c];
    return {};
}

CallResult set_bools(const char* call, emu::StaticFlowConstants& flow, uint32_t start, std::span<const uint32_t> values) {
    if (start > kMaxConstantsB || values.size() > kMaxConstantsB - start)
        return CallResult::fail(std::string(call) + ": registers " + std::to_string(start) + ".." +
                                std::to_string(start + values.size()) + " exceed 16");
    for (size_t i = 0; i < values.size(); ++i) flow.booleans[start + i] = values[i] != 0;
    return {};
}

}  // namespace

// Registers start .. start + count join the recorded state block (the set succeeded: in range).
template <size_t N>
void mark_registers(std::bitset<N>& registers, uint32_t start, size_t count) {
    for (size_t r = start; r < start + count && r < N; ++r) registers.set(r);
}

CallResult Device::set_vertex_shader_constant_f(uint32_t start, std::span<const float> values) {
    auto result = set_floats("SetVertexShaderConstantF", vs_f_, start, values);
    if (result && recording_) mark_registers(recording_->vs_float, start, values.size() / 4);
    return result;
}
CallResult Device::set_pixel_shader_constant_f(uint32_t start, std::span<const float> values) {
    auto result = set_floats("SetPixelShaderConstantF", ps_f_, start, values);
    if (result && recording_) mark_registers(recording_->ps_float, start, values.size() / 4);
    return result;
}
CallResult Device::set_vertex_shader_constant_i(uint32_t start, std::span<const int32_t> values) {
    auto result = set_ints("SetVertexShaderConstantI", vs_flow_, start, values);
    if (result && recording_) mark_registers(recording_->vs_int, start, values.size() / 4);
    return result;
}
CallResult Device::set_pixel_shader_constant_i(uint32_t start, std::span<const int32_t> values) {
    auto result = set_ints("SetPixelShaderConstantI", ps_flow_, start, values);
    if (result && recording_) mark_registers(recording_->ps_int, start, values.size() / 4);
    return result;
}
CallResult Device::set_vertex_shader_constant_b(uint32_t start, std::span<const uint32_t> values) {
    auto result = set_bools("SetVertexShaderConstantB", vs_flow_, start, values);
    if (result && recording_) mark_registers(recording_->vs_bool, start, values.size());
    return result;
}
CallResult Device::set_pixel_shader_constant_b(uint32_t start, std::span<const uint32_t> values) {
    auto result = set_bools("SetPixelShaderConstantB", ps_flow_, start, values);
    if (result && recording_) mark_registers(recording_->ps_bool, start, values.size());
    return result;
}

CallResult Device::set_viewport(const Viewport& viewport) {
    const Surface* rt = render_target_surface(0);
    if (!rt) return CallResult::fail("SetViewport: no render target is bound");
    if (viewport.width == 0 || viewport.height == 0 || viewport.x > rt->width() ||
        viewport.width > rt->width() - viewport.x || viewport.y > rt->height() ||
        viewport.height > rt->height() - viewport.y)
        return CallResult::fail("SetViewport: the viewport does not fit the render target");
    if (!(viewport.min_z >= 0.0f && viewport.min_z <= 1.0f && viewport.max_z >= 0.0f && viewport.max_z <= 1.0f))
        return CallResult::fail("SetViewport: MinZ/MaxZ outside [0, 1]");
    viewport_ = viewport;
    select_binding([](StateSelection& s, uint32_t) { s.viewport = true; }, 0);
    return {};
}

CallResult Device::set_scissor_rect(const PixelRect& rect) {
    if (rect.left < 0 || rect.top < 0 || rect.right < rect.left || rect.bottom < rect.top)
        return CallResult::fail("SetScissorRect: malformed rectangle");
    scissor_ = rect;
    select_binding([](StateSelection& s, uint32_t) { s.scissor = true; }, 0);
    return {};
}

CallResult Device::set_clip_plane(uint32_t index, const Vec4& plane) {
    if (index >= kMaxUserClipPlanes) return CallResult::fail("SetClipPlane: index " + std::to_string(index) + " out of range");
    clip_planes_[index] = plane;
    select_binding([](StateSelection& s, uint32_t i) { s.clip_planes.set(i); }, index);
    return {};
}

// ---------------------------------------------------------------------------------------------
// Fixed-function state

CallResult Device::set_fvf(uint32_t fvf) {
    if (fvf == 0) {
        // D3D9 accepts SetFVF(0) and leaves the declaration as it was.
        fixed_function_.fvf = 0;
        select_binding([](StateSelection& s, uint32_t) { s.fvf = true; }, 0);
        return {};
    }
    FvfLayout layout = fvf_layout(fvf);
    if (!layout.error.empty()) return CallResult::fail("SetFVF: " + layout.error);
    auto declaration = std::make_shared<Resource>();
    declaration->kind = Resource::Kind::Declaration;
    declaration->elements = std::move(layout.elements);
    declaration_ = std::move(declaration);
    fixed_function_.fvf = fvf;
    select_binding([](StateSelection& s, uint32_t) { s.declaration = s.fvf = true; }, 0);
    return {};
}

namespace {

std::string transform_refusal(const char* call, uint32_t state) {
    return std::string(call) + ": transform state " + std::to_string(state) +
           " is not VIEW, PROJECTION, TEXTURE0..7 or WORLDMATRIX(0..255)";
}

}  // namespace

CallResult Device::set_transform(uint32_t state, const Matrix4& matrix) {
    Matrix4* target = fixed_function_.transform(state);
    if (!target) return CallResult::fail(transform_refusal("SetTransform", state));
    *target = matrix;
    select_binding([](StateSelection& s, uint32_t selected) { s.transforms.set(transform_slot(selected)); }, state);
    return {};
}

CallResult Device::multiply_transform(uint32_t state, const Matrix4& matrix) {
    Matrix4* target = fixed_function_.transform(state);
    if (!target) return CallResult::fail(transform_refusal("MultiplyTransform", state));
    *target = multiply(matrix, *target);
    select_binding([](StateSelection& s, uint32_t selected) { s.transforms.set(transform_slot(selected)); }, state);
    return {};
}

CallResult Device::set_material(const Material& material) {
    fixed_function_.material = material;
    select_binding([](StateSelection& s, uint32_t) { s.material = true; }, 0);
    return {};
}

CallResult Device::set_light(uint32_t index, const Light& light) {
    if (auto refused = fixed_function_.set_light(index, light)) return CallResult::fail("SetLight: " + *refused);
    select_binding([](StateSelection& s, uint32_t) { s.lights = true; }, 0);
    return {};
}

CallResult Device::light_enable(uint32_t index, bool enable) {
    if (auto refused = fixed_function_.light_enable(index, enable)) return CallResult::fail("LightEnable: " + *refused);
    select_binding([](StateSelection& s, uint32_t) { s.lights = true; }, 0);
    return {};
}

CallResult Device::set_texture_stage_state(uint32_t stage, uint32_t type, uint32_t value) {
    if (auto refused = fixed_function_.set_texture_stage_state(stage, type, value))
        return CallResult::fail("SetTextureStageState: " + *refused);
    select_binding([](StateSelection& s, uint32_t packed) { s.stage_states[packed >> 8].set(packed & 0xFF); },
                   stage << 8 | type);
    return {};
}

// ---------------------------------------------------------------------------------------------
// Frame

CallResult Device::clear(uint32_t flags, uint32_t color, float z, uint32_t stencil, std::span<const PixelRect> rects) {
    if (flags == 0 || (flags & ~(kClearTarget | kClearZBuffer | kClearStencil)) != 0)
        return CallResult::fail("Clear: flags " + std::to_string(flags) + " are not D3DCLEAR_TARGET/ZBUFFER/STENCIL");
    Surface* rt0 = render_target_surface(0);
    if (!rt0) return CallResult::fail("Clear: no render target is bound");
    DepthStencilSurface* ds = depth_stencil_ ? &*depth_stencil_->depth : nullptr;
    if ((flags & (kClearZBuffer | kClearStencil)) && !ds)
        return CallResult::fail("Clear: ZBUFFER/STENCIL without a depth-stencil surface");
    if ((flags & kClearStencil) && ds->info().stencil_bits == 0)
        return CallResult::fail("Clear: STENCIL on a depth format without stencil bits");
    if ((flags & kClearZBuffer) && !(z >= 0.0f && z <= 1.0f)) return CallResult::fail("Clear: z outside [0, 1]");
    PixelRect area{static_cast<int32_t>(viewport_.x), static_cast<int32_t>(viewport_.y),
                   static_cast<int32_t>(viewport_.x + viewport_.width),
                   static_cast<int32_t>(viewport_.y + viewport_.height)};
    if (render_state_.scissor_test_enable) area = area.intersect(scissor_);
    // Each D3DRECT is clipped to the viewport (and scissor) rectangle; none: the whole of it.
    const std::span<const PixelRect> parts = rects.empty() ? std::span<const PixelRect>(&area, 1) : rects;
    for (const PixelRect& part : parts) {
        const PixelRect rect = rects.empty() ? area : part.intersect(area);
        if (rect.empty()) continue;
        clear_rect(flags, color, z, stencil, rect);
    }
    return {};
}

void Device::clear_rect(uint32_t flags, uint32_t color, float z, uint32_t stencil, const PixelRect& rect) {
    DepthStencilSurface* ds = depth_stencil_ ? &*depth_stencil_->depth : nullptr;
    if (flags & kClearTarget) {
        const auto rgba = color_to_float4(color);
        const Float4 value{rgba[0], rgba[1], rgba[2], rgba[3]};
        for (unsigned i = 0; i < kMaxRenderTargets; ++i) {
            Surface* s = render_target_surface(i);
            if (!s) continue;
            const PixelRect r = rect.intersect(PixelRect{0, 0, static_cast<int32_t>(s->width()), static_cast<int32_t>(s->height())});
            if (r.empty()) continue;
            const unsigned bytes = format_info(s->format())->bytes;
            std::array<std::byte, 16> texel{};
            encode_texel(s->format(), value, texel.data());
            // The rectangle's first row texel by texel, doubling what is done; then each other
            // row as a copy of it.
            const size_t run = static_cast<size_t>(r.right - r.left) * bytes;
            std::byte* const first = s->bytes().data() + static_cast<size_t>(r.top) * s->row_pitch() +
                                     static_cast<size_t>(r.left) * bytes;
            std::memcpy(first, texel.data(), bytes);
            for (size_t done = bytes; done < run; done *= 2) std::memcpy(first + done, first, std::min(done, run - done));
            for (int32_t y = r.top + 1; y < r.bottom; ++y)
                std::memcpy(first + static_cast<size_t>(y - r.top) * s->row_pitch(), first, run);
        }
    }
    if (ds && (flags & (kClearZBuffer | kClearStencil)))
        ds->clear(rect, (flags & kClearZBuffer) != 0, z, (flags & kClearStencil) != 0, stencil);
}

CallResult Device::begin_scene() {
    if (in_scene_) return CallResult::fail("BeginScene: already inside BeginScene/EndScene");
    in_scene_ = true;
    return {};
}

CallResult Device::end_scene() {
    if (!in_scene_) return CallResult::fail("EndScene: without BeginScene");
    in_scene_ = false;
    return {};
}

namespace {

void write_file(const DeviceOptions& options, const Surface& surface, const std::string& path) {
    if (options.write_image) options.write_image(surface, path);
    else write_surface(surface, path);
}

}  // namespace

CallResult Device::present() {
    if (!back_buffer_) return CallResult::fail("Present: no device (CreateDevice) and so no back buffer");
    if (!options_.output_dir.empty()) {
        char file[32];
        std::snprintf(file, sizeof file, "frame_%04u.png", frame_);
        try {
            write_file(options_, gamma_ramp_.empty() ? back_buffer_->surface : through_gamma_ramp(back_buffer_->surface),
                       options_.output_dir + "/" + file);
        } catch (const std::exception& e) {
            return CallResult::fail(std::string("Present: ") + e.what());
        }
    }
    ++frame_;
    return {};
}

CallResult Device::set_software_vertex_processing(bool software) {
    software_vertex_processing_ = software;
    return {};
}

CallResult Device::set_npatch_mode(float segments) {
    if (segments == 0.0f) return {};
    return CallResult::fail("SetNPatchMode: N-patches (" + std::to_string(segments) +
                            " segments) are not drawn by sm2emu; only 0 (off) is accepted");
}

CallResult Device::set_gamma_ramp(uint32_t swap_chain, std::span<const uint16_t> ramp) {
    if (swap_chain != 0) return CallResult::fail("SetGammaRamp: swap chain " + std::to_string(swap_chain) + " does not exist");
    if (ramp.size() != 3 * 256)
        return CallResult::fail("SetGammaRamp: " + std::to_string(ramp.size()) + " WORDs given, a D3DGAMMARAMP holds 768");
    bool identity = true;
    for (size_t i = 0; i < ramp.size(); ++i) identity = identity && ramp[i] == (i % 256) * 257;
    if (identity) gamma_ramp_.clear();
    else gamma_ramp_.assign(ramp.begin(), ramp.end());
    return {};
}

Surface Device::through_gamma_ramp(const Surface& surface) const {
    Surface out = surface;
    for (uint32_t y = 0; y < out.height(); ++y)
        for (uint32_t x = 0; x < out.width(); ++x) {
            Float4 v = out.read(x, y);
            for (unsigned c = 0; c < 3; ++c) {
                // The 8-bit level of the channel (NaN and out-of-range values clamped first).
                const float level = std::isnan(v[c]) ? 0.0f : std::clamp(v[c], 0.0f, 1.0f) * 255.0f;
                const auto index = static_cast<size_t>(std::lround(level));
                v[c] = static_cast<float>(gamma_ramp_[c * 256 + index]) / 65535.0f;
            }
            out.write(x, y, 0, v);
        }
    return out;
}

CallResult Device::set_max_instruction_slots(uint32_t slots) {
    if (slots > 65535)
        return CallResult::fail("instruction-slot limit " + std::to_string(slots) +
                                " out of range (0 for the profile's, or 1 to 65535)");
    options_.max_instruction_slots = slots;
    return CallResult::success();
}

CallResult Device::save_surface(const std::string& name, const std::string& path, uint32_t level, uint32_t face) {
    auto r = find(name);
    const bool texture = r && r->kind == Resource::Kind::Texture;
    if (!r || (r->kind != Resource::Kind::RenderTarget && !texture && r->kind != Resource::Kind::DepthStencil))
        return CallResult::fail("SaveSurface: '" + name + "' is not a surface or texture");
    if (texture ? face >= r->texture.faces() || level >= r->texture.levels() : face != 0 || level != 0)
        return CallResult::fail("SaveSurface: '" + name + "' has no level " + std::to_string(level) + " face " +
                                std::to_string(face));
    // A depth/stencil surface: depth to a float file (.exr, .raw), stencil to an 8-bit one (.png, .tga).
    std::optional<Surface> converted;
    if (r->kind == Resource::Kind::DepthStencil) {
        std::string ext = std::filesystem::path(path).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext == ".exr" || ext == ".raw") {
            converted = depth_as_surface(*r->depth);
        } else if (ext == ".png" || ext == ".tga") {
            if (r->depth->info().stencil_bits == 0)
                return CallResult::fail("SaveSurface: '" + name + "' has no stencil (" + path +
                                        "; depth is written to .exr or .raw files)");
            converted = stencil_as_surface(*r->depth);
        } else {
            return CallResult::fail("SaveSurface: " + path +
                                    ": a depth/stencil surface is written as depth to .exr or .raw, stencil to .png or .tga");
        }
    }
    const Surface& s = converted ? *converted
                       : texture ? r->texture.surface(level, face)
                                 : r->surface;
    // Inside the output folder only (the working folder when there is none): no absolute path,
    // no `..` or symbolic link leaving it.
    std::string error;
    const std::string root = options_.output_dir.empty() ? std::string(".") : options_.output_dir;
    const auto resolved = resolve_inside(root, root, path, error);
    if (!resolved) return CallResult::fail("SaveSurface: " + error);
    // Written under the name as given, made lexically normal ("sub/../a.png" is "a.png").
    const std::string full = (options_.output_dir.empty() ? std::filesystem::path(path)
                                                          : std::filesystem::path(options_.output_dir) / path)
                                 .lexically_normal()
                                 .string();
    try {
        write_file(options_, s, full);
    } catch (const std::exception& e) {
        return CallResult::fail(std::string("SaveSurface: ") + e.what());
    }
    return {};
}

const Surface* Device::surface(const std::string& name) const {
    auto r = find(name);
    if (!r) return nullptr;
    if (r->kind == Resource::Kind::RenderTarget) return &r->surface;
    if (r->kind == Resource::Kind::Texture) return &r->texture.surface(0, 0);
    return nullptr;
}

const DepthStencilSurface* Device::depth_stencil(const std::string& name) const {
    auto r = find(name);
    return r && r->kind == Resource::Kind::DepthStencil ? &*r->depth : nullptr;
}

}  // namespace sm2::runtime
