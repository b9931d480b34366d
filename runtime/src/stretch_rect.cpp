// StretchRect on whole surfaces: the source (a render target or level 0 of a 2D texture) is
// scaled onto the whole destination render target with point or bilinear filtering, reading
// texels as a sampler decodes them and storing them with the destination format's conversion.
//
// Destination pixel (x, y) samples the source at its centre mapped into the source:
// u = (x + 1/2) * source_width / destination_width (texel units, texel centres at k + 1/2).
// POINT (and NONE) takes texel floor(u); LINEAR blends texels floor(u - 1/2) and the next one,
// clamped to the edge. Equal sizes copy every texel exactly under either filter.
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
    if (filter != TextureFilter::None && filter != TextureFilter::Point && filter != TextureFilter::Linear)
        return CallResult::fail("StretchRect: filter " + std::to_string(static_cast<uint32_t>(filter)) +
                                " is not NONE, POINT or LINEAR");
    const auto src = find(source);
    if (!src) return CallResult::fail("StretchRect: no resource named '" + source + "'");
    const auto dst = find(destination);
    if (!dst) return CallResult::fail("StretchRect: no resource named '" + destination + "'");
    if (src == dst) return CallResult::fail("StretchRect: source and destination are the same surface");

    const Surface* from = nullptr;
    if (src->kind == Resource::Kind::RenderTarget) from = &src->surface;
    else if (src->kind == Resource::Kind::Texture && src->texture.type() == TextureType::Texture2D)
        from = &src->texture.surface(0, 0);
    if (!from) return CallResult::fail("StretchRect: '" + source + "' is not a render target or 2D texture");

    Surface* to = nullptr;
    if (dst->kind == Resource::Kind::RenderTarget) to = &dst->surface;
    else if (dst->kind == Resource::Kind::Texture && dst->render_target_usage &&
             dst->texture.type() == TextureType::Texture2D)
        to = &dst->texture.surface(0, 0);
    if (!to) return CallResult::fail("StretchRect: '" + destination + "' is not a render target");

    const bool linear = filter == TextureFilter::Linear;
    const uint32_t sw = from->width(), sh = from->height(), dw = to->width(), dh = to->height();
    std::vector<Tap> columns(dw);
    for (uint32_t x = 0; x < dw; ++x) columns[x] = linear ? linear_tap(x, sw, dw) : point_tap(x, sw, dw);
    for (uint32_t y = 0; y < dh; ++y) {
        const Tap row = linear ? linear_tap(y, sh, dh) : point_tap(y, sh, dh);
        for (uint32_t x = 0; x < dw; ++x) {
            const Tap& col = columns[x];
            Float4 value;
            if (!linear) {
                value = from->read(col.first, row.first);
            } else {
                const Float4 a = from->read(col.first, row.first), b = from->read(col.second, row.first);
                const Float4 c = from->read(col.first, row.second), d = from->read(col.second, row.second);
                for (unsigned k = 0; k < 4; ++k) {
                    const double top = lerp(a[k], b[k], col.weight);
                    const double bottom = lerp(c[k], d[k], col.weight);
                    value[k] = static_cast<float>(lerp(top, bottom, row.weight));
                }
            }
            to->write(x, y, 0, value);
        }
    }
    return {};
}

}  // namespace sm2::runtime
