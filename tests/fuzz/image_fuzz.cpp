// Fuzz target: bytes as an image file through the project's loaders: load_dds (from memory),
// load_texture (sm2 run --texture, LoadTexture) and read_image (sm2 diff), the file named by the
// format its first bytes claim (PNG, EXR, DDS, JPEG, HDR; TGA otherwise). Property: every input
// is read or refused with TextureIoError / ImageIoError; no crash, no allocation past the limits
// (run with -rss_limit_mb), no hang (-timeout).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>

#include "sm2/runtime/image_io.h"
#include "sm2/runtime/texture_io.h"

namespace {

std::string extension_for(const uint8_t* data, size_t size) {
    auto starts = [&](const char* magic, size_t n) { return size >= n && std::memcmp(data, magic, n) == 0; };
    if (starts("\x89PNG", 4)) return ".png";
    if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
    if (starts("DDS ", 4)) return ".dds";
    if (starts("\xff\xd8\xff", 3)) return ".jpg";
    if (starts("#?", 2)) return ".hdr";
    return ".tga";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace sm2::runtime;
    try {
        (void)load_dds(std::span<const std::byte>(reinterpret_cast<const std::byte*>(data), size), "fuzz");
    } catch (const TextureIoError&) {
    }
    // One file per process, rewritten for each input.
    static const std::string base = "/tmp/sm2_image_fuzz_" + std::to_string(getpid());
    const std::string path = base + extension_for(data, size);
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        if (size > 0) std::fwrite(data, 1, size, f);
        std::fclose(f);
    } else {
        return 0;
    }
    try {
        (void)load_texture(path);
    } catch (const TextureIoError&) {
    }
    try {
        (void)read_image(path, ImageReadLimits{.max_side = 4096, .max_bytes = uint64_t{64} << 20});
    } catch (const ImageIoError&) {
    }
    std::remove(path.c_str());
    return 0;
}
