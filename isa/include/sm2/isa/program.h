// The decoded, in-memory form of a shader: what the assembler produces, the decoder reads, the
// validator checks and the emulator lowers. Statements keep their order (and comments) so that
// encode(decode(x)) == x for every well-formed stream.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "sm2/isa/opcodes.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/version.h"

namespace sm2::isa {

// D3DSHADER_PARAM_SRCMOD_TYPE
enum class SourceModifier : uint8_t {
    None = 0, Negate = 1, Bias = 2, BiasNegate = 3, Sign = 4, SignNegate = 5, Complement = 6,
    X2 = 7, X2Negate = 8, DivideZ = 9, DivideW = 10, Abs = 11, AbsNegate = 12, Not = 13,
};

// D3DDECLUSAGE
enum class DeclUsage : uint8_t {
    Position = 0, BlendWeight = 1, BlendIndices = 2, Normal = 3, PointSize = 4, TexCoord = 5,
    Tangent = 6, Binormal = 7, TessFactor = 8, PositionT = 9, Color = 10, Fog = 11, Depth = 12,
    Sample = 13,
};
constexpr uint8_t kMaxDeclUsage = 13;

// D3DSAMPLER_TEXTURE_TYPE (bits 27..30 of a sampler dcl's type token)
enum class TextureType : uint8_t { Unknown = 0, Texture1D = 1, Texture2D = 2, Cube = 3, Volume = 4 };

constexpr uint8_t kSwizzleIdentity = 0xE4;  // .xyzw
constexpr uint8_t kMaskAll = 0xF;

// Component `channel` (0..3) of a swizzle byte.
[[nodiscard]] constexpr uint8_t swizzle_component(uint8_t swizzle, int channel) {
    return static_cast<uint8_t>((swizzle >> (2 * channel)) & 3);
}
[[nodiscard]] constexpr uint8_t replicate_swizzle(uint8_t component) {
    return static_cast<uint8_t>(component * 0x55);
}
[[nodiscard]] constexpr bool is_replicate_swizzle(uint8_t swizzle) {
    return swizzle == 0x00 || swizzle == 0x55 || swizzle == 0xAA || swizzle == 0xFF;
}

// Where a statement came from in assembly text; line 0 = not from text.
struct SourceLocation {
    uint32_t line = 0;
    uint32_t column = 0;
    friend bool operator==(const SourceLocation&, const SourceLocation&) = default;
};

// The extra token after a relatively addressed source: a0.c or aL.
struct RelativeAddress {
    RegisterType type = RegisterType::Address;  // Address (a0) or Loop (aL)
    uint8_t swizzle = 0x00;                     // a0.x = 0x00 ... a0.w = 0xFF; aL / bare a0: 0xE4
    friend bool operator==(const RelativeAddress&, const RelativeAddress&) = default;
};

struct SourceParameter {
    RegisterType type = RegisterType::Temp;
    uint16_t index = 0;  // 11-bit register number (the constant offset when relative)
    uint8_t swizzle = kSwizzleIdentity;
    SourceModifier modifier = SourceModifier::None;
    std::optional<RelativeAddress> relative;
    friend bool operator==(const SourceParameter&, const SourceParameter&) = default;
};

struct DestinationParameter {
    RegisterType type = RegisterType::Temp;
    uint16_t index = 0;
    uint8_t write_mask = kMaskAll;  // bit 0 = x ... bit 3 = w
    bool saturate = false;
    bool partial_precision = false;
    bool centroid = false;
    uint8_t shift = 0;              // 4-bit result shift (ps_1_x only; 0 in SM2)
    friend bool operator==(const DestinationParameter&, const DestinationParameter&) = default;
};

// Fields of a dcl's usage/type token.
struct Declaration {
    DeclUsage usage = DeclUsage::Position;  // vs inputs (bits 0..4)
    uint8_t usage_index = 0;                // bits 16..19
    TextureType texture_type = TextureType::Unknown;  // samplers (bits 27..30)
    friend bool operator==(const Declaration&, const Declaration&) = default;
};

struct Instruction {
    Opcode opcode = Opcode::Nop;
    uint8_t control = 0;                              // bits 16..23 of the instruction token
    std::optional<DestinationParameter> dest;         // also dcl/def* register, texkill operand
    std::optional<SourceParameter> predicate;         // 2_x predication (bit 28)
    std::vector<SourceParameter> sources;
    Declaration declaration;                          // dcl only
    std::array<uint32_t, 4> constant_bits{};          // def: float bits; defi: ints; defb: [0]
    std::vector<uint32_t> comment;                    // Comment only: the opaque payload
    uint32_t token_offset = 0;                        // index of the instruction token in the stream
    SourceLocation location;                          // set by the assembler

    // The table row (nullptr for Comment, which has no row).
    [[nodiscard]] const OpcodeInfo* info() const { return find_opcode(opcode, control); }
    [[nodiscard]] bool is_setup() const {
        return opcode == Opcode::Dcl || opcode == Opcode::Def || opcode == Opcode::DefI ||
               opcode == Opcode::DefB;
    }
    // Semantic equality: everything but token_offset and location.
    [[nodiscard]] bool same_as(const Instruction& other) const;
};

struct Program {
    ShaderVersion version;
    std::vector<Instruction> instructions;  // in stream order, comments included
};

}  // namespace sm2::isa
