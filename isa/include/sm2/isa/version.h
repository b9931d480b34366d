// Shader versions and the profiles sm2emu supports, with their limits as data.
//
// Adding a profile (vs_2_x, ps_3_0, ...) means adding a row to the profile table in
// version.cpp, rows to the register-file table in registers.cpp, and widening the version
// ranges of the opcodes it gains in opcodes.cpp. Nothing else encodes "which version".
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sm2::isa {

enum class ShaderType : uint8_t { Vertex, Pixel };

struct ShaderVersion {
    ShaderType type = ShaderType::Vertex;
    uint8_t major = 2;
    uint8_t minor = 0;

    // The version token: 0xFFFE (vertex) or 0xFFFF (pixel) in bits 16..31.
    [[nodiscard]] constexpr uint32_t token() const {
        return (type == ShaderType::Vertex ? 0xFFFE0000u : 0xFFFF0000u) |
               (static_cast<uint32_t>(major) << 8) | minor;
    }
    [[nodiscard]] static constexpr std::optional<ShaderVersion> from_token(uint32_t token) {
        const uint32_t kind = token >> 16;
        if (kind != 0xFFFEu && kind != 0xFFFFu) return std::nullopt;
        return ShaderVersion{kind == 0xFFFEu ? ShaderType::Vertex : ShaderType::Pixel,
                             static_cast<uint8_t>((token >> 8) & 0xFF),
                             static_cast<uint8_t>(token & 0xFF)};
    }
    // Ordering within one shader type: 2.0 < 2.1 (2_x) < 3.0.
    [[nodiscard]] constexpr uint16_t number() const {
        return static_cast<uint16_t>((major << 8) | minor);
    }
    [[nodiscard]] constexpr bool is_vertex() const { return type == ShaderType::Vertex; }
    [[nodiscard]] constexpr bool is_pixel() const { return type == ShaderType::Pixel; }
    // "vs_2_0", "ps_2_x", "vs_2_sw"
    [[nodiscard]] std::string name() const;
    friend constexpr bool operator==(const ShaderVersion&, const ShaderVersion&) = default;
};

// A closed range of versions of one shader type, e.g. vs 2.0 .. 3.0. Empty when min > max.
struct VersionRange {
    uint16_t min = 0xFFFF;  // ShaderVersion::number()
    uint16_t max = 0;

    [[nodiscard]] constexpr bool empty() const { return min > max; }
    [[nodiscard]] constexpr bool contains(uint16_t number) const {
        return number >= min && number <= max;
    }
};

constexpr uint16_t kUnlimited = 0xFFFF;

// Documented limits of one profile (registers-and-limits.md).
struct Profile {
    std::string_view name;  // "vs_2_0"
    ShaderVersion version;
    uint16_t max_instruction_slots;   // vs: 256; ps_2_0: 96 (64 arithmetic + 32 texture)
    uint16_t max_arithmetic_slots;    // ps budget for class-A instructions (vs: same as total)
    uint16_t max_texture_slots;       // ps budget for texture instructions (vs: 0)
    uint8_t max_dependent_read_order; // ps_2_0: third-order dependent (kUnlimited8 = none)
    uint8_t max_loop_nesting;         // loop/rep depth; 0 = no loops at all
    uint8_t max_call_nesting;         // subroutine call depth; 0 = no calls
    uint8_t max_static_flow_count;    // if/else/rep/loop/call/callnz each add one
    uint16_t max_labels;              // l0 .. l(max_labels-1)
    uint8_t max_render_targets;       // oC0 .. oC(n-1)
    bool arbitrary_swizzle;           // false: ps_2_0's short list of source swizzles
    bool flow_control;                // any flow-control instruction allowed
    bool relative_addressing;         // c[a0.x + n] / c[aL + n]
};

constexpr uint8_t kUnlimited8 = 0xFF;

[[nodiscard]] std::span<const Profile> profiles();
[[nodiscard]] const Profile* find_profile(ShaderVersion version);
// Accepts "vs_2_0" and the dotted form "vs.2.0".
[[nodiscard]] const Profile* find_profile(std::string_view name);

}  // namespace sm2::isa
