// Image files through OpenImageIO, loaded only when a file is read or written.
//
// OpenImageIO pulls in about 200 shared libraries, which cost every process a quarter of a
// second to load: `sm2 asm` or `sm2 --version` must not pay for them. So the code that calls
// OpenImageIO lives in a module of its own (runtime/src/image_codec/oiio.cpp, built as
// sm2emu_image_io.so), and the runtime dlopen()s it on the first image read or write. The
// interface between the two is this table of functions; the module is built from the same
// sources with the same compiler, and kAbiVersion changes whenever the table does.
//
// Where the module is looked for: common/sm2_internal/module_loader.h ($SM2EMU_IMAGE_IO first).
#pragma once

#include <cstdint>
#include <string>

namespace sm2::runtime::image_codec {

constexpr uint32_t kAbiVersion = 3;

enum class PixelType : int { U8, U16, Half, Float, Other };

struct Info {
    int width = 0, height = 0, depth = 1, channels = 0;
    PixelType type = PixelType::Other;
};

enum class OpenStatus : int { Ok, NoReader, CannotOpen };

// ImageBufAlgo::compare's results for two float RGBA images (sm2 diff).
struct CompareStats {
    double mean_error = 0, rms_error = 0, psnr = 0, max_error = 0;
    int max_x = 0, max_y = 0, max_channel = 0;
    uint64_t warn_pixels = 0, fail_pixels = 0;
};

struct Functions {
    uint32_t abi_version;
    uint32_t size;  // sizeof(Functions)
    // Opens `path` for reading, alpha unassociated (values as stored). On failure: nullptr,
    // *status says whether no reader knows the file or the reader failed, *error why.
    void* (*open)(const char* path, Info* info, OpenStatus* status, std::string* error);
    // Reads subimage 0, level 0, the first `channels` channels (1 to Info::channels), as float.
    // False and *error on failure.
    bool (*read)(void* reader, int channels, float* pixels, std::string* error);
    void (*close)(void* reader);
    // Writes RGBA: 8-bit (`rgba` is uint8_t) or float (`rgba` is float), unassociated alpha, and
    // no wall-clock time in the file (a fixed DateTime): the same pixels give the same bytes.
    // False and *error ("no writer for this file: ...", "cannot open for writing: ...", "write
    // failed: ...") on failure.
    bool (*write)(const char* path, uint32_t width, uint32_t height, bool eight_bit, const void* rgba,
                  std::string* error);
    // Two float RGBA images of width x height: ImageBufAlgo::compare with these thresholds.
    bool (*compare)(uint32_t width, uint32_t height, const float* a, const float* b, float fail_threshold,
                    float warn_threshold, CompareStats* stats, std::string* error);
    // |a - b|, its largest channel divided by `scale`, through a black-to-red color_map: float
    // RGBA (alpha 1) into `heat` (width x height x 4).
    bool (*heatmap)(uint32_t width, uint32_t height, const float* a, const float* b, float scale, float* heat,
                    std::string* error);
    // The image resized to fit max_side x max_side, as an 8-bit PNG in memory, base64-encoded
    // into *base64 (for an HTML data: URI). `keep_peaks`: each thumbnail pixel is the largest of
    // the pixels it stands for (a heat map's lone differing pixels stay visible), else filtered.
    bool (*png_thumbnail)(uint32_t width, uint32_t height, const float* rgba, uint32_t max_side, bool keep_peaks,
                          std::string* base64, std::string* error);
};

// The module's functions, loaded on the first call (thread-safe). nullptr when the module cannot
// be loaded; `error` then says where it was looked for and why it failed.
const Functions* functions(std::string& error);

// A reader that closes itself.
class Reader {
public:
    Reader(const Functions* f, void* handle) : f_(f), handle_(handle) {}
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;
    ~Reader() {
        if (handle_) f_->close(handle_);
    }
    bool read(int channels, float* pixels, std::string& error) { return f_->read(handle_, channels, pixels, &error); }

private:
    const Functions* f_;
    void* handle_;
};

}  // namespace sm2::runtime::image_codec

// The module's one exported symbol.
extern "C" const sm2::runtime::image_codec::Functions* sm2emu_image_codec_v1();
