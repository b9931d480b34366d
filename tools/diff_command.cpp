// sm2 diff: compare two images (render output against a reference) and optionally write a heat map.
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <vector>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/image_io.h"

namespace sm2::tools {

namespace {

struct DiffOptions {
    std::string a, b;
    double tolerance = 0.0;
    std::string heatmap;
    std::optional<double> heatmap_scale;
};

std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// The image file's extension from its first bytes, for OpenImageIO, which picks its reader by
// name (TGA has no signature: the fallback).
std::string extension_for(const std::vector<std::byte>& bytes) {
    auto starts = [&](std::string_view magic) {
        return bytes.size() >= magic.size() && std::memcmp(bytes.data(), magic.data(), magic.size()) == 0;
    };
    if (starts("\x89PNG")) return ".png";
    if (starts("\x76\x2f\x31\x01")) return ".exr";
    if (starts("DDS ")) return ".dds";
    if (starts("\xff\xd8\xff")) return ".jpg";
    if (starts("#?RADIANCE") || starts("#?RGBE")) return ".hdr";
    return ".tga";
}

// An image from a file, or from stdin for "-" (copied to a temporary file, read, and removed).
runtime::Image read_image_argument(const std::string& path) {
    if (path != "-") return runtime::read_image(path);
    std::string error;
    const auto bytes = runtime::read_file_limited("-", runtime::kMaxImageFileBytes, error);
    if (!bytes) throw runtime::ImageIoError(error);
    const char* tmp = std::getenv("TMPDIR");
    const std::string ext = extension_for(*bytes);
    std::string name = std::string(tmp && *tmp ? tmp : "/tmp") + "/sm2-diff-stdin-XXXXXX" + ext;
    const int fd = ::mkstemps(name.data(), static_cast<int>(ext.size()));
    if (fd < 0) throw runtime::ImageIoError("<stdin>: cannot create a temporary file: " + std::string(std::strerror(errno)));
    struct Remove {
        std::string path;
        ~Remove() { ::unlink(path.c_str()); }
    } remove{name};
    size_t done = 0;
    while (done < bytes->size()) {
        const ssize_t n = ::write(fd, bytes->data() + done, bytes->size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            ::close(fd);
            throw runtime::ImageIoError("<stdin>: cannot write a temporary file: " + std::string(std::strerror(errno)));
        }
        done += static_cast<size_t>(n);
    }
    ::close(fd);
    try {
        return runtime::read_image(name);
    } catch (const runtime::ImageIoError& e) {
        std::string message = e.what();
        if (message.rfind(name, 0) == 0) message = "<stdin>" + message.substr(name.size());
        throw runtime::ImageIoError(message);
    }
}

int run_diff(const DiffOptions& o) {
    if (o.a == "-" && o.b == "-") {
        std::cerr << "sm2 diff: only one of the two images can be read from stdin\n";
        return kBadUsage;
    }
    try {
        const runtime::Image a = read_image_argument(o.a);
        const runtime::Image b = read_image_argument(o.b);
        const runtime::ImageDifference d = runtime::compare_images(a, b, o.tolerance);
        const uint64_t total = uint64_t{a.width} * a.height;
        std::cout << "size: " << a.width << "x" << a.height << '\n'
                  << "max abs error: " << number(d.max_abs_error) << '\n'
                  << "mean abs error: " << number(d.mean_abs_error) << '\n'
                  << "PSNR: " << number(d.psnr_db) << " dB\n"
                  << "differing pixels: " << d.differing_pixels << " of " << total << " (tolerance "
                  << number(o.tolerance) << ")\n";
        if (!o.heatmap.empty()) {
            // By default the worst pixel is full red.
            double scale = o.heatmap_scale.value_or(d.max_abs_error);
            if (!(scale > 0.0) || std::isinf(scale)) scale = 1.0;
            runtime::write_image(runtime::difference_heatmap(a, b, scale), o.heatmap);
        }
        return d.differing_pixels > 0 ? kInvalidInput : kOk;
    } catch (const runtime::ImageIoError& e) {
        std::cerr << "sm2 diff: " << e.what() << '\n';
        return kInvalidInput;
    }
}

// Range checks with readable messages (CLI11's own print the range's bound, DBL_MAX in full).
// NaN is refused too: every comparison with it is false, so a NaN tolerance would make every
// pixel equal.
std::string non_negative(const std::string& text) {
    double v = 0;
    if (!CLI::detail::lexical_cast(text, v) || std::isnan(v)) return "'" + text + "' is not a number";
    if (v < 0) return "'" + text + "' is negative: give 0 or more";
    return {};
}
std::string positive(const std::string& text) {
    double v = 0;
    if (!CLI::detail::lexical_cast(text, v) || std::isnan(v)) return "'" + text + "' is not a number";
    if (!(v > 0)) return "'" + text + "' is not positive: give a number above 0";
    return {};
}

}  // namespace

void add_diff_command(CLI::App& app, int& status) {
    auto o = std::make_shared<DiffOptions>();
    auto* cmd = app.add_subcommand(
        "diff", "Compare two images: max/mean absolute error, PSNR, differing pixels; exit 1 if any pixel "
                "differs by more than the tolerance");
    cmd->add_option("a", o->a, "First image (PNG, TGA, EXR, DDS, ... anything OpenImageIO reads; '-' for stdin)")
        ->required();
    cmd->add_option("b", o->b, "Second image, same size ('-' for stdin)")->required();
    cmd->add_option("--tolerance", o->tolerance, "Per-channel absolute difference allowed (default 0)")
        ->check(CLI::Validator(non_negative, "NUMBER >= 0", "non-negative"));
    cmd->add_option("--heatmap", o->heatmap, "Write a heat map of |a - b| (black = equal, red = scale or more)");
    cmd->add_option("--heatmap-scale", o->heatmap_scale,
                    "Error shown as full red (default: the max abs error)")
        ->check(CLI::Validator(positive, "NUMBER > 0", "positive"));
    cmd->callback([o, &status] { status = run_diff(*o); });
}

}  // namespace sm2::tools
