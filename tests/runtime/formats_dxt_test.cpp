// DXT1..DXT5 blocks decoded by hand (pipeline.md §15; rounding rules as in dxt.cpp: 5/6-bit
// expansion by bit replication, (2*c0 + c1 + 1) / 3, (c0 + c1 + 1) / 2, alpha +3 / 7, +2 / 5).
#include <gtest/gtest.h>

#include <vector>

#include "dxt.h"
#include "sm2/runtime/formats.h"

namespace sm2::runtime {
namespace {

std::vector<std::byte> B(std::initializer_list<unsigned> v) {
    std::vector<std::byte> out;
    for (unsigned b : v) out.push_back(static_cast<std::byte>(b));
    return out;
}

Float4 C8(unsigned r, unsigned g, unsigned b, unsigned a) {
    return {r / 255.0f, g / 255.0f, b / 255.0f, a / 255.0f};
}

std::array<Float4, 16> decode(Format f, const std::vector<std::byte>& block) {
    std::array<Float4, 16> t;
    decode_block(f, block.data(), t);
    return t;
}

// c0 = 0xF800 (pure red: R 31 -> 255), c1 = 0x001F (pure blue), c0 > c1: 4 colours
//   p2 = (2*c0 + c1 + 1)/3: r (510 + 0 + 1)/3 = 170, b (0 + 255 + 1)/3 = 85
//   p3 = (c0 + 2*c1 + 1)/3: r (255 + 1)/3 = 85,     b (510 + 1)/3 = 170
// indices: row 0 = 0, 1, 2, 3 (byte 0b11100100 = 0xE4), row 1 all 3 (0xFF), row 2 all 0, row 3 all 1 (0x55)
const auto kColourBlock = B({0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xFF, 0x00, 0x55});

TEST(Dxt, Dxt1FourColour) {
    const auto t = decode(Format::DXT1, kColourBlock);
    EXPECT_EQ(t[0], C8(255, 0, 0, 255));
    EXPECT_EQ(t[1], C8(0, 0, 255, 255));
    EXPECT_EQ(t[2], C8(170, 0, 85, 255));
    EXPECT_EQ(t[3], C8(85, 0, 170, 255));
    for (int x = 0; x < 4; ++x) {
        EXPECT_EQ(t[4 + x], C8(85, 0, 170, 255));
        EXPECT_EQ(t[8 + x], C8(255, 0, 0, 255));
        EXPECT_EQ(t[12 + x], C8(0, 0, 255, 255));
    }
}

TEST(Dxt, Dxt1ThreeColourAndTransparent) {
    // c0 = 0x001F (blue) < c1 = 0xF800 (red): p2 = (c0 + c1 + 1)/2 = (128, 0, 128), p3 = transparent black
    const auto t = decode(Format::DXT1, B({0x1F, 0x00, 0x00, 0xF8, 0xE4, 0, 0, 0}));
    EXPECT_EQ(t[0], C8(0, 0, 255, 255));
    EXPECT_EQ(t[1], C8(255, 0, 0, 255));
    EXPECT_EQ(t[2], C8(128, 0, 128, 255));
    EXPECT_EQ(t[3], C8(0, 0, 0, 0));
    EXPECT_EQ(t[4], C8(0, 0, 255, 255));
    // c0 == c1 = 0x8420 (R 16, G 33, B 0) is also the 3-colour mode. Bit replication:
    // R (16 << 3) | (16 >> 2) = 132, G (33 << 2) | (33 >> 4) = 134; index 3 is transparent
    const auto u = decode(Format::DXT1, B({0x20, 0x84, 0x20, 0x84, 0x0E, 0, 0, 0}));  // row 0: 2, 3, 0, 0
    EXPECT_EQ(u[0], C8(132, 134, 0, 255));
    EXPECT_EQ(u[1], C8(0, 0, 0, 0));
    EXPECT_EQ(u[2], C8(132, 134, 0, 255));
}

TEST(Dxt, Dxt3ExplicitAlphaAndAlwaysFourColours) {
    // alpha row 0: 0, 15, 8, 1 -> bytes (0 | 15 << 4) = 0xF0, (8 | 1 << 4) = 0x18; rows 1-3 all 15
    // colour: c0 = 0x001F < c1 = 0xF800 but DXT3 is always 4-colour:
    //   p2 = (2*c0 + c1 + 1)/3 = (85, 0, 170), p3 = (170, 0, 85)
    const auto block = B({0xF0, 0x18, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                          0x1F, 0x00, 0x00, 0xF8, 0xE4, 0, 0, 0});
    const auto t = decode(Format::DXT3, block);
    EXPECT_EQ(t[0], C8(0, 0, 255, 0));
    EXPECT_EQ(t[1], C8(255, 0, 0, 255));          // 15 * 17 = 255
    EXPECT_EQ(t[2], C8(85, 0, 170, 136));         // 8 * 17 = 136 (= 8/15)
    EXPECT_EQ(t[3], C8(170, 0, 85, 17));          // 1 * 17
    EXPECT_EQ(t[2][3], 8 / 15.0f);
    // DXT2 is the same layout with premultiplied colour: the stored colour is returned as is
    EXPECT_EQ(decode(Format::DXT2, block), t);
}

TEST(Dxt, Dxt5EightAlphas) {
    // a0 = 200 > a1 = 100: a_k = ((8-k)*a0 + (k-1)*a1 + 3)/7:
    //   a2 = 1303/7 = 186, a3 = 1203/7 = 171, a4 = 1103/7 = 157, a5 = 1003/7 = 143,
    //   a6 = 903/7 = 129, a7 = 803/7 = 114
    // indices t0..t4 = 0, 1, 2, 7, 6: 1 << 3 | 2 << 6 | 7 << 9 | 6 << 12 = 0x6E88, rest 0
    const auto block = B({200, 100, 0x88, 0x6E, 0, 0, 0, 0,
                          0x00, 0xF8, 0x1F, 0x00, 0, 0, 0, 0});
    const auto t = decode(Format::DXT5, block);
    EXPECT_EQ(t[0], C8(255, 0, 0, 200));
    EXPECT_EQ(t[1], C8(255, 0, 0, 100));
    EXPECT_EQ(t[2], C8(255, 0, 0, 186));
    EXPECT_EQ(t[3], C8(255, 0, 0, 114));
    EXPECT_EQ(t[4], C8(255, 0, 0, 129));
    EXPECT_EQ(t[5], C8(255, 0, 0, 200));
    EXPECT_EQ(decode(Format::DXT4, block), t);
}

TEST(Dxt, Dxt5SixAlphasWithZeroAndOne) {
    // a0 = 50 <= a1 = 100: a_k = ((6-k)*a0 + (k-1)*a1 + 2)/5: a2 = 302/5 = 60, a3 = 352/5 = 70,
    // a4 = 402/5 = 80, a5 = 452/5 = 90, a6 = 0, a7 = 255. Indices t_k = k for k = 0..7:
    // sum k << 3k = 0xFAC688 -> bytes 88 C6 FA 00 00 00
    const auto block = B({50, 100, 0x88, 0xC6, 0xFA, 0, 0, 0,
                          0x00, 0xF8, 0x1F, 0x00, 0, 0, 0, 0});
    const auto t = decode(Format::DXT5, block);
    const unsigned expected[8] = {50, 100, 60, 70, 80, 90, 0, 255};
    for (int k = 0; k < 8; ++k) EXPECT_EQ(t[k][3], expected[k] / 255.0f) << k;
}

// The single-texel decoder the sampler uses agrees with the whole-block decoder on random blocks.
TEST(Dxt, TexelDecoderMatchesBlockDecoder) {
    uint32_t seed = 99;
    for (Format f : {Format::DXT1, Format::DXT2, Format::DXT3, Format::DXT4, Format::DXT5}) {
        for (int n = 0; n < 2000; ++n) {
            std::array<std::byte, 16> block;
            for (auto& b : block) {
                seed = seed * 1664525u + 1013904223u;
                b = static_cast<std::byte>(seed >> 24);
            }
            if (n % 2) std::swap(block[f == Format::DXT1 ? 0 : 8], block[f == Format::DXT1 ? 2 : 10]);
            std::array<dxt::Rgba8, 16> all;
            dxt::decode_block(f, block.data(), all);
            for (unsigned i = 0; i < 16; ++i) {
                const dxt::Rgba8 t = dxt::decode_texel(f, block.data(), i % 4, i / 4);
                ASSERT_TRUE(t.r == all[i].r && t.g == all[i].g && t.b == all[i].b && t.a == all[i].a) << n << " " << i;
            }
        }
    }
}

}  // namespace
}  // namespace sm2::runtime
