// The Device: D3D9 device state and resources, and the draws that run the pipeline stages
// (docs/pipeline.md "A draw with these stages"). Every call returns a CallResult; a refused call
// (D3DERR_INVALIDCALL: bad enum, index out of range, missing resource, wrong shader type, bad
// sizes) carries a message and leaves the device exactly as it was.
//
// Resources are named by the caller (the command stream's handles). Bindings hold shared
// references, so Release of a bound resource drops its name but the binding keeps it alive
// until it is replaced (D3D9's reference counting).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/emu/engine.h"
#include "sm2/isa/program.h"
#include "sm2/runtime/clipper.h"
#include "sm2/runtime/depth_stencil.h"
#include "sm2/runtime/fixed_function.h"
#include "sm2/runtime/formats.h"
#include "sm2/runtime/primitive_assembly.h"
#include "sm2/runtime/render_state.h"
#include "sm2/runtime/sampler.h"
#include "sm2/runtime/surface.h"
#include "sm2/runtime/texture.h"
#include "sm2/runtime/vertex_fetch.h"

namespace sm2::runtime {

class WorkerPool;
struct StateBlockObject;
struct DeviceInspection;  // sm2/runtime/device_inspection.h
struct PixelWatch;        // sm2/runtime/pixel_history.h
struct VertexWatch;       // sm2/runtime/pixel_history.h

// The HRESULT a refused call returns: D3DERR_INVALIDCALL for bad arguments and state,
// D3DERR_OUTOFVIDEOMEMORY when a resource does not fit in DeviceOptions::memory_limit, and
// E_OUTOFMEMORY when the host cannot allocate what a call needs.
enum class CallError : uint8_t { InvalidCall, OutOfVideoMemory, OutOfMemory };
// "D3DERR_INVALIDCALL", "D3DERR_OUTOFVIDEOMEMORY", "E_OUTOFMEMORY".
[[nodiscard]] const char* call_error_name(CallError error);

struct CallResult {
    bool ok = true;
    std::string error;  // why D3D9 would refuse the call
    CallError code = CallError::InvalidCall;
    [[nodiscard]] static CallResult success() { return {}; }
    [[nodiscard]] static CallResult fail(std::string message, CallError code = CallError::InvalidCall) {
        return {false, std::move(message), code};
    }
    explicit operator bool() const { return ok; }
};

// D3DCLEAR_* flags.
constexpr uint32_t kClearTarget = 1, kClearZBuffer = 2, kClearStencil = 4;

// D3DPOOL: where a resource lives, which decides what may be done with it (docs/command-stream.md
// "Pools"): DEFAULT resources can be rendered to and sampled but locked only when DYNAMIC (or an
// off-screen plain surface); MANAGED ones sampled and locked; SYSTEMMEM ones locked and used as
// UpdateSurface/UpdateTexture sources or GetRenderTargetData destinations; SCRATCH ones locked only.
enum class Pool : uint8_t { Default = 0, Managed = 1, SystemMem = 2, Scratch = 3 };
[[nodiscard]] const char* pool_name(Pool pool);  // "DEFAULT", "MANAGED", "SYSTEMMEM", "SCRATCH"

// Usage and pool of a created texture: D3DUSAGE_RENDERTARGET, D3DUSAGE_DYNAMIC, D3DPOOL.
// D3DBOX: a part of a volume level; right, bottom and back exclusive.
struct VolumeBox {
    uint32_t left = 0, top = 0, front = 0, right = 0, bottom = 0, back = 0;
};

struct TextureUsage {
    bool render_target = false;
    bool dynamic = false;
    // MANAGED unless given; a RENDERTARGET texture is always DEFAULT.
    std::optional<Pool> pool;
};

// D3DSTATEBLOCKTYPE
enum class StateBlockType : uint8_t { All = 1, PixelState = 2, VertexState = 3 };

constexpr unsigned kMaxVertexShaderConstantsF = 256;  // our D3DCAPS9.MaxVertexShaderConst
constexpr unsigned kMaxPixelShaderConstantsF = 224;   // D3D9's SetPixelShaderConstantF range
constexpr unsigned kMaxConstantsI = 16;
constexpr unsigned kMaxConstantsB = 16;
constexpr unsigned kMaxSamplers = 16;
// The default of DeviceOptions::memory_limit: 2 GiB of resources.
constexpr uint64_t kDefaultMemoryLimit = uint64_t{2} << 30;

struct DeviceOptions {
    // Where Present writes frame_NNNN.png (empty: frames are counted but not written).
    std::string output_dir;
    // Writes a surface to a file; default: image_io's write_surface.
    std::function<void(const Surface&, const std::string& path)> write_image;
    // Tiles are processed by this many threads (1: on the calling thread). Output does not
    // depend on it.
    unsigned threads = 1;
    // Shader arithmetic (fp32, fp24 as ps_2_0 hardware rounds, _pp as fp16; the fp64 reference
    // is sm2 run's and is refused by draws) and the sampler's filter weights.
    emu::PrecisionOptions precision{};
    FilterPrecision filter_precision = FilterPrecision::Fixed8;
    // Instruction-slot limit CreateVertexShader/CreatePixelShader validate against (0: the
    // profile's, 256 vs / 96 ps); a larger value is a ps_2_x-size device for long shaders.
    unsigned max_instruction_slots = 0;
    // Only the reference paths: every texel is sampled and every pixel merged one lane at a
    // time, never by the 16-lane block paths. The bytes are the same; tests compare the two.
    bool reference_paths = false;
    // How draws run shaders: the interpreter (the reference engine), or native code the JIT
    // compiles once per distinct lowered shader (emu/jit.h), where this build has a JIT; the
    // bytes are the same (tests/scenes and tests/emu/jit compare the two).
    enum class Engine : uint8_t { Interpreter, Jit };
    Engine engine = Engine::Interpreter;
    // Bytes all resources together may hold (buffers, textures with every level and face,
    // render targets, depth-stencil surfaces, the back buffer). A creation that would pass it is
    // refused with D3DERR_OUTOFVIDEOMEMORY before anything is allocated; Release gives the bytes
    // back (a released resource that is still bound lives on until unbound, uncounted).
    uint64_t memory_limit = kDefaultMemoryLimit;
};

struct DrawStatistics {
    uint64_t draws = 0, vertices_shaded = 0, primitives = 0, pixels_shaded = 0;
    uint64_t pipelines_built = 0;
    // Pixels covered by a primitive (inside viewport and scissor), discarded by texkill, and
    // that wrote a colour (past texkill, alpha, depth and stencil tests). pixels_shaded counts
    // the ones the pixel shader ran for (after an early depth/stencil test, when one runs), or
    // whose results the draw knew without running it (pixels_outside_texture).
    uint64_t pixels_rasterized = 0, pixels_killed = 0, pixels_written = 0;
    // Of pixels_shaded: pixels of batches whose shader did not run because their alpha lookups
    // lie outside the texture, BORDER with a transparent BORDERCOLOR, in a draw that writes
    // nothing transparent (draw.cpp's outside_cull): their results are known without it.
    uint64_t pixels_outside_texture = 0;
    // Wall time per stage, summed over draws (seconds): building pipelines (lowering), vertex
    // fetch and shading, primitive assembly + clipping + setup + binning, and the tile work
    // (rasterization, interpolation, pixel shading, output merger; all threads together).
    double pipeline_seconds = 0, vertex_seconds = 0, setup_seconds = 0, pixel_seconds = 0;
    // Engine::Jit: shaders compiled by this device's draws and the wall time that took (part of
    // pipeline_seconds). A shader another Device already compiled is reused, not counted.
    uint64_t routines_compiled = 0;
    uint64_t routines_from_cache = 0;  // of routines_compiled: loaded from the JIT cache (emu/jit.h)
    double compile_seconds = 0;
};

class Device {
public:
    explicit Device(DeviceOptions options = {});
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // Resources
    CallResult create_device(uint32_t width, uint32_t height, Format format,
                             std::optional<Format> depth_format = std::nullopt);
    // IDirect3DDevice9::Reset: refused (D3DERR_INVALIDCALL) while a DEFAULT-pool resource other
    // than the back buffer and automatic depth surface is alive; otherwise those two are made
    // again at the new size and format, every state and binding returns to its default, and the
    // viewport and scissor rectangle cover the new back buffer.
    CallResult reset(uint32_t width, uint32_t height, Format format, std::optional<Format> depth_format);
    CallResult create_vertex_buffer(const std::string& name, uint32_t length);
    CallResult create_index_buffer(const std::string& name, uint32_t length, Format format);
    CallResult create_texture(const std::string& name, uint32_t width, uint32_t height, uint32_t levels,
                              Format format, bool render_target = false);
    CallResult create_texture(const std::string& name, uint32_t width, uint32_t height, uint32_t levels,
                              Format format, TextureUsage usage);
    CallResult create_cube_texture(const std::string& name, uint32_t edge, uint32_t levels, Format format,
                                   bool render_target = false);
    CallResult create_cube_texture(const std::string& name, uint32_t edge, uint32_t levels, Format format,
                                   TextureUsage usage);
    CallResult create_volume_texture(const std::string& name, uint32_t width, uint32_t height,
                                     uint32_t depth, uint32_t levels, Format format, TextureUsage usage = {});
    // CreateOffscreenPlainSurface: a lockable surface that cannot be a render target; in the
    // DEFAULT pool it can be ColorFill'ed and StretchRect'ed to, in SYSTEMMEM it receives
    // GetRenderTargetData.
    CallResult create_offscreen_plain_surface(const std::string& name, uint32_t width, uint32_t height,
                                              Format format, Pool pool);
    CallResult create_render_target(const std::string& name, uint32_t width, uint32_t height, Format format);
    CallResult create_depth_stencil_surface(const std::string& name, uint32_t width, uint32_t height,
                                            Format format);
    CallResult create_vertex_declaration(const std::string& name, std::vector<VertexElement> elements);
    // The program is validated (isa::validate) and must be a vertex / pixel shader.
    CallResult create_vertex_shader(const std::string& name, isa::Program program);
    CallResult create_pixel_shader(const std::string& name, isa::Program program);
    CallResult lock(const std::string& buffer, uint32_t offset, std::span<const std::byte> data);
    // Rows tightly packed; data must be exactly one level (face) of the texture or surface.
    CallResult lock_rect(const std::string& texture, uint32_t face, uint32_t level,
                         std::span<const std::byte> data);
    CallResult lock_box(const std::string& texture, uint32_t level, std::span<const std::byte> data);
    // LockBox of a part of the level (D3DBOX: right, bottom and back exclusive): `data` holds the
    // box's texels, rows and slices tightly packed; the box must lie inside the level (not DXTn).
    CallResult lock_box(const std::string& texture, uint32_t level, const VolumeBox& box, std::span<const std::byte> data);
    // LockRect of a part of the level: `data` holds the rectangle's texels, rows tightly packed;
    // the rectangle must lie inside the level (not for DXTn formats).
    CallResult lock_rect(const std::string& texture, uint32_t face, uint32_t level, const PixelRect& rect,
                         std::span<const std::byte> data);
    CallResult load_texture(const std::string& name, const std::string& path, bool generate_mips);
    CallResult generate_mip_sub_levels(const std::string& texture);
    CallResult release(const std::string& name);

    // Bindings ("" unbinds)
    CallResult set_vertex_declaration(const std::string& name);
    CallResult set_vertex_shader(const std::string& name);
    CallResult set_pixel_shader(const std::string& name);
    CallResult set_indices(const std::string& name);
    CallResult set_stream_source(uint32_t stream, const std::string& buffer, uint32_t offset, uint32_t stride);
    CallResult set_texture(uint32_t stage, const std::string& texture);
    CallResult set_render_target(uint32_t index, const std::string& surface);
    CallResult set_depth_stencil_surface(const std::string& surface);

    // States and constants
    CallResult set_render_state(uint32_t type, uint32_t value);
    CallResult set_sampler_state(uint32_t sampler, uint32_t type, uint32_t value);
    CallResult set_vertex_shader_constant_f(uint32_t start, std::span<const float> values);
    CallResult set_pixel_shader_constant_f(uint32_t start, std::span<const float> values);
    CallResult set_vertex_shader_constant_i(uint32_t start, std::span<const int32_t> values);
    CallResult set_pixel_shader_constant_i(uint32_t start, std::span<const int32_t> values);
    CallResult set_vertex_shader_constant_b(uint32_t start, std::span<const uint32_t> values);
    CallResult set_pixel_shader_constant_b(uint32_t start, std::span<const uint32_t> values);
    CallResult set_viewport(const Viewport& viewport);
    CallResult set_scissor_rect(const PixelRect& rect);
    CallResult set_clip_plane(uint32_t index, const Vec4& plane);

    // Fixed-function state (fixed_function.h; draws without a vertex shader do not use it yet).
    // SetFVF also binds the FVF's vertex layout as the vertex declaration, as D3D9 does, so a
    // shader draw can read an FVF buffer; SetVertexDeclaration sets the FVF back to 0.
    CallResult set_fvf(uint32_t fvf);
    CallResult set_transform(uint32_t state, const Matrix4& matrix);
    // state = matrix times state (D3D9's order).
    CallResult multiply_transform(uint32_t state, const Matrix4& matrix);
    CallResult set_material(const Material& material);
    CallResult set_light(uint32_t index, const Light& light);
    CallResult light_enable(uint32_t index, bool enable);
    CallResult set_texture_stage_state(uint32_t stage, uint32_t type, uint32_t value);

    // Frame
    // `rects` (D3DRECTs) empty: the whole viewport; otherwise each rectangle clipped to the
    // viewport (and to the scissor rectangle when SCISSORTESTENABLE is TRUE).
    CallResult clear(uint32_t flags, uint32_t color, float z, uint32_t stencil, std::span<const PixelRect> rects = {});
    CallResult begin_scene();
    CallResult end_scene();
    CallResult present();
    // SaveSurface: a render target, a texture's level/face (volume: slice 0 of the level), or a
    // depth/stencil surface (depth to .exr/.raw as float, stencil to .png/.tga as the integer
    // value; depth_as_surface / stencil_as_surface in image_io.h).
    CallResult save_surface(const std::string& surface, const std::string& path, uint32_t level = 0, uint32_t face = 0);
    // SetDeviceLimits: the instruction-slot limit that later CreateVertexShader/CreatePixelShader
    // calls validate against (0: the profile's, 256 vs / 96 ps; 1..65535 otherwise; a larger
    // value is a ps_2_x-size device). DeviceOptions::max_instruction_slots is its initial value.
    CallResult set_max_instruction_slots(uint32_t slots);
    [[nodiscard]] unsigned max_instruction_slots() const { return options_.max_instruction_slots; }
    // Copies the whole source surface (render target, or level 0 of a 2D texture) onto the whole
    // destination render target, scaling with POINT (NONE) or LINEAR filtering and converting
    // the format through decode_texel/encode_texel (stretch_rect.cpp).
    CallResult stretch_rect(const std::string& source, const std::string& destination, TextureFilter filter);
    // StretchRect of a source rectangle onto a destination rectangle (nullopt: the whole surface).
    CallResult stretch_rect(const std::string& source, const std::optional<PixelRect>& source_rect,
                            const std::string& destination, const std::optional<PixelRect>& destination_rect,
                            TextureFilter filter);
    // ColorFill: a DEFAULT-pool surface (render target, RENDERTARGET texture level 0, off-screen
    // plain surface) or its rectangle, set to a D3DCOLOR (surface_copy.cpp).
    CallResult color_fill(const std::string& surface, const std::optional<PixelRect>& rect, uint32_t color);
    // UpdateSurface: the source rectangle (whole surface) of a SYSTEMMEM surface or texture level
    // copied unscaled, same format, to `destination_x/y` of a DEFAULT one (surface_copy.cpp).
    CallResult update_surface(const std::string& source, uint32_t source_level, const std::optional<PixelRect>& source_rect,
                              const std::string& destination, uint32_t destination_level, uint32_t destination_x,
                              uint32_t destination_y);
    // UpdateTexture: every level of a DEFAULT texture from the SYSTEMMEM texture level of the same size.
    CallResult update_texture(const std::string& source, const std::string& destination);
    // GetRenderTargetData: a render target copied to a SYSTEMMEM surface of its size and format.
    CallResult get_render_target_data(const std::string& render_target, const std::string& destination);
    // SetSoftwareVertexProcessing: accepted (vertex processing is software here either way).
    CallResult set_software_vertex_processing(bool software);
    // SetNPatchMode: 0 segments (N-patches off) is accepted; N-patches are not drawn, so any other
    // count is refused.
    CallResult set_npatch_mode(float segments);
    // SetGammaRamp (swap chain 0): 256 red, 256 green, then 256 blue WORDs. Present writes the
    // back buffer through it (channel value v in 0..255 becomes ramp[v] / 65535); the back buffer
    // itself keeps its values, as the ramp is the display's.
    CallResult set_gamma_ramp(uint32_t swap_chain, std::span<const uint16_t> ramp);

    // State blocks (state_block.cpp): CreateStateBlock captures the type's states now;
    // BeginStateBlock/EndStateBlock records which states are set in between (their values when
    // EndStateBlock is called: the calls are applied, as D3D9 records them into the block and
    // Capture/Apply use the block's selection); Capture re-reads the selected states from the
    // device, Apply sets them.
    CallResult create_state_block(const std::string& name, StateBlockType type);
    CallResult begin_state_block();
    CallResult end_state_block(const std::string& name);
    CallResult capture_state_block(const std::string& name);
    CallResult apply_state_block(const std::string& name);

    // Draws
    CallResult draw_primitive(uint32_t type, uint32_t start_vertex, uint32_t primitive_count);
    CallResult draw_indexed_primitive(uint32_t type, int32_t base_vertex, uint32_t min_index,
                                      uint32_t num_vertices, uint32_t start_index, uint32_t primitive_count);
    CallResult draw_primitive_up(uint32_t type, uint32_t primitive_count, std::span<const std::byte> vertices,
                                 uint32_t stride);
    CallResult draw_indexed_primitive_up(uint32_t type, uint32_t min_index, uint32_t num_vertices,
                                         uint32_t primitive_count, std::span<const std::byte> indices,
                                         Format index_format, std::span<const std::byte> vertices,
                                         uint32_t stride);

    // Inspection (tests, tools)
    [[nodiscard]] const Surface* surface(const std::string& name) const;  // render target, back buffer, texture level 0
    [[nodiscard]] const DepthStencilSurface* depth_stencil(const std::string& name) const;
    [[nodiscard]] const RenderState& render_state() const { return render_state_; }
    [[nodiscard]] const Viewport& viewport() const { return viewport_; }
    [[nodiscard]] const FixedFunctionState& fixed_function() const { return fixed_function_; }
    [[nodiscard]] bool has_resource(const std::string& name) const { return resources_.count(name) != 0; }
    [[nodiscard]] uint32_t frames_presented() const { return frame_; }
    [[nodiscard]] const DrawStatistics& statistics() const { return stats_; }
    // Bytes the named resources hold now (counted against DeviceOptions::memory_limit).
    [[nodiscard]] uint64_t memory_used() const { return memory_used_; }
    [[nodiscard]] uint64_t memory_limit() const { return options_.memory_limit; }
    [[nodiscard]] const SamplerState& sampler_state(uint32_t sampler) const { return sampler_states_.at(sampler); }
    [[nodiscard]] const std::array<float, 4>& vertex_shader_constant_f(uint32_t reg) const { return vs_f_.at(reg); }
    [[nodiscard]] const std::array<float, 4>& pixel_shader_constant_f(uint32_t reg) const { return ps_f_.at(reg); }
    [[nodiscard]] const emu::StaticFlowConstants& vertex_shader_flow_constants() const { return vs_flow_; }
    [[nodiscard]] const emu::StaticFlowConstants& pixel_shader_flow_constants() const { return ps_flow_; }
    [[nodiscard]] const PixelRect& scissor_rect() const { return scissor_; }
    [[nodiscard]] const Vec4& clip_plane(uint32_t index) const { return clip_planes_.at(index); }
    // Everything bound and set now, for sm2 state and sm2 replay --snapshot (device_inspection.cpp).
    [[nodiscard]] DeviceInspection inspect() const;
    // Pixel history (sm2 pixel): while `watch` is set, each draw appends what its primitives did
    // to pixel (watch->x, watch->y) of its render targets. Null (the default) turns it off.
    void watch_pixel(PixelWatch* watch) { pixel_watch_ = watch; }
    // Vertex debugging (sm2 debug --vertex): while `watch` is set, each draw appends the trace of
    // its vertex shader for vertex watch->index, when the draw fetches that vertex.
    void watch_vertex(VertexWatch* watch) { vertex_watch_ = watch; }

    struct Resource;
    struct ShaderObject;
    struct StateSelection;
    struct StateSnapshot;

private:
    CallResult lock_box(const std::string& texture, uint32_t level, const VolumeBox* box, std::span<const std::byte> data);
    struct Draw;
    void select(uint32_t render_state);  // while recording a state block: the state joins it
    void select_sampler(uint32_t sampler, uint32_t type);
    void select_binding(void (*mark)(StateSelection&, uint32_t), uint32_t index);
    void capture(const StateSelection& selection, StateSnapshot& snapshot) const;
    void apply(const StateSelection& selection, const StateSnapshot& snapshot);
    CallResult create_shader(const std::string& name, isa::Program program, isa::ShaderType type);
    CallResult add_resource(const std::string& name, std::shared_ptr<Resource> resource);
    // Refuses (D3DERR_OUTOFVIDEOMEMORY, "WHAT needs N bytes; ...") when `bytes` more would pass
    // the memory limit.
    CallResult reserve_memory(const std::string& what, uint64_t bytes) const;
    std::shared_ptr<Resource> find(const std::string& name) const;
    CallResult run_draw(PrimitiveType type, uint32_t primitive_count, std::vector<uint32_t> draw_vertices,
                        std::span<const VertexStream> streams);
    Surface* render_target_surface(unsigned index) const;
    void clear_rect(uint32_t flags, uint32_t color, float z, uint32_t stencil, const PixelRect& rect);
    [[nodiscard]] Surface through_gamma_ramp(const Surface& surface) const;
    std::vector<VertexStream> bound_streams() const;  // SetStreamSource bindings, as spans

    DeviceOptions options_;
    std::map<std::string, std::shared_ptr<Resource>> resources_;
    bool created_ = false;
    RenderState render_state_ = RenderState::defaults(false);
    std::array<SamplerState, kMaxSamplers> sampler_states_{};
    std::array<std::shared_ptr<Resource>, kMaxSamplers> textures_{};
    std::array<std::shared_ptr<Resource>, kMaxRenderTargets> render_targets_{};
    std::shared_ptr<Resource> depth_stencil_, back_buffer_;
    std::shared_ptr<Resource> declaration_, vertex_shader_, pixel_shader_, indices_;
    struct StreamBinding {
        std::shared_ptr<Resource> buffer;
        uint32_t offset = 0, stride = 0;
    };
    std::array<StreamBinding, kMaxVertexStreams> streams_{};
    std::vector<std::array<float, 4>> vs_f_, ps_f_;
    emu::StaticFlowConstants vs_flow_{}, ps_flow_{};
    Viewport viewport_{};
    PixelRect scissor_{};
    std::array<Vec4, kMaxUserClipPlanes> clip_planes_{};
    FixedFunctionState fixed_function_;
    bool in_scene_ = false;
    bool software_vertex_processing_ = false;
    std::vector<uint16_t> gamma_ramp_;  // empty: the identity
    // Render states accepted but not modelled by RenderState (fixed-function, tessellation):
    // their last DWORDs, so that state blocks capture and apply them like the others.
    std::map<uint32_t, uint32_t> other_render_states_;
    // Fixed-function programs generated for draws without shaders, by program text (their key).
    std::map<std::string, std::shared_ptr<ShaderObject>> fixed_function_programs_;
    // BeginStateBlock ... EndStateBlock: what the calls in between set.
    std::unique_ptr<StateSelection> recording_;
    std::shared_ptr<StateBlockObject> state_before_recording_;  // given back at EndStateBlock
    uint32_t frame_ = 0;
    PixelWatch* pixel_watch_ = nullptr;
    VertexWatch* vertex_watch_ = nullptr;
    DrawStatistics stats_{};
    uint64_t memory_used_ = 0;
    TextureSampler sampler_;
    std::unique_ptr<WorkerPool> pool_;  // the tile threads, started by the first draw
};

}  // namespace sm2::runtime
