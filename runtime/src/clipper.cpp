// The clipper (pipeline.md §3). See clipper.h for the planes and the precision rules.
#include "sm2/runtime/clipper.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/vec4.hpp>

namespace sm2::runtime {
namespace {

// Plane numbering: bit p of an outcode = distance to plane p is negative.
enum : unsigned {
    kPlaneW = 0, kPlaneNear, kPlaneFar, kPlaneRight, kPlaneLeft, kPlaneBottom, kPlaneTop,
    kPlaneUser0, kPlaneCount = kPlaneUser0 + kMaxUserClipPlanes,
};

uint32_t active_planes(const ClipState& s) {
    uint32_t planes = (1u << kPlaneW) | (0xFu << kPlaneRight);
    if (s.clipping) {
        planes |= (1u << kPlaneNear) | (1u << kPlaneFar);
        planes |= (s.user_plane_enable & 0x3Fu) << kPlaneUser0;
    }
    return planes;
}

double distance(const Vec4& p, unsigned plane, const ClipState& s) {
    const double x = p[0], y = p[1], z = p[2], w = p[3];
    switch (plane) {
    case kPlaneW: return w - static_cast<double>(kMinClipW);
    case kPlaneNear: return z;
    case kPlaneFar: return w - z;
    case kPlaneRight: return s.guard.x * w - x;
    case kPlaneLeft: return s.guard.x * w + x;
    case kPlaneBottom: return s.guard.y * w - y;
    case kPlaneTop: return s.guard.y * w + y;
    default: {
        const Vec4& u = s.user_planes[plane - kPlaneUser0];
        return static_cast<double>(u[0]) * x + static_cast<double>(u[1]) * y +
               static_cast<double>(u[2]) * z + static_cast<double>(u[3]) * w;
    }
    }
}

bool finite_position(const ClipVertex& v) {
    return std::isfinite(v.position[0]) && std::isfinite(v.position[1]) &&
           std::isfinite(v.position[2]) && std::isfinite(v.position[3]);
}

uint32_t outcode(const ClipVertex& v, uint32_t planes, const ClipState& s) {
    uint32_t code = 0;
    for (unsigned p = 0; p < kPlaneCount; ++p)
        if ((planes >> p & 1u) && distance(v.position, p, s) < 0.0) code |= 1u << p;
    return code;
}

// a*(1 - t) + b*t in double, rounded once to float (glm::mix with a double t): exact at both
// ends, no cancellation between huge and tiny values.
Vec4 lerp(const Vec4& a, const Vec4& b, double t) {
    const glm::vec4 r = glm::mix(glm::make_vec4(a.data()), glm::make_vec4(b.data()), t);
    return {r.x, r.y, r.z, r.w};
}

// The point where the edge from `in` (distance din >= 0) to `out` (dout < 0) meets the plane.
ClipVertex intersect(const ClipVertex& in, const ClipVertex& out, double din, double dout,
                     unsigned plane, const ClipState& s) {
    const double t = din / (din - dout);
    ClipVertex r;
    r.position = lerp(in.position, out.position, t);
    for (unsigned v = 0; v < kVaryingCount; ++v)
        if (s.varying_mask >> v & 1u) r.varyings[v] = lerp(in.varyings[v], out.varyings[v], t);
    r.point_size = glm::mix(in.point_size, out.point_size, t);
    float& x = r.position[0];
    float& y = r.position[1];
    float& z = r.position[2];
    float& w = r.position[3];
    // Rounding must never bring w below the w plane (the divide needs w > 0).
    if (!(w >= kMinClipW)) w = kMinClipW;
    switch (plane) {  // put the new vertex exactly on the frustum plane
    case kPlaneW: w = kMinClipW; break;
    case kPlaneNear: z = 0.0f; break;
    case kPlaneFar: z = w; break;
    case kPlaneRight: x = s.guard.x * w; break;
    case kPlaneLeft: x = -s.guard.x * w; break;
    case kPlaneBottom: y = s.guard.y * w; break;
    case kPlaneTop: y = -s.guard.y * w; break;
    default: break;
    }
    return r;
}

}  // namespace

ClipVertex vertex_from_batch(const emu::Batch& batch, unsigned lane, bool shader_writes_point_size) {
    ClipVertex v;
    for (unsigned c = 0; c < 4; ++c) v.position[c] = batch.position()[c][lane];
    for (unsigned d = 0; d < 2; ++d)
        for (unsigned c = 0; c < 4; ++c) {
            const float x = batch.color_out(d)[c][lane];
            v.varyings[kVaryingColor0 + d][c] = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;  // NaN -> 0
        }
    for (unsigned t = 0; t < 8; ++t)
        for (unsigned c = 0; c < 4; ++c) v.varyings[kVaryingTexCoord0 + t][c] = batch.texcoord_out(t)[c][lane];
    v.varyings[kVaryingFog] = {batch.fog()[0][lane], 0.0f, 0.0f, 1.0f};
    v.point_size = shader_writes_point_size ? batch.point_size()[0][lane] : 0.0f;
    return v;
}

GuardBand guard_band(const Viewport& vp) {
    auto axis = [](double origin, double size) {
        if (size <= 0.0) return 1.0f;
        const double half = size / 2.0;
        const double k_low = 1.0 + (origin + kGuardBandPixels) / half;    // left/top end
        const double k_high = (kGuardBandPixels - origin) / half - 1.0;   // right/bottom end
        return static_cast<float>(std::max(1.0, std::floor(std::min(k_low, k_high))));
    };
    return {axis(vp.x, vp.width), axis(vp.y, vp.height)};
}

uint32_t vertex_clip_code(const ClipVertex& v, const ClipState& s) {
    if (!finite_position(v)) return 1u << 31;  // above every plane's bit
    return outcode(v, active_planes(s), s);
}

ClipResult clip_triangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                         const ClipState& s, ClippedPolygon& out) {
    if (!finite_position(a) || !finite_position(b) || !finite_position(c)) return ClipResult::Outside;
    const uint32_t planes = active_planes(s);
    const uint32_t ca = outcode(a, planes, s), cb = outcode(b, planes, s), cc = outcode(c, planes, s);
    if ((ca | cb | cc) == 0) return ClipResult::Inside;
    if ((ca & cb & cc) != 0) return ClipResult::Outside;

    std::array<ClipVertex, kMaxClipPolygon> buffer;
    ClipVertex* src = out.vertices.data();
    ClipVertex* dst = buffer.data();
    src[0] = a; src[1] = b; src[2] = c;
    unsigned n = 3;
    const uint32_t cut = ca | cb | cc;
    for (unsigned p = 0; p < kPlaneCount && n > 0; ++p) {
        if (!(cut >> p & 1u)) continue;
        std::array<double, kMaxClipPolygon> d{};
        for (unsigned i = 0; i < n; ++i) d[i] = distance(src[i].position, p, s);
        unsigned m = 0;
        for (unsigned i = 0; i < n; ++i) {
            const unsigned j = (i + 1) % n;  // edge i -> j
            const bool in_i = d[i] >= 0.0, in_j = d[j] >= 0.0;
            if (in_i && in_j) {
                dst[m++] = src[j];
            } else if (in_i && !in_j) {
                dst[m++] = intersect(src[i], src[j], d[i], d[j], p, s);
            } else if (!in_i && in_j) {
                dst[m++] = intersect(src[j], src[i], d[j], d[i], p, s);
                dst[m++] = src[j];
            }
        }
        std::swap(src, dst);
        n = m;
    }
    if (n < 3) return ClipResult::Outside;
    if (src != out.vertices.data())
        std::copy(src, src + n, out.vertices.data());
    out.count = n;
    return ClipResult::Clipped;
}

ClipResult clip_line(const ClipVertex& a, const ClipVertex& b, const ClipState& s,
                     std::array<ClipVertex, 2>& out) {
    if (!finite_position(a) || !finite_position(b)) return ClipResult::Outside;
    const uint32_t planes = active_planes(s);
    const uint32_t ca = outcode(a, planes, s), cb = outcode(b, planes, s);
    out = {a, b};
    if ((ca | cb) == 0) return ClipResult::Inside;
    if ((ca & cb) != 0) return ClipResult::Outside;
    for (unsigned p = 0; p < kPlaneCount; ++p) {
        if (!((ca | cb) >> p & 1u)) continue;
        const double d0 = distance(out[0].position, p, s), d1 = distance(out[1].position, p, s);
        if (d0 < 0.0 && d1 < 0.0) return ClipResult::Outside;
        if (d0 < 0.0) out[0] = intersect(out[1], out[0], d1, d0, p, s);
        else if (d1 < 0.0) out[1] = intersect(out[0], out[1], d0, d1, p, s);
    }
    return ClipResult::Clipped;
}

bool point_visible(const ClipVertex& v, const ClipState& s) {
    if (!finite_position(v)) return false;
    uint32_t planes = active_planes(s) & ~(0xFu << kPlaneRight);  // x/y: the rasterizer trims
    return outcode(v, planes, s) == 0;
}

}  // namespace sm2::runtime
