// The rasterizer (pipeline.md §6): top-left rule, points, lines, quads. See rasterizer.h.
#include "sm2/runtime/rasterizer.h"

#include <algorithm>
#include <array>

#include "unorm8_avx512.h"

namespace sm2::runtime {
namespace {

int64_t floor_div(int64_t a, int64_t b) {
    if (b < 0) { a = -a; b = -b; }
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

int32_t even_floor(int32_t v) { return v & ~1; }

bool inside(const PixelRect& r, int32_t px, int32_t py) {
    return px >= r.left && px < r.right && py >= r.top && py < r.bottom;
}

// The pixel on the line's major axis at `major` (a column for x-major lines); returns the
// minor coordinate.
int64_t line_minor_at(const LineCoverage& l, int64_t major) {
    const int64_t half = kSubPixelScale / 2;
    // x-major: row = floor(y(c) + 1/2), y(c) = y0 + (256c - x0) * dy / dx (fixed point).
    const int64_t a0 = l.x_major ? l.x0 : l.y0, b0 = l.x_major ? l.y0 : l.x0;
    const int64_t da = l.x_major ? l.x1 - l.x0 : l.y1 - l.y0;
    const int64_t db = l.x_major ? l.y1 - l.y0 : l.x1 - l.x0;
    if (da == 0) return floor_div(b0 + half, kSubPixelScale);
    const int64_t num = (b0 + half) * da + (major * kSubPixelScale - a0) * db;
    return floor_div(num, kSubPixelScale * da);
}

// Major-axis pixels [first, last] of a line and whether the range is empty.
bool line_major_range(const LineCoverage& l, int64_t& first, int64_t& last) {
    const int64_t half = kSubPixelScale / 2;
    const int64_t a0 = l.x_major ? l.x0 : l.y0, a1 = l.x_major ? l.x1 : l.y1;
    const int64_t cs = floor_div(a0 + half, kSubPixelScale), ce = floor_div(a1 + half, kSubPixelScale);
    if (a1 >= a0) {  // columns cs .. ce-1 (+ ce)
        first = cs;
        last = l.last_pixel ? ce : ce - 1;
    } else {         // columns ce+1 .. cs (+ ce)
        first = l.last_pixel ? ce : ce + 1;
        last = cs;
    }
    if (a1 == a0 && (l.x_major ? l.y1 == l.y0 : l.x1 == l.x0) && !l.last_pixel) return false;
    return first <= last;
}

bool line_covers(const LineCoverage& l, int32_t px, int32_t py) {
    int64_t first = 0, last = 0;
    if (!line_major_range(l, first, last)) return false;
    const int64_t major = l.x_major ? px : py, minor = l.x_major ? py : px;
    return major >= first && major <= last && line_minor_at(l, major) == minor;
}

}  // namespace
}  // namespace sm2::runtime

// The block kernels, once per instruction set (block_instances.inc).
#define SM2_BLOCK_KERNELS "rasterizer_block.inc"
#include "block_instances.inc"

namespace sm2::runtime {

PixelRect tile_rect(int32_t tx, int32_t ty) {
    return {tx * kTileSize, ty * kTileSize, (tx + 1) * kTileSize, (ty + 1) * kTileSize};
}

bool covers(const PrimitiveSetup& p, int32_t px, int32_t py) {
    if (!inside(p.bounds, px, py)) return false;
    const int64_t X = static_cast<int64_t>(px) * kSubPixelScale, Y = static_cast<int64_t>(py) * kSubPixelScale;
    switch (p.kind) {
    case CoverageKind::Triangle:
        return p.edges[0].at(X, Y) >= 0 && p.edges[1].at(X, Y) >= 0 && p.edges[2].at(X, Y) >= 0;
    case CoverageKind::Rectangle:
        return X >= p.rect_left && X < p.rect_right && Y >= p.rect_top && Y < p.rect_bottom;
    case CoverageKind::Line:
        return line_covers(p.line, px, py);
    }
    return false;
}

size_t max_quads(const PixelRect& r) {
    if (r.empty()) return 0;
    return static_cast<size_t>((r.right - even_floor(r.left) + 1) / 2) * static_cast<size_t>((r.bottom - even_floor(r.top) + 1) / 2);
}

size_t rasterize(const PrimitiveSetup& p, const PixelRect& region, Quad* out, bool portable) {
    const PixelRect r = region.intersect(p.bounds);
    if (r.empty()) return 0;
    Quad* const first_out = out;
    if (p.kind == CoverageKind::Line) {
        // One pixel per major-axis step: walk the steps inside the region, then gather quads.
        const LineCoverage& l = p.line;
        int64_t first = 0, last = 0;
        if (!line_major_range(l, first, last)) return 0;
        const int64_t lo = std::max<int64_t>(first, l.x_major ? r.left : r.top);
        const int64_t hi = std::min<int64_t>(last, (l.x_major ? r.right : r.bottom) - 1);
        std::vector<Quad> pixels;
        for (int64_t m = lo; m <= hi; ++m) {
            const int64_t n = line_minor_at(l, m);
            const auto px = static_cast<int32_t>(l.x_major ? m : n), py = static_cast<int32_t>(l.x_major ? n : m);
            if (!inside(r, px, py)) continue;
            pixels.push_back({even_floor(px), even_floor(py),
                              static_cast<uint8_t>(1u << ((px & 1) + 2 * (py & 1)))});
        }
        std::sort(pixels.begin(), pixels.end(), [](const Quad& a, const Quad& b) {
            return a.y != b.y ? a.y < b.y : a.x < b.x;
        });
        for (const Quad& q : pixels) {
            if (out != first_out && out[-1].x == q.x && out[-1].y == q.y)
                out[-1].mask = static_cast<uint8_t>(out[-1].mask | q.mask);
            else
                *out++ = q;
        }
        return static_cast<size_t>(out - first_out);
    }
    if (p.kind == CoverageKind::Triangle) {
        // Edge functions are linear: their extremes over the rectangle's pixel centres are at its
        // corners. All corners outside one edge: nothing; all corners inside every edge: every
        // pixel (no per-pixel tests). Both are exact.
        const int64_t x0 = static_cast<int64_t>(r.left) * kSubPixelScale, x1 = static_cast<int64_t>(r.right - 1) * kSubPixelScale;
        const int64_t y0 = static_cast<int64_t>(r.top) * kSubPixelScale, y1 = static_cast<int64_t>(r.bottom - 1) * kSubPixelScale;
        bool all_inside = true;
        for (const EdgeFunction& e : p.edges) {
            const int64_t c00 = e.at(x0, y0), c10 = e.at(x1, y0), c01 = e.at(x0, y1), c11 = e.at(x1, y1);
            if (c00 < 0 && c10 < 0 && c01 < 0 && c11 < 0) return 0;
            if (c00 < 0 || c10 < 0 || c01 < 0 || c11 < 0) all_inside = false;
        }
        if (all_inside) {
            // Every pixel of r: a quad's mask only loses the columns and rows outside r.
            const int32_t qx0 = even_floor(r.left), qy0 = even_floor(r.top);
            for (int32_t qy = qy0; qy < r.bottom; qy += 2) {
                const unsigned rows = (qy >= r.top ? 0x3u : 0u) | (qy + 1 < r.bottom ? 0xCu : 0u);
                for (int32_t qx = qx0; qx < r.right; qx += 2) {
                    const unsigned columns = (qx >= r.left ? 0x5u : 0u) | (qx + 1 < r.right ? 0xAu : 0u);
                    *out++ = {qx, qy, static_cast<uint8_t>(rows & columns)};
                }
            }
            return static_cast<size_t>(out - first_out);
        }
        if (!portable && cpu_has_avx512()) return avx512::rasterize_partial_block(p, r, out);
        if (!portable && cpu_has_avx2()) return avx2::rasterize_partial_block(p, r, out);
        // Each quad's mask without branches: per edge, its sign at the quad's four pixels (bit i
        // = pixel (qx + (i & 1), qy + (i >> 1))), ANDed with the pixels inside r.
        std::array<int64_t, 3> dx{}, dy{}, step{};
        for (unsigned e = 0; e < 3; ++e) {
            dx[e] = p.edges[e].a * kSubPixelScale;
            dy[e] = p.edges[e].b * kSubPixelScale;
            step[e] = 2 * dx[e];
        }
        for (int32_t qy = even_floor(r.top); qy < r.bottom; qy += 2) {
            const int64_t Y = static_cast<int64_t>(qy) * kSubPixelScale;
            const unsigned rows = (qy >= r.top ? 0x3u : 0u) | (qy + 1 < r.bottom ? 0xCu : 0u);
            std::array<int64_t, 3> row{};  // E at (qx, qy), stepped along the row
            const int32_t qx0 = even_floor(r.left);
            for (unsigned e = 0; e < 3; ++e) row[e] = p.edges[e].at(static_cast<int64_t>(qx0) * kSubPixelScale, Y);
            for (int32_t qx = qx0; qx < r.right; qx += 2) {
                unsigned mask = rows & ((qx >= r.left ? 0x5u : 0u) | (qx + 1 < r.right ? 0xAu : 0u));
                for (unsigned e = 0; e < 3; ++e) {
                    const int64_t v = row[e];
                    mask &= (v >= 0 ? 1u : 0u) | (v + dx[e] >= 0 ? 2u : 0u) | (v + dy[e] >= 0 ? 4u : 0u) |
                            (v + dx[e] + dy[e] >= 0 ? 8u : 0u);
                    row[e] += step[e];
                }
                if (mask) *out++ = {qx, qy, static_cast<uint8_t>(mask)};
            }
        }
        return static_cast<size_t>(out - first_out);
    }
    for (int32_t qy = even_floor(r.top); qy < r.bottom; qy += 2) {
        for (int32_t qx = even_floor(r.left); qx < r.right; qx += 2) {
            uint8_t mask = 0;
            for (unsigned i = 0; i < 4; ++i) {
                const int32_t px = qx + static_cast<int32_t>(i & 1u), py = qy + static_cast<int32_t>(i >> 1);
                if (inside(r, px, py) && covers(p, px, py)) mask = static_cast<uint8_t>(mask | (1u << i));
            }
            if (mask) *out++ = {qx, qy, mask};
        }
    }
    return static_cast<size_t>(out - first_out);
}

void rasterize(const PrimitiveSetup& p, const PixelRect& region, std::vector<Quad>& quads, bool portable) {
    const size_t start = quads.size();
    quads.resize(start + max_quads(region.intersect(p.bounds)));
    quads.resize(start + rasterize(p, region, quads.data() + start, portable));
}

}  // namespace sm2::runtime
