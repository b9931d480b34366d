// Image comparison reports shared by sm2 diff and sm2 replay --compare (image_compare.h).
#include "image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sm2::tools {

namespace {

const char* const kChannelNames[] = {"R", "G", "B", "A"};

const char* channel_name(uint32_t c) { return c < 4 ? kChannelNames[c] : "?"; }

std::string percent(uint64_t count, uint64_t total) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g%%", total == 0 ? 0.0 : 100.0 * static_cast<double>(count) / static_cast<double>(total));
    return buf;
}

// JSON has no infinity: null stands for it.
nlohmann::ordered_json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

std::string html_escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string check_number(const std::string& text, bool positive) {
    double v = 0;
    if (!CLI::detail::lexical_cast(text, v) || std::isnan(v)) return "'" + text + "' is not a number";
    if (positive && !(v > 0)) return "'" + text + "' is not positive: give a number above 0";
    if (!positive && v < 0) return "'" + text + "' is negative: give 0 or more";
    return {};
}

}  // namespace

CLI::Validator non_negative_number() {
    return CLI::Validator([](const std::string& text) { return check_number(text, false); }, "NUMBER >= 0", "non-negative");
}
CLI::Validator positive_number() {
    return CLI::Validator([](const std::string& text) { return check_number(text, true); }, "NUMBER > 0", "positive");
}

std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

void ThresholdOptions::add_to(CLI::App& cmd) {
    auto* fail_option = cmd.add_option("--fail", fail,
                                       "A pixel fails when a channel differs by more than this (absolute, 0-1 for "
                                       "8-bit images; default 0)")
                            ->check(non_negative_number());
    cmd.add_option("--tolerance", fail, "The older name of --fail")->check(non_negative_number())->excludes(fail_option);
    cmd.add_option("--warn", warn, "A pixel warns when a channel differs by more than this (default: --fail)")
        ->check(non_negative_number());
    cmd.add_option("--failpercent", fail_percent,
                   "Percentage of failing pixels allowed: up to it the verdict is WARNING, not FAILURE (default 0)")
        ->check(CLI::Range(0.0, 100.0));
    cmd.add_option("--hardfail", hard_fail, "FAILURE if any channel differs by more than this, whatever --failpercent")
        ->check(non_negative_number());
}

runtime::DiffThresholds ThresholdOptions::thresholds() const {
    runtime::DiffThresholds t;
    t.fail = fail;
    t.warn = warn.value_or(fail);
    t.fail_percent = fail_percent;
    if (hard_fail) t.hard_fail = *hard_fail;
    return t;
}

ImageComparison compare_loaded(const std::string& name, const runtime::Image& a, const runtime::Image& b,
                               const runtime::DiffThresholds& t) {
    ImageComparison c;
    c.name = name;
    c.width = a.width;
    c.height = a.height;
    if (a.width != b.width || a.height != b.height) {
        c.status = kDiffSizeMismatch;
        c.error = "image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                  std::to_string(b.width) + "x" + std::to_string(b.height);
        return c;
    }
    try {
        c.difference = runtime::compare_images(a, b, t);
    } catch (const runtime::ImageIoError& e) {  // the image module is missing
        c.status = kDiffUnreadable;
        c.error = e.what();
        return c;
    }
    c.verdict = runtime::diff_verdict(c.difference, t);
    c.status = c.verdict == runtime::DiffVerdict::Pass ? kDiffPass
               : c.verdict == runtime::DiffVerdict::Warning ? kDiffWarning
                                                           : kDiffFailure;
    return c;
}

ImageComparison compare_files(const std::string& name, const std::string& a, const std::string& b,
                              const runtime::DiffThresholds& t) {
    runtime::Image image_a, image_b;
    try {
        image_a = runtime::read_image(a);
        image_b = runtime::read_image(b);
    } catch (const runtime::ImageIoError& e) {
        ImageComparison c;
        c.name = name;
        c.status = kDiffUnreadable;
        c.error = e.what();
        return c;
    }
    return compare_loaded(name, image_a, image_b, t);
}

const char* status_word(int status) {
    switch (status) {
    case kDiffPass: return "PASS";
    case kDiffWarning: return "WARNING";
    case kDiffFailure: return "FAILURE";
    case kDiffSizeMismatch: return "SIZE MISMATCH";
    default: return "UNREADABLE";
    }
}

void print_report(std::ostream& out, const ImageComparison& c, const runtime::DiffThresholds& t) {
    if (c.status == kDiffSizeMismatch || c.status == kDiffUnreadable) {
        out << c.error << '\n' << status_word(c.status) << '\n';
        return;
    }
    const auto& d = c.difference;
    out << "size: " << c.width << "x" << c.height << '\n' << "max abs error: " << number(d.max_abs_error) << '\n';
    if (d.max_abs_error != 0)
        out << "worst pixel: (" << d.worst_x << ", " << d.worst_y << ") channel " << channel_name(d.worst_channel) << '\n';
    out << "mean abs error: " << number(d.mean_abs_error) << '\n'
        << "RMS error: " << number(d.rms_error) << '\n'
        << "PSNR: " << number(d.psnr_db) << " dB\n"
        << "warning pixels: " << d.warning_pixels << " of " << d.pixels << " (" << percent(d.warning_pixels, d.pixels)
        << ") over " << number(t.warn) << '\n'
        << "differing pixels: " << d.differing_pixels << " of " << d.pixels << " ("
        << percent(d.differing_pixels, d.pixels) << ") over " << number(t.fail) << '\n'
        << status_word(c.status) << '\n';
}

std::string summary_line(const ImageComparison& c) {
    std::string line = c.name + ": " + status_word(c.status);
    if (c.status == kDiffSizeMismatch || c.status == kDiffUnreadable) return line + ": " + c.error;
    const auto& d = c.difference;
    line += ", max error " + number(d.max_abs_error);
    if (d.max_abs_error != 0)
        line += " at (" + std::to_string(d.worst_x) + ", " + std::to_string(d.worst_y) + ") " + channel_name(d.worst_channel);
    line += ", PSNR " + number(d.psnr_db) + " dB, " + std::to_string(d.differing_pixels) + " of " +
            std::to_string(d.pixels) + " pixels failing";
    return line;
}

nlohmann::ordered_json to_json(const ImageComparison& c) {
    nlohmann::ordered_json j = {{"name", c.name}, {"verdict", status_word(c.status)}, {"status", c.status}};
    if (c.status == kDiffSizeMismatch || c.status == kDiffUnreadable) {
        j["error"] = c.error;
        return j;
    }
    const auto& d = c.difference;
    j["width"] = c.width;
    j["height"] = c.height;
    j["max_error"] = finite_or_null(d.max_abs_error);
    j["worst_pixel"] = {{"x", d.worst_x}, {"y", d.worst_y}, {"channel", channel_name(d.worst_channel)}};
    j["mean_error"] = d.mean_abs_error;
    j["rms_error"] = d.rms_error;
    j["psnr_db"] = finite_or_null(d.psnr_db);
    j["pixels"] = d.pixels;
    j["warning_pixels"] = d.warning_pixels;
    j["failing_pixels"] = d.differing_pixels;
    return j;
}

std::string json_text(const nlohmann::ordered_json& j) {
    return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string html_row(const ImageComparison& c, const runtime::Image* a, const runtime::Image* b) {
    constexpr uint32_t kThumbnailSide = 160;
    auto cell = [](const runtime::Image* image, bool keep_peaks = false) -> std::string {
        if (image == nullptr) return "<td></td>";
        try {
            return "<td><img alt=\"\" src=\"data:image/png;base64," +
                   runtime::png_thumbnail_base64(*image, kThumbnailSide, keep_peaks) + "\"></td>";
        } catch (const runtime::ImageIoError& e) {
            return "<td>" + html_escape(e.what()) + "</td>";
        }
    };
    const std::string word = status_word(c.status);
    std::string html = "<tr><td>" + html_escape(c.name) + "</td><td class=\"" + word.substr(0, word.find(' ')) +
                       "\">" + word + "</td><td>";
    const bool compared = c.status != kDiffSizeMismatch && c.status != kDiffUnreadable;
    const auto& d = c.difference;
    if (compared)
        html += "max error " + number(d.max_abs_error) + "<br>PSNR " + number(d.psnr_db) + " dB<br>RMS " +
                number(d.rms_error) + "<br>" + std::to_string(d.differing_pixels) + " of " + std::to_string(d.pixels) +
                " pixels failing";
    else
        html += html_escape(c.error);
    html += "</td>" + cell(a) + cell(b);
    if (compared && a != nullptr && b != nullptr && d.max_abs_error > 0) {
        const double scale = std::isfinite(d.max_abs_error) ? d.max_abs_error : 1.0;
        try {
            const runtime::Image heat = runtime::difference_heatmap(*a, *b, scale);
            html += cell(&heat, true);
        } catch (const runtime::ImageIoError& e) {
            html += "<td>" + html_escape(e.what()) + "</td>";
        }
    } else {
        html += "<td></td>";
    }
    return html + "</tr>\n";
}

std::string html_report(const std::string& title, const std::vector<ImageComparison>& comparisons,
                        const std::vector<std::string>& rows) {
    int worst = kDiffPass;
    for (const auto& c : comparisons) worst = std::max(worst, c.status);
    std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + html_escape(title) +
                       "</title>\n<style>body{font-family:sans-serif}td,th{border:1px solid #ccc;padding:4px;"
                       "vertical-align:top}table{border-collapse:collapse}.PASS{color:green}.WARNING{color:#b80}"
                       ".FAILURE,.SIZE,.UNREADABLE{color:red}img{image-rendering:pixelated}</style></head><body>\n<h1>" +
                       html_escape(title) + "</h1>\n<p>" + std::to_string(comparisons.size()) + " images: <b>" +
                       status_word(worst) +
                       "</b></p>\n<table>\n<tr><th>image</th><th>verdict</th><th>numbers</th><th>A</th><th>B</th>"
                       "<th>|A - B| (red: the max error)</th></tr>\n";
    for (const auto& row : rows) html += row;
    return html + "</table>\n</body></html>\n";
}

}  // namespace sm2::tools
