// Private: the channel layout of every uncompressed D3DFORMAT (pipeline.md §15), from which the
// texel decoders and encoders in formats.cpp are generated, and the decoder lookup the sampler
// uses to pick one function per texture instead of a switch per texel.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "half.h"
#include "sm2/runtime/formats.h"

namespace sm2::runtime {

// 256 entries: srgb_to_linear(i / 255).
[[nodiscard]] const std::array<float, 256>& srgb_to_linear_table();

// The sRGB write of an 8-bit field, byte(v) = layout::encode's round(255 linear_to_srgb(v)) for
// v in [0, 1], as thresholds: entry k (1-255) is the least float v in [0, 1] with byte(v) >= k
// (entry 0 is 0), so byte(v) is the number of entries 1-255 at or below v. byte is
// non-decreasing in v (linear_to_srgb is: its pieces are monotonic, glibc's pow is correctly
// rounded, and the curve steps up where they meet; every float in [0, 1] was checked once, see
// docs/performance.md), which makes the search and the thresholds exact.
[[nodiscard]] const std::array<float, 256>& linear_to_srgb_byte_thresholds();

// byte(v) of linear_to_srgb_byte_thresholds() for v in [0, 1], by binary search.
[[nodiscard]] inline uint32_t linear_to_srgb_byte(float v, const std::array<float, 256>& thresholds) {
    uint32_t k = 0;
    for (uint32_t step = 128; step != 0; step >>= 1) k += v >= thresholds[k + step] ? step : 0;
    return k;
}

namespace layout {

enum class Type : uint8_t {
    Zero,   // channel the format lacks, reads 0 (A8's colour)
    One,    // channel the format lacks, reads 1
    Unorm,  // v / (2^n - 1)
    Snorm,  // max(v / (2^(n-1) - 1), -1), v two's complement
    Half,   // IEEE binary16
    Float,  // IEEE binary32
    Uint,   // the raw integer as a float (stencil bits, indices)
};

struct Channel {
    Type type = Type::One;
    uint8_t shift = 0;  // lowest bit of the channel in the little-endian texel
    uint8_t bits = 0;
};

struct Layout {
    bool valid = false;
    std::array<Channel, 4> rgba{};
};

constexpr Channel zero() { return {Type::Zero, 0, 0}; }
constexpr Channel one() { return {Type::One, 0, 0}; }
constexpr Channel un(uint8_t shift, uint8_t bits) { return {Type::Unorm, shift, bits}; }
constexpr Channel sn(uint8_t shift, uint8_t bits) { return {Type::Snorm, shift, bits}; }
constexpr Channel hf(uint8_t shift) { return {Type::Half, shift, 16}; }
constexpr Channel fl(uint8_t shift) { return {Type::Float, shift, 32}; }
constexpr Channel ui(uint8_t shift, uint8_t bits) { return {Type::Uint, shift, bits}; }
constexpr Layout L(Channel r, Channel g, Channel b, Channel a) { return {true, {r, g, b, a}}; }

// Channel order in the table below is what a sampler returns: (r, g, b, a), with §14.7's
// values for missing channels. Bump formats return (u, v, w, q) (and L6V5U5 / X8L8V8U8 return
// (u, v, l, 1)). Depth formats (not sampleable in sm2emu) decode to (depth, stencil, 0, 1).
constexpr Layout layout_of(Format f) {
    using enum Format;
    switch (f) {
    case R8G8B8: return L(un(16, 8), un(8, 8), un(0, 8), one());
    case A8R8G8B8: return L(un(16, 8), un(8, 8), un(0, 8), un(24, 8));
    case X8R8G8B8: return L(un(16, 8), un(8, 8), un(0, 8), one());
    case R5G6B5: return L(un(11, 5), un(5, 6), un(0, 5), one());
    case X1R5G5B5: return L(un(10, 5), un(5, 5), un(0, 5), one());
    case A1R5G5B5: return L(un(10, 5), un(5, 5), un(0, 5), un(15, 1));
    case A4R4G4B4: return L(un(8, 4), un(4, 4), un(0, 4), un(12, 4));
    case R3G3B2: return L(un(5, 3), un(2, 3), un(0, 2), one());
    case A8: return L(zero(), zero(), zero(), un(0, 8));
    case A8R3G3B2: return L(un(5, 3), un(2, 3), un(0, 2), un(8, 8));
    case X4R4G4B4: return L(un(8, 4), un(4, 4), un(0, 4), one());
    case A2B10G10R10: return L(un(0, 10), un(10, 10), un(20, 10), un(30, 2));
    case A8B8G8R8: return L(un(0, 8), un(8, 8), un(16, 8), un(24, 8));
    case X8B8G8R8: return L(un(0, 8), un(8, 8), un(16, 8), one());
    case G16R16: return L(un(0, 16), un(16, 16), one(), one());
    case A2R10G10B10: return L(un(20, 10), un(10, 10), un(0, 10), un(30, 2));
    case A16B16G16R16: return L(un(0, 16), un(16, 16), un(32, 16), un(48, 16));
    case L8: return L(un(0, 8), un(0, 8), un(0, 8), one());
    case A8L8: return L(un(0, 8), un(0, 8), un(0, 8), un(8, 8));
    case A4L4: return L(un(0, 4), un(0, 4), un(0, 4), un(4, 4));
    case L16: return L(un(0, 16), un(0, 16), un(0, 16), one());
    case V8U8: return L(sn(0, 8), sn(8, 8), one(), one());
    case L6V5U5: return L(sn(0, 5), sn(5, 5), un(10, 6), one());
    case X8L8V8U8: return L(sn(0, 8), sn(8, 8), un(16, 8), one());
    case Q8W8V8U8: return L(sn(0, 8), sn(8, 8), sn(16, 8), sn(24, 8));
    case V16U16: return L(sn(0, 16), sn(16, 16), one(), one());
    case A2W10V10U10: return L(sn(0, 10), sn(10, 10), sn(20, 10), un(30, 2));
    case Q16W16V16U16: return L(sn(0, 16), sn(16, 16), sn(32, 16), sn(48, 16));
    case R16F: return L(hf(0), one(), one(), one());
    case G16R16F: return L(hf(0), hf(16), one(), one());
    case A16B16G16R16F: return L(hf(0), hf(16), hf(32), hf(48));
    case R32F: return L(fl(0), one(), one(), one());
    case G32R32F: return L(fl(0), fl(32), one(), one());
    case A32B32G32R32F: return L(fl(0), fl(32), fl(64), fl(96));
    case D16_LOCKABLE: case D16: return L(un(0, 16), zero(), zero(), one());
    case D32: return L(un(0, 32), zero(), zero(), one());
    case D15S1: return L(un(1, 15), ui(0, 1), zero(), one());
    case D24S8: return L(un(8, 24), ui(0, 8), zero(), one());
    case D24X8: return L(un(8, 24), zero(), zero(), one());
    case D24X4S4: return L(un(8, 24), ui(0, 4), zero(), one());
    case D32F_LOCKABLE: return L(fl(0), zero(), zero(), one());
    case INDEX16: return L(ui(0, 16), zero(), zero(), one());
    case INDEX32: return L(ui(0, 32), zero(), zero(), one());
    default: return {};
    }
}

// Bits [shift, shift + bits) of a little-endian texel; bits <= 32.
inline uint32_t extract(const std::byte* texel, unsigned shift, unsigned bits) {
    const unsigned first = shift / 8, last = (shift + bits - 1) / 8;
    uint64_t v = 0;
    for (unsigned i = last + 1; i-- > first;) v = v << 8 | static_cast<uint8_t>(texel[i]);
    v >>= shift % 8;
    return static_cast<uint32_t>(bits == 32 ? v & 0xFFFFFFFFu : v & ((uint64_t{1} << bits) - 1));
}

inline void insert(std::byte* texel, unsigned shift, unsigned bits, uint32_t value) {
    for (unsigned b = 0; b < bits;) {
        const unsigned bit = shift + b, byte = bit / 8, at = bit % 8;
        const unsigned n = bits - b < 8 - at ? bits - b : 8 - at;
        const unsigned mask = ((1u << n) - 1u) << at;
        const unsigned part = static_cast<unsigned>((value >> b) << at) & mask;
        texel[byte] = static_cast<std::byte>((static_cast<unsigned>(texel[byte]) & ~mask) | part);
        b += n;
    }
}

inline float decode_channel(Channel c, const std::byte* texel) {
    switch (c.type) {
    case Type::Zero: return 0.0f;
    case Type::One: return 1.0f;
    case Type::Unorm: {
        const uint32_t v = extract(texel, c.shift, c.bits);
        if (c.bits <= 16) return static_cast<float>(v) / static_cast<float>((1u << c.bits) - 1u);
        return static_cast<float>(static_cast<double>(v) / static_cast<double>((uint64_t{1} << c.bits) - 1));
    }
    case Type::Snorm: {
        const uint32_t v = extract(texel, c.shift, c.bits);
        const int32_t s = static_cast<int32_t>(v << (32 - c.bits)) >> (32 - c.bits);
        const float q = static_cast<float>(s) / static_cast<float>((1u << (c.bits - 1)) - 1u);
        return q < -1.0f ? -1.0f : q;
    }
    case Type::Half: return half_to_float(static_cast<uint16_t>(extract(texel, c.shift, 16)));
    case Type::Float: {
        float f;
        std::memcpy(&f, texel + c.shift / 8, 4);
        return f;
    }
    case Type::Uint: return static_cast<float>(extract(texel, c.shift, c.bits));
    }
    return 0.0f;
}

template <Format F>
Float4 decode(const std::byte* texel) {
    constexpr Layout Lay = layout_of(F);
    return {decode_channel(Lay.rgba[0], texel), decode_channel(Lay.rgba[1], texel),
            decode_channel(Lay.rgba[2], texel), decode_channel(Lay.rgba[3], texel)};
}

// Whether every stored channel is an 8-bit UNORM on a byte boundary, each in its own byte
// (A8R8G8B8, X8R8G8B8, A8B8G8R8, A8, ...): the render-target formats a frame is written in.
constexpr bool bytewise_unorm8(const Layout& lay) {
    unsigned used = 0;
    for (const auto& c : lay.rgba) {
        if (c.type == Type::Zero || c.type == Type::One) continue;
        if (c.type != Type::Unorm || c.bits != 8 || c.shift % 8 != 0 || c.shift >= 32) return false;
        if (used >> (c.shift / 8) & 1u) return false;  // luminance: one byte feeds several channels
        used |= 1u << (c.shift / 8);
    }
    return true;
}

// round(x) with halves up, for x already clamped to a small non-negative range.
inline uint32_t round_to_uint(double x) { return static_cast<uint32_t>(std::floor(x + 0.5)); }

inline void encode(const Layout& lay, unsigned bytes, const Float4& value, std::byte* texel) {
    std::memset(texel, 0, bytes);
    for (unsigned i = 0; i < 4; ++i) {
        const Channel c = lay.rgba[i];
        if (c.type == Type::Zero || c.type == Type::One) continue;
        bool duplicate = false;  // luminance: L is stored from r
        for (unsigned j = 0; j < i; ++j)
            duplicate |= lay.rgba[j].type == c.type && lay.rgba[j].shift == c.shift && lay.rgba[j].bits == c.bits;
        if (duplicate) continue;
        const double v = value[i];
        switch (c.type) {
        case Type::Unorm: case Type::Uint: {
            const double max = static_cast<double>((uint64_t{1} << c.bits) - 1);
            const double scaled = c.type == Type::Unorm ? v * max : v;
            const double clamped = !(scaled > 0.0) ? 0.0 : scaled > max ? max : scaled;  // NaN -> 0
            insert(texel, c.shift, c.bits, round_to_uint(clamped));
            break;
        }
        case Type::Snorm: {
            const double max = static_cast<double>((1u << (c.bits - 1)) - 1u);
            const double clamped = std::isnan(v) ? 0.0 : v < -1.0 ? -1.0 : v > 1.0 ? 1.0 : v;
            const double s = clamped * max;  // round half away from zero
            const auto q = static_cast<int32_t>(std::floor(std::fabs(s) + 0.5)) * (s < 0 ? -1 : 1);
            insert(texel, c.shift, c.bits, static_cast<uint32_t>(q) & ((1u << c.bits) - 1u));
            break;
        }
        case Type::Half: insert(texel, c.shift, 16, float_to_half(value[i])); break;
        case Type::Float: std::memcpy(texel + c.shift / 8, &value[i], 4); break;
        default: break;
        }
    }
}

}  // namespace layout
}  // namespace sm2::runtime
