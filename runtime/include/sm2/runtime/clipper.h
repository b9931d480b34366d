// The clipper (pipeline.md §3): homogeneous clipping of triangles, lines and points in clip
// space (the space of oPos), Sutherland-Hodgman one plane at a time.
//
// Planes, in the order they are applied (a point is kept when every distance is >= 0):
//   w >= kMinClipW          always (so the divide never sees w <= 0; exact for triangles that
//                           cross w = 0: the part with w < kMinClipW is cut away)
//   z >= 0, w - z >= 0      near and far, when D3DRS_CLIPPING is TRUE
//   K*w -+ x >= 0, K*w -+ y >= 0
//                           the guard band, always: K (from guard_band()) keeps every screen
//                           position inside the rasterizer's fixed-point range, and is wide
//                           enough that triangles crossing only the viewport's x/y sides need no
//                           clipping (the rasterizer's viewport/scissor rectangle trims them)
//   user planes             A*x + B*y + C*z + D*w >= 0 for each bit of CLIPPLANEENABLE, when
//                           D3DRS_CLIPPING is TRUE (clip space: a vertex shader is bound)
// Positions with a NaN or infinite component discard their primitive.
// New vertices: every attribute is interpolated linearly in clip space, always from the vertex
// inside the plane towards the one outside it (t = d_in / (d_in - d_out), value
// (1 - t)*in + t*out, in double), so two triangles sharing a clipped edge create bit-identical
// vertices; w is kept >= kMinClipW after rounding, and frustum planes then set the clipped
// coordinate exactly onto the plane (z = 0, z = w, x = +-K*w, ...).
#pragma once

#include <array>
#include <cstdint>

#include "sm2/emu/batch.h"
#include "sm2/runtime/render_state.h"

namespace sm2::runtime {

using Vec4 = std::array<float, 4>;

// The vertex shader outputs the later stages interpolate, as "varyings".
constexpr unsigned kVaryingColor0 = 0;     // oD0 -> ps v0
constexpr unsigned kVaryingColor1 = 1;     // oD1 -> ps v1
constexpr unsigned kVaryingTexCoord0 = 2;  // oT0..oT7 -> ps t0..t7
constexpr unsigned kVaryingFog = 10;       // oFog (.x)
constexpr unsigned kVaryingCount = 11;
constexpr uint16_t kAllVaryings = (1u << kVaryingCount) - 1;
constexpr uint16_t kColorVaryings = 0x3;   // what flat shading affects

// One vertex after the vertex shader.
struct ClipVertex {
    Vec4 position{};  // oPos
    std::array<Vec4, kVaryingCount> varyings{};
    float point_size = 0.0f;  // oPts.x (0 when the shader does not write it)
};

// Lane `lane` of a vertex batch after the vertex shader ran. oD0/oD1 are saturated to [0, 1]
// (pipeline.md §6.4: colour interpolators carry [0, 1]); a NaN colour becomes 0.
[[nodiscard]] ClipVertex vertex_from_batch(const emu::Batch& batch, unsigned lane,
                                           bool shader_writes_point_size);

constexpr float kMinClipW = 1.0f / 1099511627776.0f;  // 2^-40: 1/w stays far from overflow
constexpr float kGuardBandPixels = 16384.0f;           // |screen x|, |screen y| <= 2^14

struct GuardBand {
    float x = 1.0f, y = 1.0f;  // K per axis: |x| <= K*w, |y| <= K*w
};
// The widest whole-number K for which the viewport maps every kept position within
// +-kGuardBandPixels (at least 1: the viewport itself).
[[nodiscard]] GuardBand guard_band(const Viewport& viewport);

struct ClipState {
    bool clipping = true;              // D3DRS_CLIPPING
    uint32_t user_plane_enable = 0;    // D3DRS_CLIPPLANEENABLE (bits 0..5)
    std::array<Vec4, kMaxUserClipPlanes> user_planes{};  // SetClipPlane, clip space
    GuardBand guard{};
    uint16_t varying_mask = kAllVaryings;  // varyings the later stages read (others skipped)
};

constexpr unsigned kMaxClipPolygon = 3 + 7 + kMaxUserClipPlanes;  // one more vertex per plane

struct ClippedPolygon {
    unsigned count = 0;  // vertices; the triangles are the fan (0, i, i+1)
    std::array<ClipVertex, kMaxClipPolygon> vertices{};
};

enum class ClipResult : uint8_t {
    Inside,   // no plane cuts the primitive: use its vertices as they are
    Clipped,  // the output holds the clipped primitive
    Outside,  // nothing is left (or a position is NaN/infinite)
};

[[nodiscard]] ClipResult clip_triangle(const ClipVertex& a, const ClipVertex& b,
                                       const ClipVertex& c, const ClipState& state,
                                       ClippedPolygon& out);
// 0 when no plane cuts the vertex and its position is finite: a triangle of three such vertices
// is one clip_triangle() leaves Inside (the set-up works this out once per shaded vertex
// instead of three times per triangle).
[[nodiscard]] uint32_t vertex_clip_code(const ClipVertex& v, const ClipState& state);
// Lines: out[0], out[1] get the clipped end points (copies when Inside).
[[nodiscard]] ClipResult clip_line(const ClipVertex& a, const ClipVertex& b,
                                   const ClipState& state, std::array<ClipVertex, 2>& out);
// Points are kept or discarded by their centre against w, near/far and the user planes; their
// x/y extent is trimmed by the rasterizer's rectangle (Point Sprites page).
[[nodiscard]] bool point_visible(const ClipVertex& v, const ClipState& state);

}  // namespace sm2::runtime
