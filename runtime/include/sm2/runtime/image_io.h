// Writing surfaces to image files and comparing images (Present, SaveSurface, sm2 diff).
#pragma once

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sm2/runtime/depth_stencil.h"
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

// An image comparison (sm2 diff), computed by OpenImageIO's ImageBufAlgo::compare: errors are
// absolute differences per channel. A channel that is NaN or infinite on one side only makes
// max_abs_error infinite (at that pixel) and is left out of the mean, RMS and pixel counts;
// NaN against NaN and equal infinities are equal.
struct ImageDifference {
    uint64_t pixels = 0;            // width x height
    double max_abs_error = 0;       // over all channels
    uint32_t worst_x = 0, worst_y = 0, worst_channel = 0;  // where it is (0 R, 1 G, 2 B, 3 A)
    double mean_abs_error = 0;
    double rms_error = 0;
    double psnr_db = 0;             // 20 log10(peak / RMS), peak max(1, largest value); infinity when RMS is 0
    uint64_t differing_pixels = 0;  // pixels with a channel differing by more than the fail threshold
    uint64_t warning_pixels = 0;    // ... by more than the warn threshold
};

// idiff's thresholds (absolute difference per channel): a pixel fails or warns when a channel
// differs by more than `fail` or `warn` (an equal error is allowed).
struct DiffThresholds {
    double fail = 0.0;
    double warn = 0.0;
    double fail_percent = 0.0;  // percentage of failing pixels allowed before FAILURE (a WARNING then)
    double hard_fail = std::numeric_limits<double>::max();  // FAILURE if any error is above it (infinite ones are)
};
enum class DiffVerdict { Pass, Warning, Failure };
// FAILURE when failing pixels are more than fail_percent of the image or the max error is above
// hard_fail; otherwise WARNING when any pixel warns or fails; otherwise PASS.
[[nodiscard]] DiffVerdict diff_verdict(const ImageDifference& d, const DiffThresholds& t);
[[nodiscard]] const char* to_string(DiffVerdict v);  // "PASS", "WARNING", "FAILURE"

// Sizes must match (ImageIoError otherwise).
[[nodiscard]] ImageDifference compare_images(const Image& a, const Image& b, const DiffThresholds& thresholds = {});
// `tolerance` as both the fail and the warn threshold.
[[nodiscard]] ImageDifference compare_images(const Image& a, const Image& b, double tolerance);
// A heat map of |a - b| (max over channels) scaled so that `scale` maps to full red (ImageBufAlgo's
// absdiff, maxchan and color_map). Non-finite differences show black.
[[nodiscard]] Image difference_heatmap(const Image& a, const Image& b, double scale);
// The image shrunk to fit max_side x max_side, as 8-bit PNG bytes in base64 (for HTML reports);
// `keep_peaks` makes each thumbnail pixel the largest of those it stands for (heat maps).
[[nodiscard]] std::string png_thumbnail_base64(const Image& image, uint32_t max_side, bool keep_peaks = false);
// A surface (level/face/slice 0) as float RGBA, as its format's decode gives it.
[[nodiscard]] Image surface_image(const Surface& surface);
void write_image(const Image& image, const std::string& path);
// A depth/stencil surface as colour surfaces to write (SaveSurface, sm2 replay --snapshot):
// depth as A32B32G32R32F (z, z, z, 1), the float value each texel stands for (an .exr keeps it);
// stencil as A8R8G8B8 (s, s, s, 255)/255, so that an 8-bit .png holds the integer value s.
[[nodiscard]] Surface depth_as_surface(const DepthStencilSurface& ds);
[[nodiscard]] Surface stencil_as_surface(const DepthStencilSurface& ds);

}  // namespace sm2::runtime
