// The rasterizer (pipeline.md §6): coverage of one set-up primitive inside a screen region (a
// tile), as 2x2 quads. Coverage is decided only on the 16.8 fixed-point integers setup made, so
// it is exact and independent of the order primitives arrive in.
//
// Triangles: the top-left rule (a pixel centre exactly on an edge belongs to the triangle only
// when that edge is a top or a left edge; the rule is folded into the edge functions by
// setup_triangle). Two triangles sharing an edge cover each pixel on it exactly once.
//
// Points: the square [X - S/2, X + S/2) x [Y - S/2, Y + S/2) under the same rule: pixel centres
// on the top and left sides are in, on the right and bottom sides out.
//
// Lines (aliased, one pixel wide; the GDI-style rule): along the major axis (x when
// |dx| >= |dy|, ties go to x) the line draws exactly one pixel per column (row for y-major):
//   columns c from c_start = floor(x0 + 1/2) towards c_end = floor(x1 + 1/2), c_end excluded
//   unless LASTPIXEL is TRUE; in column c the row floor(y(c) + 1/2), where y(c) is the line's
//   y at x = c (exact rational arithmetic on the fixed-point end points).
// A zero-length line draws the pixel nearest its point when LASTPIXEL is TRUE, else nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sm2/runtime/setup.h"

namespace sm2::runtime {

constexpr int32_t kTileSize = 32;  // pixels per tile side (a multiple of 2: quads never straddle)

// A 2x2 quad at even (x, y): mask bit 0 = (x, y), 1 = (x+1, y), 2 = (x, y+1), 3 = (x+1, y+1),
// the lane order of emu batches (top-left, top-right, bottom-left, bottom-right).
struct Quad {
    int32_t x = 0, y = 0;
    uint8_t mask = 0;
    friend bool operator==(const Quad&, const Quad&) = default;
};

// Pixels of tile (tx, ty): [tx*kTileSize, +kTileSize) x [ty*kTileSize, +kTileSize).
[[nodiscard]] PixelRect tile_rect(int32_t tx, int32_t ty);

// Whether the primitive covers pixel (px, py) (inside its bounds, which include the viewport,
// render target and scissor rectangle).
[[nodiscard]] bool covers(const PrimitiveSetup& prim, int32_t px, int32_t py);

// The most quads rasterize() can write for a region (after its intersection with the
// primitive's bounds): every quad the rectangle touches. A tile's is at most kTileQuads.
[[nodiscard]] size_t max_quads(const PixelRect& region);
constexpr size_t kTileQuads = static_cast<size_t>(kTileSize / 2) * static_cast<size_t>(kTileSize / 2);

// Writes the quads with at least one covered pixel inside `region` from `out` (room for
// max_quads(region) of them) and returns their count: rows of quads from top to bottom, each
// row left to right. Pixels outside `region` are not in any mask. Triangles that cover part of
// the region take an AVX-512 loop (8 quads at a time) where the CPU has it; `portable` forces
// the scalar loop, which gives the same quads (DeviceOptions::reference_paths).
size_t rasterize(const PrimitiveSetup& prim, const PixelRect& region, Quad* out, bool portable = false);
// The same, appended to `quads`.
void rasterize(const PrimitiveSetup& prim, const PixelRect& region, std::vector<Quad>& quads, bool portable = false);

}  // namespace sm2::runtime
