// The sampler: address modes, filters, LOD, cube maps, volumes, sRGB, special coordinates.
// Every expected value is computed by hand from pipeline.md §14 and docs/texturing.md; the
// arithmetic is in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sm2/runtime/sampler.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {
namespace {

using A = TextureAddress;
using Fl = TextureFilter;

Texture r32f(uint32_t w, uint32_t h, const std::vector<float>& values) {
    Texture t = Texture::create_2d(Format::R32F, w, h, 1);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) t.surface(0).write(x, y, 0, {values[y * w + x], 0, 0, 0});
    return t;
}

struct Fixture {
    TextureSampler sampler;
    SamplerState state;
    explicit Fixture(const Texture& t) { sampler.set_texture(0, &t); }
    Float4 at(float u, float v = 0.5f, float w = 0.0f) {
        sampler.set_state(0, state);
        return sampler.sample_gradient(0, {u, v, w}, {0, 0, 0}, {0, 0, 0});
    }
    Float4 grad(std::array<float, 3> p, std::array<float, 3> dx, std::array<float, 3> dy, float bias = 0) {
        sampler.set_state(0, state);
        return sampler.sample_gradient(0, p, dx, dy, bias);
    }
};

// 4x1 texture 10 20 30 40. POINT: texel floor(u * 4) (texel-space x = u*4 - 0.5, nearest =
// floor(x + 0.5)); exactly on an edge the texel to the right is taken.
TEST(SamplerAddress, PointEveryModeIncludingFarOutside) {
    const Texture t = r32f(4, 1, {10, 20, 30, 40});
    Fixture f(t);
    f.state.border_color = 0x80FF0000;  // border (r, g, b, a) = (1, 0, 0, 128/255)
    struct Case { float u; float wrap, mirror, clamp, border, mirror_once; };
    const Case cases[] = {
        {0.125f, 10, 10, 10, 10, 10},      // 0.5 -> texel 0
        {0.25f, 20, 20, 20, 20, 20},       // exactly on the edge 1.0 -> texel 1
        {1.0f, 10, 40, 40, 1, 40},         // 4: wrap 0; mirror 4 mod 8 = 4 -> 7-4 = 3; clamp 3; border; 3
        {-0.125f, 40, 10, 10, 1, 10},      // -0.5 -> -1: wrap 3; mirror 7 -> 0; clamp 0; border; -1-(-1) = 0
        {1e4f, 10, 10, 40, 1, 40},         // 40000: wrap 0; mirror 40000 mod 8 = 0; clamp 3; border; 3
        {-1e4f, 10, 10, 10, 1, 40},        // -40000: wrap 0; mirror 0; clamp 0; border; 39999 -> 3
        {10000.375f, 20, 20, 40, 1, 40},   // 40001.5 -> 40001: wrap 1; mirror 1
        {1.75f, 40, 20, 40, 1, 40},        // 7: wrap 3; mirror 7 -> 8-1-7 = 0?? no: see below
    };
    for (const Case& c : cases) {
        const float expected[5] = {c.wrap, c.mirror, c.clamp, c.border, c.mirror_once};
        const A modes[5] = {A::Wrap, A::Mirror, A::Clamp, A::Border, A::MirrorOnce};
        for (int m = 0; m < 5; ++m) {
            if (c.u == 1.75f && m == 1) continue;  // checked separately below
            f.state.address_u = modes[m];
            EXPECT_EQ(f.at(c.u)[0], expected[m]) << "u " << c.u << " mode " << m + 1;
        }
    }
    // MIRROR at u = 1.75: 7 mod 8 = 7 >= 4 -> 2*4 - 1 - 7 = 0 -> texel 0 = 10
    f.state.address_u = A::Mirror;
    EXPECT_EQ(f.at(1.75f)[0], 10.0f);
    // u = 1.25: 5 mod 8 = 5 -> 8 - 1 - 5 = 2 -> 30
    EXPECT_EQ(f.at(1.25f)[0], 30.0f);
    // The border colour as a whole
    f.state.address_u = A::Border;
    EXPECT_EQ(f.at(-0.5f), (Float4{1, 0, 0, 128 / 255.0f}));
}

TEST(SamplerAddress, PerAxis) {
    // 2x2: row 0 = 0 1, row 1 = 2 3. U clamps, V wraps: (u, v) = (1.5, 1.25) -> x clamp 1,
    // y = floor(2.5) = 2 -> wrap 0 -> texel (1, 0) = 1. With U wrap, V clamp: x = 3 -> 1, y -> 1 -> 3
    const Texture t = r32f(2, 2, {0, 1, 2, 3});
    Fixture f(t);
    f.state.address_u = A::Clamp;
    f.state.address_v = A::Wrap;
    EXPECT_EQ(f.at(1.5f, 1.25f)[0], 1.0f);
    f.state.address_u = A::Wrap;
    f.state.address_v = A::Clamp;
    EXPECT_EQ(f.at(1.5f, 1.25f)[0], 3.0f);
}

// LINEAR, 4x1 texture 10 20 30 40: x = u*4 - 0.5, i0 = floor(x), a = x - i0 (8-bit by default)
TEST(SamplerFilter, LinearEveryModeAndEdges) {
    const Texture t = r32f(4, 1, {10, 20, 30, 40});
    Fixture f(t);
    f.state.mag_filter = Fl::Linear;
    f.state.border_color = 0x80FF0000;
    // on a texel centre: u = 0.375 -> x = 1 -> exactly 20
    EXPECT_EQ(f.at(0.375f)[0], 20.0f);
    // on the edge between texels 0 and 1: u = 0.25 -> x = 0.5 -> 15
    EXPECT_EQ(f.at(0.25f)[0], 15.0f);
    // u = 0 (texture edge): x = -0.5 -> taps -1, 0 with a = 0.5
    f.state.address_u = A::Wrap;       EXPECT_EQ(f.at(0.0f)[0], 25.0f);   // 40, 10
    f.state.address_u = A::Clamp;      EXPECT_EQ(f.at(0.0f)[0], 10.0f);   // 10, 10
    f.state.address_u = A::Mirror;     EXPECT_EQ(f.at(0.0f)[0], 10.0f);   // -1 -> 0
    f.state.address_u = A::MirrorOnce; EXPECT_EQ(f.at(0.0f)[0], 10.0f);
    f.state.address_u = A::Border;
    {
        // half border (1, 0, 0, 128/255), half texel (10, 1, 1, 1)
        const Float4 r = f.at(0.0f);
        EXPECT_EQ(r[0], 5.5f);
        EXPECT_EQ(r[1], 0.5f);
        EXPECT_EQ(r[2], 0.5f);
        EXPECT_FLOAT_EQ(r[3], 0.5f * 128 / 255.0f + 0.5f);
    }
    // u = 1e4: x = 39999.5 -> taps 39999, 40000, a = 0.5
    f.state.address_u = A::Wrap;  EXPECT_EQ(f.at(1e4f)[0], 25.0f);   // 39999 mod 4 = 3 (40), 0 (10)
    f.state.address_u = A::Clamp; EXPECT_EQ(f.at(1e4f)[0], 40.0f);
    // u = -1e4: x = -40000.5 -> taps -40001, -40000
    f.state.address_u = A::Wrap;   EXPECT_EQ(f.at(-1e4f)[0], 25.0f);  // -40001 mod 4 = 3, -40000 mod 4 = 0
    f.state.address_u = A::Clamp;  EXPECT_EQ(f.at(-1e4f)[0], 10.0f);
    f.state.address_u = A::Mirror; EXPECT_EQ(f.at(-1e4f)[0], 10.0f);  // 7 -> 0 and 0 -> 0
    f.state.address_u = A::Border; EXPECT_EQ(f.at(-1e4f)[0], 1.0f);   // both taps border
}

TEST(SamplerFilter, FixedPointWeightsAndExactReference) {
    const Texture t = r32f(4, 1, {10, 20, 30, 40});
    Fixture f(t);
    f.state.mag_filter = Fl::Linear;
    // u = 0.3f: 0.3f * 4 = 1.2000000477, x = 0.70000005. 8-bit: floor(0.70000005 * 256) = 179,
    // a = 179/256: 10 * 77/256 + 20 * 179/256 = 3.0078125 + 13.984375 = 16.9921875 (exact in float)
    EXPECT_EQ(f.at(0.3f)[0], 16.9921875f);
    f.sampler.set_precision(FilterPrecision::Exact);
    EXPECT_NEAR(f.at(0.3f)[0], 17.0f, 1e-5f);
}

TEST(SamplerFilter, Bilinear2D) {
    // 2x2: 0 1 / 2 3. (0.375, 0.625): x = 0.25, y = 0.75:
    // 0*(0.75*0.25) + 1*(0.25*0.25) + 2*(0.75*0.75) + 3*(0.25*0.75) = 0.0625 + 1.125 + 0.5625 = 1.75
    const Texture t = r32f(2, 2, {0, 1, 2, 3});
    Fixture f(t);
    f.state.mag_filter = Fl::Linear;
    f.state.address_u = f.state.address_v = A::Clamp;
    EXPECT_EQ(f.at(0.375f, 0.625f)[0], 1.75f);
    EXPECT_EQ(f.at(0.5f, 0.5f)[0], 1.5f);  // the centre: all four at 1/4
}

TEST(SamplerFilter, SpecialCoordinates) {
    const Texture t = r32f(4, 1, {10, 20, 30, 40});
    Fixture f(t);
    // NaN counts as 0 -> texel 0
    EXPECT_EQ(f.at(NAN)[0], 10.0f);
    // +inf -> texel space clamps to 2^30: wrap 2^30 mod 4 = 0; clamp -> 3
    EXPECT_EQ(f.at(INFINITY)[0], 10.0f);
    f.state.address_u = A::Clamp;
    EXPECT_EQ(f.at(INFINITY)[0], 40.0f);
    EXPECT_EQ(f.at(-INFINITY)[0], 10.0f);
    f.state.mag_filter = Fl::Linear;
    EXPECT_EQ(f.at(INFINITY)[0], 40.0f);
    EXPECT_EQ(f.at(NAN)[0], 10.0f);  // u = 0: taps -1, 0 clamp -> 10
    f.state.address_u = A::Wrap;
    EXPECT_EQ(f.at(3e38f)[0], 10.0f);  // 3e38 * 4 = inf -> 2^30 -> 0 (a = 0)
    // huge derivatives: lambda clamps to 64 -> last level; zero derivatives: magnification
    f.state.min_filter = Fl::Linear;
    f.state.mip_filter = Fl::Linear;
    EXPECT_EQ(f.grad({0.375f, 0.5f, 0}, {INFINITY, 0, 0}, {0, NAN, 0})[0], 20.0f);
    EXPECT_EQ(f.grad({0.375f, 0.5f, 0}, {1e30f, 0, 0}, {0, 0, 0})[0], 20.0f);
}

// LOD on a 16x16 texture whose 5 levels are solid k (level k reads k). d/dx = s texels along u:
// rho = s, lambda = log2(s) (+ biases).
Texture levels16() {
    Texture t = Texture::create_2d(Format::R32F, 16, 16);
    for (uint32_t k = 0; k < t.levels(); ++k) t.surface(k).fill({static_cast<float>(k), 0, 0, 0});
    return t;
}

TEST(SamplerLod, MipPointLinearBiasAndMaxMipLevel) {
    const Texture t = levels16();
    Fixture f(t);
    f.state.min_filter = Fl::Linear;
    f.state.mip_filter = Fl::Point;
    auto level = [&](float s, float bias = 0) { return f.grad({0.5f, 0.5f, 0}, {s / 16, 0, 0}, {0, 0, 0}, bias)[0]; };
    EXPECT_EQ(level(1), 0.0f);     // lambda 0: magnification
    EXPECT_EQ(level(2), 1.0f);     // lambda 1
    EXPECT_EQ(level(2.8f), 1.0f);  // log2 2.8 = 1.485 -> 1
    EXPECT_EQ(level(3), 2.0f);     // log2 3 = 1.585 -> 2
    EXPECT_EQ(level(100), 4.0f);   // 6.64 -> clamped to the last level
    EXPECT_EQ(level(2, 1), 2.0f);  // texldb-style bias +1
    f.state.mip_lod_bias = 1;      // MIPMAPLODBIAS adds to it
    EXPECT_EQ(level(2, 1), 3.0f);
    f.state.mip_lod_bias = -1;
    EXPECT_EQ(level(2), 0.0f);     // lambda 0 -> magnification
    f.state.mip_lod_bias = 0;
    f.state.mip_filter = Fl::None;
    EXPECT_EQ(level(8), 0.0f);     // no mipmapping
    f.state.mip_filter = Fl::Point;
    f.state.max_mip_level = 2;     // largest level allowed: 2
    EXPECT_EQ(level(1), 2.0f);
    EXPECT_EQ(level(2), 2.0f);     // clamp(1, 2, 4)
    EXPECT_EQ(level(8), 3.0f);     // lambda 3
    f.state.max_mip_level = 9;     // beyond the chain: the last level
    EXPECT_EQ(level(1), 4.0f);
    f.state.max_mip_level = 0;
    // LINEAR: s = 3, lambda = log2 3 = 1.5849625; 8-bit: floor(405.75)/256 = 1.58203125,
    // blend levels 1 and 2 by 0.58203125 -> 1.58203125
    f.state.mip_filter = Fl::Linear;
    EXPECT_EQ(level(3), 1.58203125f);
    f.sampler.set_precision(FilterPrecision::Exact);
    EXPECT_NEAR(level(3), 1.5849625f, 1e-6f);
}

TEST(SamplerLod, Anisotropic) {
    const Texture t = levels16();
    Fixture f(t);
    f.state.min_filter = Fl::Anisotropic;
    f.state.mip_filter = Fl::Point;
    f.state.max_anisotropy = 16;
    auto level = [&](float sx, float sy) { return f.grad({0.5f, 0.5f, 0}, {sx / 16, 0, 0}, {0, sy / 16, 0})[0]; };
    // major 8, minor 1: N = ceil(8) = 8 probes, lambda = log2(8/8) = 0 -> level 0
    EXPECT_EQ(level(8, 1), 0.0f);
    // major 8, minor 3: N = ceil(2.67) = 3, lambda = log2(8/3) = 1.415 -> 1
    EXPECT_EQ(level(8, 3), 1.0f);
    // major 16 (y), minor 1 with MAXANISOTROPY 4: N = 4, lambda = log2(16/4) = 2
    f.state.max_anisotropy = 4;
    EXPECT_EQ(level(1, 16), 2.0f);
    // MAXANISOTROPY 1: isotropic, lambda = log2(8) = 3
    f.state.max_anisotropy = 1;
    EXPECT_EQ(level(8, 1), 3.0f);
    const auto info = f.sampler.level_of_detail(0, {8, 0, 0}, {0, 3, 0});
    EXPECT_EQ(info.probes, 1u);
    f.state.max_anisotropy = 16;
    f.sampler.set_state(0, f.state);
    EXPECT_EQ(f.sampler.level_of_detail(0, {8, 0, 0}, {0, 3, 0}).probes, 3u);
    EXPECT_EQ(f.sampler.level_of_detail(0, {8, 0, 0}, {0, 0, 0}).probes, 16u);  // minor 0: the cap
}

TEST(SamplerLod, AnisotropicProbesAlongTheMajorAxis) {
    // 16x1 step: texels 0..7 = 0, 8..15 = 1. MIN ANISOTROPIC, MAXANISOTROPY 4, no mips.
    // At u = 7/16 (texel space 7) with d/dx = 4 texels, d/dy = 1: N = 4 probes at offsets
    // (i + 0.5)/4 - 0.5 = -3/8, -1/8, 1/8, 3/8 of 4 texels -> 5.5, 6.5, 7.5, 8.5;
    // bilinear at texel-space t reads x = t - 0.5 = 5, 6, 7, 8 -> 0, 0, 0, 1: average 0.25.
    std::vector<float> v(16);
    for (int i = 8; i < 16; ++i) v[i] = 1;
    const Texture t = r32f(16, 1, v);
    Fixture f(t);
    f.state.min_filter = Fl::Anisotropic;
    f.state.max_anisotropy = 4;
    f.state.address_u = A::Clamp;
    EXPECT_EQ(f.grad({7 / 16.0f, 0.5f, 0}, {4 / 16.0f, 0, 0}, {0, 1, 0})[0], 0.25f);
    // plain bilinear there: x = 6.5 -> 0
    f.state.min_filter = Fl::Linear;
    EXPECT_EQ(f.grad({7 / 16.0f, 0.5f, 0}, {4 / 16.0f, 0, 0}, {0, 1, 0})[0], 0.0f);
}

// A ground plane at a grazing angle through the engine interface: pixel (x, y) maps to
// u = x/256, v = 16/y on a 256x256 texture whose 9 levels are solid k. Quad with top-left
// (x, y): d/dx = 1 texel; d/dy = 256 * (16/(y+1) - 16/y) -> |d/dy| = 4096 / (y (y+1)) texels.
//   y = 2 : 682.67 -> lambda 9.42; y = 8 : 56.89 -> 5.83; y = 16: 15.06 -> 3.91;
//   y = 32: 3.879 -> 1.956;       y = 64: 0.985 -> rho = max(1, 0.985) = 1 -> lambda 0
struct PlaneProbe { unsigned y; float point, aniso; };

void plane_quads(const std::vector<unsigned>& rows, std::array<emu::FloatLanes, 4>& c) {
    for (auto& comp : c) comp.fill(0);
    for (unsigned q = 0; q < rows.size(); ++q)
        for (unsigned i = 0; i < 4; ++i) {
            const unsigned x = 10 + (i & 1), y = rows[q] + (i >> 1);
            c[0][4 * q + i] = static_cast<float>(x) / 256.0f;
            c[1][4 * q + i] = 16.0f / static_cast<float>(y);
            c[3][4 * q + i] = 1.0f;
        }
}

TEST(SamplerLod, GrazingPlaneThroughQuads) {
    Texture t = Texture::create_2d(Format::R32F, 256, 256);
    ASSERT_EQ(t.levels(), 9u);
    for (uint32_t k = 0; k < 9; ++k) t.surface(k).fill({static_cast<float>(k), 0, 0, 0});
    TextureSampler s;
    s.set_texture(0, &t);
    SamplerState st;
    st.min_filter = Fl::Linear;
    st.mag_filter = Fl::Linear;
    st.mip_filter = Fl::Point;
    s.set_state(0, st);
    std::array<emu::FloatLanes, 4> c, out;
    emu::TextureRequest r;
    r.coordinates = &c;
    // POINT mip: round(lambda) clamped to 8: y 2 -> 8, 16 -> 4, 32 -> 2, 64 -> 0
    plane_quads({2, 16, 32, 64}, c);
    s.sample(r, out);
    const float point[4] = {8, 4, 2, 0};
    for (unsigned q = 0; q < 4; ++q)
        for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(out[0][4 * q + i], point[q]) << "quad " << q;
    // LINEAR mip at y = 32: lambda 1.9556; 8-bit: floor(500.64)/256 = 1.953125 -> 1.953125;
    // y = 8: lambda log2(56.89) = 5.830; 8-bit floor(1492.5)/256 = 5.828125
    st.mip_filter = Fl::Linear;
    s.set_state(0, st);
    plane_quads({32, 8}, c);
    r.quad_count = 2;
    s.sample(r, out);
    EXPECT_EQ(out[0][0], 1.953125f);
    EXPECT_EQ(out[0][4], 5.828125f);
    // ANISOTROPIC x16, POINT mip: N = min(ceil(major/1), 16) = 16, lambda = log2(major/16):
    //   y = 2: 682.67/16 = 42.67 -> 5.415 -> 5; y = 8: 56.89/16 = 3.556 -> 1.83 -> 2;
    //   y = 16: 15.06 -> N = 16, 0.94 -> negative -> level 0; y = 32: N = 4, 0.97 -> level 0
    st.min_filter = Fl::Anisotropic;
    st.max_anisotropy = 16;
    st.mip_filter = Fl::Point;
    s.set_state(0, st);
    plane_quads({2, 8, 16, 32}, c);
    r.quad_count = 4;
    s.sample(r, out);
    const float aniso[4] = {5, 2, 0, 0};
    for (unsigned q = 0; q < 4; ++q) EXPECT_EQ(out[0][4 * q], aniso[q]) << "quad " << q;
}

TEST(SamplerLod, TexldbBiasPerLaneAndTexldpProjection) {
    const Texture t = levels16();
    TextureSampler s;
    s.set_texture(0, &t);
    SamplerState st;
    st.min_filter = Fl::Point;
    st.mip_filter = Fl::Point;
    s.set_state(0, st);
    std::array<emu::FloatLanes, 4> c, out;
    for (auto& comp : c) comp.fill(0.5f);
    // one quad, 1 texel per pixel in u (lambda 0); biases 0, 1, 2.5, -3 -> levels 0, 1, 3, 0
    for (unsigned i = 0; i < 4; ++i) c[0][i] = 0.5f + static_cast<float>(i & 1) / 16.0f;
    const float bias[4] = {0, 1, 2.5f, -3};
    for (unsigned i = 0; i < 4; ++i) c[3][i] = bias[i];
    emu::TextureRequest r;
    r.coordinates = &c;
    r.quad_count = 1;
    r.variant = emu::TextureVariant::Bias;
    s.sample(r, out);
    EXPECT_EQ(out[0][0], 0.0f);
    EXPECT_EQ(out[0][1], 1.0f);
    EXPECT_EQ(out[0][2], 3.0f);  // round(2.5) = floor(3.0) = 3
    EXPECT_EQ(out[0][3], 0.0f);
    // texldp: (x, y) / w with w = 0.25: x steps 1/64 -> 1/16 after projection = 1 texel... use
    // 2/64 per pixel -> 2 texels after projection -> lambda 1 -> level 1
    for (unsigned i = 0; i < 4; ++i) {
        c[0][i] = 0.125f + static_cast<float>(i & 1) * 2.0f / 64.0f;
        c[1][i] = 0.125f;
        c[3][i] = 0.25f;
    }
    r.variant = emu::TextureVariant::Projected;
    s.sample(r, out);
    for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(out[0][i], 1.0f);
    // w = 0: x/0 = +inf (clamped to the texel-space limit), 0/0 = NaN (counts as 0); the
    // derivatives are inf - inf = NaN -> 0 -> magnification on level 0. Defined, not UB.
    for (unsigned i = 0; i < 4; ++i) c[3][i] = 0.0f;
    s.sample(r, out);
    for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(out[0][i], 0.0f);
}

TEST(SamplerLod, InfiniteAndNaNDerivativesWithAnisotropy) {
    const Texture t = levels16();
    Fixture f(t);
    f.state.min_filter = Fl::Anisotropic;
    f.state.mip_filter = Fl::Point;
    f.state.max_anisotropy = 8;
    f.state.address_u = f.state.address_v = A::Clamp;
    // both derivatives infinite: inf / inf ratio -> the cap (8 probes), lambda clamps -> last level
    EXPECT_EQ(f.grad({0.5f, 0.5f, 0}, {INFINITY, 0, 0}, {0, INFINITY, 0})[0], 4.0f);
    f.sampler.set_state(0, f.state);
    EXPECT_EQ(f.sampler.level_of_detail(0, {INFINITY, 0, 0}, {0, INFINITY, 0}).probes, 8u);
    EXPECT_EQ(f.sampler.level_of_detail(0, {INFINITY, 0, 0}, {0, INFINITY, 0}).lambda, 64.0f);
    // NaN derivatives count as 0: magnification, level 0
    EXPECT_EQ(f.grad({0.5f, 0.5f, 0}, {NAN, 0, 0}, {0, NAN, 0})[0], 0.0f);
    EXPECT_TRUE(f.sampler.level_of_detail(0, {NAN, 0, 0}, {0, NAN, 0}).magnify);
    // a NaN texldb bias counts as 0; a huge one clamps to the last level
    EXPECT_EQ(f.grad({0.5f, 0.5f, 0}, {2 / 16.0f, 0, 0}, {0, 2 / 16.0f, 0}, NAN)[0], 1.0f);
    EXPECT_EQ(f.grad({0.5f, 0.5f, 0}, {2 / 16.0f, 0, 0}, {0, 2 / 16.0f, 0}, 1e30f)[0], 4.0f);
}

TEST(SamplerLod, UnboundStageAndLanesReturnDefined) {
    TextureSampler s;
    std::array<emu::FloatLanes, 4> c{}, out;
    emu::TextureRequest r;
    r.coordinates = &c;
    r.sampler = 3;
    s.sample(r, out);
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) EXPECT_EQ((Float4{out[0][l], out[1][l], out[2][l], out[3][l]}), (Float4{0, 0, 0, 1}));
    // an empty (default-constructed) texture samples like an unbound stage
    const Texture empty;
    s.set_texture(3, &empty);
    s.sample(r, out);
    EXPECT_EQ(out[3][0], 1.0f);
    EXPECT_EQ(s.sample_gradient(3, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}), (Float4{0, 0, 0, 1}));
    EXPECT_THROW(s.set_texture(16, nullptr), std::out_of_range);
}

// Cube: 2x2 faces, texel (x, y) of face f reads 10 f + 2 y + x.
Texture cube2() {
    Texture t = Texture::create_cube(Format::R32F, 2, 1);
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x)
                t.surface(0, f).write(x, y, 0, {static_cast<float>(10 * f + 2 * y + x), 0, 0, 0});
    return t;
}

TEST(SamplerCube, EachFace) {
    const Texture t = cube2();
    Fixture f(t);
    // u = (sc/|ma| + 1)/2, v = (tc/|ma| + 1)/2, texel floor(2u), floor(2v)
    EXPECT_EQ(f.at(1, 0.5f, 0.5f)[0], 0.0f);     // +X: sc = -rz = -0.5 -> u 0.25; tc = -ry -> v 0.25: (0,0)
    EXPECT_EQ(f.at(-1, 0.5f, 0.5f)[0], 11.0f);   // -X: sc = +rz -> 0.75; tc = -0.5 -> 0.25: (1,0)
    EXPECT_EQ(f.at(0.5f, 1, 0.5f)[0], 23.0f);    // +Y: sc = rx -> 0.75; tc = +rz -> 0.75: (1,1)
    EXPECT_EQ(f.at(0.5f, -1, 0.5f)[0], 31.0f);   // -Y: sc = rx -> 0.75; tc = -rz -> 0.25: (1,0)
    EXPECT_EQ(f.at(0.5f, 0.5f, 1)[0], 41.0f);    // +Z: sc = rx -> 0.75; tc = -ry -> 0.25: (1,0)
    EXPECT_EQ(f.at(0.5f, 0.5f, -1)[0], 50.0f);   // -Z: sc = -rx -> 0.25; tc = -ry -> 0.25: (0,0)
    // the magnitude does not matter
    EXPECT_EQ(f.at(1000, 500, 500)[0], 0.0f);
}

TEST(SamplerCube, EdgeAndCornerTiesAndSpecialDirections) {
    const Texture t = cube2();
    Fixture f(t);
    // Ties: z over y over x. Face edges clamp (no filtering across faces).
    EXPECT_EQ(f.at(1, 1, 0)[0], 23.0f);     // |x| = |y|: +Y, sc = 1 -> u 1 -> x 2 -> clamp 1; tc = 0 -> y 1
    EXPECT_EQ(f.at(-1, -1, 0)[0], 32.0f);   // -Y: sc = -1 -> u 0 -> x 0; tc = -rz = 0 -> y 1
    EXPECT_EQ(f.at(1, 0, 1)[0], 43.0f);     // |x| = |z|: +Z, u 1 -> 1, v 0.5 -> 1
    EXPECT_EQ(f.at(0, -1, -1)[0], 53.0f);   // |y| = |z|: -Z, sc = -0 -> u 0.5 -> 1; tc = 1 -> v 1 -> 1
    EXPECT_EQ(f.at(1, 1, 1)[0], 41.0f);     // corner: +Z, u 1 -> 1, tc = -1 -> v 0 -> 0
    EXPECT_EQ(f.at(-1, -1, -1)[0], 53.0f);  // corner: -Z, sc = 1, tc = 1 -> (1,1)
    EXPECT_EQ(f.at(0, 0, 0)[0], 43.0f);     // zero vector: +Z centre (0.5, 0.5) -> (1,1)
    EXPECT_EQ(f.at(NAN, 1, 0)[0], 23.0f);   // NaN -> 0: +Y centre
    EXPECT_EQ(f.at(INFINITY, 1, 0)[0], 3.0f);   // only the infinite component: +X centre
    // Bilinear at the face edge clamps: +X at u = 1 (sc = -rz = 1 -> rz = -1 with x = 1 ties z:
    // use x = 2): (2, 0, -2) -> +Z? |x| = |z| -> z wins: -Z face, sc = -rx = -2/2 -> u 0, v 0.5
    f.state.mag_filter = Fl::Linear;
    // -Z face (50 51 / 52 53) at u = 0, v = 0.5: x = -0.5 -> taps clamp 0,0; y = 0.5 -> 0,1: (50+52)/2
    EXPECT_EQ(f.at(2, 0, -2)[0], 51.0f);
}

// All 26 directions with components in {-1, 0, 1}: 6 face centres, 12 edges, 8 corners. Ties
// go to z, then y, then x: the face is the sign of z if z != 0, else of y, else of x.
TEST(SamplerCube, EveryEdgeAndCornerTie) {
    const Texture t = cube2();
    Fixture f(t);
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                const int face = z != 0 ? (z > 0 ? 4 : 5) : y != 0 ? (y > 0 ? 2 : 3) : (x > 0 ? 0 : 1);
                const float value = f.at(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z))[0];
                EXPECT_EQ(static_cast<int>(value) / 10, face) << x << " " << y << " " << z;
            }
}

TEST(SamplerVolume, PointAndTrilinear) {
    // 2x2x2, texel (x, y, z) = x + 2y + 4z
    Texture t = Texture::create_volume(Format::R32F, 2, 2, 2, 1);
    for (uint32_t z = 0; z < 2; ++z)
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x) t.surface(0).write(x, y, z, {static_cast<float>(x + 2 * y + 4 * z), 0, 0, 0});
    Fixture f(t);
    EXPECT_EQ(f.at(0.75f, 0.25f, 0.75f)[0], 5.0f);  // (1, 0, 1)
    f.state.address_w = A::Wrap;
    EXPECT_EQ(f.at(0.25f, 0.25f, -0.1f)[0], 4.0f);  // z = floor(-0.2) = -1 -> wrap 1
    f.state.address_w = A::Clamp;
    EXPECT_EQ(f.at(0.25f, 0.25f, -0.1f)[0], 0.0f);
    f.state.mag_filter = Fl::Linear;
    EXPECT_EQ(f.at(0.5f, 0.5f, 0.5f)[0], 3.5f);   // all 8 at 1/8: (0+...+7)/8
    // (0.5, 0.5, 0.625): z = 0.75 -> 0.25 * (0+1+2+3)/4 + 0.75 * (4+5+6+7)/4 = 0.375 + 4.125 = 4.5
    EXPECT_EQ(f.at(0.5f, 0.5f, 0.625f)[0], 4.5f);
}

TEST(SamplerSrgb, ConvertsRgbBeforeFilteringNeverAlpha) {
    Texture t = Texture::create_2d(Format::A8R8G8B8, 2, 1, 1);
    // texel 0 = (0, 10, 128, 128)/255, texel 1 = (255, 255, 255, 0)
    t.surface(0).write(0, 0, 0, {0, 10 / 255.0f, 128 / 255.0f, 128 / 255.0f});
    t.surface(0).write(1, 0, 0, {1, 1, 1, 0});
    Fixture f(t);
    f.state.srgb_texture = true;
    const Float4 p = f.at(0.25f);
    EXPECT_EQ(p[0], 0.0f);
    EXPECT_FLOAT_EQ(p[1], 10 / 255.0f / 12.92f);   // linear segment
    EXPECT_NEAR(p[2], 0.215861f, 1e-6f);           // ((128/255 + 0.055)/1.055)^2.4
    EXPECT_EQ(p[3], 128 / 255.0f);                 // alpha untouched
    // Before filtering: midway between r = 0 and r = 1 is (lin(0) + lin(1))/2 = 0.5, not lin(0.5)
    f.state.mag_filter = Fl::Linear;
    f.state.address_u = A::Clamp;
    EXPECT_EQ(f.at(0.5f)[0], 0.5f);
    // Formats without sRGB reads ignore the state
    Texture h = Texture::create_2d(Format::A16B16G16R16F, 1, 1, 1);
    h.surface(0).write(0, 0, 0, {0.5f, 0.5f, 0.5f, 0.5f});
    Fixture g(h);
    g.state.srgb_texture = true;
    EXPECT_EQ(g.at(0.5f)[0], 0.5f);
}

TEST(SamplerFormats, MissingChannelsAndDxt) {
    Texture a = Texture::create_2d(Format::A8, 1, 1, 1);
    a.surface(0).write(0, 0, 0, {0, 0, 0, 1});
    Fixture f(a);
    EXPECT_EQ(f.at(0.5f), (Float4{0, 0, 0, 1}));
    // DXT1 8x4 texture: block 1 is the 4-colour block of formats_dxt_test (row 0: red, blue, p2, p3)
    Texture d = Texture::create_2d(Format::DXT1, 8, 4, 1);
    const uint8_t block[8] = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xFF, 0x00, 0x55};
    for (int i = 0; i < 8; ++i) d.surface(0).bytes()[8 + i] = static_cast<std::byte>(block[i]);
    Fixture g(d);
    EXPECT_EQ(g.at(5.5f / 8, 0.5f / 4), (Float4{0, 0, 1, 1}));                         // texel (5, 0) = (1, 0) of block 1
    EXPECT_EQ(g.at(6.5f / 8, 0.5f / 4), (Float4{170 / 255.0f, 0, 85 / 255.0f, 1}));    // p2
    EXPECT_EQ(g.at(0.5f / 8, 0.5f / 4), (Float4{0, 0, 0, 1}));                         // zero block 0
}

// Point sampling at every texel centre returns exactly Surface::read (the format decoder), for
// every texture format, whether the sampler inlines its decoder or not. NaN-safe comparison.
TEST(SamplerFormats, EveryFormatReadsLikeTheSurface) {
    uint32_t seed = 4242;
    for (const FormatInfo& info : format_table()) {
        if (!info.texture) continue;
        Texture t = Texture::create_2d(info.format, 8, 4, 1);
        for (auto& b : t.surface(0).bytes()) {
            seed = seed * 1664525u + 1013904223u;
            b = static_cast<std::byte>(seed >> 24);
        }
        TextureSampler s;
        s.set_texture(0, &t);
        for (uint32_t y = 0; y < 4; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                const Float4 got = s.sample_gradient(0, {(x + 0.5f) / 8, (y + 0.5f) / 4, 0}, {0, 0, 0}, {0, 0, 0});
                const Float4 want = t.surface(0).read(x, y);
                for (int c = 0; c < 4; ++c) {
                    if (std::isnan(got[c]) && std::isnan(want[c])) continue;
                    ASSERT_EQ(got[c], want[c]) << info.name << " texel " << x << "," << y << " channel " << c;
                }
            }
    }
}

TEST(SamplerState, DefaultsAndRawDwords) {
    const SamplerState s;
    EXPECT_EQ(s.get(1), 1u);   // ADDRESSU WRAP
    EXPECT_EQ(s.get(3), 1u);
    EXPECT_EQ(s.get(4), 0u);   // BORDERCOLOR
    EXPECT_EQ(s.get(5), 1u);   // MAGFILTER POINT
    EXPECT_EQ(s.get(6), 1u);
    EXPECT_EQ(s.get(7), 0u);   // MIPFILTER NONE
    EXPECT_EQ(s.get(8), 0u);
    EXPECT_EQ(s.get(9), 0u);
    EXPECT_EQ(s.get(10), 1u);  // MAXANISOTROPY
    EXPECT_EQ(s.get(11), 0u);
    EXPECT_EQ(s.get(12), 0u);
    EXPECT_EQ(s.get(13), 0u);
    EXPECT_FALSE(s.get(0).has_value());
    EXPECT_FALSE(s.get(14).has_value());
    SamplerState t;
    EXPECT_TRUE(t.set(8, 0xBF800000u));  // MIPMAPLODBIAS = -1.0f as bits
    EXPECT_EQ(t.mip_lod_bias, -1.0f);
    EXPECT_FALSE(t.set(99, 1));
    EXPECT_TRUE(t.set(1, 77));           // stored as given; sampled as WRAP
    EXPECT_EQ(t.get(1), 77u);
}

// Fixed 8-bit weights against the exact reference over a sweep: 64x64 random-ish texture of
// L8 values, bilinear, 200000 coordinates. The bound is the weight quantization: each weight
// is off by < 1/256 per axis, so |error| < 2/256 of the texel range.
TEST(SamplerPrecision, FixedVsExactSweep) {
    Texture t = Texture::create_2d(Format::A8R8G8B8, 64, 64, 1);
    uint32_t seed = 12345;
    auto next = [&] { seed = seed * 1664525u + 1013904223u; return seed >> 8; };
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            t.surface(0).write(x, y, 0, {(next() & 255) / 255.0f, (next() & 255) / 255.0f, (next() & 255) / 255.0f, 1});
    TextureSampler fixed, exact;
    SamplerState st;
    st.mag_filter = Fl::Linear;
    for (TextureSampler* s : {&fixed, &exact}) {
        s->set_texture(0, &t);
        s->set_state(0, st);
    }
    exact.set_precision(FilterPrecision::Exact);
    float max_error = 0;
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const float u = static_cast<float>(next() % 1000000) / 1000000.0f;
        const float v = static_cast<float>(next() % 1000000) / 1000000.0f;
        const Float4 a = fixed.sample_gradient(0, {u, v, 0}, {0, 0, 0}, {0, 0, 0});
        const Float4 b = exact.sample_gradient(0, {u, v, 0}, {0, 0, 0}, {0, 0, 0});
        for (int c = 0; c < 3; ++c) {
            const float e = std::fabs(a[c] - b[c]);
            max_error = std::max(max_error, e);
            sum += e;
        }
    }
    std::printf("bilinear Fixed8 vs Exact over %d lookups: max abs error %.6f (%.3f/255), mean %.6f\n", n,
                max_error, max_error * 255, sum / (3.0 * n));
    EXPECT_LT(max_error, 2.0f / 256.0f);
    EXPECT_GT(max_error, 0.0f);
}

// The same for trilinear filtering (8-bit LOD fraction as well) with derivatives of 0.5 to 16
// texels per pixel on a 64x64 texture with a box-filtered mip chain. Bound: 2/256 from the
// bilinear weights plus < 1/256 from the mip weight, plus the LOD itself being truncated to
// 1/256 (which shifts the mip weight by < 1/256 more): < 4/256 of the texel range.
TEST(SamplerPrecision, FixedVsExactTrilinearSweep) {
    Texture t = Texture::create_2d(Format::A8R8G8B8, 64, 64);
    uint32_t seed = 777;
    auto next = [&] { seed = seed * 1664525u + 1013904223u; return seed >> 8; };
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            t.surface(0).write(x, y, 0, {(next() & 255) / 255.0f, (next() & 255) / 255.0f, (next() & 255) / 255.0f, 1});
    t.generate_mips();
    TextureSampler fixed, exact;
    SamplerState st;
    st.mag_filter = st.min_filter = st.mip_filter = Fl::Linear;
    for (TextureSampler* s : {&fixed, &exact}) {
        s->set_texture(0, &t);
        s->set_state(0, st);
    }
    exact.set_precision(FilterPrecision::Exact);
    float max_error = 0;
    double sum = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const float u = static_cast<float>(next() % 1000000) / 1000000.0f;
        const float v = static_cast<float>(next() % 1000000) / 1000000.0f;
        const float d = (0.5f + 15.5f * static_cast<float>(next() % 10000) / 10000.0f) / 64.0f;
        const Float4 a = fixed.sample_gradient(0, {u, v, 0}, {d, 0, 0}, {0, d, 0});
        const Float4 b = exact.sample_gradient(0, {u, v, 0}, {d, 0, 0}, {0, d, 0});
        for (int c = 0; c < 3; ++c) {
            const float e = std::fabs(a[c] - b[c]);
            max_error = std::max(max_error, e);
            sum += e;
        }
    }
    std::printf("trilinear Fixed8 vs Exact over %d lookups: max abs error %.6f (%.3f/255), mean %.6f\n", n,
                max_error, max_error * 255, sum / (3.0 * n));
    EXPECT_LT(max_error, 4.0f / 256.0f);
}

}  // namespace
}  // namespace sm2::runtime
