// Surface copies and fills outside draws: ColorFill, UpdateSurface, UpdateTexture and
// GetRenderTargetData, with D3D9's pool rules (device.h Pool): ColorFill writes DEFAULT-pool
// surfaces; UpdateSurface/UpdateTexture copy from SYSTEMMEM to DEFAULT; GetRenderTargetData
// from a render target to SYSTEMMEM. Copies are byte copies: the formats must be the same.
#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "device_internal.h"

namespace sm2::runtime {

namespace {

std::string rect_text(const PixelRect& r) {
    return "{" + std::to_string(r.left) + " " + std::to_string(r.top) + " " + std::to_string(r.right) + " " +
           std::to_string(r.bottom) + "}";
}

bool inside(const PixelRect& r, const Surface& s) {
    return r.left >= 0 && r.top >= 0 && r.right > r.left && r.bottom > r.top &&
           static_cast<uint32_t>(r.right) <= s.width() && static_cast<uint32_t>(r.bottom) <= s.height();
}

PixelRect whole(const Surface& s) {
    return PixelRect{0, 0, static_cast<int32_t>(s.width()), static_cast<int32_t>(s.height())};
}

// Copies `from`'s rectangle to (x, y) of `to`: same format, rectangle inside both (checked).
void copy_rect(const Surface& from, const PixelRect& r, Surface& to, uint32_t x, uint32_t y) {
    const unsigned bytes = format_info(from.format())->bytes;
    const size_t row = static_cast<size_t>(r.right - r.left) * bytes;
    for (int32_t sy = r.top; sy < r.bottom; ++sy)
        std::memcpy(to.bytes().data() + (y + static_cast<size_t>(sy - r.top)) * to.row_pitch() + size_t{x} * bytes,
                    from.bytes().data() + static_cast<size_t>(sy) * from.row_pitch() + static_cast<size_t>(r.left) * bytes,
                    row);
}

bool copyable_format(Format format) {
    const FormatInfo* info = format_info(format);
    return info && info->kind != FormatKind::Compressed && info->kind != FormatKind::Depth;
}

}  // namespace

CallResult Device::color_fill(const std::string& name, const std::optional<PixelRect>& rect, uint32_t color) {
    auto r = find(name);
    if (!r) return CallResult::fail("ColorFill: no resource named '" + name + "'");
    // "A render target, a render-target texture surface, or an off-screen plain surface with a
    // pool type of D3DPOOL_DEFAULT" (IDirect3DDevice9::ColorFill).
    Surface* target = nullptr;
    if (r->kind == Resource::Kind::RenderTarget && r->pool_of() == Pool::Default) target = &r->surface;
    else if (r->kind == Resource::Kind::Texture && r->render_target_usage && r->texture.type() == TextureType::Texture2D)
        target = &r->texture.surface(0, 0);
    if (!target)
        return CallResult::fail("ColorFill: '" + name + "' is not a render target or a DEFAULT-pool off-screen plain surface");
    if (!copyable_format(target->format())) return CallResult::fail("ColorFill: the surface's format cannot be filled");
    const PixelRect area = rect.value_or(whole(*target));
    if (!inside(area, *target))
        return CallResult::fail("ColorFill: rectangle " + rect_text(area) + " is not inside the " + std::to_string(target->width()) +
                                "x" + std::to_string(target->height()) + " surface");
    const auto rgba = color_to_float4(color);
    const Float4 value{rgba[0], rgba[1], rgba[2], rgba[3]};
    const unsigned bytes = format_info(target->format())->bytes;
    std::array<std::byte, 16> texel{};
    encode_texel(target->format(), value, texel.data());
    for (int32_t y = area.top; y < area.bottom; ++y)
        for (int32_t x = area.left; x < area.right; ++x)
            std::memcpy(target->bytes().data() + static_cast<size_t>(y) * target->row_pitch() + static_cast<size_t>(x) * bytes,
                        texel.data(), bytes);
    return {};
}

CallResult Device::update_surface(const std::string& source, uint32_t source_level, const std::optional<PixelRect>& source_rect,
                                  const std::string& destination, uint32_t destination_level, uint32_t destination_x,
                                  uint32_t destination_y) {
    auto src = find(source);
    if (!src) return CallResult::fail("UpdateSurface: no resource named '" + source + "'");
    auto dst = find(destination);
    if (!dst) return CallResult::fail("UpdateSurface: no resource named '" + destination + "'");
    Surface* from = src->level_surface(source_level);
    Surface* to = dst->level_surface(destination_level);
    if (!from) return CallResult::fail("UpdateSurface: '" + source + "' has no 2D surface at level " + std::to_string(source_level));
    if (!to) return CallResult::fail("UpdateSurface: '" + destination + "' has no 2D surface at level " + std::to_string(destination_level));
    if (src->pool_of() != Pool::SystemMem)
        return CallResult::fail("UpdateSurface: the source '" + source + "' is in the " + pool_name(src->pool_of()) +
                                " pool, not SYSTEMMEM");
    if (dst->pool_of() != Pool::Default)
        return CallResult::fail("UpdateSurface: the destination '" + destination + "' is in the " + pool_name(dst->pool_of()) +
                                " pool, not DEFAULT");
    if (from->format() != to->format() || !copyable_format(from->format()))
        return CallResult::fail("UpdateSurface: the surfaces' formats differ or cannot be copied");
    const PixelRect area = source_rect.value_or(whole(*from));
    if (!inside(area, *from)) return CallResult::fail("UpdateSurface: source rectangle " + rect_text(area) + " is not inside the source");
    const uint64_t right = uint64_t{destination_x} + static_cast<uint64_t>(area.right - area.left);
    const uint64_t bottom = uint64_t{destination_y} + static_cast<uint64_t>(area.bottom - area.top);
    if (right > to->width() || bottom > to->height())
        return CallResult::fail("UpdateSurface: the rectangle at (" + std::to_string(destination_x) + ", " +
                                std::to_string(destination_y) + ") does not fit the destination");
    copy_rect(*from, area, *to, destination_x, destination_y);
    return {};
}

CallResult Device::update_texture(const std::string& source, const std::string& destination) {
    auto src = find(source);
    auto dst = find(destination);
    if (!src || src->kind != Resource::Kind::Texture) return CallResult::fail("UpdateTexture: '" + source + "' is not a texture");
    if (!dst || dst->kind != Resource::Kind::Texture) return CallResult::fail("UpdateTexture: '" + destination + "' is not a texture");
    if (src->pool != Pool::SystemMem) return CallResult::fail(std::string("UpdateTexture: the source is in the ") + pool_name(src->pool) + " pool, not SYSTEMMEM");
    if (dst->pool != Pool::Default) return CallResult::fail(std::string("UpdateTexture: the destination is in the ") + pool_name(dst->pool) + " pool, not DEFAULT");
    const Texture& from = src->texture;
    Texture& to = dst->texture;
    if (from.type() != to.type() || from.format() != to.format())
        return CallResult::fail("UpdateTexture: the textures differ in type or format");
    // The source level of the destination's top size; the source may have more levels above it.
    uint32_t first = 0;
    while (first < from.levels() && (from.level_width(first) != to.level_width(0) || from.level_height(first) != to.level_height(0) ||
                                     from.level_depth(first) != to.level_depth(0)))
        ++first;
    if (first == from.levels() || from.levels() - first < to.levels())
        return CallResult::fail("UpdateTexture: the source has no levels of the destination's sizes");
    for (uint32_t face = 0; face < to.faces(); ++face)
        for (uint32_t level = 0; level < to.levels(); ++level) to.surface(level, face).bytes() = from.surface(first + level, face).bytes();
    return {};
}

CallResult Device::get_render_target_data(const std::string& render_target, const std::string& destination) {
    auto src = find(render_target);
    auto dst = find(destination);
    Surface* from = nullptr;
    if (src && src->kind == Resource::Kind::RenderTarget && !src->offscreen_plain) from = &src->surface;
    else if (src && src->kind == Resource::Kind::Texture && src->render_target_usage) from = src->level_surface(0);
    if (!from) return CallResult::fail("GetRenderTargetData: '" + render_target + "' is not a render target");
    Surface* to = dst ? dst->level_surface(0) : nullptr;
    if (!to || dst->pool_of() != Pool::SystemMem)
        return CallResult::fail("GetRenderTargetData: '" + destination + "' is not a SYSTEMMEM surface");
    if (from->format() != to->format() || from->width() != to->width() || from->height() != to->height())
        return CallResult::fail("GetRenderTargetData: the surfaces differ in size or format");
    to->bytes() = from->bytes();
    return {};
}

}  // namespace sm2::runtime
