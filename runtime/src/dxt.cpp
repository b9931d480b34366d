// DXT1..DXT5 decoders (our own code, from the block layouts of pipeline.md §15).
//
// Rounding (one rule everywhere, the docs' integer reference):
//   5/6-bit endpoints expand to 8 bits by bit replication: (c << 3) | (c >> 2), (c << 2) | (c >> 4)
//   4-colour block:   p2 = (2*c0 + c1 + 1) / 3,  p3 = (c0 + 2*c1 + 1) / 3   per 8-bit channel
//   3-colour (DXT1):  p2 = (c0 + c1 + 1) / 2,    p3 = transparent black (0, 0, 0, 0)
//   DXT4/5 alpha:     a0 > a1: a_k = ((8-k)*a0 + (k-1)*a1 + 3) / 7, k = 2..7
//                     else    : a_k = ((6-k)*a0 + (k-1)*a1 + 2) / 5, k = 2..5; a6 = 0, a7 = 255
//   DXT2/3 alpha:     a4 * 17 (so the float is exactly a4 / 15)
// (integer division; the float a sampler returns is the 8-bit value / 255). DXT2 and DXT4 hold
// colour premultiplied by alpha; like D3D9 the decoder returns the stored (premultiplied) colour.
#include "dxt.h"


namespace sm2::runtime::dxt {

using namespace detail;  // load16, expand565, mix3, ... (dxt.h)

namespace {

// The colour palette of an 8-byte colour block. `three_colour_allowed`: DXT1 only.
std::array<Rgba8, 4> colour_palette(const std::byte* block, bool three_colour_allowed) {
    const uint16_t c0 = load16(block), c1 = load16(block + 2);
    const Rgba8 p0 = expand565(c0), p1 = expand565(c1);
    std::array<Rgba8, 4> p{p0, p1, {}, {}};
    if (c0 > c1 || !three_colour_allowed) {
        p[2] = {mix3(p0.r, p1.r), mix3(p0.g, p1.g), mix3(p0.b, p1.b), 255};
        p[3] = {mix3(p1.r, p0.r), mix3(p1.g, p0.g), mix3(p1.b, p0.b), 255};
    } else {
        p[2] = {mix2(p0.r, p1.r), mix2(p0.g, p1.g), mix2(p0.b, p1.b), 255};
        p[3] = {0, 0, 0, 0};
    }
    return p;
}

std::array<uint8_t, 8> alpha_palette(const std::byte* block) {
    const unsigned a0 = static_cast<uint8_t>(block[0]), a1 = static_cast<uint8_t>(block[1]);
    std::array<uint8_t, 8> a{static_cast<uint8_t>(a0), static_cast<uint8_t>(a1)};
    if (a0 > a1) {
        for (unsigned k = 2; k < 8; ++k) a[k] = static_cast<uint8_t>(((8 - k) * a0 + (k - 1) * a1 + 3) / 7);
    } else {
        for (unsigned k = 2; k < 6; ++k) a[k] = static_cast<uint8_t>(((6 - k) * a0 + (k - 1) * a1 + 2) / 5);
        a[6] = 0;
        a[7] = 255;
    }
    return a;
}



}  // namespace

void decode_block(Format format, const std::byte* block, std::array<Rgba8, 16>& texels) {
    const bool dxt1 = format == Format::DXT1;
    const std::byte* colour = dxt1 ? block : block + 8;
    const auto palette = colour_palette(colour, dxt1);
    const uint32_t indices = load32(colour + 4);
    for (unsigned i = 0; i < 16; ++i) texels[i] = palette[indices >> (2 * i) & 3u];
    if (format == Format::DXT2 || format == Format::DXT3) {
        for (unsigned i = 0; i < 16; ++i) texels[i].a = static_cast<uint8_t>(explicit_alpha(block, i));
    } else if (format == Format::DXT4 || format == Format::DXT5) {
        const auto alphas = alpha_palette(block);
        const uint64_t bits = alpha_indices(block);
        for (unsigned i = 0; i < 16; ++i) texels[i].a = alphas[bits >> (3 * i) & 7u];
    }
}

}  // namespace sm2::runtime::dxt
