// Setup (pipeline.md §4, §5, §6, §8). See setup.h for the precision and interpolation model.
#include "sm2/runtime/setup.h"

#include <algorithm>
#include <cmath>

namespace sm2::runtime {
namespace {

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

int32_t clamp32(int64_t v) {
    return static_cast<int32_t>(std::clamp<int64_t>(v, INT32_MIN / 2, INT32_MAX / 2));
}

// Pixels px with lo <= 256*px <= hi (inclusive fixed-point range), as [first, last + 1).
void pixel_span(int64_t lo, int64_t hi, int32_t& first, int32_t& end) {
    first = clamp32(ceil_div(lo, kSubPixelScale));
    end = clamp32(floor_div(hi, kSubPixelScale) + 1);
}

bool finish_bounds(PrimitiveSetup& out, const PixelRect& box, const SetupState& state) {
    out.bounds = box.intersect(state.clip_rect);
    return !out.bounds.empty();
}

void set_attributes(PrimitiveSetup& out, const ClipVertex& v0, const ClipVertex& v1,
                    const ClipVertex* v2, const ClipVertex& provoking, const SetupState& state) {
    out.varying_mask = state.varying_mask;
    for (unsigned v = 0; v < kVaryingCount; ++v) {
        if (!(state.varying_mask >> v & 1u)) continue;
        const bool flat = state.flat_shading && (kColorVaryings >> v & 1u);
        for (unsigned c = 0; c < 4; ++c) {
            if (flat) {
                out.a0[v][c] = provoking.varyings[v][c];
                out.d1[v][c] = 0.0f;
                out.d2[v][c] = 0.0f;
            } else {
                out.a0[v][c] = v0.varyings[v][c];
                out.d1[v][c] = v1.varyings[v][c] - v0.varyings[v][c];
                out.d2[v][c] = v2 ? v2->varyings[v][c] - v0.varyings[v][c] : 0.0f;
            }
        }
    }
}

}  // namespace

SetupState make_setup_state(const RenderState& rs, const Viewport& vp, uint32_t target_width,
                            uint32_t target_height, const PixelRect& scissor) {
    SetupState s;
    s.viewport = vp;
    const auto clamp_u = [](uint64_t v) { return static_cast<int32_t>(std::min<uint64_t>(v, INT32_MAX)); };
    PixelRect rect{clamp_u(vp.x), clamp_u(vp.y), clamp_u(static_cast<uint64_t>(vp.x) + vp.width),
                   clamp_u(static_cast<uint64_t>(vp.y) + vp.height)};
    rect = rect.intersect(PixelRect{0, 0, clamp_u(target_width), clamp_u(target_height)});
    if (rs.scissor_test_enable) rect = rect.intersect(scissor);
    s.clip_rect = rect;
    s.cull = rs.cull_mode;
    s.flat_shading = rs.shade_mode == ShadeMode::Flat;
    s.depth_bias = rs.depth_bias;
    s.slope_scale_depth_bias = rs.slope_scale_depth_bias;
    s.point_size = rs.point_size;
    s.point_size_min = rs.point_size_min;
    s.point_size_max = rs.point_size_max;
    s.point_sprite = rs.point_sprite_enable;
    s.last_pixel = rs.last_pixel;
    return s;
}

ScreenPosition to_screen(const Vec4& clip, const Viewport& vp) {
    const double w = clip[3];
    const double xn = clip[0] / w, yn = clip[1] / w, zn = clip[2] / w;
    ScreenPosition s;
    s.x = vp.x + (xn + 1.0) * vp.width / 2.0;
    s.y = vp.y + (1.0 - yn) * vp.height / 2.0;
    s.z = static_cast<double>(vp.min_z) + zn * (static_cast<double>(vp.max_z) - vp.min_z);
    s.rhw = 1.0 / w;
    return s;
}

int64_t snap(double screen) {
    const double f = std::nearbyint(screen * kSubPixelScale);
    // Positions reaching here are inside the guard band; the clamp only guards NaN/huge input.
    if (!(f > -4.0e15 && f < 4.0e15)) return 0;
    return static_cast<int64_t>(f);
}

std::optional<bool> screen_winding(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                                   const Viewport& viewport) {
    const ScreenPosition s[3] = {to_screen(v0.position, viewport), to_screen(v1.position, viewport),
                                 to_screen(v2.position, viewport)};
    int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) {
        X[i] = snap(s[i].x);
        Y[i] = snap(s[i].y);
    }
    const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
    if (area == 0) return std::nullopt;
    return area > 0;
}

bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                    const ClipVertex& provoking, const SetupState& state, PrimitiveSetup& out) {
    return setup_triangle(v0, v1, v2,
                          {to_screen(v0.position, state.viewport), to_screen(v1.position, state.viewport),
                           to_screen(v2.position, state.viewport)},
                          provoking, state, out);
}

bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                    const std::array<ScreenPosition, 3>& s, const ClipVertex& provoking, const SetupState& state,
                    PrimitiveSetup& out) {
    int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) {
        X[i] = snap(s[i].x);
        Y[i] = snap(s[i].y);
    }
    // §5: area > 0 is clockwise on screen (y down); 0 draws nothing.
    const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
    if (area == 0) return false;
    const bool cw = area > 0;
    if (culled(state.cull, cw)) return false;

    out = PrimitiveSetup{};
    out.kind = CoverageKind::Triangle;
    out.clockwise = cw;
    // Edges in clockwise order; the top-left rule (§6.1): a pixel centre on an edge is covered
    // only when the edge is a top edge (horizontal, going right) or a left edge (going up).
    const int order[3] = {0, cw ? 1 : 2, cw ? 2 : 1};
    for (int e = 0; e < 3; ++e) {
        const int ia = order[e], ib = order[(e + 1) % 3];
        EdgeFunction& f = out.edges[e];
        f.a = -(Y[ib] - Y[ia]);
        f.b = X[ib] - X[ia];
        f.c = -(f.a * X[ia] + f.b * Y[ia]);
        const bool top = Y[ib] == Y[ia] && X[ib] > X[ia];
        const bool left = Y[ib] < Y[ia];
        if (!top && !left) f.c -= 1;  // E > 0 strictly <=> E - 1 >= 0 on integers
    }
    PixelRect box;
    pixel_span(std::min({X[0], X[1], X[2]}), std::max({X[0], X[1], X[2]}), box.left, box.right);
    pixel_span(std::min({Y[0], Y[1], Y[2]}), std::max({Y[0], Y[1], Y[2]}), box.top, box.bottom);
    if (!finish_bounds(out, box, state)) return false;

    // Barycentric planes (origin at vertex 0). Coverage uses the positions snapped to 1/256
    // pixel; attributes the unsnapped ones, so that a value at a pixel centre is the exact
    // perspective-correct one (snapping a thin or far triangle moves its vertices by up to 1/512
    // pixel, which put a texture coordinate of a w 1..100 quad 6.6e-5 off). Where snapping
    // changed the triangle's area by more than a factor of 2 (a sliver: its unsnapped planes
    // would be steep and extrapolated to the snapped pixels), or flipped or zeroed it, the
    // snapped positions are used.
    double x0 = s[0].x, y0 = s[0].y;
    double x1 = s[1].x - x0, y1 = s[1].y - y0;
    double x2 = s[2].x - x0, y2 = s[2].y - y0;
    double a2 = x1 * y2 - x2 * y1;
    const double snapped_area = static_cast<double>(area) / (static_cast<double>(kSubPixelScale) * kSubPixelScale);
    const double ratio = a2 / snapped_area;
    if (!(ratio >= 0.5 && ratio <= 2.0)) {  // also NaN
        x0 = static_cast<double>(X[0]) / kSubPixelScale;
        y0 = static_cast<double>(Y[0]) / kSubPixelScale;
        x1 = static_cast<double>(X[1]) / kSubPixelScale - x0;
        y1 = static_cast<double>(Y[1]) / kSubPixelScale - y0;
        x2 = static_cast<double>(X[2]) / kSubPixelScale - x0;
        y2 = static_cast<double>(Y[2]) / kSubPixelScale - y0;
        a2 = x1 * y2 - x2 * y1;
    }
    out.origin_x = x0;
    out.origin_y = y0;
    out.b1 = {0.0, y2 / a2, -x2 / a2};
    out.b2 = {0.0, -y1 / a2, x1 / a2};
    out.rhw = {static_cast<float>(s[0].rhw), static_cast<float>(s[1].rhw), static_cast<float>(s[2].rhw)};
    out.perspective = !(out.rhw[0] == out.rhw[1] && out.rhw[1] == out.rhw[2]);
    out.z0 = s[0].z;
    out.dz1 = s[1].z - s[0].z;
    out.dz2 = s[2].z - s[0].z;
    // §8: offset = m * SLOPESCALEDEPTHBIAS + DEPTHBIAS, m = max |dZ/dX|, |dZ/dY|.
    const double dzdx = out.dz1 * out.b1.dx + out.dz2 * out.b2.dx;
    const double dzdy = out.dz1 * out.b1.dy + out.dz2 * out.b2.dy;
    const double m = std::max(std::fabs(dzdx), std::fabs(dzdy));
    out.depth_offset = (state.slope_scale_depth_bias != 0.0f ? m * state.slope_scale_depth_bias : 0.0) +
                       state.depth_bias;
    set_attributes(out, v0, v1, &v2, provoking, state);
    return true;
}

bool setup_line(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& provoking,
                const SetupState& state, PrimitiveSetup& out) {
    const ScreenPosition s0 = to_screen(v0.position, state.viewport);
    const ScreenPosition s1 = to_screen(v1.position, state.viewport);
    out = PrimitiveSetup{};
    out.kind = CoverageKind::Line;
    out.clockwise = true;
    LineCoverage& l = out.line;
    l.x0 = snap(s0.x); l.y0 = snap(s0.y); l.x1 = snap(s1.x); l.y1 = snap(s1.y);
    const int64_t dx = l.x1 - l.x0, dy = l.y1 - l.y0;
    l.x_major = std::llabs(dx) >= std::llabs(dy);
    l.last_pixel = state.last_pixel;
    if (dx == 0 && dy == 0 && !l.last_pixel) return false;
    // Bounds: the nearest pixel centres of both ends, one more row/column on the minor axis
    // (the first pixel's centre may lie up to half a pixel before the start point).
    const int64_t half = kSubPixelScale / 2;
    const int64_t cx0 = floor_div(l.x0 + half, kSubPixelScale), cx1 = floor_div(l.x1 + half, kSubPixelScale);
    const int64_t cy0 = floor_div(l.y0 + half, kSubPixelScale), cy1 = floor_div(l.y1 + half, kSubPixelScale);
    PixelRect box{clamp32(std::min(cx0, cx1) - 1), clamp32(std::min(cy0, cy1) - 1),
                  clamp32(std::max(cx0, cx1) + 2), clamp32(std::max(cy0, cy1) + 2)};
    if (!finish_bounds(out, box, state)) return false;

    out.origin_x = static_cast<double>(l.x0) / kSubPixelScale;
    out.origin_y = static_cast<double>(l.y0) / kSubPixelScale;
    if (dx != 0 || dy != 0) {
        if (l.x_major) out.b1 = {0.0, kSubPixelScale / static_cast<double>(dx), 0.0};
        else out.b1 = {0.0, 0.0, kSubPixelScale / static_cast<double>(dy)};
    }
    out.rhw = {static_cast<float>(s0.rhw), static_cast<float>(s1.rhw), static_cast<float>(s1.rhw)};
    out.perspective = out.rhw[0] != out.rhw[1];
    out.z0 = s0.z;
    out.dz1 = s1.z - s0.z;
    set_attributes(out, v0, v1, nullptr, provoking, state);
    return true;
}

bool setup_point(const ClipVertex& v, const SetupState& state, PrimitiveSetup& out) {
    const ScreenPosition s = to_screen(v.position, state.viewport);
    float size = state.shader_point_size ? v.point_size : state.point_size;
    const float hi = std::min(state.point_size_max, kMaxPointSize);
    if (!(size >= state.point_size_min)) size = state.point_size_min;  // also NaN
    if (size > hi) size = hi;
    if (!(size > 0.0f)) return false;
    const double limit = static_cast<double>(kGuardBandPixels) + size;
    if (!(std::fabs(s.x) < limit && std::fabs(s.y) < limit)) return false;

    out = PrimitiveSetup{};
    out.kind = CoverageKind::Rectangle;
    out.clockwise = true;
    // §6.2: the square (X +- S/2, Y +- S/2) under the triangle rule: its top and left edges are
    // inclusive, right and bottom exclusive.
    out.rect_left = snap(s.x - size / 2.0);
    out.rect_right = snap(s.x + size / 2.0);
    out.rect_top = snap(s.y - size / 2.0);
    out.rect_bottom = snap(s.y + size / 2.0);
    if (out.rect_right <= out.rect_left || out.rect_bottom <= out.rect_top) return false;
    PixelRect box;
    box.left = clamp32(ceil_div(out.rect_left, kSubPixelScale));
    box.right = clamp32(ceil_div(out.rect_right, kSubPixelScale));
    box.top = clamp32(ceil_div(out.rect_top, kSubPixelScale));
    box.bottom = clamp32(ceil_div(out.rect_bottom, kSubPixelScale));
    if (!finish_bounds(out, box, state)) return false;

    out.origin_x = static_cast<double>(out.rect_left) / kSubPixelScale;
    out.origin_y = static_cast<double>(out.rect_top) / kSubPixelScale;
    out.b1 = {0.0, kSubPixelScale / static_cast<double>(out.rect_right - out.rect_left), 0.0};
    out.b2 = {0.0, 0.0, kSubPixelScale / static_cast<double>(out.rect_bottom - out.rect_top)};
    const auto rhw = static_cast<float>(s.rhw);
    out.rhw = {rhw, rhw, rhw};
    out.perspective = false;
    out.z0 = s.z;
    out.varying_mask = state.varying_mask;
    for (unsigned i = 0; i < kVaryingCount; ++i) {
        out.a0[i] = v.varyings[i];
        out.d1[i] = {0.0f, 0.0f, 0.0f, 0.0f};
        out.d2[i] = {0.0f, 0.0f, 0.0f, 0.0f};
    }
    if (state.point_sprite) {  // every t#.xy runs (0,0) at the top-left to (1,1) bottom-right
        for (unsigned t = 0; t < 8; ++t) {
            auto& a = out.a0[kVaryingTexCoord0 + t];
            a[0] = 0.0f;
            a[1] = 0.0f;
            out.d1[kVaryingTexCoord0 + t][0] = 1.0f;
            out.d2[kVaryingTexCoord0 + t][1] = 1.0f;
        }
    }
    return true;
}

unsigned setup_fill_mode(std::span<const ClipVertex> polygon, const ClipVertex& provoking,
                         FillMode mode, const SetupState& state, std::vector<PrimitiveSetup>& out) {
    if (mode == FillMode::Solid || polygon.size() < 3) return 0;
    // Facing and depth bias from the first fan triangle with non-zero area.
    SetupState unculled = state;
    unculled.cull = CullMode::None;
    unculled.clip_rect = PixelRect{INT32_MIN / 2, INT32_MIN / 2, INT32_MAX / 2, INT32_MAX / 2};
    PrimitiveSetup face;
    bool found = false;
    for (size_t i = 1; i + 1 < polygon.size() && !found; ++i)
        found = setup_triangle(polygon[0], polygon[i], polygon[i + 1], provoking, unculled, face);
    if (!found || culled(state.cull, face.clockwise)) return 0;
    unsigned added = 0;
    PrimitiveSetup p;
    for (size_t i = 0; i < polygon.size(); ++i) {
        bool ok = false;
        if (mode == FillMode::Point) {
            ok = setup_point(polygon[i], state, p);
            if (ok && state.flat_shading)
                for (unsigned v = 0; v < kVaryingCount; ++v)
                    if (kColorVaryings >> v & 1u) p.a0[v] = provoking.varyings[v];
        } else {
            ok = setup_line(polygon[i], polygon[(i + 1) % polygon.size()], provoking, state, p);
        }
        if (!ok) continue;
        p.clockwise = face.clockwise;
        p.depth_offset = face.depth_offset;
        out.push_back(p);
        ++added;
    }
    return added;
}

}  // namespace sm2::runtime
