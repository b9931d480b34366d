// Image files -> Textures. DDS is parsed here (exact bits, mip chains, cube faces, volumes);
// everything else goes through OpenImageIO, loaded on first use (image_codec.h).
#include "sm2/runtime/texture_io.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include "dxt.h"
#include "image_codec.h"
#include "sm2/runtime/file_io.h"

namespace sm2::runtime {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& why) { throw TextureIoError(name + ": " + why); }

uint32_t le32(std::span<const std::byte> d, size_t at) {
    return static_cast<uint32_t>(d[at]) | static_cast<uint32_t>(d[at + 1]) << 8 |
           static_cast<uint32_t>(d[at + 2]) << 16 | static_cast<uint32_t>(d[at + 3]) << 24;
}

bool pow2(uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

// DDS_PIXELFORMAT flags
constexpr uint32_t kAlphaPixels = 0x1, kAlpha = 0x2, kFourCC = 0x4, kRgb = 0x40, kLuminance = 0x20000,
                   kBumpDuDv = 0x80000;
// DDS_HEADER flags / caps2
constexpr uint32_t kHeaderDepth = 0x800000, kCaps2Cubemap = 0x200, kCaps2AllFaces = 0xFC00, kCaps2Volume = 0x200000;

struct MaskFormat {
    Format format;
    uint32_t kind;  // kRgb, kLuminance, kAlpha or kBumpDuDv
    uint32_t bits, r, g, b, a;
};

constexpr MaskFormat kMaskFormats[] = {
    {Format::A8R8G8B8, kRgb, 32, 0x00FF0000, 0x0000FF00, 0x000000FF, 0xFF000000},
    {Format::X8R8G8B8, kRgb, 32, 0x00FF0000, 0x0000FF00, 0x000000FF, 0},
    {Format::A8B8G8R8, kRgb, 32, 0x000000FF, 0x0000FF00, 0x00FF0000, 0xFF000000},
    {Format::X8B8G8R8, kRgb, 32, 0x000000FF, 0x0000FF00, 0x00FF0000, 0},
    {Format::G16R16, kRgb, 32, 0x0000FFFF, 0xFFFF0000, 0, 0},
    {Format::A2R10G10B10, kRgb, 32, 0x3FF00000, 0x000FFC00, 0x000003FF, 0xC0000000},
    {Format::A2B10G10R10, kRgb, 32, 0x000003FF, 0x000FFC00, 0x3FF00000, 0xC0000000},
    {Format::R8G8B8, kRgb, 24, 0xFF0000, 0x00FF00, 0x0000FF, 0},
    {Format::R5G6B5, kRgb, 16, 0xF800, 0x07E0, 0x001F, 0},
    {Format::A1R5G5B5, kRgb, 16, 0x7C00, 0x03E0, 0x001F, 0x8000},
    {Format::X1R5G5B5, kRgb, 16, 0x7C00, 0x03E0, 0x001F, 0},
    {Format::A4R4G4B4, kRgb, 16, 0x0F00, 0x00F0, 0x000F, 0xF000},
    {Format::X4R4G4B4, kRgb, 16, 0x0F00, 0x00F0, 0x000F, 0},
    {Format::A8R3G3B2, kRgb, 16, 0x00E0, 0x001C, 0x0003, 0xFF00},
    {Format::R3G3B2, kRgb, 8, 0xE0, 0x1C, 0x03, 0},
    {Format::L8, kLuminance, 8, 0xFF, 0, 0, 0},
    {Format::A8L8, kLuminance, 16, 0x00FF, 0, 0, 0xFF00},
    {Format::A4L4, kLuminance, 8, 0x0F, 0, 0, 0xF0},
    {Format::L16, kLuminance, 16, 0xFFFF, 0, 0, 0},
    {Format::A8, kAlpha, 8, 0, 0, 0, 0xFF},
    {Format::V8U8, kBumpDuDv, 16, 0x00FF, 0xFF00, 0, 0},
    {Format::Q8W8V8U8, kBumpDuDv, 32, 0x000000FF, 0x0000FF00, 0x00FF0000, 0xFF000000},
    {Format::V16U16, kBumpDuDv, 32, 0x0000FFFF, 0xFFFF0000, 0, 0},
};

Format dds_format(std::span<const std::byte> d, const std::string& name) {
    const uint32_t flags = le32(d, 80), fourcc = le32(d, 84), bits = le32(d, 88);
    const uint32_t r = le32(d, 92), g = le32(d, 96), b = le32(d, 100), a = le32(d, 104);
    if (flags & kFourCC) {
        if (fourcc == runtime::fourcc('D', 'X', '1', '0')) fail(name, "DX10 extended headers are not supported (no D3D9 format)");
        const FormatInfo* info = format_info(static_cast<Format>(fourcc));
        if (info == nullptr || !info->texture) fail(name, "unsupported FourCC 0x" + [&] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%08X", fourcc);
            return std::string(buf);
        }());
        return info->format;
    }
    uint32_t kind = flags & kRgb ? kRgb : flags & kLuminance ? kLuminance : flags & kBumpDuDv ? kBumpDuDv
                                                        : flags & kAlpha ? kAlpha : 0;
    const uint32_t alpha = (flags & (kAlphaPixels | kAlpha)) ? a : 0;
    for (const MaskFormat& m : kMaskFormats) {
        if (m.kind != kind || m.bits != bits) continue;
        const bool colour = kind == kAlpha || (m.r == r && m.g == g && m.b == b);
        if (colour && m.a == alpha) return m.format;
    }
    char hex[16];
    std::snprintf(hex, sizeof hex, "%X", flags);
    fail(name, "unsupported pixel format (flags 0x" + std::string(hex) + ", " + std::to_string(bits) + " bits)");
}

Texture load_oiio(const std::string& path, const TextureLoadOptions& options) {
    std::string error;
    if (!check_input_file(path, kMaxImageFileBytes, error)) throw TextureIoError(error);
    const image_codec::Functions* f = image_codec::functions(error);
    if (!f) fail(path, error);
    image_codec::Info spec;
    image_codec::OpenStatus status{};
    image_codec::Reader input(f, f->open(path.c_str(), &spec, &status, &error));
    if (status == image_codec::OpenStatus::NoReader) fail(path, "no reader for this file: " + error);
    if (status != image_codec::OpenStatus::Ok) fail(path, "cannot read image: " + error);
    if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0) fail(path, "empty image");
    if (spec.depth > 1) fail(path, "volume images are read from DDS files only");
    if (spec.width > static_cast<int>(Texture::kMaxSize2D) || spec.height > static_cast<int>(Texture::kMaxSize2D))
        fail(path, "larger than 4096 texels per side");
    // At most 4 channels are read (an image may declare thousands), so the pixels below take at
    // most 4096 x 4096 x 4 floats.
    const int channels = std::min(spec.channels, 4);
    Format format;
    if (spec.type == image_codec::PixelType::U8)
        format = channels == 1 ? Format::L8 : channels == 2 ? Format::A8L8 : Format::A8R8G8B8;
    else if (spec.type == image_codec::PixelType::U16)
        format = channels == 1 ? Format::L16 : Format::A16B16G16R16;
    else if (spec.type == image_codec::PixelType::Half)
        format = channels == 1 ? Format::R16F : channels == 2 ? Format::G16R16F : Format::A16B16G16R16F;
    else
        format = channels == 1 ? Format::R32F : channels == 2 ? Format::G32R32F : Format::A32B32G32R32F;

    const auto w = static_cast<uint32_t>(spec.width), h = static_cast<uint32_t>(spec.height);
    std::vector<float> pixels(size_t{w} * h * static_cast<size_t>(channels));
    if (!input.read(channels, pixels.data(), error)) fail(path, "cannot read pixels: " + error);

    const bool mips = options.generate_mips && pow2(w) && pow2(h);
    if (options.generate_mips && !mips) fail(path, "mip generation needs power-of-two sizes");
    Texture t = Texture::create_2d(format, w, h, mips ? 0 : 1);
    Surface& s = t.surface(0);
    const bool luminance = format == Format::L8 || format == Format::A8L8 || format == Format::L16;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float* p = &pixels[(size_t{y} * w + x) * static_cast<size_t>(channels)];
            Float4 v{0, 0, 0, 1};
            if (luminance) {
                v = {p[0], p[0], p[0], channels > 1 ? p[1] : 1.0f};
            } else {
                for (int c = 0; c < std::min(channels, 4); ++c) v[static_cast<size_t>(c)] = p[c];
            }
            s.write(x, y, 0, v);
        }
    if (mips) t.generate_mips();
    return t;
}

}  // namespace

Texture load_dds(std::span<const std::byte> d, const std::string& name, const TextureLoadOptions& options) {
    if (d.size() < 128) fail(name, "too short for a DDS header (" + std::to_string(d.size()) + " bytes)");
    if (le32(d, 0) != fourcc('D', 'D', 'S', ' ')) fail(name, "not a DDS file (bad magic)");
    if (le32(d, 4) != 124) fail(name, "bad DDS header size");
    if (le32(d, 76) != 32) fail(name, "bad DDS pixel format size");
    const uint32_t height = le32(d, 12), width = le32(d, 16);
    const uint32_t caps2 = le32(d, 112);
    const bool cube = (caps2 & kCaps2Cubemap) != 0;
    const bool volume = (caps2 & kCaps2Volume) != 0 || (le32(d, 8) & kHeaderDepth && le32(d, 24) > 1);
    const uint32_t depth = volume ? std::max(1u, le32(d, 24)) : 1;
    uint32_t levels = std::max(1u, le32(d, 28));
    const Format format = dds_format(d, name);
    const FormatInfo* info = format_info(format);

    if (cube && (caps2 & kCaps2AllFaces) != kCaps2AllFaces) fail(name, "cube maps must have all 6 faces");
    if (cube && width != height) fail(name, "cube faces must be square");
    const uint32_t limit = volume ? Texture::kMaxSizeVolume : Texture::kMaxSize2D;
    if (width == 0 || height == 0 || width > limit || height > limit || depth > limit)
        fail(name, "size " + std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(depth) +
                       " outside 1.." + std::to_string(limit));
    if (levels > Texture::full_chain(width, height, depth)) fail(name, "more mip levels than the chain has");

    const bool make_mips = options.generate_mips && levels == 1 && info->kind != FormatKind::Compressed &&
                           pow2(width) && pow2(height) && pow2(depth);
    Texture t;
    try {
        t = cube ? Texture::create_cube(format, width, make_mips ? 0 : levels)
            : volume ? Texture::create_volume(format, width, height, depth, make_mips ? 0 : levels)
                     : Texture::create_2d(format, width, height, make_mips ? 0 : levels);
    } catch (const std::invalid_argument& e) {
        fail(name, e.what());
    }
    size_t at = 128;
    for (uint32_t f = 0; f < t.faces(); ++f)
        for (uint32_t l = 0; l < levels; ++l) {
            Surface& s = t.surface(l, f);
            const size_t bytes = s.bytes().size();
            if (d.size() - at < bytes)
                fail(name, "truncated: level " + std::to_string(l) + " of face " + std::to_string(f) + " needs " +
                               std::to_string(bytes) + " bytes, " + std::to_string(d.size() - at) + " left");
            std::memcpy(s.bytes().data(), d.data() + at, bytes);
            at += bytes;
        }
    if (make_mips) t.generate_mips();
    return t;
}

Texture load_texture(const std::string& path, const TextureLoadOptions& options) {
    // Only regular files of at most kMaxImageFileBytes (not a directory, a FIFO or /dev/zero).
    std::string error;
    if (!check_input_file(path, kMaxImageFileBytes, error)) throw TextureIoError(error);
    {
        std::ifstream in(path, std::ios::binary);
        if (!in) fail(path, "cannot open");
        char magic[4] = {};
        in.read(magic, 4);
        if (in.gcount() == 4 && std::memcmp(magic, "DDS ", 4) == 0) {
            const auto data = read_file_limited(path, kMaxImageFileBytes, error);
            if (!data) throw TextureIoError(error);
            return load_dds(*data, path, options);
        }
    }
    return load_oiio(path, options);
}

}  // namespace sm2::runtime
