// Command-stream syntax: parsing (values checked byte for byte against hand-derived encodings),
// canonical printing, binary packing, and every error path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "half.h"
#include "sm2/runtime/command_stream.h"

namespace sm2::runtime::cs {
namespace {

std::vector<uint8_t> as_u8(const std::vector<std::byte>& b) {
    std::vector<uint8_t> out(b.size());
    if (!b.empty()) std::memcpy(out.data(), b.data(), b.size());
    return out;
}

Stream parse_ok(std::string_view text, const TextOptions& options = {}) {
    auto r = parse_text(text, options);
    EXPECT_TRUE(r.ok()) << (r.error ? r.error->to_string() : "");
    return r.ok() ? *r.stream : Stream{};
}

// A canonical stream using every value form.
const char* const kCanonical =
    "sm2cs 1\n"
    "# a triangle\n"
    "\n"
    "CreateRenderTarget rt0 64 32 A8R8G8B8\n"
    "SetRenderTarget 0 rt0  # colour target 0\n"
    "CreateVertexBuffer vb0 24\n"
    "Lock vb0 0 f32[ -0.5 0.5 1.0 0.001 inf -inf nan -0.0 ]\n"
    "CreateVertexDeclaration decl0 { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 D3DCOLOR DEFAULT COLOR 0 }\n"
    "SetRenderState FOGSTART 0.25\n"
    "SetRenderState BLENDFACTOR 0xFF00FF00\n"
    "Clear 0 -1 TARGET 0x00000000 1.0 0\n"
    "Lock vb0 0 u16[ 1 258 65535 ]\n"
    "Lock vb0 0 hex[ 00ff10aa 01 ]\n"
    "Lock vb0 0 f16[ 1.0 -2.0 ]\n"
    "Lock vb0 0 u8[\n"
    "  0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\n"
    "  16\n"
    "]\n"
    "SaveSurface rt0 \"out/a \\\"b\\\".png\"\n"
    "CreateVertexShader vs0 asm<<END\n"
    "vs_2_0\n"
    "mov oPos, v0\n"
    "END\n"
    "Present\n";

TEST(CommandStreamText, ParsesEveryValueForm) {
    Stream s = parse_ok(kCanonical);
    ASSERT_EQ(s.statements.size(), 17u);
    EXPECT_EQ(s.statements[0].kind, Statement::Kind::Comment);
    EXPECT_EQ(s.statements[0].name, " a triangle");
    EXPECT_EQ(s.statements[1].kind, Statement::Kind::Blank);

    const Statement& rt = s.statements[2];
    EXPECT_EQ(rt.name, "CreateRenderTarget");
    EXPECT_EQ(rt.line, 4u);
    ASSERT_EQ(rt.arguments.size(), 4u);
    EXPECT_EQ(rt.arguments[0].kind, Value::Kind::Identifier);
    EXPECT_EQ(rt.arguments[1].integer, 64);
    EXPECT_EQ(rt.arguments[3].text, "A8R8G8B8");
    EXPECT_EQ(s.statements[3].trailing_comment, " colour target 0");

    // f32: -0.5 = BF000000, 0.5 = 3F000000, 1 = 3F800000, 0.001 = 3A83126F, inf = 7F800000,
    // -inf = FF800000, nan = 7FC00000, -0 = 80000000 (little-endian bytes)
    const Value& floats = s.statements[5].arguments[2];
    ASSERT_EQ(floats.kind, Value::Kind::Blob);
    EXPECT_EQ(as_u8(floats.bytes), (std::vector<uint8_t>{
        0x00, 0x00, 0x00, 0xBF, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x80, 0x3F, 0x6F, 0x12, 0x83, 0x3A,
        0x00, 0x00, 0x80, 0x7F, 0x00, 0x00, 0x80, 0xFF, 0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0x00, 0x80}));

    const Value& element = s.statements[6].arguments[1];
    ASSERT_EQ(element.kind, Value::Kind::Tuple);
    ASSERT_EQ(element.items.size(), 6u);
    EXPECT_EQ(element.items[2].text, "FLOAT3");

    const Value& fog = s.statements[7].arguments[1];
    EXPECT_EQ(fog.kind, Value::Kind::Float);
    EXPECT_EQ(fog.float_bits, 0x3E800000u);  // 0.25
    const Value& factor = s.statements[8].arguments[1];
    EXPECT_EQ(factor.kind, Value::Kind::Integer);
    EXPECT_TRUE(factor.hex);
    EXPECT_EQ(factor.integer, 0xFF00FF00);
    EXPECT_EQ(s.statements[9].arguments[1].integer, -1);

    EXPECT_EQ(as_u8(s.statements[10].arguments[2].bytes),
              (std::vector<uint8_t>{0x01, 0x00, 0x02, 0x01, 0xFF, 0xFF}));  // 258 = 0x0102
    EXPECT_EQ(as_u8(s.statements[11].arguments[2].bytes),
              (std::vector<uint8_t>{0x00, 0xFF, 0x10, 0xAA, 0x01}));
    // half 1.0 = 0x3C00, -2.0 = 0xC000
    EXPECT_EQ(as_u8(s.statements[12].arguments[2].bytes), (std::vector<uint8_t>{0x00, 0x3C, 0x00, 0xC0}));
    EXPECT_EQ(s.statements[13].arguments[2].bytes.size(), 17u);
    EXPECT_EQ(s.statements[14].arguments[1].text, "out/a \"b\".png");

    const Value& shader = s.statements[15].arguments[1];
    ASSERT_EQ(shader.kind, Value::Kind::Heredoc);
    EXPECT_EQ(shader.text, "END");
    const std::string body(reinterpret_cast<const char*>(shader.bytes.data()), shader.bytes.size());
    EXPECT_EQ(body, "vs_2_0\nmov oPos, v0\n");
    EXPECT_EQ(s.statements[16].name, "Present");
    EXPECT_EQ(s.statements[16].line, 24u);  // the heredoc ends with END on line 23
}

TEST(CommandStreamText, CanonicalTextPrintsBackUnchanged) {
    EXPECT_EQ(to_text(parse_ok(kCanonical)), kCanonical);
}

TEST(CommandStreamText, NonCanonicalInputIsNormalised) {
    const Stream s = parse_ok("sm2cs 1\n   Lock  vb0 0 f32[1 2\n 0.5]   \nClear 0 -1 TARGET 0xff 1 0\n");
    EXPECT_EQ(to_text(s), "sm2cs 1\nLock vb0 0 f32[ 1.0 2.0 0.5 ]\nClear 0 -1 TARGET 0x000000FF 1 0\n");
}

TEST(CommandStreamBinary, PackThenDumpIsTheIdentity) {
    const Stream s = parse_ok(kCanonical);
    const auto packed = pack(s);
    EXPECT_TRUE(looks_packed(packed));
    auto r = unpack(packed);
    ASSERT_TRUE(r.ok()) << r.error->to_string();
    EXPECT_EQ(r.stream->statements, s.statements);
    EXPECT_EQ(to_text(*r.stream), kCanonical);
}

TEST(CommandStreamBinary, HeaderAndRecordLayout) {
    const Stream s = parse_ok("sm2cs 1\nPresent\n");
    const auto packed = as_u8(pack(s));
    // "SM2C", version 1, record: id of Present, 0 arguments, payload = empty trailing comment (4)
    const uint16_t id = *call_id("Present");
    EXPECT_EQ(packed, (std::vector<uint8_t>{'S', 'M', '2', 'C', 1, 0, 0, 0,
                                            static_cast<uint8_t>(id & 0xFF), static_cast<uint8_t>(id >> 8),
                                            0, 0, 4, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(CommandStreamText, SideFilesAreReadThroughTheReader) {
    TextOptions options;
    options.side_files = [](const std::string& root, const std::string& dir, const std::string& path,
                            std::string& error) -> std::optional<std::vector<std::byte>> {
        EXPECT_EQ(root, "scenes");  // no root_dir: the stream's folder
        error = "not found";
        if (dir != "scenes" || path != "mesh.bin") return std::nullopt;
        return std::vector<std::byte>{std::byte{1}, std::byte{2}};
    };
    options.base_dir = "scenes";
    const Stream s = parse_ok("sm2cs 1\nLock vb0 0 @\"mesh.bin\"\n", options);
    const Value& v = s.statements[0].arguments[2];
    EXPECT_EQ(v.kind, Value::Kind::SideFile);
    EXPECT_EQ(v.text, "mesh.bin");
    EXPECT_EQ(as_u8(v.bytes), (std::vector<uint8_t>{1, 2}));
    EXPECT_EQ(to_text(s), "sm2cs 1\nLock vb0 0 @\"mesh.bin\"\n");
    auto r = unpack(pack(s));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(as_u8(r.stream->statements[0].arguments[2].bytes), (std::vector<uint8_t>{1, 2}));

    auto missing = parse_text("sm2cs 1\nLock vb0 0 @\"other.bin\"\n", options);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error->to_string(), "<input>:2:12: error: cannot read side file 'other.bin': not found");
}

struct BadText {
    const char* text;
    uint32_t line, column;
    const char* message;
};

class MalformedText : public ::testing::TestWithParam<BadText> {};

TEST_P(MalformedText, StopsWithLineAndColumn) {
    const BadText& b = GetParam();
    auto r = parse_text(b.text);
    ASSERT_FALSE(r.ok()) << b.text;
    EXPECT_EQ(r.error->line, b.line) << r.error->to_string();
    EXPECT_EQ(r.error->column, b.column) << r.error->to_string();
    EXPECT_NE(r.error->message.find(b.message), std::string::npos) << r.error->to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Parser, MalformedText,
    ::testing::Values(
        BadText{"", 1, 1, "starts with 'sm2cs"},
        BadText{"hello\n", 1, 6, "starts with 'sm2cs"},
        BadText{"sm2cs 2\n", 1, 8, "unsupported command-stream version 2"},
        BadText{"sm2cs\n", 1, 6, "expected the format version"},
        BadText{"sm2cs 1\nFrobnicate 1\n", 2, 1, "unknown call 'Frobnicate'"},
        BadText{"sm2cs 1\nPresent\n  DrawPrimitive 12x 0\n", 3, 17, "not a number '12x'"},
        BadText{"sm2cs 1\nClear 99999999999\n", 2, 7, "out of 32-bit range"},
        BadText{"sm2cs 1\nLock vb0 0 f32[ 1 2\n", 3, 1, "unterminated blob"},
        BadText{"sm2cs 1\nLock vb0 0 u8[ 1 256 ]\n", 2, 18, "out of range '256' in u8 blob"},
        BadText{"sm2cs 1\nLock vb0 0 f32[ 1 x ]\n", 2, 19, "not a float 'x'"},
        BadText{"sm2cs 1\nLock vb0 0 hex[ abc ]\n", 2, 17, "odd number of hex digits"},
        BadText{"sm2cs 1\nLock vb0 0 q8[ 1 ]\n", 2, 14, "unknown blob type 'q8'"},
        BadText{"sm2cs 1\nSaveSurface rt0 \"abc\n", 2, 21, "unterminated string"},
        BadText{"sm2cs 1\nSaveSurface rt0 \"a\\n\"\n", 2, 20, "escapes"},
        BadText{"sm2cs 1\nCreateVertexDeclaration d { 0 0\n", 3, 1, "unterminated '{'"},
        BadText{"sm2cs 1\nCreateVertexShader vs asm<<END\nmov r0, r1\n", 2, 23, "never terminated"},
        BadText{"sm2cs 1\nCreateVertexShader vs asm<<END x\n", 2, 32, "next line"},
        BadText{"sm2cs 1\nClear 1,2\n", 2, 8, "expected a blank"},
        BadText{"sm2cs 1\nClear \"a\"b\n", 2, 10, "expected a blank"},
        BadText{"sm2cs 1\nLock a @b\n", 2, 9, "quoted file name"},
        BadText{"sm2cs 1\nClear { asm<<END\nEND\n}\n", 2, 9, "not inside"}));

TEST(CommandStreamText, DeepTuplesAreRefused) {
    std::string text = "sm2cs 1\nClear ";
    for (int i = 0; i < 40; ++i) text += "{ ";
    auto r = parse_text(text);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error->message.find("nested too deeply"), std::string::npos);
}

struct BadBinary {
    const char* name;
    std::vector<uint8_t> bytes;
    size_t offset;
    const char* message;
};

class MalformedBinary : public ::testing::TestWithParam<BadBinary> {};

TEST_P(MalformedBinary, StopsWithTheByteOffset) {
    const BadBinary& b = GetParam();
    std::vector<std::byte> bytes(b.bytes.size());
    if (!bytes.empty()) std::memcpy(bytes.data(), b.bytes.data(), b.bytes.size());
    auto r = unpack(bytes);
    ASSERT_FALSE(r.ok()) << b.name;
    EXPECT_EQ(r.error->byte_offset, b.offset) << r.error->to_string();
    EXPECT_NE(r.error->message.find(b.message), std::string::npos) << r.error->to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Reader, MalformedBinary,
    ::testing::Values(
        BadBinary{"no magic", {'S', 'M', '2'}, 0, "no SM2C header"},
        BadBinary{"truncated version", {'S', 'M', '2', 'C', 1}, 4, "truncated header"},
        BadBinary{"bad version", {'S', 'M', '2', 'C', 9, 0, 0, 0}, 4, "unsupported"},
        BadBinary{"truncated record", {'S', 'M', '2', 'C', 1, 0, 0, 0, 5, 0}, 8, "truncated record"},
        BadBinary{"payload too long", {'S', 'M', '2', 'C', 1, 0, 0, 0, 2, 0, 0, 0, 200, 0, 0, 0}, 8, "past the end"},
        BadBinary{"unknown call", {'S', 'M', '2', 'C', 1, 0, 0, 0, 0xFF, 0x7F, 0, 0, 0, 0, 0, 0}, 8, "unknown call id"},
        BadBinary{"bad tag", {'S', 'M', '2', 'C', 1, 0, 0, 0, 2, 0, 1, 0, 5, 0, 0, 0, 99, 0, 0, 0, 0}, 16,
                  "unknown argument tag 99"},
        BadBinary{"length mismatch", {'S', 'M', '2', 'C', 1, 0, 0, 0, 2, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0, 7}, 8,
                  "does not match"}));

TEST(Half, ConversionsWorkedByHand) {
    EXPECT_EQ(float_to_half(1.0f), 0x3C00);
    EXPECT_EQ(float_to_half(-2.0f), 0xC000);
    EXPECT_EQ(float_to_half(65504.0f), 0x7BFF);      // largest half
    EXPECT_EQ(float_to_half(65520.0f), 0x7C00);      // halfway to 2^16 rounds (to even) to inf
    EXPECT_EQ(float_to_half(1.0f / 3.0f), 0x3555);   // 1.0101010101|01.. x 2^-2, rounds down
    EXPECT_EQ(float_to_half(5.9604645e-8f), 0x0001); // 2^-24, smallest denormal
    EXPECT_EQ(float_to_half(2.9802322e-8f), 0x0000); // 2^-25: halfway, ties to even (0)
    EXPECT_EQ(float_to_half(-0.0f), 0x8000);
    EXPECT_EQ(half_to_float(0x3555), 0.333251953125f);  // 0x155/1024 + 1 = 1.3330078125, x 1/4
    EXPECT_EQ(half_to_float(0x0001), 5.9604645e-8f);
    EXPECT_EQ(half_to_float(0x03FF), 6.0975552e-5f);    // largest denormal: 1023 x 2^-24
    EXPECT_TRUE(std::isinf(half_to_float(0x7C00)));
    EXPECT_TRUE(std::isnan(half_to_float(0x7E00)));
    for (uint32_t h = 0; h < 0x10000; ++h) {
        const auto half = static_cast<uint16_t>(h);
        const float f = half_to_float(half);
        if (std::isnan(f)) continue;
        EXPECT_EQ(float_to_half(f), half) << std::hex << h;
    }
}

}  // namespace
}  // namespace sm2::runtime::cs
