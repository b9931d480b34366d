// Texels sampled per second through the engine's sampler interface (4 quads = 16 lookups per
// call) for point, bilinear, trilinear and 16x anisotropic filtering on A8R8G8B8, DXT1,
// A16B16G16R16F and A16B16G16R16 256x256 textures with full mip chains, DXT1 through the
// per-lane path too, and bilinear WRAP on a 320x240 texture by both paths.
// Run: build/bench/texture_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>

#include "sm2/runtime/sampler.h"
#include "sm2/runtime/texture.h"

namespace {

using namespace sm2::runtime;

Texture make_texture(Format format) {
    Texture t = Texture::create_2d(format, 256, 256);
    uint32_t seed = 7;
    for (uint32_t l = 0; l < t.levels(); ++l) {
        Surface& s = t.surface(l);
        if (format == Format::DXT1) {
            for (auto& b : s.bytes()) {
                seed = seed * 1664525u + 1013904223u;
                b = static_cast<std::byte>(seed >> 24);
            }
            continue;
        }
        for (uint32_t y = 0; y < s.height(); ++y)
            for (uint32_t x = 0; x < s.width(); ++x) {
                seed = seed * 1664525u + 1013904223u;
                const float v = static_cast<float>(seed >> 8 & 255) / 255.0f;
                s.write(x, y, 0, {v, 1 - v, 0.5f * v, 1});
            }
    }
    return t;
}

// Times stage 0 of `sampler` on batches of 4 quads side by side that move across the texture,
// (du, dv) apart from pixel to pixel in normalized coordinates.
void time_lookups(benchmark::State& state, TextureSampler& sampler, float du, float dv) {
    std::array<sm2::emu::FloatLanes, 4> coords{}, out{};
    sm2::emu::TextureRequest request;
    request.coordinates = &coords;
    float base = 0;
    for (auto _ : state) {
        for (unsigned q = 0; q < sm2::emu::kBatchQuads; ++q)
            for (unsigned i = 0; i < 4; ++i) {
                const float px = static_cast<float>(2 * q + (i & 1)), py = static_cast<float>(i >> 1);
                coords[0][4 * q + i] = base + px * du;
                coords[1][4 * q + i] = 0.3f * base + py * dv;
            }
        sampler.sample(request, out);
        benchmark::DoNotOptimize(out);
        base += 0.0123f;
        if (base > 4) base -= 4;
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * sm2::emu::kBatchLanes);
    state.counters["texels/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * sm2::emu::kBatchLanes,
                                                     benchmark::Counter::kIsRate);
}

enum Mode { kPoint, kBilinear, kTrilinear, kAniso16 };

// per_lane: the sampler's per-lane path (the reference) instead of its 16-lane block path.
void BM_Sample(benchmark::State& state, Format format, Mode mode, bool per_lane = false) {
    const Texture texture = make_texture(format);
    TextureSampler sampler;
    sampler.set_texture(0, &texture);
    if (per_lane) sampler.set_block_path(false);
    SamplerState st;
    // pixel steps in texels along x and y
    float step_x = 0.75f, step_y = 0.75f;
    switch (mode) {
    case kPoint: break;
    case kBilinear: st.mag_filter = st.min_filter = TextureFilter::Linear; break;
    case kTrilinear:
        st.mag_filter = st.min_filter = st.mip_filter = TextureFilter::Linear;
        step_x = step_y = 2.5f;
        break;
    case kAniso16:
        st.mag_filter = TextureFilter::Linear;
        st.min_filter = TextureFilter::Anisotropic;
        st.mip_filter = TextureFilter::Linear;
        st.max_anisotropy = 16;
        step_x = 16.0f;
        step_y = 1.0f;
        break;
    }
    sampler.set_state(0, st);
    time_lookups(state, sampler, step_x / 256.0f, step_y / 256.0f);
}

// Bilinear WRAP on a 320x240 A8R8G8B8 texture (one level: a size that is not a power of two, as a
// render target sampled by a post-processing pass): WRAP by the remainder in the block path,
// against the per-lane path, which every such lookup took before.
void BM_SampleWrapNotPow2(benchmark::State& state, bool per_lane) {
    Texture texture = Texture::create_2d(Format::A8R8G8B8, 320, 240, 1);
    uint32_t seed = 7;
    for (auto& b : texture.surface(0).bytes()) {
        seed = seed * 1664525u + 1013904223u;
        b = static_cast<std::byte>(seed >> 24);
    }
    TextureSampler sampler;
    sampler.set_texture(0, &texture);
    if (per_lane) sampler.set_block_path(false);
    SamplerState st;
    st.mag_filter = st.min_filter = TextureFilter::Linear;
    sampler.set_state(0, st);
    time_lookups(state, sampler, 0.75f / 320.0f, 0.75f / 240.0f);
}
BENCHMARK_CAPTURE(BM_SampleWrapNotPow2, A8R8G8B8_bilinear_wrap_320x240, false);
BENCHMARK_CAPTURE(BM_SampleWrapNotPow2, A8R8G8B8_bilinear_wrap_320x240_per_lane, true);

#define SM2_TEXTURE_BENCH(fmt)                                                                     \
    BENCHMARK_CAPTURE(BM_Sample, fmt##_point, Format::fmt, kPoint);                                \
    BENCHMARK_CAPTURE(BM_Sample, fmt##_bilinear, Format::fmt, kBilinear);                          \
    BENCHMARK_CAPTURE(BM_Sample, fmt##_trilinear, Format::fmt, kTrilinear);                        \
    BENCHMARK_CAPTURE(BM_Sample, fmt##_aniso16, Format::fmt, kAniso16)

SM2_TEXTURE_BENCH(A8R8G8B8);
SM2_TEXTURE_BENCH(DXT1);
// DXT1 through the per-lane path, which every DXTn lookup took before the block path read the
// decoded texels (Texture::decoded_dxt()): the same bits, this run's ratio.
BENCHMARK_CAPTURE(BM_Sample, DXT1_bilinear_per_lane, Format::DXT1, kBilinear, true);
BENCHMARK_CAPTURE(BM_Sample, DXT1_trilinear_per_lane, Format::DXT1, kTrilinear, true);
SM2_TEXTURE_BENCH(A16B16G16R16F);
// 16-bit UNORM channels in 8-byte texels (scene 20's blur reads them): each tap decoded by its
// quotient, no exact integer sum.
SM2_TEXTURE_BENCH(A16B16G16R16);

}  // namespace

BENCHMARK_MAIN();
