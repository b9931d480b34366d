// image_io: surfaces written to PNG/EXR/raw and read back, and the image comparison metrics,
// with every expected value worked out by hand.
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/texture_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace sm2::runtime {
namespace {

namespace fs = std::filesystem;

// One folder per test process (ctest runs tests in parallel processes).
class ImageIo : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("sm2_image_io_" + std::to_string(getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }

private:
    fs::path dir_;
};

// A8R8G8B8 texels are stored B, G, R, A in memory.
void put_argb(Surface& s, uint32_t x, uint32_t y, uint8_t a, uint8_t r, uint8_t g, uint8_t b) {
    std::byte* p = s.bytes().data() + y * s.row_pitch() + x * 4;
    p[0] = std::byte{b};
    p[1] = std::byte{g};
    p[2] = std::byte{r};
    p[3] = std::byte{a};
}

void expect_pixel(const Image& image, uint32_t x, uint32_t y, float r, float g, float b, float a) {
    const float* p = &image.rgba[(size_t{y} * image.width + x) * 4];
    EXPECT_FLOAT_EQ(p[0], r) << "pixel " << x << "," << y;
    EXPECT_FLOAT_EQ(p[1], g) << "pixel " << x << "," << y;
    EXPECT_FLOAT_EQ(p[2], b) << "pixel " << x << "," << y;
    EXPECT_FLOAT_EQ(p[3], a) << "pixel " << x << "," << y;
}

Image make_image(uint32_t width, uint32_t height, std::vector<float> rgba) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba = std::move(rgba);
    return image;
}

TEST_F(ImageIo, PngKeepsEightBitValuesAndUnassociatedAlpha) {
    Surface s(Format::A8R8G8B8, 2, 2);
    put_argb(s, 0, 0, 0xFF, 0x33, 0x66, 0x99);
    put_argb(s, 1, 0, 0x80, 0x40, 0x00, 0xFF);  // half alpha: colour must not be premultiplied
    put_argb(s, 0, 1, 0x00, 0x01, 0x02, 0x03);
    put_argb(s, 1, 1, 0xFE, 0xFF, 0xFF, 0xFF);
    write_surface(s, path("a.png"));
    const Image image = read_image(path("a.png"));
    ASSERT_EQ(image.width, 2u);
    ASSERT_EQ(image.height, 2u);
    expect_pixel(image, 0, 0, 51.0f / 255, 102.0f / 255, 153.0f / 255, 1.0f);
    expect_pixel(image, 1, 0, 64.0f / 255, 0.0f, 1.0f, 128.0f / 255);
    expect_pixel(image, 0, 1, 1.0f / 255, 2.0f / 255, 3.0f / 255, 0.0f);
    expect_pixel(image, 1, 1, 1.0f, 1.0f, 1.0f, 254.0f / 255);
}

TEST_F(ImageIo, PngOfALuminanceSurfaceIsGreyWithOpaqueAlpha) {
    Surface s(Format::L8, 1, 1);
    s.bytes()[0] = std::byte{200};
    write_surface(s, path("l.png"));
    const Image image = read_image(path("l.png"));
    expect_pixel(image, 0, 0, 200.0f / 255, 200.0f / 255, 200.0f / 255, 1.0f);
}

TEST_F(ImageIo, PngClampsFloatSurfacesAndRoundsToNearest) {
    Surface s(Format::A32B32G32R32F, 1, 1);
    // 2 -> 1, -1 -> 0, 0.5 -> round(127.5) = 128, 0.1 -> round(25.5) = 26
    s.write(0, 0, 0, Float4{2.0f, -1.0f, 0.5f, 0.1f});
    write_surface(s, path("f.png"));
    expect_pixel(read_image(path("f.png")), 0, 0, 1.0f, 0.0f, 128.0f / 255, 26.0f / 255);
}

TEST_F(ImageIo, ExrKeepsFloatValuesOutsideZeroToOne) {
    Surface s(Format::A32B32G32R32F, 2, 1);
    s.write(0, 0, 0, Float4{0.25f, -2.5f, 1000.0f, 1.0f});
    s.write(1, 0, 0, Float4{3.0f, 0.0f, -0.125f, 0.5f});
    write_surface(s, path("f.exr"));
    const Image image = read_image(path("f.exr"));
    ASSERT_EQ(image.width, 2u);
    ASSERT_EQ(image.height, 1u);
    expect_pixel(image, 0, 0, 0.25f, -2.5f, 1000.0f, 1.0f);
    expect_pixel(image, 1, 0, 3.0f, 0.0f, -0.125f, 0.5f);
}

TEST_F(ImageIo, RawIsLittleEndianFloatRgbaRowMajor) {
    Surface s(Format::A8R8G8B8, 2, 1);
    put_argb(s, 0, 0, 0xFF, 0xFF, 0x00, 0x00);  // red
    put_argb(s, 1, 0, 0x00, 0x00, 0x00, 0xFF);  // blue, alpha 0
    write_surface(s, path("s.raw"));
    std::ifstream in(path("s.raw"), std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(bytes.size(), 2u * 4u * 4u);
    // 1.0f = 0x3F800000 -> bytes 00 00 80 3F
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x00);
    EXPECT_EQ(static_cast<unsigned char>(bytes[2]), 0x80);
    EXPECT_EQ(static_cast<unsigned char>(bytes[3]), 0x3F);
    std::vector<float> values(8);
    for (size_t i = 0; i < 8; ++i) {
        uint32_t bits = 0;
        for (size_t b = 0; b < 4; ++b) bits |= uint32_t{static_cast<unsigned char>(bytes[i * 4 + b])} << (8 * b);
        values[i] = std::bit_cast<float>(bits);
    }
    EXPECT_EQ(values, (std::vector<float>{1, 0, 0, 1, 0, 0, 1, 0}));
}

TEST_F(ImageIo, UnknownExtensionAndRawReadAreErrorsNamingThePath) {
    Surface s(Format::A8R8G8B8, 1, 1);
    try {
        write_surface(s, path("x.bmpx"));
        FAIL() << "no error";
    } catch (const ImageIoError& e) {
        EXPECT_NE(std::string(e.what()).find("x.bmpx"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)read_image(path("x.raw")), ImageIoError);
    EXPECT_THROW((void)read_image(path("missing.png")), ImageIoError);
    EXPECT_FALSE(fs::exists(path("x.bmpx")));
}

TEST(CompareImages, IdenticalImagesHaveNoErrorAndInfinitePsnr) {
    const Image a = make_image(2, 1, {0.1f, 0.2f, 0.3f, 1, 0.5f, 0.5f, 0.5f, 0.5f});
    const ImageDifference d = compare_images(a, a);
    EXPECT_EQ(d.max_abs_error, 0.0);
    EXPECT_EQ(d.mean_abs_error, 0.0);
    EXPECT_TRUE(std::isinf(d.psnr_db) && d.psnr_db > 0);
    EXPECT_EQ(d.differing_pixels, 0u);
}

TEST(CompareImages, MetricsWorkedOutByHand) {
    const Image a = make_image(2, 1, {0, 0, 0, 0, 0, 0, 0, 0});
    const Image b = make_image(2, 1, {0.5f, 0, 0, 0, 0, 0.25f, 0, 0});
    const ImageDifference d = compare_images(a, b);
    // errors over 8 channels: 0.5 and 0.25, the rest 0
    EXPECT_DOUBLE_EQ(d.max_abs_error, 0.5);
    EXPECT_DOUBLE_EQ(d.mean_abs_error, 0.75 / 8);  // 0.09375
    // MSE = (0.25 + 0.0625) / 8 = 0.0390625; PSNR = 10 log10(1 / MSE) = 10 log10(25.6)
    EXPECT_NEAR(d.psnr_db, 14.0823996531, 1e-9);
    EXPECT_EQ(d.differing_pixels, 2u);
    // A tolerance of 0.3 forgives the 0.25 but not the 0.5.
    EXPECT_EQ(compare_images(a, b, 0.3).differing_pixels, 1u);
    // The tolerance is a bound, not a strict one: an error equal to it is allowed.
    EXPECT_EQ(compare_images(a, b, 0.5).differing_pixels, 0u);
}

TEST(CompareImages, NanAgainstNanIsEqualNanAgainstANumberIsInfinitelyWrong) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Image a = make_image(1, 2, {nan, 0, 0, 1, nan, 0, 0, 1});
    const Image b = make_image(1, 2, {nan, 0, 0, 1, 0.0f, 0, 0, 1});
    const ImageDifference d = compare_images(a, b, 1.0);
    EXPECT_TRUE(std::isinf(d.max_abs_error));
    EXPECT_EQ(d.worst_x, 0u);
    EXPECT_EQ(d.worst_y, 1u);
    EXPECT_EQ(d.worst_channel, 0u);
    // ImageBufAlgo::compare leaves the non-finite channel out of the counts and means; the
    // infinite max error fails through the hard-fail threshold.
    EXPECT_EQ(d.differing_pixels, 0u);
    EXPECT_EQ(d.mean_abs_error, 0.0);
    EXPECT_EQ(diff_verdict(d, DiffThresholds{1.0, 1.0}), DiffVerdict::Failure);
}

TEST(CompareImages, WorstPixelRmsAndWarnings) {
    // 2x2; errors: (1,0) green 0.25, (0,1) alpha 0.125, (1,1) blue 0.5
    const Image a = make_image(2, 2, std::vector<float>(16, 0.0f));
    Image b = a;
    b.rgba[1 * 4 + 1] = 0.25f;
    b.rgba[2 * 4 + 3] = 0.125f;
    b.rgba[3 * 4 + 2] = 0.5f;
    const ImageDifference d = compare_images(a, b, DiffThresholds{0.3, 0.2});
    EXPECT_EQ(d.pixels, 4u);
    EXPECT_DOUBLE_EQ(d.max_abs_error, 0.5);
    EXPECT_EQ(d.worst_x, 1u);
    EXPECT_EQ(d.worst_y, 1u);
    EXPECT_EQ(d.worst_channel, 2u);
    // RMS = sqrt((0.0625 + 0.015625 + 0.25) / 16) = sqrt(0.0205078125); PSNR = 20 log10(1 / RMS)
    EXPECT_NEAR(d.rms_error, 0.143205, 1e-6);
    EXPECT_NEAR(d.psnr_db, 16.88, 0.005);
    EXPECT_EQ(d.warning_pixels, 2u);    // 0.25 and 0.5 are over 0.2
    EXPECT_EQ(d.differing_pixels, 1u);  // 0.5 only is over 0.3
    EXPECT_EQ(diff_verdict(d, DiffThresholds{0.3, 0.2}), DiffVerdict::Failure);
    EXPECT_EQ(diff_verdict(d, DiffThresholds{0.3, 0.2, 25.0}), DiffVerdict::Warning);  // 1 of 4 allowed
    EXPECT_EQ(diff_verdict(d, DiffThresholds{0.3, 0.2, 25.0, 0.4}), DiffVerdict::Failure);
    EXPECT_EQ(diff_verdict(compare_images(a, b, DiffThresholds{0.6, 0.2}), DiffThresholds{0.6, 0.2}), DiffVerdict::Warning);
    EXPECT_EQ(diff_verdict(compare_images(a, b, 0.5), DiffThresholds{0.5, 0.5}), DiffVerdict::Pass);
    EXPECT_STREQ(to_string(DiffVerdict::Warning), "WARNING");
}

TEST(CompareImages, SizeMismatchIsAnError) {
    const Image a = make_image(2, 1, std::vector<float>(8, 0.0f));
    const Image b = make_image(1, 1, std::vector<float>(4, 0.0f));
    try {
        (void)compare_images(a, b);
        FAIL() << "no error";
    } catch (const ImageIoError& e) {
        EXPECT_STREQ(e.what(), "image sizes differ: 2x1 and 1x1");
    }
    EXPECT_THROW((void)difference_heatmap(a, b, 1.0), ImageIoError);
}

TEST(CompareImages, HeatmapIsRedScaledByTheLargestChannelError) {
    const Image a = make_image(3, 1, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
    // errors: pixel 0 max 0.5 (blue), pixel 1 max 0.25 (alpha), pixel 2 none
    const Image b = make_image(3, 1, {0.1f, 0, 0.5f, 1, 0, 0, 0, 0.75f, 0, 0, 0, 1});
    const Image map = difference_heatmap(a, b, 0.5);
    ASSERT_EQ(map.width, 3u);
    expect_pixel(map, 0, 0, 1.0f, 0, 0, 1);
    expect_pixel(map, 1, 0, 0.5f, 0, 0, 1);
    expect_pixel(map, 2, 0, 0.0f, 0, 0, 1);
    // errors beyond the scale saturate at full red
    expect_pixel(difference_heatmap(a, b, 0.25), 0, 0, 1.0f, 0, 0, 1);
    EXPECT_THROW((void)difference_heatmap(a, b, 0.0), ImageIoError);
}

TEST_F(ImageIo, PngThumbnailIsAShrunkPng) {
    Image big = make_image(300, 150, std::vector<float>(300 * 150 * 4, 1.0f));
    const std::string base64 = png_thumbnail_base64(big, 100);
    EXPECT_EQ(base64.rfind("iVBORw0KGgo", 0), 0u) << base64.substr(0, 16);  // "\x89PNG\r\n\x1a\n"
    // PNG's IHDR: width and height big-endian at bytes 16-23; 300x150 fits 100x100 as 100x50.
    // Bytes 15-23 ('R' of "IHDR", 00 00 00 64, 00 00 00 32) are base64 characters 20-31.
    EXPECT_EQ(base64.substr(20, 12), "UgAAAGQAAAAy") << base64.substr(0, 40);
}

// RFC 4648 base64 back to bytes, to read a thumbnail (the library has the encoder only).
std::string base64_decode(const std::string& text) {
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string bytes;
    uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        const size_t v = alphabet.find(c);
        if (v == std::string::npos) break;  // '=' padding
        bits = (bits << 6) | static_cast<uint32_t>(v);
        count += 6;
        if (count >= 8) {
            count -= 8;
            bytes += static_cast<char>((bits >> count) & 0xFF);
        }
    }
    return bytes;
}

TEST_F(ImageIo, HeatmapThumbnailKeepsALonePixel) {
    // 300x150 black, one red pixel at (151, 76): shrunk 3 times to 100x50, a filter averages it
    // away; keeping peaks makes thumbnail pixel (50, 25) (source pixels 150-152, 75-77) red.
    Image heat = make_image(300, 150, std::vector<float>(300 * 150 * 4, 0.0f));
    for (size_t i = 3; i < heat.rgba.size(); i += 4) heat.rgba[i] = 1.0f;
    heat.rgba[(76 * 300 + 151) * 4] = 1.0f;
    auto thumbnail = [&](bool keep_peaks) {
        std::ofstream(path("thumb.png"), std::ios::binary) << base64_decode(png_thumbnail_base64(heat, 100, keep_peaks));
        return read_image(path("thumb.png"));
    };
    const Image peaks = thumbnail(true);
    ASSERT_EQ(peaks.width, 100u);
    ASSERT_EQ(peaks.height, 50u);
    expect_pixel(peaks, 50, 25, 1.0f, 0, 0, 1);
    expect_pixel(peaks, 10, 10, 0.0f, 0, 0, 1);
    const Image filtered = thumbnail(false);
    EXPECT_LT(filtered.rgba[(25 * 100 + 50) * 4], 0.5f);
}

TEST_F(ImageIo, WriteImageThenReadImageRoundTripsAHeatmap) {
    const Image map = make_image(2, 1, {1.0f, 0, 0, 1, 0.5f, 0, 0, 1});
    write_image(map, path("h.png"));
    const Image back = read_image(path("h.png"));
    expect_pixel(back, 0, 0, 1.0f, 0, 0, 1);
    expect_pixel(back, 1, 0, 128.0f / 255, 0, 0, 1);  // round(0.5 * 255) = round(127.5) = 128
}

// ---------------------------------------------------------------------------------------------
// Bad files: the reproducers of tests/fuzz/corpus/images, each a few bytes asking for gigabytes
// (or overflowing a size), are refused from their headers before any pixel is allocated, by
// read_image (sm2 diff) and load_texture (sm2 run --texture, LoadTexture) alike.

const std::string kImages = std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/images/";

std::string read_error(const std::string& path) {
    try {
        (void)read_image(path);
    } catch (const ImageIoError& e) {
        return e.what();
    }
    return "no error";
}
std::string texture_error(const std::string& path) {
    try {
        (void)load_texture(path);
    } catch (const TextureIoError& e) {
        return e.what();
    }
    return "no error";
}

TEST(ImageLimits, AbsurdHeadersAreRefusedBeforeAllocating) {
    struct Case {
        const char* file;
        const char* diff_error;     // read_image
        const char* texture_error;  // load_texture
    };
    const Case cases[] = {
        {"big.png", "100000x100000 is larger than 16384 pixels per side", "larger than 4096 texels per side"},
        {"big.tga", "65535x65535 is larger than 16384 pixels per side", "larger than 4096 texels per side"},
        {"wide.exr", "1048576x1 is larger than 16384 pixels per side", "larger than 4096 texels per side"},
        // DDS goes through the project's reader in both
        {"tall.dds", "size 4x2147483647x1 outside 1..4096", "size 4x2147483647x1 outside 1..4096"},
        {"dxt.dds", "size 65536x65536x1 outside 1..4096", "size 65536x65536x1 outside 1..4096"},
        {"mut.dds", "unsupported pixel format (flags 0x20041, 4294967295 bits)",
         "unsupported pixel format (flags 0x20041, 4294967295 bits)"},
    };
    for (const Case& c : cases) {
        const std::string path = kImages + c.file;
        EXPECT_EQ(read_error(path), path + ": " + c.diff_error) << c.file;
        EXPECT_EQ(texture_error(path), path + ": " + c.texture_error) << c.file;
    }
}

TEST(ImageLimits, OnlyFourOfAnExrsManyChannelsAreRead) {
    // 2x1, 300 half channels c0000..c0299: c0000 = 1, the others 0.5.
    const Image image = read_image(kImages + "many_channels.exr");
    ASSERT_EQ(image.width, 2u);
    ASSERT_EQ(image.height, 1u);
    EXPECT_EQ(image.rgba, (std::vector<float>{1, 0.5f, 0.5f, 0.5f, 1, 0.5f, 0.5f, 0.5f}));
    const Texture t = load_texture(kImages + "many_channels.exr");
    EXPECT_EQ(t.format(), Format::A16B16G16R16F);
    EXPECT_EQ(t.surface(0).read(1, 0), (Float4{1, 0.5f, 0.5f, 0.5f}));
}

TEST_F(ImageIo, LimitsAreCheckedAgainstTheHeader) {
    write_image(make_image(64, 32, std::vector<float>(64 * 32 * 4, 0.25f)), path("a.png"));
    EXPECT_EQ(read_image(path("a.png"), {.max_side = 64, .max_bytes = 64 * 32 * 16}).width, 64u);
    try {
        (void)read_image(path("a.png"), {.max_side = 63});
        ADD_FAILURE() << "no error";
    } catch (const ImageIoError& e) {
        EXPECT_EQ(std::string(e.what()), path("a.png") + ": 64x32 is larger than 63 pixels per side");
    }
    try {
        (void)read_image(path("a.png"), {.max_side = 64, .max_bytes = 64 * 32 * 16 - 1});
        ADD_FAILURE() << "no error";
    } catch (const ImageIoError& e) {
        EXPECT_EQ(std::string(e.what()),
                  path("a.png") + ": 64x32 needs 32768 bytes as float RGBA, more than the 32767-byte limit");
    }
}

TEST_F(ImageIo, DirectoriesAndDevicesAreNotImages) {
    fs::create_directories(path("folder.png"));
    EXPECT_EQ(read_error(path("folder.png")), path("folder.png") + ": is a directory");
    EXPECT_EQ(texture_error(path("folder.png")), path("folder.png") + ": is a directory");
    EXPECT_EQ(read_error("/dev/zero"), "/dev/zero: is a character device, not a regular file");
    EXPECT_EQ(texture_error("/dev/zero"), "/dev/zero: is a character device, not a regular file");
}

// EXR files carry no wall-clock time: the same surface gives the same bytes (capDate fixed).
TEST_F(ImageIo, ExrFilesAreByteReproducible) {
    const Image image = make_image(2, 1, {1.5f, -2, 0, 1, 0.25f, 0, 0, 1});
    write_image(image, path("a.exr"));
    const auto slurp = [](const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    const std::string first = slurp(path("a.exr"));
    EXPECT_NE(first.find("capDate"), std::string::npos);
    EXPECT_NE(first.find("1970:01:01 00:00:00"), std::string::npos);
    write_image(image, path("b.exr"));
    EXPECT_EQ(slurp(path("b.exr")), first);
}

}  // namespace
}  // namespace sm2::runtime
