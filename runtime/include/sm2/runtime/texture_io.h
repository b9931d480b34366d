// Textures from image files: PNG, TGA, JPEG, EXR, HDR (through OpenImageIO) and DDS (read
// here, so DXTn blocks and every D3DFORMAT keep their exact bits, with mip chains, cube faces
// and volumes). Errors throw TextureIoError with the file name and the reason; bad files
// never crash.
#pragma once

#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>

#include "sm2/runtime/texture.h"

namespace sm2::runtime {

class TextureIoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct TextureLoadOptions {
    // Build the full mip chain with the 2x2 box filter (Texture::generate_mips). For DDS files
    // this applies only when the file has a single level and an uncompressed format.
    bool generate_mips = false;
};

// Picks the reader by content (DDS magic "DDS ") and otherwise by OpenImageIO. Formats chosen
// for OIIO images (level 0, first subimage):
//   8-bit:  1 channel L8, 2 channels A8L8, 3 or 4 channels A8R8G8B8 (alpha 1 when absent)
//   16-bit unsigned: 1 channel L16, otherwise A16B16G16R16
//   half:   1 channel R16F, 2 G16R16F, otherwise A16B16G16R16F
//   float (and anything else): 1 channel R32F, 2 G32R32F, otherwise A32B32G32R32F
[[nodiscard]] Texture load_texture(const std::string& path, const TextureLoadOptions& options = {});

// A DDS file already in memory; `name` is used in error messages.
[[nodiscard]] Texture load_dds(std::span<const std::byte> file, const std::string& name = "DDS",
                               const TextureLoadOptions& options = {});

}  // namespace sm2::runtime
