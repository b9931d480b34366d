// Private: DXT1..DXT5 (BC1..BC3) block decoding (pipeline.md §15). Results are 8-bit RGBA, the
// precision of the block's palette; rounding rules are in dxt.cpp and docs/texturing.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "sm2/runtime/formats.h"

namespace sm2::runtime::dxt {

struct Rgba8 {
    uint8_t r = 0, g = 0, b = 0, a = 0;
};

[[nodiscard]] constexpr bool is_dxt(Format f) {
    return f == Format::DXT1 || f == Format::DXT2 || f == Format::DXT3 || f == Format::DXT4 ||
           f == Format::DXT5;
}
[[nodiscard]] constexpr unsigned block_bytes(Format f) { return f == Format::DXT1 ? 8u : 16u; }

// All 16 texels, texel (x, y) at index 4y + x.
void decode_block(Format format, const std::byte* block, std::array<Rgba8, 16>& texels);

namespace detail {
inline uint16_t load16(const std::byte* p) {
    return static_cast<uint16_t>(static_cast<unsigned>(p[0]) | static_cast<unsigned>(p[1]) << 8);
}

inline uint32_t load32(const std::byte* p) {
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
           static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

inline Rgba8 expand565(uint16_t c) {
    const unsigned r = c >> 11 & 31u, g = c >> 5 & 63u, b = c & 31u;
    return {static_cast<uint8_t>(r << 3 | r >> 2), static_cast<uint8_t>(g << 2 | g >> 4),
            static_cast<uint8_t>(b << 3 | b >> 2), 255};
}

inline uint8_t mix3(unsigned a, unsigned b) { return static_cast<uint8_t>((2 * a + b + 1) / 3); }

inline uint8_t mix2(unsigned a, unsigned b) { return static_cast<uint8_t>((a + b + 1) / 2); }

inline uint64_t alpha_indices(const std::byte* block) {
    uint64_t v = 0;
    for (unsigned i = 8; i-- > 2;) v = v << 8 | static_cast<uint8_t>(block[i]);
    return v;
}

inline unsigned explicit_alpha(const std::byte* block, unsigned i) {
    const unsigned byte = static_cast<uint8_t>(block[i / 2]);
    return (i & 1u ? byte >> 4 : byte & 15u) * 17u;
}
}  // namespace detail

// One texel (x, y in 0..3) of a block (inline: the sampler's inner loop).
[[nodiscard]] inline Rgba8 decode_texel(Format format, const std::byte* block, unsigned x, unsigned y) {
    // The same palette rules as decode_block, computing only the entry the texel uses.
    const unsigned i = 4 * y + x;
    const bool dxt1 = format == Format::DXT1;
    const std::byte* colour = dxt1 ? block : block + 8;
    const uint16_t c0 = detail::load16(colour), c1 = detail::load16(colour + 2);
    const unsigned index = detail::load32(colour + 4) >> (2 * i) & 3u;
    Rgba8 texel;
    if (index < 2) {
        texel = detail::expand565(index == 0 ? c0 : c1);
    } else {
        const Rgba8 p0 = detail::expand565(c0), p1 = detail::expand565(c1);
        if (c0 > c1 || !dxt1) {
            texel = index == 2 ? Rgba8{detail::mix3(p0.r, p1.r), detail::mix3(p0.g, p1.g), detail::mix3(p0.b, p1.b), 255}
                               : Rgba8{detail::mix3(p1.r, p0.r), detail::mix3(p1.g, p0.g), detail::mix3(p1.b, p0.b), 255};
        } else {
            texel = index == 2 ? Rgba8{detail::mix2(p0.r, p1.r), detail::mix2(p0.g, p1.g), detail::mix2(p0.b, p1.b), 255} : Rgba8{0, 0, 0, 0};
        }
    }
    if (format == Format::DXT2 || format == Format::DXT3) {
        texel.a = static_cast<uint8_t>(detail::explicit_alpha(block, i));
    } else if (format == Format::DXT4 || format == Format::DXT5) {
        const unsigned a0 = static_cast<uint8_t>(block[0]), a1 = static_cast<uint8_t>(block[1]);
        const unsigned k = static_cast<unsigned>(detail::alpha_indices(block) >> (3 * i) & 7u);
        unsigned a;
        if (k == 0) a = a0;
        else if (k == 1) a = a1;
        else if (a0 > a1) a = ((8 - k) * a0 + (k - 1) * a1 + 3) / 7;
        else if (k < 6) a = ((6 - k) * a0 + (k - 1) * a1 + 2) / 5;
        else a = k == 6 ? 0 : 255;
        texel.a = static_cast<uint8_t>(a);
    }
    return texel;
}

[[nodiscard]] inline Float4 to_float(Rgba8 c) {
    return {static_cast<float>(c.r) / 255.0f, static_cast<float>(c.g) / 255.0f,
            static_cast<float>(c.b) / 255.0f, static_cast<float>(c.a) / 255.0f};
}

}  // namespace sm2::runtime::dxt
