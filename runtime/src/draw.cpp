// The draw: every stage of docs/pipeline.md "A draw with these stages", in order, with a pipeline
// specialized for the draw's state. Checks that can refuse the draw (D3DERR_INVALIDCALL) all run
// before the first pixel is written, so a refused draw leaves every surface as it was.
//
//   key      = (vs flow key, ps flow key, outputs the next stage reads)  -> lowered executables
//   vertices = fetch + vertex shader, each distinct vertex once (post-transform cache)
//   setups   = primitive assembly -> clipper -> setup (culling, edges, planes), in draw order
//   tiles    = setups binned by their bounds; each tile is owned by one thread and rasterizes,
//              interpolates, shades and merges its primitives in draw order
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "compiled_shaders.h"
#include "device_internal.h"
#include "fixed_function_programs.h"
#include "worker_pool.h"
#include "sm2/emu/alpha_source.h"
#include "sm2/isa/validator.h"
#include "sm2/runtime/interpolation.h"
#include "sm2/runtime/output_merger.h"
#include "sm2/runtime/pixel_history.h"
#include "sm2/runtime/rasterizer.h"
#include "sm2/runtime/setup.h"

namespace sm2::runtime {

namespace {

namespace slot = emu::slot;

// Seconds since `start`, and restarts the clock (the per-stage figures of DrawStatistics).
double lap(std::chrono::steady_clock::time_point& start) {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    return seconds;
}

// Output bits of emu::LoweringOptions::outputs_read (bit s - slot::kPosition).
constexpr uint32_t output_bit(unsigned s) { return 1u << (s - slot::kPosition); }

// The ps inputs a pixel shader reads, as varying bits (v0/v1 -> colours, t# -> texcoords).
uint16_t varyings_read_by(const emu::Executable& ps) {
    const auto& read = ps.components_read();
    uint16_t mask = 0;
    for (unsigned d = 0; d < 2; ++d)
        if (read[slot::kInputFirst + d]) mask |= static_cast<uint16_t>(1u << (kVaryingColor0 + d));
    for (unsigned t = 0; t < slot::kTexCoordCount; ++t)
        if (read[slot::kTexCoordFirst + t]) mask |= static_cast<uint16_t>(1u << (kVaryingTexCoord0 + t));
    return mask;
}

// The vertex shader outputs that carry the varyings in `mask`.
uint32_t vs_outputs_for(uint16_t varyings) {
    uint32_t outputs = output_bit(slot::kPosition);
    for (unsigned d = 0; d < 2; ++d)
        if (varyings >> (kVaryingColor0 + d) & 1u) outputs |= output_bit(slot::kColorOutFirst + d);
    for (unsigned t = 0; t < slot::kTexCoordOutCount; ++t)
        if (varyings >> (kVaryingTexCoord0 + t) & 1u) outputs |= output_bit(slot::kTexCoordOutFirst + t);
    if (varyings >> kVaryingFog & 1u) outputs |= output_bit(slot::kFog);
    return outputs;
}

emu::LoweringOptions lowering_options(const Device::ShaderObject& object, uint32_t outputs_read,
                                      const emu::PrecisionOptions& precision) {
    emu::LoweringOptions options;
    options.precision = precision;
    options.outputs_read = outputs_read;
    if (object.shader->version().is_vertex()) options.constant_count = kMaxVertexShaderConstantsF;
    return options;
}

// The pipeline cache: one lowered executable per (flow key, outputs read) of a shader.
Device::ShaderObject::Lowered* lowered_for(Device::ShaderObject& object, const emu::StaticFlowConstants& application,
                                   uint32_t outputs_read, const emu::PrecisionOptions& precision,
                                   DrawStatistics& stats, std::string& error) {
    const emu::StaticFlowConstants key = object.shader->flow_key(application);
    for (auto& entry : object.lowered)
        if (entry.flow == key && entry.outputs_read == outputs_read) return &entry;
    // The draw's executable computes its uniform steps once per draw (bind_constants()); the
    // debugger's (debug_shader()) keeps every step as the source has it.
    emu::LoweringOptions options = lowering_options(object, outputs_read, precision);
    options.hoist_uniform_steps = true;
    auto lowered = emu::lower(*object.shader, key, options);
    if (!lowered.executable) {
        error = lowered.error;
        return nullptr;
    }
    object.lowered.push_back({key, outputs_read, std::move(*lowered.executable), false, nullptr});
    ++stats.pipelines_built;
    return &object.lowered.back();
}

// A shader lowered as for the draw but keeping every instruction, dead or not (sm2 debug shows
// each source instruction), with its constants bound as the draw binds them.
struct DebugShader {
    std::shared_ptr<const isa::Program> program;
    bool fixed_function = false;
    std::optional<emu::Executable> executable;
    emu::ConstantFile constants;
};

std::optional<DebugShader> debug_shader(const std::shared_ptr<Device::ShaderObject>& object, bool fixed_function,
                                        const emu::StaticFlowConstants& application, uint32_t outputs_read,
                                        const emu::PrecisionOptions& precision,
                                        std::span<const std::array<float, 4>> constants) {
    emu::LoweringOptions options = lowering_options(*object, outputs_read, precision);
    options.keep_dead_code = true;
    auto lowered = emu::lower(*object->shader, object->shader->flow_key(application), options);
    if (!lowered.executable) return std::nullopt;
    DebugShader debug{std::shared_ptr<const isa::Program>(object, &object->shader->program()), fixed_function,
                      std::move(lowered.executable), {}};
    debug.constants = debug.executable->bind_constants(constants);
    return debug;
}

// The inputs (v#, t#) `executable` reads, with every lane's value in `batch`.
std::vector<emu::InstructionWrite> inputs_read(const emu::Executable& executable, const emu::Batch& batch) {
    static_assert(slot::kTexCoordFirst == slot::kInputFirst + slot::kInputCount, "v# and t# slots are contiguous");
    std::vector<emu::InstructionWrite> inputs;
    for (unsigned s = slot::kInputFirst; s < slot::kTexCoordFirst + slot::kTexCoordCount; ++s) {
        const uint8_t mask = executable.components_read()[s];
        if (!mask) continue;
        emu::InstructionWrite input{static_cast<uint16_t>(s), false, mask, {}};
        for (unsigned lane = 0; lane < emu::kBatchLanes; ++lane)
            for (unsigned c = 0; c < 4; ++c) input.lanes[lane][c] = batch.registers[s][c][lane];
        inputs.push_back(input);
    }
    return inputs;
}

// The constants `executable` reads by number, as bound for the draw.
std::vector<std::pair<uint16_t, Float4>> constants_read(const emu::Executable& executable, const emu::ConstantFile& constants) {
    std::vector<std::pair<uint16_t, Float4>> read;
    for (const emu::Step& step : executable.steps())
        for (unsigned k = 0; k < step.source_count; ++k) {
            const emu::StepSource& source = step.sources[k];
            if (source.kind != emu::OperandKind::Constant || source.index >= constants.registers.size()) continue;
            if (std::any_of(read.begin(), read.end(), [&](const auto& r) { return r.first == source.index; })) continue;
            read.emplace_back(source.index, constants.registers[source.index]);
        }
    std::sort(read.begin(), read.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return read;
}

// `debug` run on `batch` (its inputs as the draw set them), one source instruction at a time.
std::shared_ptr<ShaderDebug> trace_shader(const DebugShader& debug, emu::Batch& batch, emu::Sampler* sampler) {
    auto trace = std::make_shared<ShaderDebug>();
    trace->program = debug.program;
    trace->fixed_function = debug.fixed_function;
    trace->inputs = inputs_read(*debug.executable, batch);
    trace->constants = constants_read(*debug.executable, debug.constants);
    trace->steps = emu::trace_instructions(*debug.executable, debug.constants, batch, sampler);
    return trace;
}

// Engine::Jit: the entry's executable as native code, from the process-wide cache on the
// entry's first draw (and counted in `stats` when that compiled it); null: interpret.
const emu::jit::CompiledShader* compiled_for(Device::ShaderObject::Lowered& entry, DrawStatistics& stats) {
    if (!entry.compiled_looked_up) {
        const CompiledLookup lookup = compiled_shader(entry.executable);
        entry.compiled = lookup.shader;
        entry.compiled_looked_up = true;
        if (lookup.compiled_now && lookup.shader) {
            ++stats.routines_compiled;
            if (lookup.from_cache) ++stats.routines_from_cache;
            stats.compile_seconds += lookup.compile_seconds;
        }
    }
    return entry.compiled.get();
}

// Batches whose alpha-deciding lookup lies outside its texture (outside_cull()): the t# the
// texld reads (x, y, z: u, v, w) and the sampler's box.
struct OutsideCull {
    unsigned texcoord = 0;
    TextureSampler::BorderBox box;
};

// Everything the pixel part of a draw reads: built once, shared read-only by the tile threads.
struct PixelPipeline {
    const emu::Executable* ps = nullptr;  // the application's shader or the fixed-function program
    const emu::jit::CompiledShader* ps_compiled = nullptr;  // ps as native code (Engine::Jit)
    const emu::ConstantFile* ps_constants = nullptr;
    uint16_t ps_varyings = 0;             // what interpolation writes
    OutputMergerState merger{};
    RenderTargets targets{};
    MergeInput merge_template{};
    MergePlan merge_plan{};  // merge_plan(merger, targets, merge_template)
    bool early_depth_stencil = false;
    // Whether anything reads the interpolated depth: the depth and stencil tests, fog, pixel
    // history (sm2 pixel, sm2 debug). Without, interpolation leaves it out.
    bool interpolated_depth = true;
    bool reference_paths = false;  // DeviceOptions::reference_paths: the portable interpolation
    const TextureSampler* sampler = nullptr;
    std::optional<OutsideCull> outside_cull;  // batches not shaded (outside_cull())
};

// One tile owner's working set.
struct TileWorker {
    emu::Batch batch;
    PixelLanes lanes;
    std::array<Quad, kTileQuads> tile_quads;  // one primitive's quads in one tile (process_tile)
    TextureSampler sampler;
    uint64_t pixels_shaded = 0, pixels_rasterized = 0, pixels_killed = 0, pixels_written = 0;
    uint64_t pixels_outside_texture = 0;
};

// What draws see of their own work: nothing (every draw), or the watched pixel's stages
// (PixelRecorder, only in a draw's second pass over that one pixel). Empty inline calls compile
// away, so the draw's code is the same with and without pixel history.
struct NoObserver {
    void before_shader(const emu::Batch&) {}
    void early_tested(emu::LaneMask) {}
    void shaded(const emu::Batch&, emu::LaneMask) {}
    void merged(emu::LaneMask) {}
};

// The lanes set in a 16-lane mask. std::popcount is a library call in the baseline x86-64
// build (no POPCNT instruction assumed), four times a batch; this is a few register operations.
constexpr uint64_t lanes_in(emu::LaneMask mask) {
    static_assert(emu::kBatchLanes == 16, "the sum below covers 16 bits");
    uint32_t x = mask & 0xFFFFu;
    x = x - ((x >> 1) & 0x5555u);
    x = (x & 0x3333u) + ((x >> 2) & 0x3333u);
    x = (x + (x >> 4)) & 0x0F0Fu;
    return (x + (x >> 8)) & 0x1Fu;
}
static_assert(lanes_in(0) == 0 && lanes_in(0xFFFF) == 16 && lanes_in(0x8001) == 2 && lanes_in(0x7FFE) == 14);

// The texld whose lookups may leave their colour unset where their alpha is transparent on
// every lane (TextureSampler::set_alpha_gate, on its sampler stage): the one texld whose alpha
// the shader's oC0.w follows (emu::alpha_source_texld), in a draw that writes render target 0
// alone and skips its transparent batches (TargetPlan::transparent_skips). Such a batch writes
// nothing, so no colour of it is read. Not with texkill or oDepth, whose lanes and depth the
// colour could decide. Its index in ps.steps().
std::optional<size_t> alpha_gate_texld(const emu::Executable& ps, const MergePlan& plan, const MergeInput& outputs,
                                       bool kills) {
    if (kills || outputs.shader_depth || outputs.color_outputs != 1u || !plan.targets[0].transparent_skips)
        return std::nullopt;
    for (unsigned t = 1; t < kMaxRenderTargets; ++t)
        if (plan.targets[t].path != TargetPath::Skip) return std::nullopt;
    const std::optional<size_t> texld = emu::alpha_source_texld(ps);
    if (!texld || ps.steps()[*texld].sampler >= TextureSampler::kStages) return std::nullopt;
    return texld;
}

// The alpha gate's texld (`texld`) reads an interpolated t# as it is (a plain texld, no swizzle
// or negate, fp32) and its stage has a TextureSampler::transparent_border(): a batch whose every
// live lane reads that t# outside the border box on one BORDER axis samples alpha +0 on all of
// them, and so writes nothing (the slices of a volume drawn beyond it). Nor does anything else
// of it change where no alpha test drops lanes and the depth and stencil tests ran before the
// shader or are off: such a batch is not shaded (shade_quads). Pixel history shades every batch.
std::optional<OutsideCull> outside_cull(const emu::Executable& ps, size_t texld, const TextureSampler& sampler,
                                        const OutputMergerState& merger, bool early_depth_stencil) {
    const emu::Step& step = ps.steps()[texld];
    const emu::StepSource& coordinate = step.sources[0];
    if (ps.precision() != emu::Precision::Fp32 || step.control != isa::kTexLdPlain ||
        coordinate.kind != emu::OperandKind::Lanes || coordinate.index < slot::kTexCoordFirst ||
        coordinate.index >= slot::kTexCoordFirst + slot::kTexCoordCount || coordinate.swizzle != 0xE4 || coordinate.negate)
        return std::nullopt;
    // An alpha test decides lanes, and so the depth written, after the shader. Without one the
    // gate's draw (no texkill, no oDepth) tests depth and stencil before it (the second test
    // guards that).
    if (merger.alpha_test || (merger.depth_stencil.active() && !early_depth_stencil)) return std::nullopt;
    const std::optional<TextureSampler::BorderBox> box = sampler.transparent_border(step.sampler);
    if (!box) return std::nullopt;
    return OutsideCull{coordinate.index - slot::kTexCoordFirst, *box};
}

// Whether every lane of `live` reads its OutsideCull coordinate outside the border box.
bool lookups_outside(const OutsideCull& cull, const TextureSampler& sampler, const emu::Batch& batch,
                     emu::LaneMask live) {
    const emu::Batch::Register& t = batch.texcoord(cull.texcoord);
    return (live & ~sampler.outside_border(cull.box, {t[0].data(), t[1].data(), t[2].data()})) == 0;
}

template <class Observer>
void shade_quads(const PixelPipeline& pipe, const PrimitiveSetup& prim, std::span<const Quad> quads,
                 TileWorker& w, Observer& observer) {
    interpolate(prim, quads, pipe.ps_varyings, w.batch, w.lanes, pipe.reference_paths, pipe.interpolated_depth);
    emu::LaneMask live = w.lanes.coverage;
    w.pixels_rasterized += lanes_in(live);
    MergeInput input = pipe.merge_template;
    input.batch = &w.batch;
    input.lanes = &w.lanes;
    if (pipe.early_depth_stencil) {
        // The shader can change neither depth nor coverage: test first, shade only survivors.
        live = depth_stencil_test(pipe.merger.depth_stencil, pipe.targets.depth_stencil, w.lanes.x, w.lanes.y,
                                  w.lanes.depth, live, w.lanes.clockwise, pipe.reference_paths);
        input.depth_stencil_done = true;
        observer.early_tested(live);
        if (!live) return;
    }
    if constexpr (std::is_same_v<Observer, NoObserver>) {
        if (pipe.outside_cull && lookups_outside(*pipe.outside_cull, w.sampler, w.batch, live)) {
            // What shading and merge() would count: every live lane shaded, none killed, and all
            // past the tests (written: the target skips them). `live` lies within the batch's
            // quads (the coverage interpolate() set), so merge()'s mask to them changes nothing.
            const uint64_t lanes = lanes_in(live);
            w.pixels_shaded += lanes;
            w.pixels_written += lanes;
            w.pixels_outside_texture += lanes;
            return;
        }
    }
    w.batch.killed = 0;
    // A batch whose lanes a texkill has all killed writes nothing: the shader may stop there.
    // Pixel history records every fragment's outputs, so its pass runs the whole shader.
    w.batch.stop_when_all_killed = std::is_same_v<Observer, NoObserver>;
    observer.before_shader(w.batch);
    if (pipe.ps_compiled)
        pipe.ps_compiled->run(*pipe.ps_constants, w.batch, &w.sampler);
    else
        emu::execute(*pipe.ps, *pipe.ps_constants, w.batch, &w.sampler);
    w.pixels_shaded += lanes_in(live);
    w.pixels_killed += lanes_in(live & w.batch.killed);
    observer.shaded(w.batch, live);
    input.live = live;
    const emu::LaneMask written = merge(pipe.merger, pipe.targets, input, pipe.merge_plan);
    observer.merged(written);
    w.pixels_written += lanes_in(written);
}

void process_tile(const PixelPipeline& pipe, std::span<const PrimitiveSetup> setups,
                  std::span<const uint32_t> primitives, const PixelRect& region, TileWorker& w) {
    NoObserver none;
    for (uint32_t index : primitives) {
        const PrimitiveSetup& prim = setups[index];
        // (A tile's region: at most kTileQuads quads.)
        const size_t count = rasterize(prim, region, w.tile_quads.data(), pipe.reference_paths);
        const std::span<const Quad> quads(w.tile_quads.data(), count);
        for (size_t q = 0; q < count; q += emu::kBatchQuads)
            shade_quads(pipe, prim, quads.subspan(q, std::min<size_t>(emu::kBatchQuads, count - q)), w, none);
    }
}

// ---------------------------------------------------------------------------------------------
// Pixel history: a second pass of the draw over the watched pixel alone, through the same
// rasterize / shade_quads / merge, after the pixel is given back its value from before the draw.

// The watched pixel's stored values in every target.
struct PixelValues {
    std::array<Float4, kMaxRenderTargets> color{};
    float depth = 0.0f;
    uint32_t stencil = 0;
};

PixelValues read_pixel(const RenderTargets& targets, uint32_t x, uint32_t y) {
    PixelValues v;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i)
        if (targets.color[i] && x < targets.color[i]->width() && y < targets.color[i]->height())
            v.color[i] = targets.color[i]->read(x, y);
    if (const DepthStencilSurface* ds = targets.depth_stencil; ds && x < ds->width() && y < ds->height()) {
        v.depth = ds->depth(x, y);
        v.stencil = ds->stencil(x, y);
    }
    return v;
}

// Stored bytes, so that giving the pixel back its value is exact in every format.
struct PixelBytes {
    std::array<std::vector<std::byte>, kMaxRenderTargets> color;
    uint32_t depth = 0, stencil = 0;
};

size_t texel_offset(const Surface& s, uint32_t x, uint32_t y) {
    return static_cast<size_t>(y) * s.row_pitch() + static_cast<size_t>(x) * (s.row_pitch() / std::max(1u, s.width()));
}

PixelBytes save_pixel(const RenderTargets& targets, uint32_t x, uint32_t y) {
    PixelBytes b;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i) {
        const Surface* s = targets.color[i];
        if (!s || x >= s->width() || y >= s->height()) continue;
        const size_t bytes = s->row_pitch() / std::max(1u, s->width());
        const auto first = s->bytes().begin() + static_cast<std::ptrdiff_t>(texel_offset(*s, x, y));
        b.color[i].assign(first, first + static_cast<std::ptrdiff_t>(bytes));
    }
    if (const DepthStencilSurface* ds = targets.depth_stencil; ds && x < ds->width() && y < ds->height()) {
        b.depth = ds->stored_depth(x, y);
        b.stencil = ds->stencil(x, y);
    }
    return b;
}

void restore_pixel(const RenderTargets& targets, uint32_t x, uint32_t y, const PixelBytes& b) {
    for (unsigned i = 0; i < kMaxRenderTargets; ++i) {
        Surface* s = targets.color[i];
        if (!s || b.color[i].empty()) continue;
        std::copy(b.color[i].begin(), b.color[i].end(), s->bytes().begin() + static_cast<std::ptrdiff_t>(texel_offset(*s, x, y)));
    }
    if (DepthStencilSurface* ds = targets.depth_stencil; ds && x < ds->width() && y < ds->height()) {
        ds->set_stored_depth(x, y, b.depth);
        ds->set_stencil(x, y, b.stencil);
    }
}

// Notes the watched lane's results as shade_quads runs.
struct PixelRecorder {
    uint32_t x = 0, y = 0;
    const TileWorker* worker = nullptr;
    PixelFragment* fragment = nullptr;
    const emu::Executable* ps = nullptr;
    bool keep_shader_input = false;             // sm2 debug: the batch as the shader starts
    std::unique_ptr<emu::Batch> shader_input;

    [[nodiscard]] int lane() const {
        for (unsigned l = 0; l < worker->lanes.quad_count * 4 && l < emu::kBatchLanes; ++l)
            if (worker->lanes.x[l] == static_cast<int32_t>(x) && worker->lanes.y[l] == static_cast<int32_t>(y)) return static_cast<int>(l);
        return -1;
    }
    [[nodiscard]] bool has(emu::LaneMask mask) const {
        const int l = lane();
        return l >= 0 && (mask >> l & 1u);
    }
    void before_shader(const emu::Batch& batch) {
        if (keep_shader_input) shader_input = std::make_unique<emu::Batch>(batch);
    }
    void early_tested(emu::LaneMask live) {
        fragment->early_depth_stencil = true;
        fragment->depth_stencil_passed = has(live);
    }
    void shaded(const emu::Batch& batch, emu::LaneMask live) {
        const int l = lane();
        if (l < 0 || !(live >> l & 1u)) return;
        fragment->shaded = true;
        fragment->killed = batch.killed >> l & 1u;
        for (unsigned t = 0; t < kMaxRenderTargets; ++t)
            for (unsigned c = 0; c < 4; ++c) fragment->shader_color[t][c] = batch.render_target(t)[c][l];
        fragment->depth = worker->lanes.depth[l];
        if (!ps) return;
        // The shader cannot write its inputs: after it ran they still hold the interpolated values.
        for (unsigned s = slot::kInputFirst; s < slot::kTexCoordFirst + slot::kTexCoordCount; ++s)
            if (ps->components_read()[s])
                fragment->inputs.emplace_back(static_cast<uint16_t>(s), Float4{batch.registers[s][0][l], batch.registers[s][1][l],
                                                                          batch.registers[s][2][l], batch.registers[s][3][l]});
    }
    void merged(emu::LaneMask written) { fragment->written = has(written); }
};



// Vertex stage: fetches each distinct vertex (in batches of 16 lanes), runs the vertex shader and
// keeps what later stages read. Returns a fetch error (a read past a buffer), else "".
std::string shade_vertices(const FetchPlan& plan, std::span<const VertexStream> streams,
                           std::span<const uint32_t> vertices, const emu::Executable& vs,
                           const emu::jit::CompiledShader* vs_compiled, const emu::ConstantFile& constants,
                           bool writes_point_size, std::vector<ClipVertex>& shaded) {
    emu::Batch batch;
    for (size_t first = 0; first < vertices.size(); first += emu::kBatchLanes) {
        const size_t n = std::min<size_t>(emu::kBatchLanes, vertices.size() - first);
        batch.reset();
        std::string error = fetch(plan, streams, vertices.subspan(first, n), batch);
        if (!error.empty()) return error;
        if (vs_compiled) vs_compiled->run(constants, batch, nullptr);
        else emu::execute(vs, constants, batch, nullptr);
        for (size_t l = 0; l < n; ++l) shaded[first + l] = vertex_from_batch(batch, static_cast<unsigned>(l), writes_point_size);
    }
    return {};
}

// Clipping and setup of every primitive, in draw order. `slots` maps a draw vertex to its
// shaded vertex (the post-transform cache).
std::vector<PrimitiveSetup> setup_primitives(PrimitiveType type, FillMode fill_mode, std::span<const Primitive> primitives,
                                             std::span<const ClipVertex> shaded, std::span<const uint32_t> slots,
                                             const ClipState& clip, const SetupState& state) {
    std::vector<PrimitiveSetup> setups;
    setups.reserve(primitives.size());
    ClippedPolygon polygon;
    // Solid triangles: each shaded vertex's clip code and, where no plane cuts it, its screen
    // position, worked out once (a vertex serves about six triangles of a mesh).
    const bool solid_triangles = type >= PrimitiveType::TriangleList && fill_mode == FillMode::Solid;
    std::vector<uint32_t> codes;
    std::vector<ScreenPosition> screen;
    if (solid_triangles && primitives.size() > 1) {
        codes.resize(shaded.size());
        screen.resize(shaded.size());
        for (size_t v = 0; v < shaded.size(); ++v) {
            codes[v] = vertex_clip_code(shaded[v], clip);
            if (codes[v] == 0) screen[v] = to_screen(shaded[v].position, state.viewport);
        }
    }
    for (const Primitive& p : primitives) {
        const ClipVertex& v0 = shaded[slots[p.v[0]]];
        const ClipVertex& provoking = shaded[slots[p.provoking]];
        PrimitiveSetup s;
        if (type == PrimitiveType::PointList) {
            if (point_visible(v0, clip) && setup_point(v0, state, s)) setups.push_back(s);
            continue;
        }
        const ClipVertex& v1 = shaded[slots[p.v[1]]];
        if (type == PrimitiveType::LineList || type == PrimitiveType::LineStrip) {
            std::array<ClipVertex, 2> ends;
            if (clip_line(v0, v1, clip, ends) != ClipResult::Outside && setup_line(ends[0], ends[1], provoking, state, s))
                setups.push_back(s);
            continue;
        }
        const ClipVertex& v2 = shaded[slots[p.v[2]]];
        if (!codes.empty()) {
            const uint32_t i0 = slots[p.v[0]], i1 = slots[p.v[1]], i2 = slots[p.v[2]];
            if ((codes[i0] | codes[i1] | codes[i2]) == 0) {  // clip_triangle()'s Inside
                setups.emplace_back();
                if (!setup_triangle(v0, v1, v2, {screen[i0], screen[i1], screen[i2]}, provoking, state, setups.back()))
                    setups.pop_back();
                continue;
            }
        }
        const ClipResult result = clip_triangle(v0, v1, v2, clip, polygon);
        if (result == ClipResult::Outside) continue;
        if (fill_mode != FillMode::Solid) {
            const std::array<ClipVertex, 3> triangle{v0, v1, v2};
            const std::span<const ClipVertex> vertices =
                result == ClipResult::Inside ? std::span<const ClipVertex>(triangle)
                                             : std::span<const ClipVertex>(polygon.vertices.data(), polygon.count);
            (void)setup_fill_mode(vertices, provoking, fill_mode, state, setups);
            continue;
        }
        if (result == ClipResult::Inside) {
            if (setup_triangle(v0, v1, v2, provoking, state, s)) setups.push_back(s);
            continue;
        }
        for (unsigned i = 1; i + 1 < polygon.count; ++i)
            if (setup_triangle(polygon.vertices[0], polygon.vertices[i], polygon.vertices[i + 1], provoking, state, s))
                setups.push_back(s);
    }
    return setups;
}

// Set-up primitives by kTileSize tile, in draw order inside each tile.
struct TileBins {
    int32_t tiles_x = 0;
    std::vector<std::vector<uint32_t>> primitives;  // per tile, row-major
    std::vector<size_t> busy;                       // tiles with at least one primitive
};

TileBins bin_by_tile(std::span<const PrimitiveSetup> setups, uint32_t width, uint32_t height) {
    TileBins bins;
    bins.tiles_x = static_cast<int32_t>((width + kTileSize - 1) / kTileSize);
    const int32_t tiles_y = static_cast<int32_t>((height + kTileSize - 1) / kTileSize);
    bins.primitives.resize(static_cast<size_t>(bins.tiles_x) * static_cast<size_t>(tiles_y));
    for (uint32_t i = 0; i < setups.size(); ++i) {
        const PixelRect& b = setups[i].bounds;
        if (b.empty()) continue;
        const int32_t tx0 = std::max(0, b.left / kTileSize), tx1 = std::min(bins.tiles_x - 1, (b.right - 1) / kTileSize);
        const int32_t ty0 = std::max(0, b.top / kTileSize), ty1 = std::min(tiles_y - 1, (b.bottom - 1) / kTileSize);
        for (int32_t ty = ty0; ty <= ty1; ++ty)
            for (int32_t tx = tx0; tx <= tx1; ++tx)
                bins.primitives[static_cast<size_t>(ty) * static_cast<size_t>(bins.tiles_x) + static_cast<size_t>(tx)].push_back(i);
    }
    for (size_t t = 0; t < bins.primitives.size(); ++t)
        if (!bins.primitives[t].empty()) bins.busy.push_back(t);
    return bins;
}

// Tiles are independent (disjoint pixels and bytes): workers take whole tiles from a shared
// counter, and any number of threads gives the same bytes. Adds the pixel counts to `stats`.
void run_tiles(const PixelPipeline& pipe, std::span<const PrimitiveSetup> setups, const TileBins& bins,
               const TextureSampler& sampler, WorkerPool& pool, DrawStatistics& stats) {
    const unsigned thread_count =
        static_cast<unsigned>(std::clamp<size_t>(pool.size(), 1, std::max<size_t>(bins.busy.size(), 1)));
    std::vector<TileWorker> workers(thread_count);
    for (auto& w : workers) w.sampler = sampler;
    std::atomic<size_t> next{0};
    pool.run(thread_count, [&](unsigned index) {
        TileWorker& w = workers[index];
        for (size_t k = next.fetch_add(1); k < bins.busy.size(); k = next.fetch_add(1)) {
            const size_t t = bins.busy[k];
            const auto tx = static_cast<int32_t>(t % static_cast<size_t>(bins.tiles_x));
            const auto ty = static_cast<int32_t>(t / static_cast<size_t>(bins.tiles_x));
            process_tile(pipe, setups, bins.primitives[t], tile_rect(tx, ty), w);
        }
    });
    for (const auto& w : workers) {
        stats.pixels_shaded += w.pixels_shaded;
        stats.pixels_rasterized += w.pixels_rasterized;
        stats.pixels_killed += w.pixels_killed;
        stats.pixels_written += w.pixels_written;
        stats.pixels_outside_texture += w.pixels_outside_texture;
    }
}

// The engine's shader for a generated fixed-function program, from `cache` when a draw already
// generated the same program. Null, with `error`, when the program fails validation (a generator
// bug, reported rather than run). Internal programs may pass vs_2_0/ps_2_0's slot counts.
std::shared_ptr<Device::ShaderObject> fixed_function_shader(
    std::map<std::string, std::shared_ptr<Device::ShaderObject>>& cache, FixedFunctionProgram& generated,
    std::string& error) {
    if (auto it = cache.find(generated.key); it != cache.end()) return it->second;
    isa::ValidationOptions validation;
    validation.max_instruction_slots = 512;
    const auto violations = isa::validate(*generated.program, validation);
    if (!violations.empty()) {
        error = "generated fixed-function program: " + violations.front().message;
        return nullptr;
    }
    auto object = std::make_shared<Device::ShaderObject>();
    if (generated.program->version.is_vertex()) object->inputs = shader_inputs(*generated.program);
    auto created = emu::Shader::create(std::move(*generated.program));
    if (!created.shader) {
        error = "generated fixed-function program: " + created.error;
        return nullptr;
    }
    object->shader.emplace(std::move(*created.shader));
    return cache.emplace(generated.key, std::move(object)).first->second;
}

std::optional<isa::TextureType> isa_texture_type(TextureType type) {
    switch (type) {
    case TextureType::Texture2D: return isa::TextureType::Texture2D;
    case TextureType::Cube: return isa::TextureType::Cube;
    case TextureType::Volume: return isa::TextureType::Volume;
    }
    return std::nullopt;
}

// The draw's second pass over the watched pixel (run_draw, only while a watch is set): the pixel
// gets back its value from before the draw, then each primitive covering it runs again through
// rasterize and shade_quads restricted to that pixel, in draw order, recording each stage.
void record_pixel_history(PixelWatch& watch, const PixelPipeline& pipe, PrimitiveType type, FillMode fill_mode,
                          std::span<const Primitive> primitives, std::span<const ClipVertex> shaded,
                          std::span<const uint32_t> slots, const ClipState& clip, const SetupState& setup_state,
                          const SetupState& unscissored_state, bool scissor_test, const TextureSampler& sampler,
                          const PixelBytes& before, bool shader_depth, const DebugShader* debug) {
    PixelDraw& draw = watch.draws.back();
    const uint32_t x = watch.x, y = watch.y;
    const PixelValues drawn = read_pixel(pipe.targets, x, y);
    restore_pixel(pipe.targets, x, y, before);
    const PixelRect pixel{static_cast<int32_t>(x), static_cast<int32_t>(y), static_cast<int32_t>(x) + 1, static_cast<int32_t>(y) + 1};
    TileWorker w;
    w.sampler = sampler;
    std::vector<Quad> quads;  // the watched pixel's quad, if a primitive covers it
    for (uint32_t p = 0; p < primitives.size(); ++p) {
        const auto setups = setup_primitives(type, fill_mode, primitives.subspan(p, 1), shaded, slots, clip, setup_state);
        bool covered = false;
        for (const PrimitiveSetup& prim : setups) {
            quads.clear();
            rasterize(prim, pixel, quads);
            if (quads.empty()) continue;
            covered = true;
            PixelFragment f;
            f.primitive = p;
            const PixelValues start = read_pixel(pipe.targets, x, y);
            f.color_before = start.color;
            f.depth_before = start.depth;
            f.stencil_before = start.stencil;
            PixelRecorder recorder{x, y, &w, &f, pipe.ps, debug != nullptr, nullptr};
            shade_quads(pipe, prim, std::span<const Quad>(quads), w, recorder);
            if (debug && recorder.shader_input && recorder.lane() >= 0) {
                // The same quad again, from the same inputs, one source instruction at a time.
                auto trace = trace_shader(*debug, *recorder.shader_input, &w.sampler);
                trace->lanes = emu::kQuadLanes;
                trace->watched_lane = static_cast<unsigned>(recorder.lane());
                // The pass ran on one pixel: the quad's other lanes are covered if the primitive
                // covers them in the draw.
                const Quad& quad = quads.front();
                std::vector<Quad> whole_quad;
                rasterize(prim, PixelRect{quad.x, quad.y, quad.x + 2, quad.y + 2}, whole_quad);
                trace->covered = whole_quad.empty() ? w.lanes.coverage & 0xFu : whole_quad.front().mask;
                f.shader_debug = std::move(trace);
            }
            if (shader_depth && f.shaded) f.depth = w.batch.registers[emu::slot::kDepth][0][static_cast<size_t>(recorder.lane())];
            // The late tests, in merge's order: alpha, then depth/stencil (both decided by what
            // merge wrote: a pixel past the alpha test that wrote nothing failed depth/stencil).
            if (f.shaded && !f.killed) {
                if (pipe.merger.alpha_test) {
                    const bool clamps = !pipe.targets.color[0] || !is_float_target(pipe.targets.color[0]->format());
                    f.alpha_test_passed = alpha_test_passes(pipe.merger, f.shader_color[0][3], clamps);
                }
                if (!f.early_depth_stencil && pipe.merger.depth_stencil.active() && f.alpha_test_passed.value_or(true))
                    f.depth_stencil_passed = f.written;
            }
            const PixelValues end = read_pixel(pipe.targets, x, y);
            f.color_after = end.color;
            f.depth_after = end.depth;
            f.stencil_after = end.stencil;
            draw.fragments.push_back(f);
        }
        if (!covered && scissor_test) {
            // Outside the scissor rectangle: does the primitive cover the pixel without it?
            for (const PrimitiveSetup& prim :
                 setup_primitives(type, fill_mode, primitives.subspan(p, 1), shaded, slots, clip, unscissored_state)) {
                quads.clear();
                rasterize(prim, pixel, quads);
                if (quads.empty()) continue;
                PixelFragment f;
                f.primitive = p;
                f.scissored = true;
                const PixelValues now = read_pixel(pipe.targets, x, y);
                f.color_before = f.color_after = now.color;
                f.depth_before = f.depth_after = now.depth;
                f.stencil_before = f.stencil_after = now.stencil;
                draw.fragments.push_back(f);
                break;
            }
        }
    }
    const PixelValues recorded = read_pixel(pipe.targets, x, y);
    draw.consistent = recorded.color == drawn.color && recorded.depth == drawn.depth && recorded.stencil == drawn.stencil;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

CallResult Device::run_draw(PrimitiveType type, uint32_t primitive_count, std::vector<uint32_t> draw_vertices,
                            std::span<const VertexStream> streams) {
    if (!in_scene_) return CallResult::fail("draw outside BeginScene/EndScene");
    if (!declaration_) return CallResult::fail("no vertex declaration is set");
    if (options_.precision.precision == emu::Precision::Fp64)
        return CallResult::fail("the fp64 reference precision is for single shaders (sm2 run), not draws");

    // Render targets: all bound ones must have target 0's size; the depth buffer must cover it.
    Surface* rt0 = render_target_surface(0);
    if (!rt0) return CallResult::fail("no render target 0");
    RenderTargets targets;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i) {
        targets.color[i] = render_target_surface(i);
        if (targets.color[i] && (targets.color[i]->width() != rt0->width() || targets.color[i]->height() != rt0->height()))
            return CallResult::fail("render target " + std::to_string(i) + " is not the size of render target 0");
    }
    const bool depth_in_use = render_state_.z_enable != ZBufferType::False || render_state_.stencil_enable;
    if (depth_stencil_ && depth_in_use) {
        DepthStencilSurface& ds = *depth_stencil_->depth;
        if (ds.width() < rt0->width() || ds.height() < rt0->height())
            return CallResult::fail("the depth-stencil surface is smaller than render target 0");
        targets.depth_stencil = &ds;
    }

    const auto assembled = assemble(type, primitive_count, static_cast<uint32_t>(draw_vertices.size()));
    if (!assembled.ok()) return CallResult::fail(assembled.error);

    auto clock = std::chrono::steady_clock::now();
    // Pipeline: the pixel shader first, since what it reads decides what the vertex shader
    // must compute.
    // Without a shader, the fixed-function program generated from the state (its constants
    // filled for this draw) stands in for it.
    std::string error;
    std::shared_ptr<ShaderObject> ff_vs, ff_ps;
    std::vector<std::array<float, 4>> ff_vs_constants, ff_ps_constants;
    bool ff_w_fog = false;  // the fixed-function vertex program passes the eye depth for W-fog
    if (!vertex_shader_) {
        const auto state = [&](uint32_t id, uint32_t fallback) {
            const auto it = other_render_states_.find(id);
            return it != other_render_states_.end() ? it->second : fallback;
        };
        VertexProcessingStates states;
        states.lighting = state(137, 1) != 0;  // D3DRS_LIGHTING
        states.ambient = state(139, 0);
        states.color_vertex = state(141, 1) != 0;
        states.local_viewer = state(142, 1) != 0;
        states.normalize_normals = state(143, 0) != 0;
        states.diffuse_source = state(145, 1);
        states.specular_source = state(146, 2);
        states.ambient_source = state(147, 0);
        states.emissive_source = state(148, 0);
        states.vertex_blend = state(151, 0);
        states.indexed_vertex_blend = state(167, 0) != 0;
        states.tween_factor = std::bit_cast<float>(state(170, 0));  // D3DRS_TWEENFACTOR
        auto generated = fixed_function_vertex_program(fixed_function_, render_state_, states, viewport_,
                                                       declaration_->elements);
        if (!generated.program) return CallResult::fail(generated.error);
        ff_vs = fixed_function_shader(fixed_function_programs_, generated, error);
        if (!ff_vs) return CallResult::fail(error);
        ff_vs_constants = std::move(generated.constants);
        ff_w_fog = generated.w_fog;
        ff_vs_constants.resize(kMaxVertexShaderConstantsF, {0.0f, 0.0f, 0.0f, 0.0f});
    }
    if (!pixel_shader_) {
        std::array<std::optional<isa::TextureType>, kMaxTextureStages> stage_textures{};
        for (unsigned s = 0; s < kMaxTextureStages; ++s)
            if (textures_[s] && textures_[s]->kind == Resource::Kind::Texture)
                stage_textures[s] = isa_texture_type(textures_[s]->texture.type());
        auto generated = fixed_function_pixel_program(fixed_function_, render_state_, stage_textures);
        if (!generated.program) return CallResult::fail(generated.error);
        ff_ps = fixed_function_shader(fixed_function_programs_, generated, error);
        if (!ff_ps) return CallResult::fail(error);
        ff_ps_constants = std::move(generated.constants);
        ff_ps_constants.resize(kMaxPixelShaderConstantsF, {0.0f, 0.0f, 0.0f, 0.0f});
    }
    ShaderObject& vs_object = vertex_shader_ ? *vertex_shader_->shader : *ff_vs;
    ShaderObject& ps_object = pixel_shader_ ? *pixel_shader_->shader : *ff_ps;
    const emu::StaticFlowConstants no_flow{};
    const emu::StaticFlowConstants& vs_flow = vertex_shader_ ? vs_flow_ : no_flow;
    const emu::StaticFlowConstants& ps_flow = pixel_shader_ ? ps_flow_ : no_flow;
    OutputMergerState merger = output_merger_state(render_state_);
    if (!targets.depth_stencil) merger.depth_stencil.depth_enable = merger.depth_stencil.stencil_enable = false;
    if (targets.depth_stencil && targets.depth_stencil->info().stencil_bits == 0) merger.depth_stencil.stencil_enable = false;
    uint32_t ps_outputs = 0;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i)
        if (targets.color[i] && (merger.write_mask[i] & 0xF)) ps_outputs |= output_bit(slot::kRenderTargetFirst + i);
    ps_outputs |= output_bit(slot::kDepth);
    ShaderObject::Lowered* ps_entry = lowered_for(ps_object, ps_flow, ps_outputs, options_.precision, stats_, error);
    if (!ps_entry) return CallResult::fail("pixel shader: " + error);
    const emu::Executable& ps = ps_entry->executable;
    uint16_t varyings = varyings_read_by(ps);
    merger.table_fog_of_w = ff_w_fog;
    if (merger.fog_enable && (merger.fog_table_mode == FogMode::None || ff_w_fog)) varyings |= 1u << kVaryingFog;
    const bool points = type == PrimitiveType::PointList ||
                        (render_state_.fill_mode == FillMode::Point && type >= PrimitiveType::TriangleList);
    uint32_t vs_outputs = vs_outputs_for(varyings);
    if (points) vs_outputs |= output_bit(slot::kPointSize);
    ShaderObject::Lowered* vs_entry = lowered_for(vs_object, vs_flow, vs_outputs, options_.precision, stats_, error);
    if (!vs_entry) return CallResult::fail("vertex shader: " + error);
    const emu::Executable* vs = &vs_entry->executable;

    // Engine::Jit: the shaders as native code (compiled on first use, shared by every device).
    const bool jit = options_.engine == DeviceOptions::Engine::Jit;
    const emu::jit::CompiledShader* vs_compiled = jit ? compiled_for(*vs_entry, stats_) : nullptr;
    const emu::jit::CompiledShader* ps_compiled = jit ? compiled_for(*ps_entry, stats_) : nullptr;

    stats_.pipeline_seconds += lap(clock);

    // Vertex stage: fetch and shade each distinct vertex once.
    const auto plan = plan_fetch(declaration_->elements, vs_object.inputs);
    if (!plan.plan) return CallResult::fail("vertex declaration: " + plan.error);
    for (unsigned s = 0; s < kMaxVertexStreams; ++s)
        if ((plan.plan->streams_used >> s & 1u) && (s >= streams.size() || streams[s].stride == 0))
            return CallResult::fail("stream " + std::to_string(s) + " is read by the declaration but not set");
    const UniqueVertices unique = deduplicate(draw_vertices);
    const bool writes_point_size = (vs->components_written()[slot::kPointSize] & 1u) != 0;
    std::vector<ClipVertex> shaded(unique.vertices.size());
    const std::string fetch_error =
        shade_vertices(*plan.plan, streams, unique.vertices, *vs, vs_compiled,
                       vs->bind_constants(vertex_shader_ ? vs_f_ : ff_vs_constants),
                       writes_point_size, shaded);
    if (!fetch_error.empty()) return CallResult::fail("vertex fetch: " + fetch_error);
    if (vertex_watch_) {
        // sm2 debug --vertex: the watched vertex fetched again and its shader traced (one test per
        // draw when no watch is set).
        std::shared_ptr<ShaderDebug> trace;
        const auto found = std::find(unique.vertices.begin(), unique.vertices.end(), vertex_watch_->index);
        auto debug = found == unique.vertices.end()
                         ? std::nullopt
                         : debug_shader(vertex_shader_ ? vertex_shader_->shader : ff_vs, !vertex_shader_, vs_flow,
                                        vs_outputs, options_.precision,
                                        vertex_shader_ ? std::span(vs_f_) : std::span(ff_vs_constants));
        if (debug) {
            auto batch = std::make_unique<emu::Batch>();
            if (fetch(*plan.plan, streams, std::span(&*found, 1), *batch).empty()) {
                trace = trace_shader(*debug, *batch, nullptr);
                trace->lanes = 1;
                trace->covered = 1;
            }
        }
        vertex_watch_->draws.push_back(std::move(trace));
    }

    stats_.vertex_seconds += lap(clock);

    // Clipping and setup, in draw order.
    ClipState clip;
    clip.clipping = render_state_.clipping;
    clip.user_plane_enable = render_state_.clip_plane_enable & 0x3Fu;
    clip.user_planes = clip_planes_;
    clip.guard = guard_band(viewport_);
    clip.varying_mask = varyings;
    SetupState setup_state = make_setup_state(render_state_, viewport_, rt0->width(), rt0->height(), scissor_);
    setup_state.varying_mask = varyings;
    setup_state.shader_point_size = writes_point_size;
    const std::vector<PrimitiveSetup> setups =
        setup_primitives(type, render_state_.fill_mode, assembled.primitives, shaded, unique.slots, clip, setup_state);

    // Pixel pipeline for this draw.
    PixelPipeline pipe;
    pipe.ps = &ps;
    pipe.ps_compiled = ps_compiled;
    const emu::ConstantFile ps_constants = ps.bind_constants(pixel_shader_ ? ps_f_ : ff_ps_constants);
    pipe.ps_constants = &ps_constants;
    pipe.ps_varyings = varyings;
    pipe.merger = merger;
    pipe.targets = targets;
    const auto& written = ps.components_written();
    pipe.merge_template.color_outputs = 0;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i)
        if (written[slot::kRenderTargetFirst + i]) pipe.merge_template.color_outputs |= static_cast<uint8_t>(1u << i);
    pipe.merge_template.shader_depth = written[slot::kDepth] != 0;
    pipe.merge_template.generic_path = options_.reference_paths;
    pipe.merge_plan = merge_plan(merger, targets, pipe.merge_template);
    pipe.reference_paths = options_.reference_paths;
    const bool kills = ps_object.texkill;
    pipe.early_depth_stencil = merger.depth_stencil.active() && !pipe.merge_template.shader_depth && !kills &&
                               !merger.alpha_test;
    pipe.interpolated_depth = merger.depth_stencil.active() || merger.fog_enable || pixel_watch_;

    const TileBins bins = bin_by_tile(setups, rt0->width(), rt0->height());

    stats_.setup_seconds += lap(clock);

    // A texture that is also a bound render target (undefined in D3D9) is sampled as it was
    // before the draw: the tiles read a snapshot, so the result does not depend on the order in
    // which threads write it.
    std::vector<Texture> snapshots;
    snapshots.reserve(kMaxSamplers);
    TextureSampler sampler = sampler_;
    for (unsigned stage = 0; stage < kMaxSamplers; ++stage) {
        const auto& bound = textures_[stage];
        if (!bound || std::find(render_targets_.begin(), render_targets_.end(), bound) == render_targets_.end()) continue;
        snapshots.push_back(bound->texture);
        sampler.set_texture(stage, &snapshots.back());
    }
    sampler.prepare();
    // Pixel history records the shader's outputs as they are: its pass samples without the gate.
    std::optional<TextureSampler> history_sampler;
    if (pixel_watch_) history_sampler = sampler;
    if (const std::optional<size_t> texld = alpha_gate_texld(ps, pipe.merge_plan, pipe.merge_template, kills)) {
        sampler.set_alpha_gate(ps.steps()[*texld].sampler, true);
        pipe.outside_cull = outside_cull(ps, *texld, sampler, merger, pipe.early_depth_stencil);
    }
    if (!pool_) pool_ = std::make_unique<WorkerPool>(options_.threads);
    // Pixel history (sm2 pixel): one test per draw; the tiles run as they always do.
    std::optional<PixelBytes> watched_before;
    if (pixel_watch_) {
        PixelDraw draw;
        std::copy(targets.color.begin(), targets.color.end(), draw.targets.begin());
        draw.inside = pixel_watch_->x < rt0->width() && pixel_watch_->y < rt0->height();
        pixel_watch_->draws.push_back(std::move(draw));
        if (pixel_watch_->draws.back().inside) watched_before = save_pixel(targets, pixel_watch_->x, pixel_watch_->y);
    }
    run_tiles(pipe, setups, bins, sampler, *pool_, stats_);
    if (watched_before) {
        RenderState unscissored_rs = render_state_;
        unscissored_rs.scissor_test_enable = false;
        SetupState unscissored = setup_state;
        unscissored.clip_rect = make_setup_state(unscissored_rs, viewport_, rt0->width(), rt0->height(), scissor_).clip_rect;
        const DrawStatistics counted = stats_;  // the second pass is not the draw's work
        std::optional<DebugShader> ps_debug;
        if (pixel_watch_->debug_shaders)
            ps_debug = debug_shader(pixel_shader_ ? pixel_shader_->shader : ff_ps, !pixel_shader_, ps_flow, ps_outputs,
                                    options_.precision, pixel_shader_ ? std::span(ps_f_) : std::span(ff_ps_constants));
        record_pixel_history(*pixel_watch_, pipe, type, render_state_.fill_mode, assembled.primitives, shaded,
                             unique.slots, clip, setup_state, unscissored, render_state_.scissor_test_enable, *history_sampler,
                             *watched_before, pipe.merge_template.shader_depth, ps_debug ? &*ps_debug : nullptr);
        stats_ = counted;
    }

    stats_.pixel_seconds += lap(clock);
    ++stats_.draws;
    stats_.vertices_shaded += unique.vertices.size();
    stats_.primitives += assembled.primitives.size();
    return {};
}

// ---------------------------------------------------------------------------------------------
// The four draw calls: they differ only in where the vertex numbers and streams come from.

namespace {

std::string draw_error(const char* call, const CallResult& result) { return std::string(call) + ": " + result.error; }

// A draw's primitive type and the number of draw vertices its PrimitiveCount reads; nullopt for
// a type that is not a D3DPRIMITIVETYPE or a count whose vertices overflow.
struct DrawShape {
    PrimitiveType type;
    uint32_t vertex_count;
};
std::optional<DrawShape> draw_shape(uint32_t type, uint32_t primitive_count) {
    const auto pt = primitive_type_from(type);
    const auto count = pt ? vertices_for(*pt, primitive_count) : std::nullopt;
    if (!count) return std::nullopt;
    return DrawShape{*pt, *count};
}

// The streams of a DrawPrimitiveUP / DrawIndexedPrimitiveUP: the user's vertices as stream 0.
std::vector<VertexStream> user_pointer_streams(std::span<const std::byte> vertices, uint32_t stride) {
    std::vector<VertexStream> streams(kMaxVertexStreams);
    streams[0] = VertexStream{vertices, 0, stride};
    return streams;
}

}  // namespace

std::vector<VertexStream> Device::bound_streams() const {
    std::vector<VertexStream> streams(kMaxVertexStreams);
    for (unsigned s = 0; s < kMaxVertexStreams; ++s)
        if (streams_[s].buffer) streams[s] = VertexStream{streams_[s].buffer->bytes, streams_[s].offset, streams_[s].stride};
    return streams;
}

CallResult Device::draw_primitive(uint32_t type, uint32_t start_vertex, uint32_t primitive_count) {
    const auto shape = draw_shape(type, primitive_count);
    if (!shape) return CallResult::fail("DrawPrimitive: bad primitive type or count");
    auto ids = sequential_vertices(start_vertex, shape->vertex_count);
    if (!ids.ok()) return CallResult::fail("DrawPrimitive: " + ids.error);
    auto result = run_draw(shape->type, primitive_count, std::move(ids.vertices), bound_streams());
    return result ? result : CallResult::fail(draw_error("DrawPrimitive", result));
}

CallResult Device::draw_indexed_primitive(uint32_t type, int32_t base_vertex, uint32_t /*min_index: a hint*/,
                                          uint32_t num_vertices, uint32_t start_index, uint32_t primitive_count) {
    const auto shape = draw_shape(type, primitive_count);
    if (!shape) return CallResult::fail("DrawIndexedPrimitive: bad primitive type or count");
    if (num_vertices == 0) return CallResult::fail("DrawIndexedPrimitive: NumVertices is 0");
    if (!indices_) return CallResult::fail("DrawIndexedPrimitive: no index buffer is set");
    auto ids = read_indices(indices_->bytes, indices_->index_format, start_index, shape->vertex_count, base_vertex);
    if (!ids.ok()) return CallResult::fail("DrawIndexedPrimitive: " + ids.error);
    auto result = run_draw(shape->type, primitive_count, std::move(ids.vertices), bound_streams());
    return result ? result : CallResult::fail(draw_error("DrawIndexedPrimitive", result));
}

CallResult Device::draw_primitive_up(uint32_t type, uint32_t primitive_count, std::span<const std::byte> vertices,
                                     uint32_t stride) {
    const auto shape = draw_shape(type, primitive_count);
    if (!shape) return CallResult::fail("DrawPrimitiveUP: bad primitive type or count");
    if (stride == 0) return CallResult::fail("DrawPrimitiveUP: stride 0");
    auto ids = sequential_vertices(0, shape->vertex_count);
    if (!ids.ok()) return CallResult::fail("DrawPrimitiveUP: " + ids.error);
    auto result = run_draw(shape->type, primitive_count, std::move(ids.vertices), user_pointer_streams(vertices, stride));
    if (!result) return CallResult::fail(draw_error("DrawPrimitiveUP", result));
    // D3D9: after a UP draw, stream 0 is unset.
    streams_[0] = StreamBinding{};
    return {};
}

CallResult Device::draw_indexed_primitive_up(uint32_t type, uint32_t /*min_index*/, uint32_t num_vertices,
                                             uint32_t primitive_count, std::span<const std::byte> indices,
                                             Format index_format, std::span<const std::byte> vertices,
                                             uint32_t stride) {
    const auto shape = draw_shape(type, primitive_count);
    if (!shape) return CallResult::fail("DrawIndexedPrimitiveUP: bad primitive type or count");
    if (stride == 0) return CallResult::fail("DrawIndexedPrimitiveUP: stride 0");
    if (num_vertices == 0) return CallResult::fail("DrawIndexedPrimitiveUP: NumVertices is 0");
    if (index_format != Format::INDEX16 && index_format != Format::INDEX32)
        return CallResult::fail("DrawIndexedPrimitiveUP: the index format is not INDEX16 or INDEX32");
    auto ids = read_indices(indices, index_format == Format::INDEX16 ? IndexFormat::Index16 : IndexFormat::Index32, 0,
                            shape->vertex_count, 0);
    if (!ids.ok()) return CallResult::fail("DrawIndexedPrimitiveUP: " + ids.error);
    auto result = run_draw(shape->type, primitive_count, std::move(ids.vertices), user_pointer_streams(vertices, stride));
    if (!result) return CallResult::fail(draw_error("DrawIndexedPrimitiveUP", result));
    // D3D9: after a UP draw, stream 0 and the index buffer are unset.
    streams_[0] = StreamBinding{};
    indices_ = nullptr;
    return {};
}

}  // namespace sm2::runtime
