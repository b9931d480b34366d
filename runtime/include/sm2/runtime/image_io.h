// Writing surfaces to image files and comparing images (Present, SaveSurface, sm2 diff).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "sm2/runtime/surface.h"

namespace sm2::runtime {

class ImageIoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Writes `surface` (level/face/slice 0 of depth 1) by the file's extension: .png and .tga as
// 8-bit RGBA (values clamped to [0,1] and rounded, as the format's decode gives them), .exr as
// half or float RGBA, .raw as the float RGBA values (little-endian, row-major, no header).
// Throws ImageIoError with the path in the message.
void write_surface(const Surface& surface, const std::string& path);

// An image read back as float RGBA, row-major.
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;  // width * height * 4
};
// What read_image accepts, checked from the header before any pixel is allocated: sides up to
// max_side and width x height x 16 bytes (float RGBA) up to max_bytes (default 16384 per side,
// 1 GiB: an 8192x8192 image). The file must be a regular file of at most kMaxImageFileBytes.
struct ImageReadLimits {
    uint64_t max_side = 16384;
    uint64_t max_bytes = uint64_t{1} << 30;
};
// PNG, TGA, EXR, ... through OpenImageIO; DDS through texture_io's reader (level 0 of a 2D
// texture). Throws ImageIoError with the path and the reason.
[[nodiscard]] Image read_image(const std::string& path, const ImageReadLimits& limits = {});

struct ImageDifference {
    double max_abs_error = 0;      // over all channels
    double mean_abs_error = 0;
    double psnr_db = 0;            // infinity when identical (peak 1.0)
    uint64_t differing_pixels = 0; // pixels with any channel differing by more than the tolerance
};
// Sizes must match (ImageIoError otherwise). `tolerance` is per channel, absolute.
[[nodiscard]] ImageDifference compare_images(const Image& a, const Image& b, double tolerance = 0.0);
// A heat map of |a - b| (max over channels) scaled so that `scale` maps to full red.
[[nodiscard]] Image difference_heatmap(const Image& a, const Image& b, double scale);
void write_image(const Image& image, const std::string& path);

}  // namespace sm2::runtime
