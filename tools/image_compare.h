// Image comparison as `sm2 diff` and `sm2 replay --compare` report it (docs/inspection.md):
// idiff's thresholds and verdicts, exit statuses, text, JSON and an HTML summary.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sm2/runtime/image_io.h"

namespace sm2::tools {

// Exit statuses of a comparison, as idiff's; a set of comparisons exits with the largest.
enum DiffStatus : int { kDiffPass = 0, kDiffWarning = 1, kDiffFailure = 2, kDiffSizeMismatch = 3, kDiffUnreadable = 4 };

// Option checks with readable messages; NaN is refused (every comparison with it is false).
[[nodiscard]] CLI::Validator non_negative_number();
[[nodiscard]] CLI::Validator positive_number();
// "%.6g", "inf" for infinity.
[[nodiscard]] std::string number(double v);

// --fail, --warn, --failpercent, --hardfail (and --tolerance, the older name of --fail) on `cmd`;
// thresholds() gives them with --warn defaulting to --fail.
struct ThresholdOptions {
    double fail = 0.0;
    std::optional<double> warn;
    double fail_percent = 0.0;
    std::optional<double> hard_fail;
    void add_to(CLI::App& cmd);
    [[nodiscard]] runtime::DiffThresholds thresholds() const;
};

// One comparison of A against B: the difference, or why there is none (size, unreadable file).
struct ImageComparison {
    std::string name;  // the file name (folders), or A's path
    int status = kDiffPass;
    std::string error;  // kDiffSizeMismatch, kDiffUnreadable: the reason
    uint32_t width = 0, height = 0;
    runtime::ImageDifference difference{};
    runtime::DiffVerdict verdict = runtime::DiffVerdict::Pass;
};

// Compares two images already read; sizes that differ give kDiffSizeMismatch.
[[nodiscard]] ImageComparison compare_loaded(const std::string& name, const runtime::Image& a,
                                             const runtime::Image& b, const runtime::DiffThresholds& t);
// Reads and compares two files; a file that cannot be read gives kDiffUnreadable.
[[nodiscard]] ImageComparison compare_files(const std::string& name, const std::string& a, const std::string& b,
                                            const runtime::DiffThresholds& t);

// "PASS", "WARNING", "FAILURE", "SIZE MISMATCH", "UNREADABLE".
[[nodiscard]] const char* status_word(int status);
// The full report of one comparison, a line each, the verdict last.
void print_report(std::ostream& out, const ImageComparison& c, const runtime::DiffThresholds& t);
// One line: "name: VERDICT, max error 0.5 at (1, 1) R, PSNR 18 dB, 1 of 4 pixels over 0".
[[nodiscard]] std::string summary_line(const ImageComparison& c);
[[nodiscard]] nlohmann::ordered_json to_json(const ImageComparison& c);
// Indented JSON text; bytes of names that are not UTF-8 (file names may be anything) become
// U+FFFD instead of an exception.
[[nodiscard]] std::string json_text(const nlohmann::ordered_json& j);

// HTML: a row per comparison with its numbers and thumbnails of A, B and the heat map (built as
// each pair is compared, so that a folder's images are not all held at once; a and b are null
// where they were not read), then the page around the rows.
[[nodiscard]] std::string html_row(const ImageComparison& c, const runtime::Image* a, const runtime::Image* b);
[[nodiscard]] std::string html_report(const std::string& title, const std::vector<ImageComparison>& comparisons,
                                      const std::vector<std::string>& rows);

}  // namespace sm2::tools
