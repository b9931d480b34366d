// Register types (D3DSPR_*) and the register files of each profile, as data.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "sm2/isa/version.h"

namespace sm2::isa {

// The 5-bit D3DSPR_* value, split across bits 28..30 and 11..12 of parameter tokens.
enum class RegisterType : uint8_t {
    Temp = 0,         // r#
    Input = 1,        // v#
    Const = 2,        // c#
    Address = 3,      // a0 in a vertex shader
    Texture = 3,      // t# in a pixel shader (same number as Address)
    RastOut = 4,      // oPos (0), oFog (1), oPts (2)
    AttrOut = 5,      // oD#
    TexCrdOut = 6,    // oT# (vs < 3.0), o# (vs_3_0)
    ConstInt = 7,     // i#
    ColorOut = 8,     // oC#
    DepthOut = 9,     // oDepth
    Sampler = 10,     // s#
    Const2 = 11,      // c2048..c4095
    Const3 = 12,
    Const4 = 13,
    ConstBool = 14,   // b#
    Loop = 15,        // aL
    TempFloat16 = 16, // reserved
    MiscType = 17,    // vPos (0), vFace (1)
    Label = 18,       // l#
    Predicate = 19,   // p0
};
constexpr uint8_t kMaxRegisterType = 19;

// RASTOUT register numbers.
constexpr uint16_t kRastOutPosition = 0;
constexpr uint16_t kRastOutFog = 1;
constexpr uint16_t kRastOutPointSize = 2;

// One register file of one profile: a row of the register table.
struct RegisterFile {
    ShaderType shader;
    VersionRange versions;       // which versions of `shader` have this file
    RegisterType type;
    std::string_view name;       // assembly name: "r", "c", "oPos", "a0", "aL", "oDepth"
    bool numbered;               // "r5" (true) vs "oPos"/"a0"/"aL" (false: fixed number)
    uint16_t first;              // first register number (oFog is RastOut #1)
    uint16_t count;              // documented count (validator limit)
    uint16_t encodable;          // highest count the assemblers still encode (>= count)
    bool readable;               // may appear as a source
    bool writable;               // may appear as a destination
    bool relative_addressing;    // may be indexed with a0 / aL
    bool needs_declaration;      // must be declared with dcl before it is read
    uint8_t read_ports;          // distinct registers of this file one instruction may read
    bool scalar;                 // oFog, oPts: mask forced to .xyzw by the assemblers
};

[[nodiscard]] std::span<const RegisterFile> register_files();

// The file a register of `type` and number `index` belongs to in `version`.
[[nodiscard]] const RegisterFile* find_register_file(ShaderVersion version, RegisterType type,
                                                     uint32_t index);
// The file named `name` ("r", "oPos", "a0", ...) in `version`; for numbered files the caller
// parses the number that follows the name.
[[nodiscard]] const RegisterFile* find_register_file(ShaderVersion version,
                                                     std::string_view name);

// Assembly name of a register: "r3", "oPos", "c[?]" never: relative forms are printed by the
// disassembler. Unknown combinations print as "?type:index".
[[nodiscard]] std::string register_name(ShaderVersion version, RegisterType type, uint32_t index);

}  // namespace sm2::isa
