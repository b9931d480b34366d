// Surfaces and textures: memory layout, level sizes, limits, box-filtered mips.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sm2::runtime
