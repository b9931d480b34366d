// Token codec and stream decode/encode. Expected tokens are worked out by hand from the bit
// layouts of bytecode.md (§3 instruction, §4 register type split, §5 destination, §6 source,
// §6.1 relative, §7 dcl, §8 def) and its worked examples.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "sm2/isa/bytecode.h"
#include "sm2/isa/opcodes.h"
#include "sm2/isa/tokens.h"
#include "worked_examples.h"

namespace sm2::isa {
namespace {

using tokens::encode_destination;
using tokens::encode_source;

DestinationParameter dst(RegisterType t, uint16_t i, uint8_t mask = 0xF) {
    DestinationParameter d;
    d.type = t;
    d.index = i;
    d.write_mask = mask;
    return d;
}

SourceParameter src(RegisterType t, uint16_t i, uint8_t swz = kSwizzleIdentity,
                    SourceModifier m = SourceModifier::None) {
    SourceParameter s;
    s.type = t;
    s.index = i;
    s.swizzle = swz;
    s.modifier = m;
    return s;
}

TEST(TokenCodec, InstructionToken) {
    // opcode in bits 0..15, control 16..23, length 24..27
    EXPECT_EQ(tokens::encode_instruction(1, 0, 2), 0x02000001u);        // mov d, s
    EXPECT_EQ(tokens::encode_instruction(66, 1, 3), 0x03010042u);       // texldp
    EXPECT_EQ(tokens::encode_instruction(28, 0, 0), 0x0000001Cu);       // ret
    EXPECT_EQ(tokens::encode_instruction(2, 0, 4, true), 0x14000002u);  // predicated add
    const auto f = tokens::decode_instruction(0x03020042u);
    EXPECT_EQ(f.opcode, 66);
    EXPECT_EQ(f.control, 2);
    EXPECT_EQ(f.length, 3);
    EXPECT_FALSE(f.predicated);
}

TEST(TokenCodec, RegisterTypeSplit) {
    // type bits 0..2 -> token bits 28..30, bits 3..4 -> token bits 11..12
    EXPECT_EQ(tokens::encode_register_type(RegisterType::Temp), 0x00000000u);
    EXPECT_EQ(tokens::encode_register_type(RegisterType::ConstInt), 0x70000000u);  // 7
    EXPECT_EQ(tokens::encode_register_type(RegisterType::ColorOut), 0x00000800u);  // 8 = 0b01000
    EXPECT_EQ(tokens::encode_register_type(RegisterType::Loop), 0x70000800u);      // 15 = 0b01111
    EXPECT_EQ(tokens::encode_register_type(RegisterType::Label), 0x20001000u);     // 18 = 0b10010
    EXPECT_EQ(tokens::encode_register_type(RegisterType::Predicate), 0x30001000u); // 19 = 0b10011
    for (uint8_t t = 0; t <= kMaxRegisterType; ++t)
        EXPECT_EQ(tokens::decode_register_type(
                      0x80000000u | tokens::encode_register_type(static_cast<RegisterType>(t))),
                  t);
}

TEST(TokenCodec, DestinationTokens) {
    // bytecode.md §5 examples
    EXPECT_EQ(encode_destination(dst(RegisterType::Temp, 0)), 0x800F0000u);
    EXPECT_EQ(encode_destination(dst(RegisterType::Temp, 5, 0b0101)), 0x80050005u);  // r5.xz
    EXPECT_EQ(encode_destination(dst(RegisterType::RastOut, 0)), 0xC00F0000u);        // oPos
    EXPECT_EQ(encode_destination(dst(RegisterType::AttrOut, 1)), 0xD00F0001u);        // oD1
    EXPECT_EQ(encode_destination(dst(RegisterType::TexCrdOut, 7, 0b0011)), 0xE0030007u);
    EXPECT_EQ(encode_destination(dst(RegisterType::Address, 0, 0b0001)), 0xB0010000u);  // a0.x
    EXPECT_EQ(encode_destination(dst(RegisterType::ColorOut, 1)), 0x800F0801u);         // oC1
    EXPECT_EQ(encode_destination(dst(RegisterType::DepthOut, 0)), 0x900F0800u);         // oDepth
    auto pp = dst(RegisterType::Temp, 1);
    pp.partial_precision = true;
    EXPECT_EQ(encode_destination(pp), 0x802F0001u);
    auto sat = dst(RegisterType::Temp, 2);
    sat.saturate = true;
    EXPECT_EQ(encode_destination(sat), 0x801F0002u);
    auto centroid = dst(RegisterType::Texture, 1, 0b0011);
    centroid.centroid = true;
    EXPECT_EQ(encode_destination(centroid), 0xB0430001u);  // dcl_centroid t1.xy's register

    std::string error;
    auto d = tokens::decode_destination(0x802F0001u, &error);
    ASSERT_TRUE(d);
    EXPECT_EQ(*d, pp);
}

TEST(TokenCodec, SourceTokens) {
    // bytecode.md §6 examples
    EXPECT_EQ(encode_source(src(RegisterType::Input, 0)), 0x90E40000u);
    EXPECT_EQ(encode_source(src(RegisterType::Const, 1, 0xE4, SourceModifier::Negate)), 0xA1E40001u);
    EXPECT_EQ(encode_source(src(RegisterType::Const, 0, 0x00)), 0xA0000000u);  // c0.x
    EXPECT_EQ(encode_source(src(RegisterType::Texture, 1)), 0xB0E40001u);
    EXPECT_EQ(encode_source(src(RegisterType::Sampler, 2)), 0xA0E40802u);
    EXPECT_EQ(encode_source(src(RegisterType::ConstInt, 0)), 0xF0E40000u);
    EXPECT_EQ(encode_source(src(RegisterType::ConstBool, 0)), 0xE0E40800u);
    EXPECT_EQ(encode_source(src(RegisterType::ConstBool, 0, 0xE4, SourceModifier::Not)), 0xEDE40800u);
    EXPECT_EQ(encode_source(src(RegisterType::Loop, 0)), 0xF0E40800u);
    EXPECT_EQ(encode_source(src(RegisterType::Label, 3)), 0xA0E41003u);
    // swizzle byte: .yzxw = 1 | 2<<2 | 0<<4 | 3<<6 = 0xC9; .wzyx = 3 | 2<<2 | 1<<4 | 0 = 0x1B
    EXPECT_EQ(encode_source(src(RegisterType::Temp, 0, 0xC9)), 0x80C90000u);
    EXPECT_EQ(encode_source(src(RegisterType::Temp, 0, 0x1B)), 0x801B0000u);
}

TEST(TokenCodec, RelativeAddressTokens) {
    // bytecode.md §6.1: c[a0.x + 5] = A0E42005 B0000000; c10[aL] = A0E4200A F0E40800
    auto c5 = src(RegisterType::Const, 5);
    c5.relative = RelativeAddress{RegisterType::Address, 0x00};
    EXPECT_EQ(encode_source(c5), 0xA0E42005u);
    EXPECT_EQ(tokens::encode_relative(*c5.relative), 0xB0000000u);
    EXPECT_EQ(tokens::encode_relative({RegisterType::Address, 0x55}), 0xB0550000u);  // a0.y
    EXPECT_EQ(tokens::encode_relative({RegisterType::Address, 0xFF}), 0xB0FF0000u);  // a0.w
    EXPECT_EQ(tokens::encode_relative({RegisterType::Loop, 0xE4}), 0xF0E40800u);     // aL
    std::string error;
    EXPECT_FALSE(tokens::decode_relative(0xA0000000u, &error));  // c# cannot be an index
    EXPECT_NE(error.find("a0 or aL"), std::string::npos);
    EXPECT_FALSE(tokens::decode_relative(0xB0000001u, &error));  // register number must be 0
}

TEST(TokenCodec, DeclarationTokens) {
    // bytecode.md §7: usage bits 0..4, index bits 16..19, texture type bits 27..30
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Position, 0, TextureType::Unknown}), 0x80000000u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::TexCoord, 3, TextureType::Unknown}), 0x80030005u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Normal, 12, TextureType::Unknown}), 0x800C0003u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Color, 1, TextureType::Unknown}), 0x8001000Au);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Position, 0, TextureType::Texture2D}), 0x90000000u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Position, 0, TextureType::Cube}), 0x98000000u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Position, 0, TextureType::Volume}), 0xA0000000u);
    EXPECT_EQ(tokens::encode_declaration({DeclUsage::Position, 0, TextureType::Texture1D}), 0x88000000u);
    std::string error;
    EXPECT_FALSE(tokens::decode_declaration(0x8000000Eu, &error));  // usage 14 does not exist
    EXPECT_FALSE(tokens::decode_declaration(0x80000100u, &error));  // reserved bit 8
}

// --- worked examples of bytecode.md §13 (worked_examples.h) -----------------------------

using examples::kExampleA;
using examples::kExampleB;
using examples::kExampleC;

TEST(StreamCodec, ExampleADecodesToItsSource) {
    auto r = decode(kExampleA);
    ASSERT_TRUE(r.ok()) << r.error->to_string();
    const Program& p = *r.program;
    EXPECT_EQ(p.version, (ShaderVersion{ShaderType::Pixel, 2, 0}));
    ASSERT_EQ(p.instructions.size(), 12u);
    // dcl t0.xy
    EXPECT_EQ(p.instructions[0].opcode, Opcode::Dcl);
    EXPECT_EQ(p.instructions[0].dest->type, RegisterType::Texture);
    EXPECT_EQ(p.instructions[0].dest->write_mask, 0b0011);
    // dcl_cube s1
    EXPECT_EQ(p.instructions[4].declaration.texture_type, TextureType::Cube);
    EXPECT_EQ(p.instructions[4].dest->index, 1);
    // def c0, 0.5, 1, 0, 0.25
    float values[4];
    std::memcpy(values, p.instructions[5].constant_bits.data(), sizeof values);
    EXPECT_EQ(values[0], 0.5f);
    EXPECT_EQ(values[1], 1.0f);
    EXPECT_EQ(values[2], 0.0f);
    EXPECT_EQ(values[3], 0.25f);
    // texldp_pp r1, t1, s1
    const Instruction& texldp = p.instructions[7];
    EXPECT_EQ(texldp.opcode, Opcode::Tex);
    EXPECT_EQ(texldp.control, kTexLdProject);
    EXPECT_EQ(texldp.info()->mnemonic, "texldp");
    EXPECT_TRUE(texldp.dest->partial_precision);
    ASSERT_EQ(texldp.sources.size(), 2u);
    EXPECT_EQ(texldp.sources[1].type, RegisterType::Sampler);
    // lrp_sat r2, c0.x, r0, r1
    const Instruction& lrp = p.instructions[9];
    EXPECT_EQ(lrp.opcode, Opcode::Lrp);
    EXPECT_TRUE(lrp.dest->saturate);
    EXPECT_EQ(lrp.sources[0].swizzle, 0x00);
    // mov oC0, r2
    EXPECT_EQ(p.instructions[11].dest->type, RegisterType::ColorOut);
    EXPECT_EQ(encode(p), kExampleA);
}

TEST(StreamCodec, ExampleBRelativeAndSincos) {
    auto r = decode(kExampleB);
    ASSERT_TRUE(r.ok()) << r.error->to_string();
    const Program& p = *r.program;
    ASSERT_EQ(p.instructions.size(), 14u);
    // mul oD0, r0.x, c[a0.x + 5]
    const Instruction& mul = p.instructions[10];
    EXPECT_EQ(mul.opcode, Opcode::Mul);
    ASSERT_EQ(mul.sources.size(), 2u);
    ASSERT_TRUE(mul.sources[1].relative);
    EXPECT_EQ(mul.sources[1].index, 5);
    EXPECT_EQ(mul.sources[1].relative->type, RegisterType::Address);
    EXPECT_EQ(mul.sources[1].relative->swizzle, 0x00);
    // sincos r1.xy, v2.x, c9, c10: three sources
    EXPECT_EQ(p.instructions[11].sources.size(), 3u);
    // mov oFog, c8.x keeps mask 0xF
    EXPECT_EQ(p.instructions[13].dest->write_mask, 0xF);
    EXPECT_EQ(p.instructions[13].dest->index, kRastOutFog);
    EXPECT_EQ(encode(p), kExampleB);
}

TEST(StreamCodec, ExampleCFlowControl) {
    auto r = decode(kExampleC);
    ASSERT_TRUE(r.ok()) << r.error->to_string();
    const Program& p = *r.program;
    ASSERT_EQ(p.instructions.size(), 15u);
    EXPECT_EQ(p.instructions[1].opcode, Opcode::DefB);
    EXPECT_EQ(p.instructions[1].constant_bits[0], 1u);
    EXPECT_EQ(p.instructions[2].opcode, Opcode::DefI);
    EXPECT_EQ(p.instructions[2].constant_bits[0], 4u);
    const Instruction& loop = p.instructions[4];
    EXPECT_EQ(loop.opcode, Opcode::Loop);
    EXPECT_EQ(loop.sources[0].type, RegisterType::Loop);
    EXPECT_EQ(loop.sources[1].type, RegisterType::ConstInt);
    EXPECT_EQ(p.instructions[5].sources[1].relative->type, RegisterType::Loop);
    EXPECT_EQ(p.instructions[12].opcode, Opcode::Label);
    EXPECT_EQ(encode(p), kExampleC);
    // token offsets point at each instruction token
    EXPECT_EQ(p.instructions[0].token_offset, 1u);
    // endloop: version 1 + dcl 3 + defb 3 + defi 6 + mov 3 + loop 3 + add 5 = token 24
    EXPECT_EQ(p.instructions[6].token_offset, 24u);
}

TEST(StreamCodec, CommentsAreKeptForRoundTrip) {
    // A compiler-style CTAB comment right after the version token.
    const std::vector<uint32_t> stream = {0xFFFF0200, 0x0002FFFE, 0x42415443, 0x12345678,
                                          0x02000001, 0x800F0800, 0xA0E40000, 0x0000FFFF};
    auto r = decode(stream);
    ASSERT_TRUE(r.ok()) << r.error->to_string();
    ASSERT_EQ(r.program->instructions.size(), 2u);
    EXPECT_EQ(r.program->instructions[0].opcode, Opcode::Comment);
    EXPECT_EQ(r.program->instructions[0].comment, (std::vector<uint32_t>{0x42415443, 0x12345678}));
    EXPECT_EQ(encode(*r.program), stream);
}

TEST(StreamCodec, BytesAreLittleEndian) {
    const std::vector<uint32_t> stream = {0xFFFE0200, 0x0000FFFF};
    auto bytes = to_bytes(stream);
    ASSERT_EQ(bytes.size(), 8u);
    EXPECT_EQ(static_cast<unsigned>(bytes[0]), 0x00u);
    EXPECT_EQ(static_cast<unsigned>(bytes[1]), 0x02u);
    EXPECT_EQ(static_cast<unsigned>(bytes[2]), 0xFEu);
    EXPECT_EQ(static_cast<unsigned>(bytes[3]), 0xFFu);
    EXPECT_TRUE(looks_like_bytecode(bytes));
    auto r = decode_bytes(bytes);
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r.program->instructions.empty());
}

// --- malformed streams: every error names the offending token --------------------------------

struct Malformed {
    const char* name;
    std::vector<uint32_t> tokens;
    size_t bad_token;
    const char* message_part;
};

class MalformedStream : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedStream, IsRejectedAtTheRightToken) {
    const Malformed& m = GetParam();
    auto r = decode(m.tokens);
    ASSERT_FALSE(r.ok()) << m.name;
    EXPECT_EQ(r.error->token_index, m.bad_token) << r.error->message;
    EXPECT_NE(r.error->message.find(m.message_part), std::string::npos) << r.error->message;
}

INSTANTIATE_TEST_SUITE_P(
    Decoder, MalformedStream,
    ::testing::Values(
        Malformed{"empty", {}, 0, "no version"},
        Malformed{"not a version", {0x12345678, 0xFFFF}, 0, "not a shader version"},
        Malformed{"unsupported version", {0xFFFE0101, 0xFFFF}, 0, "unsupported shader version vs_1_1"},
        Malformed{"no end", {0xFFFE0200}, 1, "without the END"},
        Malformed{"no end after instruction", {0xFFFE0200, 0x00000000}, 2, "without the END"},
        Malformed{"trailing data", {0xFFFE0200, 0xFFFF, 0x0}, 2, "after the END"},
        Malformed{"unknown opcode", {0xFFFE0200, 0x00000039, 0xFFFF}, 1, "unknown or non-SM2 opcode 57"},
        Malformed{"ps_1_x opcode", {0xFFFF0200, 0x01000040, 0x800F0000, 0xFFFF}, 1, "opcode 64"},
        Malformed{"parameter where instruction", {0xFFFE0200, 0x800F0000, 0xFFFF}, 1, "parameter token"},
        Malformed{"coissue", {0xFFFF0200, 0x42000001, 0x800F0000, 0x80E40000, 0xFFFF}, 1, "co-issue"},
        Malformed{"reserved bit 29", {0xFFFF0200, 0x22000001, 0x800F0000, 0x80E40000, 0xFFFF}, 1, "bit 29"},
        Malformed{"length past end", {0xFFFE0200, 0x05000001, 0x800F0000, 0xFFFF}, 1, "runs past the end"},
        Malformed{"dest bit 31 clear", {0xFFFE0200, 0x02000001, 0x000F0000, 0x80E40000, 0xFFFF}, 2, "bit 31"},
        Malformed{"src reserved bits", {0xFFFE0200, 0x02000001, 0x800F0000, 0x80E44000, 0xFFFF}, 3, "reserved bits"},
        Malformed{"too many sources", {0xFFFE0200, 0x03000001, 0x800F0000, 0x80E40000, 0x80E40000, 0xFFFF}, 1, "more than 1"},
        Malformed{"too few sources", {0xFFFE0200, 0x02000002, 0x800F0000, 0x80E40000, 0xFFFF}, 1, "needs 2"},
        Malformed{"relative missing", {0xFFFE0200, 0x02000001, 0x800F0000, 0xA0E42000, 0xFFFF}, 3, "missing its address"},
        Malformed{"relative bad type", {0xFFFE0200, 0x03000001, 0x800F0000, 0xA0E42000, 0xA0000000, 0xFFFF}, 4, "a0 or aL"},
        Malformed{"relative dest", {0xFFFE0200, 0x02000001, 0x800F2000, 0x80E40000, 0xFFFF}, 2, "vs_3_0"},
        Malformed{"dcl wrong length", {0xFFFE0200, 0x0300001F, 0x80000000, 0x900F0000, 0x0, 0xFFFF}, 1, "needs length 2"},
        Malformed{"dcl bad usage", {0xFFFE0200, 0x0200001F, 0x8000000F, 0x900F0000, 0xFFFF}, 2, "unknown dcl usage 15"},
        Malformed{"predicated def", {0xFFFE0200, 0x15000051, 0xA00F0000, 0, 0, 0, 0, 0xFFFF}, 1, "cannot be predicated"},
        Malformed{"def short", {0xFFFE0200, 0x04000051, 0xA00F0000, 0, 0, 0, 0xFFFF}, 1, "needs length 5"},
        Malformed{"texld control 3", {0xFFFF0200, 0x03030042, 0x800F0000, 0xB0E40000, 0xA0E40800, 0xFFFF}, 1, "texld control 3"},
        Malformed{"control on mov", {0xFFFE0200, 0x02010001, 0x800F0000, 0x80E40000, 0xFFFF}, 1, "control bits"},
        Malformed{"comment overrun", {0xFFFE0200, 0x0005FFFE, 0x1, 0xFFFF}, 1, "comment of 5"},
        Malformed{"bad source modifier", {0xFFFE0200, 0x02000001, 0x800F0000, 0x8EE40000, 0xFFFF}, 3, "source modifier 14"}));

TEST(StreamCodec, OddByteCountIsRejected) {
    std::vector<std::byte> bytes(5, std::byte{0xFF});
    auto r = decode_bytes(bytes);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error->message.find("not a whole number of DWORDs"), std::string::npos);
}

// --- random valid token streams: decode then encode is the identity ------------------------

class RandomStream {
public:
    explicit RandomStream(uint32_t seed) : rng_(seed) {}

    std::vector<uint32_t> make() {
        std::vector<uint32_t> t;
        const bool vertex = coin();
        t.push_back(vertex ? 0xFFFE0200u : 0xFFFF0200u);
        const int count = pick(0, 40);
        auto table = opcode_table();
        for (int n = 0; n < count; ++n) {
            if (pick(0, 15) == 0) {  // a comment block
                const int size = pick(0, 5);
                t.push_back(0xFFFEu | (static_cast<uint32_t>(size) << 16));
                for (int k = 0; k < size; ++k) t.push_back(word());
                continue;
            }
            const OpcodeInfo& row = table[static_cast<size_t>(pick(0, static_cast<int>(table.size()) - 1))];
            const auto op = static_cast<uint16_t>(row.opcode);
            switch (row.layout) {
            case OperandLayout::Declaration:
                t.push_back(tokens::encode_instruction(op, 0, 2));
                t.push_back(0x80000000u | static_cast<uint32_t>(pick(0, kMaxDeclUsage)) |
                            static_cast<uint32_t>(pick(0, 15)) << 16 |
                            static_cast<uint32_t>(pick(0, 4)) << 27);
                t.push_back(dest_token());
                continue;
            case OperandLayout::FloatDef:
            case OperandLayout::IntDef:
                t.push_back(tokens::encode_instruction(op, 0, 5));
                t.push_back(dest_token());
                for (int k = 0; k < 4; ++k) t.push_back(word());
                continue;
            case OperandLayout::BoolDef:
                t.push_back(tokens::encode_instruction(op, 0, 2));
                t.push_back(dest_token());
                t.push_back(word());
                continue;
            case OperandLayout::Standard:
                break;
            }
            std::vector<uint32_t> body;
            if (row.has_dest()) body.push_back(dest_token());
            const bool predicated = pick(0, 9) == 0;
            if (predicated) body.push_back(source_token(false));
            const int sources = pick(row.min_sources, row.num_sources);
            for (int s = 0; s < sources; ++s) {
                const bool rel = pick(0, 4) == 0;
                body.push_back(source_token(rel));
                if (rel) body.push_back(relative_token());
            }
            const bool comparison = row.opcode == Opcode::Ifc || row.opcode == Opcode::BreakC ||
                                    row.opcode == Opcode::SetP;
            const uint8_t control = comparison ? static_cast<uint8_t>(pick(1, 6)) : row.control;
            t.push_back(tokens::encode_instruction(op, control, static_cast<uint8_t>(body.size()),
                                                   predicated));
            t.insert(t.end(), body.begin(), body.end());
        }
        t.push_back(tokens::kEnd);
        return t;
    }

private:
    int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    bool coin() { return pick(0, 1) == 1; }
    uint32_t word() { return static_cast<uint32_t>(rng_()); }
    uint32_t reg_fields() {
        return tokens::encode_register_type(static_cast<RegisterType>(pick(0, kMaxRegisterType))) |
               static_cast<uint32_t>(pick(0, 0x7FF));
    }
    uint32_t dest_token() {
        return 0x80000000u | reg_fields() | static_cast<uint32_t>(pick(0, 15)) << 16 |
               static_cast<uint32_t>(pick(0, 7)) << 20 | static_cast<uint32_t>(pick(0, 15)) << 24;
    }
    uint32_t source_token(bool relative) {
        return 0x80000000u | reg_fields() | (relative ? 0x2000u : 0u) |
               static_cast<uint32_t>(pick(0, 255)) << 16 | static_cast<uint32_t>(pick(0, 13)) << 24;
    }
    uint32_t relative_token() {
        return 0x80000000u |
               tokens::encode_register_type(coin() ? RegisterType::Address : RegisterType::Loop) |
               static_cast<uint32_t>(pick(0, 255)) << 16;
    }
    std::mt19937 rng_;
};

TEST(StreamCodec, RandomValidStreamsRoundTrip) {
    for (uint32_t seed = 1; seed <= 2000; ++seed) {
        RandomStream gen(seed);
        const auto stream = gen.make();
        auto r = decode(stream);
        ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.error->to_string();
        ASSERT_EQ(encode(*r.program), stream) << "seed " << seed;
    }
}

}  // namespace
}  // namespace sm2::isa
