// Whole-draw throughput through the Device: vertex fetch and shading, clipping, setup,
// rasterization, pixel shading and the output merger. Reported (frames, pixels and vertices per
// second), never asserted. Each mode that changes results also reports its error against the
// reference frame (fp32, exact transcendentals, exact filter weights) of the same scene:
// max_err and mean_err in 8-bit steps over all channels of the 512x512 A8R8G8B8 target.
//   build/release/bench/pipeline_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/runtime/device.h"

namespace {

using namespace sm2;
using namespace sm2::runtime;

constexpr uint32_t kSize = 512;
constexpr unsigned kGrid = 64;  // 64 x 64 quads, 8192 triangles, over the whole target

isa::Program program(const char* text) {
    auto r = assembler::assemble(text);
    if (!r.ok()) throw std::runtime_error("benchmark shader does not assemble");
    return *r.program;
}

const char* kVertexShader = R"(vs_2_0
dcl_position v0
dcl_texcoord v1
mov oPos, v0
mov oT0, v1
mov oT1, v0
)";

// Gouraud-like: colour from the coordinates.
const char* kFlatPixelShader = R"(ps_2_0
dcl t0
mov oC0, t0
)";

// Textured per-pixel lighting: texld, nrm, dp3, pow; colour arithmetic marked _pp (half
// precision allowed), as a compiler writes it for half-typed HLSL.
const char* kTexturedPhongPixelShader = R"(ps_2_0
def c0, 0.3, 0.5, 0.8, 16
def c1, 0.2, 0.2, 0.2, 1
dcl t0.xy
dcl t1.xyz
dcl_2d s0
texld r0, t0, s0
nrm_pp r1.xyz, t1
dp3_sat r2.x, r1, c0
pow r2.y, r2.x, c0.w
mad_pp r3, r0, r2.x, c1
add_pp r3.xyz, r3, r2.y
mov oC0, r3
)";

struct Scene {
    std::unique_ptr<Device> device;
    std::vector<float> vertices;
    std::vector<uint16_t> indices;
};

// A numeric mode of the whole pipeline.
struct Mode {
    emu::PrecisionOptions precision{};
    FilterPrecision filter = FilterPrecision::Fixed8;
};
constexpr Mode kReference{{emu::Precision::Fp32, emu::Transcendentals::Exact, false}, FilterPrecision::Exact};
constexpr Mode kDefault{};
constexpr Mode kFast{{emu::Precision::Fp32, emu::Transcendentals::Fast, false}, FilterPrecision::Fixed8};
constexpr Mode kFp24{{emu::Precision::Fp24, emu::Transcendentals::Exact, false}, FilterPrecision::Fixed8};
constexpr Mode kFp16pp{{emu::Precision::Fp24, emu::Transcendentals::Exact, true}, FilterPrecision::Fixed8};

Scene make_scene(unsigned threads, const Mode& mode, const char* pixel_shader) {
    DeviceOptions options;
    options.threads = threads;
    options.precision = mode.precision;
    options.filter_precision = mode.filter;
    Scene s;
    s.device = std::make_unique<Device>(options);
    Device& d = *s.device;
    auto check = [](const CallResult& r) {
        if (!r) throw std::runtime_error(r.error);
    };
    check(d.create_device(kSize, kSize, Format::A8R8G8B8, Format::D24S8));
    check(d.create_vertex_declaration("decl", {VertexElement{0, 0, static_cast<uint8_t>(DeclType::FLOAT4), 0, 0, 0},
                                               VertexElement{0, 16, static_cast<uint8_t>(DeclType::FLOAT2), 0, 5, 0}}));
    check(d.create_vertex_shader("vs", program(kVertexShader)));
    check(d.create_pixel_shader("ps", program(pixel_shader)));
    check(d.create_texture("tex", 256, 256, 0, Format::A8R8G8B8));
    for (uint32_t level = 0; (256u >> level) >= 1; ++level) {
        const uint32_t edge = 256u >> level;
        std::vector<uint32_t> texels(edge * edge);
        for (uint32_t y = 0; y < edge; ++y)
            for (uint32_t x = 0; x < edge; ++x) texels[y * edge + x] = ((x / 8 + y / 8) & 1) ? 0xFFFFFFFFu : 0xFF404040u;
        check(d.lock_rect("tex", 0, level, std::as_bytes(std::span(texels))));
        if (edge == 1) break;
    }
    check(d.set_texture(0, "tex"));
    check(d.set_sampler_state(0, 5, 2));  // MAGFILTER LINEAR
    check(d.set_sampler_state(0, 6, 2));  // MINFILTER LINEAR
    check(d.set_sampler_state(0, 7, 2));  // MIPFILTER LINEAR
    check(d.set_vertex_declaration("decl"));
    check(d.set_vertex_shader("vs"));
    check(d.set_pixel_shader("ps"));
    for (unsigned y = 0; y <= kGrid; ++y)
        for (unsigned x = 0; x <= kGrid; ++x) {
            const float u = static_cast<float>(x) / kGrid, v = static_cast<float>(y) / kGrid;
            s.vertices.insert(s.vertices.end(), {2 * u - 1, 1 - 2 * v, 0.5f, 1.0f, 4 * u, 4 * v});
        }
    for (unsigned y = 0; y < kGrid; ++y)
        for (unsigned x = 0; x < kGrid; ++x) {
            const auto i = static_cast<uint16_t>(y * (kGrid + 1) + x);
            const auto below = static_cast<uint16_t>(i + kGrid + 1);
            s.indices.insert(s.indices.end(), {i, static_cast<uint16_t>(i + 1), below, static_cast<uint16_t>(i + 1),
                                               static_cast<uint16_t>(below + 1), below});
        }
    return s;
}

CallResult draw_frame(Scene& s) {
    Device& d = *s.device;
    const auto vertex_bytes = std::as_bytes(std::span(s.vertices));
    const auto index_bytes = std::as_bytes(std::span(s.indices));
    const uint32_t triangles = static_cast<uint32_t>(s.indices.size() / 3);
    (void)d.clear(kClearTarget | kClearZBuffer | kClearStencil, 0xFF000000u, 1.0f, 0);
    (void)d.begin_scene();
    const CallResult r = d.draw_indexed_primitive_up(4, 0, static_cast<uint32_t>(s.vertices.size() / 6), triangles,
                                                     index_bytes, Format::INDEX16, vertex_bytes, 6 * sizeof(float));
    (void)d.end_scene();
    return r;
}

void BM_Frame(benchmark::State& state, const char* pixel_shader, Mode mode) {
    const auto threads = static_cast<unsigned>(state.range(0));
    Scene s = make_scene(threads, mode, pixel_shader);
    Device& d = *s.device;
    for (auto _ : state) {
        const CallResult r = draw_frame(s);
        if (!r) {
            state.SkipWithError(r.error.c_str());
            return;
        }
    }
    // Error against the reference frame, in 8-bit steps.
    Scene reference = make_scene(1, kReference, pixel_shader);
    (void)draw_frame(reference);
    const auto& a = d.surface("backbuffer")->bytes();
    const auto& b = reference.device->surface("backbuffer")->bytes();
    int max_error = 0;
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const int e = std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
        max_error = std::max(max_error, e);
        sum += e;
    }
    state.counters["max_err"] = max_error;
    state.counters["mean_err"] = sum / static_cast<double>(a.size());
    const auto& stats = d.statistics();
    state.counters["frames/s"] = benchmark::Counter(static_cast<double>(stats.draws), benchmark::Counter::kIsRate);
    state.counters["pixels/s"] = benchmark::Counter(static_cast<double>(stats.pixels_shaded), benchmark::Counter::kIsRate);
    state.counters["vertices/s"] =
        benchmark::Counter(static_cast<double>(stats.vertices_shaded), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Frame, flat_default, kFlatPixelShader, kDefault)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_Frame, phong_reference, kTexturedPhongPixelShader, kReference)->Arg(1)->UseRealTime();
BENCHMARK_CAPTURE(BM_Frame, phong_default, kTexturedPhongPixelShader, kDefault)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_Frame, phong_fast_transcendentals, kTexturedPhongPixelShader, kFast)->Arg(1)->UseRealTime();
BENCHMARK_CAPTURE(BM_Frame, phong_fp24, kTexturedPhongPixelShader, kFp24)->Arg(1)->UseRealTime();
BENCHMARK_CAPTURE(BM_Frame, phong_fp24_pp_fp16, kTexturedPhongPixelShader, kFp16pp)->Arg(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
