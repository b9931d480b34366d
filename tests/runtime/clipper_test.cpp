// The clipper (pipeline.md §3): near/far planes, triangles crossing w = 0, user clip planes, the
// guard band, lines and points. New vertices are derived by hand from t = d_in / (d_in - d_out).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sm2/runtime/clipper.h"

namespace sm2::runtime {
namespace {

ClipVertex vert(float x, float y, float z, float w, float red = 0.0f) {
    ClipVertex v;
    v.position = {x, y, z, w};
    v.varyings[kVaryingColor0] = {red, 0.0f, 0.0f, 1.0f};
    return v;
}

ClipState state_8x8() {
    ClipState s;
    s.guard = guard_band(Viewport{0, 0, 8, 8, 0.0f, 1.0f});
    return s;
}

TEST(Clipper, GuardBand) {
    // K = min(1 + (X + 16384) / (W/2), (16384 - X) / (W/2) - 1), floored, at least 1.
    // 8x8 at 0: min(1 + 4096, 4096 - 1) = 4095.
    EXPECT_EQ(guard_band(Viewport{0, 0, 8, 8, 0, 1}).x, 4095.0f);
    // 640x480: x min(52.2, 50.2) -> 50; y min(69.27, 67.27) -> 67.
    const auto g = guard_band(Viewport{0, 0, 640, 480, 0, 1});
    EXPECT_EQ(g.x, 50.0f);
    EXPECT_EQ(g.y, 67.0f);
    EXPECT_EQ(guard_band(Viewport{0, 0, 0, 0, 0, 1}).x, 1.0f);
    EXPECT_EQ(guard_band(Viewport{0, 0, 16384, 16384, 0, 1}).x, 1.0f);
}

TEST(Clipper, InsideTriangleIsUntouched) {
    ClippedPolygon out;
    EXPECT_EQ(clip_triangle(vert(0, 0, 0.5f, 1), vert(1, 0, 0.5f, 1), vert(0, 1, 1, 1), state_8x8(), out),
              ClipResult::Inside);
    // Beyond the viewport's x/y but inside the guard band: no clipping (the rasterizer trims).
    EXPECT_EQ(clip_triangle(vert(-3, 0, 0.5f, 1), vert(5, 0, 0.5f, 1), vert(0, 9, 0.5f, 1), state_8x8(), out),
              ClipResult::Inside);
}

TEST(Clipper, NearPlane) {
    // Near-plane distances d = z: A -1 (out), B 1, C 1.
    // Edge A->B: from B towards A, t = 1 / (1 + 1) = 0.5: (0, 0.5, 0, 1), red 0.5.
    // Edge C->A: from C towards A, t = 0.5: (0.5, 0, 0, 1), red 0.5.
    // Output order: [AB, B, C, CA].
    ClippedPolygon out;
    ASSERT_EQ(clip_triangle(vert(0, 0, -1, 1, 0), vert(0, 1, 1, 1, 1), vert(1, 0, 1, 1, 1), state_8x8(), out),
              ClipResult::Clipped);
    ASSERT_EQ(out.count, 4u);
    EXPECT_EQ(out.vertices[0].position, (Vec4{0, 0.5f, 0, 1}));
    EXPECT_EQ(out.vertices[0].varyings[kVaryingColor0][0], 0.5f);
    EXPECT_EQ(out.vertices[1].position, (Vec4{0, 1, 1, 1}));
    EXPECT_EQ(out.vertices[2].position, (Vec4{1, 0, 1, 1}));
    EXPECT_EQ(out.vertices[3].position, (Vec4{0.5f, 0, 0, 1}));
    EXPECT_EQ(out.vertices[3].varyings[kVaryingColor0][0], 0.5f);
}

TEST(Clipper, FarPlane) {
    // Far distance w - z: A = (0, 0, 3, 2) -> -1 (out), B = (0, 1, 1, 2) and C -> 1. t = 0.5:
    // the midpoint of B and A is (0, 0.5, 2, 2), on the plane z = w; likewise C-A -> (0.5, 0, 2, 2).
    ClippedPolygon out;
    ASSERT_EQ(clip_triangle(vert(0, 0, 3, 2), vert(0, 1, 1, 2), vert(1, 0, 1, 2), state_8x8(), out),
              ClipResult::Clipped);
    ASSERT_EQ(out.count, 4u);
    EXPECT_EQ(out.vertices[0].position, (Vec4{0, 0.5f, 2, 2}));
    EXPECT_EQ(out.vertices[3].position, (Vec4{0.5f, 0, 2, 2}));
}

TEST(Clipper, SharedEdgeGivesIdenticalVertices) {
    // Two triangles share the edge P-Q that crosses the near plane; walking the edge in either
    // direction gives the same new vertex bit for bit.
    const ClipVertex p = vert(0.1f, 0.2f, -0.3f, 1.1f, 0.7f), q = vert(0.9f, -0.4f, 0.8f, 1.3f, 0.1f);
    ClippedPolygon a, b;
    ASSERT_EQ(clip_triangle(p, q, vert(0, 1, 0.5f, 1), state_8x8(), a), ClipResult::Clipped);
    ASSERT_EQ(clip_triangle(q, p, vert(1, 1, 0.5f, 1), state_8x8(), b), ClipResult::Clipped);
    auto find_on_plane = [](const ClippedPolygon& poly) {
        for (unsigned i = 0; i < poly.count; ++i)
            if (poly.vertices[i].position[2] == 0.0f && poly.vertices[i].position[0] > 0.1f) return poly.vertices[i];
        return ClipVertex{};
    };
    const ClipVertex va = find_on_plane(a), vb = find_on_plane(b);
    EXPECT_EQ(va.position, vb.position);
    EXPECT_EQ(va.varyings[kVaryingColor0], vb.varyings[kVaryingColor0]);
    EXPECT_NE(va.position[3], 0.0f);
}

TEST(Clipper, TriangleCrossingWZero) {
    // B is behind the eye (w = -1). Along A -> B: z = 0.5 - 2.5t, w = 1 - 2t, x = t. The visible
    // part ends where z = 0: t = 0.2 -> (0.2, 0, 0, 0.6). Along C -> B: x = t, y = 1 - t,
    // z = 0.5 - 2.5t, w = 1 - 2t: t = 0.2 -> (0.2, 0.8, 0, 0.6).
    ClippedPolygon out;
    ASSERT_EQ(clip_triangle(vert(0, 0, 0.5f, 1), vert(1, 0, -2, -1), vert(0, 1, 0.5f, 1), state_8x8(), out),
              ClipResult::Clipped);
    ASSERT_EQ(out.count, 4u);
    bool found_ab = false, found_cb = false;
    for (unsigned i = 0; i < out.count; ++i) {
        const Vec4& p = out.vertices[i].position;
        EXPECT_GT(p[3], 0.0f);
        EXPECT_GE(p[2], 0.0f);
        EXPECT_LE(p[2], p[3]);
        if (std::fabs(p[0] - 0.2f) < 1e-6f && std::fabs(p[1]) < 1e-6f) {
            found_ab = true;
            EXPECT_NEAR(p[3], 0.6f, 1e-6f);
            EXPECT_EQ(p[2], 0.0f);  // set exactly onto the near plane
        }
        if (std::fabs(p[0] - 0.2f) < 1e-6f && std::fabs(p[1] - 0.8f) < 1e-6f) found_cb = true;
    }
    EXPECT_TRUE(found_ab);
    EXPECT_TRUE(found_cb);
}

TEST(Clipper, WPlaneEvenWithClippingOff) {
    // CLIPPING FALSE drops near/far/user planes, but w > 0 and the guard band stay: no vertex
    // reaching the divide has w <= 0.
    ClipState s = state_8x8();
    s.clipping = false;
    ClippedPolygon out;
    ASSERT_EQ(clip_triangle(vert(0, 0, 0.5f, 1), vert(1, 0, -2, -1), vert(0, 1, 0.5f, 1), s, out),
              ClipResult::Clipped);
    for (unsigned i = 0; i < out.count; ++i) EXPECT_GE(out.vertices[i].position[3], kMinClipW);
    // Near plane off: z < 0 is kept.
    EXPECT_EQ(clip_triangle(vert(0, 0, -1, 1), vert(1, 0, -1, 1), vert(0, 1, -1, 1), s, out), ClipResult::Inside);
}

TEST(Clipper, UserClipPlane) {
    // Plane (1, 0, 0, 0) keeps x >= 0. Distances A -1, B 1, C 1; t = 0.5 on both cut edges:
    // AB -> (0, 0, 0.5, 1), CA -> (0, 0.5, 0.5, 1).
    ClipState s = state_8x8();
    s.user_plane_enable = 1u << 2;
    s.user_planes[2] = {1, 0, 0, 0};
    ClippedPolygon out;
    const ClipVertex a = vert(-1, 0, 0.5f, 1), b = vert(1, 0, 0.5f, 1), c = vert(1, 1, 0.5f, 1);
    ASSERT_EQ(clip_triangle(a, b, c, s, out), ClipResult::Clipped);
    ASSERT_EQ(out.count, 4u);
    EXPECT_EQ(out.vertices[0].position, (Vec4{0, 0, 0.5f, 1}));
    EXPECT_EQ(out.vertices[1].position, b.position);
    EXPECT_EQ(out.vertices[2].position, c.position);
    EXPECT_EQ(out.vertices[3].position, (Vec4{0, 0.5f, 0.5f, 1}));
    // Disabled bit, or CLIPPING FALSE: no clipping.
    s.user_plane_enable = 1u << 3;
    EXPECT_EQ(clip_triangle(a, b, c, s, out), ClipResult::Inside);
    s.user_plane_enable = 1u << 2;
    s.clipping = false;
    EXPECT_EQ(clip_triangle(a, b, c, s, out), ClipResult::Inside);
    // Every vertex outside: nothing left.
    s.clipping = true;
    s.user_planes[2] = {-1, 0, 0, -2};  // keeps x <= -2
    EXPECT_EQ(clip_triangle(a, b, c, s, out), ClipResult::Outside);
}

TEST(Clipper, OutsideAndNonFinite) {
    ClippedPolygon out;
    EXPECT_EQ(clip_triangle(vert(0, 0, -1, 1), vert(1, 0, -1, 1), vert(0, 1, -2, 1), state_8x8(), out),
              ClipResult::Outside);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(clip_triangle(vert(nan, 0, 0.5f, 1), vert(1, 0, 0.5f, 1), vert(0, 1, 0.5f, 1), state_8x8(), out),
              ClipResult::Outside);
    EXPECT_EQ(clip_triangle(vert(0, 0, 0.5f, inf), vert(1, 0, 0.5f, 1), vert(0, 1, 0.5f, 1), state_8x8(), out),
              ClipResult::Outside);
    // Huge coordinates far outside the guard band on one side: clipped to it, not overflowing.
    ASSERT_EQ(clip_triangle(vert(0, 0, 0.5f, 1), vert(1e30f, 0, 0.5f, 1), vert(0, 1, 0.5f, 1), state_8x8(), out),
              ClipResult::Clipped);
    for (unsigned i = 0; i < out.count; ++i) EXPECT_LE(out.vertices[i].position[0], 4095.0f * out.vertices[i].position[3]);
}

TEST(Clipper, WNearZero) {
    // Every w below 2^-40: nothing is left. One tiny w: cut where w = 2^-40, never below.
    ClippedPolygon out;
    EXPECT_EQ(clip_triangle(vert(0, 0, 0, 1e-20f), vert(0, 0, 0, 0), vert(0, 0, 0, 1e-15f), state_8x8(), out),
              ClipResult::Outside);
    ASSERT_EQ(clip_triangle(vert(0, 0, 0, 1e-20f), vert(1, 0, 0.5f, 1), vert(0, 1, 0.5f, 1), state_8x8(), out),
              ClipResult::Clipped);
    for (unsigned i = 0; i < out.count; ++i) EXPECT_GE(out.vertices[i].position[3], kMinClipW);
}

TEST(Clipper, Lines) {
    // A (z = -1) to B (z = 1): A moves to the midpoint (0, 0, 0, 1).
    std::array<ClipVertex, 2> out;
    ASSERT_EQ(clip_line(vert(0, 0, -1, 1, 0), vert(0, 0, 1, 1, 1), state_8x8(), out), ClipResult::Clipped);
    EXPECT_EQ(out[0].position, (Vec4{0, 0, 0, 1}));
    EXPECT_EQ(out[0].varyings[kVaryingColor0][0], 0.5f);
    EXPECT_EQ(out[1].position, (Vec4{0, 0, 1, 1}));
    EXPECT_EQ(clip_line(vert(0, 0, 0.5f, 1), vert(1, 1, 0.5f, 1), state_8x8(), out), ClipResult::Inside);
    EXPECT_EQ(clip_line(vert(0, 0, -1, 1), vert(1, 1, -0.5f, 1), state_8x8(), out), ClipResult::Outside);
}

TEST(Clipper, Points) {
    EXPECT_TRUE(point_visible(vert(0, 0, 0.5f, 1), state_8x8()));
    EXPECT_FALSE(point_visible(vert(0, 0, -0.5f, 1), state_8x8()));   // in front of the near plane
    EXPECT_FALSE(point_visible(vert(0, 0, 1.5f, 1), state_8x8()));    // beyond far
    EXPECT_FALSE(point_visible(vert(0, 0, 0, 0), state_8x8()));       // w = 0
    EXPECT_TRUE(point_visible(vert(1.2f, 0, 0.5f, 1), state_8x8()));  // x/y: the rasterizer trims
}

TEST(Clipper, VertexFromBatchSaturatesColours) {
    emu::Batch batch;
    batch.set(batch.position(), 3, 1, 2, 3, 4);
    batch.set(batch.color_out(0), 3, 1.5f, -0.5f, 0.25f, std::numeric_limits<float>::quiet_NaN());
    batch.set(batch.texcoord_out(7), 3, 5, -6, 7, 8);
    batch.set(batch.fog(), 3, 0.75f, 0, 0, 0);
    batch.set(batch.point_size(), 3, 9, 0, 0, 0);
    const ClipVertex v = vertex_from_batch(batch, 3, true);
    EXPECT_EQ(v.position, (Vec4{1, 2, 3, 4}));
    EXPECT_EQ(v.varyings[kVaryingColor0], (Vec4{1, 0, 0.25f, 0}));
    EXPECT_EQ(v.varyings[kVaryingTexCoord0 + 7], (Vec4{5, -6, 7, 8}));  // not saturated
    EXPECT_EQ(v.varyings[kVaryingFog][0], 0.75f);
    EXPECT_EQ(v.point_size, 9.0f);
    EXPECT_EQ(vertex_from_batch(batch, 3, false).point_size, 0.0f);
}

}  // namespace
}  // namespace sm2::runtime
