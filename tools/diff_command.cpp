// sm2 diff: compare two images (render output against a reference) and optionally write a heat map.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
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

int run_diff(const DiffOptions& o) {
    try {
        const runtime::Image a = runtime::read_image(o.a);
        const runtime::Image b = runtime::read_image(o.b);
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

}  // namespace

void add_diff_command(CLI::App& app, int& status) {
    auto o = std::make_shared<DiffOptions>();
    auto* cmd = app.add_subcommand(
        "diff", "Compare two images: max/mean absolute error, PSNR, differing pixels; exit 1 if any pixel "
                "differs by more than the tolerance");
    cmd->add_option("a", o->a, "First image (PNG, TGA, EXR, ... anything OpenImageIO reads)")->required();
    cmd->add_option("b", o->b, "Second image, same size")->required();
    cmd->add_option("--tolerance", o->tolerance, "Per-channel absolute difference allowed (default 0)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--heatmap", o->heatmap, "Write a heat map of |a - b| (black = equal, red = scale or more)");
    cmd->add_option("--heatmap-scale", o->heatmap_scale,
                    "Error shown as full red (default: the max abs error)")
        ->check(CLI::PositiveNumber);
    cmd->callback([o, &status] { status = run_diff(*o); });
}

}  // namespace sm2::tools
