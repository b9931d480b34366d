// Setup (pipeline.md §4, §5, §6, §8): perspective divide, viewport transform with D3D9's
// integer pixel centres, fixed-point snapping, culling, edge equations with the top-left rule,
// depth bias, and the plane equations the interpolator evaluates. One PrimitiveSetup per
// triangle, line or point; it is plain data that tiles on any thread read.
//
// Precision: screen positions are snapped to 1/256 pixel (16.8 fixed point, D3D10's choice)
// with round-to-nearest-even; coverage uses only the snapped integers (exact, independent of
// triangle order). Pixel (px, py) is sampled at (px, py) (the D3D9 centre), which in fixed
// point is (256 px, 256 py). Interpolation planes of triangles are computed in double from the
// unsnapped positions (the exact perspective-correct value at each centre), from the snapped
// ones where snapping changed the area by more than a factor of 2 (slivers); lines and points
// use their snapped positions.
//
// Interpolation model: b1, b2 are the screen-space barycentrics of vertices 1 and 2 (linear
// planes); perspective-correct ones are b_i' = b_i*rhw_i / (b0*rhw0 + b1*rhw1 + b2*rhw2), and
// every attribute is a0 + b1'*(a1 - a0) + b2'*(a2 - a0), so a constant attribute is exact.
// Depth is linear in screen space: z0 + b1*(z1 - z0) + b2*(z2 - z0), plus the depth bias.
// Points and lines use the same model (a point: b1 = u, b2 = v across the square; a line:
// b1 = t along its major axis, b2 = 0).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sm2/runtime/clipper.h"
#include "sm2/runtime/render_state.h"

namespace sm2::runtime {

constexpr int kSubPixelBits = 8;
constexpr int32_t kSubPixelScale = 1 << kSubPixelBits;  // 256 steps per pixel
constexpr float kMaxPointSize = 256.0f;                  // our D3DCAPS9.MaxPointSize

// Per-draw state setup reads (plain data, built once per draw).
struct SetupState {
    Viewport viewport{};
    // Pixels a primitive may produce: viewport rectangle ∩ render target ∩ scissor (when
    // SCISSORTESTENABLE). The scissor test is done here; the image is the same as testing
    // after the shader (pipeline.md §7 step 3).
    PixelRect clip_rect{};
    CullMode cull = CullMode::CCW;
    bool flat_shading = false;       // SHADEMODE FLAT: colours from the provoking vertex
    float depth_bias = 0.0f;         // DEPTHBIAS
    float slope_scale_depth_bias = 0.0f;
    uint16_t varying_mask = kAllVaryings;  // varyings later stages read
    // Points
    bool shader_point_size = false;  // the vertex shader writes oPts
    float point_size = 1.0f, point_size_min = 1.0f, point_size_max = 64.0f;
    bool point_sprite = false;       // POINTSPRITEENABLE: t#.xy = (0,0) top-left .. (1,1)
    // Lines
    bool last_pixel = true;          // LASTPIXEL
};

// SetupState from the render state, the viewport, the render target's size and the scissor
// rectangle (SetScissorRect). varying_mask and shader_point_size depend on the shaders: the
// caller sets them.
[[nodiscard]] SetupState make_setup_state(const RenderState& state, const Viewport& viewport,
                                          uint32_t target_width, uint32_t target_height,
                                          const PixelRect& scissor);

enum class CoverageKind : uint8_t { Triangle, Rectangle, Line };

// E(X, Y) = a*X + b*Y + c over fixed-point pixel centres (X = 256 px); covered when >= 0 for
// all three edges. The top-left rule is folded into c (-1 on edges that are not top or left).
struct EdgeFunction {
    int64_t a = 0, b = 0, c = 0;
    [[nodiscard]] int64_t at(int64_t x, int64_t y) const { return a * x + b * y + c; }
};

struct LineCoverage {
    int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // fixed-point end points
    bool x_major = true;
    bool last_pixel = true;
};

// A linear function of the pixel centre: value = c + dx*(px - origin_x) + dy*(py - origin_y).
struct Plane {
    double c = 0.0, dx = 0.0, dy = 0.0;
};

struct PrimitiveSetup {
    CoverageKind kind = CoverageKind::Triangle;
    // Clockwise on screen (points and lines count as clockwise: the stencil's front set).
    bool clockwise = true;
    // Pixels that can be covered (already ∩ clip_rect); never empty for a setup that succeeded.
    PixelRect bounds{};
    std::array<EdgeFunction, 3> edges{};  // Triangle
    int64_t rect_left = 0, rect_top = 0, rect_right = 0, rect_bottom = 0;  // Rectangle (fixed)
    LineCoverage line{};                  // Line

    double origin_x = 0.0, origin_y = 0.0;
    Plane b1{}, b2{};                      // screen-space barycentrics of vertices 1 and 2
    std::array<float, 3> rhw{1.0f, 1.0f, 1.0f};
    bool perspective = false;              // false when all rhw are equal: b' = b
    double z0 = 0.0, dz1 = 0.0, dz2 = 0.0; // Zs at vertex 0 and the differences to 1 and 2
    double depth_offset = 0.0;             // depth bias (triangles only; §8)
    uint16_t varying_mask = kAllVaryings;
    std::array<Vec4, kVaryingCount> a0{}, d1{}, d2{};  // attribute = a0 + b1'*d1 + b2'*d2
};

// D3D9 viewport transform of a clip-space position (after clipping, w > 0): screen x, y
// (pixel centres at integers), Zs and 1/w. In double.
struct ScreenPosition {
    double x = 0.0, y = 0.0, z = 0.0, rhw = 0.0;
};
[[nodiscard]] ScreenPosition to_screen(const Vec4& clip, const Viewport& viewport);
// Screen coordinate -> 16.8 fixed point (round to nearest even).
[[nodiscard]] int64_t snap(double screen);

// The screen-space winding of a triangle from its snapped positions (§5): true = clockwise,
// nullopt = zero area.
[[nodiscard]] std::optional<bool> screen_winding(const ClipVertex& v0, const ClipVertex& v1,
                                                 const ClipVertex& v2, const Viewport& viewport);
[[nodiscard]] constexpr bool culled(CullMode cull, bool clockwise) {
    return (cull == CullMode::CW && clockwise) || (cull == CullMode::CCW && !clockwise);
}

// Each returns false when the primitive produces no pixels (culled, zero area, outside the
// clip rectangle); `out` is then unspecified. `provoking` gives the flat-shaded colours.
[[nodiscard]] bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                                  const ClipVertex& provoking, const SetupState& state,
                                  PrimitiveSetup& out);
// The same with the vertices' to_screen() positions already worked out (once per shaded vertex
// for the triangles no plane cuts).
[[nodiscard]] bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                                  const std::array<ScreenPosition, 3>& screen, const ClipVertex& provoking,
                                  const SetupState& state, PrimitiveSetup& out);
[[nodiscard]] bool setup_line(const ClipVertex& v0, const ClipVertex& v1,
                              const ClipVertex& provoking, const SetupState& state,
                              PrimitiveSetup& out);
[[nodiscard]] bool setup_point(const ClipVertex& v, const SetupState& state, PrimitiveSetup& out);

// FILLMODE POINT and WIREFRAME (§5: culling still applies) for one triangle, or the clipped
// polygon made from it (vertices in order, a fan). The polygon is culled as a whole by the
// winding of its first triangle with non-zero area (clipping keeps the winding); then its
// vertices become points (POINT) or its boundary edges lines (WIREFRAME). Every primitive
// carries the triangle's facing (for two-sided stencil), its depth bias (§8: bias applies in
// every fill mode) and, with flat shading, the provoking vertex's colours. Appends to `out`;
// returns how many were added. FillMode::Solid adds nothing (use setup_triangle).
unsigned setup_fill_mode(std::span<const ClipVertex> polygon, const ClipVertex& provoking,
                         FillMode mode, const SetupState& state, std::vector<PrimitiveSetup>& out);

}  // namespace sm2::runtime
