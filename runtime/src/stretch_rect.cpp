// StretchRect: a rectangle of the source (a render target or level 0 of a 2D texture; the whole
// surface by default) is scaled onto a rectangle of the destination render target with point or
// bilinear filtering, reading texels as a sampler decodes them and storing them with the
// destination format's conversion. Both rectangles must lie inside their surfaces.
//
// Destination pixel (x, y) of the destination rectangle samples the source rectangle at its
// centre mapped into it: u = (x - dest.left + 1/2) * source_width / destination_width (texel
// units from source.left, texel centres at k + 1/2). POINT (and NONE) takes texel floor(u);
// LINEAR blends texels floor(u - 1/2) and the next one, clamped to the source rectangle's edge.
// Equal sizes copy every texel exactly under either filter.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "device_internal.h"

namespace sm2::runtime {

namespace {

// Source texel index and weight of the next texel along one axis, for destination index `d`.
struct Tap {
    uint32_t first = 0, second = 0;
    double weight = 0;  // of `second`
};

double lerp(double a, double b, double weight) { return weight == 0.0 ? a : a + (b - a) * weight; }

Tap point_tap(uint32_t d, uint32_t source_size, uint32_t destination_size) {
    // floor((d + 1/2) * s / D) in integers: (2d + 1) * s / (2D).
    const uint64_t index = (2 * uint64_t{d} + 1) * source_size / (2 * uint64_t{destination_size});
    const auto clamped = static_cast<uint32_t>(std::min<uint64_t>(index, source_size - 1));
    return {clamped, clamped, 0.0};
}

Tap linear_tap(uint32_t d, uint32_t source_size, uint32_t destination_size) {
    const double u = (static_cast<double>(d) + 0.5) * source_size / destination_size - 0.5;
    if (u <= 0.0) return {0, 0, 0.0};
    const double base = std::floor(u);
    const auto first = static_cast<uint32_t>(std::min<double>(base, source_size - 1));
    const uint32_t second = std::min(first + 1, source_size - 1);
    return {first, second, u - base};
}

}  // namespace

CallResult Device::stretch_rect(const std::string& source, const std::string& destination, TextureFilter filter) {
    return stretch_rect(source, std::nullopt, destination, std::nullopt, filter);
}

CallResult Device::stretch_rect(const std::string& source, const std::optional<PixelRect>& source_rect,
                                const std::string& destination, const std::optional<PixelRect>& destination_rect,
                                TextureFilter filter) {
    if (filter != TextureFilter::None && filter != TextureFilter::Point && filter != TextureFilter::Linear)
        return CallResult::fail("StretchRect: filter " + std::to_string(static_cast<uint32_t>(filter)) +
                                " is not NONE, POINT or LINEAR");
    const auto src = find(source);
    if (!src) return CallResult::fail("StretchRect: no resource named '" + source + "'");
    const auto dst = find(destination);
    if (!dst) return CallResult::fail("StretchRect: no resource named '" + destination + "'");
    if (src == dst) return CallResult::fail("StretchRect: source and destination are the same surface");

    const Surface* from = nullptr;
    if (src->kind == Resource::Kind::RenderTarget && src->pool_of() == Pool::Default) from = &src->surface;
    else if (src->kind == Resource::Kind::Texture && src->texture.type() == TextureType::Texture2D)
        from = &src->texture.surface(0, 0);
    if (!from) return CallResult::fail("StretchRect: '" + source + "' is not a render target or 2D texture");

    Surface* to = nullptr;
    if (dst->kind == Resource::Kind::RenderTarget && dst->pool_of() == Pool::Default) to = &dst->surface;
    else if (dst->kind == Resource::Kind::Texture && dst->render_target_usage &&
             dst->texture.type() == TextureType::Texture2D)
        to = &dst->texture.surface(0, 0);
    if (!to) return CallResult::fail("StretchRect: '" + destination + "' is not a render target");

    const auto whole = [](const Surface& s) {
        return PixelRect{0, 0, static_cast<int32_t>(s.width()), static_cast<int32_t>(s.height())};
    };
    const auto inside = [](const PixelRect& r, const Surface& s) {
        return r.left >= 0 && r.top >= 0 && r.right > r.left && r.bottom > r.top &&
               static_cast<uint32_t>(r.right) <= s.width() && static_cast<uint32_t>(r.bottom) <= s.height();
    };
    const PixelRect sr = source_rect.value_or(whole(*from)), dr = destination_rect.value_or(whole(*to));
    if (!inside(sr, *from)) return CallResult::fail("StretchRect: the source rectangle is not inside '" + source + "'");
    if (!inside(dr, *to)) return CallResult::fail("StretchRect: the destination rectangle is not inside '" + destination + "'");

    const bool linear = filter == TextureFilter::Linear;
    const auto sx0 = static_cast<uint32_t>(sr.left), sy0 = static_cast<uint32_t>(sr.top);
    const auto dx0 = static_cast<uint32_t>(dr.left), dy0 = static_cast<uint32_t>(dr.top);
    const auto sw = static_cast<uint32_t>(sr.right - sr.left), sh = static_cast<uint32_t>(sr.bottom - sr.top);
    const auto dw = static_cast<uint32_t>(dr.right - dr.left), dh = static_cast<uint32_t>(dr.bottom - dr.top);
    std::vector<Tap> columns(dw);
    for (uint32_t x = 0; x < dw; ++x) columns[x] = linear ? linear_tap(x, sw, dw) : point_tap(x, sw, dw);
    for (uint32_t y = 0; y < dh; ++y) {
        const Tap row = linear ? linear_tap(y, sh, dh) : point_tap(y, sh, dh);
        for (uint32_t x = 0; x < dw; ++x) {
            const Tap& col = columns[x];
            Float4 value;
            if (!linear) {
                value = from->read(sx0 + col.first, sy0 + row.first);
            } else {
                const Float4 a = from->read(sx0 + col.first, sy0 + row.first), b = from->read(sx0 + col.second, sy0 + row.first);
                const Float4 c = from->read(sx0 + col.first, sy0 + row.second), d = from->read(sx0 + col.second, sy0 + row.second);
                for (unsigned k = 0; k < 4; ++k) {
                    const double top = lerp(a[k], b[k], col.weight);
                    const double bottom = lerp(c[k], d[k], col.weight);
                    value[k] = static_cast<float>(lerp(top, bottom, row.weight));
                }
            }
            to->write(dx0 + x, dy0 + y, 0, value);
        }
    }
    return {};
}

}  // namespace sm2::runtime
