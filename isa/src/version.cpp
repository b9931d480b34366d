#include "sm2/isa/version.h"

#include <array>

namespace sm2::isa {

std::string ShaderVersion::name() const {
    std::string s = is_vertex() ? "vs_" : "ps_";
    s += std::to_string(major);
    s += '_';
    if (minor == 0x01 && major == 2) s += 'x';
    else if (minor == 0xFF) s += "sw";
    else s += std::to_string(minor);
    return s;
}

namespace {

// registers-and-limits.md §1, §2, §12.3 (instructions.md).
constexpr std::array kProfiles = {
    Profile{
        .name = "vs_2_0",
        .version = {ShaderType::Vertex, 2, 0},
        .max_instruction_slots = 256,
        .max_arithmetic_slots = 256,
        .max_texture_slots = 0,
        .max_dependent_read_order = kUnlimited8,
        .max_loop_nesting = 1,
        .max_call_nesting = 1,
        .max_static_flow_count = 16,
        .max_labels = 16,
        .max_render_targets = 0,
        .arbitrary_swizzle = true,
        .flow_control = true,
        .relative_addressing = true,
    },
    Profile{
        .name = "ps_2_0",
        .version = {ShaderType::Pixel, 2, 0},
        .max_instruction_slots = 96,
        .max_arithmetic_slots = 64,
        .max_texture_slots = 32,
        .max_dependent_read_order = 3,
        .max_loop_nesting = 0,
        .max_call_nesting = 0,
        .max_static_flow_count = 0,
        .max_labels = 0,
        .max_render_targets = 4,
        .arbitrary_swizzle = false,
        .flow_control = false,
        .relative_addressing = false,
    },
};

}  // namespace

std::span<const Profile> profiles() { return kProfiles; }

const Profile* find_profile(ShaderVersion version) {
    for (const auto& p : kProfiles)
        if (p.version == version) return &p;
    return nullptr;
}

const Profile* find_profile(std::string_view name) {
    for (const auto& p : kProfiles) {
        if (p.name == name) return &p;
        // dotted form: vs.2.0
        if (name.size() == p.name.size()) {
            bool same = true;
            for (size_t i = 0; i < name.size() && same; ++i) {
                const char a = name[i], b = p.name[i];
                same = a == b || (a == '.' && b == '_');
            }
            if (same) return &p;
        }
    }
    return nullptr;
}

}  // namespace sm2::isa
