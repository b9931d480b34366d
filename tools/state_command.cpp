// sm2 state: the device state after one call of a stream or trace, as text or JSON.
#include <algorithm>
#include <bit>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "call_walk.h"
#include "commands.h"
#include "image_compare.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/device_inspection.h"
#include "sm2/runtime/replay.h"
#include "stream_io.h"

namespace sm2::tools {

namespace {

using json = nlohmann::ordered_json;
namespace rt = runtime;

struct StateCliOptions {
    std::string stream;
    uint64_t call = 0;
    bool json = false;
    std::string read_root;
};

std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08X", v);
    return buf;
}

std::string float_text(float f) {
    std::ostringstream s;
    s << f;
    return s.str();
}

// A state's DWORD as its table says to read it: "NONE", "TRUE", "0.5", "0xFF00FF00", "XYZ|DIFFUSE".
std::string state_value_text(const rt::StateInfo& info, uint32_t value) {
    switch (info.kind) {
    case rt::StateValueKind::Enum: {
        const auto name = rt::enum_name(info.family, value);
        return name.empty() ? std::to_string(value) : std::string(name);
    }
    case rt::StateValueKind::Bool: return value ? "TRUE" : "FALSE";
    case rt::StateValueKind::Float: return float_text(std::bit_cast<float>(value));
    case rt::StateValueKind::Color: return hex(value);
    case rt::StateValueKind::Bits: {
        if (info.family == rt::EnumFamily::Bool) return hex(value);
        std::string text;
        for (const auto& n : rt::flag_names(info.family, value)) text += (text.empty() ? "" : "|") + n;
        return text.empty() ? "0" : text;
    }
    case rt::StateValueKind::Integer: return std::to_string(value);
    }
    return std::to_string(value);
}

json resource_json(const rt::ResourceDescription& r) {
    json j = {{"name", r.name.empty() ? json() : json(r.name)}, {"kind", r.kind}};
    if (r.width) {
        j["width"] = r.width;
        j["height"] = r.height;
        if (r.depth > 1) j["depth"] = r.depth;
        j["levels"] = r.levels;
        const rt::FormatInfo* f = rt::format_info(r.format);
        j["format"] = f ? std::string(f->name) : std::to_string(static_cast<uint32_t>(r.format));
        j["pool"] = rt::pool_name(r.pool);
        if (r.render_target_usage) j["usage_render_target"] = true;
        if (r.dynamic_usage) j["usage_dynamic"] = true;
    } else if (r.kind.ends_with("buffer")) {
        j["bytes"] = r.bytes;
    }
    return j;
}

// "rt (render target 64x64 A8R8G8B8, DEFAULT, 1 level)"
std::string resource_text(const rt::ResourceDescription& r) {
    std::string s = (r.name.empty() ? "(released)" : r.name) + " (" + r.kind;
    if (r.width) {
        const rt::FormatInfo* f = rt::format_info(r.format);
        s += " " + std::to_string(r.width) + "x" + std::to_string(r.height);
        if (r.depth > 1) s += "x" + std::to_string(r.depth);
        s += " " + (f ? std::string(f->name) : std::to_string(static_cast<uint32_t>(r.format))) + ", " +
             rt::pool_name(r.pool) + ", " + std::to_string(r.levels) + (r.levels == 1 ? " level" : " levels");
        if (r.render_target_usage) s += ", RENDERTARGET";
        if (r.dynamic_usage) s += ", DYNAMIC";
    } else if (r.kind.ends_with("buffer")) {
        s += ", " + std::to_string(r.bytes) + " bytes";
    }
    return s + ")";
}

json vec4_json(const std::array<float, 4>& v) { return json::array({v[0], v[1], v[2], v[3]}); }

// The whole state as JSON; the text form prints the same object.
json state_json(const rt::DeviceInspection& now, const rt::DeviceInspection& defaults, uint64_t call,
                const CallWalk& walk) {
    json j = {{"file", walk.file_name}, {"call", call}, {"frame", now.frames_presented}, {"in_scene", now.in_scene}};
    json targets = json::object();
    for (unsigned i = 0; i < now.render_target_resources.size(); ++i)
        if (now.render_target_resources[i]) targets[std::to_string(i)] = resource_json(*now.render_target_resources[i]);
    j["render_targets"] = targets;
    j["depth_stencil"] = now.depth_stencil_resource ? resource_json(*now.depth_stencil_resource) : json();
    json textures = json::object();
    for (unsigned s = 0; s < now.textures.size(); ++s)
        if (now.textures[s]) textures[std::to_string(s)] = resource_json(*now.textures[s]);
    j["textures"] = textures;
    j["viewport"] = {{"x", now.viewport.x},         {"y", now.viewport.y},         {"width", now.viewport.width},
                     {"height", now.viewport.height}, {"min_z", now.viewport.min_z}, {"max_z", now.viewport.max_z}};
    j["scissor_rect"] = {{"left", now.scissor.left}, {"top", now.scissor.top}, {"right", now.scissor.right},
                         {"bottom", now.scissor.bottom}};

    json render_states = json::object();
    for (size_t i = 0; i < now.render_states.size(); ++i) {
        const auto [id, value] = now.render_states[i];
        if (value == defaults.render_states[i].second) continue;
        const rt::StateInfo* info = rt::find_render_state(id);
        render_states[std::string(info->name)] = {{"value", state_value_text(*info, value)}, {"dword", value},
                                                  {"default", state_value_text(*info, defaults.render_states[i].second)}};
    }
    j["render_states"] = render_states;
    json samplers = json::object();
    for (unsigned s = 0; s < now.samplers.size(); ++s) {
        json changed = json::object();
        for (const auto& info : rt::sampler_states()) {
            const uint32_t value = now.samplers[s].get(info.id).value_or(0);
            const uint32_t initial = defaults.samplers[s].get(info.id).value_or(0);
            if (value != initial)
                changed[std::string(info.name)] = {{"value", state_value_text(info, value)}, {"dword", value},
                                                   {"default", state_value_text(info, initial)}};
        }
        if (!changed.empty()) samplers[std::to_string(s)] = changed;
    }
    j["sampler_states"] = samplers;
    json stages = json::object();
    for (unsigned stage = 0; stage < rt::kMaxTextureStages; ++stage) {
        json changed = json::object();
        for (const auto& info : rt::texture_stage_states()) {
            if (info.id >= rt::kTextureStageStateCount) continue;
            const uint32_t value = now.fixed_function->stages[stage][info.id];
            const uint32_t initial = defaults.fixed_function->stages[stage][info.id];
            if (value != initial)
                changed[std::string(info.name)] = {{"value", state_value_text(info, value)}, {"dword", value},
                                                   {"default", state_value_text(info, initial)}};
        }
        if (!changed.empty()) stages[std::to_string(stage)] = changed;
    }
    j["texture_stage_states"] = stages;

    auto constants = [](const std::vector<std::array<float, 4>>& f, const emu::StaticFlowConstants& flow) {
        json c = json::object();
        for (size_t r = 0; r < f.size(); ++r)
            if (f[r] != std::array<float, 4>{}) c["c" + std::to_string(r)] = vec4_json(f[r]);
        for (size_t r = 0; r < flow.integers.size(); ++r)
            if (flow.integers[r] != emu::Int4{})
                c["i" + std::to_string(r)] = json::array({flow.integers[r][0], flow.integers[r][1], flow.integers[r][2],
                                                          flow.integers[r][3]});
        for (size_t r = 0; r < flow.booleans.size(); ++r)
            if (flow.booleans[r]) c["b" + std::to_string(r)] = true;
        return c;
    };
    j["vertex_shader_constants"] = constants(*now.vertex_constants_f, *now.vertex_flow);
    j["pixel_shader_constants"] = constants(*now.pixel_constants_f, *now.pixel_flow);

    if (now.declaration) {
        json d = resource_json(*now.declaration);
        d["elements"] = json::array();
        for (const auto& e : now.declaration_elements) {
            const auto type = rt::enum_name(rt::EnumFamily::DeclType, e.type);
            const auto usage = rt::enum_name(rt::EnumFamily::DeclUsage, e.usage);
            d["elements"].push_back({{"stream", e.stream}, {"offset", e.offset},
                                     {"type", type.empty() ? json(e.type) : json(std::string(type))},
                                     {"method", e.method},
                                     {"usage", usage.empty() ? json(e.usage) : json(std::string(usage))},
                                     {"usage_index", e.usage_index}});
        }
        j["vertex_declaration"] = d;
    } else {
        j["vertex_declaration"] = json();
    }
    if (now.fixed_function->fvf != 0) {
        std::string fvf;
        for (const auto& n : rt::flag_names(rt::EnumFamily::Fvf, now.fixed_function->fvf)) fvf += (fvf.empty() ? "" : "|") + n;
        j["fvf"] = fvf;
    } else {
        j["fvf"] = json();
    }
    json streams = json::object();
    for (unsigned s = 0; s < now.streams.size(); ++s)
        if (now.streams[s]) {
            json st = resource_json(now.streams[s]->buffer);
            st["offset"] = now.streams[s]->offset;
            st["stride"] = now.streams[s]->stride;
            streams[std::to_string(s)] = st;
        }
    j["streams"] = streams;
    if (now.indices) {
        json ib = resource_json(*now.indices);
        ib["format"] = now.index_format == rt::IndexFormat::Index32 ? "INDEX32" : "INDEX16";
        j["indices"] = ib;
    } else {
        j["indices"] = json();
    }
    auto shader = [](const std::optional<rt::ShaderInspection>& s) -> json {
        if (!s) return json();
        json sj = resource_json(s->resource);
        sj["disassembly"] = s->program ? json(assembler::disassemble(*s->program)) : json();
        return sj;
    };
    j["vertex_shader"] = shader(now.vertex_shader);
    j["pixel_shader"] = shader(now.pixel_shader);
    return j;
}

// A state's entries "NAME = value (default d)".
void print_states(const json& states, const std::string& indent) {
    for (const auto& [name, s] : states.items())
        std::cout << indent << name << " = " << s["value"].get<std::string>() << " (default "
                  << s["default"].get<std::string>() << ")\n";
}

void print_state_text(const json& j, const rt::DeviceInspection& now) {
    std::cout << "state after call " << j["call"] << " of " << j["file"].get<std::string>() << " (frame " << j["frame"]
              << (j["in_scene"].get<bool>() ? ", inside BeginScene/EndScene" : "") << ")\n";
    std::cout << "render targets:\n";
    for (unsigned i = 0; i < now.render_target_resources.size(); ++i)
        if (now.render_target_resources[i]) std::cout << "  " << i << ": " << resource_text(*now.render_target_resources[i]) << '\n';
    std::cout << "depth stencil: " << (now.depth_stencil_resource ? resource_text(*now.depth_stencil_resource) : "none") << '\n';
    std::cout << "textures:" << (j["textures"].empty() ? " none" : "") << '\n';
    for (unsigned s = 0; s < now.textures.size(); ++s)
        if (now.textures[s]) std::cout << "  " << s << ": " << resource_text(*now.textures[s]) << '\n';
    const auto& v = now.viewport;
    std::cout << "viewport: x " << v.x << ", y " << v.y << ", " << v.width << "x" << v.height << ", z " << float_text(v.min_z)
              << ".." << float_text(v.max_z) << '\n';
    std::cout << "scissor rect: left " << now.scissor.left << ", top " << now.scissor.top << ", right " << now.scissor.right
              << ", bottom " << now.scissor.bottom << '\n';
    std::cout << "render states differing from their defaults:" << (j["render_states"].empty() ? " none" : "") << '\n';
    print_states(j["render_states"], "  ");
    std::cout << "sampler states differing from their defaults:" << (j["sampler_states"].empty() ? " none" : "") << '\n';
    for (const auto& [s, states] : j["sampler_states"].items()) {
        std::cout << "  sampler " << s << ":\n";
        print_states(states, "    ");
    }
    std::cout << "texture stage states differing from their defaults:" << (j["texture_stage_states"].empty() ? " none" : "")
              << '\n';
    for (const auto& [s, states] : j["texture_stage_states"].items()) {
        std::cout << "  stage " << s << ":\n";
        print_states(states, "    ");
    }
    for (const char* which : {"vertex_shader_constants", "pixel_shader_constants"}) {
        std::cout << (which[0] == 'v' ? "vertex" : "pixel") << " shader constants (non-zero):"
                  << (j[which].empty() ? " none" : "") << '\n';
        for (const auto& [reg, value] : j[which].items()) {
            std::string text;
            for (const auto& component : value)
                text += (text.empty() ? "" : ", ") +
                        (component.is_number_float() ? float_text(component.get<float>()) : component.dump());
            std::cout << "  " << reg << " = (" << text << ")\n";
        }
    }
    std::cout << "vertex declaration: " << (now.declaration ? resource_text(*now.declaration) : "none") << '\n';
    if (now.declaration)
        for (const auto& e : j["vertex_declaration"]["elements"])
            std::cout << "  stream " << e["stream"] << " offset " << e["offset"] << " "
                      << (e["type"].is_string() ? e["type"].get<std::string>() : e["type"].dump()) << " "
                      << (e["usage"].is_string() ? e["usage"].get<std::string>() : e["usage"].dump()) << " "
                      << e["usage_index"] << '\n';
    std::cout << "FVF: " << (j["fvf"].is_null() ? "none" : j["fvf"].get<std::string>()) << '\n';
    std::cout << "streams:" << (j["streams"].empty() ? " none" : "") << '\n';
    for (unsigned s = 0; s < now.streams.size(); ++s)
        if (now.streams[s])
            std::cout << "  " << s << ": " << resource_text(now.streams[s]->buffer) << ", offset " << now.streams[s]->offset
                      << ", stride " << now.streams[s]->stride << '\n';
    std::cout << "indices: "
              << (now.indices ? resource_text(*now.indices) + ", " + j["indices"]["format"].get<std::string>() : "none") << '\n';
    for (const char* which : {"vertex_shader", "pixel_shader"}) {
        const auto& s = which[0] == 'v' ? now.vertex_shader : now.pixel_shader;
        std::cout << (which[0] == 'v' ? "vertex" : "pixel") << " shader: " << (s ? resource_text(s->resource) : "none") << '\n';
        if (s && !j[which]["disassembly"].is_null()) {
            std::istringstream lines(j[which]["disassembly"].get<std::string>());
            for (std::string line; std::getline(lines, line);) std::cout << "  " << line << '\n';
        }
    }
}

int run_state(const StateCliOptions& o) {
    rt::Device device(inspection_device_options());
    // The defaults are those of a device created as this one was (ZENABLE is TRUE with an
    // automatic depth-stencil surface): its CreateDevice replayed on a second device.
    rt::Device fresh;
    rt::ReplayOptions fresh_options;
    rt::Replayer fresh_replayer(fresh, fresh_options);
    auto walk = walk_calls(o.stream, o.read_root, "state", device, [&](uint64_t call, const rt::cs::Statement& st) {
        if (call > o.call) return false;
        if (st.name == "CreateDevice") fresh_replayer.execute(st);
        return true;
    });
    if (!walk) return kInvalidInput;
    if (o.call < walk->first_call || o.call > walk->last_call) {
        std::cerr << "sm2 state: --call " << o.call << ": out of range: " << walk->file_name << " has "
                  << walk->range_text() << '\n';
        return kInvalidInput;
    }
    // A trace call with no statement (a query, a skipped call) leaves the state of the calls before.
    const rt::DeviceInspection now = device.inspect();
    const json j = state_json(now, fresh.inspect(), o.call, *walk);
    if (o.json) std::cout << json_text(j) << '\n';
    else print_state_text(j, now);
    return kOk;
}

}  // namespace

void add_state_command(CLI::App& app, int& status) {
    auto o = std::make_shared<StateCliOptions>();
    auto* cmd = app.add_subcommand(
        "state", "The device state after one call of a command stream or trace: bound resources, render/sampler/"
                 "texture-stage states that differ from their defaults, constants, viewport, streams, shaders "
                 "with their disassembly");
    add_stream_argument(*cmd, o->stream);
    cmd->add_option("--call", o->call,
                    "The call after which to show the state: numbered from 1 in streams (as sm2 replay --stats), the "
                    "trace's own numbers in traces")
        ->required();
    cmd->add_flag("--json", o->json, "The state as JSON on stdout");
    add_read_root_option(*cmd, o->read_root);
    cmd->callback([o, &status] { status = run_state(*o); });
}

}  // namespace sm2::tools
