// sm2 diff: compare two images, or two folders of images matched by name, as idiff does (exit
// statuses, thresholds, verdict line), with a heat map, JSON and an HTML summary when asked.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "commands.h"
#include "image_compare.h"
#include "io.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/image_io.h"

namespace sm2::tools {

namespace {

struct DiffOptions {
    std::string a, b;
    ThresholdOptions thresholds;
    std::string heatmap;
    std::optional<double> heatmap_scale;
    bool json = false;
    std::string html;
};

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

// The image files of a folder (by extension), by name.
std::set<std::string> image_names(const std::filesystem::path& folder) {
    static const std::set<std::string> kExtensions = {".png", ".tga", ".exr", ".dds", ".jpg", ".jpeg",
                                                      ".hdr", ".tif", ".tiff", ".bmp"};
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        std::string ext = entry.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
        if (kExtensions.count(ext) != 0 && entry.is_regular_file(ec)) names.insert(entry.path().filename().string());
    }
    return names;
}

bool write_html(const std::string& path, const std::string& html) {
    std::string error;
    if (write_output(path, html, error)) return true;
    std::cerr << "sm2 diff: " << error << '\n';
    return false;
}

int diff_folders(const DiffOptions& o, const runtime::DiffThresholds& t) {
    namespace fs = std::filesystem;
    const std::set<std::string> in_a = image_names(o.a), in_b = image_names(o.b);
    std::set<std::string> names = in_a;
    names.insert(in_b.begin(), in_b.end());
    std::vector<ImageComparison> comparisons;
    std::vector<std::string> rows;
    for (const auto& name : names) {
        ImageComparison c;
        c.name = name;
        runtime::Image a, b;
        bool read = false;
        if (in_a.count(name) == 0 || in_b.count(name) == 0) {
            c.status = kDiffUnreadable;
            c.error = "only in " + (in_a.count(name) ? o.a : o.b);
        } else {
            try {
                a = runtime::read_image((fs::path(o.a) / name).string());
                b = runtime::read_image((fs::path(o.b) / name).string());
                read = true;
                c = compare_loaded(name, a, b, t);
            } catch (const runtime::ImageIoError& e) {
                c.status = kDiffUnreadable;
                c.error = e.what();
            }
        }
        if (!o.json) std::cout << summary_line(c) << '\n';
        if (!o.html.empty()) rows.push_back(html_row(c, read ? &a : nullptr, read ? &b : nullptr));
        comparisons.push_back(std::move(c));
    }
    int status = kDiffPass;
    size_t count[5] = {};
    for (const auto& c : comparisons) {
        status = std::max(status, c.status);
        ++count[c.status];
    }
    if (comparisons.empty()) {
        std::cerr << "sm2 diff: no images in " << o.a << " or " << o.b << '\n';
        status = kDiffUnreadable;
    }
    if (o.json) {
        nlohmann::ordered_json j = {{"a", o.a}, {"b", o.b}, {"images", nlohmann::ordered_json::array()}};
        for (const auto& c : comparisons) j["images"].push_back(to_json(c));
        j["verdict"] = status_word(status);
        j["status"] = status;
        std::cout << json_text(j) << '\n';
    } else {
        std::cout << comparisons.size() << " images: " << count[kDiffPass] << " pass, " << count[kDiffWarning]
                  << " warning, " << count[kDiffFailure] << " failure, " << count[kDiffSizeMismatch]
                  << " size mismatch, " << count[kDiffUnreadable] << " unreadable or missing\n"
                  << status_word(status) << '\n';
    }
    if (!o.html.empty() && !write_html(o.html, html_report("sm2 diff " + o.a + " " + o.b, comparisons, rows)))
        return std::max(status, static_cast<int>(kDiffUnreadable));
    return status;
}

int diff_files(const DiffOptions& o, const runtime::DiffThresholds& t) {
    runtime::Image a, b;
    ImageComparison c;
    try {
        a = read_image_argument(o.a);
        b = read_image_argument(o.b);
        c = compare_loaded(display_name(o.a), a, b, t);
    } catch (const runtime::ImageIoError& e) {
        c.name = display_name(o.a);
        c.status = kDiffUnreadable;
        c.error = e.what();
    }
    const bool compared = c.status != kDiffSizeMismatch && c.status != kDiffUnreadable;
    if (!compared) std::cerr << "sm2 diff: " << c.error << '\n';
    if (o.json) {
        nlohmann::ordered_json j = {{"a", display_name(o.a)}, {"b", display_name(o.b)}};
        const nlohmann::ordered_json numbers = to_json(c);
        for (const auto& [key, value] : numbers.items())
            if (key != "name") j[key] = value;
        std::cout << json_text(j) << '\n';
    } else if (!compared) {
        std::cout << status_word(c.status) << '\n';
    } else {
        print_report(std::cout, c, t);
    }
    if (compared && !o.heatmap.empty()) {
        // By default the worst pixel is full red. The heat map is a by-product: failing to write
        // it is said, and changes no verdict.
        double scale = o.heatmap_scale.value_or(c.difference.max_abs_error);
        if (!(scale > 0.0) || std::isinf(scale)) scale = 1.0;
        try {
            runtime::write_image(runtime::difference_heatmap(a, b, scale), o.heatmap);
        } catch (const runtime::ImageIoError& e) {
            std::cerr << "sm2 diff: heat map not written: " << e.what() << '\n';
        }
    }
    if (!o.html.empty()) {
        const std::string row = html_row(c, compared ? &a : nullptr, compared ? &b : nullptr);
        if (!write_html(o.html, html_report("sm2 diff " + display_name(o.a) + " " + display_name(o.b), {c}, {row})))
            return std::max(c.status, static_cast<int>(kDiffUnreadable));
    }
    return c.status;
}

int run_diff(const DiffOptions& o) {
    if (o.a == "-" && o.b == "-") {
        std::cerr << "sm2 diff: only one of the two images can be read from stdin\n";
        return kBadUsage;
    }
    std::error_code ec;
    const bool folder_a = o.a != "-" && std::filesystem::is_directory(o.a, ec);
    const bool folder_b = o.b != "-" && std::filesystem::is_directory(o.b, ec);
    if (folder_a != folder_b) {
        std::cerr << "sm2 diff: " << (folder_a ? o.a : o.b) << " is a folder and " << (folder_a ? o.b : o.a)
                  << " is not: compare two images or two folders\n";
        return kDiffUnreadable;
    }
    const runtime::DiffThresholds t = o.thresholds.thresholds();
    if (!folder_a) return diff_files(o, t);
    if (!o.heatmap.empty()) {
        std::cerr << "sm2 diff: --heatmap names one image: with folders, --html shows each pair's heat map\n";
        return kBadUsage;
    }
    return diff_folders(o, t);
}

}  // namespace

void add_diff_command(CLI::App& app, int& status) {
    auto o = std::make_shared<DiffOptions>();
    auto* cmd = app.add_subcommand(
        "diff", "Compare two images, or two folders of images matched by name, as OpenImageIO's idiff: max error "
                "and where, RMS, PSNR, a PASS/WARNING/FAILURE line; exit 0 pass, 1 warning, 2 failure, 3 sizes "
                "differ, 4 a file unreadable or missing");
    cmd->add_option("a", o->a, "First image (PNG, TGA, EXR, DDS, ... anything OpenImageIO reads; '-' for stdin) or folder")
        ->required();
    cmd->add_option("b", o->b, "Second image, same size ('-' for stdin), or folder")->required();
    o->thresholds.add_to(*cmd);
    cmd->add_option("--heatmap", o->heatmap,
                    "Write a heat map of |a - b| (black = equal, red = scale or more); two images only");
    cmd->add_option("--heatmap-scale", o->heatmap_scale, "Error shown as full red (default: the max abs error)")
        ->check(positive_number());
    cmd->add_flag("--json", o->json, "The numbers as JSON on stdout instead of text");
    cmd->add_option("--html", o->html, "Write an HTML summary with thumbnails of A, B and the heat map of each pair");
    cmd->callback([o, &status] { status = run_diff(*o); });
}

}  // namespace sm2::tools
