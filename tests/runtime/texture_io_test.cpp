// Loading textures: PNG and EXR written here through OpenImageIO, DDS files written by hand.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "sm2/runtime/texture_io.h"

namespace sm2::runtime {
namespace {

std::string temp_path(const std::string& name) {
    // the process id keeps parallel test runs (ctest -j, several build folders) apart
    return (std::filesystem::temp_directory_path() /
            ("sm2_texture_io_" + std::to_string(::getpid()) + "_" + name)).string();
}

void write_image(const std::string& path, int w, int h, int channels, OIIO::TypeDesc type, const void* data) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(w, h, channels, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store the values as given
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(type, data));
    out->close();
}

TEST(TextureIo, PngEightBitExact) {
    const std::string path = temp_path("a.png");
    // 2x2 RGBA: texel (1, 0) = (10, 20, 30, 40)
    const uint8_t px[16] = {0, 0, 0, 255, 10, 20, 30, 40, 255, 255, 255, 255, 1, 2, 3, 4};
    write_image(path, 2, 2, 4, OIIO::TypeDesc::UINT8, px);
    const Texture t = load_texture(path);
    EXPECT_EQ(t.format(), Format::A8R8G8B8);
    EXPECT_EQ(t.levels(), 1u);
    EXPECT_EQ(t.surface(0).read(1, 0), (Float4{10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 40 / 255.0f}));
    // A8R8G8B8 memory: B, G, R, A
    EXPECT_EQ(t.surface(0).bytes()[4], std::byte{30});
    EXPECT_EQ(t.surface(0).bytes()[7], std::byte{40});
    // Mip generation on request: level 1 = box average of the four texels
    const Texture m = load_texture(path, {.generate_mips = true});
    EXPECT_EQ(m.levels(), 2u);
    // red: (0 + 10 + 255 + 1) / 4 = 66.5 -> 67 (halves up)
    EXPECT_EQ(m.surface(1).read(0, 0)[0], 67 / 255.0f);
    std::filesystem::remove(path);
}

TEST(TextureIo, PngGreyAndExrFloat) {
    const std::string png = temp_path("g.png");
    const uint8_t grey[2] = {7, 200};
    write_image(png, 2, 1, 1, OIIO::TypeDesc::UINT8, grey);
    const Texture g = load_texture(png);
    EXPECT_EQ(g.format(), Format::L8);
    EXPECT_EQ(g.surface(0).read(1, 0), (Float4{200 / 255.0f, 200 / 255.0f, 200 / 255.0f, 1}));
    std::filesystem::remove(png);

    const std::string exr = temp_path("f.exr");
    const float rgba[8] = {1.5f, -2.0f, 65504.0f, 0.25f, 0, 0, 0, 1};
    write_image(exr, 2, 1, 4, OIIO::TypeDesc::FLOAT, rgba);
    const Texture f = load_texture(exr);
    EXPECT_EQ(f.format(), Format::A32B32G32R32F);
    EXPECT_EQ(f.surface(0).read(0, 0), (Float4{1.5f, -2.0f, 65504.0f, 0.25f}));
    std::filesystem::remove(exr);
}

TEST(TextureIo, TgaJpegHdr) {
    const uint8_t rgb[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
    const std::string tga = temp_path("c.tga");
    write_image(tga, 2, 2, 3, OIIO::TypeDesc::UINT8, rgb);
    const Texture t = load_texture(tga);
    EXPECT_EQ(t.format(), Format::A8R8G8B8);
    EXPECT_EQ(t.surface(0).read(1, 0), (Float4{0, 1, 0, 1}));  // alpha 1 when the file has none
    std::filesystem::remove(tga);

    const std::string jpg = temp_path("c.jpg");
    const uint8_t grey[64] = {};  // 8x8 black: lossless enough to compare exactly
    write_image(jpg, 8, 8, 1, OIIO::TypeDesc::UINT8, grey);
    const Texture j = load_texture(jpg);
    EXPECT_EQ(j.width(), 8u);
    EXPECT_NEAR(j.surface(0).read(3, 3)[0], 0.0f, 2 / 255.0f);
    std::filesystem::remove(jpg);

    const std::string hdr = temp_path("c.hdr");
    const float px[12] = {1, 2, 4, 0.5f, 0.25f, 0.125f, 8, 8, 8, 0, 0, 0};
    write_image(hdr, 2, 2, 3, OIIO::TypeDesc::FLOAT, px);
    const Texture h = load_texture(hdr);
    EXPECT_EQ(h.format(), Format::A32B32G32R32F);
    EXPECT_EQ(h.surface(0).read(0, 0), (Float4{1, 2, 4, 1}));  // RGBE holds powers of two exactly
    std::filesystem::remove(hdr);
}

TEST(TextureIo, BadImageFilesGiveErrors) {
    EXPECT_THROW((void)load_texture(temp_path("does_not_exist.png")), TextureIoError);
    const std::string junk = temp_path("junk.png");
    {
        // Not a PNG at all. (A PNG signature followed by garbage is refused too, but libpng's
        // longjmp inside OpenImageIO 2.4 leaks a 31-byte string, which LeakSanitizer reports.)
        std::ofstream(junk, std::ios::binary) << "this is not an image at all";
    }
    EXPECT_THROW((void)load_texture(junk), TextureIoError);
    std::filesystem::remove(junk);
}

// A DDS file by hand: "DDS ", 124-byte header, then the data face by face, level by level.
struct Dds {
    std::vector<std::byte> bytes = std::vector<std::byte>(128);
    void put(size_t at, uint32_t v) {
        for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::byte>(v >> (8 * i) & 0xFF);
    }
    void append(std::initializer_list<unsigned> data) {
        for (unsigned b : data) bytes.push_back(static_cast<std::byte>(b));
    }
    void append_n(size_t n, unsigned value) { bytes.insert(bytes.end(), n, static_cast<std::byte>(value)); }
    Dds(uint32_t w, uint32_t h, uint32_t levels) {
        put(0, 0x20534444);  // "DDS "
        put(4, 124);
        put(8, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000);  // CAPS HEIGHT WIDTH PIXELFORMAT MIPMAPCOUNT
        put(12, h);
        put(16, w);
        put(28, levels);
        put(76, 32);
        put(108, 0x1000 | 0x400000 | 0x8);  // TEXTURE MIPMAP COMPLEX
    }
    void fourcc(uint32_t f) { put(80, 0x4); put(84, f); }
    void rgb(uint32_t bits, uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
        put(80, 0x40 | (a ? 0x1 : 0));
        put(88, bits);
        put(92, r); put(96, g); put(100, b); put(104, a);
    }
};

TEST(TextureIo, DdsDxt1MipChain) {
    // 8x8 DXT1 with 4 levels: 8x8 (4 blocks), 4x4 (1), 2x2 (1 block), 1x1 (1 block)
    Dds f(8, 8, 4);
    f.fourcc(fourcc('D', 'X', 'T', '1'));
    f.append_n(4 * 8, 0);                                           // level 0: black
    f.append({0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xFF, 0x00, 0x55});     // level 1: the hand-decoded block
    f.append({0xE0, 0x07, 0xE0, 0x07, 0, 0, 0, 0});                 // level 2: green (c0 = c1 = 0x07E0)
    f.append({0x1F, 0x00, 0x1F, 0x00, 0xFF, 0xFF, 0xFF, 0xFF});     // level 3: index 3 = transparent
    const Texture t = load_dds(f.bytes);
    EXPECT_EQ(t.format(), Format::DXT1);
    EXPECT_EQ(t.levels(), 4u);
    EXPECT_EQ(t.surface(1).read(1, 0), (Float4{0, 0, 1, 1}));
    EXPECT_EQ(t.surface(1).read(2, 0), (Float4{170 / 255.0f, 0, 85 / 255.0f, 1}));
    EXPECT_EQ(t.surface(2).read(1, 1), (Float4{0, 1, 0, 1}));
    EXPECT_EQ(t.surface(3).read(0, 0), (Float4{0, 0, 0, 0}));
    // one byte short: a clear error
    Dds g = f;
    g.bytes.pop_back();
    EXPECT_THROW((void)load_dds(g.bytes), TextureIoError);
}

TEST(TextureIo, DdsCubeFacesAndUncompressed) {
    // 2x2 A8R8G8B8 cube, 2 levels: per face 2x2 then 1x1, texels (B, G, R, A) with R = face
    Dds f(2, 2, 2);
    f.rgb(32, 0x00FF0000, 0x0000FF00, 0x000000FF, 0xFF000000);
    f.put(112, 0x200 | 0xFC00);  // CUBEMAP, all faces
    for (unsigned face = 0; face < 6; ++face)
        for (int i = 0; i < 5; ++i) f.append({0, 0, face * 40, 255});
    const Texture t = load_dds(f.bytes);
    EXPECT_EQ(t.type(), TextureType::Cube);
    EXPECT_EQ(t.levels(), 2u);
    for (unsigned face = 0; face < 6; ++face) {
        EXPECT_EQ(t.surface(0, face).read(1, 1)[0], static_cast<float>(face * 40) / 255.0f);
        EXPECT_EQ(t.surface(1, face).read(0, 0)[0], static_cast<float>(face * 40) / 255.0f);
    }
    Dds partial = f;
    partial.put(112, 0x200 | 0x400);
    EXPECT_THROW((void)load_dds(partial.bytes), TextureIoError);
}

TEST(TextureIo, DdsVolumeAndFloatFourCC) {
    // 2x2x2 R16F volume (FourCC = D3DFMT value 111), one level; half 0x3C00 = 1, 0x4000 = 2
    Dds f(2, 2, 1);
    f.fourcc(111);
    f.put(8, 0x1 | 0x2 | 0x4 | 0x1000 | 0x800000);
    f.put(24, 2);
    f.put(112, 0x200000);
    for (int i = 0; i < 4; ++i) f.append({0x00, 0x3C});
    for (int i = 0; i < 4; ++i) f.append({0x00, 0x40});
    const Texture t = load_dds(f.bytes);
    EXPECT_EQ(t.type(), TextureType::Volume);
    EXPECT_EQ(t.format(), Format::R16F);
    EXPECT_EQ(t.surface(0).read(1, 1, 1), (Float4{2, 1, 1, 1}));
    EXPECT_EQ(t.surface(0).read(0, 0, 0), (Float4{1, 1, 1, 1}));
}

TEST(TextureIo, BadDdsHeadersNeverCrash) {
    Dds good(4, 4, 1);
    good.rgb(16, 0xF800, 0x07E0, 0x001F, 0);
    good.append_n(32, 0x11);
    EXPECT_EQ(load_dds(good.bytes).format(), Format::R5G6B5);
    auto expect_error = [](const std::vector<std::byte>& b, const char* what) {
        EXPECT_THROW((void)load_dds(b), TextureIoError) << what;
    };
    Dds m = good; m.put(0, 0x12345678); expect_error(m.bytes, "magic");
    Dds s = good; s.put(4, 100); expect_error(s.bytes, "header size");
    Dds w = good; w.put(16, 0); expect_error(w.bytes, "zero width");
    Dds big = good; big.put(16, 8192); expect_error(big.bytes, "too wide");
    Dds lv = good; lv.put(28, 9); expect_error(lv.bytes, "too many levels");
    Dds px = good; px.rgb(16, 0x1234, 0, 0, 0); expect_error(px.bytes, "unknown masks");
    Dds dx = good; dx.fourcc(fourcc('D', 'X', '1', '0')); expect_error(dx.bytes, "DX10");
    Dds np = good; np.put(16, 6); np.put(28, 2); expect_error(np.bytes, "NPOT with mips");
    // Every truncation of a valid file is an error, never a crash
    for (size_t n = 0; n < good.bytes.size(); ++n) {
        std::vector<std::byte> cut(good.bytes.begin(), good.bytes.begin() + static_cast<std::ptrdiff_t>(n));
        EXPECT_THROW((void)load_dds(cut), TextureIoError) << n;
    }
    // A DDS on disk goes through load_texture too
    const std::string path = temp_path("x.dds");
    {
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(good.bytes.data()), static_cast<std::streamsize>(good.bytes.size()));
    }
    EXPECT_EQ(load_texture(path).format(), Format::R5G6B5);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace sm2::runtime
