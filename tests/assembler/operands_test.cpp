// Register kinds, write masks, swizzles, modifiers and relative addressing. Expected tokens are
// derived by hand from bytecode.md §4 (type split: bits 0..2 -> 28..30, bits 3..4 -> 11..12),
// §5 (destination: mask bits 16..19, modifiers 20..23) and §6 (source: swizzle 16..23,
// modifier 24..27, relative bit 13).
#include "helpers.h"

namespace sm2::assembler::test {
namespace {

// Token i (0-based, after the instruction token) of a one-statement program.
uint32_t operand(std::string_view profile, std::string_view statement, size_t i) {
    const Tokens t = statement_tokens(profile, statement);
    EXPECT_GT(t.size(), i + 1) << statement;
    return t.size() > i + 1 ? t[i + 1] : 0;
}

TEST(Registers, VertexDestinations) {
    EXPECT_EQ(operand("vs_2_0", "mov r0, r1", 0), 0x800F0000u);
    EXPECT_EQ(operand("vs_2_0", "mov r11, r1", 0), 0x800F000Bu);
    EXPECT_EQ(operand("vs_2_0", "mov oPos, r1", 0), 0xC00F0000u);   // RASTOUT #0
    EXPECT_EQ(operand("vs_2_0", "mov oFog, r1.w", 0), 0xC00F0001u);  // RASTOUT #1, mask forced
    EXPECT_EQ(operand("vs_2_0", "mov oFog.x, r1.w", 0), 0xC00F0001u);
    EXPECT_EQ(operand("vs_2_0", "mov oPts, r1.x", 0), 0xC00F0002u);  // RASTOUT #2
    EXPECT_EQ(operand("vs_2_0", "mov oPts.y, r1.x", 0), 0xC00F0002u);
    EXPECT_EQ(operand("vs_2_0", "mov oD0, r1", 0), 0xD00F0000u);     // ATTROUT
    EXPECT_EQ(operand("vs_2_0", "mov oD1, r1", 0), 0xD00F0001u);
    EXPECT_EQ(operand("vs_2_0", "mov oT0, r1", 0), 0xE00F0000u);     // TEXCRDOUT
    EXPECT_EQ(operand("vs_2_0", "mov oT7.xy, r1", 0), 0xE0030007u);
    EXPECT_EQ(operand("vs_2_0", "mova a0.x, r1.x", 0), 0xB0010000u);  // ADDR
    EXPECT_EQ(operand("vs_2_0", "mova a0, r1", 0), 0xB00F0000u);
    EXPECT_EQ(operand("vs_2_0", "mov a0.x, r1.x", 0), 0xB0010000u);  // Wine encodes mov a0
}

TEST(Registers, PixelDestinations) {
    EXPECT_EQ(operand("ps_2_0", "mov r0, r1", 0), 0x800F0000u);
    EXPECT_EQ(operand("ps_2_0", "mov r31, r1", 0), 0x800F001Fu);  // Wine encodes r12..r31
    EXPECT_EQ(operand("ps_2_0", "mov oC0, r1", 0), 0x800F0800u);  // COLOROUT = 8
    EXPECT_EQ(operand("ps_2_0", "mov oC1, r1", 0), 0x800F0801u);
    EXPECT_EQ(operand("ps_2_0", "mov oC3, r1", 0), 0x800F0803u);
    EXPECT_EQ(operand("ps_2_0", "mov oDepth, r1.x", 0), 0x900F0800u);  // DEPTHOUT = 9
    EXPECT_EQ(operand("ps_2_0", "mov oDepth.x, r1", 0), 0x90010800u);
}

TEST(Registers, VertexSources) {
    EXPECT_EQ(operand("vs_2_0", "mov r0, r11", 1), 0x80E4000Bu);
    EXPECT_EQ(operand("vs_2_0", "mov r0, v0", 1), 0x90E40000u);
    EXPECT_EQ(operand("vs_2_0", "mov r0, v15", 1), 0x90E4000Fu);
    EXPECT_EQ(operand("vs_2_0", "mov r0, c0", 1), 0xA0E40000u);
    EXPECT_EQ(operand("vs_2_0", "mov r0, c255", 1), 0xA0E400FFu);
    EXPECT_EQ(operand("vs_2_0", "mov r0, c2047", 1), 0xA0E407FFu);
    EXPECT_EQ(operand("vs_2_0", "rep i0", 0), 0xF0E40000u);        // CONSTINT = 7
    EXPECT_EQ(operand("vs_2_0", "rep i15", 0), 0xF0E4000Fu);
    EXPECT_EQ(operand("vs_2_0", "if b0", 0), 0xE0E40800u);         // CONSTBOOL = 14
    EXPECT_EQ(operand("vs_2_0", "if b15", 0), 0xE0E4080Fu);
    EXPECT_EQ(operand("vs_2_0", "loop aL, i3", 0), 0xF0E40800u);   // LOOP = 15
    EXPECT_EQ(operand("vs_2_0", "loop aL, i3", 1), 0xF0E40003u);
    EXPECT_EQ(operand("vs_2_0", "call l3", 0), 0xA0E41003u);       // LABEL = 18
    EXPECT_EQ(operand("vs_2_0", "call l2047", 0), 0xA0E417FFu);    // Wine encodes l16..l2047
}

TEST(Registers, PixelSources) {
    EXPECT_EQ(operand("ps_2_0", "mov r0, v0", 1), 0x90E40000u);
    EXPECT_EQ(operand("ps_2_0", "mov r0, v1", 1), 0x90E40001u);
    EXPECT_EQ(operand("ps_2_0", "mov r0, t0", 1), 0xB0E40000u);    // TEXTURE = 3
    EXPECT_EQ(operand("ps_2_0", "mov r0, t7", 1), 0xB0E40007u);
    EXPECT_EQ(operand("ps_2_0", "mov r0, c31", 1), 0xA0E4001Fu);
    EXPECT_EQ(operand("ps_2_0", "mov r0, r31", 1), 0x80E4001Fu);
    EXPECT_EQ(operand("ps_2_0", "texld r0, t1, s2", 2), 0xA0E40802u);  // SAMPLER = 10
    EXPECT_EQ(operand("ps_2_0", "texld r0, r1, s15", 2), 0xA0E4080Fu);
    EXPECT_EQ(operand("ps_2_0", "mov r0, i0", 1), 0xF0E40000u);    // Wine accepts i#/b# in ps
    EXPECT_EQ(operand("ps_2_0", "mov r0, b1", 1), 0xE0E40801u);
}

TEST(Masks, EveryMask) {
    const std::pair<const char*, uint32_t> masks[] = {
        {".x", 0x1}, {".y", 0x2}, {".xy", 0x3}, {".z", 0x4}, {".xz", 0x5}, {".yz", 0x6},
        {".xyz", 0x7}, {".w", 0x8}, {".xw", 0x9}, {".yw", 0xA}, {".xyw", 0xB}, {".zw", 0xC},
        {".xzw", 0xD}, {".yzw", 0xE}, {".xyzw", 0xF}, {"", 0xF}, {".r", 0x1}, {".rg", 0x3},
        {".rgba", 0xF}, {".ba", 0xC}, {".xg", 0x3}, {".RB", 0x5},
    };
    for (const auto& [text, mask] : masks)
        EXPECT_EQ(operand("vs_2_0", std::string("mov r5") + text + ", r1", 0), 0x80000005u | mask << 16)
            << text;
    EXPECT_EQ(operand("vs_2_0", "mov r5.xz, r1", 0), 0x80050005u);  // bytecode.md §5 example
}

TEST(Swizzles, FullAndShortForms) {
    const std::pair<const char*, uint32_t> swizzles[] = {
        {"", 0xE4},     {".xyzw", 0xE4}, {".rgba", 0xE4}, {".x", 0x00},    {".xxxx", 0x00},
        {".y", 0x55},   {".z", 0xAA},    {".w", 0xFF},    {".a", 0xFF},    {".yzxw", 0xC9},
        {".zxyw", 0xD2}, {".wzyx", 0x1B}, {".xy", 0x54},  {".xyyy", 0x54}, {".xyww", 0xF4},
        {".xyw", 0xF4}, {".wzx", 0x0B},  {".xyz", 0xA4},  {".xg", 0x54},   {".bgr", 0x06},
        {".WZYX", 0x1B},
    };
    // .bgr = z y x x: 2 | 1<<2 | 0<<4 | 0<<6 = 0x06; .wzx = w z x x = 3 | 2<<2 = 0x0B;
    // .xyz = x y z z = 0 | 1<<2 | 2<<4 | 2<<6 = 0xA4.
    for (const auto& [text, swizzle] : swizzles)
        EXPECT_EQ(operand("vs_2_0", std::string("mov r0, r1") + text, 1), 0x80000001u | swizzle << 16)
            << text;
}

TEST(Modifiers, ResultModifiers) {
    EXPECT_EQ(operand("ps_2_0", "mov_sat r2, r1", 0), 0x801F0002u);
    EXPECT_EQ(operand("ps_2_0", "mov_pp r1, r1", 0), 0x802F0001u);
    EXPECT_EQ(operand("ps_2_0", "mov_sat_pp r0, r1", 0), 0x803F0000u);
    EXPECT_EQ(operand("ps_2_0", "mov_pp_sat r0, r1", 0), 0x803F0000u);
    EXPECT_EQ(operand("ps_2_0", "mov_centroid r0, r1", 0), 0x804F0000u);
    EXPECT_EQ(operand("ps_2_0", "mad_sat_pp r0.xy, r1, r2, r3", 0), 0x80330000u);
    EXPECT_EQ(operand("ps_2_0", "texld_pp r0, t0, s0", 0), 0x802F0000u);
    EXPECT_EQ(operand("vs_2_0", "mov_sat r0, r1", 0), 0x801F0000u);  // Wine encodes _sat in vs
    EXPECT_EQ(operand("vs_2_0", "frc_sat r0, r1", 0), 0x801F0000u);
}

TEST(Modifiers, SourceModifiers) {
    EXPECT_EQ(operand("vs_2_0", "mov r0, -r1", 1), 0x81E40001u);
    EXPECT_EQ(operand("vs_2_0", "mov r0, -c1", 1), 0xA1E40001u);
    EXPECT_EQ(operand("vs_2_0", "mov r0, -v2.x", 1), 0x91000002u);
    EXPECT_EQ(operand("ps_2_0", "mov r0, -t1.wzyx", 1), 0xB11B0001u);
    EXPECT_EQ(operand("vs_2_0", "if !b0", 0), 0xEDE40800u);
    EXPECT_EQ(operand("vs_2_0", "callnz l2, !b3", 1), 0xEDE40803u);
}

TEST(Relative, EveryForm) {
    // bytecode.md §6.1
    const std::pair<const char*, const char*> forms[] = {
        {"c[a0.x]", "A0E42000 B0000000"},
        {"c0[a0.y]", "A0E42000 B0550000"},
        {"c[a0.x + 5]", "A0E42005 B0000000"},
        {"c5[a0.x]", "A0E42005 B0000000"},
        {"c[5 + a0.x]", "A0E42005 B0000000"},
        {"c[a0.x+5]", "A0E42005 B0000000"},
        {"c10[a0.w]", "A0E4200A B0FF0000"},
        {"-c0[a0.w+5].x", "A1002005 B0FF0000"},
        {"c10[aL]", "A0E4200A F0E40800"},
        {"c[aL + 10]", "A0E4200A F0E40800"},
        {"c[10 + aL]", "A0E4200A F0E40800"},
        {"c[a0]", "A0E42000 B0E40000"},
        {"c[a0.z]", "A0E42000 B0AA0000"},
        {"c2[a0.x + 3]", "A0E42005 B0000000"},
        {"c[2 + a0.z + 3]", "A0E42005 B0AA0000"},
        {"c[a0.x + 5].yzxw", "A0C92005 B0000000"},
        {"c[ a0.x + 255 ]", "A0E420FF B0000000"},
        // Constant indexing without an address register is a plain register number.
        {"c[3]", "A0E40003"},
        {"c2[3]", "A0E40005"},
    };
    for (const auto& [text, tokens] : forms) {
        const Tokens t = statement_tokens("vs_2_0", std::string("mov r0, ") + text);
        ASSERT_GE(t.size(), 3u) << text;
        EXPECT_EQ(hex(Tokens(t.begin() + 2, t.end())), tokens) << text;
        // Instruction length counts the relative token.
        const bool relative = std::string_view(tokens).size() > 8;
        EXPECT_EQ(t[0], relative ? 0x03000001u : 0x02000001u) << text;
    }
    // A relative source in the middle keeps the operand order.
    EXPECT_EQ(hex(statement_tokens("vs_2_0", "mad r0, c[a0.x + 1], r1, c[aL + 2]")),
              "06000004 800F0000 A0E42001 B0000000 80E40001 A0E42002 F0E40800");
}

}  // namespace
}  // namespace sm2::assembler::test
