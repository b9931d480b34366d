// The instruction table (instructions.md §2). One row per instruction; texld's three
// variants are rows of their own because the control bits change the mnemonic.
#include "sm2/isa/opcodes.h"

#include <array>

namespace sm2::isa {

namespace {

constexpr VersionRange kNone{};
constexpr VersionRange k20Up{0x0200, 0x03FF};  // 2.0, 2_x, 2_sw, 3.0
constexpr VersionRange k2xUp{0x0201, 0x03FF};  // 2_x onwards
constexpr VersionRange k30Up{0x0300, 0x03FF};  // 3.0 onwards

using O = Opcode;
using L = OperandLayout;
using C = Category;
using D = DestKind;
using S = SourceKind;
using SC = SlotClass;

constexpr S V = S::Value;
constexpr S N = S::None;

struct Row {
    // Builder with the common defaults, so each table line states only what is particular.
    OpcodeInfo info;
    constexpr Row(O op, std::string_view mn, C cat, D dest, std::array<S, 4> src, uint8_t nsrc,
                  VersionRange vs, VersionRange ps, uint8_t vs_slots, uint8_t ps_slots,
                  SC cls)
        : info{op,  0,   mn,       L::Standard, cat,      dest, nsrc, nsrc, src,
               vs,  ps,  vs_slots, ps_slots,    cls,      0,    0,    0} {}
    constexpr Row control(uint8_t c) const { Row r = *this; r.info.control = c; return r; }
    constexpr Row layout(L l) const { Row r = *this; r.info.layout = l; return r; }
    constexpr Row replicate(uint8_t mask) const {
        Row r = *this; r.info.replicate_sources = mask; return r;
    }
    constexpr Row matrix(uint8_t rows, uint8_t cols) const {
        Row r = *this; r.info.matrix_rows = rows; r.info.matrix_columns = cols; return r;
    }
    constexpr Row min_sources(uint8_t n) const { Row r = *this; r.info.min_sources = n; return r; }
};

constexpr std::array<S, 4> src0{N, N, N, N};
constexpr std::array<S, 4> src1{V, N, N, N};
constexpr std::array<S, 4> src2{V, V, N, N};
constexpr std::array<S, 4> src3{V, V, V, N};

// clang-format off
constexpr std::array kRows = {
    //  opcode      mnemonic   category          dest        sources  n  vs      ps      vs ps class
    Row(O::Nop,     "nop",     C::Other,         D::None,    src0,    0, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Mov,     "mov",     C::ComponentWise, D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Add,     "add",     C::ComponentWise, D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Sub,     "sub",     C::ComponentWise, D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Mad,     "mad",     C::ComponentWise, D::Value,   src3,    3, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Mul,     "mul",     C::ComponentWise, D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Rcp,     "rcp",     C::Scalar,        D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic).replicate(0b1),
    Row(O::Rsq,     "rsq",     C::Scalar,        D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic).replicate(0b1),
    Row(O::Dp3,     "dp3",     C::DotProduct,    D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Dp4,     "dp4",     C::DotProduct,    D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Min,     "min",     C::ComponentWise, D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Max,     "max",     C::ComponentWise, D::Value,   src2,    2, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Slt,     "slt",     C::ComponentWise, D::Value,   src2,    2, k20Up,  kNone,  1, 0, SC::Arithmetic),
    Row(O::Sge,     "sge",     C::ComponentWise, D::Value,   src2,    2, k20Up,  kNone,  1, 0, SC::Arithmetic),
    Row(O::Exp,     "exp",     C::Scalar,        D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic).replicate(0b1),
    Row(O::Log,     "log",     C::Scalar,        D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic).replicate(0b1),
    Row(O::Lit,     "lit",     C::Special,       D::Value,   src1,    1, k20Up,  kNone,  3, 0, SC::Arithmetic),
    Row(O::Dst,     "dst",     C::Special,       D::Value,   src2,    2, k20Up,  kNone,  1, 0, SC::Arithmetic),
    Row(O::Lrp,     "lrp",     C::ComponentWise, D::Value,   src3,    3, k20Up,  k20Up,  2, 2, SC::Arithmetic),
    Row(O::Frc,     "frc",     C::ComponentWise, D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::M4x4,    "m4x4",    C::Matrix,        D::Value,   src2,    2, k20Up,  k20Up,  4, 4, SC::Arithmetic).matrix(4, 4),
    Row(O::M4x3,    "m4x3",    C::Matrix,        D::Value,   src2,    2, k20Up,  k20Up,  3, 3, SC::Arithmetic).matrix(3, 4),
    Row(O::M3x4,    "m3x4",    C::Matrix,        D::Value,   src2,    2, k20Up,  k20Up,  4, 4, SC::Arithmetic).matrix(4, 3),
    Row(O::M3x3,    "m3x3",    C::Matrix,        D::Value,   src2,    2, k20Up,  k20Up,  3, 3, SC::Arithmetic).matrix(3, 3),
    Row(O::M3x2,    "m3x2",    C::Matrix,        D::Value,   src2,    2, k20Up,  k20Up,  2, 2, SC::Arithmetic).matrix(2, 3),
    Row(O::Call,    "call",    C::FlowControl,   D::None,    {S::Label, N, N, N},       1, k20Up, k2xUp, 2, 2, SC::FlowControl),
    Row(O::CallNz,  "callnz",  C::FlowControl,   D::None,    {S::Label, S::Bool, N, N}, 2, k20Up, k2xUp, 3, 3, SC::FlowControl),
    Row(O::Loop,    "loop",    C::FlowControl,   D::None,    {S::LoopCounter, S::Int, N, N}, 2, k20Up, k30Up, 3, 3, SC::FlowControl),
    Row(O::Ret,     "ret",     C::FlowControl,   D::None,    src0,    0, k20Up,  k2xUp,  1, 1, SC::FlowControl),
    Row(O::EndLoop, "endloop", C::FlowControl,   D::None,    src0,    0, k20Up,  k30Up,  2, 2, SC::FlowControl),
    Row(O::Label,   "label",   C::FlowControl,   D::None,    {S::Label, N, N, N},       1, k20Up, k2xUp, 0, 0, SC::FlowControl),
    Row(O::Dcl,     "dcl",     C::Setup,         D::Value,   src0,    0, k20Up,  k20Up,  0, 0, SC::Setup).layout(L::Declaration),
    Row(O::Pow,     "pow",     C::Scalar,        D::Value,   src2,    2, k20Up,  k20Up,  3, 3, SC::Arithmetic).replicate(0b11),
    Row(O::Crs,     "crs",     C::Special,       D::Temp,    src2,    2, k20Up,  k20Up,  2, 2, SC::Arithmetic),
    Row(O::Sgn,     "sgn",     C::ComponentWise, D::Value,   src3,    3, k20Up,  kNone,  3, 0, SC::Arithmetic),
    Row(O::Abs,     "abs",     C::ComponentWise, D::Value,   src1,    1, k20Up,  k20Up,  1, 1, SC::Arithmetic),
    Row(O::Nrm,     "nrm",     C::Special,       D::Temp,    src1,    1, k20Up,  k20Up,  3, 3, SC::Arithmetic),
    // Wine's assembler writes the one-source ps form; the documented 2.0 form has three.
    Row(O::SinCos,  "sincos",  C::Special,       D::Temp,    src3,    3, k20Up,  k20Up,  8, 8, SC::Arithmetic).replicate(0b1).min_sources(1),
    Row(O::Rep,     "rep",     C::FlowControl,   D::None,    {S::Int, N, N, N},         1, k20Up, k2xUp, 3, 3, SC::FlowControl),
    Row(O::EndRep,  "endrep",  C::FlowControl,   D::None,    src0,    0, k20Up,  k2xUp,  2, 2, SC::FlowControl),
    Row(O::If,      "if",      C::FlowControl,   D::None,    {S::Bool, N, N, N},        1, k20Up, k2xUp, 3, 3, SC::FlowControl),
    Row(O::Ifc,     "ifc",     C::FlowControl,   D::None,    src2,    2, k2xUp,  k2xUp,  3, 3, SC::FlowControl),
    Row(O::Else,    "else",    C::FlowControl,   D::None,    src0,    0, k20Up,  k2xUp,  1, 1, SC::FlowControl),
    Row(O::EndIf,   "endif",   C::FlowControl,   D::None,    src0,    0, k20Up,  k2xUp,  1, 1, SC::FlowControl),
    Row(O::Break,   "break",   C::FlowControl,   D::None,    src0,    0, k2xUp,  k2xUp,  1, 1, SC::FlowControl),
    Row(O::BreakC,  "breakc",  C::FlowControl,   D::None,    src2,    2, k2xUp,  k2xUp,  3, 3, SC::FlowControl),
    Row(O::Mova,    "mova",    C::Special,       D::Address, src1,    1, k20Up,  kNone,  1, 0, SC::Arithmetic),
    Row(O::DefB,    "defb",    C::Setup,         D::Value,   src0,    0, k20Up,  k2xUp,  0, 0, SC::Setup).layout(L::BoolDef),
    Row(O::DefI,    "defi",    C::Setup,         D::Value,   src0,    0, k20Up,  k2xUp,  0, 0, SC::Setup).layout(L::IntDef),
    Row(O::TexKill, "texkill", C::Texture,       D::Tested,  src0,    0, kNone,  k20Up,  0, 1, SC::Texture),
    Row(O::Tex,     "texld",   C::Texture,       D::Temp,    {V, S::Sampler, N, N},     2, kNone, k20Up, 0, 1, SC::Texture),
    Row(O::Tex,     "texldp",  C::Texture,       D::Temp,    {V, S::Sampler, N, N},     2, kNone, k20Up, 0, 1, SC::Texture).control(kTexLdProject),
    Row(O::Tex,     "texldb",  C::Texture,       D::Temp,    {V, S::Sampler, N, N},     2, kNone, k20Up, 0, 1, SC::Texture).control(kTexLdBias),
    Row(O::ExpP,    "expp",    C::Scalar,        D::Value,   src1,    1, k20Up,  kNone,  1, 0, SC::Arithmetic).replicate(0b1),
    Row(O::LogP,    "logp",    C::Scalar,        D::Value,   src1,    1, k20Up,  kNone,  1, 0, SC::Arithmetic).replicate(0b1),
    Row(O::Def,     "def",     C::Setup,         D::Value,   src0,    0, k20Up,  k20Up,  0, 0, SC::Setup).layout(L::FloatDef),
    Row(O::Cmp,     "cmp",     C::ComponentWise, D::Value,   src3,    3, kNone,  k20Up,  0, 1, SC::Arithmetic),
    Row(O::Dp2Add,  "dp2add",  C::DotProduct,    D::Value,   src3,    3, kNone,  k20Up,  0, 2, SC::Arithmetic).replicate(0b100),
    Row(O::Dsx,     "dsx",     C::Other,         D::Value,   src1,    1, kNone,  k2xUp,  0, 2, SC::Arithmetic),
    Row(O::Dsy,     "dsy",     C::Other,         D::Value,   src1,    1, kNone,  k2xUp,  0, 2, SC::Arithmetic),
    Row(O::TexLdd,  "texldd",  C::Texture,       D::Temp,    {V, S::Sampler, V, V},     4, kNone, k2xUp, 0, 3, SC::Texture),
    Row(O::SetP,    "setp",    C::FlowControl,   D::Value,   src2,    2, k2xUp,  k2xUp,  1, 1, SC::FlowControl),
    Row(O::TexLdl,  "texldl",  C::Texture,       D::Temp,    {V, S::Sampler, N, N},     2, k30Up, k30Up, 2, 2, SC::Texture),
    Row(O::BreakP,  "breakp",  C::FlowControl,   D::None,    {S::Predicate, N, N, N},   1, k2xUp, k2xUp, 3, 3, SC::FlowControl),
};
// clang-format on

constexpr auto kTable = [] {
    std::array<OpcodeInfo, kRows.size()> table{};
    for (size_t i = 0; i < kRows.size(); ++i) table[i] = kRows[i].info;
    return table;
}();

// Opcodes whose control bits carry a comparison rather than selecting a row.
constexpr bool control_selects_row(Opcode op) { return op == Opcode::Tex; }

}  // namespace

std::span<const OpcodeInfo> opcode_table() { return kTable; }

const OpcodeInfo* find_opcode(Opcode opcode, uint8_t control) {
    const bool by_control = control_selects_row(opcode);
    for (const auto& row : kTable)
        if (row.opcode == opcode && (!by_control || row.control == control)) return &row;
    return nullptr;
}

const OpcodeInfo* find_opcode(uint16_t opcode, uint8_t control) {
    return find_opcode(static_cast<Opcode>(opcode), control);
}

const OpcodeInfo* find_mnemonic(std::string_view mnemonic) {
    for (const auto& row : kTable)
        if (row.mnemonic == mnemonic) return &row;
    return nullptr;
}

}  // namespace sm2::isa
