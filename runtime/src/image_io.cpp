// Surfaces -> image files, image files -> float RGBA, and image comparison (sm2 diff).
// PNG, TGA and EXR go through OpenImageIO, loaded on first use (image_codec.h); .raw (float
// RGBA, no header) is written here.
#include "sm2/runtime/image_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "image_codec.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/texture_io.h"

namespace sm2::runtime {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) { throw ImageIoError(path + ": " + why); }

enum class FileKind { Png, Tga, Exr, Raw, Other };

FileKind file_kind(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
    if (ext == ".png") return FileKind::Png;
    if (ext == ".tga") return FileKind::Tga;
    if (ext == ".exr") return FileKind::Exr;
    if (ext == ".raw") return FileKind::Raw;
    return FileKind::Other;
}

void check_image(const Image& image, const std::string& what) {
    if (image.rgba.size() != size_t{image.width} * image.height * 4)
        throw ImageIoError(what + ": pixel data does not match " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " RGBA");
}

// 8-bit storage: clamped to [0,1], round(v * 255); NaN stores 0.
uint8_t to_unorm8(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return static_cast<uint8_t>(std::lround(static_cast<double>(v) * 255.0));
}

void write_raw(const Image& image, const std::string& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) fail(path, "cannot open for writing");
    std::vector<char> bytes(image.rgba.size() * 4);
    for (size_t i = 0; i < image.rgba.size(); ++i) {
        uint32_t bits = std::bit_cast<uint32_t>(image.rgba[i]);
        for (size_t b = 0; b < 4; ++b) bytes[i * 4 + b] = static_cast<char>((bits >> (8 * b)) & 0xFF);  // little-endian
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) fail(path, "write failed");
}

const image_codec::Functions& codec(const std::string& path) {
    std::string error;
    const image_codec::Functions* f = image_codec::functions(error);
    if (!f) fail(path, error);
    return *f;
}

void write_oiio(const Image& image, const std::string& path, bool eight_bit) {
    const image_codec::Functions& f = codec(path);
    std::string error;
    bool ok;
    if (eight_bit) {
        std::vector<uint8_t> bytes(image.rgba.size());
        std::transform(image.rgba.begin(), image.rgba.end(), bytes.begin(), to_unorm8);
        ok = f.write(path.c_str(), image.width, image.height, true, bytes.data(), &error);
    } else {
        ok = f.write(path.c_str(), image.width, image.height, false, image.rgba.data(), &error);
    }
    if (!ok) fail(path, error);
}

void check_same_size(const Image& a, const Image& b) {
    check_image(a, "first image");
    check_image(b, "second image");
    if (a.width != b.width || a.height != b.height)
        throw ImageIoError("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                           " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
}

}  // namespace

void write_image(const Image& image, const std::string& path) {
    check_image(image, path);
    if (image.width == 0 || image.height == 0) fail(path, "empty image");
    switch (file_kind(path)) {
    case FileKind::Png:
    case FileKind::Tga: write_oiio(image, path, true); return;
    case FileKind::Exr: write_oiio(image, path, false); return;
    case FileKind::Raw: write_raw(image, path); return;
    case FileKind::Other: break;
    }
    fail(path, "unknown image file extension (expected .png, .tga, .exr or .raw)");
}

Image surface_image(const Surface& surface) {
    Image image;
    image.width = surface.width();
    image.height = surface.height();
    image.rgba.resize(size_t{image.width} * image.height * 4);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const Float4 v = surface.read(x, y, 0);
            std::copy(v.begin(), v.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>((size_t{y} * image.width + x) * 4));
        }
    return image;
}

Surface depth_as_surface(const DepthStencilSurface& ds) {
    Surface out(Format::A32B32G32R32F, ds.width(), ds.height());
    for (uint32_t y = 0; y < ds.height(); ++y)
        for (uint32_t x = 0; x < ds.width(); ++x) {
            const float z = ds.depth(x, y);
            out.write(x, y, 0, Float4{z, z, z, 1.0f});
        }
    return out;
}

Surface stencil_as_surface(const DepthStencilSurface& ds) {
    Surface out(Format::A8R8G8B8, ds.width(), ds.height());
    for (uint32_t y = 0; y < ds.height(); ++y)
        for (uint32_t x = 0; x < ds.width(); ++x) {
            const float s = static_cast<float>(ds.stencil(x, y)) / 255.0f;
            out.write(x, y, 0, Float4{s, s, s, 1.0f});
        }
    return out;
}

void write_surface(const Surface& surface, const std::string& path) {
    if (surface.width() == 0 || surface.height() == 0) fail(path, "empty surface");
    // Checked before decoding so that an unknown extension is reported without work.
    if (file_kind(path) == FileKind::Other)
        fail(path, "unknown image file extension (expected .png, .tga, .exr or .raw)");
    write_image(surface_image(surface), path);
}

Image read_image(const std::string& path, const ImageReadLimits& limits) {
    if (file_kind(path) == FileKind::Raw)
        fail(path, ".raw files have no header, so their size is unknown; compare .exr files for float data");
    std::string error;
    if (!check_input_file(path, kMaxImageFileBytes, error)) throw ImageIoError(error);
    // Size checks before any pixel is allocated: sides up to limits.max_side (so that w * h
    // cannot overflow), and w * h RGBA floats within limits.max_bytes.
    auto check_size = [&](uint64_t w, uint64_t h) {
        if (w == 0 || h == 0) fail(path, "empty image");
        if (w > limits.max_side || h > limits.max_side)
            fail(path, std::to_string(w) + "x" + std::to_string(h) + " is larger than " +
                           std::to_string(limits.max_side) + " pixels per side");
        if (w * h > limits.max_bytes / 16)
            fail(path, std::to_string(w) + "x" + std::to_string(h) + " needs " + std::to_string(w * h * 16) +
                           " bytes as float RGBA, more than the " + std::to_string(limits.max_bytes) + "-byte limit");
    };
    {
        // DDS files go through the project's own reader (exact bits, every D3DFORMAT; DXTn decoded).
        std::ifstream in(path, std::ios::binary);
        char magic[4] = {};
        in.read(magic, 4);
        if (in.gcount() == 4 && std::memcmp(magic, "DDS ", 4) == 0) {
            const auto data = read_file_limited(path, kMaxImageFileBytes, error);
            if (!data) throw ImageIoError(error);
            Texture texture;
            try {
                texture = load_dds(*data, path);
            } catch (const TextureIoError& e) {
                throw ImageIoError(e.what());
            }
            if (texture.type() != TextureType::Texture2D) fail(path, "cube and volume DDS files cannot be compared");
            const Surface& s = texture.surface(0, 0);
            check_size(s.width(), s.height());
            return surface_image(s);
        }
    }
    const image_codec::Functions& f = codec(path);
    image_codec::Info spec;
    image_codec::OpenStatus status{};
    image_codec::Reader input(&f, f.open(path.c_str(), &spec, &status, &error));
    if (status != image_codec::OpenStatus::Ok) fail(path, "cannot read image: " + error);
    if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0) fail(path, "empty image");
    if (spec.depth > 1) fail(path, "volume images are not supported");
    check_size(static_cast<uint64_t>(spec.width), static_cast<uint64_t>(spec.height));
    const auto w = static_cast<uint32_t>(spec.width), h = static_cast<uint32_t>(spec.height);
    // At most 4 channels are read (a file may declare any number), straight into the RGBA
    // buffer, then spread out in place: the image costs w * h * 16 bytes and no more.
    const int channels = std::min(spec.channels, 4);
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(size_t{w} * h * 4);
    if (!input.read(channels, image.rgba.data(), error)) fail(path, "cannot read pixels: " + error);
    const size_t c = static_cast<size_t>(channels);
    for (size_t i = size_t{w} * h; i-- > 0;) {  // last pixel first: never overwrites unread input
        float p[4] = {0, 0, 0, 1};
        std::copy_n(&image.rgba[i * c], c, p);
        float* o = &image.rgba[i * 4];
        if (channels <= 2) {  // grey (and alpha)
            o[0] = o[1] = o[2] = p[0];
            o[3] = channels == 2 ? p[1] : 1.0f;
        } else {
            o[0] = p[0];
            o[1] = p[1];
            o[2] = p[2];
            o[3] = channels == 4 ? p[3] : 1.0f;
        }
    }
    return image;
}

DiffVerdict diff_verdict(const ImageDifference& d, const DiffThresholds& t) {
    const double allowed_failures = t.fail_percent / 100.0 * static_cast<double>(d.pixels);
    if (static_cast<double>(d.differing_pixels) > allowed_failures || d.max_abs_error > t.hard_fail)
        return DiffVerdict::Failure;
    if (d.warning_pixels > 0 || d.differing_pixels > 0) return DiffVerdict::Warning;
    return DiffVerdict::Pass;
}

const char* to_string(DiffVerdict v) {
    switch (v) {
    case DiffVerdict::Pass: return "PASS";
    case DiffVerdict::Warning: return "WARNING";
    case DiffVerdict::Failure: return "FAILURE";
    }
    return "?";
}

ImageDifference compare_images(const Image& a, const Image& b, const DiffThresholds& thresholds) {
    check_same_size(a, b);
    ImageDifference d;
    d.pixels = uint64_t{a.width} * a.height;
    if (d.pixels == 0) {  // nothing differs (OpenImageIO would divide by zero)
        d.psnr_db = std::numeric_limits<double>::infinity();
        return d;
    }
    const image_codec::Functions& f = codec("image comparison");
    image_codec::CompareStats stats;
    std::string error;
    if (!f.compare(a.width, a.height, a.rgba.data(), b.rgba.data(), static_cast<float>(thresholds.fail),
                   static_cast<float>(thresholds.warn), &stats, &error))
        throw ImageIoError(error);
    d.max_abs_error = stats.max_error;
    d.worst_x = static_cast<uint32_t>(stats.max_x);
    d.worst_y = static_cast<uint32_t>(stats.max_y);
    d.worst_channel = static_cast<uint32_t>(stats.max_channel);
    d.mean_abs_error = stats.mean_error;
    d.rms_error = stats.rms_error;
    d.psnr_db = stats.psnr;
    d.differing_pixels = stats.fail_pixels;
    d.warning_pixels = stats.warn_pixels;
    return d;
}

ImageDifference compare_images(const Image& a, const Image& b, double tolerance) {
    return compare_images(a, b, DiffThresholds{tolerance, tolerance});
}

Image difference_heatmap(const Image& a, const Image& b, double scale) {
    check_same_size(a, b);
    if (!(scale > 0.0) || std::isinf(scale))
        throw ImageIoError("heat map scale must be a positive number (got " + std::to_string(scale) + ")");
    const image_codec::Functions& f = codec("heat map");
    Image map;
    map.width = a.width;
    map.height = a.height;
    map.rgba.resize(a.rgba.size());
    std::string error;
    if (!f.heatmap(a.width, a.height, a.rgba.data(), b.rgba.data(), static_cast<float>(scale), map.rgba.data(), &error))
        throw ImageIoError(error);
    return map;
}

std::string png_thumbnail_base64(const Image& image, uint32_t max_side, bool keep_peaks) {
    check_image(image, "thumbnail");
    if (image.width == 0 || image.height == 0 || max_side == 0) throw ImageIoError("thumbnail: empty image");
    const image_codec::Functions& f = codec("thumbnail");
    std::string base64, error;
    if (!f.png_thumbnail(image.width, image.height, image.rgba.data(), max_side, keep_peaks, &base64, &error))
        throw ImageIoError(error);
    return base64;
}

}  // namespace sm2::runtime
