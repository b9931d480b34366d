// Attribute interpolation (pipeline.md §6.4): screen-linear and perspective-correct values at
// D3D9 pixel centres, exact constants, depth linear in screen space, point-sprite coordinates,
// and the lane layout of a pixel batch.
#include <gtest/gtest.h>

#include "sm2/runtime/interpolation.h"

namespace sm2::runtime {
namespace {

// 16x16 viewport: screen X -> x = X/8 - 1, Y -> y = 1 - Y/8; the clip position is scaled by w.
ClipVertex at(double X, double Y, float z, float w) {
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

// Interpolates the single pixel (px, py) (as lane 0 or its place in the quad).
struct Probe {
    emu::Batch batch;
    PixelLanes lanes;
    unsigned lane = 0;
};
Probe probe(const PrimitiveSetup& p, int32_t px, int32_t py) {
    Probe r;
    const Quad q{px & ~1, py & ~1, 0xF};
    interpolate(p, std::span(&q, 1), kAllVaryings, r.batch, r.lanes);
    r.lane = static_cast<unsigned>((px & 1) + 2 * (py & 1));
    return r;
}

TEST(Interpolation, ScreenLinearWhenWIsConstant) {
    // (0,0) red 0, (8,0) red 1, (0,8) green 1; w = 2 everywhere (affine).
    ClipVertex a = at(0, 0, 0.25f, 2), b = at(8, 0, 0.25f, 2), c = at(0, 8, 0.25f, 2);
    b.varyings[kVaryingColor0] = {1, 0, 0, 1};
    c.varyings[kVaryingColor0] = {0, 1, 0, 1};
    a.varyings[kVaryingColor0][3] = 1;
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(a, b, c, a, state16(), p));
    EXPECT_FALSE(p.perspective);
    // Pixel (2, 3): b1 = 2/8 = 0.25 (red), b2 = 3/8 = 0.375 (green), alpha 1 everywhere.
    const auto r = probe(p, 2, 3);
    EXPECT_EQ(r.lanes.x[r.lane], 2);
    EXPECT_EQ(r.lanes.y[r.lane], 3);
    EXPECT_EQ(r.batch.input(0)[0][r.lane], 0.25f);
    EXPECT_EQ(r.batch.input(0)[1][r.lane], 0.375f);
    EXPECT_EQ(r.batch.input(0)[2][r.lane], 0.0f);
    EXPECT_EQ(r.batch.input(0)[3][r.lane], 1.0f);
    EXPECT_EQ(r.lanes.depth[r.lane], 0.25f);
}

TEST(Interpolation, PerspectiveCorrect) {
    // v0 at (0,0) with w = 1, v1 at (8,0) with w = 3, v2 at (0,8) with w = 1. Texcoord u = 0 at
    // v0, 1 at v1. At pixel (4, 0): screen b1 = 0.5, b2 = 0; rhw = (1, 1/3, 1):
    //   u = (0.5 * 1/3) / (0.5 * 1 + 0.5 * 1/3) = (1/6) / (2/3) = 0.25 (not the screen-linear 0.5).
    // Depth is linear in screen space: Zs 0 at v0, 1 at v1 -> 0.5.
    ClipVertex a = at(0, 0, 0, 1), b = at(8, 0, 1, 3), c = at(0, 8, 0, 1);
    b.varyings[kVaryingTexCoord0] = {1, 0, 0, 1};
    a.varyings[kVaryingTexCoord0] = {0, 0, 0, 1};
    c.varyings[kVaryingTexCoord0] = {0, 0, 0, 1};
    for (ClipVertex* v : {&a, &b, &c}) v->varyings[kVaryingTexCoord0 + 1] = {0.3f, -7, 1e6f, 1};
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(a, b, c, a, state16(), p));
    EXPECT_TRUE(p.perspective);
    const auto r = probe(p, 4, 0);
    EXPECT_FLOAT_EQ(r.batch.texcoord(0)[0][r.lane], 0.25f);
    EXPECT_EQ(r.lanes.depth[r.lane], 0.5f);
    // A constant attribute stays exact under perspective: a0 + b1'*0 + b2'*0.
    EXPECT_EQ(r.batch.texcoord(1)[0][r.lane], 0.3f);
    EXPECT_EQ(r.batch.texcoord(1)[1][r.lane], -7.0f);
    EXPECT_EQ(r.batch.texcoord(1)[2][r.lane], 1e6f);
    // At the vertices themselves: u(0,0) = 0; u(8,0) would be 1.
    EXPECT_EQ(probe(p, 0, 0).batch.texcoord(0)[0][0], 0.0f);
}

TEST(Interpolation, DepthBiasIsInTheDepth) {
    SetupState s = state16();
    s.depth_bias = 0.125f;
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(at(0, 0, 0.5f, 1), at(8, 0, 0.5f, 1), at(0, 8, 0.5f, 1), at(0, 0, 0, 1), s, p));
    EXPECT_EQ(probe(p, 1, 1).lanes.depth[3], 0.625f);  // 0.5 + 0.125
}

TEST(Interpolation, FogAndLaneLayout) {
    ClipVertex a = at(0, 0, 0.5f, 1), b = at(8, 0, 0.5f, 1), c = at(0, 8, 0.5f, 1);
    b.varyings[kVaryingFog] = {1, 0, 0, 1};  // fog 0 at v0 and v2, 1 at v1: fog = x / 8
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(a, b, c, a, state16(), p));
    const Quad quads[2] = {{2, 2, 0x9}, {4, 6, 0xF}};
    emu::Batch batch;
    PixelLanes lanes;
    interpolate(p, quads, kAllVaryings, batch, lanes);
    EXPECT_EQ(lanes.quad_count, 2u);
    EXPECT_EQ(batch.lane_count, 8u);
    EXPECT_EQ(lanes.coverage, 0x9u | 0xF0u);  // quad 0: lanes 0 and 3; quad 1: lanes 4..7
    // Lane 5 = quad 1 top-right = (5, 6); lane 6 = bottom-left = (4, 7).
    EXPECT_EQ(lanes.x[5], 5);
    EXPECT_EQ(lanes.y[5], 6);
    EXPECT_EQ(lanes.x[6], 4);
    EXPECT_EQ(lanes.y[6], 7);
    EXPECT_EQ(lanes.fog[5], 5.0f / 8);
    EXPECT_TRUE(lanes.clockwise);
}

TEST(Interpolation, PointSpriteCoordinates) {
    // Size 4 at (4, 4): the square [2, 6) x [2, 6); u = (px - 2) / 4, v = (py - 2) / 4.
    SetupState s = state16();
    s.point_size = 4.0f;
    s.point_sprite = true;
    ClipVertex v = at(4, 4, 0.5f, 1);
    v.varyings[kVaryingColor0] = {0.5f, 0.5f, 0.5f, 1};
    PrimitiveSetup p;
    ASSERT_TRUE(setup_point(v, s, p));
    auto r = probe(p, 3, 2);
    EXPECT_EQ(r.batch.texcoord(0)[0][r.lane], 0.25f);
    EXPECT_EQ(r.batch.texcoord(0)[1][r.lane], 0.0f);
    EXPECT_EQ(r.batch.texcoord(5)[0][r.lane], 0.25f);  // every t#
    EXPECT_EQ(r.batch.input(0)[0][r.lane], 0.5f);      // colours constant
    r = probe(p, 5, 5);
    EXPECT_EQ(r.batch.texcoord(0)[0][r.lane], 0.75f);
    EXPECT_EQ(r.batch.texcoord(0)[1][r.lane], 0.75f);
    // Without sprites every pixel gets the vertex's coordinates.
    s.point_sprite = false;
    v.varyings[kVaryingTexCoord0] = {0.1f, 0.2f, 0.3f, 0.4f};
    ASSERT_TRUE(setup_point(v, s, p));
    r = probe(p, 5, 5);
    EXPECT_EQ(r.batch.texcoord(0)[0][r.lane], 0.1f);
    EXPECT_EQ(r.batch.texcoord(0)[3][r.lane], 0.4f);
}

TEST(Interpolation, LinesAlongTheMajorAxis) {
    // (0, 0) colour 0 to (8, 2) colour 1, w = 1: t = x / 8 -> pixel (4, 1): 0.5.
    ClipVertex a = at(0, 0, 0.5f, 1), b = at(8, 2, 0.5f, 1);
    b.varyings[kVaryingColor1] = {1, 1, 1, 1};
    PrimitiveSetup p;
    ASSERT_TRUE(setup_line(a, b, a, state16(), p));
    const auto r = probe(p, 4, 1);
    EXPECT_EQ(r.batch.input(1)[0][r.lane], 0.5f);
}

}  // namespace
}  // namespace sm2::runtime
