// The rasterizer (pipeline.md §6): the top-left rule on shared edges, D3D9 pixel centres,
// scissor, tiles and quads, points and lines. Every expected pixel set is derived by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "sm2/runtime/rasterizer.h"

namespace sm2::runtime {
namespace {

using Pixel = std::pair<int32_t, int32_t>;  // (x, y)

// A 32x32 viewport at the origin: screen X -> clip x = X/16 - 1, Y -> y = 1 - Y/16 (w = 1).
ClipVertex at(double X, double Y) {
    ClipVertex v;
    v.position = {static_cast<float>(X / 16.0 - 1.0), static_cast<float>(1.0 - Y / 16.0), 0.5f, 1.0f};
    return v;
}

SetupState state32() {
    SetupState s;
    s.viewport = {0, 0, 32, 32, 0.0f, 1.0f};
    s.clip_rect = {0, 0, 32, 32};
    s.cull = CullMode::None;
    return s;
}

std::set<Pixel> pixels_of(const PrimitiveSetup& p, const PixelRect& region = {0, 0, 32, 32}, bool portable = false) {
    std::vector<Quad> quads;
    rasterize(p, region, quads, portable);
    std::set<Pixel> out;
    for (const Quad& q : quads) {
        EXPECT_EQ(q.x % 2, 0);
        EXPECT_EQ(q.y % 2, 0);
        EXPECT_NE(q.mask, 0);
        for (unsigned i = 0; i < 4; ++i)
            if (q.mask >> i & 1u) {
                const Pixel px{q.x + static_cast<int32_t>(i & 1u), q.y + static_cast<int32_t>(i >> 1)};
                EXPECT_TRUE(out.insert(px).second) << "pixel twice";
                EXPECT_TRUE(covers(p, px.first, px.second));
            }
    }
    return out;
}

std::set<Pixel> triangle(double x0, double y0, double x1, double y1, double x2, double y2,
                         SetupState s = state32()) {
    PrimitiveSetup p;
    if (!setup_triangle(at(x0, y0), at(x1, y1), at(x2, y2), at(x0, y0), s, p)) return {};
    return pixels_of(p);
}

TEST(Rasterizer, TopLeftRuleDocsExample) {
    // (0,0),(5,0),(5,5): top edge y = 0 in, right edge x = 5 out, diagonal x = y is a left edge
    // (goes up) so in: rows y = 0..4 hold x = y..4 -> 5+4+3+2+1 = 15 pixels.
    const auto upper = triangle(0, 0, 5, 0, 5, 5);
    EXPECT_EQ(upper.size(), 15u);
    // (0,5),(0,0),(5,5): left edge x = 0 in, bottom y = 5 out, diagonal (going down, right of
    // the interior) out: rows y = 1..4 hold x = 0..y-1 -> 1+2+3+4 = 10 pixels.
    const auto lower = triangle(0, 5, 0, 0, 5, 5);
    EXPECT_EQ(lower.size(), 10u);
    // Together: the 5x5 square, each pixel exactly once.
    std::set<Pixel> both = upper;
    for (const Pixel& p : lower) EXPECT_TRUE(both.insert(p).second) << p.first << "," << p.second;
    EXPECT_EQ(both.size(), 25u);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_TRUE(both.count({x, y}));
    EXPECT_TRUE(upper.count({4, 0}) && upper.count({0, 0}) && upper.count({4, 4}) && !upper.count({0, 1}));
    // Winding does not change coverage.
    EXPECT_EQ(triangle(0, 0, 5, 5, 5, 0), upper);
}

TEST(Rasterizer, FanAroundAPointCoversEachPixelOnce) {
    // Eight triangles fanned around (8, 8) to the boundary of the square [4, 12]: shared edges
    // in eight directions (horizontal, vertical, both diagonals, both ways).
    const double c = 8, lo = 4, hi = 12;
    const double ring[8][2] = {{lo, lo}, {c, lo}, {hi, lo}, {hi, c}, {hi, hi}, {c, hi}, {lo, hi}, {lo, c}};
    std::map<Pixel, int> count;
    for (int i = 0; i < 8; ++i) {
        const auto* a = ring[i];
        const auto* b = ring[(i + 1) % 8];
        for (const Pixel& p : triangle(c, c, a[0], a[1], b[0], b[1])) ++count[p];
    }
    // The square's top and left sides are in, right and bottom out: x, y in [4, 12) -> 64.
    EXPECT_EQ(count.size(), 64u);
    for (const auto& [p, n] : count) {
        EXPECT_EQ(n, 1) << p.first << "," << p.second;
        EXPECT_TRUE(p.first >= 4 && p.first < 12 && p.second >= 4 && p.second < 12);
    }
}

TEST(Rasterizer, JitteredMeshCoversEachPixelOnce) {
    // A 6x6 grid of points over the square [2, 26]: border points exactly on the square, inner
    // points moved by fixed sub-pixel offsets (some onto pixel centres, some between); every
    // cell split in two along alternating diagonals. The union must be the square's pixels
    // [2, 26) x [2, 26), each exactly once: 24 * 24 = 576.
    const double offsets[] = {0.0, 0.5, -0.375, 0.25, 1.0, -0.75, 0.125};
    double px[6][6], py[6][6];
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) {
            px[j][i] = 2 + 4.8 * i;
            py[j][i] = 2 + 4.8 * j;
            if (i == 0 || i == 5) px[j][i] = i == 0 ? 2 : 26;
            if (j == 0 || j == 5) py[j][i] = j == 0 ? 2 : 26;
            if (i > 0 && i < 5) px[j][i] = std::round(px[j][i]) + offsets[(i + 2 * j) % 7];
            if (j > 0 && j < 5) py[j][i] = std::round(py[j][i]) + offsets[(3 * i + j) % 7];
        }
    std::map<Pixel, int> count;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const double ax = px[j][i], ay = py[j][i], bx = px[j][i + 1], by = py[j][i + 1];
            const double cx = px[j + 1][i + 1], cy = py[j + 1][i + 1], dx = px[j + 1][i], dy = py[j + 1][i];
            const bool flip = (i + j) % 2 == 1;
            const std::array<std::array<double, 6>, 2> tris =
                flip ? std::array<std::array<double, 6>, 2>{{{ax, ay, bx, by, dx, dy}, {bx, by, cx, cy, dx, dy}}}
                     : std::array<std::array<double, 6>, 2>{{{ax, ay, bx, by, cx, cy}, {ax, ay, cx, cy, dx, dy}}};
            for (const auto& t : tris)
                for (const Pixel& p : triangle(t[0], t[1], t[2], t[3], t[4], t[5])) ++count[p];
        }
    EXPECT_EQ(count.size(), 576u);
    for (const auto& [p, n] : count) {
        EXPECT_EQ(n, 1) << p.first << "," << p.second;
        EXPECT_TRUE(p.first >= 2 && p.first < 26 && p.second >= 2 && p.second < 26);
    }
}

TEST(Rasterizer, QuadWalkMatchesThePixelRule) {
    // rasterize() (corner rejection, whole-region acceptance, stepped edge functions) gives
    // exactly the pixels covers() accepts, for pseudo-random triangles and odd regions (up to 39
    // pixels wide: rows of 1 to 20 quads, so the vector loop's groups of 8 end anywhere), with
    // its vector loop (where the CPU has one) and with the portable loop; both give the same
    // quads in the same order.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> pos(-6.0, 38.0);
    std::uniform_int_distribution<int32_t> edge(-3, 35);
    for (int n = 0; n < 400; ++n) {
        PrimitiveSetup p;
        if (!setup_triangle(at(pos(rng), pos(rng)), at(pos(rng), pos(rng)), at(pos(rng), pos(rng)),
                            at(0, 0), state32(), p))
            continue;
        int32_t a = edge(rng), b = edge(rng), c = edge(rng), d = edge(rng);
        const PixelRect region{std::min(a, b), std::min(c, d), std::max(a, b) + 1, std::max(c, d) + 1};
        std::set<Pixel> expect;
        for (int32_t y = region.top; y < region.bottom; ++y)
            for (int32_t x = region.left; x < region.right; ++x)
                if (covers(p, x, y)) expect.insert({x, y});
        EXPECT_EQ(pixels_of(p, region), expect) << n;
        EXPECT_EQ(pixels_of(p, region, true), expect) << n;
        std::vector<Quad> fast, portable;
        rasterize(p, region, fast);
        rasterize(p, region, portable, true);
        ASSERT_EQ(fast.size(), portable.size()) << n;
        for (size_t q = 0; q < fast.size(); ++q)
            EXPECT_TRUE(fast[q].x == portable[q].x && fast[q].y == portable[q].y && fast[q].mask == portable[q].mask)
                << n << " quad " << q;
    }
}

TEST(Rasterizer, PixelCentresAreIntegers) {
    // A square with edges at -0.5 and 3.5 covers the centres 0..3: 16 pixels (1:1 texel mapping).
    auto sq = [](double a, double b) {
        auto t1 = triangle(a, a, b, a, b, b), t2 = triangle(a, a, b, b, a, b);
        t1.insert(t2.begin(), t2.end());
        return t1;
    };
    const auto s1 = sq(-0.5, 3.5);
    EXPECT_EQ(s1.size(), 16u);
    EXPECT_TRUE(s1.count({0, 0}) && s1.count({3, 3}) && !s1.count({4, 4}));
    // Edges exactly on centres 0 and 4: top/left in (0), bottom/right out (4): still 0..3.
    EXPECT_EQ(sq(0, 4), s1);
    // Edges at 0.5 and 4.5: centres 1..4.
    const auto s3 = sq(0.5, 4.5);
    EXPECT_EQ(s3.size(), 16u);
    EXPECT_TRUE(s3.count({1, 1}) && s3.count({4, 4}) && !s3.count({0, 0}));
    // A triangle that misses every centre: (0.25, 0.25)-(0.75, 0.25)-(0.75, 0.75) covers nothing.
    EXPECT_TRUE(triangle(0.25, 0.25, 0.75, 0.25, 0.75, 0.75).empty());
}

TEST(Rasterizer, ScissorAndTiles) {
    SetupState s = state32();
    s.clip_rect = {2, 3, 5, 6};  // the scissor rectangle [2, 5) x [3, 6)
    const auto clipped = triangle(0, 0, 30, 0, 0, 30, s);
    std::set<Pixel> expect;
    for (int y = 3; y < 6; ++y)
        for (int x = 2; x < 5; ++x) expect.insert({x, y});
    EXPECT_EQ(clipped, expect);

    // A 64x64 target in 32x32 tiles: the union over tiles is the whole, no pixel twice.
    SetupState big;
    big.viewport = {0, 0, 64, 64, 0, 1};
    big.clip_rect = {0, 0, 64, 64};
    big.cull = CullMode::None;
    auto at64 = [](double X, double Y) {
        ClipVertex v;
        v.position = {static_cast<float>(X / 32.0 - 1.0), static_cast<float>(1.0 - Y / 32.0), 0.5f, 1.0f};
        return v;
    };
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(at64(3.3, 1.7), at64(60.2, 20.9), at64(10.1, 62.4), at64(0, 0), big, p));
    const auto whole = pixels_of(p, {0, 0, 64, 64});
    std::set<Pixel> tiled;
    for (int ty = 0; ty < 2; ++ty)
        for (int tx = 0; tx < 2; ++tx)
            for (const Pixel& px : pixels_of(p, tile_rect(tx, ty))) {
                EXPECT_TRUE(tiled.insert(px).second);
                EXPECT_EQ(px.first / kTileSize, tx);
                EXPECT_EQ(px.second / kTileSize, ty);
            }
    EXPECT_EQ(tiled, whole);
    EXPECT_GT(whole.size(), 1000u);
}

// max_quads(): every quad a rectangle touches, counted by hand. rasterize() into a buffer of
// exactly that many quads (on the heap: a write past it is an AddressSanitizer error) gives the
// quads of the vector form, for a triangle covering the whole region (one quad per slot) and
// for ones covering part of it, on both loops.
TEST(Rasterizer, MaxQuadsBoundsWhatRasterizeWrites) {
    EXPECT_EQ(max_quads({0, 0, 32, 32}), 256u);  // a tile: 16 x 16 quads
    EXPECT_EQ(max_quads({1, 1, 3, 3}), 4u);      // x 1, 2 and y 1, 2: quads at 0 and 2 both ways
    EXPECT_EQ(max_quads({2, 3, 5, 6}), 4u);      // x 2..4: quads 2, 4; y 3..5: quads 2, 4
    EXPECT_EQ(max_quads({4, 4, 5, 5}), 1u);
    EXPECT_EQ(max_quads({5, 5, 5, 9}), 0u);      // empty
    // A triangle over the whole 32x32 target: every pixel inside, each quad of the region full.
    PrimitiveSetup whole;
    ASSERT_TRUE(setup_triangle(at(-40, -40), at(200, -40), at(-40, 200), at(0, 0), state32(), whole));
    std::mt19937 rng(11);
    std::uniform_int_distribution<int32_t> pos(0, 32), edge(-3, 35);
    for (int n = 0; n < 300; ++n) {
        PrimitiveSetup partial;
        const PrimitiveSetup* p = &whole;
        if (n % 3 != 0) {
            if (!setup_triangle(at(pos(rng), pos(rng)), at(pos(rng), pos(rng)), at(pos(rng), pos(rng)), at(0, 0), state32(), partial))
                continue;
            p = &partial;
        }
        const int32_t a = edge(rng), b = edge(rng), c = edge(rng), d = edge(rng);
        const PixelRect region{std::min(a, b), std::min(c, d), std::max(a, b) + 1, std::max(c, d) + 1};
        const size_t room = max_quads(region.intersect(p->bounds));
        for (const bool portable : {false, true}) {
            std::vector<Quad> expect;
            rasterize(*p, region, expect, portable);
            const auto buffer = std::make_unique<Quad[]>(std::max<size_t>(room, 1));
            const size_t count = rasterize(*p, region, buffer.get(), portable);
            ASSERT_LE(count, room) << n;
            ASSERT_EQ(count, expect.size()) << n;
            for (size_t q = 0; q < count; ++q) EXPECT_EQ(buffer[q], expect[q]) << n << " quad " << q;
            if (p == &whole) {
                EXPECT_EQ(count, room) << n;  // every quad of the region, none twice
            }
        }
    }
}

TEST(Rasterizer, QuadMasksFollowLaneOrder) {
    // Triangle covering only pixel (3, 2): centred tiny triangle around it.
    const auto px = triangle(2.5, 1.5, 3.5, 2.5, 2.5, 2.5);
    // Centres inside: (3,2) is on the diagonal from (2.5,1.5) to (3.5,2.5)? x - y = 1 there
    // (3 - 2 = 1): on the edge; that edge goes down-right (not top/left) so out. (3,2) is
    // excluded; the triangle holds no other centre.
    EXPECT_TRUE(px.empty());
    PrimitiveSetup p;
    ASSERT_TRUE(setup_triangle(at(2.5, 1.5), at(3.5, 1.5), at(3.5, 2.5), at(0, 0), state32(), p));
    // Now (3, 2): left of x = 3.5, below y = 1.5, and on the diagonal x - y = 1 which goes
    // down-right from (2.5,1.5) to (3.5,2.5) in clockwise order: interior to its right? The
    // clockwise order is (2.5,1.5) -> (3.5,1.5) -> (3.5,2.5): the diagonal is the edge
    // (3.5,2.5) -> (2.5,1.5), going up: a left edge, so (3, 2) is covered.
    std::vector<Quad> quads;
    rasterize(p, {0, 0, 32, 32}, quads);
    ASSERT_EQ(quads.size(), 1u);
    EXPECT_EQ(quads[0], (Quad{2, 2, 0x2}));  // bit 1 = top-right pixel of the quad at (2, 2)
}

TEST(Rasterizer, Points) {
    SetupState s = state32();
    PrimitiveSetup p;
    s.point_size = 1.0f;  // [1.5, 2.5) x [2.5, 3.5): pixel (2, 3) only
    ASSERT_TRUE(setup_point(at(2, 3), s, p));
    EXPECT_EQ(pixels_of(p), (std::set<Pixel>{{2, 3}}));
    s.point_size = 2.0f;  // [1, 3) x [1, 3): centres 1 and 2 on both axes
    s.point_size_min = 1.0f;
    ASSERT_TRUE(setup_point(at(2, 2), s, p));
    EXPECT_EQ(pixels_of(p), (std::set<Pixel>{{1, 1}, {2, 1}, {1, 2}, {2, 2}}));
    ASSERT_TRUE(setup_point(at(2.5, 2.5), s, p));  // [1.5, 3.5): centres 2 and 3
    EXPECT_EQ(pixels_of(p), (std::set<Pixel>{{2, 2}, {3, 2}, {2, 3}, {3, 3}}));
    // Partly outside the viewport: trimmed to it.
    ASSERT_TRUE(setup_point(at(0, 0), s, p));  // [-1, 1): centres -1, 0 -> only (0, 0) inside
    EXPECT_EQ(pixels_of(p), (std::set<Pixel>{{0, 0}}));
}

std::set<Pixel> line(double x0, double y0, double x1, double y1, bool last_pixel = true) {
    SetupState s = state32();
    s.last_pixel = last_pixel;
    PrimitiveSetup p;
    if (!setup_line(at(x0, y0), at(x1, y1), at(x0, y0), s, p)) return {};
    return pixels_of(p);
}

TEST(Rasterizer, Lines) {
    // Horizontal (0,0)-(4,0): columns floor(0 + 0.5) = 0 .. floor(4 + 0.5) = 4; LASTPIXEL TRUE
    // keeps column 4.
    EXPECT_EQ(line(0, 0, 4, 0), (std::set<Pixel>{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}}));
    EXPECT_EQ(line(0, 0, 4, 0, false), (std::set<Pixel>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
    // (0,0)-(4,1): y(c) = c/4 -> rows floor(c/4 + 0.5): 0, 0, 1 (0.5 + 0.5 = 1), 1, 1.
    const std::set<Pixel> shallow{{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 1}};
    EXPECT_EQ(line(0, 0, 4, 1), shallow);
    EXPECT_EQ(line(4, 1, 0, 0), shallow);  // the same line drawn backwards
    // Without the last pixel, each direction drops its own end.
    EXPECT_EQ(line(4, 1, 0, 0, false), (std::set<Pixel>{{1, 0}, {2, 1}, {3, 1}, {4, 1}}));
    // 45 degrees: |dx| = |dy| counts as x-major: (0,0),(1,1),(2,2),(3,3).
    EXPECT_EQ(line(0, 0, 3, 3), (std::set<Pixel>{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
    // y-major (0,0)-(1,4): x(r) = r/4 -> columns floor(r/4 + 0.5): 0, 0, 1, 1, 1.
    EXPECT_EQ(line(0, 0, 1, 4), (std::set<Pixel>{{0, 0}, {0, 1}, {1, 2}, {1, 3}, {1, 4}}));
    // Vertical (2,0)-(2,3) without last pixel: rows 0..2.
    EXPECT_EQ(line(2, 0, 2, 3, false), (std::set<Pixel>{{2, 0}, {2, 1}, {2, 2}}));
    // Zero length: the nearest pixel with LASTPIXEL, nothing without.
    EXPECT_EQ(line(5.2, 6.7, 5.2, 6.7), (std::set<Pixel>{{5, 7}}));
    EXPECT_TRUE(line(5.2, 6.7, 5.2, 6.7, false).empty());
    // Two lines of a strip share their joint pixel once each: (0,0)-(3,0)-(3,3) without last
    // pixel: {0..2, 0} and {3, 0..2}: 6 pixels, no overlap.
    auto a = line(0, 0, 3, 0, false), b = line(3, 0, 3, 3, false);
    for (const Pixel& p : b) EXPECT_FALSE(a.count(p));
    EXPECT_EQ(a.size() + b.size(), 6u);
}

}  // namespace
}  // namespace sm2::runtime
