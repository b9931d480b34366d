// The ISA tables checked against the numbers printed in the spec: opcode values
// (bytecode.md §9), slot costs and versions (instructions.md §2), register files
// (registers-and-limits.md §1-§2), profile limits.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "sm2/isa/opcodes.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/version.h"

namespace sm2::isa {
namespace {

constexpr ShaderVersion kVs20{ShaderType::Vertex, 2, 0};
constexpr ShaderVersion kPs20{ShaderType::Pixel, 2, 0};

TEST(OpcodeTable, MnemonicsAreUniqueAndRowsAreFoundByOpcode) {
    std::set<std::string_view> seen;
    for (const auto& row : opcode_table()) {
        EXPECT_TRUE(seen.insert(row.mnemonic).second) << row.mnemonic;
        EXPECT_EQ(find_opcode(row.opcode, row.control), &row) << row.mnemonic;
        EXPECT_EQ(find_mnemonic(row.mnemonic), &row) << row.mnemonic;
        EXPECT_LE(row.min_sources, row.num_sources) << row.mnemonic;
    }
}

struct OpcodeFact {
    const char* mnemonic;
    uint16_t value;       // bytecode.md §9
    bool vs, ps;          // instructions.md §2 columns
    uint8_t vs_slots, ps_slots;
    SlotClass ps_class;
};

// Rows copied from the spec's tables (not from opcodes.cpp).
const OpcodeFact kFacts[] = {
    {"nop", 0, true, true, 1, 1, SlotClass::Arithmetic},
    {"mov", 1, true, true, 1, 1, SlotClass::Arithmetic},
    {"sub", 3, true, true, 1, 1, SlotClass::Arithmetic},
    {"rsq", 7, true, true, 1, 1, SlotClass::Arithmetic},
    {"slt", 12, true, false, 1, 0, SlotClass::Arithmetic},
    {"lit", 16, true, false, 3, 0, SlotClass::Arithmetic},
    {"lrp", 18, true, true, 2, 2, SlotClass::Arithmetic},
    {"m4x4", 20, true, true, 4, 4, SlotClass::Arithmetic},
    {"m4x3", 21, true, true, 3, 3, SlotClass::Arithmetic},
    {"m3x4", 22, true, true, 4, 4, SlotClass::Arithmetic},
    {"m3x3", 23, true, true, 3, 3, SlotClass::Arithmetic},
    {"m3x2", 24, true, true, 2, 2, SlotClass::Arithmetic},
    {"call", 25, true, false, 2, 0, SlotClass::FlowControl},
    {"callnz", 26, true, false, 3, 0, SlotClass::FlowControl},
    {"loop", 27, true, false, 3, 0, SlotClass::FlowControl},
    {"ret", 28, true, false, 1, 0, SlotClass::FlowControl},
    {"endloop", 29, true, false, 2, 0, SlotClass::FlowControl},
    {"label", 30, true, false, 0, 0, SlotClass::FlowControl},
    {"pow", 32, true, true, 3, 3, SlotClass::Arithmetic},
    {"crs", 33, true, true, 2, 2, SlotClass::Arithmetic},
    {"sgn", 34, true, false, 3, 0, SlotClass::Arithmetic},
    {"nrm", 36, true, true, 3, 3, SlotClass::Arithmetic},
    {"sincos", 37, true, true, 8, 8, SlotClass::Arithmetic},
    {"rep", 38, true, false, 3, 0, SlotClass::FlowControl},
    {"endrep", 39, true, false, 2, 0, SlotClass::FlowControl},
    {"if", 40, true, false, 3, 0, SlotClass::FlowControl},
    {"else", 42, true, false, 1, 0, SlotClass::FlowControl},
    {"endif", 43, true, false, 1, 0, SlotClass::FlowControl},
    {"mova", 46, true, false, 1, 0, SlotClass::Arithmetic},
    {"texkill", 65, false, true, 0, 1, SlotClass::Texture},
    {"texld", 66, false, true, 0, 1, SlotClass::Texture},
    {"texldp", 66, false, true, 0, 1, SlotClass::Texture},
    {"texldb", 66, false, true, 0, 1, SlotClass::Texture},
    {"expp", 78, true, false, 1, 0, SlotClass::Arithmetic},
    {"logp", 79, true, false, 1, 0, SlotClass::Arithmetic},
    {"cmp", 88, false, true, 0, 1, SlotClass::Arithmetic},
    {"dp2add", 90, false, true, 0, 2, SlotClass::Arithmetic},
};

TEST(OpcodeTable, MatchesTheSpecTables) {
    for (const auto& f : kFacts) {
        const OpcodeInfo* row = find_mnemonic(f.mnemonic);
        ASSERT_NE(row, nullptr) << f.mnemonic;
        EXPECT_EQ(static_cast<uint16_t>(row->opcode), f.value) << f.mnemonic;
        EXPECT_EQ(row->allowed_in(kVs20), f.vs) << f.mnemonic;
        EXPECT_EQ(row->allowed_in(kPs20), f.ps) << f.mnemonic;
        if (f.vs) {
            EXPECT_EQ(row->vs_slots, f.vs_slots) << f.mnemonic;
        }
        if (f.ps) {
            EXPECT_EQ(row->ps_slots, f.ps_slots) << f.mnemonic;
            EXPECT_EQ(row->slot_class, f.ps_class) << f.mnemonic;
        }
    }
    // texld variants are told apart by control bits 16..23 (bytecode.md §3)
    EXPECT_EQ(find_opcode(Opcode::Tex, 0)->mnemonic, "texld");
    EXPECT_EQ(find_opcode(Opcode::Tex, 1)->mnemonic, "texldp");
    EXPECT_EQ(find_opcode(Opcode::Tex, 2)->mnemonic, "texldb");
    EXPECT_EQ(find_opcode(Opcode::Tex, 3), nullptr);
}

TEST(OpcodeTable, OperandShapes) {
    // instructions.md §2 "ops" column and §10/§12 operand kinds
    EXPECT_EQ(find_mnemonic("mad")->num_sources, 3);
    EXPECT_EQ(find_mnemonic("dp2add")->replicate_sources, 0b100);  // s2.r
    EXPECT_EQ(find_mnemonic("pow")->replicate_sources, 0b11);      // s0.r, s1.r
    EXPECT_EQ(find_mnemonic("texkill")->dest, DestKind::Tested);
    EXPECT_EQ(find_mnemonic("texkill")->num_sources, 0);
    EXPECT_EQ(find_mnemonic("loop")->sources[0], SourceKind::LoopCounter);
    EXPECT_EQ(find_mnemonic("loop")->sources[1], SourceKind::Int);
    EXPECT_EQ(find_mnemonic("callnz")->sources[1], SourceKind::Bool);
    EXPECT_EQ(find_mnemonic("texld")->sources[1], SourceKind::Sampler);
    EXPECT_EQ(find_mnemonic("mova")->dest, DestKind::Address);
    EXPECT_EQ(find_mnemonic("sincos")->num_sources, 3);
    EXPECT_EQ(find_mnemonic("sincos")->min_sources, 1);  // Wine's ps form
    EXPECT_EQ(find_mnemonic("m3x2")->matrix_rows, 2);
    EXPECT_EQ(find_mnemonic("m4x3")->matrix_columns, 4);
    EXPECT_EQ(find_mnemonic("def")->layout, OperandLayout::FloatDef);
    EXPECT_EQ(find_mnemonic("defb")->layout, OperandLayout::BoolDef);
}

TEST(RegisterTable, Vs20Files) {
    // registers-and-limits.md §1
    EXPECT_EQ(find_register_file(kVs20, "r")->count, 12);
    EXPECT_EQ(find_register_file(kVs20, "v")->count, 16);
    EXPECT_EQ(find_register_file(kVs20, "c")->count, 256);
    EXPECT_TRUE(find_register_file(kVs20, "c")->relative_addressing);
    EXPECT_EQ(find_register_file(kVs20, "b")->count, 16);
    EXPECT_EQ(find_register_file(kVs20, "i")->count, 16);
    EXPECT_EQ(find_register_file(kVs20, "oT")->count, 8);
    EXPECT_EQ(find_register_file(kVs20, "oD")->count, 2);
    EXPECT_TRUE(find_register_file(kVs20, "oFog")->scalar);
    EXPECT_TRUE(find_register_file(kVs20, "oPts")->scalar);
    EXPECT_FALSE(find_register_file(kVs20, "oPos")->scalar);
    EXPECT_EQ(find_register_file(kVs20, RegisterType::RastOut, 1)->name, "oFog");
    EXPECT_EQ(find_register_file(kVs20, RegisterType::Address, 0)->name, "a0");
    EXPECT_EQ(find_register_file(kVs20, "t"), nullptr);  // no t# in a vertex shader
    EXPECT_EQ(find_register_file(kVs20, "oC"), nullptr);
    // read ports, §4
    EXPECT_EQ(find_register_file(kVs20, "c")->read_ports, 2);
    EXPECT_EQ(find_register_file(kVs20, "v")->read_ports, 1);
    EXPECT_EQ(find_register_file(kVs20, "r")->read_ports, 3);
}

TEST(RegisterTable, Ps20Files) {
    // registers-and-limits.md §2 (the original DirectX 9.0 SDK table)
    EXPECT_EQ(find_register_file(kPs20, "v")->count, 2);
    EXPECT_EQ(find_register_file(kPs20, "c")->count, 32);
    EXPECT_FALSE(find_register_file(kPs20, "c")->relative_addressing);
    EXPECT_EQ(find_register_file(kPs20, "t")->count, 8);
    EXPECT_EQ(find_register_file(kPs20, "s")->count, 16);
    EXPECT_EQ(find_register_file(kPs20, "r")->count, 12);
    EXPECT_EQ(find_register_file(kPs20, "r")->encodable, 32);  // Wine encodes r12..r31 (§11)
    EXPECT_EQ(find_register_file(kPs20, "oC")->count, 4);
    EXPECT_EQ(find_register_file(kPs20, "i")->count, 0);       // not in ps_2_0 ...
    EXPECT_EQ(find_register_file(kPs20, "i")->encodable, 16);  // ... but Wine encodes it
    EXPECT_TRUE(find_register_file(kPs20, "t")->needs_declaration);
    EXPECT_TRUE(find_register_file(kPs20, "s")->needs_declaration);
    EXPECT_EQ(find_register_file(kPs20, RegisterType::Texture, 3)->name, "t");
    EXPECT_EQ(find_register_file(kPs20, "a0"), nullptr);
    EXPECT_EQ(find_register_file(kPs20, "aL"), nullptr);
}

TEST(RegisterTable, Names) {
    EXPECT_EQ(register_name(kVs20, RegisterType::RastOut, 0), "oPos");
    EXPECT_EQ(register_name(kVs20, RegisterType::RastOut, 2), "oPts");
    EXPECT_EQ(register_name(kVs20, RegisterType::TexCrdOut, 7), "oT7");
    EXPECT_EQ(register_name(kVs20, RegisterType::Address, 0), "a0");
    EXPECT_EQ(register_name(kPs20, RegisterType::Texture, 0), "t0");
    EXPECT_EQ(register_name(kPs20, RegisterType::DepthOut, 0), "oDepth");
    EXPECT_EQ(register_name(kPs20, RegisterType::ColorOut, 3), "oC3");
    EXPECT_EQ(register_name(kPs20, RegisterType::Loop, 0), "?15:0");  // no aL in ps_2_0
}

TEST(Profiles, LimitsAndNames) {
    const Profile* vs = find_profile("vs_2_0");
    const Profile* ps = find_profile("ps.2.0");
    ASSERT_NE(vs, nullptr);
    ASSERT_NE(ps, nullptr);
    EXPECT_EQ(vs->version, kVs20);
    EXPECT_EQ(vs->max_instruction_slots, 256);
    EXPECT_EQ(vs->max_static_flow_count, 16);
    EXPECT_EQ(vs->max_labels, 16);
    EXPECT_EQ(ps->max_arithmetic_slots, 64);
    EXPECT_EQ(ps->max_texture_slots, 32);
    EXPECT_EQ(ps->max_dependent_read_order, 3);
    EXPECT_FALSE(ps->flow_control);
    EXPECT_FALSE(ps->arbitrary_swizzle);
    EXPECT_EQ(find_profile("vs_3_0"), nullptr);
    EXPECT_EQ(find_profile(ShaderVersion{ShaderType::Pixel, 2, 1}), nullptr);
    EXPECT_EQ((ShaderVersion{ShaderType::Pixel, 2, 1}).name(), "ps_2_x");
    EXPECT_EQ(kVs20.token(), 0xFFFE0200u);
    EXPECT_EQ(kPs20.token(), 0xFFFF0200u);
}

}  // namespace
}  // namespace sm2::isa
