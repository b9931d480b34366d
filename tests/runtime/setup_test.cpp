// Setup (pipeline.md §4, §5, §8): viewport transform and the D3D9 pixel centre, snapping,
// culling by screen-space winding, depth bias, flat shading, point sizes.
#include <gtest/gtest.h>

#include "sm2/runtime/setup.h"

namespace sm2::runtime {
namespace {

// A 16x16 viewport at the origin: screen X maps to clip x = X/8 - 1, Y to y = 1 - Y/8 (w = 1).
ClipVertex at(double X, double Y, float z = 0.5f, float w = 1.0f) {
    ClipVertex v;
    v.position = {static_cast<float>((X / 8.0 - 1.0) * w), static_cast<float>((1.0 - Y / 8.0) * w), z * w, w};
    return v;
}

SetupState state16() {
    SetupState s;
    s.viewport = {0, 0, 16, 16, 0.0f, 1.0f};
    s.clip_rect = {0, 0, 16, 16};
    s.cull = CullMode::None;
    return s;
}

TEST(Setup, ViewportTransformAndPixelCentres) {
    const Viewport vp{0, 0, 8, 8, 0.0f, 1.0f};
    // Xs = X + (x/w + 1) * W/2, Ys = Y + (1 - y/w) * H/2: (0, 0) -> the centre (4, 4).
    auto s = to_screen({0, 0, 0.5f, 1}, vp);
    EXPECT_EQ(s.x, 4.0);
    EXPECT_EQ(s.y, 4.0);
    EXPECT_EQ(s.z, 0.5);
    // (-1, 1) -> (0, 0): the centre of pixel (0, 0) in D3D9 (the target's corner is (-0.5, -0.5)).
    s = to_screen({-2, 2, 0, 2}, vp);
    EXPECT_EQ(s.x, 0.0);
    EXPECT_EQ(s.y, 0.0);
    EXPECT_EQ(s.rhw, 0.5);
    // Offset viewport (2, 3, 4, 2): (1, -1) -> (2 + 2*4/2, 3 + 2*2/2) = (6, 5).
    s = to_screen({1, -1, 0, 1}, Viewport{2, 3, 4, 2, 0.0f, 1.0f});
    EXPECT_EQ(s.x, 6.0);
    EXPECT_EQ(s.y, 5.0);
    // MinZ 0.25, MaxZ 0.75: Zs = 0.25 + z * 0.5; z = 1 -> 0.75, z = 0.5 -> 0.5.
    EXPECT_EQ(to_screen({0, 0, 1, 1}, Viewport{0, 0, 8, 8, 0.25f, 0.75f}).z, 0.75);
    EXPECT_EQ(to_screen({0, 0, 0.5f, 1}, Viewport{0, 0, 8, 8, 0.25f, 0.75f}).z, 0.5);
}

TEST(Setup, SnapsTo16Dot8WithRoundHalfEven) {
    EXPECT_EQ(snap(0.5), 128);
    EXPECT_EQ(snap(-1.25), -320);
    EXPECT_EQ(snap(1.0 / 512), 0);  // 0.5 steps -> 0 (even)
    EXPECT_EQ(snap(3.0 / 512), 2);  // 1.5 steps -> 2 (even)
    EXPECT_EQ(snap(1.0 / 256 * 0.49), 0);
}

TEST(Setup, CullingByScreenWinding) {
    // (0,0), (5,0), (5,5): area = 5*5 - 5*0 = 25 > 0, clockwise on screen.
    const ClipVertex a = at(0, 0), b = at(5, 0), c = at(5, 5);
    PrimitiveSetup p;
    SetupState s = state16();
    ASSERT_TRUE(setup_triangle(a, b, c, a, s, p));
    EXPECT_TRUE(p.clockwise);
    ASSERT_TRUE(setup_triangle(a, c, b, a, s, p));
    EXPECT_FALSE(p.clockwise);
    s.cull = CullMode::CW;  // culls clockwise
    EXPECT_FALSE(setup_triangle(a, b, c, a, s, p));
    EXPECT_TRUE(setup_triangle(a, c, b, a, s, p));
    s.cull = CullMode::CCW;  // the default: culls counter-clockwise
    EXPECT_TRUE(setup_triangle(a, b, c, a, s, p));
    EXPECT_FALSE(setup_triangle(a, c, b, a, s, p));
    // Zero area: nothing, even without culling.
    s.cull = CullMode::None;
    EXPECT_FALSE(setup_triangle(a, b, at(10, 0), a, s, p));
    // A sliver thinner than 1/256 pixel snaps to zero area.
    EXPECT_FALSE(setup_triangle(at(0, 0), at(8, 0), at(4, 0.001), a, s, p));
}

TEST(Setup, WindingForFillModes) {
    const Viewport vp{0, 0, 16, 16, 0, 1};
    EXPECT_EQ(screen_winding(at(0, 0), at(5, 0), at(5, 5), vp), true);
    EXPECT_EQ(screen_winding(at(0, 0), at(5, 5), at(5, 0), vp), false);
    EXPECT_EQ(screen_winding(at(0, 0), at(5, 5), at(10, 10), vp), std::nullopt);
    EXPECT_TRUE(culled(CullMode::CCW, false));
    EXPECT_FALSE(culled(CullMode::CCW, true));
    EXPECT_TRUE(culled(CullMode::CW, true));
    EXPECT_FALSE(culled(CullMode::None, true));
    EXPECT_FALSE(culled(CullMode::None, false));
}

TEST(Setup, PointAndWireframeFillModes) {
    // Clockwise (0,0),(8,0),(0,8) with Zs 0, 0.5, 0: bias = max(0.5/8, 0) * 2 = 0.125.
    ClipVertex tri[3] = {at(0, 0, 0), at(8, 0, 0.5f), at(0, 8, 0)};
    tri[1].varyings[kVaryingColor0] = {1, 1, 1, 1};
    SetupState s = state16();
    s.slope_scale_depth_bias = 2.0f;
    s.flat_shading = true;
    std::vector<PrimitiveSetup> out;
    EXPECT_EQ(setup_fill_mode(tri, tri[0], FillMode::Wireframe, s, out), 3u);
    ASSERT_EQ(out.size(), 3u);
    for (const PrimitiveSetup& p : out) {
        EXPECT_EQ(p.kind, CoverageKind::Line);
        EXPECT_TRUE(p.clockwise);
        EXPECT_EQ(p.depth_offset, 0.125);
        EXPECT_EQ(p.a0[kVaryingColor0], (Vec4{0, 0, 0, 0}));  // flat: the provoking vertex's
    }
    EXPECT_EQ(setup_fill_mode(tri, tri[0], FillMode::Point, s, out), 3u);
    EXPECT_EQ(out.back().kind, CoverageKind::Rectangle);
    EXPECT_EQ(out.back().a0[kVaryingColor0], (Vec4{0, 0, 0, 0}));
    // Culling applies in every fill mode: CW culls this triangle; CCW culls it reversed.
    s.cull = CullMode::CW;
    EXPECT_EQ(setup_fill_mode(tri, tri[0], FillMode::Wireframe, s, out), 0u);
    s.cull = CullMode::CCW;
    const ClipVertex reversed[3] = {tri[0], tri[2], tri[1]};
    EXPECT_EQ(setup_fill_mode(reversed, tri[0], FillMode::Point, s, out), 0u);
    EXPECT_EQ(setup_fill_mode(tri, tri[0], FillMode::Solid, s, out), 0u);
    // Degenerate: nothing.
    const ClipVertex flat_line[3] = {at(0, 0), at(4, 4), at(8, 8)};
    EXPECT_EQ(setup_fill_mode(flat_line, flat_line[0], FillMode::Wireframe, state16(), out), 0u);
}

TEST(Setup, OutsideClipRectangle) {
    SetupState s = state16();
    s.clip_rect = {8, 8, 16, 16};
    PrimitiveSetup p;
    EXPECT_FALSE(setup_triangle(at(0, 0), at(5, 0), at(5, 5), at(0, 0), s, p));
    EXPECT_TRUE(setup_triangle(at(0, 0), at(12, 0), at(12, 12), at(0, 0), s, p));
    EXPECT_EQ(p.bounds, (PixelRect{8, 8, 13, 13}));
}

TEST(Setup, DepthBias) {
    // Zs: 0 at (0,0), 0.5 at (4,0), 0 at (0,4): dZ/dX = 0.5/4 = 0.125, dZ/dY = 0, so
    // m = 0.125; SLOPESCALEDEPTHBIAS 2, DEPTHBIAS 0.25: offset = 0.125*2 + 0.25 = 0.5.
    SetupState s = state16();
    s.slope_scale_depth_bias = 2.0f;
    s.depth_bias = 0.25f;
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(at(0, 0, 0), at(4, 0, 0.5f), at(0, 4, 0), at(0, 0), s, p));
    EXPECT_EQ(p.depth_offset, 0.5);
    // Lines and points get no bias.
    ASSERT_TRUE(setup_line(at(0, 0, 0), at(4, 0, 0.5f), at(0, 0), s, p));
    EXPECT_EQ(p.depth_offset, 0.0);
    ASSERT_TRUE(setup_point(at(4, 4, 0.5f), s, p));
    EXPECT_EQ(p.depth_offset, 0.0);
}

TEST(Setup, FlatShadingTakesColoursFromTheProvokingVertex) {
    ClipVertex a = at(0, 0), b = at(8, 0), c = at(0, 8), prov = a;
    a.varyings[kVaryingColor0] = {1, 0, 0, 1};
    b.varyings[kVaryingColor0] = {0, 1, 0, 1};
    c.varyings[kVaryingColor0] = {0, 0, 1, 1};
    a.varyings[kVaryingTexCoord0] = {0, 0, 0, 1};
    b.varyings[kVaryingTexCoord0] = {1, 0, 0, 1};
    prov.varyings[kVaryingColor0] = {0.25f, 0.5f, 0.75f, 1};
    SetupState s = state16();
    s.flat_shading = true;
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(a, b, c, prov, s, p));
    EXPECT_EQ(p.a0[kVaryingColor0], (Vec4{0.25f, 0.5f, 0.75f, 1}));
    EXPECT_EQ(p.d1[kVaryingColor0], (Vec4{0, 0, 0, 0}));
    EXPECT_EQ(p.d2[kVaryingColor0], (Vec4{0, 0, 0, 0}));
    EXPECT_EQ(p.d1[kVaryingTexCoord0], (Vec4{1, 0, 0, 0}));  // texture coordinates stay smooth
}

TEST(Setup, PointSizeClamps) {
    SetupState s = state16();
    s.shader_point_size = true;
    s.point_size_min = 2.0f;
    s.point_size_max = 4.0f;
    ClipVertex v = at(8, 8);
    PrimitiveSetup p;
    v.point_size = 100.0f;  // clamped to 4: [6, 10) in 16.8 -> [1536, 2560)
    ASSERT_TRUE(setup_point(v, s, p));
    EXPECT_EQ(p.rect_left, 1536);
    EXPECT_EQ(p.rect_right, 2560);
    v.point_size = 0.5f;  // clamped up to 2: [7, 9)
    ASSERT_TRUE(setup_point(v, s, p));
    EXPECT_EQ(p.rect_left, 7 * 256);
    EXPECT_EQ(p.rect_bottom, 9 * 256);
    s.shader_point_size = false;  // POINTSIZE 1 -> clamped to the minimum 2
    s.point_size = 1.0f;
    ASSERT_TRUE(setup_point(v, s, p));
    EXPECT_EQ(p.rect_right - p.rect_left, 2 * 256);
    // Far outside the guard band: dropped without overflow.
    EXPECT_FALSE(setup_point(at(1e9, 8), s, p));
}

TEST(Setup, MakeSetupState) {
    RenderState rs;
    rs.scissor_test_enable = true;
    rs.shade_mode = ShadeMode::Flat;
    const SetupState s = make_setup_state(rs, Viewport{2, 2, 100, 100, 0, 1}, 64, 32, PixelRect{0, 0, 40, 20});
    // Viewport [2, 102) x [2, 102) ∩ target [0, 64) x [0, 32) ∩ scissor [0, 40) x [0, 20).
    EXPECT_EQ(s.clip_rect, (PixelRect{2, 2, 40, 20}));
    EXPECT_TRUE(s.flat_shading);
    EXPECT_EQ(s.cull, CullMode::CCW);
    rs.scissor_test_enable = false;
    EXPECT_EQ(make_setup_state(rs, Viewport{2, 2, 100, 100, 0, 1}, 64, 32, PixelRect{0, 0, 40, 20}).clip_rect,
              (PixelRect{2, 2, 64, 32}));
}

}  // namespace
}  // namespace sm2::runtime

#include <limits>
#include <random>
#include <vector>

#include "sm2/runtime/rasterizer.h"

namespace sm2::runtime {
namespace {

// Clip -> setup -> rasterize over random positions mixed with extreme values (huge, tiny w,
// negative w, NaN, infinities): nothing crashes, every pixel produced lies in the clip
// rectangle, and clipped vertices reaching setup have w > 0.
#ifndef SM2_EXTREME_ITERATIONS
#define SM2_EXTREME_ITERATIONS 3000
#endif
constexpr int kIterations = SM2_EXTREME_ITERATIONS;

TEST(Setup, ExtremePositionsNeverEscape) {
    std::mt19937 rng(12345);
    const float specials[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1e30f, -1e30f, 3.0e38f,
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN(), 1.0f, -1.0f, 0.5f};
    std::uniform_real_distribution<float> uni(-3.0f, 3.0f);
    std::uniform_int_distribution<int> pick(0, 19);
    auto value = [&]() {
        const int k = pick(rng);
        return k < 13 ? specials[k] : uni(rng);
    };
    SetupState s;
    s.viewport = {3, 5, 40, 30, 0.0f, 1.0f};
    s.clip_rect = {3, 5, 43, 35};
    s.cull = CullMode::None;
    ClipState cs;
    cs.guard = guard_band(s.viewport);
    size_t pixels = 0;
    for (int iteration = 0; iteration < kIterations; ++iteration) {
        std::array<ClipVertex, 3> v;
        for (auto& x : v) x.position = {value(), value(), value(), value()};
        cs.clipping = iteration % 3 != 0;
        ClippedPolygon poly;
        const ClipResult r = clip_triangle(v[0], v[1], v[2], cs, poly);
        std::vector<std::array<const ClipVertex*, 3>> tris;
        if (r == ClipResult::Inside) tris.push_back({&v[0], &v[1], &v[2]});
        if (r == ClipResult::Clipped)
            for (unsigned i = 1; i + 1 < poly.count; ++i)
                tris.push_back({&poly.vertices[0], &poly.vertices[i], &poly.vertices[i + 1]});
        for (const auto& t : tris) {
            for (const ClipVertex* x : t) ASSERT_GE(x->position[3], kMinClipW);
            PrimitiveSetup p;
            if (!setup_triangle(*t[0], *t[1], *t[2], *t[0], s, p)) continue;
            std::vector<Quad> quads;
            rasterize(p, s.clip_rect, quads);
            for (const Quad& q : quads)
                for (unsigned i = 0; i < 4; ++i)
                    if (q.mask >> i & 1u) {
                        const int32_t x = q.x + static_cast<int32_t>(i & 1u), y = q.y + static_cast<int32_t>(i >> 1);
                        ASSERT_TRUE(x >= 3 && x < 43 && y >= 5 && y < 35);
                        ++pixels;
                    }
        }
        // Lines and points through the same values.
        std::array<ClipVertex, 2> line;
        PrimitiveSetup p;
        if (clip_line(v[0], v[1], cs, line) != ClipResult::Outside && setup_line(line[0], line[1], line[0], s, p)) {
            std::vector<Quad> quads;
            rasterize(p, s.clip_rect, quads);
        }
        s.shader_point_size = iteration % 2 == 0;
        v[2].point_size = value();
        if (point_visible(v[2], cs) && setup_point(v[2], s, p)) {
            std::vector<Quad> quads;
            rasterize(p, s.clip_rect, quads);
            // At most the clip rectangle's quads: x 3..42 -> quads at 2..42 (21), y 5..34 -> 4..34 (16).
            EXPECT_LE(quads.size(), 21u * 16u);
        }
    }
    EXPECT_GT(pixels, 0u);
}

}  // namespace
}  // namespace sm2::runtime
