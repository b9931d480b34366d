// Attribute interpolation (pipeline.md §6.4): screen-linear and perspective-correct values at
// D3D9 pixel centres, exact constants, depth linear in screen space, point-sprite coordinates,
// and the lane layout of a pixel batch.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>

#include <vector>

#include <cstdio>

#include <cmath>

#include "sm2/runtime/interpolation.h"
#include "sm2/runtime/rasterizer.h"
#include "sm2/runtime/setup.h"

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

// Accuracy (issue 13): a 128x128 target, a quad of two triangles whose vertices lie between
// the 1/256-pixel snapping points, with w from 1 (left) to w_far (right) and a texture
// coordinate u from 0 (left) to 1 (right). At every covered pixel centre the interpolated u
// must be within 1e-6 relative (or 4 ulp) of the exact perspective-correct value, worked out
// here from the same float clip positions in long double: the screen barycentrics (l0, l1, l2)
// of the centre, then u = sum(li ui / wi) / sum(li / wi).
void expect_exact_perspective(float w_far) {
    SetupState state;
    state.viewport = {0, 0, 128, 128, 0.0f, 1.0f};
    state.clip_rect = {0, 0, 128, 128};
    state.cull = CullMode::None;
    // Screen corners (not on the 1/256 grid) and their w and u.
    const double sx[4] = {0.3711, 127.6289, 127.1093, 0.8007}, sy[4] = {0.2093, 3.1417, 124.7771, 127.5311};
    const float w[4] = {1.0f, w_far, w_far, 1.0f}, u[4] = {0.0f, 1.0f, 1.0f, 0.0f};
    ClipVertex v[4];
    for (int i = 0; i < 4; ++i) {
        v[i].position = {static_cast<float>((sx[i] / 64.0 - 1.0) * w[i]), static_cast<float>((1.0 - sy[i] / 64.0) * w[i]),
                         0.5f * w[i], w[i]};
        v[i].varyings[kVaryingTexCoord0] = {u[i], 0, 0, 1};
    }
    // The screen position sm2 derives from a float clip position (to_screen), in long double.
    auto screen = [](const ClipVertex& c, long double& x, long double& y) {
        x = (static_cast<long double>(c.position[0]) / c.position[3] + 1.0L) * 64.0L;
        y = (1.0L - static_cast<long double>(c.position[1]) / c.position[3]) * 64.0L;
    };
    const int triangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
    size_t checked = 0;
    double worst = 0;
    for (const auto& t : triangles) {
        PrimitiveSetup p;
        ASSERT_TRUE(setup_triangle(v[t[0]], v[t[1]], v[t[2]], v[t[0]], state, p));
        ASSERT_TRUE(p.perspective);
        long double X[3], Y[3];
        for (int i = 0; i < 3; ++i) screen(v[t[i]], X[i], Y[i]);
        std::vector<Quad> quads;
        rasterize(p, PixelRect{0, 0, 128, 128}, quads);
        for (size_t first = 0; first < quads.size(); first += emu::kBatchQuads) {
            const size_t n = std::min<size_t>(emu::kBatchQuads, quads.size() - first);
            emu::Batch batch;
            PixelLanes lanes;
            interpolate(p, std::span(quads).subspan(first, n), kAllVaryings, batch, lanes);
            for (unsigned lane = 0; lane < 4 * n; ++lane) {
                if (!(lanes.coverage >> lane & 1u)) continue;
                const long double px = lanes.x[lane], py = lanes.y[lane];
                const long double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
                const long double l1 = ((px - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (py - Y[0])) / area;
                const long double l2 = ((X[1] - X[0]) * (py - Y[0]) - (px - X[0]) * (Y[1] - Y[0])) / area;
                const long double l[3] = {1.0L - l1 - l2, l1, l2};
                long double num = 0, den = 0;
                for (int i = 0; i < 3; ++i) {
                    num += l[i] * u[t[i]] / w[t[i]];
                    den += l[i] / w[t[i]];
                }
                const double exact = static_cast<double>(num / den);
                const float got = batch.texcoord(0)[0][lane];
                const double error = std::fabs(got - exact);
                const double ulp = std::nextafter(static_cast<float>(std::fabs(exact)), INFINITY) - static_cast<float>(std::fabs(exact));
                EXPECT_TRUE(error <= 1e-6 * std::fabs(exact) || error <= 4 * ulp)
                    << "w 1.." << w_far << " pixel (" << lanes.x[lane] << ", " << lanes.y[lane] << "): " << got
                    << " against " << exact;
                worst = std::max(worst, exact != 0 ? error / std::fabs(exact) : 0.0);
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 15000u);  // nearly all 128 x 128 centres
    std::printf("w 1..%g: %zu centres, worst relative error %.3g\n", static_cast<double>(w_far), checked, worst);
}

TEST(Interpolation, ExactPerspectiveAtPixelCentresForW1To4) { expect_exact_perspective(4.0f); }
TEST(Interpolation, ExactPerspectiveAtPixelCentresForW1To100) { expect_exact_perspective(100.0f); }

// The AVX-512 code and the portable loops (reference = true) give the same bits for every
// lane's depth, fog and varyings: random triangles with random w (perspective) or one w
// (affine), depth bias, every batch of their quads.
TEST(Interpolation, VectorCodeGivesThePortableLoopsBits) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> position(-20.0f, 36.0f), value(-4.0f, 4.0f), depth(0.0f, 1.0f);
    size_t lanes_compared = 0;
    for (unsigned round = 0; round < 300; ++round) {
        const bool affine = round % 3 == 0;
        std::array<ClipVertex, 3> v;
        for (ClipVertex& c : v) {
            const float w = affine ? 2.0f : std::uniform_real_distribution<float>(0.05f, 50.0f)(rng);
            c = at(position(rng), position(rng), depth(rng), w);
            for (auto& varying : c.varyings)
                for (float& x : varying) x = value(rng);
        }
        SetupState s = state16();
        s.depth_bias = round % 4 == 0 ? 0.0625f : 0.0f;
        PrimitiveSetup p;
        if (!setup_triangle(v[0], v[1], v[2], v[0], s, p)) continue;
        EXPECT_EQ(p.perspective, !affine);
        std::vector<Quad> quads;
        rasterize(p, PixelRect{0, 0, 16, 16}, quads);
        for (size_t first = 0; first < quads.size(); first += emu::kBatchQuads) {
            const size_t n = std::min<size_t>(emu::kBatchQuads, quads.size() - first);
            emu::Batch fast, portable;
            PixelLanes fast_lanes, portable_lanes;
            interpolate(p, std::span(quads).subspan(first, n), kAllVaryings, fast, fast_lanes, false);
            interpolate(p, std::span(quads).subspan(first, n), kAllVaryings, portable, portable_lanes, true);
            // A draw that reads no depth (depth = false): the depth left as it was, everything
            // else the same bits.
            emu::Batch depthless;
            PixelLanes depthless_lanes;
            depthless_lanes.depth.fill(std::bit_cast<float>(0x7FC0DEADu));
            interpolate(p, std::span(quads).subspan(first, n), kAllVaryings, depthless, depthless_lanes, round % 2 == 0, false);
            for (unsigned lane = 0; lane < 4 * n; ++lane) {
                ASSERT_EQ(std::bit_cast<uint32_t>(fast_lanes.depth[lane]), std::bit_cast<uint32_t>(portable_lanes.depth[lane]));
                ASSERT_EQ(std::bit_cast<uint32_t>(depthless_lanes.depth[lane]), 0x7FC0DEADu);
                ASSERT_EQ(std::bit_cast<uint32_t>(depthless_lanes.fog[lane]), std::bit_cast<uint32_t>(fast_lanes.fog[lane]));
                for (unsigned t = 0; t < 8; ++t)
                    for (unsigned c = 0; c < 4; ++c)
                        ASSERT_EQ(std::bit_cast<uint32_t>(depthless.texcoord(t)[c][lane]), std::bit_cast<uint32_t>(fast.texcoord(t)[c][lane]));
                ASSERT_EQ(std::bit_cast<uint32_t>(fast_lanes.fog[lane]), std::bit_cast<uint32_t>(portable_lanes.fog[lane]));
                for (unsigned r = 0; r < 2; ++r)
                    for (unsigned c = 0; c < 4; ++c)
                        ASSERT_EQ(std::bit_cast<uint32_t>(fast.input(r)[c][lane]), std::bit_cast<uint32_t>(portable.input(r)[c][lane]))
                            << "v" << r << " component " << c << " lane " << lane << " round " << round;
                for (unsigned t = 0; t < 8; ++t)
                    for (unsigned c = 0; c < 4; ++c)
                        ASSERT_EQ(std::bit_cast<uint32_t>(fast.texcoord(t)[c][lane]), std::bit_cast<uint32_t>(portable.texcoord(t)[c][lane]))
                            << "t" << t << " component " << c << " lane " << lane << " round " << round;
                ++lanes_compared;
            }
        }
    }
    EXPECT_GT(lanes_compared, 10000u);
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
