// Surfaces and textures: memory layout, level sizes, limits, box-filtered mips.
#include <gtest/gtest.h>

#include <random>

#include "sm2/runtime/surface.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {
namespace {

TEST(Surface, LayoutAndReadWrite) {
    Surface s(Format::A8R8G8B8, 3, 2);
    EXPECT_EQ(s.row_pitch(), 12u);
    EXPECT_EQ(s.slice_pitch(), 24u);
    s.write(2, 1, 0, {1.0f, 0.0f, 0.0f, 1.0f});
    // texel (2, 1) at byte 12 + 8: B, G, R, A = 00 00 FF FF
    EXPECT_EQ(s.bytes()[20], std::byte{0x00});
    EXPECT_EQ(s.bytes()[22], std::byte{0xFF});
    EXPECT_EQ(s.bytes()[23], std::byte{0xFF});
    EXPECT_EQ(s.read(2, 1), (Float4{1, 0, 0, 1}));
    EXPECT_EQ(s.read(0, 0), (Float4{0, 0, 0, 0}));
    EXPECT_THROW((void)s.read(3, 0), std::out_of_range);
    s.fill({0, 1, 0, 0});
    EXPECT_EQ(s.read(1, 1), (Float4{0, 1, 0, 0}));
}

TEST(Surface, CompressedBlocks) {
    Surface s(Format::DXT1, 6, 2);  // 2 x 1 blocks of 8 bytes
    EXPECT_EQ(s.row_pitch(), 16u);
    EXPECT_EQ(s.bytes().size(), 16u);
    Surface t(Format::DXT5, 1, 1);  // a 1x1 level still occupies a whole block
    EXPECT_EQ(t.bytes().size(), 16u);
    EXPECT_THROW(s.write(0, 0, 0, {}), std::invalid_argument);
    // zero block: c0 = c1 = 0 -> 3-colour mode, index 0 = black opaque
    EXPECT_EQ(s.read(5, 1), (Float4{0, 0, 0, 1}));
}

TEST(Surface, BadArguments) {
    EXPECT_THROW(Surface(Format::Unknown, 1, 1), std::invalid_argument);
    EXPECT_THROW(Surface(Format::A8, 0, 1), std::invalid_argument);
}

TEST(Texture, LevelSizes) {
    const Texture t = Texture::create_2d(Format::A8R8G8B8, 16, 4);
    EXPECT_EQ(t.levels(), 5u);  // 16x4, 8x2, 4x1, 2x1, 1x1
    EXPECT_EQ(t.surface(2).width(), 4u);
    EXPECT_EQ(t.surface(2).height(), 1u);
    EXPECT_EQ(t.surface(4).width(), 1u);
    EXPECT_THROW((void)t.surface(5), std::out_of_range);
    const Texture v = Texture::create_volume(Format::L8, 8, 4, 2);
    EXPECT_EQ(v.levels(), 4u);
    EXPECT_EQ(v.surface(1).depth(), 1u);
    EXPECT_EQ(v.surface(3).width(), 1u);
    const Texture c = Texture::create_cube(Format::R32F, 8, 2);
    EXPECT_EQ(c.faces(), 6u);
    EXPECT_EQ(c.surface(1, 5).width(), 4u);
    EXPECT_THROW((void)c.surface(0, 6), std::out_of_range);
}

TEST(Texture, Limits) {
    EXPECT_NO_THROW((void)Texture::create_2d(Format::A8, 4096, 1));
    EXPECT_THROW((void)Texture::create_2d(Format::A8, 4097, 1), std::invalid_argument);
    EXPECT_THROW((void)Texture::create_cube(Format::A8, 8192), std::invalid_argument);
    EXPECT_THROW((void)Texture::create_volume(Format::A8, 1024, 1, 1), std::invalid_argument);
    EXPECT_THROW((void)Texture::create_2d(Format::A8, 0, 1), std::invalid_argument);
    EXPECT_THROW((void)Texture::create_2d(Format::D24S8, 4, 4), std::invalid_argument);
    EXPECT_THROW((void)Texture::create_2d(Format::A8, 4, 4, 4), std::invalid_argument);  // chain has 3
    // Non-power-of-two: one level only (conditional NONPOW2)
    EXPECT_EQ(Texture::create_2d(Format::A8, 100, 30).levels(), 1u);
    EXPECT_THROW((void)Texture::create_2d(Format::A8, 100, 30, 2), std::invalid_argument);
    // DXTn level 0 must be a multiple of 4
    EXPECT_THROW((void)Texture::create_2d(Format::DXT1, 6, 4), std::invalid_argument);
    EXPECT_EQ(Texture::create_2d(Format::DXT1, 8, 4).levels(), 4u);
}

TEST(Texture, BoxFilterMips) {
    Texture t = Texture::create_2d(Format::R32F, 4, 2);
    // level 0: row 0 = 1 2 3 4, row 1 = 5 6 7 8
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 4; ++x) t.surface(0).write(x, y, 0, {static_cast<float>(1 + x + 4 * y), 0, 0, 0});
    t.generate_mips();
    // level 1 (2x1): (1+2+5+6)/4 = 3.5, (3+4+7+8)/4 = 5.5; level 2 (1x1): rows repeat: (3.5+5.5)/2 = 4.5
    EXPECT_EQ(t.surface(1).read(0, 0)[0], 3.5f);
    EXPECT_EQ(t.surface(1).read(1, 0)[0], 5.5f);
    EXPECT_EQ(t.surface(2).read(0, 0)[0], 4.5f);

    Texture v = Texture::create_volume(Format::L8, 2, 2, 2);
    // 8 texels 0, 255 alternating in x: average 127.5 -> rounds to 128
    for (uint32_t z = 0; z < 2; ++z)
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x) v.surface(0).write(x, y, z, {x ? 1.0f : 0.0f, 0, 0, 0});
    v.generate_mips();
    EXPECT_EQ(v.surface(1).read(0, 0, 0)[0], 128 / 255.0f);

    Texture d = Texture::create_2d(Format::DXT1, 8, 8);
    EXPECT_THROW(d.generate_mips(), std::invalid_argument);
}

// The box filter on texels of 8-bit UNORM bytes (Texture::generate_mips()'s byte path), by
// hand: each byte the rounded mean of its taps, a byte no channel stores written 0.
TEST(Texture, BoxFilterMipsOfBytes) {
    Texture t = Texture::create_2d(Format::A8R8G8B8, 2, 2);
    // Bytes B, G, R, A of the four texels: B 0 1 2 2 (mean 1.25 -> 1), G 255 255 255 254
    // (254.75 -> 255), R 10 20 30 41 (25.25 -> 25), A 0 0 1 2 (0.75 -> 1).
    const uint8_t level0[16] = {0, 255, 10, 0, 1, 255, 20, 0, 2, 255, 30, 1, 2, 254, 41, 2};
    for (unsigned i = 0; i < 16; ++i) t.surface(0).bytes()[i] = static_cast<std::byte>(level0[i]);
    t.generate_mips();
    const uint8_t expected[4] = {1, 255, 25, 1};
    for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(t.surface(1).bytes()[i], static_cast<std::byte>(expected[i])) << "byte " << i;

    // X8R8G8B8: the X byte of a mip is 0 whatever level 0 holds there; a volume's 8 taps:
    // B 0 x4 and 255 x4 (127.5 -> 128), G 3 x8 (3), R 0 x7 and 4 (0.5 -> 1).
    Texture v = Texture::create_volume(Format::X8R8G8B8, 2, 2, 2);
    auto& bytes = v.surface(0).bytes();
    for (unsigned texel = 0; texel < 8; ++texel) {
        bytes[4 * texel + 0] = static_cast<std::byte>(texel % 2 ? 255 : 0);
        bytes[4 * texel + 1] = std::byte{3};
        bytes[4 * texel + 2] = static_cast<std::byte>(texel == 7 ? 4 : 0);
        bytes[4 * texel + 3] = std::byte{0xFF};
    }
    v.generate_mips();
    const uint8_t volume_expected[4] = {128, 3, 1, 0};
    for (unsigned i = 0; i < 4; ++i)
        EXPECT_EQ(v.surface(1).bytes()[i], static_cast<std::byte>(volume_expected[i])) << "byte " << i;
}

// The byte path against the box filter written with Surface::read() and write() (the filter of
// every other format): 2D textures of odd and even sizes, cube maps and volumes of random
// bytes, every level the same bytes.
TEST(Texture, BoxFilterMipsOfBytesMatchTheFloatFilter) {
    std::mt19937 rng(20261203);
    const Format formats[] = {Format::A8R8G8B8, Format::X8R8G8B8, Format::A8B8G8R8, Format::X8B8G8R8, Format::A8};
    unsigned levels_compared = 0;
    for (unsigned round = 0; round < 40; ++round) {
        const Format format = formats[round % std::size(formats)];
        const unsigned kind = rng() % 3;
        // Powers of two (the sizes with mips), unequal sides: a side of 1 repeats its texel.
        const uint32_t w = 1u << rng() % 7, h = kind == 1 ? w : 1u << rng() % 7, d = 1u << rng() % 4;
        Texture t = kind == 0   ? Texture::create_2d(format, w, h)
                    : kind == 1 ? Texture::create_cube(format, w)
                                : Texture::create_volume(format, w, h, d);
        for (uint32_t f = 0; f < t.faces(); ++f)
            for (std::byte& b : t.surface(0, f).bytes()) b = static_cast<std::byte>(rng());
        Texture reference = t;
        t.generate_mips();
        for (uint32_t f = 0; f < t.faces(); ++f)
            for (uint32_t l = 1; l < t.levels(); ++l) {
                const Surface& src = reference.surface(l - 1, f);
                Surface& dst = reference.surface(l, f);
                const auto at = [](uint32_t i, uint32_t size) { return i < size ? i : size - 1; };
                const uint32_t zn = src.depth() > 1 ? 2 : 1;
                for (uint32_t z = 0; z < dst.depth(); ++z)
                    for (uint32_t y = 0; y < dst.height(); ++y)
                        for (uint32_t x = 0; x < dst.width(); ++x) {
                            Float4 sum{0, 0, 0, 0};
                            for (uint32_t dz = 0; dz < zn; ++dz)
                                for (uint32_t dy = 0; dy < 2; ++dy)
                                    for (uint32_t dx = 0; dx < 2; ++dx) {
                                        const Float4 tap = src.read(at(2 * x + dx, src.width()),
                                                                    at(2 * y + dy, src.height()), at(2 * z + dz, src.depth()));
                                        for (unsigned c = 0; c < 4; ++c) sum[c] += tap[c];
                                    }
                            for (float& c : sum) c *= 1.0f / static_cast<float>(4 * zn);
                            dst.write(x, y, z, sum);
                        }
                ASSERT_EQ(t.surface(l, f).bytes(), dst.bytes())
                    << "round " << round << ", " << w << "x" << h << " kind " << kind << ", face " << f << ", level " << l;
                ++levels_compared;
            }
    }
    EXPECT_GT(levels_compared, 200u);
}

}  // namespace
}  // namespace sm2::runtime
