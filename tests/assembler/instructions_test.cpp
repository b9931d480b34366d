// One statement per instruction of the opcode table, in each 2.0 profile that allows it.
// Expected tokens worked out by hand from bytecode.md: instruction token = opcode |
// control << 16 | length << 24; r0 full-mask destination 0x800F0000; sources r1..r3 with the
// identity swizzle 0x80E40001..0x80E40003; c0 = 0xA0E40000.
#include <set>

#include "helpers.h"
#include "sm2/isa/opcodes.h"

namespace sm2::assembler::test {
namespace {

struct Case {
    const char* profile;
    const char* text;
    Tokens tokens;
};

const std::vector<Case>& cases() {
    static const std::vector<Case> kCases = {
        // ---- vs_2_0 ---------------------------------------------------------------------
        {"vs_2_0", "nop", {0x00000000}},
        {"vs_2_0", "mov r0, r1", {0x02000001, 0x800F0000, 0x80E40001}},
        {"vs_2_0", "add r0, r1, r2", {0x03000002, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "sub r0, r1, r2", {0x03000003, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "mad r0, r1, r2, r3", {0x04000004, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"vs_2_0", "mul r0, r1, r2", {0x03000005, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "rcp r0, r1.x", {0x02000006, 0x800F0000, 0x80000001}},
        {"vs_2_0", "rsq r0, r1.y", {0x02000007, 0x800F0000, 0x80550001}},
        {"vs_2_0", "dp3 r0, r1, r2", {0x03000008, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "dp4 r0, r1, r2", {0x03000009, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "min r0, r1, r2", {0x0300000A, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "max r0, r1, r2", {0x0300000B, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "slt r0, r1, r2", {0x0300000C, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "sge r0, r1, r2", {0x0300000D, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "exp r0, r1.z", {0x0200000E, 0x800F0000, 0x80AA0001}},
        {"vs_2_0", "log r0, r1.w", {0x0200000F, 0x800F0000, 0x80FF0001}},
        {"vs_2_0", "lit r0, r1", {0x02000010, 0x800F0000, 0x80E40001}},
        {"vs_2_0", "dst r0, r1, r2", {0x03000011, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "lrp r0, r1, r2, r3", {0x04000012, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"vs_2_0", "frc r0, r1", {0x02000013, 0x800F0000, 0x80E40001}},
        {"vs_2_0", "m4x4 r0, r1, c0", {0x03000014, 0x800F0000, 0x80E40001, 0xA0E40000}},
        {"vs_2_0", "m4x3 r0.xyz, r1, c0", {0x03000015, 0x80070000, 0x80E40001, 0xA0E40000}},
        {"vs_2_0", "m3x4 r0, r1, c0", {0x03000016, 0x800F0000, 0x80E40001, 0xA0E40000}},
        {"vs_2_0", "m3x3 r0.xyz, r1, c0", {0x03000017, 0x80070000, 0x80E40001, 0xA0E40000}},
        {"vs_2_0", "m3x2 r0.xy, r1, c0", {0x03000018, 0x80030000, 0x80E40001, 0xA0E40000}},
        {"vs_2_0", "call l0", {0x01000019, 0xA0E41000}},
        {"vs_2_0", "callnz l0, b0", {0x0200001A, 0xA0E41000, 0xE0E40800}},
        {"vs_2_0", "loop aL, i0", {0x0200001B, 0xF0E40800, 0xF0E40000}},
        {"vs_2_0", "ret", {0x0000001C}},
        {"vs_2_0", "endloop", {0x0000001D}},
        {"vs_2_0", "label l0", {0x0100001E, 0xA0E41000}},
        {"vs_2_0", "dcl_position v0", {0x0200001F, 0x80000000, 0x900F0000}},
        {"vs_2_0", "pow r0, r1.x, r2.y", {0x03000020, 0x800F0000, 0x80000001, 0x80550002}},
        {"vs_2_0", "crs r0.xyz, r1, r2", {0x03000021, 0x80070000, 0x80E40001, 0x80E40002}},
        {"vs_2_0", "sgn r0, r1, r2, r3", {0x04000022, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"vs_2_0", "abs r0, r1", {0x02000023, 0x800F0000, 0x80E40001}},
        {"vs_2_0", "nrm r0, r1", {0x02000024, 0x800F0000, 0x80E40001}},
        {"vs_2_0", "sincos r0.xy, r1.x, c0, c1", {0x04000025, 0x80030000, 0x80000001, 0xA0E40000, 0xA0E40001}},
        {"vs_2_0", "rep i0", {0x01000026, 0xF0E40000}},
        {"vs_2_0", "endrep", {0x00000027}},
        {"vs_2_0", "if b0", {0x01000028, 0xE0E40800}},
        {"vs_2_0", "else", {0x0000002A}},
        {"vs_2_0", "endif", {0x0000002B}},
        {"vs_2_0", "mova a0.x, r1.x", {0x0200002E, 0xB0010000, 0x80000001}},
        {"vs_2_0", "defb b0, true", {0x0200002F, 0xE00F0800, 0x00000001}},
        {"vs_2_0", "defi i0, 1, 2, 3, 4", {0x05000030, 0xF00F0000, 1, 2, 3, 4}},
        {"vs_2_0", "expp r0, r1.x", {0x0200004E, 0x800F0000, 0x80000001}},
        {"vs_2_0", "logp r0, r1.x", {0x0200004F, 0x800F0000, 0x80000001}},
        // 1.0, 2.0, 3.0, 4.0
        {"vs_2_0", "def c0, 1, 2, 3, 4", {0x05000051, 0xA00F0000, 0x3F800000, 0x40000000, 0x40400000, 0x40800000}},

        // ---- ps_2_0 ---------------------------------------------------------------------
        {"ps_2_0", "nop", {0x00000000}},
        {"ps_2_0", "mov r0, r1", {0x02000001, 0x800F0000, 0x80E40001}},
        {"ps_2_0", "add r0, r1, r2", {0x03000002, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "sub r0, r1, r2", {0x03000003, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "mad r0, r1, r2, r3", {0x04000004, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"ps_2_0", "mul r0, r1, r2", {0x03000005, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "rcp r0, r1.x", {0x02000006, 0x800F0000, 0x80000001}},
        {"ps_2_0", "rsq r0, r1.x", {0x02000007, 0x800F0000, 0x80000001}},
        {"ps_2_0", "dp3 r0, r1, r2", {0x03000008, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "dp4 r0, r1, r2", {0x03000009, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "min r0, r1, r2", {0x0300000A, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "max r0, r1, r2", {0x0300000B, 0x800F0000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "exp r0, r1.x", {0x0200000E, 0x800F0000, 0x80000001}},
        {"ps_2_0", "log r0, r1.x", {0x0200000F, 0x800F0000, 0x80000001}},
        {"ps_2_0", "lrp r0, r1, r2, r3", {0x04000012, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"ps_2_0", "frc r0, r1", {0x02000013, 0x800F0000, 0x80E40001}},
        {"ps_2_0", "m4x4 r0, r1, c0", {0x03000014, 0x800F0000, 0x80E40001, 0xA0E40000}},
        {"ps_2_0", "m4x3 r0.xyz, r1, c0", {0x03000015, 0x80070000, 0x80E40001, 0xA0E40000}},
        {"ps_2_0", "m3x4 r0, r1, c0", {0x03000016, 0x800F0000, 0x80E40001, 0xA0E40000}},
        {"ps_2_0", "m3x3 r0.xyz, r1, c0", {0x03000017, 0x80070000, 0x80E40001, 0xA0E40000}},
        {"ps_2_0", "m3x2 r0.xy, r1, c0", {0x03000018, 0x80030000, 0x80E40001, 0xA0E40000}},
        {"ps_2_0", "dcl t0", {0x0200001F, 0x80000000, 0xB00F0000}},
        {"ps_2_0", "pow r0, r1.x, r2.x", {0x03000020, 0x800F0000, 0x80000001, 0x80000002}},
        {"ps_2_0", "crs r0.xyz, r1, r2", {0x03000021, 0x80070000, 0x80E40001, 0x80E40002}},
        {"ps_2_0", "abs r0, r1", {0x02000023, 0x800F0000, 0x80E40001}},
        {"ps_2_0", "nrm r0, r1", {0x02000024, 0x800F0000, 0x80E40001}},
        // Microsoft's three-source form and Wine's one-source form (spec README item 2).
        {"ps_2_0", "sincos r0.xy, r1.x, c0, c1", {0x04000025, 0x80030000, 0x80000001, 0xA0E40000, 0xA0E40001}},
        {"ps_2_0", "sincos r0.xy, r1.x", {0x02000025, 0x80030000, 0x80000001}},
        {"ps_2_0", "texkill r0", {0x01000041, 0x800F0000}},
        {"ps_2_0", "texkill t0.xyz", {0x01000041, 0xB0070000}},
        {"ps_2_0", "texld r0, t0, s0", {0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
        {"ps_2_0", "texldp r0, t0, s0", {0x03010042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
        {"ps_2_0", "texldb r0, t0, s0", {0x03020042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
        {"ps_2_0", "def c0, 1, 2, 3, 4", {0x05000051, 0xA00F0000, 0x3F800000, 0x40000000, 0x40400000, 0x40800000}},
        {"ps_2_0", "cmp r0, r1, r2, r3", {0x04000058, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
        {"ps_2_0", "dp2add r0, r1, r2, r3.x", {0x0400005A, 0x800F0000, 0x80E40001, 0x80E40002, 0x80000003}},
        // Encoded by Wine in ps_2_0 although the documents forbid them (README item 3).
        {"ps_2_0", "expp r0, r1.x", {0x0200004E, 0x800F0000, 0x80000001}},
        {"ps_2_0", "logp r0, r1.x", {0x0200004F, 0x800F0000, 0x80000001}},
        {"ps_2_0", "defi i0, 1, 2, 3, 4", {0x05000030, 0xF00F0000, 1, 2, 3, 4}},
        {"ps_2_0", "defb b0, false", {0x0200002F, 0xE00F0800, 0x00000000}},
    };
    return kCases;
}

TEST(Instructions, EncodeByHand) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(std::string(c.profile) + ": " + c.text);
        EXPECT_EQ(hex(statement_tokens(c.profile, c.text)), hex(c.tokens));
    }
}

TEST(Instructions, EveryTableRowAllowedIn20IsCovered) {
    std::set<std::string> vs, ps;
    for (const Case& c : cases()) {
        std::string text = c.text;
        std::string mnemonic = text.substr(0, text.find_first_of(" _"));
        (std::string(c.profile) == "vs_2_0" ? vs : ps).insert(mnemonic);
    }
    const isa::ShaderVersion vs20{isa::ShaderType::Vertex, 2, 0};
    const isa::ShaderVersion ps20{isa::ShaderType::Pixel, 2, 0};
    for (const isa::OpcodeInfo& row : isa::opcode_table()) {
        const std::string m(row.mnemonic);
        if (row.allowed_in(vs20)) {
            EXPECT_TRUE(vs.count(m)) << "vs_2_0 case missing for " << m;
        }
        if (row.allowed_in(ps20)) {
            EXPECT_TRUE(ps.count(m)) << "ps_2_0 case missing for " << m;
        }
    }
}

TEST(Instructions, MnemonicsInAnyCase) {
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "MOV R0, R1")), "02000001 800F0000 80E40001");
    EXPECT_EQ(hex(statement_tokens("ps_2_0", "TexLdP_PP r0, T0, S0")),
              "03010042 802F0000 B0E40000 A0E40800");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "Mov oPOS, V0.XYZW")), "02000001 C00F0000 90E40000");
}

TEST(Instructions, FlowControlForms) {
    // bytecode.md §10
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "if !b0")), "01000028 EDE40800");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "callnz l0, !b0")), "0200001A A0E41000 EDE40800");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "call l15")), "01000019 A0E4100F");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "rep i15")), "01000026 F0E4000F");
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "if b15")), "01000028 E0E4080F");
}

// Instructions Wine rejects in a profile are rejected with the profile named.
TEST(Instructions, NotAvailableInProfile) {
    struct Bad {
        const char* profile;
        const char* text;
    };
    const Bad bad[] = {
        {"ps_2_0", "slt r0, r1, r2"}, {"ps_2_0", "sge r0, r1, r2"}, {"ps_2_0", "lit r0, r1"},
        {"ps_2_0", "dst r0, r1, r2"}, {"ps_2_0", "sgn r0, r1, r2, r3"}, {"ps_2_0", "mova r0, r1"},
        {"ps_2_0", "if b0"}, {"ps_2_0", "rep i0"}, {"ps_2_0", "ret"}, {"ps_2_0", "call l0"},
        {"ps_2_0", "endif"}, {"vs_2_0", "cmp r0, r1, r2, r3"}, {"vs_2_0", "dp2add r0, r1, r2, r3.x"},
        {"vs_2_0", "texld r0, r1, r2"}, {"vs_2_0", "texkill r0"}, {"vs_2_0", "break"},
        {"vs_2_0", "dsx r0, r1"}, {"ps_2_0", "texldl r0, t0, s0"},
    };
    for (const Bad& b : bad) {
        const std::string text = std::string(b.profile) + "\n" + b.text + "\n";
        const AssembleResult r = assemble_unvalidated(text);
        ASSERT_FALSE(r.ok()) << text;
        ASSERT_EQ(r.diagnostics.size(), 1u) << text << diagnostics_text(r);
        EXPECT_EQ(r.diagnostics[0].line, 2u);
        EXPECT_EQ(r.diagnostics[0].column, 1u);
        EXPECT_NE(r.diagnostics[0].message.find(std::string("not available in ") + b.profile),
                  std::string::npos)
            << r.diagnostics[0].message;
    }
}

}  // namespace
}  // namespace sm2::assembler::test
