// sm2 pixel: the history of one pixel of one frame: every draw that covered it, with each
// primitive's shader output, tests and the value before and after, recorded by the draws
// themselves (Device::watch_pixel).
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "call_walk.h"
#include "commands.h"
#include "image_compare.h"
#include "sm2/runtime/device_inspection.h"
#include "sm2/runtime/pixel_history.h"
#include "stream_io.h"

namespace sm2::tools {

namespace {

using json = nlohmann::ordered_json;
namespace rt = runtime;

struct PixelCliOptions {
    std::string stream;
    uint32_t frame = 0;
    std::string pixel;
    bool json = false;
    std::string read_root;
};

// "X,Y" -> (x, y); nullopt for anything else.
std::optional<std::pair<uint32_t, uint32_t>> parse_pixel(const std::string& text) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos) return std::nullopt;
    uint32_t x = 0, y = 0;
    const char* end = text.data() + text.size();
    const auto px = std::from_chars(text.data(), text.data() + comma, x);
    const auto py = std::from_chars(text.data() + comma + 1, end, y);
    if (px.ec != std::errc() || px.ptr != text.data() + comma || py.ec != std::errc() || py.ptr != end || comma == 0)
        return std::nullopt;
    return std::pair{x, y};
}

std::string number(float f) {
    std::ostringstream s;
    s << f;
    return s.str();
}

std::string vec_text(const rt::Float4& v) {
    return "(" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + ", " + number(v[3]) + ")";
}

json vec_json(const rt::Float4& v) { return json::array({v[0], v[1], v[2], v[3]}); }

json outcome(const std::optional<bool>& passed) { return passed ? json(*passed ? "pass" : "fail") : json(); }

std::string outcome_text(const std::optional<bool>& passed) { return passed ? (*passed ? "pass" : "fail") : "-"; }

struct DrawAtCall {
    uint64_t call = 0;
    std::string name;
    rt::PixelDraw draw;
};

json fragment_json(const rt::PixelFragment& f) {
    json j = {{"primitive", f.primitive}, {"scissor", f.scissored ? "fail" : "pass"}};
    j["depth_stencil"] = outcome(f.depth_stencil_passed);
    j["early_depth_stencil"] = f.early_depth_stencil;
    j["shaded"] = f.shaded;
    j["texkill"] = f.shaded ? json(f.killed ? "fail" : "pass") : json();
    j["alpha_test"] = outcome(f.alpha_test_passed);
    j["written"] = f.written;
    j["shader_color"] = f.shaded ? vec_json(f.shader_color[0]) : json();
    j["depth"] = f.shaded || f.early_depth_stencil ? json(f.depth) : json();
    j["before"] = {{"color", vec_json(f.color_before[0])}, {"depth", f.depth_before}, {"stencil", f.stencil_before}};
    j["after"] = {{"color", vec_json(f.color_after[0])}, {"depth", f.depth_after}, {"stencil", f.stencil_after}};
    return j;
}

int run_pixel(const PixelCliOptions& o) {
    const auto xy = parse_pixel(o.pixel);
    if (!xy) {
        std::cerr << "sm2 pixel: --pixel '" << o.pixel << "': expected X,Y (two whole numbers, e.g. 12,40)\n";
        return kBadUsage;
    }
    rt::DeviceOptions device_options;
    device_options.threads = std::max(1u, std::thread::hardware_concurrency());
    device_options.engine = rt::DeviceOptions::Engine::Jit;
    rt::Device device(device_options);
    rt::PixelWatch watch;
    watch.x = xy->first;
    watch.y = xy->second;
    std::vector<DrawAtCall> draws;
    uint64_t last_call = 0;
    std::string last_name;
    size_t attributed = 0;
    auto attribute = [&] {  // the draws the last call made belong to it
        for (; attributed < watch.draws.size(); ++attributed) draws.push_back({last_call, last_name, watch.draws[attributed]});
    };
    auto walk = walk_calls(o.stream, o.read_root, "pixel", device, [&](uint64_t call, const rt::cs::Statement& st) {
        attribute();
        if (device.frames_presented() > o.frame) return false;  // the frame has been presented
        device.watch_pixel(device.frames_presented() == o.frame ? &watch : nullptr);
        last_call = call;
        last_name = st.name;
        return true;
    });
    attribute();
    device.watch_pixel(nullptr);
    if (!walk) return kInvalidInput;
    if (device.frames_presented() <= o.frame) {
        std::cerr << "sm2 pixel: --frame " << o.frame << ": out of range: " << walk->file_name << " presents "
                  << device.frames_presented() << " frame" << (device.frames_presented() == 1 ? "" : "s") << '\n';
        return kInvalidInput;
    }
    const rt::DeviceInspection state = device.inspect();
    const rt::Surface* back = state.back_buffer;
    if (!back || watch.x >= back->width() || watch.y >= back->height()) {
        std::cerr << "sm2 pixel: --pixel " << watch.x << "," << watch.y << ": outside the "
                  << (back ? std::to_string(back->width()) + "x" + std::to_string(back->height()) : std::string("missing"))
                  << " back buffer\n";
        return kInvalidInput;
    }
    const rt::Float4 final_value = back->read(watch.x, watch.y);
    // The frame shows the back buffer: the draws into it are its history.
    std::erase_if(draws, [back](const DrawAtCall& d) { return d.draw.target != back || d.draw.fragments.empty(); });
    bool consistent = true;
    for (const auto& d : draws) consistent = consistent && d.draw.consistent;

    if (o.json) {
        json j = {{"file", walk->file_name}, {"frame", o.frame}, {"x", watch.x}, {"y", watch.y},
                  {"width", back->width()}, {"height", back->height()}, {"draws", json::array()}};
        for (const auto& d : draws) {
            json dj = {{"call", d.call}, {"name", d.name}, {"fragments", json::array()}};
            for (const auto& f : d.draw.fragments) dj["fragments"].push_back(fragment_json(f));
            j["draws"].push_back(dj);
        }
        j["final"] = vec_json(final_value);
        j["consistent"] = consistent;
        std::cout << json_text(j) << '\n';
    } else {
        std::cout << "pixel (" << watch.x << ", " << watch.y << ") of frame " << o.frame << " of " << walk->file_name
                  << ": " << draws.size() << " draw" << (draws.size() == 1 ? "" : "s") << " covered it\n";
        for (const auto& d : draws)
            for (const auto& f : d.draw.fragments) {
                std::cout << "call " << d.call << " " << d.name << ", primitive " << f.primitive << ":\n";
                if (f.shaded)
                    std::cout << "  shader: oC0 " << vec_text(f.shader_color[0]) << ", depth " << number(f.depth) << '\n';
                std::cout << "  tests: scissor " << (f.scissored ? "fail" : "pass") << ", depth/stencil "
                          << outcome_text(f.depth_stencil_passed) << (f.early_depth_stencil ? " (early)" : "")
                          << ", texkill " << (f.shaded ? (f.killed ? "fail" : "pass") : "-") << ", alpha "
                          << outcome_text(f.alpha_test_passed) << (f.written ? "; written" : "; not written") << '\n';
                std::cout << "  before: " << vec_text(f.color_before[0]) << ", depth " << number(f.depth_before)
                          << ", stencil " << f.stencil_before << '\n';
                std::cout << "  after:  " << vec_text(f.color_after[0]) << ", depth " << number(f.depth_after)
                          << ", stencil " << f.stencil_after << '\n';
            }
        std::cout << "final: " << vec_text(final_value) << " (the frame's pixel)\n";
    }
    if (!consistent) {
        std::cerr << "sm2 pixel: the recorded history does not end at the value the draw wrote (a bug: please report)\n";
        return kInvalidInput;
    }
    return kOk;
}

}  // namespace

void add_pixel_command(CLI::App& app, int& status) {
    auto o = std::make_shared<PixelCliOptions>();
    auto* cmd = app.add_subcommand(
        "pixel", "The history of one pixel of one frame: every draw into the back buffer that covered it, each "
                 "primitive's shader colour, test outcomes (scissor, depth/stencil, texkill, alpha) and the value "
                 "before and after; the last value is the frame's pixel");
    cmd->add_option("stream", o->stream, "Command stream (.sm2cs, .sm2cb, '-' for stdin) or apitrace capture (.trace)")
        ->required();
    cmd->add_option("--frame", o->frame, "The frame (0 is the first Present's)")->required();
    cmd->add_option("--pixel", o->pixel, "X,Y: the pixel, from the top left of the back buffer")->required();
    cmd->add_flag("--json", o->json, "The history as JSON on stdout");
    add_read_root_option(*cmd, o->read_root);
    cmd->callback([o, &status] { status = run_pixel(*o); });
}

}  // namespace sm2::tools
