// The instruction table: every instruction of the SM2 family named once, with its token value,
// operands, the versions that allow it, its slot cost and slot class. The assembler,
// disassembler, validator and emulator all read this table; nothing else lists opcodes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "sm2/isa/version.h"

namespace sm2::isa {

// D3DSHADER_INSTRUCTION_OPCODE_TYPE
enum class Opcode : uint16_t {
    Nop = 0, Mov = 1, Add = 2, Sub = 3, Mad = 4, Mul = 5, Rcp = 6, Rsq = 7, Dp3 = 8, Dp4 = 9,
    Min = 10, Max = 11, Slt = 12, Sge = 13, Exp = 14, Log = 15, Lit = 16, Dst = 17, Lrp = 18,
    Frc = 19, M4x4 = 20, M4x3 = 21, M3x4 = 22, M3x3 = 23, M3x2 = 24, Call = 25, CallNz = 26,
    Loop = 27, Ret = 28, EndLoop = 29, Label = 30, Dcl = 31, Pow = 32, Crs = 33, Sgn = 34,
    Abs = 35, Nrm = 36, SinCos = 37, Rep = 38, EndRep = 39, If = 40, Ifc = 41, Else = 42,
    EndIf = 43, Break = 44, BreakC = 45, Mova = 46, DefB = 47, DefI = 48,
    TexCoord = 64, TexKill = 65, Tex = 66, ExpP = 78, LogP = 79, Cnd = 80, Def = 81,
    Cmp = 88, Bem = 89, Dp2Add = 90, Dsx = 91, Dsy = 92, TexLdd = 93, SetP = 94, TexLdl = 95,
    BreakP = 96,
    Phase = 0xFFFD, Comment = 0xFFFE, End = 0xFFFF,
};

// Controls in bits 16..23 of the instruction token.
constexpr uint8_t kTexLdPlain = 0;
constexpr uint8_t kTexLdProject = 1;  // texldp
constexpr uint8_t kTexLdBias = 2;     // texldb

// How an instruction's operand tokens are shaped.
enum class OperandLayout : uint8_t {
    Standard,     // [destination] sources...
    Declaration,  // dcl: usage/type token, destination token
    FloatDef,     // def: destination, 4 raw float bits
    IntDef,       // defi: destination, 4 integers
    BoolDef,      // defb: destination, 1 DWORD
};

// What a destination may be.
enum class DestKind : uint8_t {
    None,
    Value,    // any writable register of the profile (temps, outputs)
    Temp,     // r# only
    Address,  // a0 (mova)
    Tested,   // texkill: the register it tests, t# or r#, stored as a destination token
};

// What a source operand may be.
enum class SourceKind : uint8_t {
    None,
    Value,        // any readable value register (r, v, c, t)
    Sampler,      // s#
    Label,        // l#
    Bool,         // b# (with optional ! modifier)
    Int,          // i#
    LoopCounter,  // aL
    Predicate,    // p0
};

// Which ps_2_0 budget an instruction draws on (vertex shaders have one budget).
enum class SlotClass : uint8_t {
    Arithmetic,
    Texture,
    FlowControl,  // vs flow control: counted in the vs budget
    Setup,        // dcl, def*: no slots
};

// Semantic grouping the emulator and validator use.
enum class Category : uint8_t {
    ComponentWise,  // mov add sub mad mul min max slt sge frc lrp abs cmp sgn
    DotProduct,     // dp3 dp4 dp2add
    Scalar,         // rcp rsq exp log expp logp pow: replicated result
    Matrix,         // m4x4 .. m3x2
    Special,        // lit dst nrm crs sincos mova
    Texture,        // texld*, texkill
    FlowControl,
    Setup,          // dcl def defi defb
    Other,          // nop, ps_1_x/ps_2_x-only instructions
};

struct OpcodeInfo {
    Opcode opcode;
    uint8_t control;              // bits 16..23 that select this row (texld variants)
    std::string_view mnemonic;
    OperandLayout layout;
    Category category;
    DestKind dest;
    uint8_t num_sources;          // the documented source count
    uint8_t min_sources;          // fewest sources an assembler writes (ps sincos: 1)
    std::array<SourceKind, 4> sources;
    VersionRange vs;              // vertex-shader versions that allow it
    VersionRange ps;              // pixel-shader versions that allow it
    uint8_t vs_slots;
    uint8_t ps_slots;
    SlotClass slot_class;
    uint8_t replicate_sources;    // bit i: source i needs a replicate swizzle (.x .y .z .w)
    uint8_t matrix_rows;          // matrix macros: rows read from src1 (0 otherwise)
    uint8_t matrix_columns;       // matrix macros: components per row (3 or 4)

    [[nodiscard]] bool allowed_in(ShaderVersion v) const {
        return (v.is_vertex() ? vs : ps).contains(v.number());
    }
    [[nodiscard]] uint8_t slots_in(ShaderVersion v) const {
        return v.is_vertex() ? vs_slots : ps_slots;
    }
    [[nodiscard]] bool has_dest() const { return dest != DestKind::None; }
};

[[nodiscard]] std::span<const OpcodeInfo> opcode_table();
// The row for an opcode and its control bits (texld variants); nullptr if not an SM2 opcode.
[[nodiscard]] const OpcodeInfo* find_opcode(Opcode opcode, uint8_t control = 0);
[[nodiscard]] const OpcodeInfo* find_opcode(uint16_t opcode, uint8_t control = 0);
// The row for a mnemonic without modifiers ("texldp", "mov"); nullptr if unknown.
[[nodiscard]] const OpcodeInfo* find_mnemonic(std::string_view mnemonic);

}  // namespace sm2::isa
