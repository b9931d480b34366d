// Whole draws through the Device, probed the way D3D9 conformance tests probe: every expected
// colour below is worked out by hand from the rules (pixel centres at integer coordinates, the
// top-left rule, clipping, compare functions, blending, rounding to 8 bits).
//
// The render target is 8x8 unless said otherwise. A clip-space vertex (x, y, z, 1) lands on
// screen at ((x + 1) * 4, (1 - y) * 4).
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/runtime/device.h"

namespace sm2::runtime {
namespace {

uint32_t rs(RenderStateType t) { return static_cast<uint32_t>(t); }

isa::Program program(const std::string& text) {
    auto r = assembler::assemble(text);
    EXPECT_TRUE(r.ok()) << text;
    return *r.program;
}

// Position (FLOAT4) and one FLOAT4 colour per vertex; the VS passes both through (colour in
// oD0 and oT0), the PS writes the chosen input to oC0.
struct Vertex {
    float x, y, z, w;
    float r, g, b, a;
};

std::span<const std::byte> bytes_of(const std::vector<Vertex>& v) { return std::as_bytes(std::span(v)); }

constexpr uint32_t kTriangleList = 4, kTriangleStrip = 5, kPointList = 1;

class DeviceTest : public ::testing::Test {
protected:
    void make(uint32_t width = 8, uint32_t height = 8, std::optional<Format> depth = std::nullopt,
              unsigned threads = 1) {
        DeviceOptions options;
        options.threads = threads;
        device = std::make_unique<Device>(options);
        ASSERT_TRUE(device->create_device(width, height, Format::A8R8G8B8, depth));
        ASSERT_TRUE(device->create_vertex_declaration(
            "decl", {VertexElement{0, 0, static_cast<uint8_t>(DeclType::FLOAT4), 0, 0, 0},
                     VertexElement{0, 16, static_cast<uint8_t>(DeclType::FLOAT4), 0, 10, 0}}));
        ASSERT_TRUE(device->create_vertex_shader("vs", program("vs_2_0\ndcl_position v0\ndcl_color v1\n"
                                                               "mov oPos, v0\nmov oD0, v1\nmov oT0, v1\n")));
        ASSERT_TRUE(device->create_pixel_shader("ps_color", program("ps_2_0\ndcl v0\nmov oC0, v0\n")));
        ASSERT_TRUE(device->create_pixel_shader("ps_texcoord", program("ps_2_0\ndcl t0\nmov oC0, t0\n")));
        ASSERT_TRUE(device->set_vertex_declaration("decl"));
        ASSERT_TRUE(device->set_vertex_shader("vs"));
        ASSERT_TRUE(device->set_pixel_shader("ps_color"));
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::CullMode), 1));  // NONE
        ASSERT_TRUE(device->clear(kClearTarget, 0xFF000000u, 1.0f, 0));
        ASSERT_TRUE(device->begin_scene());
    }
    CallResult draw(uint32_t type, uint32_t count, const std::vector<Vertex>& v) {
        return device->draw_primitive_up(type, count, bytes_of(v), sizeof(Vertex));
    }
    // The stored A8R8G8B8 texel as 0xAARRGGBB.
    uint32_t pixel(uint32_t x, uint32_t y, const std::string& surface = "backbuffer") const {
        const Surface* s = device->surface(surface);
        uint32_t v = 0;
        std::memcpy(&v, s->bytes().data() + y * s->row_pitch() + x * 4, 4);
        return v;
    }
    unsigned count_pixels(uint32_t value) const {
        const Surface* s = device->surface("backbuffer");
        unsigned n = 0;
        for (uint32_t y = 0; y < s->height(); ++y)
            for (uint32_t x = 0; x < s->width(); ++x) n += pixel(x, y) == value;
        return n;
    }
    std::unique_ptr<Device> device;
};

const Vertex kTopLeftRed{-1, 1, 0.5f, 1, 1, 0, 0, 1};

// Screen (0,0), (8,0), (0,8): top edge y = 0 and left edge x = 0 are in, the hypotenuse
// x + y = 8 is a right/bottom edge and out. Covered: x, y >= 0 and x + y < 8: 8+7+...+1 = 36.
TEST_F(DeviceTest, TopLeftRuleOnOneTriangle) {
    make();
    ASSERT_TRUE(draw(kTriangleList, 1, {kTopLeftRed, {1, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -1, 0.5f, 1, 1, 0, 0, 1}}));
    EXPECT_EQ(count_pixels(0xFFFF0000u), 36u);
    EXPECT_EQ(pixel(0, 0), 0xFFFF0000u);  // corner on the top and left edges
    EXPECT_EQ(pixel(7, 0), 0xFFFF0000u);  // 7 + 0 < 8
    EXPECT_EQ(pixel(3, 4), 0xFFFF0000u);  // 3 + 4 < 8
    EXPECT_EQ(pixel(4, 4), 0xFF000000u);  // on the hypotenuse: not a top or left edge
    EXPECT_EQ(pixel(0, 7), 0xFFFF0000u);
}

// Two triangles share the diagonal; stencil INCR counts how often each pixel is drawn: every
// one of the 64 pixels exactly once.
TEST_F(DeviceTest, SharedEdgeDrawsEveryPixelOnce) {
    make(8, 8, Format::D24S8);
    ASSERT_TRUE(device->clear(kClearStencil | kClearZBuffer, 0, 1.0f, 0));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::StencilEnable), 1));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::StencilPass), 7));  // INCR
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::ZFunc), 8));        // ALWAYS
    const Vertex a{-1, 1, 0.5f, 1, 0, 1, 0, 1}, b{1, 1, 0.5f, 1, 0, 1, 0, 1}, c{-1, -1, 0.5f, 1, 0, 1, 0, 1},
        d{1, -1, 0.5f, 1, 0, 1, 0, 1};
    ASSERT_TRUE(draw(kTriangleList, 2, {a, b, c, b, d, c}));
    const DepthStencilSurface* ds = device->depth_stencil("autodepth");
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) ASSERT_EQ(ds->stencil(x, y), 1u) << x << "," << y;
    EXPECT_EQ(count_pixels(0xFF00FF00u), 64u);
}

// (0,0) -> (8,0) -> (0,8) is clockwise on screen (y down): CULLMODE CCW (the default) keeps it,
// CW removes it; the reversed order is the opposite.
TEST_F(DeviceTest, CullModes) {
    const std::vector<Vertex> cw{kTopLeftRed, {1, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -1, 0.5f, 1, 1, 0, 0, 1}};
    const std::vector<Vertex> ccw{cw[0], cw[2], cw[1]};
    struct Case { uint32_t cull; const std::vector<Vertex>* tri; unsigned expected; };
    for (const Case& k : {Case{1, &cw, 36}, Case{1, &ccw, 36}, Case{2, &cw, 0}, Case{2, &ccw, 36},
                          Case{3, &cw, 36}, Case{3, &ccw, 0}}) {
        make();
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::CullMode), k.cull));
        ASSERT_TRUE(draw(kTriangleList, 1, *k.tri));
        EXPECT_EQ(count_pixels(0xFFFF0000u), k.expected) << "cull " << k.cull;
    }
}

// Colours interpolate with weights x/8 (vertex 1) and y/8 (vertex 2) at pixel centres; pixel
// (2,0): red 0.75 -> 191.25 -> 191, green 0.25 -> 63.75 -> 64.
TEST_F(DeviceTest, GouraudColoursAtPixelCentres) {
    make();
    ASSERT_TRUE(draw(kTriangleList, 1, {kTopLeftRed, {1, 1, 0.5f, 1, 0, 1, 0, 1}, {-1, -1, 0.5f, 1, 0, 0, 1, 1}}));
    EXPECT_EQ(pixel(0, 0), 0xFFFF0000u);  // exactly vertex 0
    EXPECT_EQ(pixel(2, 0), 0xFFBF4000u);
    EXPECT_EQ(pixel(0, 2), 0xFFBF0040u);  // blue 0.25
}

// Vertex 1 sits at screen (8, 0) with w = 2 (clip (2, 2, 0, 2)). At pixel (4, 0) the screen
// weight of vertex 1 is 1/2; perspective-correct it is (1/2 * 1/2) / (1/2 * 1 + 1/2 * 1/2) = 1/3,
// so t0.x = 1/3 -> 85 (an affine interpolator would give 127.5).
TEST_F(DeviceTest, PerspectiveCorrectTexcoord) {
    make();
    ASSERT_TRUE(device->set_pixel_shader("ps_texcoord"));
    ASSERT_TRUE(draw(kTriangleList, 1, {{-1, 1, 0, 1, 0, 0, 0, 1}, {2, 2, 0, 2, 1, 0, 0, 1}, {-1, -1, 0, 1, 0, 0, 0, 1}}));
    EXPECT_EQ(pixel(4, 0), 0xFF550000u);
    EXPECT_EQ(pixel(0, 0), 0xFF000000u);
}

// A full-screen quad whose z runs from -0.5 at the top (screen y 0) to 1.5 at the bottom
// (y 8): z = -0.5 + y/4. The near plane z = 0 cuts at y = 2 (a top edge: row 2 is in) and the
// far plane z = w at y = 6 (a bottom edge: row 6 is out): rows 2..5 are drawn.
TEST_F(DeviceTest, NearAndFarPlanesClip) {
    make();
    const Vertex a{-1, 1, -0.5f, 1, 1, 1, 1, 1}, b{1, 1, -0.5f, 1, 1, 1, 1, 1}, c{-1, -1, 1.5f, 1, 1, 1, 1, 1},
        d{1, -1, 1.5f, 1, 1, 1, 1, 1};
    ASSERT_TRUE(draw(kTriangleStrip, 2, {a, b, c, d}));
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            ASSERT_EQ(pixel(x, y), y >= 2 && y <= 5 ? 0xFFFFFFFFu : 0xFF000000u) << x << "," << y;
    // D3DRS_CLIPPING FALSE: no near/far planes, every pixel is drawn (depth is clamped later).
    make();
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::Clipping), 0));
    ASSERT_TRUE(draw(kTriangleStrip, 2, {a, b, c, d}));
    EXPECT_EQ(count_pixels(0xFFFFFFFFu), 64u);
}

// A triangle with a vertex behind the eye: A (-1, 1, 0, 1), B (-1, -1, 0, 1), C (3, 0, 0, -1).
// Its part with w > 0 is cut at w = 2^-40 and never reaches the divide with w <= 0. A point
// aA + bB + cC lands at x = (3c - a - b)/(a + b - c), y = (a - b)/(a + b - c): for a = b, x runs
// from -1 (c = 0) to +infinity as c -> 2a, and the edges A-C and B-C leave the screen at the
// top and bottom (A-C passes (0, 1.5)). So the whole screen is covered; column 0 lies on the
// left edge A-B and is in by the top-left rule.
TEST_F(DeviceTest, TriangleCrossingWZero) {
    make();
    ASSERT_TRUE(draw(kTriangleList, 1, {{-1, 1, 0, 1, 1, 1, 1, 1}, {-1, -1, 0, 1, 1, 1, 1, 1}, {3, 0, 0, -1, 1, 1, 1, 1}}));
    EXPECT_EQ(count_pixels(0xFFFFFFFFu), 64u);
    // With C at (-3, 0, 0, -1) instead, x = (-2a - 3c)/(2a - c) runs from -1 to -infinity: the
    // visible part lies left of the screen and nothing is drawn.
    make();
    ASSERT_TRUE(draw(kTriangleList, 1, {{-1, 1, 0, 1, 1, 1, 1, 1}, {-1, -1, 0, 1, 1, 1, 1, 1}, {-3, 0, 0, -1, 1, 1, 1, 1}}));
    EXPECT_EQ(count_pixels(0xFFFFFFFFu), 0u);
}

// LESS keeps the first of two equal depths, LESSEQUAL lets the second through; a nearer
// triangle wins in either order.
TEST_F(DeviceTest, DepthCompare) {
    const std::vector<Vertex> red{{-1, 1, 0.5f, 1, 1, 0, 0, 1}, {3, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -3, 0.5f, 1, 1, 0, 0, 1}};
    std::vector<Vertex> blue = red;
    for (auto& v : blue) v.r = 0, v.b = 1;
    for (uint32_t func : {2u, 4u}) {  // LESS, LESSEQUAL
        make(8, 8, Format::D24S8);
        ASSERT_TRUE(device->clear(kClearZBuffer, 0, 1.0f, 0));
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::ZFunc), func));
        ASSERT_TRUE(draw(kTriangleList, 1, red));
        ASSERT_TRUE(draw(kTriangleList, 1, blue));
        EXPECT_EQ(count_pixels(func == 2 ? 0xFFFF0000u : 0xFF0000FFu), 64u) << func;
    }
    make(8, 8, Format::D16);
    ASSERT_TRUE(device->clear(kClearZBuffer, 0, 1.0f, 0));
    std::vector<Vertex> near_blue = blue;
    for (auto& v : near_blue) v.z = 0.25f;
    ASSERT_TRUE(draw(kTriangleList, 1, near_blue));
    ASSERT_TRUE(draw(kTriangleList, 1, red));
    EXPECT_EQ(count_pixels(0xFF0000FFu), 64u);
    EXPECT_EQ(device->depth_stencil("autodepth")->stored_depth(3, 3), 16384u);  // round(0.25 * 65535)
}

// SRCALPHA / INVSRCALPHA of (1, 1, 1, 0.25) over 0x80402010:
//   r = 0.25 + 0.75 * 64/255 = 0.438235 -> 111.75 -> 112 (0x70)
//   g = 0.25 + 0.75 * 32/255 -> 87.75 -> 88 (0x58);  b = 0.25 + 0.75 * 16/255 -> 75.75 -> 76 (0x4C)
//   a = 0.25 * 0.25 + 0.75 * 128/255 = 0.438971 -> 111.94 -> 112 (0x70)
TEST_F(DeviceTest, AlphaBlending) {
    make();
    ASSERT_TRUE(device->clear(kClearTarget, 0x80402010u, 1.0f, 0));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::AlphaBlendEnable), 1));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::SrcBlend), 5));   // SRCALPHA
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::DestBlend), 6));  // INVSRCALPHA
    const Vertex v{-1, 1, 0, 1, 1, 1, 1, 0.25f};
    ASSERT_TRUE(draw(kTriangleList, 1, {v, {3, 1, 0, 1, 1, 1, 1, 0.25f}, {-1, -3, 0, 1, 1, 1, 1, 0.25f}}));
    EXPECT_EQ(count_pixels(0x7070584Cu), 64u);
}

// Two render targets: oC0 and oC1 go to their own surfaces; COLORWRITEENABLE1 = red only keeps
// the cleared green/blue/alpha of target 1.
TEST_F(DeviceTest, MultipleRenderTargets) {
    make();
    ASSERT_TRUE(device->create_render_target("rt1", 8, 8, Format::A8R8G8B8));
    ASSERT_TRUE(device->set_render_target(1, "rt1"));
    ASSERT_TRUE(device->clear(kClearTarget, 0x11223344u, 1.0f, 0));
    ASSERT_TRUE(device->create_pixel_shader(
        "mrt", program("ps_2_0\ndef c0, 1, 0, 0, 1\ndef c1, 0, 0, 1, 0\nmov oC0, c0\nmov oC1, c1\n")));
    ASSERT_TRUE(device->set_pixel_shader("mrt"));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::ColorWriteEnable1), kWriteRed | kWriteBlue));
    ASSERT_TRUE(draw(kTriangleList, 1, {kTopLeftRed, {3, 1, 0, 1, 0, 0, 0, 0}, {-1, -3, 0, 1, 0, 0, 0, 0}}));
    EXPECT_EQ(pixel(5, 5), 0xFFFF0000u);
    EXPECT_EQ(pixel(5, 5, "rt1"), 0x110033FFu);  // r = 0 written, g kept 0x33, b = 1 written, a kept
}

// The scissor rectangle [2, 5) x [1, 3) keeps 3 x 2 pixels of a full-screen triangle.
TEST_F(DeviceTest, ScissorTest) {
    make();
    ASSERT_TRUE(device->set_scissor_rect(PixelRect{2, 1, 5, 3}));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::ScissorTestEnable), 1));
    ASSERT_TRUE(draw(kTriangleList, 1, {{-1, 1, 0, 1, 1, 1, 1, 1}, {3, 1, 0, 1, 1, 1, 1, 1}, {-1, -3, 0, 1, 1, 1, 1, 1}}));
    EXPECT_EQ(count_pixels(0xFFFFFFFFu), 6u);
    EXPECT_EQ(pixel(2, 1), 0xFFFFFFFFu);
    EXPECT_EQ(pixel(4, 2), 0xFFFFFFFFu);
    EXPECT_EQ(pixel(5, 2), 0xFF000000u);
}

// A point of size 1 centred on pixel (3, 3): clip x = 3/4 - 1 = -0.25, y = 1 - 3/4 = 0.25.
// The square [2.5, 3.5) x [2.5, 3.5) holds exactly one pixel centre.
TEST_F(DeviceTest, PointCoversItsPixel) {
    make();
    ASSERT_TRUE(draw(kPointList, 1, {{-0.25f, 0.25f, 0, 1, 0, 1, 0, 1}}));
    EXPECT_EQ(count_pixels(0xFF00FF00u), 1u);
    EXPECT_EQ(pixel(3, 3), 0xFF00FF00u);
}

// Indexed draw from buffers with BaseVertexIndex: indices 0,1,2 + base 1 read vertices 1..3.
TEST_F(DeviceTest, IndexedDrawWithBaseVertex) {
    make();
    const std::vector<Vertex> v{{9, 9, 9, 1, 0, 0, 0, 1}, kTopLeftRed, {1, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -1, 0.5f, 1, 1, 0, 0, 1}};
    ASSERT_TRUE(device->create_vertex_buffer("vb", static_cast<uint32_t>(v.size() * sizeof(Vertex))));
    ASSERT_TRUE(device->lock("vb", 0, bytes_of(v)));
    const std::array<uint16_t, 3> idx{0, 1, 2};
    ASSERT_TRUE(device->create_index_buffer("ib", 6, Format::INDEX16));
    ASSERT_TRUE(device->lock("ib", 0, std::as_bytes(std::span(idx))));
    ASSERT_TRUE(device->set_stream_source(0, "vb", 0, sizeof(Vertex)));
    ASSERT_TRUE(device->set_indices("ib"));
    ASSERT_TRUE(device->draw_indexed_primitive(kTriangleList, 1, 0, 3, 0, 1));
    EXPECT_EQ(count_pixels(0xFFFF0000u), 36u);
    EXPECT_EQ(device->statistics().vertices_shaded, 3u);
}

// Refused draws leave the target untouched and the device usable.
TEST_F(DeviceTest, RefusedDrawsChangeNothing) {
    make();
    const std::vector<Vertex> tri{kTopLeftRed, {1, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -1, 0.5f, 1, 1, 0, 0, 1}};
    EXPECT_FALSE(device->draw_primitive(kTriangleList, 0, 1));                  // stream 0 not set
    ASSERT_TRUE(device->create_vertex_buffer("small", 40));
    ASSERT_TRUE(device->set_stream_source(0, "small", 0, sizeof(Vertex)));
    const auto past = device->draw_primitive(kTriangleList, 0, 1);               // reads past the buffer
    EXPECT_FALSE(past);
    EXPECT_NE(past.error.find("DrawPrimitive"), std::string::npos);
    EXPECT_FALSE(device->draw_primitive(99, 0, 1));                              // bad type
    EXPECT_TRUE(draw(kTriangleList, 0, tri));                                    // zero primitives: a no-op (D3D_OK, as Wine)
    // No vertex shader: the fixed-function program, refused for a state the vertex cannot meet
    // (D3DVBF_TWEENING vertex blending without a second position).
    ASSERT_TRUE(device->set_vertex_shader(""));
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::VertexBlend), 255));
    const auto tweening = draw(kTriangleList, 1, tri);
    EXPECT_FALSE(tweening);
    EXPECT_NE(tweening.error.find("TWEENING: the declaration has no POSITION 1"), std::string::npos) << tweening.error;
    ASSERT_TRUE(device->set_render_state(rs(RenderStateType::VertexBlend), 0));
    ASSERT_TRUE(device->set_vertex_shader("vs"));
    ASSERT_TRUE(device->end_scene());
    EXPECT_FALSE(draw(kTriangleList, 1, tri));                                   // outside a scene
    EXPECT_EQ(count_pixels(0xFF000000u), 64u);
    ASSERT_TRUE(device->begin_scene());
    EXPECT_TRUE(draw(kTriangleList, 1, tri));
    EXPECT_EQ(count_pixels(0xFFFF0000u), 36u);
}

// Texturing through the whole pipeline: the LOD comes from the 2x2 quads the rasterizer makes.
// A full-screen quad maps u, v from 0 to 1 over 8 pixels, so a 32-texel texture steps 4 texels
// per pixel: lambda = log2(4) = 2. Each mip level is one solid colour; MIPFILTER POINT picks
// level 2 (blue). MIPMAPLODBIAS -1 gives level 1 (green); MAXMIPLEVEL 3 clamps to level 3 (white).
TEST_F(DeviceTest, MipLevelFromQuadDerivatives) {
    const std::array<uint32_t, 6> level_colors{0xFFFF0000u, 0xFF00FF00u, 0xFF0000FFu, 0xFFFFFFFFu, 0xFF808080u, 0xFF000000u};
    auto run = [&](uint32_t state, uint32_t value) {
        make();
        EXPECT_TRUE(device->create_texture("tex", 32, 32, 0, Format::A8R8G8B8));
        for (uint32_t level = 0; level < 6; ++level) {
            const uint32_t edge = 32u >> level;
            std::vector<uint32_t> texels(edge * edge, level_colors[level]);
            EXPECT_TRUE(device->lock_rect("tex", 0, level, std::as_bytes(std::span(texels))));
        }
        EXPECT_TRUE(device->create_pixel_shader(
            "ps_tex", program("ps_2_0\ndcl t0.xy\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\n")));
        EXPECT_TRUE(device->set_pixel_shader("ps_tex"));
        EXPECT_TRUE(device->set_texture(0, "tex"));
        for (uint32_t f : {5u, 6u, 7u}) EXPECT_TRUE(device->set_sampler_state(0, f, 1));  // MAG/MIN/MIP POINT
        if (state) {
            EXPECT_TRUE(device->set_sampler_state(0, state, value));
        }
        EXPECT_TRUE(draw(kTriangleStrip, 2, {{-1, 1, 0, 1, 0, 0, 0, 1}, {1, 1, 0, 1, 1, 0, 0, 1},
                                             {-1, -1, 0, 1, 0, 1, 0, 1}, {1, -1, 0, 1, 1, 1, 0, 1}}));
    };
    run(0, 0);
    EXPECT_EQ(count_pixels(0xFF0000FFu), 64u);
    float minus_one = -1.0f;
    uint32_t bias_bits = 0;
    std::memcpy(&bias_bits, &minus_one, 4);
    run(8, bias_bits);  // MIPMAPLODBIAS
    EXPECT_EQ(count_pixels(0xFF00FF00u), 64u);
    run(9, 3);  // MAXMIPLEVEL
    EXPECT_EQ(count_pixels(0xFFFFFFFFu), 64u);
}

// Extreme input through the whole pipeline: huge, tiny, infinite and NaN coordinates, w near
// and below 0, slivers. Nothing crashes, every draw is accepted, and no pixel outside the
// viewport [2, 6) x [3, 7) is ever touched.
TEST_F(DeviceTest, ExtremeCoordinatesStayInsideTheViewport) {
    make(10, 10, Format::D24S8);
    ASSERT_TRUE(device->set_viewport(Viewport{2, 3, 4, 4, 0.0f, 1.0f}));
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const std::array<float, 16> values{0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 1e30f, -1e30f, inf, -inf, nan,
                                       1e-45f, 3.4e38f, 0.999f, 2.0f, -7.5f};
    uint32_t seed = 12345;
    auto pick = [&] {
        seed = seed * 1664525u + 1013904223u;
        return values[(seed >> 16) % values.size()];
    };
    std::vector<Vertex> tris;
    for (int i = 0; i < 3 * 400; ++i) tris.push_back({pick(), pick(), pick(), pick(), pick(), pick(), pick(), 1});
    for (uint32_t clipping : {1u, 0u}) {
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::Clipping), clipping));
        ASSERT_TRUE(draw(kTriangleList, 400, tris));
        ASSERT_TRUE(draw(kPointList, 1200, tris));
        ASSERT_TRUE(draw(2 /* LINELIST */, 600, tris));
    }
    for (uint32_t y = 0; y < 10; ++y)
        for (uint32_t x = 0; x < 10; ++x)
            if (x < 2 || x >= 6 || y < 3 || y >= 7) {
                ASSERT_EQ(pixel(x, y), 0xFF000000u) << x << "," << y;
            }
}

// A texture sampled while it is the render target (undefined in D3D9) is read as it was before
// the draw, whatever the thread count. The target is cleared to red; each pixel samples its right
// neighbour's texel (u = (x + 1.5)/8, v = (y + 0.5)/8, point, wrap) and writes half of it: every
// pixel gets 0x80800000, none reads a neighbour already halved by this draw.
TEST_F(DeviceTest, RenderTargetSampledDuringItsOwnDrawReadsTheOldContents) {
    for (unsigned threads : {1u, 3u}) {
        make(8, 8, std::nullopt, threads);
        ASSERT_TRUE(device->create_texture("rtt", 8, 8, 1, Format::A8R8G8B8, true));
        ASSERT_TRUE(device->set_render_target(0, "rtt"));
        ASSERT_TRUE(device->clear(kClearTarget, 0xFFFF0000u, 1.0f, 0));
        ASSERT_TRUE(device->create_pixel_shader(
            "half", program("ps_2_0\ndef c0, 0.5, 0.5, 0.5, 0.5\ndcl t0.xy\ndcl_2d s0\ntexld r0, t0, s0\nmul r0, r0, c0\nmov oC0, r0\n")));
        ASSERT_TRUE(device->set_pixel_shader("half"));
        ASSERT_TRUE(device->set_texture(0, "rtt"));
        ASSERT_TRUE(draw(kTriangleStrip, 2, {{-1, 1, 0, 1, 1.5f / 8, 0.5f / 8, 0, 1}, {1, 1, 0, 1, 9.5f / 8, 0.5f / 8, 0, 1},
                                             {-1, -1, 0, 1, 1.5f / 8, 8.5f / 8, 0, 1}, {1, -1, 0, 1, 9.5f / 8, 8.5f / 8, 0, 1}}));
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) ASSERT_EQ(pixel(x, y, "rtt"), 0x80800000u) << x << "," << y << " threads " << threads;
    }
}

// Tiles are processed by any number of threads with identical bytes: a 100x70 target (4 x 3
// tiles, partial ones at the edges) full of overlapping blended triangles.
TEST_F(DeviceTest, ThreadCountDoesNotChangeTheImage) {
    std::vector<Vertex> tris;
    for (int i = 0; i < 40; ++i) {
        const float s = static_cast<float>(i) / 40.0f;
        tris.push_back({-1.2f + s, 1.1f - s, s, 1, s, 1 - s, 0.5f, 0.5f});
        tris.push_back({1.0f - s * 0.5f, 0.9f, 1 - s, 1, 0, s, 1, 0.5f});
        tris.push_back({-0.3f, -1.3f + s * 2, 0.5f, 1, 1, 0, s, 0.5f});
    }
    TexelBytes images[2];
    for (unsigned k = 0; k < 2; ++k) {
        make(100, 70, std::nullopt, k == 0 ? 1 : 3);
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::AlphaBlendEnable), 1));
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::SrcBlend), 5));
        ASSERT_TRUE(device->set_render_state(rs(RenderStateType::DestBlend), 6));
        ASSERT_TRUE(draw(kTriangleList, 40, tris));
        images[k] = device->surface("backbuffer")->bytes();
    }
    EXPECT_EQ(images[0], images[1]);
    EXPECT_GT(device->statistics().pixels_shaded, 1000u);
}

// The pipeline cache: a second identical draw builds nothing new; changing what the PS reads
// builds a new pair.
TEST_F(DeviceTest, PipelineCache) {
    make();
    const std::vector<Vertex> tri{kTopLeftRed, {1, 1, 0.5f, 1, 1, 0, 0, 1}, {-1, -1, 0.5f, 1, 1, 0, 0, 1}};
    ASSERT_TRUE(draw(kTriangleList, 1, tri));
    const auto built = device->statistics().pipelines_built;
    EXPECT_EQ(built, 2u);  // one vs, one ps
    ASSERT_TRUE(draw(kTriangleList, 1, tri));
    EXPECT_EQ(device->statistics().pipelines_built, built);
    ASSERT_TRUE(device->set_pixel_shader("ps_texcoord"));
    ASSERT_TRUE(draw(kTriangleList, 1, tri));
    EXPECT_EQ(device->statistics().pipelines_built, built + 2);  // vs now computes oT0, not oD0
}

}  // namespace
}  // namespace sm2::runtime
