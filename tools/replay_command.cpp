// sm2 replay / sm2 bench: run a command stream on the Device, writing its frames, or timing it.
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "call_set.h"
#include "commands.h"
#include "image_compare.h"
#include "io.h"
#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/stream_hlsl_compiler.h"
#include "snapshot.h"
#include "stream_io.h"
#include "sm2/emu/jit.h"
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/apitrace_import.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"

namespace sm2::tools {

namespace {

namespace cs = runtime::cs;

runtime::ReplayOptions replay_options(const LoadedStream& loaded) {
    runtime::ReplayOptions options;
    options.file_name = loaded.file_name;
    options.base_dir = loaded.base_dir;
    options.root_dir = loaded.root_dir;
    options.assembler = runtime::stream_assembler();
    options.hlsl_compiler = runtime::stream_hlsl_compiler();
    return options;
}

void print_diagnostics(const std::vector<runtime::ReplayDiagnostic>& diagnostics) {
    for (const auto& d : diagnostics) std::cerr << d.to_string() << '\n';
}

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

// ---------------------------------------------------------------------------------------------
// sm2 replay

// The JIT is the default (kDefaultEngine, commands.h): it gives the interpreter's bytes on every
// sample scene and on the random programs of tests/emu/jit (a build without LLVM interprets).

// The numeric modes of a replay (docs/numerics.md): shader precision, transcendentals and the
// sampler's filter weights. Threads default to every core (the image does not depend on them).
struct NumericCliOptions {
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::string precision = "fp32";
    std::string transcendentals = "exact";
    std::string filter = "fixed8";
    unsigned max_slots = 0;
    std::string engine = kDefaultEngine;
    uint64_t memory_limit_mib = runtime::kDefaultMemoryLimit >> 20;
    std::string read_root;
    std::string jit_cache;

    void add_to(CLI::App& cmd) {
        cmd.add_option("--engine", engine,
                       std::string("How shaders run: interpreter (the reference) or jit (native code per shader; the "
                                   "same bytes). Default: ") + kDefaultEngine)
            ->check(CLI::IsMember({"interpreter", "jit"}));
        cmd.add_option("--jit-cache", jit_cache,
                       "Folder where the JIT keeps the machine code it compiles, made if missing, and a later run "
                       "loads it instead of compiling again (the same code: the same bytes). Sets SM2_JIT_CACHE, "
                       "which names it too; nothing is cached without either");
        cmd.add_option("--threads", threads, "Threads for tiles (default: all cores; the image does not depend on it)")
            ->check(CLI::Range(1u, 256u));
        cmd.add_option("--precision", precision,
                       "Shader arithmetic: fp32 (default), fp24 (ps results as s16e7), fp16 (fp24 and _pp as s10e5); "
                       "fp64, the reference of sm2 run, is named but draws do not run it")
            ->check(CLI::IsMember({"fp32", "fp24", "fp16", "fp64"}));
        cmd.add_option("--transcendentals", transcendentals, "exact (correctly rounded exp, log and pow; default) or fast")
            ->check(CLI::IsMember({"exact", "fast"}));
        cmd.add_option("--filter", filter, "Filter weights: fixed8 (8-bit, as hardware; default) or exact")
            ->check(CLI::IsMember({"fixed8", "exact"}));
        cmd.add_option("--max-slots", max_slots,
                       "Instruction-slot limit shaders are validated against (default: the profile's; e.g. 512 "
                       "for ps_2_x-size shaders)")
            ->check(CLI::Range(1u, 65535u));
        cmd.add_option("--memory-limit", memory_limit_mib,
                       "MiB all resources together may hold; a creation past it is refused with "
                       "D3DERR_OUTOFVIDEOMEMORY and the replay goes on (default " +
                           std::to_string(runtime::kDefaultMemoryLimit >> 20) + ")")
            ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 20));
        add_read_root_option(cmd, read_root);
    }
    // The same --precision words as sm2 run; fp64 (IEEE double, no rounding) is the reference
    // of single shaders, and the Device refuses draws in it: said once, before anything runs.
    bool check(const char* command) const {
        if (precision != "fp64") return true;
        std::cerr << "sm2 " << command << ": --precision fp64 is the reference of single shaders (sm2 run "
                  << "--precision fp64); draws run fp32, fp24 or fp16\n";
        return false;
    }
    void apply(runtime::DeviceOptions& d) const {
        d.threads = threads;
        if (precision != "fp32") d.precision.precision = emu::Precision::Fp24;
        d.precision.partial_precision_fp16 = precision == "fp16";
        if (transcendentals == "fast") d.precision.transcendentals = emu::Transcendentals::Fast;
        d.filter_precision = filter == "exact" ? runtime::FilterPrecision::Exact : runtime::FilterPrecision::Fixed8;
        d.max_instruction_slots = max_slots;
        d.memory_limit = memory_limit_mib << 20;
        d.engine = engine == "jit" ? runtime::DeviceOptions::Engine::Jit : runtime::DeviceOptions::Engine::Interpreter;
        // (Read by the JIT at each compilation: jit.h.)
        if (!jit_cache.empty()) ::setenv("SM2_JIT_CACHE", jit_cache.c_str(), 1);
    }
};

struct ReplayCliOptions {
    std::string stream;
    std::string output;
    NumericCliOptions numeric;
    bool quiet = false;
    bool overwrite = false;
    std::string compare;  // golden folder
    ThresholdOptions thresholds;
    std::string stats;    // "", "table" or "json"
    std::string snapshot;  // call set (call_set.h)
};

// --snapshot: after each call of the set, the bound render targets, depth and stencil as images
// (snapshot.h), through ReplayOptions::after_call (nothing runs per pixel).
class Snapshotter {
public:
    Snapshotter(CallSet set, std::string folder) : set_(std::move(set)), folder_(std::move(folder)) {}
    // ReplayOptions::after_call; stops the replay when an image cannot be written.
    bool after_call(const runtime::Device& device, const cs::Statement& statement, uint64_t call, bool accepted) {
        if (!set_.contains(call, statement.name)) return true;
        // A Present that ran has counted its frame already: it belongs to the frame it ends.
        const uint32_t frame = device.frames_presented() - (accepted && statement.name == "Present" ? 1u : 0u);
        try {
            images_ += write_snapshot(device.inspect(), folder_, call, frame).size();
        } catch (const runtime::ImageIoError& e) {
            error_ = e.what();
            return false;
        }
        // A trace call may replay as several statements: the call is counted once.
        if (call != last_call_ || calls_ == 0) ++calls_;
        last_call_ = call;
        return true;
    }
    // Says what was written; false (and why on stderr) when nothing could be or nothing was selected.
    bool report(const std::string& text, size_t calls_replayed) const {
        if (error_) {
            std::cerr << "sm2 replay: --snapshot: " << *error_ << '\n';
            return false;
        }
        if (calls_ == 0) {
            std::cerr << "sm2 replay: --snapshot '" << text << "': selects none of the " << calls_replayed
                      << " calls replayed\n";
            return false;
        }
        std::cout << "snapshots: " << calls_ << " call" << (calls_ == 1 ? "" : "s") << ", " << images_ << " images in "
                  << folder_ << '\n';
        return true;
    }

private:
    CallSet set_;
    std::string folder_;
    std::optional<std::string> error_;
    size_t calls_ = 0, images_ = 0;
    uint64_t last_call_ = 0;
};

// The --snapshot call set, or nullopt after saying why it is not one.
std::optional<std::optional<Snapshotter>> snapshotter_for(const ReplayCliOptions& o) {
    if (o.snapshot.empty()) return std::optional<Snapshotter>();
    std::string error;
    auto set = CallSet::parse(o.snapshot, error);
    if (!set) {
        std::cerr << "sm2 replay: --snapshot: " << error << '\n';
        return std::nullopt;
    }
    return std::optional<Snapshotter>(Snapshotter(std::move(*set), o.output));
}

// --stats: a row per draw, then the replay's totals.
void print_draw_table(const runtime::ReplayResult& result) {
    std::printf("%7s %7s %6s %11s %11s %11s %11s %9s %10s %10s  %s\n", "call", "line", "frame", "rasterized", "shaded",
                "killed", "written", "vertices", "primitives", "ms", "draw");
    for (const auto& d : result.draws) {
        const auto& s = d.statistics;
        std::printf("%7zu %7u %6zu %11llu %11llu %11llu %11llu %9llu %10llu %10.3f  %s\n", d.call, d.line, d.frame,
                    static_cast<unsigned long long>(s.pixels_rasterized), static_cast<unsigned long long>(s.pixels_shaded),
                    static_cast<unsigned long long>(s.pixels_killed), static_cast<unsigned long long>(s.pixels_written),
                    static_cast<unsigned long long>(s.vertices_shaded), static_cast<unsigned long long>(s.primitives),
                    d.seconds * 1000.0, d.name.c_str());
    }
    const auto& s = result.statistics;
    std::printf("%7s %7s %6s %11llu %11llu %11llu %11llu %9llu %10llu %10s  %zu draws\n", "total", "", "",
                static_cast<unsigned long long>(s.pixels_rasterized), static_cast<unsigned long long>(s.pixels_shaded),
                static_cast<unsigned long long>(s.pixels_killed), static_cast<unsigned long long>(s.pixels_written),
                static_cast<unsigned long long>(s.vertices_shaded), static_cast<unsigned long long>(s.primitives), "",
                result.draws.size());
}

nlohmann::ordered_json draw_json(const runtime::DrawStatistics& s) {
    return {{"pixels_rasterized", s.pixels_rasterized}, {"pixels_shaded", s.pixels_shaded},
            {"pixels_killed", s.pixels_killed},         {"pixels_written", s.pixels_written},
            {"pixels_outside_texture", s.pixels_outside_texture},
            {"vertices_shaded", s.vertices_shaded},     {"primitives", s.primitives}};
}

void print_draw_json(const runtime::ReplayResult& result) {
    nlohmann::ordered_json j = {{"calls", result.calls}, {"frames", result.frames.size()}, {"seconds", result.seconds},
                                {"refused_calls", result.refused}, {"draws", nlohmann::ordered_json::array()}};
    for (const auto& d : result.draws) {
        nlohmann::ordered_json row = {{"call", d.call}, {"line", d.line}, {"record", d.record}, {"frame", d.frame},
                                      {"name", d.name}, {"seconds", d.seconds}};
        row.update(draw_json(d.statistics));
        j["draws"].push_back(std::move(row));
    }
    j["total"] = draw_json(result.statistics);
    std::cout << json_text(j) << '\n';
}

// "call 120/4000, frame 3" on one terminal line, at most ten times a second; calls as the
// summary counts them (comments and blank lines are statements, not calls).
class Progress {
public:
    explicit Progress(bool enabled) : enabled_(enabled) {}
    void update(size_t done, size_t total, size_t calls_done, size_t calls, uint32_t frames) {
        if (!enabled_) return;
        const auto now = std::chrono::steady_clock::now();
        if (done != total && now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        std::fprintf(stderr, "\rreplay: call %zu/%zu, frame %u", calls_done, calls, frames);
        std::fflush(stderr);
        shown_ = true;
    }
    void finish() {
        if (shown_) std::fprintf(stderr, "\r\033[K");
        shown_ = false;
    }

private:
    bool enabled_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point last_{};
};

// The frames an earlier replay left in `folder` (frame_NNNN.png), sorted.
std::vector<std::filesystem::path> old_frames(const std::string& folder) {
    std::vector<std::filesystem::path> frames;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.size() >= 14 && name.rfind("frame_", 0) == 0 && name.ends_with(".png") &&
            std::all_of(name.begin() + 6, name.end() - 4, [](char c) { return c >= '0' && c <= '9'; }))
            frames.push_back(entry.path());
    }
    std::sort(frames.begin(), frames.end());
    return frames;
}

// --compare: each frame, once written, against the golden folder's file of the same name; then
// the golden frames the replay did not write.
class FrameComparer {
public:
    FrameComparer(std::string golden, runtime::DiffThresholds thresholds)
        : golden_(std::move(golden)), thresholds_(thresholds) {}
    void compare(const std::string& written) {
        const std::string name = std::filesystem::path(written).filename().string();
        const ImageComparison c =
            compare_files(name, written, (std::filesystem::path(golden_) / name).string(), thresholds_);
        std::cout << "compare " << summary_line(c) << '\n';
        status_ = std::max(status_, c.status);
        ++compared_;
    }
    // The golden frames past the last one written.
    void missing_frames(uint32_t frames_written) {
        for (const auto& f : old_frames(golden_)) {
            const std::string name = f.filename().string();
            // frame_NNNN.png (old_frames checked the digits); a number too large to parse is past the last.
            uint64_t index = 0;
            const char* digits = name.data() + 6;
            const auto parsed = std::from_chars(digits, name.data() + name.size() - 4, index);
            if (parsed.ec == std::errc() && index < frames_written) continue;
            std::cout << "compare " << name << ": " << status_word(kDiffUnreadable) << ": in " << golden_
                      << ", not written by the replay (" << frames_written << " frames)\n";
            status_ = kDiffUnreadable;
        }
    }
    [[nodiscard]] int status() const { return status_; }
    [[nodiscard]] size_t compared() const { return compared_; }

private:
    std::string golden_;
    runtime::DiffThresholds thresholds_;
    int status_ = kDiffPass;
    size_t compared_ = 0;
};

// A frame Present wrote into `output`: output/frame_NNNN.png.
bool is_frame_of(const std::string& path, const std::string& output) {
    const std::filesystem::path p(path);
    const std::string name = p.filename().string();
    return p.parent_path() == std::filesystem::path(output) && name.size() >= 14 && name.rfind("frame_", 0) == 0 &&
           name.ends_with(".png");
}

// The output folder, created, with no frames of an earlier replay left unless --overwrite
// removes them; a status to exit with when it cannot be had.
std::optional<int> prepare_output(const ReplayCliOptions& o) {
    // A folder with frames of an earlier replay would mix them with this one's.
    if (const auto frames = old_frames(o.output); !frames.empty()) {
        if (!o.overwrite) {
            std::cerr << "sm2 replay: " << o.output << " already holds " << frames.size() << " frame"
                      << (frames.size() == 1 ? "" : "s") << " of an earlier replay (" << frames.front().filename().string()
                      << (frames.size() > 1 ? " ... " + frames.back().filename().string() : std::string())
                      << "); use --overwrite to replace them, or another folder\n";
            return kBadUsage;
        }
        for (const auto& f : frames) {
            std::error_code remove_error;
            std::filesystem::remove(f, remove_error);
        }
    }
    std::error_code ec;
    std::filesystem::create_directories(o.output, ec);
    if (ec || !std::filesystem::is_directory(o.output)) {
        std::cerr << "sm2 replay: cannot create the output folder " << o.output
                  << (ec ? ": " + ec.message() : std::string()) << '\n';
        return kInvalidInput;
    }
    return std::nullopt;
}

// sm2 replay APP.trace: the apitrace capture imported and replayed one call at a time (no stream
// is built); skipped and refused calls are reported once per kind with their first call number.
int run_replay_trace(const ReplayCliOptions& o) {
    namespace at = runtime::apitrace;
    auto snapshots = snapshotter_for(o);
    if (!snapshots) return kBadUsage;
    std::optional<at::Error> error;
    auto reader = at::Reader::open_file(o.stream, error);
    if (!reader) {
        std::cerr << "sm2 replay: " << (error->io ? "" : display_name(o.stream) + ": ") << error->to_string() << '\n';
        return kInvalidInput;
    }
    if (auto status = prepare_output(o)) return *status;
    runtime::DeviceOptions device_options;
    device_options.output_dir = o.output;
    o.numeric.apply(device_options);
    runtime::Device device(device_options);
    runtime::ReplayOptions options;
    options.file_name = display_name(o.stream);
    options.assembler = runtime::stream_assembler();
    options.hlsl_compiler = runtime::stream_hlsl_compiler();
    if (*snapshots)
        options.after_call = [&device, &snapshots](const cs::Statement& st, uint64_t call, bool accepted) {
            return (*snapshots)->after_call(device, st, call, accepted);
        };
    const auto start = std::chrono::steady_clock::now();
    const at::TraceReplay result = at::replay_trace(*reader, device, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& s = device.statistics();
    std::cout << device.frames_presented() << " frames, " << result.statements << " calls in " << fixed(seconds, 3)
              << " s: " << s.draws << " draws, " << s.vertices_shaded << " vertices, " << s.primitives
              << " primitives, " << s.pixels_shaded << " pixels shaded, " << s.pipelines_built << " pipelines built\n";
    if (!o.quiet || result.import.skipped > 0)
        std::cerr << "sm2 replay: " << display_name(o.stream) << ": " << result.import.to_string();
    if (result.refused > 0)
        std::cerr << "sm2 replay: " << result.refused << " of " << result.statements << " calls refused\n"
                  << result.refusals_to_string();
    if (result.error) {
        std::cerr << "sm2 replay: " << display_name(o.stream) << ": " << result.error->to_string() << '\n';
        return kInvalidInput;
    }
    if (*snapshots && !(*snapshots)->report(o.snapshot, result.statements)) return kInvalidInput;
    return result.refused > 0 ? kInvalidInput : kOk;
}

int run_replay(const ReplayCliOptions& o) {
    if (!o.numeric.check("replay")) return kBadUsage;
    if (o.stream.ends_with(".trace")) return run_replay_trace(o);
    auto snapshots = snapshotter_for(o);
    if (!snapshots) return kBadUsage;
    if (o.stats == "json" && !o.compare.empty()) {
        std::cerr << "sm2 replay: --stats json keeps stdout for the JSON alone: run --compare separately\n";
        return kBadUsage;
    }
    std::optional<FrameComparer> comparer;
    if (!o.compare.empty()) {
        std::error_code golden_error;
        if (!std::filesystem::is_directory(o.compare, golden_error)) {
            std::cerr << "sm2 replay: --compare " << o.compare << ": not a folder\n";
            return kDiffUnreadable;
        }
        comparer.emplace(o.compare, o.thresholds.thresholds());
    }
    auto loaded = load_stream(o.stream, "replay", o.numeric.read_root);
    if (!loaded) return kInvalidInput;
    if (auto status = prepare_output(o)) return *status;
    runtime::DeviceOptions device_options;
    device_options.output_dir = o.output;
    o.numeric.apply(device_options);
    if (comparer)
        device_options.write_image = [&comparer, &o](const runtime::Surface& surface, const std::string& path) {
            runtime::write_surface(surface, path);
            if (is_frame_of(path, o.output)) comparer->compare(path);  // the file as written, as sm2 diff reads it
        };
    runtime::Device device(device_options);

    runtime::ReplayOptions options = replay_options(*loaded);
    Progress progress(!o.quiet && isatty(STDERR_FILENO) != 0);
    std::vector<size_t> calls_before(loaded->stream.statements.size() + 1, 0);
    for (size_t i = 0; i < loaded->stream.statements.size(); ++i)
        calls_before[i + 1] = calls_before[i] + (loaded->stream.statements[i].kind == cs::Statement::Kind::Call);
    options.progress = [&progress, &device, &calls_before](size_t done, size_t total) {
        progress.update(done, total, calls_before[std::min(done, calls_before.size() - 1)], calls_before.back(),
                        device.frames_presented());
    };
    options.per_draw_statistics = !o.stats.empty();
    if (*snapshots)
        options.after_call = [&device, &snapshots](const cs::Statement& st, uint64_t call, bool accepted) {
            return (*snapshots)->after_call(device, st, call, accepted);
        };
    runtime::Replayer replayer(device, options);
    const runtime::ReplayResult result = replayer.replay(loaded->stream);
    progress.finish();

    if (o.stats == "json") {  // stdout holds the JSON alone
        print_draw_json(result);
    } else if (!o.quiet) {
        for (size_t i = 0; i < result.frames.size(); ++i) {
            const auto& f = result.frames[i];
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04zu.png", i);
            std::cout << (std::filesystem::path(o.output) / name).string() << ": " << fixed(f.seconds * 1000.0, 3) << " ms, " << f.statistics.draws << " draws, "
                      << f.statistics.vertices_shaded << " vertices, " << f.statistics.pixels_shaded << " pixels\n";
        }
    }
    const auto& s = result.statistics;
    if (o.stats == "table") print_draw_table(result);
    if (o.stats != "json")
        std::cout << result.frames.size() << " frames, " << result.calls << " calls in " << fixed(result.seconds, 3)
                  << " s: " << s.draws << " draws, " << s.vertices_shaded << " vertices, " << s.primitives
                  << " primitives, " << s.pixels_shaded << " pixels shaded, " << s.pipelines_built
                  << " pipelines built\n";
    print_diagnostics(result.diagnostics);
    if (*snapshots && !(*snapshots)->report(o.snapshot, result.calls)) return kInvalidInput;
    if (comparer) {
        comparer->missing_frames(device.frames_presented());
        int status = comparer->status();
        if (!result.ok()) {  // a replay with refused calls does not pass
            std::cerr << "sm2 replay: " << result.refused << " of " << result.calls << " calls refused\n";
            status = std::max(status, static_cast<int>(kDiffFailure));
        }
        std::cout << comparer->compared() << " frames compared with " << o.compare << ": " << status_word(status) << '\n';
        return status;
    }
    if (!result.ok()) {
        std::cerr << "sm2 replay: " << result.refused << " of " << result.calls << " calls refused\n";
        return kInvalidInput;
    }
    return kOk;
}

// ---------------------------------------------------------------------------------------------
// sm2 bench

struct BenchCliOptions {
    std::string stream;
    unsigned repeat = 5;
    NumericCliOptions numeric;
    bool json = false;
};

// count / seconds; JSON null where the time is 0.
nlohmann::ordered_json json_rate(double count, double seconds) {
    return seconds > 0.0 ? nlohmann::ordered_json(count / seconds) : nlohmann::ordered_json();
}

std::string rate(double count, double seconds) {
    if (seconds <= 0.0) return "inf";
    const double r = count / seconds;
    char buf[64];
    if (r >= 1e9) std::snprintf(buf, sizeof buf, "%.3f G", r / 1e9);
    else if (r >= 1e6) std::snprintf(buf, sizeof buf, "%.3f M", r / 1e6);
    else if (r >= 1e3) std::snprintf(buf, sizeof buf, "%.3f k", r / 1e3);
    else std::snprintf(buf, sizeof buf, "%.3f", r);
    return buf;
}

int run_bench(const BenchCliOptions& o) {
    if (!o.numeric.check("bench")) return kBadUsage;
    auto loaded = load_stream(o.stream, "bench", o.numeric.read_root);
    if (!loaded) return kInvalidInput;
    const runtime::ReplayOptions options = replay_options(*loaded);

    std::vector<runtime::ReplayResult> runs;
    runs.reserve(o.repeat);
    for (unsigned i = 0; i < o.repeat; ++i) {
        runtime::DeviceOptions device_options;
        o.numeric.apply(device_options);
        device_options.write_image = [](const runtime::Surface&, const std::string&) {};  // in memory only
        runtime::Device device(device_options);
        runs.push_back(runtime::replay(device, loaded->stream, options));
    }
    // Rates are ratios of one run's counts to that run's time: the median run by time.
    std::vector<size_t> order(runs.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return runs[a].seconds < runs[b].seconds; });
    const runtime::ReplayResult& median = runs[order[order.size() / 2]];
    const runtime::ReplayResult& best = runs[order.front()];
    const auto& s = median.statistics;
    if (o.json) {
        const auto& first = runs.front().statistics;
        uint64_t later = 0;
        for (size_t i = 1; i < runs.size(); ++i) later += runs[i].statistics.routines_compiled;
        nlohmann::ordered_json j = {
            {"stream", loaded->file_name},
            {"runs", o.repeat},
            {"threads", o.numeric.threads},
            {"engine", o.numeric.engine == "jit" && emu::jit::available() ? "jit" : "interpreter"},
            {"calls", median.calls},
            {"frames", median.frames.size()},
            {"draws", s.draws},
            {"vertices_shaded", s.vertices_shaded},
            {"primitives", s.primitives},
            {"pixels_shaded", s.pixels_shaded},
            {"median_seconds", median.seconds},
            {"best_seconds", best.seconds},
            {"frames_per_second", json_rate(static_cast<double>(median.frames.size()), median.seconds)},
            {"pixels_shaded_per_second", json_rate(static_cast<double>(s.pixels_shaded), median.seconds)},
            {"vertices_per_second", json_rate(static_cast<double>(s.vertices_shaded), median.seconds)},
            {"draws_per_second", json_rate(static_cast<double>(s.draws), median.seconds)},
            {"stage_seconds",
             {{"pipelines", s.pipeline_seconds}, {"vertex", s.vertex_seconds}, {"setup", s.setup_seconds}, {"pixel", s.pixel_seconds}}},
            {"routines_compiled_first_run", first.routines_compiled},
            {"routines_from_jit_cache_first_run", first.routines_from_cache},
            {"compile_seconds_first_run", first.compile_seconds},
            {"routines_compiled_later_runs", later},
            {"run_seconds", nlohmann::ordered_json::array()},
            {"refused_calls", runs.front().refused}};
        for (const auto& run : runs) j["run_seconds"].push_back(run.seconds);
        std::cout << json_text(j) << '\n';
        if (runs.front().ok()) return kOk;
        print_diagnostics(runs.front().diagnostics);
        return kInvalidInput;
    }

    std::cout << loaded->file_name << ": " << median.calls << " calls, " << median.frames.size() << " frames, "
              << s.draws << " draws, " << s.vertices_shaded << " vertices, " << s.pixels_shaded
              << " pixels shaded per run; " << o.repeat << " runs, " << o.numeric.threads << " thread"
              << (o.numeric.threads == 1 ? "" : "s") << '\n'
              << "time per run: median " << fixed(median.seconds * 1000.0, 3) << " ms, best "
              << fixed(best.seconds * 1000.0, 3) << " ms\n"
              << "frames/s: "
              << (median.frames.empty() ? std::string("- (the stream presents no frame: runs/s ") +
                                              rate(1.0, median.seconds) + ")"
                                        : rate(static_cast<double>(median.frames.size()), median.seconds))
              << '\n'
              << "pixels shaded/s: " << rate(static_cast<double>(s.pixels_shaded), median.seconds) << '\n'
              << "vertices/s: " << rate(static_cast<double>(s.vertices_shaded), median.seconds) << '\n'
              << "draws/s: " << rate(static_cast<double>(s.draws), median.seconds) << '\n';
    if (s.draws > 0)
        std::cout << "stage time per run: pipelines " << fixed(s.pipeline_seconds * 1000.0, 3) << " ms, vertex "
                  << fixed(s.vertex_seconds * 1000.0, 3) << " ms, setup " << fixed(s.setup_seconds * 1000.0, 3)
                  << " ms, pixel " << fixed(s.pixel_seconds * 1000.0, 3) << " ms (wall time; pixel work runs on "
                  << o.numeric.threads << " thread" << (o.numeric.threads == 1 ? "" : "s") << ")\n";
    if (o.numeric.engine == "jit") {
        // Compilation happens in the first run only (the routines are shared by later runs).
        const auto& first = runs.front().statistics;
        uint64_t later = 0;
        for (size_t i = 1; i < runs.size(); ++i) later += runs[i].statistics.routines_compiled;
        std::cout << "engine: jit" << (emu::jit::available() ? "" : " (not in this build: interpreter)") << "; "
                  << first.routines_compiled << " routines compiled in the first run"
                  << (first.routines_from_cache ? " (" + std::to_string(first.routines_from_cache) + " loaded from the JIT cache)" : "")
                  << ", "
                  << fixed(first.compile_seconds * 1000.0, 3) << " ms ("
                  << fixed(first.routines_compiled ? first.compile_seconds * 1000.0 / static_cast<double>(first.routines_compiled) : 0.0, 3)
                  << " ms per routine); later runs compiled " << later << "\n";
    } else {
        std::cout << "engine: interpreter\n";
    }
    if (!runs.front().ok()) {
        print_diagnostics(runs.front().diagnostics);
        std::cerr << "sm2 bench: " << runs.front().refused << " of " << runs.front().calls << " calls refused\n";
        return kInvalidInput;
    }
    return kOk;
}

}  // namespace

void add_replay_commands(CLI::App& app, int& status) {
    auto r = std::make_shared<ReplayCliOptions>();
    auto* replay = app.add_subcommand(
        "replay", "Replay a command stream: every Present writes DIR/frame_NNNN.png, SaveSurface writes relative "
                  "to DIR; refused calls are reported with file:line (exit 1) and the replay goes on");
    add_stream_argument(*replay, r->stream);
    replay->add_option("-o,--output", r->output,
                       "Output folder (created if missing; refused if it holds frames of an earlier replay)")
        ->required();
    replay->add_flag("--overwrite", r->overwrite, "Replace the frames (frame_NNNN.png) an earlier replay left in the folder");
    r->numeric.add_to(*replay);
    replay->add_flag("-q,--quiet", r->quiet, "Print only the summary (no per-frame lines, no progress)");
    replay->add_option("--compare", r->compare,
                       "Golden folder: each frame, once written, is compared with the file of the same name there "
                       "(as sm2 diff; --fail, --warn, --failpercent, --hardfail); exit as sm2 diff: 0 pass, 1 "
                       "warning, 2 failure (or refused calls), 3 sizes differ, 4 a frame missing on either side");
    r->thresholds.add_to(*replay);
    replay->add_option("--stats", r->stats,
                       "Per draw: call number, line, frame, pixels rasterized, shaded, killed (texkill), written, "
                       "vertices, primitives and time; 'table' after the frames, or 'json' (stdout then holds the "
                       "JSON alone; it also counts pixels_outside_texture, the shaded pixels whose batch was skipped "
                       "because its alpha lookups lie outside a BORDER texture: docs/inspection.md)")
        ->check(CLI::IsMember({"table", "json"}));
    replay->add_option("--snapshot", r->snapshot,
                       "After each call of this apitrace call set (10,20-30 / 0-100/5 / */draw / frame / @FILE), "
                       "write DIR/call_NNNNNN_frame_F_rtI.png for each bound render target, _depth.exr (float) and "
                       "_stencil.png (8-bit); calls numbered from 1 as --stats does (a trace's own numbers for .trace)");
    replay->callback([r, &status] { status = run_replay(*r); });

    auto b = std::make_shared<BenchCliOptions>();
    auto* bench = app.add_subcommand(
        "bench", "Replay a command stream N times in memory (no files written) and report frames/s, pixels "
                 "shaded/s and vertices/s of the median run");
    bench->add_option("stream", b->stream, "Command stream, text (.sm2cs) or binary (.sm2cb); '-' for stdin")
        ->required();
    bench->add_option("--repeat", b->repeat, "Runs (default 5)")->check(CLI::Range(1u, 100000u));
    b->numeric.add_to(*bench);
    bench->add_flag("--json", b->json, "The counts, times and rates as JSON on stdout");
    bench->callback([b, &status] { status = run_bench(*b); });
}

}  // namespace sm2::tools
