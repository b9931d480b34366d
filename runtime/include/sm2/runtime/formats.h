// D3DFORMAT: every texture, render-target, depth and index format, as data, with the exact bit
// layouts of pipeline.md §15 and the values a sampler returns for missing channels (§14.7).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace sm2::runtime {

using Float4 = std::array<float, 4>;  // r, g, b, a

constexpr uint32_t fourcc(char a, char b, char c, char d) {
    return static_cast<uint32_t>(static_cast<unsigned char>(a)) |
           static_cast<uint32_t>(static_cast<unsigned char>(b)) << 8 |
           static_cast<uint32_t>(static_cast<unsigned char>(c)) << 16 |
           static_cast<uint32_t>(static_cast<unsigned char>(d)) << 24;
}

// D3DFORMAT values (d3d9types.h).
enum class Format : uint32_t {
    Unknown = 0,
    R8G8B8 = 20, A8R8G8B8 = 21, X8R8G8B8 = 22, R5G6B5 = 23, X1R5G5B5 = 24, A1R5G5B5 = 25,
    A4R4G4B4 = 26, R3G3B2 = 27, A8 = 28, A8R3G3B2 = 29, X4R4G4B4 = 30, A2B10G10R10 = 31,
    A8B8G8R8 = 32, X8B8G8R8 = 33, G16R16 = 34, A2R10G10B10 = 35, A16B16G16R16 = 36,
    L8 = 50, A8L8 = 51, A4L4 = 52,
    V8U8 = 60, L6V5U5 = 61, X8L8V8U8 = 62, Q8W8V8U8 = 63, V16U16 = 64, A2W10V10U10 = 67,
    D16_LOCKABLE = 70, D32 = 71, D15S1 = 73, D24S8 = 75, D24X8 = 77, D24X4S4 = 79, D16 = 80,
    L16 = 81, D32F_LOCKABLE = 82, D24FS8 = 83,
    INDEX16 = 101, INDEX32 = 102,
    Q16W16V16U16 = 110, R16F = 111, G16R16F = 112, A16B16G16R16F = 113, R32F = 114,
    G32R32F = 115, A32B32G32R32F = 116,
    DXT1 = fourcc('D', 'X', 'T', '1'), DXT2 = fourcc('D', 'X', 'T', '2'),
    DXT3 = fourcc('D', 'X', 'T', '3'), DXT4 = fourcc('D', 'X', 'T', '4'),
    DXT5 = fourcc('D', 'X', 'T', '5'),
};

enum class FormatKind : uint8_t {
    Color,       // unsigned normalized or float colour
    Signed,      // V8U8, Q8W8V8U8, V16U16, ...: signed normalized (bump maps)
    Compressed,  // DXT1..5: 4x4 blocks
    Depth,       // D16, D24S8, ...
    Index,       // INDEX16/32
};

struct FormatInfo {
    Format format;
    std::string_view name;        // "A8R8G8B8" (D3DFMT_ prefix dropped)
    FormatKind kind;
    uint8_t bytes;                // per texel; per 4x4 block for compressed formats
    bool render_target;           // usable as a render target in sm2emu
    bool texture;                 // usable as a texture in sm2emu
    bool srgb;                    // honours SRGBTEXTURE / SRGBWRITEENABLE (8-bit RGB, DXT)
    uint8_t depth_bits;           // depth formats
    uint8_t stencil_bits;         // depth formats
};

[[nodiscard]] std::span<const FormatInfo> format_table();
[[nodiscard]] const FormatInfo* format_info(Format format);
// "A8R8G8B8" or "D3DFMT_A8R8G8B8"; nullptr if unknown.
[[nodiscard]] const FormatInfo* find_format(std::string_view name);

// A format's texel conversions as plain functions, for loops over many texels of one format
// (nullptr for formats without a texel layout: DXTn, D24FS8, Unknown). Same results as
// decode_texel / encode_texel.
using TexelDecoder = Float4 (*)(const std::byte* texel);
using TexelEncoder = void (*)(const Float4& value, std::byte* texel);
[[nodiscard]] TexelDecoder texel_decoder(Format format);
[[nodiscard]] TexelEncoder texel_encoder(Format format);

// One texel of an uncompressed colour format -> the value a sampler returns, with the missing
// channels filled per §14.7 (L8 -> (l,l,l,1), A8 -> (0,0,0,a), R32F -> (r,1,1,1), ...).
[[nodiscard]] Float4 decode_texel(Format format, const std::byte* texel);
// Float4 -> one texel, with D3D9's conversion for render targets and uploads: unorm channels
// clamped to [0,1] and rounded to nearest (round(c * (2^n - 1))), float channels converted with
// round-to-nearest-even (half) or stored as is (float), channels the format lacks dropped.
void encode_texel(Format format, const Float4& value, std::byte* texel);
// A 4x4 block of DXT1..5 -> 16 texels, row-major (texel (x, y) at index 4y + x).
void decode_block(Format format, const std::byte* block, std::array<Float4, 16>& texels);

// The sRGB curves of pipeline.md §12 (evaluated in double, rounded to float once).
[[nodiscard]] float srgb_to_linear(float c);
[[nodiscard]] float linear_to_srgb(float c);

}  // namespace sm2::runtime
