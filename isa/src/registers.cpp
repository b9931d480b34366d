#include "sm2/isa/registers.h"

#include <array>

namespace sm2::isa {

namespace {

constexpr VersionRange kSm2{0x0200, 0x02FF};     // 2.0, 2_x, 2_sw
constexpr VersionRange kSm20{0x0200, 0x0200};    // exactly 2.0

using enum RegisterType;
constexpr ShaderType VS = ShaderType::Vertex;
constexpr ShaderType PS = ShaderType::Pixel;

// registers-and-limits.md §1 (vs_2_0), §2 (ps_2_0), §4 (read ports), §11 (what the
// assemblers encode beyond the documented counts).
// shader, versions, type, name, numbered, first, count, encodable, read, write, relative,
// needs dcl, read ports, scalar
constexpr std::array kFiles = {
    // vs_2_0
    RegisterFile{VS, kSm2, Temp, "r", true, 0, 12, 12, true, true, false, false, 3, false},
    RegisterFile{VS, kSm2, Input, "v", true, 0, 16, 16, true, false, false, true, 1, false},
    RegisterFile{VS, kSm2, Const, "c", true, 0, 256, 2048, true, false, true, false, 2, false},
    RegisterFile{VS, kSm2, Address, "a0", false, 0, 1, 1, false, true, false, false, 2, false},
    RegisterFile{VS, kSm2, ConstBool, "b", true, 0, 16, 16, true, false, false, false, 1, false},
    RegisterFile{VS, kSm2, ConstInt, "i", true, 0, 16, 16, true, false, false, false, 1, false},
    RegisterFile{VS, kSm2, Loop, "aL", false, 0, 1, 1, true, false, false, false, 2, false},
    RegisterFile{VS, kSm2, Label, "l", true, 0, 16, 2048, true, false, false, false, 1, false},
    RegisterFile{VS, kSm2, RastOut, "oPos", false, kRastOutPosition, 1, 1, false, true, false,
                 false, 0, false},
    RegisterFile{VS, kSm2, RastOut, "oFog", false, kRastOutFog, 1, 1, false, true, false,
                 false, 0, true},
    RegisterFile{VS, kSm2, RastOut, "oPts", false, kRastOutPointSize, 1, 1, false, true, false,
                 false, 0, true},
    RegisterFile{VS, kSm2, AttrOut, "oD", true, 0, 2, 2, false, true, false, false, 0, false},
    RegisterFile{VS, kSm2, TexCrdOut, "oT", true, 0, 8, 8, false, true, false, false, 0, false},
    // ps_2_0
    RegisterFile{PS, kSm2, Temp, "r", true, 0, 12, 32, true, true, false, false, 3, false},
    RegisterFile{PS, kSm2, Input, "v", true, 0, 2, 2, true, false, false, true, 1, false},
    RegisterFile{PS, kSm2, Const, "c", true, 0, 32, 32, true, false, false, false, 2, false},
    RegisterFile{PS, kSm2, Texture, "t", true, 0, 8, 8, true, false, false, true, 1, false},
    RegisterFile{PS, kSm2, Sampler, "s", true, 0, 16, 16, true, false, false, true, 1, false},
    // i#/b# do not exist in ps_2_0 (count 0), but Wine's assembler encodes them.
    RegisterFile{PS, kSm20, ConstInt, "i", true, 0, 0, 16, true, false, false, false, 1, false},
    RegisterFile{PS, kSm20, ConstBool, "b", true, 0, 0, 16, true, false, false, false, 1, false},
    RegisterFile{PS, kSm2, ColorOut, "oC", true, 0, 4, 4, false, true, false, false, 0, false},
    RegisterFile{PS, kSm2, DepthOut, "oDepth", false, 0, 1, 1, false, true, false, false, 0,
                 false},
};

}  // namespace

std::span<const RegisterFile> register_files() { return kFiles; }

const RegisterFile* find_register_file(ShaderVersion version, RegisterType type, uint32_t index) {
    for (const auto& f : kFiles) {
        if (f.shader != version.type || f.type != type || !f.versions.contains(version.number()))
            continue;
        const uint32_t span = f.numbered ? f.encodable : 1u;
        if (index >= f.first && index < f.first + span) return &f;
    }
    return nullptr;
}

const RegisterFile* find_register_file(ShaderVersion version, std::string_view name) {
    for (const auto& f : kFiles)
        if (f.shader == version.type && f.versions.contains(version.number()) && f.name == name)
            return &f;
    return nullptr;
}

std::string register_name(ShaderVersion version, RegisterType type, uint32_t index) {
    if (const RegisterFile* f = find_register_file(version, type, index)) {
        std::string s(f->name);
        if (f->numbered) s += std::to_string(index);
        return s;
    }
    return "?" + std::to_string(static_cast<unsigned>(type)) + ":" + std::to_string(index);
}

}  // namespace sm2::isa
