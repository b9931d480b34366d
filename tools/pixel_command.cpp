// sm2 pixel: the history of one pixel of one frame: every draw that covered it, with each
// primitive's shader inputs and output, tests and the value before and after, recorded by the
// draws themselves (Device::watch_pixel).
// sm2 debug: the pixel shader of one of those draws (or the vertex shader of a draw for one
// vertex) run again by the interpreter one source instruction at a time (runtime::ShaderDebug).
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "call_walk.h"
#include "commands.h"
#include "image_compare.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/isa/line_table.h"
#include "sm2/runtime/device_inspection.h"
#include "sm2/runtime/pixel_history.h"
#include "stream_io.h"

namespace sm2::tools {

namespace {

using json = nlohmann::ordered_json;
namespace rt = runtime;

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

std::string mask_text(uint8_t mask) {
    std::string text;
    for (unsigned c = 0; c < 4; ++c)
        if (mask >> c & 1u) text += "xyzw"[c];
    return text;
}

// --target: which surface's history. The back buffer (default), render target slot N of each
// draw, or the surface or texture the stream names (at whichever slot a draw binds it).
struct TargetChoice {
    enum class Kind { BackBuffer, Slot, Named } kind = Kind::BackBuffer;
    unsigned slot = 0;
    std::string name;
    std::string text = "back";
};

std::optional<TargetChoice> parse_target(const std::string& text) {
    TargetChoice t;
    t.text = text;
    if (text.empty()) return std::nullopt;
    if (text == "back") return t;
    if (text.size() == 3 && text.starts_with("rt") && text[2] >= '0' && text[2] < '0' + static_cast<char>(rt::kMaxRenderTargets)) {
        t.kind = TargetChoice::Kind::Slot;
        t.slot = static_cast<unsigned>(text[2] - '0');
        return t;
    }
    t.kind = TargetChoice::Kind::Named;
    t.name = text;
    return t;
}

struct DrawAtCall {
    uint64_t call = 0;
    std::string name;
    rt::PixelDraw draw;
    std::array<std::string, rt::kMaxRenderTargets> target_names;  // the stream's handles, "" for none
    unsigned slot = 0;  // the render target of the history in this draw
};

struct PixelCliOptions {
    std::string stream;
    uint32_t frame = 0;
    std::string pixel;
    std::string target = "back";
    bool json = false;
    std::string read_root;
};

// The draws of frame `o.frame` that covered the pixel in the chosen target, recorded by replaying
// the stream to the end of that frame.
struct PixelHistory {
    std::string file_name;
    uint32_t x = 0, y = 0;
    uint32_t width = 0, height = 0;
    TargetChoice target;
    std::vector<DrawAtCall> draws;
    std::optional<rt::Float4> final_value;  // the frame's pixel (back buffer only)
    bool consistent = true;
};

// Replays `o.stream` to the end of frame `o.frame`, with `watch(true)` before each of that
// frame's calls and `after_call(call, name)` after it (the draws the watch recorded are that
// call's). nullopt, after printing why, when the stream cannot be read or presents no such frame.
std::optional<CallWalk> replay_frame(const PixelCliOptions& o, const char* command, rt::Device& device,
                                     const std::function<void(bool)>& watch,
                                     const std::function<void(uint64_t, const std::string&)>& after_call) {
    uint64_t last_call = 0;
    std::string last_name;
    bool watching = false;
    const auto finish_call = [&] {
        if (watching) after_call(last_call, last_name);
    };
    auto walk = walk_calls(o.stream, o.read_root, command, device, [&](uint64_t call, const rt::cs::Statement& st) {
        finish_call();
        if (device.frames_presented() > o.frame) return false;  // the frame has been presented
        watching = device.frames_presented() == o.frame;
        watch(watching);
        last_call = call;
        last_name = st.name;
        return true;
    });
    finish_call();
    watch(false);
    if (!walk) return std::nullopt;
    if (device.frames_presented() <= o.frame) {
        std::cerr << "sm2 " << command << ": --frame " << o.frame << ": out of range: " << walk->file_name << " presents "
                  << device.frames_presented() << " frame" << (device.frames_presented() == 1 ? "" : "s") << '\n';
        return std::nullopt;
    }
    return walk;
}

// Replays and records; prints the error and returns the exit status when it cannot.
std::variant<PixelHistory, int> record_history(const PixelCliOptions& o, const char* command, bool debug_shaders) {
    const auto xy = parse_pixel(o.pixel);
    if (!xy) {
        std::cerr << "sm2 " << command << ": --pixel '" << o.pixel << "': expected X,Y (two whole numbers, e.g. 12,40)\n";
        return kBadUsage;
    }
    const auto target = parse_target(o.target);
    if (!target) {
        std::cerr << "sm2 " << command << ": --target '': expected back, rt0..rt3 or a surface's name\n";
        return kBadUsage;
    }
    rt::Device device(inspection_device_options());
    rt::PixelWatch watch;
    watch.x = xy->first;
    watch.y = xy->second;
    watch.debug_shaders = debug_shaders;
    PixelHistory h;
    h.x = watch.x;
    h.y = watch.y;
    h.target = *target;
    size_t attributed = 0;
    const auto walk = replay_frame(o, command, device, [&](bool on) { device.watch_pixel(on ? &watch : nullptr); },
                                   [&](uint64_t call, const std::string& name) {
        if (attributed == watch.draws.size()) return;
        // The targets the call drew into are still bound: their names.
        const rt::DeviceInspection bound = device.inspect();
        std::array<std::string, rt::kMaxRenderTargets> names;
        for (unsigned i = 0; i < rt::kMaxRenderTargets; ++i)
            if (bound.render_target_resources[i]) names[i] = bound.render_target_resources[i]->name;
        for (; attributed < watch.draws.size(); ++attributed)
            h.draws.push_back({call, name, std::move(watch.draws[attributed]), names, 0});
    });
    if (!walk) return kInvalidInput;
    h.file_name = walk->file_name;
    const rt::Surface* back = device.inspect().back_buffer;
    // Which slot of each draw is the chosen target (none: the draw is not in its history).
    auto slot_of = [&](const DrawAtCall& d) -> std::optional<unsigned> {
        for (unsigned i = 0; i < rt::kMaxRenderTargets; ++i) {
            if (!d.draw.targets[i]) continue;
            if ((target->kind == TargetChoice::Kind::BackBuffer && d.draw.targets[i] == back) ||
                (target->kind == TargetChoice::Kind::Slot && i == target->slot) ||
                (target->kind == TargetChoice::Kind::Named && d.target_names[i] == target->name))
                return i;
        }
        return std::nullopt;
    };
    const rt::Surface* any_target = nullptr;  // a surface of the history, for its size
    std::erase_if(h.draws, [&](DrawAtCall& d) {
        const auto slot = slot_of(d);
        if (!slot) return true;
        d.slot = *slot;
        if (!any_target) any_target = d.draw.targets[*slot];
        return d.draw.fragments.empty();
    });
    if (target->kind == TargetChoice::Kind::BackBuffer) {
        if (!back || watch.x >= back->width() || watch.y >= back->height()) {
            std::cerr << "sm2 " << command << ": --pixel " << watch.x << "," << watch.y << ": outside the "
                      << (back ? std::to_string(back->width()) + "x" + std::to_string(back->height()) : std::string("missing"))
                      << " back buffer\n";
            return kInvalidInput;
        }
        h.width = back->width();
        h.height = back->height();
        h.final_value = back->read(watch.x, watch.y);
    } else if (any_target) {
        h.width = any_target->width();
        h.height = any_target->height();
        if (watch.x >= h.width || watch.y >= h.height) {
            std::cerr << "sm2 " << command << ": --pixel " << watch.x << "," << watch.y << ": outside the " << h.width
                      << "x" << h.height << " target " << target->text << '\n';
            return kInvalidInput;
        }
    }
    for (const auto& d : h.draws) h.consistent = h.consistent && d.draw.consistent;
    return h;
}

// (register, value) pairs: lane slots (v#, t#) or, with `constants`, c# numbers.
using RegisterValues = std::vector<std::pair<uint16_t, rt::Float4>>;

std::string register_name(uint16_t index, bool constants) {
    return constants ? "c" + std::to_string(index) : emu::slot_name(index);
}

json registers_json(const RegisterValues& registers, bool constants = false) {
    json j = json::object();
    for (const auto& [index, value] : registers) j[register_name(index, constants)] = vec_json(value);
    return j;
}

std::string registers_text(const RegisterValues& registers, bool constants = false) {
    std::string text;
    for (const auto& [index, value] : registers)
        text += (text.empty() ? "" : ", ") + register_name(index, constants) + " " + vec_text(value);
    return text;
}

json fragment_json(const rt::PixelFragment& f, unsigned slot) {
    json j = {{"primitive", f.primitive}, {"scissor", f.scissored ? "fail" : "pass"}};
    j["depth_stencil"] = outcome(f.depth_stencil_passed);
    j["early_depth_stencil"] = f.early_depth_stencil;
    j["shaded"] = f.shaded;
    j["texkill"] = f.shaded ? json(f.killed ? "fail" : "pass") : json();
    j["alpha_test"] = outcome(f.alpha_test_passed);
    j["written"] = f.written;
    j["inputs"] = f.shaded ? registers_json(f.inputs) : json();
    j["shader_color"] = f.shaded ? vec_json(f.shader_color[slot]) : json();
    j["depth"] = f.shaded || f.early_depth_stencil ? json(f.depth) : json();
    j["before"] = {{"color", vec_json(f.color_before[slot])}, {"depth", f.depth_before}, {"stencil", f.stencil_before}};
    j["after"] = {{"color", vec_json(f.color_after[slot])}, {"depth", f.depth_after}, {"stencil", f.stencil_after}};
    return j;
}

std::string target_text(const DrawAtCall& d) {
    return "rt" + std::to_string(d.slot) + (d.target_names[d.slot].empty() ? "" : " (" + d.target_names[d.slot] + ")");
}

int run_pixel(const PixelCliOptions& o) {
    auto recorded = record_history(o, "pixel", false);
    if (const int* status = std::get_if<int>(&recorded)) return *status;
    const PixelHistory& h = std::get<PixelHistory>(recorded);
    const bool back = h.target.kind == TargetChoice::Kind::BackBuffer;
    if (o.json) {
        json j = {{"file", h.file_name}, {"frame", o.frame}, {"x", h.x}, {"y", h.y}, {"target", h.target.text},
                  {"width", h.width}, {"height", h.height}, {"draws", json::array()}};
        for (const auto& d : h.draws) {
            json dj = {{"call", d.call}, {"name", d.name}, {"render_target", d.slot},
                       {"surface", d.target_names[d.slot].empty() ? json() : json(d.target_names[d.slot])},
                       {"fragments", json::array()}};
            for (const auto& f : d.draw.fragments) dj["fragments"].push_back(fragment_json(f, d.slot));
            j["draws"].push_back(dj);
        }
        j["final"] = h.final_value ? vec_json(*h.final_value) : json();
        j["consistent"] = h.consistent;
        std::cout << json_text(j) << '\n';
    } else {
        std::cout << "pixel (" << h.x << ", " << h.y << ") of frame " << o.frame << " of " << h.file_name
                  << (back ? "" : ", target " + h.target.text) << ": " << h.draws.size() << " draw"
                  << (h.draws.size() == 1 ? "" : "s") << " covered it\n";
        for (const auto& d : h.draws)
            for (const auto& f : d.draw.fragments) {
                const std::string out = "oC" + std::to_string(d.slot);
                std::cout << "call " << d.call << " " << d.name << ", primitive " << f.primitive
                          << (back ? "" : ", into " + target_text(d)) << ":\n";
                if (f.shaded) {
                    std::cout << "  shader: " << out << " " << vec_text(f.shader_color[d.slot]) << ", depth " << number(f.depth) << '\n';
                    if (!f.inputs.empty()) std::cout << "  inputs: " << registers_text(f.inputs) << '\n';
                }
                std::cout << "  tests: scissor " << (f.scissored ? "fail" : "pass") << ", depth/stencil "
                          << outcome_text(f.depth_stencil_passed) << (f.early_depth_stencil ? " (early)" : "")
                          << ", texkill " << (f.shaded ? (f.killed ? "fail" : "pass") : "-") << ", alpha "
                          << outcome_text(f.alpha_test_passed) << (f.written ? "; written" : "; not written") << '\n';
                std::cout << "  before: " << vec_text(f.color_before[d.slot]) << ", depth " << number(f.depth_before)
                          << ", stencil " << f.stencil_before << '\n';
                std::cout << "  after:  " << vec_text(f.color_after[d.slot]) << ", depth " << number(f.depth_after)
                          << ", stencil " << f.stencil_after << '\n';
            }
        if (h.final_value) std::cout << "final: " << vec_text(*h.final_value) << " (the frame's pixel)\n";
    }
    if (!h.consistent) {
        std::cerr << "sm2 pixel: the recorded history does not end at the value the draw wrote (a bug: please report)\n";
        return kInvalidInput;
    }
    return kOk;
}

// ---------------------------------------------------------------------------------------------
// sm2 debug

struct DebugCliOptions {
    PixelCliOptions pixel;
    std::optional<uint32_t> vertex;
    std::optional<uint64_t> draw;
};

// Where each instruction is in `sm2 dis`'s text (1-based lines): the disassembly of the program
// up to and including it ends with it, one line per instruction.
class DisassemblyLines {
public:
    explicit DisassemblyLines(const isa::Program& program) : program_(program) {}
    uint32_t line(uint32_t instruction) {
        if (auto it = lines_.find(instruction); it != lines_.end()) return it->second;
        isa::Program prefix{program_.version, {}};
        prefix.instructions.assign(program_.instructions.begin(),
                                   program_.instructions.begin() + std::min<size_t>(instruction + 1, program_.instructions.size()));
        const std::string text = assembler::disassemble(prefix);
        const auto line = static_cast<uint32_t>(std::count(text.begin(), text.end(), '\n'));
        return lines_[instruction] = line;
    }
    std::string text(uint32_t instruction) const {
        return instruction < program_.instructions.size()
                   ? assembler::format_instruction(program_.version, program_.instructions[instruction])
                   : std::string("?");
    }

private:
    const isa::Program& program_;
    std::map<uint32_t, uint32_t> lines_;
};

// Where lane `l` of the traced quad or vertex is: "(x, y)" or "vertex I".
struct LaneNames {
    bool pixel = true;
    uint32_t x = 0, y = 0;  // pixel: the quad's top left; vertex: the vertex number in x
    [[nodiscard]] std::string name(unsigned lane) const {
        if (!pixel) return "vertex " + std::to_string(x);
        return "(" + std::to_string(x + (lane & 1u)) + ", " + std::to_string(y + (lane >> 1)) + ")";
    }
};

json lanes_json(const emu::InstructionWrite& w, unsigned lanes) {
    json j = json::array();
    for (unsigned l = 0; l < lanes; ++l) j.push_back(vec_json(w.lanes[l]));
    return j;
}

void print_register(std::ostream& out, const std::string& name, const emu::InstructionWrite& w, const rt::ShaderDebug& d,
                    const LaneNames& lanes, const std::string& indent = "") {
    out << indent << "  " << name << " (" << mask_text(w.mask) << ")";
    if (d.lanes == 1) {
        out << " " << vec_text(w.lanes[0]) << '\n';
        return;
    }
    out << '\n';
    for (unsigned l = 0; l < d.lanes; ++l)
        out << indent << "    lane " << l << " " << lanes.name(l) << ": " << vec_text(w.lanes[l])
            << (l == d.watched_lane ? "  <- the pixel" : (d.covered >> l & 1u) ? "" : "  (helper)") << '\n';
}

std::string write_name(const emu::InstructionWrite& w) { return w.address ? "a0" : emu::slot_name(w.slot); }

// The HLSL line of each step, from the shader's line table (sm2/isa/line_table.h), and the steps
// grouped into runs of consecutive steps on the same line: a reader steps by HLSL line. Without a
// table (assembly, bytecode compiled without --debug-info, fixed function) there are no groups.
struct HlslLines {
    std::optional<isa::LineTable> table;
    std::vector<const isa::LineTable::Entry*> step_entry;  // per step (nullptr: no line)
    struct Group {
        const isa::LineTable::Entry* entry = nullptr;
        std::vector<size_t> steps;  // 0-based
    };
    std::vector<Group> groups;

    HlslLines(const isa::Program& program, const std::vector<emu::InstructionTrace>& steps) {
        auto found = isa::find_line_table(program);
        if (!found || !found->ok()) return;
        table = std::move(found->table);
        const auto ordinals = isa::instruction_ordinals(program);
        for (size_t i = 0; i < steps.size(); ++i) {
            const uint32_t k = steps[i].instruction;
            const isa::LineTable::Entry* e =
                k < ordinals.size() && ordinals[k] >= 0 ? table->entry(static_cast<uint32_t>(ordinals[k])) : nullptr;
            step_entry.push_back(e);
            const bool same = !groups.empty() && (groups.back().entry == e ||
                                                  (e && groups.back().entry && groups.back().entry->file == e->file &&
                                                   groups.back().entry->line == e->line));
            if (!same) groups.push_back({e, {}});
            groups.back().steps.push_back(i);
        }
    }
    [[nodiscard]] std::string file(const isa::LineTable::Entry& e) const { return table->files.at(e.file); }
    [[nodiscard]] std::string text(const isa::LineTable::Entry& e) const {
        const std::string* t = table->text(e.file, e.line);
        return t ? *t : std::string();
    }
    [[nodiscard]] json entry_json(const isa::LineTable::Entry* e) const {
        if (!e) return nullptr;
        return {{"file", file(*e)}, {"line", e->line}, {"text", text(*e)}};
    }
};

// "  float3 n = ...;" without its indentation, for a heading.
std::string trimmed(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return std::string();
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

int print_debug(const rt::ShaderDebug& d, json header, const std::string& title, const LaneNames& lanes, bool as_json) {
    DisassemblyLines dis(*d.program);
    const HlslLines hlsl(*d.program, d.steps);
    const char* source_note =
        d.fixed_function ? "the fixed-function program generated for the draw's state (no source text)"
        : hlsl.table     ? "HLSL, stepped by source line (the shader's HLSL line table): each line's assembly "
                           "instructions under it as sm2 dis prints them"
                         : "assembly, one step per instruction as sm2 dis prints it (this shader carries no HLSL line "
                           "table)";
    if (as_json) {
        json j = std::move(header);
        j["shader"] = d.program->version.name();
        j["fixed_function"] = d.fixed_function;
        j["source"] = source_note;
        j["watched_lane"] = d.watched_lane;
        json lanes_j = json::array();
        for (unsigned l = 0; l < d.lanes; ++l) {
            json lj = {{"lane", l}};
            if (lanes.pixel) {
                lj["x"] = lanes.x + (l & 1u);
                lj["y"] = lanes.y + (l >> 1);
            }
            lj["covered"] = (d.covered >> l & 1u) != 0;
            lanes_j.push_back(lj);
        }
        j["lanes"] = lanes_j;
        j["inputs"] = json::object();
        for (const auto& in : d.inputs) j["inputs"][write_name(in)] = lanes_json(in, d.lanes);
        j["constants"] = registers_json(d.constants, true);
        j["steps"] = json::array();
        for (size_t i = 0; i < d.steps.size(); ++i) {
            const auto& s = d.steps[i];
            json sj = {{"step", i + 1}, {"instruction", s.instruction}, {"line", dis.line(s.instruction)}, {"text", dis.text(s.instruction)}};
            if (hlsl.table) sj["hlsl"] = hlsl.entry_json(hlsl.step_entry[i]);
            sj["writes"] = json::array();
            for (const auto& w : s.writes)
                sj["writes"].push_back({{"register", write_name(w)}, {"mask", mask_text(w.mask)}, {"lanes", lanes_json(w, d.lanes)}});
            if (s.texkill) {
                sj["killed"] = json::array();
                for (unsigned l = 0; l < d.lanes; ++l)
                    if (s.killed >> l & 1u) sj["killed"].push_back(l);
            }
            j["steps"].push_back(sj);
        }
        if (hlsl.table) {
            j["hlsl_lines"] = json::array();
            for (const auto& g : hlsl.groups) {
                json gj = hlsl.entry_json(g.entry);
                if (gj.is_null()) gj = json::object({{"file", nullptr}, {"line", nullptr}, {"text", nullptr}});
                gj["steps"] = json::array();
                for (size_t i : g.steps) gj["steps"].push_back(i + 1);
                j["hlsl_lines"].push_back(gj);
            }
        }
        std::cout << json_text(j) << '\n';
        return kOk;
    }
    std::cout << title << '\n' << d.program->version.name() << ": " << source_note << '\n';
    if (d.lanes > 1) {
        std::cout << "lanes:";
        for (unsigned l = 0; l < d.lanes; ++l)
            std::cout << " " << l << " " << lanes.name(l) << ((d.covered >> l & 1u) ? "" : " helper") << (l + 1 < d.lanes ? "," : "");
        std::cout << " (the pixel: lane " << d.watched_lane << ")\n";
    }
    std::cout << "inputs:\n";
    for (const auto& in : d.inputs) print_register(std::cout, write_name(in), in, d, lanes);
    if (!d.constants.empty()) std::cout << "constants: " << registers_text(d.constants, true) << '\n';
    auto print_step = [&](size_t i, const std::string& indent) {
        const auto& s = d.steps[i];
        std::cout << indent << "step " << i + 1 << ", line " << dis.line(s.instruction) << ": " << dis.text(s.instruction)
                  << '\n';
        for (const auto& w : s.writes) print_register(std::cout, write_name(w), w, d, lanes, indent);
        if (s.texkill) {
            std::cout << indent << "  killed lanes:";
            bool any = false;
            for (unsigned l = 0; l < d.lanes; ++l)
                if (s.killed >> l & 1u) {
                    std::cout << " " << l;
                    any = true;
                }
            std::cout << (any ? "\n" : " none\n");
        }
    };
    if (!hlsl.table) {
        for (size_t i = 0; i < d.steps.size(); ++i) print_step(i, "");
        return kOk;
    }
    for (const auto& g : hlsl.groups) {
        if (g.entry)
            std::cout << hlsl.file(*g.entry) << ":" << g.entry->line << ": " << trimmed(hlsl.text(*g.entry)) << '\n';
        else
            std::cout << "(no HLSL line)\n";
        for (size_t i : g.steps) print_step(i, "  ");
    }
    return kOk;
}

int run_pixel_debug(const DebugCliOptions& o) {
    auto recorded = record_history(o.pixel, "debug", true);
    if (const int* status = std::get_if<int>(&recorded)) return *status;
    const PixelHistory& h = std::get<PixelHistory>(recorded);
    // The draw, then its last primitive over the pixel that ran the pixel shader.
    const DrawAtCall* chosen = nullptr;
    for (const auto& d : h.draws)
        if (!o.draw || d.call == *o.draw) chosen = &d;
    if (!chosen) {
        std::string calls;
        for (const auto& d : h.draws) calls += (calls.empty() ? "" : ", ") + std::to_string(d.call);
        std::cerr << "sm2 debug: " << (o.draw ? "--draw " + std::to_string(*o.draw) + ": no draw at that call covered"
                                              : std::string("no draw covered"))
                  << " pixel " << h.x << "," << h.y << " of frame " << o.pixel.frame << " ("
                  << (calls.empty() ? "none did" : "draws that did: calls " + calls) << ")\n";
        return kInvalidInput;
    }
    const rt::PixelFragment* fragment = nullptr;
    for (const auto& f : chosen->draw.fragments)
        if (f.shader_debug) fragment = &f;
    if (!fragment) {
        std::string shaded;  // the draws that can be debugged here instead
        for (const auto& d : h.draws)
            if (std::any_of(d.draw.fragments.begin(), d.draw.fragments.end(), [](const auto& f) { return f.shader_debug != nullptr; }))
                shaded += (shaded.empty() ? "" : ", ") + std::to_string(d.call);
        std::cerr << "sm2 debug: call " << chosen->call << " covered pixel " << h.x << "," << h.y
                  << " but its pixel shader did not run there (scissored, or the early depth/stencil test failed); "
                  << (shaded.empty() ? std::string("no draw's shader ran there") : "--draw one of the calls whose shader ran: " + shaded)
                  << '\n';
        return kInvalidInput;
    }
    const rt::ShaderDebug& d = *fragment->shader_debug;
    const LaneNames lanes{true, h.x - (d.watched_lane & 1u), h.y - (d.watched_lane >> 1)};
    json header = {{"file", h.file_name}, {"frame", o.pixel.frame}, {"stage", "pixel"}, {"x", h.x}, {"y", h.y},
                   {"call", chosen->call}, {"name", chosen->name}, {"primitive", fragment->primitive}};
    const std::string title = "pixel shader of call " + std::to_string(chosen->call) + " " + chosen->name + ", primitive " +
                              std::to_string(fragment->primitive) + ", at pixel (" + std::to_string(h.x) + ", " +
                              std::to_string(h.y) + ") of frame " + std::to_string(o.pixel.frame) + " of " + h.file_name;
    return print_debug(d, std::move(header), title, lanes, o.pixel.json);
}

int run_vertex_debug(const DebugCliOptions& o) {
    rt::Device device(inspection_device_options());
    rt::VertexWatch watch;
    watch.index = *o.vertex;
    struct VertexAtCall {
        uint64_t call = 0;
        std::string name;
        std::shared_ptr<const rt::ShaderDebug> debug;
    };
    std::vector<VertexAtCall> draws;
    const auto walk = replay_frame(o.pixel, "debug", device, [&](bool on) { device.watch_vertex(on ? &watch : nullptr); },
                                   [&](uint64_t call, const std::string& name) {
        for (auto& traced : watch.draws) draws.push_back({call, name, std::move(traced)});
        watch.draws.clear();
    });
    if (!walk) return kInvalidInput;
    const VertexAtCall* chosen = nullptr;
    for (const auto& d : draws)
        if (d.debug && (!o.draw || d.call == *o.draw)) chosen = &d;
    if (!chosen) {
        std::string calls;
        for (const auto& d : draws)
            if (d.debug) calls += (calls.empty() ? "" : ", ") + std::to_string(d.call);
        std::cerr << "sm2 debug: " << (o.draw ? "--draw " + std::to_string(*o.draw) + ": no draw at that call fetched"
                                              : std::string("no draw fetched"))
                  << " vertex " << *o.vertex << " in frame " << o.pixel.frame << " ("
                  << (calls.empty() ? "none did" : "draws that did: calls " + calls) << ")\n";
        return kInvalidInput;
    }
    json header = {{"file", walk->file_name}, {"frame", o.pixel.frame}, {"stage", "vertex"}, {"vertex", *o.vertex},
                   {"call", chosen->call}, {"name", chosen->name}};
    const std::string title = "vertex shader of call " + std::to_string(chosen->call) + " " + chosen->name + " for vertex " +
                              std::to_string(*o.vertex) + " of frame " + std::to_string(o.pixel.frame) + " of " +
                              walk->file_name;
    return print_debug(*chosen->debug, std::move(header), title, LaneNames{false, *o.vertex, 0}, o.pixel.json);
}

int run_debug(const DebugCliOptions& o) {
    if (o.pixel.pixel.empty() == !o.vertex) {
        std::cerr << "sm2 debug: give one of --pixel X,Y and --vertex I\n";
        return kBadUsage;
    }
    return o.vertex ? run_vertex_debug(o) : run_pixel_debug(o);
}

void add_stream_and_frame(CLI::App& cmd, PixelCliOptions& o) {
    add_stream_argument(cmd, o.stream);
    cmd.add_option("--frame", o.frame, "The frame (0 is the first Present's)")->required();
}

constexpr const char* kTargetHelp =
    "Whose pixel: 'back' (the back buffer, default), 'rt0'..'rt3' (render target N of each draw, whatever is bound "
    "there), or the name of a render target surface or texture as the stream names it (sm2 state shows the names)";

}  // namespace

void add_pixel_command(CLI::App& app, int& status) {
    auto o = std::make_shared<PixelCliOptions>();
    auto* cmd = app.add_subcommand(
        "pixel", "The history of one pixel of one frame: every draw into the back buffer (or --target) that covered "
                 "it, each primitive's shader inputs and colour, test outcomes (scissor, depth/stencil, texkill, alpha) "
                 "and the value before and after; the last value is the frame's pixel");
    add_stream_and_frame(*cmd, *o);
    cmd->add_option("--pixel", o->pixel, "X,Y: the pixel, from the top left of the target")->required();
    cmd->add_option("--target", o->target, kTargetHelp);
    cmd->add_flag("--json", o->json, "The history as JSON on stdout");
    add_read_root_option(*cmd, o->read_root);
    cmd->callback([o, &status] { status = run_pixel(*o); });
}

void add_debug_command(CLI::App& app, int& status) {
    auto o = std::make_shared<DebugCliOptions>();
    auto* cmd = app.add_subcommand(
        "debug", "Step through the pixel shader of a draw at one pixel (its 2x2 quad, with the draw's interpolated "
                 "inputs, constants and textures) or the vertex shader of a draw for one vertex: the registers each "
                 "source instruction wrote, in every lane");
    add_stream_and_frame(*cmd, o->pixel);
    cmd->add_option("--pixel", o->pixel.pixel, "X,Y: debug the pixel shader at this pixel");
    cmd->add_option("--vertex", o->vertex, "I: debug the vertex shader for vertex I (the vertex number fetched: an "
                                           "index plus BaseVertexIndex, or StartVertex + n)");
    cmd->add_option("--draw", o->draw, "The draw's call number (as sm2 pixel lists it); default: the last draw of "
                                       "the frame that covered the pixel or fetched the vertex");
    cmd->add_option("--target", o->pixel.target, kTargetHelp);
    cmd->add_flag("--json", o->pixel.json, "The trace as JSON on stdout");
    add_read_root_option(*cmd, o->pixel.read_root);
    cmd->callback([o, &status] { status = run_debug(*o); });
}

}  // namespace sm2::tools
