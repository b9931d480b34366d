// Formats: every texel layout of pipeline.md §15 decoded from hand-chosen bits to hand-derived
// floats, and encoded back to the same bits. Expected values are written as the spec's formula
// (UNORM v / (2^n - 1), SNORM v / (2^(n-1) - 1)), never copied from the code's output.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "format_layout.h"
#include "sm2/runtime/formats.h"

namespace sm2::runtime {
namespace {

std::vector<std::byte> B(std::initializer_list<unsigned> v) {
    std::vector<std::byte> out;
    for (unsigned b : v) out.push_back(static_cast<std::byte>(b));
    return out;
}

float F(uint32_t bits) { return std::bit_cast<float>(bits); }

void expect_same(float a, float b, const char* what, int c) {
    if (std::isnan(a) && std::isnan(b)) return;
    EXPECT_EQ(std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b)) << what << " channel " << c << ": " << a << " vs " << b;
}

// Decodes `bits`, compares with `expected` bit for bit, encodes the result and expects `bits`.
void check(Format f, const std::vector<std::byte>& bits, Float4 expected, bool round_trips = true) {
    const FormatInfo* info = format_info(f);
    ASSERT_NE(info, nullptr);
    ASSERT_EQ(bits.size(), info->bytes) << info->name;
    const Float4 got = decode_texel(f, bits.data());
    for (int c = 0; c < 4; ++c) expect_same(got[c], expected[c], info->name.data(), c);
    std::vector<std::byte> back(info->bytes);
    encode_texel(f, got, back.data());
    if (round_trips) {
        EXPECT_EQ(back, bits) << info->name << " does not encode back to the same bits";
    }
}

TEST(Formats, Table) {
    EXPECT_EQ(find_format("A8R8G8B8")->format, Format::A8R8G8B8);
    EXPECT_EQ(find_format("D3DFMT_DXT5")->format, Format::DXT5);
    EXPECT_EQ(find_format("d3dfmt_r16f")->format, Format::R16F);
    EXPECT_EQ(find_format("NOPE"), nullptr);
    EXPECT_EQ(static_cast<uint32_t>(Format::DXT1), 0x31545844u);
    EXPECT_EQ(format_info(Format::A16B16G16R16F)->bytes, 8);
    EXPECT_EQ(format_info(Format::A32B32G32R32F)->bytes, 16);
    EXPECT_EQ(format_info(Format::DXT1)->bytes, 8);   // per 4x4 block
    EXPECT_EQ(format_info(Format::DXT3)->bytes, 16);
    EXPECT_TRUE(format_info(Format::A8R8G8B8)->srgb);
    EXPECT_FALSE(format_info(Format::R16F)->srgb);
    for (const FormatInfo& info : format_table()) EXPECT_EQ(format_info(info.format), &info);
    // Values that name no format: below 256 (looked up directly) and above (FOURCC codes).
    for (uint32_t value : {19u, 255u, 256u, 0x31545845u, 0xFFFFFFFFu})
        EXPECT_EQ(format_info(static_cast<Format>(value)), nullptr) << value;
}

TEST(Formats, EightBitColour) {
    // A8R8G8B8 bytes B, G, R, A = 0x33 0x66 0x99 0xCC -> (153, 102, 51, 204) / 255
    check(Format::A8R8G8B8, B({0x33, 0x66, 0x99, 0xCC}), {153 / 255.0f, 102 / 255.0f, 51 / 255.0f, 204 / 255.0f});
    // X8R8G8B8: the top byte is ignored, alpha reads 1 (unused bits are written as 0)
    check(Format::X8R8G8B8, B({0x33, 0x66, 0x99, 0x00}), {153 / 255.0f, 102 / 255.0f, 51 / 255.0f, 1});
    check(Format::X8R8G8B8, B({0x33, 0x66, 0x99, 0xAB}), {153 / 255.0f, 102 / 255.0f, 51 / 255.0f, 1}, false);
    // A8B8G8R8 bytes R, G, B, A
    check(Format::A8B8G8R8, B({0x99, 0x66, 0x33, 0xCC}), {153 / 255.0f, 102 / 255.0f, 51 / 255.0f, 204 / 255.0f});
    check(Format::X8B8G8R8, B({0x99, 0x66, 0x33, 0x00}), {153 / 255.0f, 102 / 255.0f, 51 / 255.0f, 1});
    // R8G8B8 bytes B, G, R
    check(Format::R8G8B8, B({0x01, 0x02, 0xFF}), {1, 2 / 255.0f, 1 / 255.0f, 1});
}

TEST(Formats, PackedSixteenAndEightBit) {
    // R5G6B5 0x8401 = R 16 << 11 | G 32 << 5 | B 1 -> bytes 01 84
    check(Format::R5G6B5, B({0x01, 0x84}), {16 / 31.0f, 32 / 63.0f, 1 / 31.0f, 1});
    // X1R5G5B5 0x7C10 = R 31 << 10 | G 0 | B 16
    check(Format::X1R5G5B5, B({0x10, 0x7C}), {1, 0, 16 / 31.0f, 1});
    // A1R5G5B5 0x8443 = A 1 << 15 | R 1 << 10 | G 2 << 5 | B 3
    check(Format::A1R5G5B5, B({0x43, 0x84}), {1 / 31.0f, 2 / 31.0f, 3 / 31.0f, 1});
    // A4R4G4B4 0x1234 = A 1, R 2, G 3, B 4
    check(Format::A4R4G4B4, B({0x34, 0x12}), {2 / 15.0f, 3 / 15.0f, 4 / 15.0f, 1 / 15.0f});
    // R3G3B2 0xAE = 101 011 10: R 5/7, G 3/7, B 2/3
    check(Format::R3G3B2, B({0xAE}), {5 / 7.0f, 3 / 7.0f, 2 / 3.0f, 1});
    // A8 0x80 -> (0, 0, 0, 128/255)
    check(Format::A8, B({0x80}), {0, 0, 0, 128 / 255.0f});
    // L8 0x40 -> (l, l, l, 1)
    check(Format::L8, B({0x40}), {64 / 255.0f, 64 / 255.0f, 64 / 255.0f, 1});
    // A8L8 0x80FF: L 0xFF (byte 0), A 0x80
    check(Format::A8L8, B({0xFF, 0x80}), {1, 1, 1, 128 / 255.0f});
    // A4L4 0x5A: A 5, L 10
    check(Format::A4L4, B({0x5A}), {10 / 15.0f, 10 / 15.0f, 10 / 15.0f, 5 / 15.0f});
    // L16 0x1234 = 4660
    check(Format::L16, B({0x34, 0x12}), {4660 / 65535.0f, 4660 / 65535.0f, 4660 / 65535.0f, 1});
}

TEST(Formats, SixteenBitAndTenBitChannels) {
    // G16R16: R 0xFFFF, G 0x8000 -> (1, 32768/65535, 1, 1)
    check(Format::G16R16, B({0xFF, 0xFF, 0x00, 0x80}), {1, 32768 / 65535.0f, 1, 1});
    // A16B16G16R16: R 1, G 0x100, B 0x1000, A 0xFFFF from the low bytes up
    check(Format::A16B16G16R16, B({0x01, 0x00, 0x00, 0x01, 0x00, 0x10, 0xFF, 0xFF}),
          {1 / 65535.0f, 256 / 65535.0f, 4096 / 65535.0f, 1});
    // 0x801803FF = 1023 | 512 << 10 | 1 << 20 | 2 << 30
    // A2B10G10R10: R bits 0-9 = 1023, G = 512, B = 1, A = 2 -> A 2/3
    check(Format::A2B10G10R10, B({0xFF, 0x03, 0x18, 0x80}), {1, 512 / 1023.0f, 1 / 1023.0f, 2 / 3.0f});
    // A2R10G10B10: the same bits are B 1023, G 512, R 1, A 2
    check(Format::A2R10G10B10, B({0xFF, 0x03, 0x18, 0x80}), {1 / 1023.0f, 512 / 1023.0f, 1, 2 / 3.0f});
}

TEST(Formats, SignedBumpFormats) {
    // V8U8: U byte 0 = 0x81 = -127 -> -1, V = 0x40 = 64 -> 64/127; (u, v, 1, 1)
    check(Format::V8U8, B({0x81, 0x40}), {-1, 64 / 127.0f, 1, 1});
    // -128 also reads -1 (clamped), and encodes back as -127 (0x81)
    check(Format::V8U8, B({0x80, 0x7F}), {-1, 1, 1, 1}, false);
    std::vector<std::byte> back(2);
    encode_texel(Format::V8U8, {-1, 1, 1, 1}, back.data());
    EXPECT_EQ(back, B({0x81, 0x7F}));
    // Q8W8V8U8 bytes U, V, W, Q = 1, -1, 127, -127
    check(Format::Q8W8V8U8, B({0x01, 0xFF, 0x7F, 0x81}), {1 / 127.0f, -1 / 127.0f, 1, -1});
    // V16U16: U 0x4000 = 16384, V 0xC000 = -16384
    check(Format::V16U16, B({0x00, 0x40, 0x00, 0xC0}), {16384 / 32767.0f, -16384 / 32767.0f, 1, 1});
}

TEST(Formats, FloatFormats) {
    // R16F 0x3555: exponent 13 -> 2^-2, mantissa 341 -> (1 + 341/1024) / 4 = 1365/4096
    check(Format::R16F, B({0x55, 0x35}), {1365 / 4096.0f, 1, 1, 1});
    // G16R16F: R 0x3C00 = 1, G 0xC000 = -2
    check(Format::G16R16F, B({0x00, 0x3C, 0x00, 0xC0}), {1, -2, 1, 1});
    // A16B16G16R16F: R 0x3800 = 0.5, G 0x7C00 = +inf, B 0x0001 = 2^-24 (denormal), A 0x8000 = -0
    check(Format::A16B16G16R16F, B({0x00, 0x38, 0x00, 0x7C, 0x01, 0x00, 0x00, 0x80}),
          {0.5f, INFINITY, std::ldexp(1.0f, -24), -0.0f});
    // R32F 0x3FC00000 = 1.5
    check(Format::R32F, B({0x00, 0x00, 0xC0, 0x3F}), {1.5f, 1, 1, 1});
    // G32R32F: R 0x40490FDB (pi as float), G 0xBF800000 = -1
    check(Format::G32R32F, B({0xDB, 0x0F, 0x49, 0x40, 0x00, 0x00, 0x80, 0xBF}), {F(0x40490FDB), -1, 1, 1});
    check(Format::A32B32G32R32F,
          B({0, 0, 0x80, 0x3F, 0, 0, 0, 0x40, 0, 0, 0x40, 0x40, 0, 0, 0x80, 0x40}), {1, 2, 3, 4});
}

TEST(Formats, EncodeRoundsAndClamps) {
    std::vector<std::byte> t(4);
    // 0.5 * 255 = 127.5 rounds up to 128; 1.5 clamps to 255; -1 clamps to 0; NaN -> 0
    encode_texel(Format::A8R8G8B8, {0.5f, 1.5f, -1.0f, NAN}, t.data());
    EXPECT_EQ(t, B({0x00, 0xFF, 0x80, 0x00}));
    // R5G6B5 of 0.5: 15.5 -> 16, 31.5 -> 32, 15.5 -> 16: 16 << 11 | 32 << 5 | 16 = 0x8410
    std::vector<std::byte> s(2);
    encode_texel(Format::R5G6B5, {0.5f, 0.5f, 0.5f, 0.0f}, s.data());
    EXPECT_EQ(s, B({0x10, 0x84}));
    // Half rounds to nearest even: 1 + 2^-11 is halfway between 0x3C00 and 0x3C01 -> 0x3C00
    encode_texel(Format::R16F, {1.0f + std::ldexp(1.0f, -11), 0, 0, 0}, s.data());
    EXPECT_EQ(s, B({0x00, 0x3C}));
    // L8 stores r
    std::vector<std::byte> l(1);
    encode_texel(Format::L8, {1.0f, 0.0f, 0.0f, 0.0f}, l.data());
    EXPECT_EQ(l, B({0xFF}));
    // Snorm: 0.5 * 127 = 63.5 rounds away from zero to 64; -0.5 -> -64 = 0xC0
    encode_texel(Format::V8U8, {0.5f, -0.5f, 0, 0}, s.data());
    EXPECT_EQ(s, B({0x40, 0xC0}));
}

// decode(encode(decode(bits))) == decode(bits) for every value of the 8- and 16-bit formats and
// 20000 random values of the wider ones.
TEST(Formats, EncodeRoundTripsEveryRepresentableValue) {
    std::mt19937 rng(1234);
    for (const FormatInfo& info : format_table()) {
        if (!info.texture || info.kind == FormatKind::Compressed) continue;
        const unsigned n = info.bytes;
        const uint64_t count = n == 1 ? 256 : n == 2 ? 65536 : 20000;
        std::vector<std::byte> bits(n), back(n);
        for (uint64_t i = 0; i < count; ++i) {
            for (unsigned b = 0; b < n; ++b)
                bits[b] = static_cast<std::byte>(n <= 2 ? (i >> (8 * b)) & 0xFF : rng() & 0xFF);
            const Float4 v = decode_texel(info.format, bits.data());
            encode_texel(info.format, v, back.data());
            const Float4 w = decode_texel(info.format, back.data());
            for (int c = 0; c < 4; ++c) {
                if (std::isnan(v[c]) && std::isnan(w[c])) continue;
                ASSERT_EQ(std::bit_cast<uint32_t>(v[c]), std::bit_cast<uint32_t>(w[c]))
                    << info.name << " value " << i << " channel " << c;
            }
        }
    }
}

TEST(Formats, Srgb) {
    EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
    EXPECT_EQ(srgb_to_linear(1.0f), 1.0f);
    // 10/255 = 0.0392 <= 0.04045: linear segment 10/255/12.92
    EXPECT_FLOAT_EQ(srgb_to_linear(10 / 255.0f), 10 / 255.0f / 12.92f);
    // ((128/255 + 0.055) / 1.055)^2.4 = 0.527925^2.4 = exp(2.4 * -0.638800) = 0.215861
    EXPECT_NEAR(srgb_to_linear(128 / 255.0f), 0.215861f, 1e-6f);
    EXPECT_NEAR(linear_to_srgb(0.215861f), 128 / 255.0f, 1e-6f);
    for (unsigned i = 0; i < 256; ++i) EXPECT_EQ(srgb_to_linear_table()[i], srgb_to_linear(static_cast<float>(i) / 255.0f));
}

TEST(Formats, UnknownFormatsThrow) {
    std::byte t[16]{};
    EXPECT_THROW((void)decode_texel(Format::Unknown, t), std::invalid_argument);
    EXPECT_THROW((void)decode_texel(Format::DXT1, t), std::invalid_argument);
    EXPECT_THROW(encode_texel(static_cast<Format>(999), {}, t), std::invalid_argument);
    std::array<Float4, 16> block;
    EXPECT_THROW(decode_block(Format::A8R8G8B8, t, block), std::invalid_argument);
}

}  // namespace
}  // namespace sm2::runtime
