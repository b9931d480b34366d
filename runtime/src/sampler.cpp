// The texture sampler: addressing, point/bilinear/trilinear/anisotropic filtering, level of
// detail from the 2x2 quad, cube face selection, volume textures and sRGB reads
// (pipeline.md §14; the conventions chosen where D3D9 leaves room are in docs/texturing.md).
#include "sm2/runtime/sampler.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <immintrin.h>

#include "dxt.h"
#include "format_layout.h"
#include "unorm8_avx512.h"

namespace sm2::runtime {

// ---------------------------------------------------------------------------------------------
// Sampler states

bool SamplerState::set(uint32_t type, uint32_t value) {
    switch (static_cast<SamplerStateType>(type)) {
    case SamplerStateType::AddressU: address_u = static_cast<TextureAddress>(value); return true;
    case SamplerStateType::AddressV: address_v = static_cast<TextureAddress>(value); return true;
    case SamplerStateType::AddressW: address_w = static_cast<TextureAddress>(value); return true;
    case SamplerStateType::BorderColor: border_color = value; return true;
    case SamplerStateType::MagFilter: mag_filter = static_cast<TextureFilter>(value); return true;
    case SamplerStateType::MinFilter: min_filter = static_cast<TextureFilter>(value); return true;
    case SamplerStateType::MipFilter: mip_filter = static_cast<TextureFilter>(value); return true;
    case SamplerStateType::MipMapLodBias: mip_lod_bias = std::bit_cast<float>(value); return true;
    case SamplerStateType::MaxMipLevel: max_mip_level = value; return true;
    case SamplerStateType::MaxAnisotropy: max_anisotropy = value; return true;
    case SamplerStateType::SrgbTexture: srgb_texture = value != 0; return true;
    case SamplerStateType::ElementIndex: element_index = value; return true;
    case SamplerStateType::DMapOffset: dmap_offset = value; return true;
    }
    return false;
}

std::optional<uint32_t> SamplerState::get(uint32_t type) const {
    switch (static_cast<SamplerStateType>(type)) {
    case SamplerStateType::AddressU: return static_cast<uint32_t>(address_u);
    case SamplerStateType::AddressV: return static_cast<uint32_t>(address_v);
    case SamplerStateType::AddressW: return static_cast<uint32_t>(address_w);
    case SamplerStateType::BorderColor: return border_color;
    case SamplerStateType::MagFilter: return static_cast<uint32_t>(mag_filter);
    case SamplerStateType::MinFilter: return static_cast<uint32_t>(min_filter);
    case SamplerStateType::MipFilter: return static_cast<uint32_t>(mip_filter);
    case SamplerStateType::MipMapLodBias: return std::bit_cast<uint32_t>(mip_lod_bias);
    case SamplerStateType::MaxMipLevel: return max_mip_level;
    case SamplerStateType::MaxAnisotropy: return max_anisotropy;
    case SamplerStateType::SrgbTexture: return srgb_texture ? 1u : 0u;
    case SamplerStateType::ElementIndex: return element_index;
    case SamplerStateType::DMapOffset: return dmap_offset;
    }
    return std::nullopt;
}

void TextureSampler::set_texture(unsigned stage, const Texture* texture) {
    stages_.at(stage).texture = texture;
    prepared_[stage] = false;
}
void TextureSampler::set_state(unsigned stage, const SamplerState& state) {
    stages_.at(stage).state = state;
    prepared_[stage] = false;
}

namespace {

// Texel-space coordinates are clamped to +-2^30 before any float -> integer conversion
// (+-inf land there too; NaN coordinates are replaced by 0 before scaling).
constexpr float kCoordLimit = 1073741824.0f;  // 2^30
constexpr float kLambdaLimit = 64.0f;
constexpr float kFixedScale = 256.0f;         // 8-bit sub-texel and LOD-fraction precision

enum class Filter : uint8_t { Point, Linear };
enum class Mip : uint8_t { None, Point, Linear };

// Filters as the sampler uses them: NONE and unknown values act as POINT; ANISOTROPIC as a
// magnification filter, PYRAMIDALQUAD and GAUSSIANQUAD act as LINEAR.
Filter resolve_filter(TextureFilter f) {
    switch (f) {
    case TextureFilter::Linear: case TextureFilter::Anisotropic: case TextureFilter::PyramidalQuad:
    case TextureFilter::GaussianQuad: return Filter::Linear;
    default: return Filter::Point;
    }
}
Mip resolve_mip(TextureFilter f) {
    switch (f) {
    case TextureFilter::Point: return Mip::Point;
    case TextureFilter::Linear: case TextureFilter::Anisotropic: case TextureFilter::PyramidalQuad:
    case TextureFilter::GaussianQuad: return Mip::Linear;
    default: return Mip::None;
    }
}
// Unknown address modes act as WRAP (the default).
TextureAddress resolve_address(TextureAddress a) {
    const auto v = static_cast<uint32_t>(a);
    return v >= 1 && v <= 5 ? a : TextureAddress::Wrap;
}

float no_nan(float v) { return std::isnan(v) ? 0.0f : v; }

struct Level {
    const std::byte* data = nullptr;
    size_t row = 0, slice = 0;
    int64_t w = 1, h = 1, d = 1;
};

struct Context {
    const Texture* texture = nullptr;
    Format format = Format::Unknown;
    TexelDecoder decode = nullptr;
    unsigned bpp = 0;
    bool dxt = false, srgb = false, cube = false, volume = false, fixed = true;
    TextureAddress address[3]{};
    Float4 border{};
    Filter mag = Filter::Point, min = Filter::Point;
    bool anisotropic = false;
    Mip mip = Mip::None;
    unsigned max_anisotropy = 1;
    int first = 0, last = 0;
    float bias = 0;
    const std::array<float, 256>* srgb_table = nullptr;
    // Fixed8 bilinear on UNORM fields of at most 8 bits sums exactly (see exact_bilinear): the
    // channels (bit k: r, g, b, a) that do, and where their fields lie in the texel.
    uint8_t exact_channels = 0;
    std::array<uint8_t, 4> exact_shift{};
    std::array<uint32_t, 4> exact_mask{};
};

Context make_context(const Texture& texture, const SamplerState& s, FilterPrecision precision) {
    Context c;
    c.texture = &texture;
    c.format = texture.format();
    c.dxt = dxt::is_dxt(c.format);
    c.decode = c.dxt ? nullptr : texel_decoder(c.format);
    const FormatInfo* info = format_info(c.format);
    c.bpp = info != nullptr ? info->bytes : 0;
    c.srgb = s.srgb_texture && info != nullptr && info->srgb;
    c.srgb_table = &srgb_to_linear_table();
    c.cube = texture.type() == TextureType::Cube;
    c.volume = texture.type() == TextureType::Volume;
    c.fixed = precision == FilterPrecision::Fixed8;
    if (c.fixed && !c.dxt && !c.srgb && c.bpp >= 1 && c.bpp <= 4) {
        const layout::Layout lay = layout::layout_of(c.format);
        for (unsigned k = 0; k < 4 && lay.valid; ++k) {
            const layout::Channel& ch = lay.rgba[k];
            if (ch.type != layout::Type::Unorm || ch.bits == 0 || ch.bits > 8 || ch.shift + ch.bits > 8 * c.bpp) continue;
            c.exact_channels = static_cast<uint8_t>(c.exact_channels | 1u << k);
            c.exact_shift[k] = static_cast<uint8_t>(ch.shift);
            c.exact_mask[k] = (1u << ch.bits) - 1u;
        }
    }
    if (c.cube) {
        // No filtering across cube face edges: every face clamps.
        c.address[0] = c.address[1] = c.address[2] = TextureAddress::Clamp;
    } else {
        c.address[0] = resolve_address(s.address_u);
        c.address[1] = resolve_address(s.address_v);
        c.address[2] = resolve_address(s.address_w);
    }
    const uint32_t bc = s.border_color;
    c.border = {static_cast<float>(bc >> 16 & 0xFFu) / 255.0f, static_cast<float>(bc >> 8 & 0xFFu) / 255.0f,
                static_cast<float>(bc & 0xFFu) / 255.0f, static_cast<float>(bc >> 24) / 255.0f};
    c.mag = resolve_filter(s.mag_filter);
    c.min = resolve_filter(s.min_filter);
    c.max_anisotropy = std::clamp<uint32_t>(s.max_anisotropy, 1u, 16u);
    c.anisotropic = s.min_filter == TextureFilter::Anisotropic && c.max_anisotropy > 1;
    c.mip = resolve_mip(s.mip_filter);
    c.last = static_cast<int>(texture.levels()) - 1;
    c.first = static_cast<int>(std::min<uint32_t>(s.max_mip_level, static_cast<uint32_t>(c.last)));
    c.bias = std::clamp(no_nan(s.mip_lod_bias), -kLambdaLimit, kLambdaLimit);
    return c;
}

// How the block path reads a channel (r, g, b, a) of a 32-bit texel, from the format's layout
// (format_layout.h): a UNORM field of up to 16 bits (decoded as the layout's v / (2^n - 1)), a
// 32-bit float, or a constant 0 or 1 for a channel the format lacks.
struct BlockChannel {
    enum class Kind : uint8_t { Zero, One, Unorm, Snorm, Half, Float } kind = Kind::Zero;
    unsigned high = 0;   // 8-byte texels: 1 when the field lies in the second 32-bit word
    unsigned shift = 0;  // within its word
    unsigned bits = 0;   // the field's width (Snorm: where its sign bit is)
    uint32_t mask = 0;   // 2^n - 1 for Unorm
    float max = 1.0f;    // float(2^n - 1); Snorm: float(2^(n-1) - 1)
    // Unorm fields of up to 5 bits: (v & mask) / max for every 5-bit v, so that a decode is one
    // permute by the bits from the field up (the bits above it index copies of the same values)
    // instead of a mask, a conversion and a corrected quotient.
    alignas(64) std::array<float, 32> decoded{};
};
using BlockFormat = std::array<BlockChannel, 4>;

}  // namespace

// The levels of a texture as tables the block path's lanes index by level number, and the
// stage's context (built once per prepare(), not per lookup).
struct TextureSampler::BlockLevels {
    static constexpr unsigned kMax = 16;
    // The faces' levels measure the same: these tables hold face 0's. size: each level's bytes.
    alignas(64) std::array<int32_t, kMax> width{}, height{}, depth{}, row{}, slice{}, size{};
    // Where face f's level l starts (f * kMax + l; 2D and volume textures: face 0, the first kMax
    // entries): its address, and where every level lies within 2^31 bytes of `anchor`, its
    // 32-bit offset from it, so a gather takes 16 32-bit offsets instead of two halves of 64-bit
    // addresses (offsets32 false: the 64-bit gathers).
    alignas(64) std::array<int32_t, kMax * 6> offset{};
    alignas(64) std::array<const std::byte*, kMax * 6> base{};
    const std::byte* anchor = nullptr;
    bool offsets32 = false;
    unsigned texel_bytes = 4;  // 1, 2 (narrow texels), 4 or 8 (two words)
    Context context;
    BlockFormat format;  // how texels decode (looked up once per prepare(), not per lookup)
    // Every channel a UNORM field wider than 5 bits (A16B16G16R16; A8R8G8B8 under float
    // filtering): the filter's instance for them decodes each tap inline, without
    // block_channel()'s call and switch.
    bool wide_unorm = false;
    // Every channel an 8-bit UNORM field of the first word or a constant (A8R8G8B8, X8R8G8B8,
    // A8B8G8R8, L8, A8L8, A8): the filter's instance for them has the fields' masks and
    // maximum in its code.
    bool bytes = false;
};

namespace {

Level level_view(const Context& c, int level, int face) {
    const Surface& s = c.texture->surface(static_cast<uint32_t>(level), static_cast<uint32_t>(face));
    return {s.bytes().data(), s.row_pitch(), s.slice_pitch(), s.width(), s.height(), s.depth()};
}

// Index mapping of §14.2; -1 = the border colour.
int64_t address(TextureAddress mode, int64_t i, int64_t n) {
    const bool pow2 = (n & (n - 1)) == 0;  // two's complement masks give the non-negative remainder
    switch (mode) {
    case TextureAddress::Mirror: {
        int64_t j = pow2 ? i & (2 * n - 1) : i % (2 * n);
        if (j < 0) j += 2 * n;
        return j >= n ? 2 * n - 1 - j : j;
    }
    case TextureAddress::Clamp: return i < 0 ? 0 : i >= n ? n - 1 : i;
    case TextureAddress::Border: return i < 0 || i >= n ? -1 : i;
    case TextureAddress::MirrorOnce: {
        const int64_t j = i < 0 ? -1 - i : i;
        return j >= n ? n - 1 : j;
    }
    default: {  // Wrap
        if (pow2) return i & (n - 1);
        int64_t j = i % n;
        return j < 0 ? j + n : j;
    }
    }
}

// F = Format::Unknown: any format (DXTn or the decoder chosen at run time); otherwise the
// decoder of F inlined (the common formats, see lookup_any).
template <Format F>
Float4 fetch(const Context& c, const Level& l, int64_t x, int64_t y, int64_t z) {
    if (x < 0 || y < 0 || z < 0) return c.border;
    Float4 t;
    const std::byte* slice = l.data + static_cast<size_t>(z) * l.slice;
    if constexpr (dxt::is_dxt(F)) {
        const std::byte* block = slice + static_cast<size_t>(y / 4) * l.row + static_cast<size_t>(x / 4) * dxt::block_bytes(F);
        const dxt::Rgba8 p = dxt::decode_texel(F, block, static_cast<unsigned>(x % 4), static_cast<unsigned>(y % 4));
        if (c.srgb) {
            const auto& lut = *c.srgb_table;
            return {lut[p.r], lut[p.g], lut[p.b], static_cast<float>(p.a) / 255.0f};
        }
        return dxt::to_float(p);
    } else if constexpr (F != Format::Unknown) {
        t = layout::decode<F>(slice + static_cast<size_t>(y) * l.row + static_cast<size_t>(x) * c.bpp);
        if (c.srgb) {
            const auto& lut = *c.srgb_table;
            for (unsigned i = 0; i < 3; ++i) t[i] = lut[static_cast<unsigned>(std::clamp(t[i], 0.0f, 1.0f) * 255.0f + 0.5f)];
        }
        return t;
    }
    if (c.dxt) {
        const std::byte* block = slice + static_cast<size_t>(y / 4) * l.row +
                                 static_cast<size_t>(x / 4) * dxt::block_bytes(c.format);
        const dxt::Rgba8 p = dxt::decode_texel(c.format, block, static_cast<unsigned>(x % 4), static_cast<unsigned>(y % 4));
        if (c.srgb) {
            const auto& lut = *c.srgb_table;
            return {lut[p.r], lut[p.g], lut[p.b], static_cast<float>(p.a) / 255.0f};
        }
        return dxt::to_float(p);
    }
    t = c.decode(slice + static_cast<size_t>(y) * l.row + static_cast<size_t>(x) * c.bpp);
    if (c.srgb) {
        const auto& lut = *c.srgb_table;
        // sRGB-capable formats are all 8-bit UNORM: t[i] is k/255, never NaN
        for (unsigned i = 0; i < 3; ++i) t[i] = lut[static_cast<unsigned>(std::clamp(t[i], 0.0f, 1.0f) * 255.0f + 0.5f)];
    }
    return t;
}

// Texel-space coordinate u * n, NaN-free and within +-2^30.
float texel_space(float u, int64_t n) {
    return std::clamp(no_nan(u) * static_cast<float>(n), -kCoordLimit, kCoordLimit);
}

struct Taps {
    int64_t i0, i1;  // addressed indices (-1 = border)
    float a;         // weight of i1
};

Taps linear_taps(const Context& c, float t, int64_t n, TextureAddress mode) {
    const float x = t - 0.5f;
    int64_t i;
    float a;
    if (c.fixed) {
        const auto fx = static_cast<int64_t>(std::floor(x * kFixedScale));
        i = fx >> 8;
        a = static_cast<float>(fx & 255) / kFixedScale;
    } else {
        const float f = std::floor(x);
        i = static_cast<int64_t>(f);
        a = x - f;
    }
    return {address(mode, i, n), address(mode, i + 1, n), a};
}

void accumulate(Float4& sum, const Float4& t, float w) {
    for (unsigned k = 0; k < 4; ++k) sum[k] += w * t[k];
}

// The texel's bytes as a little-endian word (formats of at most 4 bytes).
uint32_t texel_word(const Context& c, const Level& l, int64_t x, int64_t y) {
    const std::byte* p = l.data + static_cast<size_t>(y) * l.row + static_cast<size_t>(x) * c.bpp;
    uint32_t word = 0;
    for (unsigned i = 0; i < c.bpp; ++i) word |= std::to_integer<uint32_t>(p[i]) << (8 * i);
    return word;
}

// Fixed8 LINEAR on a channel stored as a UNORM field of n <= 8 bits (max = 2^n - 1): with the
// taps' integer values v and the weights in 1/256 units (a = A / 256), the bilinear sum
//   S = (v00 (256 - Ax) + v10 Ax)(256 - Ay) + (v01 (256 - Ax) + v11 Ax) Ay
// is an integer below 2^24, and S / (max * 65536) is the exact filtered value; both are floats
// exactly, so one division rounds it correctly. The block path computes the same S and
// quotient (block_filter_level). Only lookups whose four taps lie in the level (no BORDER tap).
void exact_bilinear(const Context& c, const Level& l, const Taps& tx, const Taps& ty, Float4& r) {
    if (tx.i0 < 0 || tx.i1 < 0 || ty.i0 < 0 || ty.i1 < 0) return;
    const auto ax = static_cast<uint32_t>(tx.a * kFixedScale), ay = static_cast<uint32_t>(ty.a * kFixedScale);
    const uint32_t t00 = texel_word(c, l, tx.i0, ty.i0), t10 = texel_word(c, l, tx.i1, ty.i0);
    const uint32_t t01 = texel_word(c, l, tx.i0, ty.i1), t11 = texel_word(c, l, tx.i1, ty.i1);
    for (unsigned k = 0; k < 4; ++k) {
        if (!(c.exact_channels >> k & 1u)) continue;
        const unsigned shift = c.exact_shift[k];
        const uint32_t mask = c.exact_mask[k];
        auto v = [&](uint32_t t) { return t >> shift & mask; };
        const uint32_t top = v(t00) * (256 - ax) + v(t10) * ax, bottom = v(t01) * (256 - ax) + v(t11) * ax;
        const uint32_t sum = top * (256 - ay) + bottom * ay;
        r[k] = static_cast<float>(sum) / static_cast<float>(mask * 65536u);
    }
}

// One probe on one level.
template <Format F>
Float4 filter_level(const Context& c, const Level& l, Filter f, float u, float v, float w) {
    const float tu = texel_space(u, l.w), tv = texel_space(v, l.h);
    if (f == Filter::Point) {
        const int64_t x = address(c.address[0], static_cast<int64_t>(std::floor(tu)), l.w);
        const int64_t y = address(c.address[1], static_cast<int64_t>(std::floor(tv)), l.h);
        const int64_t z = c.volume ? address(c.address[2], static_cast<int64_t>(std::floor(texel_space(w, l.d))), l.d) : 0;
        return fetch<F>(c, l, x, y, z);
    }
    const Taps tx = linear_taps(c, tu, l.w, c.address[0]);
    const Taps ty = linear_taps(c, tv, l.h, c.address[1]);
    // Taps summed in a fixed order: ((t00 w00 + t10 w10) + t01 w01) + t11 w11 [+ the next plane].
    auto plane = [&](int64_t z, float wz) {
        const Float4 t00 = fetch<F>(c, l, tx.i0, ty.i0, z), t10 = fetch<F>(c, l, tx.i1, ty.i0, z);
        const Float4 t01 = fetch<F>(c, l, tx.i0, ty.i1, z), t11 = fetch<F>(c, l, tx.i1, ty.i1, z);
        const float w00 = (1 - tx.a) * (1 - ty.a) * wz, w10 = tx.a * (1 - ty.a) * wz;
        const float w01 = (1 - tx.a) * ty.a * wz, w11 = tx.a * ty.a * wz;
        Float4 r;
        for (unsigned k = 0; k < 4; ++k) r[k] = t00[k] * w00 + t10[k] * w10 + t01[k] * w01 + t11[k] * w11;
        return r;
    };
    if (!c.volume) {
        Float4 r = plane(0, 1.0f);
        if (c.exact_channels != 0) exact_bilinear(c, l, tx, ty, r);
        return r;
    }
    const Taps tz = linear_taps(c, texel_space(w, l.d), l.d, c.address[2]);
    Float4 r = plane(tz.i0, 1 - tz.a);
    const Float4 r1 = plane(tz.i1, tz.a);
    for (unsigned k = 0; k < 4; ++k) r[k] += r1[k];
    return r;
}

struct Lod {
    bool magnify = true;
    float lambda = 0;     // after anisotropy's division by the probe count
    unsigned probes = 1;
    int major_axis = 0;   // 0: the x derivative is the major axis, 1: y
};

// log2 of a positive double for the LOD, written out (not the C library's) so that the block
// path's 16-lane copy (block_lod_log2) computes the same bits with the same IEEE operations: the
// exponent plus 2 atanh((m - 1) / (m + 1)) / ln 2 for the mantissa m in [sqrt(1/2), sqrt(2)),
// series to s^21 (truncation below 2^-60); a few ulp of double from the exact log2.
constexpr double kSqrt2 = 1.4142135623730951;
constexpr double kInvLn2 = 1.4426950408889634;
constexpr std::array<double, 11> kAtanhSeries = {2.0 / 21, 2.0 / 19, 2.0 / 17, 2.0 / 15, 2.0 / 13, 2.0 / 11,
                                                 2.0 / 9,  2.0 / 7,  2.0 / 5,  2.0 / 3,  2.0};

double lod_log2(double x) {
    const bool tiny = x < 0x1p-1022;  // denormal: scaled into the normal range first
    const double scaled = tiny ? x * 0x1p52 : x;
    const auto bits = std::bit_cast<uint64_t>(scaled);
    double e = static_cast<double>(static_cast<int64_t>(bits >> 52) - 1023) - (tiny ? 52.0 : 0.0);
    double m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
    const bool high = m > kSqrt2;
    m = high ? m * 0.5 : m;
    e = high ? e + 1.0 : e;
    const double s = (m - 1.0) / (m + 1.0);
    const double s2 = s * s;
    double p = kAtanhSeries[0];
    for (size_t k = 1; k < kAtanhSeries.size(); ++k) p = p * s2 + kAtanhSeries[k];
    const double r = e + (p * s) * kInvLn2;
    return x == INFINITY ? INFINITY : r;
}

float log2_lod(double rho, bool fixed) {
    // log2 in double, one rounding to float; 8 fractional bits in fixed mode.
    double l = rho > 0 ? lod_log2(rho) : -static_cast<double>(kLambdaLimit);
    if (!(l > -kLambdaLimit)) l = -kLambdaLimit;  // also catches NaN
    if (l > kLambdaLimit) l = kLambdaLimit;
    if (fixed) l = std::floor(l * kFixedScale) / kFixedScale;
    return static_cast<float>(l);
}

// Scales normalized derivatives to level-0 texels.
std::array<float, 3> to_texels(const Context& c, const std::array<float, 3>& d) {
    const Texture& t = *c.texture;
    return {d[0] * static_cast<float>(t.width()), d[1] * static_cast<float>(t.height()),
            c.volume ? d[2] * static_cast<float>(t.depth()) : 0.0f};
}

double length(const std::array<float, 3>& d) {
    const double x = d[0], y = d[1], z = d[2];
    const double len = std::sqrt(x * x + y * y + z * z);
    return std::isnan(len) ? 0.0 : len;  // NaN derivatives count as 0; inf stays inf
}

// LOD for texel-space derivative vectors; `bias` = texldb's bias (MIPMAPLODBIAS is added here).
Lod compute_lod(const Context& c, double lx, double ly, float bias) {
    Lod lod;
    const double major = std::max(lx, ly), minor = std::min(lx, ly);
    lod.major_axis = ly > lx ? 1 : 0;
    const float total_bias = c.bias + std::clamp(no_nan(bias), -kLambdaLimit, kLambdaLimit);
    const float lambda = std::clamp(log2_lod(major, c.fixed) + total_bias, -kLambdaLimit, kLambdaLimit);
    lod.lambda = lambda;
    lod.magnify = !(lambda > 0.0f);
    if (!lod.magnify && c.anisotropic) {
        const double ratio = minor > 0 ? major / minor : INFINITY;
        // !(ratio < max) also catches inf / inf = NaN (both derivatives infinite)
        const unsigned n = !(ratio < c.max_anisotropy) ? c.max_anisotropy
                                                       : static_cast<unsigned>(std::ceil(ratio));
        lod.probes = std::max(1u, n);
        lod.lambda = std::clamp(log2_lod(major / lod.probes, c.fixed) + total_bias, -kLambdaLimit, kLambdaLimit);
    }
    return lod;
}

struct Dir {
    float u = 0.5f, v = 0.5f;
    int face = 4;
};

// Face coordinates of §14.4 with `face` forced (the quad's face for derivatives); sc/|ma|.
Dir project_to_face(float x, float y, float z, int face) {
    float sc = 0, tc = 0, ma = 0;
    switch (face) {
    case 0: sc = -z; tc = -y; ma = x; break;
    case 1: sc = z; tc = -y; ma = x; break;
    case 2: sc = x; tc = z; ma = y; break;
    case 3: sc = x; tc = -z; ma = y; break;
    case 4: sc = x; tc = -y; ma = z; break;
    default: sc = -x; tc = -y; ma = z; break;
    }
    const float m = std::fabs(ma);
    Dir d;
    d.face = face;
    if (m == 0 || std::isnan(m)) return d;  // centre of the face
    d.u = (sc / m + 1.0f) * 0.5f;
    d.v = (tc / m + 1.0f) * 0.5f;
    return d;
}

// Direction -> face and (u, v). NaN components count as 0; a direction with an infinite
// component keeps only its infinite components (as +-1); the zero vector gives +Z's centre.
Dir cube_direction(float x, float y, float z) {
    x = no_nan(x);
    y = no_nan(y);
    z = no_nan(z);
    if (std::isinf(x) || std::isinf(y) || std::isinf(z)) {
        auto unit = [](float a) { return std::isinf(a) ? std::copysign(1.0f, a) : 0.0f; };
        x = unit(x);
        y = unit(y);
        z = unit(z);
    }
    const float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    int face;
    if (az >= ay && az >= ax) face = std::signbit(z) ? 5 : 4;  // ties: z over y over x
    else if (ay >= ax) face = std::signbit(y) ? 3 : 2;
    else face = std::signbit(x) ? 1 : 0;
    return project_to_face(x, y, z, face);
}

// A whole lookup at normalized (u, v, w) on `face` with a computed LOD; `axis` is the
// anisotropic major axis in normalized coordinates.
// The levels a lookup reads and the filter it reads them with (§14.5): the first level with
// the magnification filter, else the minification filter on one level or, with a LINEAR mip
// filter, two levels blended by `frac` (0: the second level is not read).
struct LevelChoice {
    Filter filter = Filter::Point;
    int l0 = 0, l1 = 0;
    float frac = 0;
};

LevelChoice choose_levels(const Context& c, const Lod& lod) {
    if (lod.magnify) return {c.mag, c.first, c.first, 0.0f};
    LevelChoice choice{c.anisotropic ? Filter::Linear : c.min, c.first, c.first, 0.0f};
    if (c.mip != Mip::None) {
        const float d = std::clamp(lod.lambda, static_cast<float>(c.first), static_cast<float>(c.last));
        if (c.mip == Mip::Point) {
            choice.l0 = choice.l1 = std::min(c.last, static_cast<int>(std::floor(d + 0.5f)));
        } else {
            choice.l0 = static_cast<int>(std::floor(d));
            choice.l1 = std::min(choice.l0 + 1, c.last);
            choice.frac = d - static_cast<float>(choice.l0);
            if (c.fixed) choice.frac = std::floor(choice.frac * kFixedScale) / kFixedScale;
        }
    }
    return choice;
}

// Blends the two levels of a LINEAR mip filter.
Float4 blend_levels(const Float4& a, const Float4& b, float frac) {
    Float4 r;
    for (unsigned k = 0; k < 4; ++k) r[k] = (1 - frac) * a[k] + frac * b[k];
    return r;
}

// Probe `probe` of an anisotropic lookup of `probes` probes centred on p along `axis`
// (lookup()'s spacing): p itself for a single probe.
std::array<float, 3> probe_position(const std::array<float, 3>& p, const std::array<float, 3>& axis, unsigned probe,
                                    unsigned probes) {
    if (probes <= 1) return p;
    const float n = static_cast<float>(probes);
    const float t = (static_cast<float>(probe) + 0.5f) / n - 0.5f;
    return {p[0] + t * axis[0], p[1] + t * axis[1], p[2] + t * axis[2]};
}

template <Format F>
Float4 lookup(const Context& c, float u, float v, float w, int face, const Lod& lod, const std::array<float, 3>& axis) {
    const LevelChoice choice = choose_levels(c, lod);
    const Filter f = choice.filter;
    const float frac = choice.frac;
    const Level a = level_view(c, choice.l0, face);
    auto probe = [&](float pu, float pv, float pw) {
        Float4 r = filter_level<F>(c, a, f, pu, pv, pw);
        if (frac > 0) r = blend_levels(r, filter_level<F>(c, level_view(c, choice.l1, face), f, pu, pv, pw), frac);
        return r;
    };
    if (lod.probes <= 1) return probe(u, v, w);
    Float4 sum{0, 0, 0, 0};
    const float n = static_cast<float>(lod.probes);
    for (unsigned i = 0; i < lod.probes; ++i) {
        const std::array<float, 3> at = probe_position({u, v, w}, axis, i, lod.probes);
        accumulate(sum, probe(at[0], at[1], at[2]), 1.0f);
    }
    for (float& s : sum) s /= n;
    return sum;
}

// The same lookup with the texel decoder inlined for the common formats (identical results).
Float4 lookup_any(const Context& c, float u, float v, float w, int face, const Lod& lod, const std::array<float, 3>& axis) {
    switch (c.format) {
#define SM2_INLINE_FORMAT(f) \
    case Format::f: return lookup<Format::f>(c, u, v, w, face, lod, axis);
    SM2_INLINE_FORMAT(A8R8G8B8)
    SM2_INLINE_FORMAT(X8R8G8B8)
    SM2_INLINE_FORMAT(A8B8G8R8)
    SM2_INLINE_FORMAT(R5G6B5)
    SM2_INLINE_FORMAT(X8B8G8R8)
    SM2_INLINE_FORMAT(A4R4G4B4)
    SM2_INLINE_FORMAT(A1R5G5B5)
    SM2_INLINE_FORMAT(X1R5G5B5)
    SM2_INLINE_FORMAT(A2R10G10B10)
    SM2_INLINE_FORMAT(A2B10G10R10)
    SM2_INLINE_FORMAT(G16R16)
    SM2_INLINE_FORMAT(A16B16G16R16)
    SM2_INLINE_FORMAT(A8)
    SM2_INLINE_FORMAT(L8)
    SM2_INLINE_FORMAT(L16)
    SM2_INLINE_FORMAT(A8L8)
    SM2_INLINE_FORMAT(R16F)
    SM2_INLINE_FORMAT(G16R16F)
    SM2_INLINE_FORMAT(A16B16G16R16F)
    SM2_INLINE_FORMAT(R32F)
    SM2_INLINE_FORMAT(G32R32F)
    SM2_INLINE_FORMAT(A32B32G32R32F)
    SM2_INLINE_FORMAT(DXT1)
    SM2_INLINE_FORMAT(DXT2)
    SM2_INLINE_FORMAT(DXT3)
    SM2_INLINE_FORMAT(DXT4)
    SM2_INLINE_FORMAT(DXT5)
#undef SM2_INLINE_FORMAT
    default: return lookup<Format::Unknown>(c, u, v, w, face, lod, axis);
    }
}

// The LOD changes nothing when both filters agree and there are no mips to choose (anisotropy
// chooses its probe count from it).
bool lod_matters(const Context& c) { return c.mip != Mip::None || c.mag != c.min || c.anisotropic; }

std::array<float, 3> diff(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// What sample() works out for the four lanes of quad q before filtering: each lane's normalized
// coordinates (and cube face), its LOD (one per quad from the coarse derivatives; texldb lanes
// with a bias their own) and the anisotropic major axis. The per-lane path and the block path's
// anisotropic lookups both start from it.
struct QuadLookups {
    std::array<std::array<float, 3>, 4> p;  // normalized (u, v, w) per lane
    std::array<int, 4> face{};
    std::array<Lod, 4> lod;
    std::array<std::array<float, 3>, 4> axis;
};

QuadLookups quad_lookups(const Context& c, const emu::TextureRequest& request, unsigned q) {
    const auto& in = *request.coordinates;
    QuadLookups s;
    std::array<float, 4> bias{};
    std::array<std::array<float, 3>, 4> raw;
    for (unsigned i = 0; i < 4; ++i) {
        const unsigned l = 4 * q + i;
        float x = in[0][l], y = in[1][l], z = in[2][l];
        const float w = in[3][l];
        if (request.variant == emu::TextureVariant::Projected) {
            x /= w;  // IEEE: w = 0 gives +-inf or NaN, handled below
            y /= w;
            z /= w;
        } else if (request.variant == emu::TextureVariant::Bias) {
            bias[i] = w;
        }
        raw[i] = {x, y, z};
        if (c.cube) {
            const Dir d = cube_direction(x, y, z);
            s.p[i] = {d.u, d.v, 0};
            s.face[i] = d.face;
        } else {
            s.p[i] = {x, y, c.volume ? z : 0.0f};
        }
    }
    // Coarse derivatives, one LOD per quad: d/dx = TR - TL, d/dy = BL - TL. Cube maps take
    // all four lanes' coordinates on the top-left lane's face.
    std::array<float, 3> dx, dy;
    if (c.cube) {
        const Dir tl = project_to_face(raw[0][0], raw[0][1], raw[0][2], s.face[0]);
        const Dir tr = project_to_face(raw[1][0], raw[1][1], raw[1][2], s.face[0]);
        const Dir bl = project_to_face(raw[2][0], raw[2][1], raw[2][2], s.face[0]);
        dx = {tr.u - tl.u, tr.v - tl.v, 0};
        dy = {bl.u - tl.u, bl.v - tl.v, 0};
    } else {
        dx = diff(s.p[1], s.p[0]);
        dy = diff(s.p[2], s.p[0]);
    }
    const double lx = length(to_texels(c, dx)), ly = length(to_texels(c, dy));
    const bool matters = lod_matters(c);
    const Lod quad_lod = matters ? compute_lod(c, lx, ly, 0.0f) : Lod{};
    for (unsigned i = 0; i < 4; ++i) {
        s.lod[i] = bias[i] == 0.0f || !matters ? quad_lod : compute_lod(c, lx, ly, bias[i]);
        s.axis[i] = s.lod[i].major_axis == 0 ? dx : dy;
    }
    return s;
}

// ---------------------------------------------------------------------------------------------
// 16 lanes at once: 2D, volume and cube lookups on textures whose texels are 1, 2, 4 or 8 bytes
// of UNORM, SNORM, 16- or 32-bit float fields (block_format()), POINT or LINEAR filtering, anisotropic
// included (block_sample_anisotropic()), CLAMP, BORDER, MIRRORONCE, and WRAP or MIRROR on
// power-of-two levels, sRGB reads, no DXTn: what most draws sample. It is filter_level() and the level blend of
// lookup() evaluated in AVX-512 registers with the same operations in the same order (IEEE
// results are the same whatever the vector width), so its texels are bit for bit those of the
// per-lane path; tests/runtime/sampler_block_test.cpp holds the two equal. The level of detail
// and the choice of levels stay per quad and per lane (compute_lod, choose_levels).

// Each lane's lookup as choose_levels() left it. Not zeroed on construction (block_sample()
// writes every lane: its quads' lanes from their lookups, the rest as a harmless lookup of level
// c.first at (0, 0)).
struct BlockLanes {
    alignas(64) std::array<float, emu::kBatchLanes> u, v, w, frac;
    alignas(64) std::array<int32_t, emu::kBatchLanes> l0, l1, linear, face;
};

using BlockLevels = TextureSampler::BlockLevels;

// The formats of 1-, 2-, 4- and 8-byte texels whose channels are all of those kinds, each
// within one 32-bit word (A8R8G8B8, X8R8G8B8, A8B8G8R8, X8B8G8R8, A2B10G10R10, A2R10G10B10,
// G16R16, R32F, R5G6B5, A4R4G4B4, A1R5G5B5, L8, A8L8, A8, L16, A16B16G16R16, G32R32F, R16F, G16R16F,
// A16B16G16R16F, the signed V8U8, L6V5U5, X8L8V8U8, Q8W8V8U8, V16U16, A2W10V10U10, Q16W16V16U16).
std::optional<BlockFormat> block_format(Format f) {
    const layout::Layout lay = layout::layout_of(f);
    const FormatInfo* info = format_info(f);
    if (!lay.valid || info == nullptr || (info->bytes != 8 && info->bytes != 4 && info->bytes != 2 && info->bytes != 1))
        return std::nullopt;
    BlockFormat format;
    for (unsigned k = 0; k < 4; ++k) {
        const layout::Channel& ch = lay.rgba[k];
        BlockChannel& b = format[k];
        switch (ch.type) {
        case layout::Type::Zero: b.kind = BlockChannel::Kind::Zero; break;
        case layout::Type::One: b.kind = BlockChannel::Kind::One; break;
        case layout::Type::Unorm:
            if (ch.bits > 16 || ch.shift % 32 + ch.bits > 32) return std::nullopt;
            b.kind = BlockChannel::Kind::Unorm;
            b.high = ch.shift / 32;
            b.shift = ch.shift % 32;
            b.mask = (1u << ch.bits) - 1u;
            b.max = static_cast<float>(b.mask);
            if (b.mask < b.decoded.size())
                for (uint32_t v = 0; v < b.decoded.size(); ++v) b.decoded[v] = static_cast<float>(v & b.mask) / b.max;
            break;
        case layout::Type::Snorm:
            if (ch.bits < 2 || ch.bits > 16 || ch.shift % 32 + ch.bits > 32) return std::nullopt;
            b.kind = BlockChannel::Kind::Snorm;
            b.high = ch.shift / 32;
            b.shift = ch.shift % 32;
            b.bits = ch.bits;
            b.max = static_cast<float>((1u << (ch.bits - 1)) - 1u);
            break;
        case layout::Type::Half:
            if (ch.bits != 16 || ch.shift % 32 + 16 > 32) return std::nullopt;
            b.kind = BlockChannel::Kind::Half;
            b.high = ch.shift / 32;
            b.shift = ch.shift % 32;
            break;
        case layout::Type::Float:
            if (ch.shift % 32 != 0 || ch.bits != 32) return std::nullopt;
            b.kind = BlockChannel::Kind::Float;
            b.high = ch.shift / 32;
            break;
        default: return std::nullopt;
        }
    }
    return format;
}

bool block_address_supported(TextureAddress mode, bool all_pow2) {
    return mode == TextureAddress::Clamp || mode == TextureAddress::Border || mode == TextureAddress::MirrorOnce ||
           ((mode == TextureAddress::Wrap || mode == TextureAddress::Mirror) && all_pow2);
}

// Whether the 16-lane path covers this context; fills the level tables.
bool block_supported(const Context& c, BlockLevels& levels) {
    if (c.dxt) return false;
    const std::optional<BlockFormat> format = block_format(c.format);
    if (!format) return false;
    levels.format = *format;
    // (Fixed8 filtering sums fields of up to 8 bits exactly, without decoding taps: the generic
    // instance serves those; given to the wide one, bench_1024 ran 2-3% slower.)
    levels.wide_unorm = std::all_of(format->begin(), format->end(), [&](const BlockChannel& ch) {
        return ch.kind == BlockChannel::Kind::Unorm && ch.mask > 31u && !(c.fixed && ch.mask <= 0xFFu);
    });
    levels.bytes = std::all_of(format->begin(), format->end(), [](const BlockChannel& ch) {
        return (ch.kind == BlockChannel::Kind::Unorm && ch.mask == 0xFFu && ch.high == 0) ||
               ch.kind == BlockChannel::Kind::One || ch.kind == BlockChannel::Kind::Zero;
    });
    levels.texel_bytes = c.bpp;
    if (c.texture->levels() > BlockLevels::kMax || (c.bpp != 8 && c.bpp != 4 && c.bpp != 2 && c.bpp != 1)) return false;
    if (!cpu_has_avx512()) return false;
    bool all_pow2 = true;
    const unsigned count = c.texture->levels();
    for (unsigned l = 0; l < count; ++l) {
        const Surface& s = c.texture->surface(l);
        if (s.width() > (1u << 24) || s.height() > (1u << 24) || s.depth() > (1u << 24) ||
            s.bytes().size() >= (size_t{1} << 31))
            return false;
        levels.width[l] = static_cast<int32_t>(s.width());
        levels.height[l] = static_cast<int32_t>(s.height());
        levels.depth[l] = static_cast<int32_t>(s.depth());
        levels.row[l] = static_cast<int32_t>(s.row_pitch());
        levels.slice[l] = static_cast<int32_t>(s.slice_pitch());
        levels.size[l] = static_cast<int32_t>(s.bytes().size());
        all_pow2 = all_pow2 && std::has_single_bit(s.width()) && std::has_single_bit(s.height()) &&
                   (!c.volume || std::has_single_bit(s.depth()));
    }
    for (unsigned l = count; l < BlockLevels::kMax; ++l) {  // never indexed; kept valid anyway
        levels.width[l] = levels.width[count - 1];
        levels.height[l] = levels.height[count - 1];
        levels.depth[l] = levels.depth[count - 1];
        levels.row[l] = levels.row[count - 1];
        levels.slice[l] = levels.slice[count - 1];
        levels.size[l] = levels.size[count - 1];
    }
    // 32-bit offsets when every byte of every level (of every face) lies within [anchor, anchor + 2^31).
    uintptr_t low = UINTPTR_MAX, high = 0;
    const unsigned faces = c.cube ? 6 : 1;
    for (unsigned f = 0; f < faces; ++f)
        for (unsigned l = 0; l < count; ++l) {
            const Surface& s = c.texture->surface(l, f);
            const auto start = reinterpret_cast<uintptr_t>(s.bytes().data());
            low = std::min(low, start);
            high = std::max(high, start + s.bytes().size());
        }
    levels.offsets32 = high - low < (uintptr_t{1} << 31);
    levels.anchor = reinterpret_cast<const std::byte*>(low);
    for (unsigned f = 0; f < faces; ++f)
        for (unsigned l = 0; l < BlockLevels::kMax; ++l) {  // levels past the last repeat it
            const std::byte* base = c.texture->surface(std::min(l, count - 1), f).bytes().data();
            levels.base[f * BlockLevels::kMax + l] = base;
            levels.offset[f * BlockLevels::kMax + l] =
                levels.offsets32 ? static_cast<int32_t>(reinterpret_cast<uintptr_t>(base) - low) : 0;
        }
    levels.context = c;
    return block_address_supported(c.address[0], all_pow2) && block_address_supported(c.address[1], all_pow2) &&
           (!c.volume || block_address_supported(c.address[2], all_pow2));
}

SM2_AVX512_CODE_BEGIN

// linear_taps() and the POINT index of filter_level() for 16 lanes: i0, i1 addressed, a the
// weight of i1 (0 for POINT lanes, whose i1 is never weighted).
// BORDER: outside0/outside1 mark the lanes whose i0/i1 lies outside the level (they read
// BORDERCOLOR; their index is clamped so that the load stays in the level).
struct BlockTaps {
    __m512i i0, i1;
    __m512 a;
    __mmask16 outside0 = 0, outside1 = 0;
};

// address() for 16 lanes: CLAMP, BORDER (the clamped index; block_outside() marks the lanes),
// MIRRORONCE, and WRAP and MIRROR on power-of-two sizes.
SM2_AVX512 inline __m512i block_address(TextureAddress mode, __m512i i, __m512i n) {
    const __m512i last = _mm512_sub_epi32(n, _mm512_set1_epi32(1));
    if (mode == TextureAddress::Clamp || mode == TextureAddress::Border)
        return _mm512_max_epi32(_mm512_min_epi32(i, last), _mm512_setzero_si512());
    if (mode == TextureAddress::MirrorOnce) {
        // -1 - i for negative i (its bitwise complement), then clamped to n - 1.
        const __m512i j = _mm512_mask_mov_epi32(i, _mm512_cmplt_epi32_mask(i, _mm512_setzero_si512()),
                                                _mm512_xor_si512(i, _mm512_set1_epi32(-1)));
        return _mm512_min_epi32(j, last);
    }
    if (mode == TextureAddress::Mirror) {
        const __m512i period = _mm512_add_epi32(last, n);  // 2n - 1
        const __m512i j = _mm512_and_si512(i, period);
        return _mm512_mask_sub_epi32(j, _mm512_cmpge_epi32_mask(j, n), period, j);
    }
    return _mm512_and_si512(i, last);  // WRAP on a power of two
}

SM2_AVX512 inline __mmask16 block_outside(TextureAddress mode, __m512i i, __m512i n) {
    if (mode != TextureAddress::Border) return 0;
    return static_cast<__mmask16>(_mm512_cmplt_epi32_mask(i, _mm512_setzero_si512()) | _mm512_cmpge_epi32_mask(i, n));
}

SM2_AVX512 __attribute__((always_inline)) inline BlockTaps block_taps(const Context& c, __m512 coord, __m512i n,
                                                                     TextureAddress mode, __mmask16 linear) {
    // texel_space(): NaN -> 0, times the level size, clamped to +-2^30.
    const __m512 finite = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(coord, coord, _CMP_ORD_Q), coord);
    const __m512 t = _mm512_max_ps(_mm512_min_ps(_mm512_mul_ps(finite, _mm512_cvtepi32_ps(n)), _mm512_set1_ps(kCoordLimit)),
                                   _mm512_set1_ps(-kCoordLimit));
    const __m512 x = _mm512_sub_ps(t, _mm512_set1_ps(0.5f));
    __m512 index, a;
    if (c.fixed) {
        // floor(x * 256) split into its integer part >> 8 and its low 8 bits / 256; every step is
        // exact in float (|x * 256| < 2^39, a multiple of 2^(e-23) that fits the mantissa).
        const __m512 fx = _mm512_roundscale_ps(_mm512_mul_ps(x, _mm512_set1_ps(kFixedScale)), _MM_FROUND_TO_NEG_INF);
        index = _mm512_roundscale_ps(_mm512_mul_ps(fx, _mm512_set1_ps(1.0f / kFixedScale)), _MM_FROUND_TO_NEG_INF);
        a = _mm512_mul_ps(_mm512_sub_ps(fx, _mm512_mul_ps(index, _mm512_set1_ps(kFixedScale))),
                          _mm512_set1_ps(1.0f / kFixedScale));
    } else {
        index = _mm512_roundscale_ps(x, _MM_FROUND_TO_NEG_INF);
        a = _mm512_sub_ps(x, index);
    }
    // POINT lanes: floor of the unshifted coordinate, weight 0.
    index = _mm512_mask_mov_ps(_mm512_roundscale_ps(t, _MM_FROUND_TO_NEG_INF), linear, index);
    a = _mm512_maskz_mov_ps(linear, a);
    const __m512i i = _mm512_cvttps_epi32(index), next = _mm512_add_epi32(i, _mm512_set1_epi32(1));
    return {block_address(mode, i, n), block_address(mode, next, n), a, block_outside(mode, i, n),
            block_outside(mode, next, n)};
}

// The integer value of UNORM channel `ch` of 16 texels, as floats.
SM2_AVX512 inline __m512 block_field(__m512i texels, const BlockChannel& ch) {
    const __m512i mask = _mm512_set1_epi32(static_cast<int32_t>(ch.mask));
    return _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(texels, ch.shift), mask));
}

// block_field() of an 8-bit field at `shift`.
SM2_AVX512 inline __m512 block_byte(__m512i texels, unsigned shift) {
    return _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(texels, shift), _mm512_set1_epi32(0xFF)));
}

// half_to_float() (half.h) of 16 binary16 values in the low halves of 32-bit lanes, bit for bit:
// normal values rebiased, infinities and NaNs with their payload as it is (not quieted, as a
// hardware conversion would), denormals as their exact value mantissa * 2^-24.
SM2_AVX512 inline __m512 block_half(__m512i h) {
    const __m512i magnitude = _mm512_and_si512(h, _mm512_set1_epi32(0x7FFF));
    const __m512i sign = _mm512_slli_epi32(_mm512_and_si512(h, _mm512_set1_epi32(0x8000)), 16);
    const __m512i shifted = _mm512_slli_epi32(magnitude, 13);
    __m512i bits = _mm512_add_epi32(shifted, _mm512_set1_epi32(112 << 23));
    const __mmask16 special = _mm512_cmpge_epu32_mask(magnitude, _mm512_set1_epi32(0x7C00));
    bits = _mm512_mask_or_epi32(bits, special, shifted, _mm512_set1_epi32(0x7F800000));
    const __mmask16 small = _mm512_cmplt_epu32_mask(magnitude, _mm512_set1_epi32(0x0400));
    const __m512 tiny = _mm512_mul_ps(_mm512_cvtepi32_ps(magnitude), _mm512_set1_ps(0x1p-24f));
    bits = _mm512_mask_mov_epi32(bits, small, _mm512_castps_si512(tiny));
    return _mm512_castsi512_ps(_mm512_or_si512(bits, sign));
}

// Channel `ch` of 16 texels, as format_layout.h decodes it.
SM2_AVX512 inline __m512 block_channel(__m512i texels, const BlockChannel& ch) {
    switch (ch.kind) {
    case BlockChannel::Kind::Zero: return _mm512_setzero_ps();
    case BlockChannel::Kind::One: return _mm512_set1_ps(1.0f);
    case BlockChannel::Kind::Float: return _mm512_castsi512_ps(texels);
    case BlockChannel::Kind::Half:
        return block_half(_mm512_and_si512(_mm512_srli_epi32(texels, ch.shift), _mm512_set1_epi32(0xFFFF)));
    case BlockChannel::Kind::Snorm: {
        // The field sign-extended, s / (2^(n-1) - 1) (the quotient is odd in s, so correctly
        // rounded for negative s too), below -1 (s = -2^(n-1)) clamped to -1.
        const __m512i field = _mm512_srai_epi32(_mm512_slli_epi32(texels, 32 - ch.shift - ch.bits), 32 - ch.bits);
        const __m512 q = unorm8::quotient(_mm512_cvtepi32_ps(field), ch.max);
        const __m512 minus_one = _mm512_set1_ps(-1.0f);
        return _mm512_mask_mov_ps(q, _mm512_cmp_ps_mask(q, minus_one, _CMP_LT_OQ), minus_one);
    }
    case BlockChannel::Kind::Unorm: break;
    }
    // The permutes read the low 4 (5) bits of each index: the field and, for a narrower one,
    // bits above it, which the table ignores.
    if (ch.mask <= 15u) return _mm512_permutexvar_ps(_mm512_srli_epi32(texels, ch.shift), _mm512_load_ps(ch.decoded.data()));
    if (ch.mask <= 31u)
        return _mm512_permutex2var_ps(_mm512_load_ps(ch.decoded.data()), _mm512_srli_epi32(texels, ch.shift),
                                      _mm512_load_ps(ch.decoded.data() + 16));
    const __m512i field = _mm512_and_si512(_mm512_srli_epi32(texels, ch.shift), _mm512_set1_epi32(static_cast<int32_t>(ch.mask)));
    return unorm8::quotient(_mm512_cvtepi32_ps(field), ch.max);
}

// fetch()'s sRGB read of a colour channel: the table's entry for the decoded 8-bit value,
// index clamp(value, 0, 1) * 255 + 0.5 truncated.
SM2_AVX512 inline __m512 block_srgb(const Context& c, __m512 value) {
    const __m512 unit = _mm512_min_ps(_mm512_max_ps(value, _mm512_setzero_ps()), _mm512_set1_ps(1.0f));
    const __m512i index =
        _mm512_cvttps_epi32(_mm512_add_ps(_mm512_mul_ps(unit, _mm512_set1_ps(255.0f)), _mm512_set1_ps(0.5f)));
    return _mm512_i32gather_ps(index, c.srgb_table->data(), 4);
}

// Channel k of 16 taps (sRGB-decoded where the stage reads sRGB), BORDERCOLOR's channel k on
// the lanes of `outside`.
// Srgb: c.srgb as a compile-time constant (a run-time test here cost bench_1024 5%).
// WideUnorm: the channel is a UNORM field wider than 5 bits (BlockLevels::wide_unorm), decoded here.
// Bytes: every channel an 8-bit UNORM field or a constant (BlockLevels::bytes), whose decode
// takes its constants from the code.
template <bool Srgb, bool WideUnorm, bool Bytes>
SM2_AVX512 inline __m512 block_tap(const Context& c, __m512i texels, const BlockChannel& ch, unsigned k,
                                   __mmask16 outside) {
    __m512 value = WideUnorm ? unorm8::quotient(block_field(texels, ch), ch.max)
                   : Bytes && ch.kind == BlockChannel::Kind::Unorm ? unorm8::decode_at(texels, ch.shift)
                                                                   : block_channel(texels, ch);
    if constexpr (Srgb)
        if (k < 3) value = block_srgb(c, value);
    return outside ? _mm512_mask_mov_ps(value, outside, _mm512_set1_ps(c.border[k])) : value;
}

// Where the lanes' texels are: a byte offset in each lane's level (`in_level`) from the level's
// start, which is `start` bytes past levels.anchor (offsets32) or at the address base_lo/base_hi
// (lanes 0-7, 8-15; 64-bit gathers otherwise).
struct BlockAddress {
    __m512i start, base_lo, base_hi, size;  // size: the lane's level's bytes
};

// 32-bit words at `in_level` for the lanes in `lanes` (others 0); each read must lie in the level.
SM2_AVX512 __attribute__((always_inline)) inline __m512i block_words(const BlockLevels& levels, const BlockAddress& a,
                                                                     __m512i in_level, __mmask16 lanes) {
    const __m512i zero = _mm512_setzero_si512();
    if (levels.offsets32)
        return _mm512_mask_i32gather_epi32(zero, lanes, _mm512_add_epi32(a.start, in_level), levels.anchor, 1);
    const __m512i lo = _mm512_add_epi64(a.base_lo, _mm512_cvtepi32_epi64(_mm512_castsi512_si256(in_level)));
    const __m512i hi = _mm512_add_epi64(a.base_hi, _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(in_level, 1)));
    const __m256i none = _mm256_setzero_si256();
    const __m256i words_lo = _mm512_mask_i64gather_epi32(none, static_cast<__mmask8>(lanes), lo, nullptr, 1);
    const __m256i words_hi = _mm512_mask_i64gather_epi32(none, static_cast<__mmask8>(lanes >> 8), hi, nullptr, 1);
    return _mm512_inserti64x4(_mm512_castsi256_si512(words_lo), words_hi, 1);
}

// The 8 bytes at `in_level` of the lanes in `lanes` (others 0) as their low and high words;
// each read must lie in the level.
SM2_AVX512 __attribute__((always_inline)) inline void block_pairs(const BlockLevels& levels, const BlockAddress& a,
                                                                  __m512i in_level, __mmask16 lanes, __m512i& first,
                                                                  __m512i& second) {
    const __m512i zero = _mm512_setzero_si512();
    __m512i lo, hi;
    if (levels.offsets32) {
        const __m512i at = _mm512_add_epi32(a.start, in_level);
        lo = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(lanes), _mm512_castsi512_si256(at), levels.anchor, 1);
        hi = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(lanes >> 8), _mm512_extracti64x4_epi64(at, 1),
                                         levels.anchor, 1);
    } else {
        const __m512i at_lo = _mm512_add_epi64(a.base_lo, _mm512_cvtepi32_epi64(_mm512_castsi512_si256(in_level)));
        const __m512i at_hi = _mm512_add_epi64(a.base_hi, _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(in_level, 1)));
        lo = _mm512_mask_i64gather_epi64(zero, static_cast<__mmask8>(lanes), at_lo, nullptr, 1);
        hi = _mm512_mask_i64gather_epi64(zero, static_cast<__mmask8>(lanes >> 8), at_hi, nullptr, 1);
    }
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odd = _mm512_add_epi32(even, _mm512_set1_epi32(1));
    first = _mm512_permutex2var_epi32(lo, even, hi);
    second = _mm512_permutex2var_epi32(lo, odd, hi);
}

// block_narrow_words() for the lanes of `last`, whose word would pass their level's end: the
// bytes up to it, the rest 0. Rare (a level's last texels), so kept out of line: with it inline
// the common path carried its stack arrays and was not inlined itself.
SM2_AVX512 __attribute__((noinline, cold)) __m512i block_last_words(const BlockAddress& a, __m512i in_level,
                                                                   __m512i words, __mmask16 last) {
    alignas(64) std::array<int32_t, emu::kBatchLanes> offset, size;
    alignas(64) std::array<uint32_t, emu::kBatchLanes> word;
    alignas(64) std::array<const std::byte*, emu::kBatchLanes> base;
    _mm512_store_si512(offset.data(), in_level);
    _mm512_store_si512(size.data(), a.size);
    _mm512_store_si512(word.data(), words);
    _mm512_store_si512(base.data(), a.base_lo);
    _mm512_store_si512(base.data() + 8, a.base_hi);
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        if (!(last >> l & 1u)) continue;
        word[l] = 0;
        std::memcpy(&word[l], base[l] + offset[l], static_cast<size_t>(size[l] - offset[l]));
    }
    return _mm512_load_si512(word.data());
}

// block_words() for narrow texels: a word would reach up to 3 bytes past a narrow texel, so a
// lane whose word would pass its level's end reads the bytes up to it (the rest 0).
SM2_AVX512 __attribute__((always_inline)) inline __m512i block_narrow_words(const BlockLevels& levels, const BlockAddress& a,
                                                                           __m512i in_level, __mmask16 lanes) {
    const __mmask16 inside = _mm512_mask_cmple_epi32_mask(lanes, _mm512_add_epi32(in_level, _mm512_set1_epi32(4)), a.size);
    const __m512i words = block_words(levels, a, in_level, inside);
    if (const auto last = static_cast<__mmask16>(lanes & ~inside)) return block_last_words(a, in_level, words, last);
    return words;
}

// block_words() for a POINT lookup of 4-byte texels. Where the batch's 4 quads lie side by
// side and read one texel a pixel (a screen-space pass over a texture of the target's size: a
// G-buffer, a light buffer), its 16 texels are two runs of 8 in two rows of the level, read by
// two plain loads instead of a gather.
SM2_AVX512 __attribute__((always_inline)) inline __m512i block_point_words(const BlockLevels& levels, const BlockAddress& a,
                                                                           __m512i in_level) {
    if (levels.offsets32) {
        const __m512i at = _mm512_add_epi32(a.start, in_level);
        const __m128i first = _mm512_castsi512_si128(at);
        const int32_t top = _mm_cvtsi128_si32(first), bottom = _mm_extract_epi32(first, 2);
        // Lane l's byte in the runs: 4 x its column, row 1 (lanes 2, 3 of each quad) `bottom`.
        const __m512i column = _mm512_setr_epi32(0, 4, 0, 4, 8, 12, 8, 12, 16, 20, 16, 20, 24, 28, 24, 28);
        const __m512i expected = _mm512_add_epi32(
            _mm512_mask_mov_epi32(_mm512_set1_epi32(top), 0xCCCC, _mm512_set1_epi32(bottom)), column);
        if (_mm512_cmpeq_epi32_mask(at, expected) == 0xFFFF) {
            // Every byte of the two runs is a lane's texel: both loads lie in the level.
            const __m256i row0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(levels.anchor + top));
            const __m256i row1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(levels.anchor + bottom));
            const __m512i from_rows = _mm512_setr_epi32(0, 1, 16, 17, 2, 3, 18, 19, 4, 5, 20, 21, 6, 7, 22, 23);
            return _mm512_permutex2var_epi32(_mm512_castsi256_si512(row0), from_rows, _mm512_castsi256_si512(row1));
        }
    }
    return block_words(levels, a, in_level, 0xFFFF);
}

// A hint for the batches that follow: the texels two and three pixel rows below lane 0 (the
// top-left pixel of the batch's first quad), extrapolated from lane 0 to lane 2 (the pixel
// below it) in `in_level`, the lanes' byte offsets in their level. A batch covers two pixel
// rows of its tile and the next quad row comes four batches later, so on a texture read near
// one texel per pixel (a G-buffer, a screen-space pass) these are the lines it will wait on
// otherwise. A prefetch never faults, so an extrapolation off the level costs nothing but the
// instruction.
SM2_AVX512 __attribute__((always_inline)) inline void prefetch_rows_below(const BlockLevels& levels, const BlockAddress& a,
                                                                          __m512i in_level) {
    const __m128i first = _mm512_castsi512_si128(in_level);
    const int64_t here = _mm_cvtsi128_si32(first), below = _mm_extract_epi32(first, 2);
    // Addresses as integers: the extrapolation may point outside the level, where pointer
    // arithmetic would be undefined; unsigned arithmetic wraps, and a prefetch never faults.
    const uintptr_t base =
        levels.offsets32
            ? reinterpret_cast<uintptr_t>(levels.anchor) + static_cast<uint32_t>(_mm_cvtsi128_si32(_mm512_castsi512_si128(a.start)))
            : static_cast<uintptr_t>(_mm_cvtsi128_si64(_mm512_castsi512_si128(a.base_lo)));
    const int64_t step = below - here;
    _mm_prefetch(reinterpret_cast<const char*>(base + static_cast<uintptr_t>(here + 2 * step)), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(base + static_cast<uintptr_t>(here + 3 * step)), _MM_HINT_T0);
}

// The four taps (x0, y0), (x1, y0), (x0, y1), (x1, y1) of one slice (`slice`: the byte offset
// of the lanes' slice in their level), as t[tap][word]: word 1 is the second 32-bit word of
// 8-byte texels.
struct BlockQuad {
    __m512i t[4][2];
};
SM2_AVX512 __attribute__((always_inline)) inline BlockQuad block_fetch(const BlockLevels& levels, const BlockAddress& a,
                                                                       const BlockTaps& tx, const BlockTaps& ty,
                                                                       __m512i row, __m512i slice, __mmask16 needed) {
    BlockQuad q{};
    const __m512i row0 = _mm512_add_epi32(_mm512_mullo_epi32(ty.i0, row), slice);
    const __m512i row1 = _mm512_add_epi32(_mm512_mullo_epi32(ty.i1, row), slice);
    // Where i1 = i0 + 1 (every lane but those on a level's right edge) one load reads both
    // texels of a row: half the gathered elements. Edge lanes read each texel alone.
    const __mmask16 adjacent = _mm512_mask_cmpeq_epi32_mask(needed, tx.i1, _mm512_add_epi32(tx.i0, _mm512_set1_epi32(1)));
    const auto edge = static_cast<__mmask16>(needed & ~adjacent);
    if (levels.texel_bytes == 4) {
        const __m512i x0 = _mm512_slli_epi32(tx.i0, 2), x1 = _mm512_slli_epi32(tx.i1, 2);
        block_pairs(levels, a, _mm512_add_epi32(row0, x0), adjacent, q.t[0][0], q.t[1][0]);
        block_pairs(levels, a, _mm512_add_epi32(row1, x0), adjacent, q.t[2][0], q.t[3][0]);
        if (edge) {
            q.t[0][0] = _mm512_mask_mov_epi32(q.t[0][0], edge, block_words(levels, a, _mm512_add_epi32(row0, x0), edge));
            q.t[1][0] = _mm512_mask_mov_epi32(q.t[1][0], edge, block_words(levels, a, _mm512_add_epi32(row0, x1), edge));
            q.t[2][0] = _mm512_mask_mov_epi32(q.t[2][0], edge, block_words(levels, a, _mm512_add_epi32(row1, x0), edge));
            q.t[3][0] = _mm512_mask_mov_epi32(q.t[3][0], edge, block_words(levels, a, _mm512_add_epi32(row1, x1), edge));
        }
        return q;
    }
    if (levels.texel_bytes == 8) {
        // Each texel's two words by one 64-bit load.
        const __m512i x0 = _mm512_slli_epi32(tx.i0, 3), x1 = _mm512_slli_epi32(tx.i1, 3);
        block_pairs(levels, a, _mm512_add_epi32(row0, x0), needed, q.t[0][0], q.t[0][1]);
        block_pairs(levels, a, _mm512_add_epi32(row0, x1), needed, q.t[1][0], q.t[1][1]);
        block_pairs(levels, a, _mm512_add_epi32(row1, x0), needed, q.t[2][0], q.t[2][1]);
        block_pairs(levels, a, _mm512_add_epi32(row1, x1), needed, q.t[3][0], q.t[3][1]);
        return q;
    }
    // Narrow texels (1 or 2 bytes): one 32-bit word holds a texel and, for adjacent lanes, the
    // next one (the fields decoded are those of the low texel; the bits above are ignored).
    const auto shift = static_cast<unsigned>(levels.texel_bytes == 2 ? 1 : 0);
    const __m512i x0 = _mm512_slli_epi32(tx.i0, shift), x1 = _mm512_slli_epi32(tx.i1, shift);
    const __m512i next = _mm512_set1_epi32(static_cast<int32_t>(8 * levels.texel_bytes));
    q.t[0][0] = block_narrow_words(levels, a, _mm512_add_epi32(row0, x0), needed);
    q.t[2][0] = block_narrow_words(levels, a, _mm512_add_epi32(row1, x0), needed);
    q.t[1][0] = _mm512_srlv_epi32(q.t[0][0], next);
    q.t[3][0] = _mm512_srlv_epi32(q.t[2][0], next);
    if (edge) {
        q.t[1][0] = _mm512_mask_mov_epi32(q.t[1][0], edge, block_narrow_words(levels, a, _mm512_add_epi32(row0, x1), edge));
        q.t[3][0] = _mm512_mask_mov_epi32(q.t[3][0], edge, block_narrow_words(levels, a, _mm512_add_epi32(row1, x1), edge));
    }
    return q;
}

// Tap `tap`'s word holding a channel (`high`: the second word of 8-byte texels), chosen by value
// so that the taps stay in registers.
SM2_AVX512 inline __m512i tap_word(const BlockQuad& q, unsigned tap, unsigned high) {
    return high != 0 ? q.t[tap][1] : q.t[tap][0];
}

// filter_level() on each lane's level `level` (POINT or LINEAR per lane), 2D or volume.
template <bool Srgb, bool WideUnorm, bool Bytes>
SM2_AVX512 void block_filter_level(const Context& c, const BlockLevels& levels, const BlockFormat& format, __m512i level,
                                   const BlockLanes& in, __mmask16 linear, __m512 (&out)[4]) {
    const __m512i w = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.width.data()));
    const __m512i h = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.height.data()));
    const __m512i row = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.row.data()));
    const __m512i bases_lo = _mm512_load_si512(levels.base.data());
    const __m512i bases_hi = _mm512_load_si512(levels.base.data() + 8);
    const __m512i base_lo =
        _mm512_permutex2var_epi64(bases_lo, _mm512_cvtepi32_epi64(_mm512_castsi512_si256(level)), bases_hi);
    const __m512i base_hi =
        _mm512_permutex2var_epi64(bases_lo, _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(level, 1)), bases_hi);
    BlockAddress address{_mm512_permutexvar_epi32(level, _mm512_load_si512(levels.offset.data())), base_lo, base_hi,
                         _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.size.data()))};
    if (c.cube) {
        // Each lane's face's level: the tables at face * kMax + level.
        const __m512i at = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_load_si512(in.face.data()),
                                                               _mm512_set1_epi32(static_cast<int32_t>(BlockLevels::kMax))),
                                            level);
        address.start = _mm512_i32gather_epi32(at, levels.offset.data(), 4);
        address.base_lo = _mm512_i32gather_epi64(_mm512_castsi512_si256(at), levels.base.data(), 8);
        address.base_hi = _mm512_i32gather_epi64(_mm512_extracti64x4_epi64(at, 1), levels.base.data(), 8);
    }
    const BlockTaps tx = block_taps(c, _mm512_load_ps(in.u.data()), w, c.address[0], linear);
    const BlockTaps ty = block_taps(c, _mm512_load_ps(in.v.data()), h, c.address[1], linear);
    if (!linear) {
        // Every lane POINT (a POINT stage, or magnified under a POINT MAGFILTER): each lane's one
        // texel t00, as the sums below leave POINT lanes, without fetching the other three taps.
        __m512i at = _mm512_mullo_epi32(ty.i0, row);
        auto outside = static_cast<__mmask16>(tx.outside0 | ty.outside0);
        if (c.volume) {
            const __m512i d = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.depth.data()));
            const __m512i slice = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.slice.data()));
            const BlockTaps tz = block_taps(c, _mm512_load_ps(in.w.data()), d, c.address[2], linear);
            at = _mm512_add_epi32(at, _mm512_mullo_epi32(tz.i0, slice));
            outside = static_cast<__mmask16>(outside | tz.outside0);
        }
        // Each lane's texel: its byte offset in the level (texels of 8, 4, 2 or 1 bytes).
        const auto shift = static_cast<unsigned>(levels.texel_bytes == 8   ? 3
                                                 : levels.texel_bytes == 4 ? 2
                                                 : levels.texel_bytes == 2 ? 1
                                                                           : 0);
        const __m512i in_level = _mm512_add_epi32(at, _mm512_slli_epi32(tx.i0, shift));
        prefetch_rows_below(levels, address, in_level);
        __m512i word0 = _mm512_setzero_si512(), word1 = _mm512_setzero_si512();
        if (outside != 0xFFFF) {  // (every lane's texel outside the level, BORDER: nothing to read)
            if (levels.texel_bytes == 8)
                block_pairs(levels, address, in_level, 0xFFFF, word0, word1);
            else if (levels.texel_bytes == 4)
                word0 = block_point_words(levels, address, in_level);
            else
                word0 = block_narrow_words(levels, address, in_level, 0xFFFF);
        }
        for (unsigned k = 0; k < 4; ++k)
            out[k] = block_tap<Srgb, WideUnorm, Bytes>(c, format[k].high != 0 ? word1 : word0, format[k], k, outside);
        return;
    }
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512 bx = _mm512_sub_ps(one, tx.a), by = _mm512_sub_ps(one, ty.a);
    if (c.volume) {
        // Two slices, each summed as a 2D level with the slice's weight folded into the tap
        // weights, then added (filter_level()'s plane()): ((1-a)(1-b)) wz etc., in that order.
        const __m512i d = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.depth.data()));
        const __m512i slice = _mm512_permutexvar_epi32(level, _mm512_load_si512(levels.slice.data()));
        const BlockTaps tz = block_taps(c, _mm512_load_ps(in.w.data()), d, c.address[2], linear);
        __m512 sum[2][4];
        __m512 point[4];
        for (unsigned p = 0; p < 2; ++p) {
            const __m512 wz = p == 0 ? _mm512_sub_ps(one, tz.a) : tz.a;
            const __m512i z = p == 0 ? tz.i0 : tz.i1;
            const auto oz = static_cast<__mmask16>(p == 0 ? tz.outside0 : tz.outside1);
            const auto o00 = static_cast<__mmask16>(tx.outside0 | ty.outside0 | oz), o10 = static_cast<__mmask16>(tx.outside1 | ty.outside0 | oz);
            const auto o01 = static_cast<__mmask16>(tx.outside0 | ty.outside1 | oz), o11 = static_cast<__mmask16>(tx.outside1 | ty.outside1 | oz);
            // A slice whose taps all lie outside the level on every lane (BORDER) reads none.
            const auto needed = static_cast<__mmask16>(~(o00 & o10 & o01 & o11));
            const BlockQuad q = needed == 0 ? BlockQuad{}
                                            : block_fetch(levels, address, tx, ty, row, _mm512_mullo_epi32(z, slice), needed);
            const __m512 w00 = _mm512_mul_ps(_mm512_mul_ps(bx, by), wz), w10 = _mm512_mul_ps(_mm512_mul_ps(tx.a, by), wz);
            const __m512 w01 = _mm512_mul_ps(_mm512_mul_ps(bx, ty.a), wz), w11 = _mm512_mul_ps(_mm512_mul_ps(tx.a, ty.a), wz);
            for (unsigned k = 0; k < 4; ++k) {
                const __m512 c00 = block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 0, format[k].high), format[k], k, o00);
                if (p == 0) point[k] = c00;
                __m512 r = _mm512_add_ps(_mm512_mul_ps(c00, w00), _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 1, format[k].high), format[k], k, o10), w10));
                r = _mm512_add_ps(r, _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 2, format[k].high), format[k], k, o01), w01));
                sum[p][k] = _mm512_add_ps(r, _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 3, format[k].high), format[k], k, o11), w11));
            }
        }
        for (unsigned k = 0; k < 4; ++k) out[k] = _mm512_mask_mov_ps(point[k], linear, _mm512_add_ps(sum[0][k], sum[1][k]));
        return;
    }
    const __m512 w00 = _mm512_mul_ps(bx, by), w10 = _mm512_mul_ps(tx.a, by);
    const __m512 w01 = _mm512_mul_ps(bx, ty.a), w11 = _mm512_mul_ps(tx.a, ty.a);
    // exact_bilinear()'s integer sums for fixed8 weights on UNORM fields of at most 8 bits:
    // every product and sum is an integer below 2^24, exact in float (POINT lanes have Ax =
    // Ay = 0: S = 65536 v00, whose quotient is v00's decode).
    const __m512 full = _mm512_set1_ps(kFixedScale);
    const __m512 ax = _mm512_mul_ps(tx.a, full), ay = _mm512_mul_ps(ty.a, full);
    const __m512 bxi = _mm512_sub_ps(full, ax), byi = _mm512_sub_ps(full, ay);
    const auto o00 = static_cast<__mmask16>(tx.outside0 | ty.outside0), o10 = static_cast<__mmask16>(tx.outside1 | ty.outside0);
    const auto o01 = static_cast<__mmask16>(tx.outside0 | ty.outside1), o11 = static_cast<__mmask16>(tx.outside1 | ty.outside1);
    // Lanes with a BORDER tap take the float sums (exact_bilinear() leaves them), POINT lanes
    // included (their one tap is t00).
    const auto bordered = static_cast<__mmask16>(o00 | o10 | o01 | o11);
    // Where every tap of every lane lies outside the level (BORDER), nothing is read.
    const auto needed = static_cast<__mmask16>(~(o00 & o10 & o01 & o11));
    const BlockQuad q = needed == 0 ? BlockQuad{} : block_fetch(levels, address, tx, ty, row, _mm512_setzero_si512(), needed);
    for (unsigned k = 0; k < 4; ++k) {
        const BlockChannel& ch = format[k];
        const bool exact = c.fixed && !Srgb && ch.kind == BlockChannel::Kind::Unorm && ch.mask <= 0xFFu;
        __m512 exact_sum = _mm512_setzero_ps();
        if (exact) {
            // (Bytes: the field's mask and maximum as constants.)
            const __m512 v00 = Bytes ? block_byte(tap_word(q, 0, 0), ch.shift) : block_field(tap_word(q, 0, ch.high), ch);
            const __m512 v10 = Bytes ? block_byte(tap_word(q, 1, 0), ch.shift) : block_field(tap_word(q, 1, ch.high), ch);
            const __m512 v01 = Bytes ? block_byte(tap_word(q, 2, 0), ch.shift) : block_field(tap_word(q, 2, ch.high), ch);
            const __m512 v11 = Bytes ? block_byte(tap_word(q, 3, 0), ch.shift) : block_field(tap_word(q, 3, ch.high), ch);
            const __m512 top = _mm512_fmadd_ps(v10, ax, _mm512_mul_ps(v00, bxi));
            const __m512 bottom = _mm512_fmadd_ps(v11, ax, _mm512_mul_ps(v01, bxi));
            const __m512 sum = _mm512_fmadd_ps(bottom, ay, _mm512_mul_ps(top, byi));
            exact_sum = unorm8::quotient(sum, Bytes ? 255.0f : ch.max, 1.0f / 65536.0f);
            if (!bordered) {
                out[k] = exact_sum;
                continue;
            }
        }
        const __m512 c00 = block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 0, ch.high), ch, k, o00);
        __m512 r = _mm512_add_ps(_mm512_mul_ps(c00, w00), _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 1, ch.high), ch, k, o10), w10));
        r = _mm512_add_ps(r, _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 2, ch.high), ch, k, o01), w01));
        r = _mm512_add_ps(r, _mm512_mul_ps(block_tap<Srgb, WideUnorm, Bytes>(c, tap_word(q, 3, ch.high), ch, k, o11), w11));
        // POINT lanes read their texel as it is (filter_level() fetches it): the weighted sum
        // equals it for finite non-negative values, not for a float texel beside an infinity.
        r = _mm512_mask_mov_ps(c00, linear, r);
        out[k] = exact ? _mm512_mask_mov_ps(exact_sum, bordered, r) : r;
    }
}

// The lookups of `in` (every lane valid: lanes without a pixel read level c.first at 0, 0).
// Inlined into both callers (block_sample, block_sample_anisotropic): as a call it cost bench_1024 3%.
SM2_AVX512 __attribute__((always_inline)) inline void block_lookup(const Context& c, const BlockLevels& levels, const BlockLanes& in, __mmask16 used,
                             std::array<emu::FloatLanes, 4>& texels) {
    const BlockFormat& format = levels.format;
    const __mmask16 linear = _mm512_cmpneq_epi32_mask(_mm512_load_si512(in.linear.data()), _mm512_setzero_si512());
    __m512 r[4];
    const auto filter = c.srgb               ? block_filter_level<true, false, false>
                        : levels.wide_unorm ? block_filter_level<false, true, false>
                        : levels.bytes      ? block_filter_level<false, false, true>
                                            : block_filter_level<false, false, false>;
    filter(c, levels, format, _mm512_load_si512(in.l0.data()), in, linear, r);
    const __m512 frac = _mm512_load_ps(in.frac.data());
    const __mmask16 second = _mm512_cmp_ps_mask(frac, _mm512_setzero_ps(), _CMP_GT_OQ);
    if (second) {
        __m512 b[4];
        filter(c, levels, format, _mm512_load_si512(in.l1.data()), in, linear, b);
        const __m512 keep = _mm512_sub_ps(_mm512_set1_ps(1.0f), frac);
        for (unsigned k = 0; k < 4; ++k)
            r[k] = _mm512_mask_mov_ps(r[k], second, _mm512_add_ps(_mm512_mul_ps(keep, r[k]), _mm512_mul_ps(frac, b[k])));
    }
    // Lanes without a pixel read (0, 0, 0, 1), as the per-lane path leaves them.
    for (unsigned k = 0; k < 4; ++k)
        _mm512_storeu_ps(texels[k].data(), _mm512_mask_mov_ps(_mm512_set1_ps(k == 3 ? 1.0f : 0.0f), used, r[k]));
}

// project_to_face() and cube_direction() for 16 lanes, each lane on its own face.
struct BlockFace {
    __m512 u, v;
    __m512i face;
};

SM2_AVX512 inline BlockFace block_project(__m512 x, __m512 y, __m512 z, __m512i face) {
    const __m512 sign = _mm512_set1_ps(-0.0f);
    const __m512 nx = _mm512_xor_ps(x, sign), ny = _mm512_xor_ps(y, sign), nz = _mm512_xor_ps(z, sign);
    const __mmask16 f0 = _mm512_cmpeq_epi32_mask(face, _mm512_set1_epi32(0));
    const __mmask16 f1 = _mm512_cmpeq_epi32_mask(face, _mm512_set1_epi32(1));
    const __mmask16 f2 = _mm512_cmpeq_epi32_mask(face, _mm512_set1_epi32(2));
    const __mmask16 f3 = _mm512_cmpeq_epi32_mask(face, _mm512_set1_epi32(3));
    const __mmask16 f4 = _mm512_cmpeq_epi32_mask(face, _mm512_set1_epi32(4));
    // face: 0: (-z, -y, x), 1: (z, -y, x), 2: (x, z, y), 3: (x, -z, y), 4: (x, -y, z), 5: (-x, -y, z)
    __m512 sc = _mm512_mask_mov_ps(nx, static_cast<__mmask16>(f2 | f3 | f4), x);
    sc = _mm512_mask_mov_ps(_mm512_mask_mov_ps(sc, f0, nz), f1, z);
    __m512 tc = _mm512_mask_mov_ps(_mm512_mask_mov_ps(ny, f2, z), f3, nz);
    __m512 ma = _mm512_mask_mov_ps(z, static_cast<__mmask16>(f0 | f1), x);
    ma = _mm512_mask_mov_ps(ma, static_cast<__mmask16>(f2 | f3), y);
    const __m512 m = _mm512_abs_ps(ma);
    const __mmask16 centre = _mm512_cmp_ps_mask(m, _mm512_setzero_ps(), _CMP_EQ_UQ);  // 0 or NaN
    const __m512 one = _mm512_set1_ps(1.0f), half = _mm512_set1_ps(0.5f);
    const __m512 u = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(sc, m), one), half);
    const __m512 v = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(tc, m), one), half);
    return {_mm512_mask_mov_ps(u, centre, half), _mm512_mask_mov_ps(v, centre, half), face};
}

SM2_AVX512 inline BlockFace block_cube_direction(__m512 x, __m512 y, __m512 z) {
    // NaN components count as 0; with an infinite component only the infinite ones stay, as +-1.
    x = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(x, x, _CMP_ORD_Q), x);
    y = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(y, y, _CMP_ORD_Q), y);
    z = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(z, z, _CMP_ORD_Q), z);
    const __m512 inf = _mm512_set1_ps(INFINITY);
    const __mmask16 ix = _mm512_cmp_ps_mask(_mm512_abs_ps(x), inf, _CMP_EQ_OQ);
    const __mmask16 iy = _mm512_cmp_ps_mask(_mm512_abs_ps(y), inf, _CMP_EQ_OQ);
    const __mmask16 iz = _mm512_cmp_ps_mask(_mm512_abs_ps(z), inf, _CMP_EQ_OQ);
    const auto infinite = static_cast<__mmask16>(ix | iy | iz);
    if (infinite) {
        // +-1 with the infinity's sign, 0 for the finite components
        const __m512 sign = _mm512_set1_ps(-0.0f), one = _mm512_set1_ps(1.0f);
        x = _mm512_mask_mov_ps(x, infinite, _mm512_maskz_mov_ps(ix, _mm512_or_ps(_mm512_and_ps(x, sign), one)));
        y = _mm512_mask_mov_ps(y, infinite, _mm512_maskz_mov_ps(iy, _mm512_or_ps(_mm512_and_ps(y, sign), one)));
        z = _mm512_mask_mov_ps(z, infinite, _mm512_maskz_mov_ps(iz, _mm512_or_ps(_mm512_and_ps(z, sign), one)));
    }
    const __m512 ax = _mm512_abs_ps(x), ay = _mm512_abs_ps(y), az = _mm512_abs_ps(z);
    // Ties: z over y over x; the sign bit chooses the negative face (-0 included).
    const auto z_major = static_cast<__mmask16>(_mm512_cmp_ps_mask(az, ay, _CMP_GE_OQ) & _mm512_cmp_ps_mask(az, ax, _CMP_GE_OQ));
    const auto y_major = static_cast<__mmask16>(~z_major & _mm512_cmp_ps_mask(ay, ax, _CMP_GE_OQ));
    const __mmask16 nx = _mm512_movepi32_mask(_mm512_castps_si512(x)), ny = _mm512_movepi32_mask(_mm512_castps_si512(y));
    const __mmask16 nz = _mm512_movepi32_mask(_mm512_castps_si512(z));
    __m512i face = _mm512_mask_mov_epi32(_mm512_setzero_si512(), nx, _mm512_set1_epi32(1));
    face = _mm512_mask_mov_epi32(face, y_major, _mm512_mask_mov_epi32(_mm512_set1_epi32(2), ny, _mm512_set1_epi32(3)));
    face = _mm512_mask_mov_epi32(face, z_major, _mm512_mask_mov_epi32(_mm512_set1_epi32(4), nz, _mm512_set1_epi32(5)));
    return block_project(x, y, z, face);
}

// block_sample()'s per-lane set-up in registers: each lane's (u, v) (and r for volumes), divided by w for texldp,
// and the squared texel-space lengths of the 4 quads' coarse derivatives (TR - TL, BL - TL) as
// to_texels() and length() compute them (float differences and products, then the sum of
// squares in double; block_lengths() takes the root). squares[q] is quad q's x length squared,
// squares[4 + q] its y.
SM2_AVX512 void block_coordinates(const Context& c, const emu::TextureRequest& request, BlockLanes& lanes,
                                  std::array<double, 8>& squares) {
    const auto& in = *request.coordinates;
    __m512 u = _mm512_loadu_ps(in[0].data()), v = _mm512_loadu_ps(in[1].data());
    const bool third = c.volume || c.cube;
    __m512 r = third ? _mm512_loadu_ps(in[2].data()) : _mm512_setzero_ps();  // volumes' and cubes' third coordinate
    if (request.variant == emu::TextureVariant::Projected) {
        const __m512 w = _mm512_loadu_ps(in[3].data());  // IEEE: w = 0 gives +-inf or NaN
        u = _mm512_div_ps(u, w);
        v = _mm512_div_ps(v, w);
        if (third) r = _mm512_div_ps(r, w);
    }
    const __m512i to = _mm512_setr_epi32(1, 5, 9, 13, 2, 6, 10, 14, 0, 0, 0, 0, 0, 0, 0, 0);
    const __m512i from = _mm512_setr_epi32(0, 4, 8, 12, 0, 4, 8, 12, 0, 0, 0, 0, 0, 0, 0, 0);
    __m512 du, dv;
    if (c.cube) {
        // cube_direction() per lane; the derivatives from the quad's lanes projected onto its
        // top-left lane's face (as sample() does, from the directions as given).
        const BlockFace d = block_cube_direction(u, v, r);
        const __m512i face = _mm512_permutexvar_epi32(from, d.face);
        const BlockFace next = block_project(_mm512_permutexvar_ps(to, u), _mm512_permutexvar_ps(to, v),
                                             _mm512_permutexvar_ps(to, r), face);
        const BlockFace top_left = block_project(_mm512_permutexvar_ps(from, u), _mm512_permutexvar_ps(from, v),
                                                 _mm512_permutexvar_ps(from, r), face);
        du = _mm512_sub_ps(next.u, top_left.u);
        dv = _mm512_sub_ps(next.v, top_left.v);
        u = d.u;
        v = d.v;
        r = _mm512_setzero_ps();
        _mm512_store_si512(lanes.face.data(), d.face);
    } else {
        du = _mm512_sub_ps(_mm512_permutexvar_ps(to, u), _mm512_permutexvar_ps(from, u));
        dv = _mm512_sub_ps(_mm512_permutexvar_ps(to, v), _mm512_permutexvar_ps(from, v));
        _mm512_store_si512(lanes.face.data(), _mm512_setzero_si512());
    }
    _mm512_store_ps(lanes.u.data(), u);
    _mm512_store_ps(lanes.v.data(), v);
    _mm512_store_ps(lanes.w.data(), r);
    const __m512 tu = _mm512_mul_ps(du, _mm512_set1_ps(static_cast<float>(c.texture->width())));
    const __m512 tv = _mm512_mul_ps(dv, _mm512_set1_ps(static_cast<float>(c.texture->height())));
    const __m512 dr = _mm512_sub_ps(_mm512_permutexvar_ps(to, r), _mm512_permutexvar_ps(from, r));
    const __m512 tr =
        c.volume ? _mm512_mul_ps(dr, _mm512_set1_ps(static_cast<float>(c.texture->depth()))) : _mm512_setzero_ps();
    const __m512d x = _mm512_cvtps_pd(_mm512_castps512_ps256(tu));
    const __m512d y = _mm512_cvtps_pd(_mm512_castps512_ps256(tv));
    const __m512d z = _mm512_cvtps_pd(_mm512_castps512_ps256(tr));
    const __m512d sum = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(x, x), _mm512_mul_pd(y, y)), _mm512_mul_pd(z, z));
    _mm512_storeu_pd(squares.data(), sum);
}

// The lengths of block_coordinates()'s squared lengths: the root, NaN -> 0 (as length()).
SM2_AVX512 std::array<double, 8> block_lengths(const std::array<double, 8>& squares) {
    const __m512d len = _mm512_sqrt_pd(_mm512_loadu_pd(squares.data()));
    std::array<double, 8> lengths;
    _mm512_storeu_pd(lengths.data(), _mm512_maskz_mov_pd(_mm512_cmp_pd_mask(len, len, _CMP_ORD_Q), len));
    return lengths;
}

SM2_AVX512 inline __m512i block_spread(__m512i quad_of_lane, const std::array<int32_t, 4>& quad_values) {
    const __m128i values = _mm_loadu_si128(reinterpret_cast<const __m128i*>(quad_values.data()));
    return _mm512_permutexvar_epi32(quad_of_lane, _mm512_castsi128_si512(values));
}

// Each lane's level choice from its quad's: lane l takes quad_value[l / 4]; lanes of `used`
// only, the others level `first`, POINT, at (0, 0).
SM2_AVX512 void block_spread_choices(const std::array<int32_t, 4>& l0, const std::array<int32_t, 4>& l1,
                                     const std::array<float, 4>& frac, const std::array<int32_t, 4>& linear,
                                     __mmask16 used, int first, BlockLanes& lanes) {
    const __m512i quad_of_lane = _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3);
    const __m512i level = _mm512_set1_epi32(first);
    _mm512_store_si512(lanes.l0.data(), _mm512_mask_mov_epi32(level, used, block_spread(quad_of_lane, l0)));
    _mm512_store_si512(lanes.l1.data(), _mm512_mask_mov_epi32(level, used, block_spread(quad_of_lane, l1)));
    _mm512_store_si512(lanes.linear.data(), _mm512_maskz_mov_epi32(used, block_spread(quad_of_lane, linear)));
    _mm512_store_ps(lanes.frac.data(), _mm512_maskz_mov_ps(used, _mm512_permutexvar_ps(quad_of_lane, _mm512_castps128_ps512(_mm_loadu_ps(frac.data())))));
    const __m512 zero = _mm512_setzero_ps();
    _mm512_store_ps(lanes.u.data(), _mm512_mask_mov_ps(zero, used, _mm512_load_ps(lanes.u.data())));
    _mm512_store_ps(lanes.v.data(), _mm512_mask_mov_ps(zero, used, _mm512_load_ps(lanes.v.data())));
    _mm512_store_ps(lanes.w.data(), _mm512_mask_mov_ps(zero, used, _mm512_load_ps(lanes.w.data())));
    _mm512_store_si512(lanes.face.data(), _mm512_maskz_mov_epi32(used, _mm512_load_si512(lanes.face.data())));
}


// lod_log2() for 8 lanes, the same operations in the same order.
SM2_AVX512 inline __m512d block_lod_log2(__m512d x) {
    const __mmask8 tiny = _mm512_cmp_pd_mask(x, _mm512_set1_pd(0x1p-1022), _CMP_LT_OQ);
    const __m512d scaled = _mm512_mask_mul_pd(x, tiny, x, _mm512_set1_pd(0x1p52));
    const __m512i bits = _mm512_castpd_si512(scaled);
    const __m512i biased = _mm512_sub_epi64(_mm512_srli_epi64(bits, 52), _mm512_set1_epi64(1023));
    __m512d e = _mm512_cvtepi64_pd(biased);
    e = _mm512_mask_sub_pd(e, tiny, e, _mm512_set1_pd(52.0));
    __m512d m = _mm512_castsi512_pd(_mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi64(0x000FFFFFFFFFFFFFll)),
                                                    _mm512_set1_epi64(0x3FF0000000000000ll)));
    const __mmask8 high = _mm512_cmp_pd_mask(m, _mm512_set1_pd(kSqrt2), _CMP_GT_OQ);
    m = _mm512_mask_mul_pd(m, high, m, _mm512_set1_pd(0.5));
    e = _mm512_mask_add_pd(e, high, e, _mm512_set1_pd(1.0));
    const __m512d one = _mm512_set1_pd(1.0);
    const __m512d s = _mm512_div_pd(_mm512_sub_pd(m, one), _mm512_add_pd(m, one));
    const __m512d s2 = _mm512_mul_pd(s, s);
    __m512d p = _mm512_set1_pd(kAtanhSeries[0]);
    for (size_t k = 1; k < kAtanhSeries.size(); ++k) p = _mm512_add_pd(_mm512_mul_pd(p, s2), _mm512_set1_pd(kAtanhSeries[k]));
    const __m512d r = _mm512_add_pd(e, _mm512_mul_pd(_mm512_mul_pd(p, s), _mm512_set1_pd(kInvLn2)));
    return _mm512_mask_mov_pd(r, _mm512_cmp_pd_mask(x, _mm512_set1_pd(INFINITY), _CMP_EQ_OQ), _mm512_set1_pd(INFINITY));
}

// std::clamp(v, lo, hi) for 8 lanes: v < lo ? lo : hi < v ? hi : v.
SM2_AVX512 inline __m256 block_clamp(__m256 v, float lo, float hi) {
    const __m256 low = _mm256_set1_ps(lo), high = _mm256_set1_ps(hi);
    const __mmask8 below = _mm256_cmp_ps_mask(v, low, _CMP_LT_OQ), above = _mm256_cmp_ps_mask(high, v, _CMP_LT_OQ);
    return _mm256_mask_mov_ps(_mm256_mask_mov_ps(v, above, high), below, low);
}

// compute_lod() (no texldb bias, no anisotropy: what the block path covers) then
// choose_levels() for the 4 quads of a batch, with the same IEEE operations: lengths[q] and
// lengths[4 + q] are quad q's x and y derivative lengths.
SM2_AVX512 void block_choose_levels(const Context& c, bool lod_matters, const std::array<double, 8>& lengths,
                                    std::array<int32_t, 4>& l0, std::array<int32_t, 4>& l1, std::array<float, 4>& frac,
                                    std::array<int32_t, 4>& linear) {
    const __m512d lx = _mm512_castpd256_pd512(_mm256_loadu_pd(lengths.data()));
    const __m512d ly = _mm512_castpd256_pd512(_mm256_loadu_pd(lengths.data() + 4));
    // log2_lod(std::max(lx, ly), fixed)
    const __m512d major = _mm512_mask_mov_pd(lx, _mm512_cmp_pd_mask(lx, ly, _CMP_LT_OQ), ly);
    const __m512d limit = _mm512_set1_pd(kLambdaLimit), neg_limit = _mm512_set1_pd(-kLambdaLimit);
    __m512d l = _mm512_mask_mov_pd(neg_limit, _mm512_cmp_pd_mask(major, _mm512_setzero_pd(), _CMP_GT_OQ),
                                   block_lod_log2(major));
    l = _mm512_mask_mov_pd(l, _mm512_cmp_pd_mask(l, neg_limit, _CMP_NGT_UQ), neg_limit);
    l = _mm512_mask_mov_pd(l, _mm512_cmp_pd_mask(l, limit, _CMP_GT_OQ), limit);
    if (c.fixed)
        l = _mm512_div_pd(_mm512_roundscale_pd(_mm512_mul_pd(l, _mm512_set1_pd(kFixedScale)), _MM_FROUND_TO_NEG_INF),
                          _mm512_set1_pd(kFixedScale));
    // lambda = clamp(log2_lod + total_bias, -limit, limit) in float; std::clamp(v, lo, hi) is
    // v < lo ? lo : hi < v ? hi : v.
    const float total_bias = c.bias + std::clamp(no_nan(0.0f), -kLambdaLimit, kLambdaLimit);
    __m256 lambda = _mm256_add_ps(_mm512_cvtpd_ps(l), _mm256_set1_ps(total_bias));
    lambda = block_clamp(lambda, -kLambdaLimit, kLambdaLimit);
    const __mmask8 magnify = lod_matters ? static_cast<__mmask8>(~_mm256_cmp_ps_mask(lambda, _mm256_setzero_ps(), _CMP_GT_OQ))
                                         : static_cast<__mmask8>(0xFF);
    // choose_levels()
    __m256i level0 = _mm256_set1_epi32(c.first), level1 = level0;
    __m256 fraction = _mm256_setzero_ps();
    if (c.mip != Mip::None) {
        const __m256 d = block_clamp(lambda, static_cast<float>(c.first), static_cast<float>(c.last));
        const __m256i last = _mm256_set1_epi32(c.last);
        if (c.mip == Mip::Point) {
            const __m256 nearest = _mm256_roundscale_ps(_mm256_add_ps(d, _mm256_set1_ps(0.5f)), _MM_FROUND_TO_NEG_INF);
            level0 = level1 = _mm256_min_epi32(last, _mm256_cvttps_epi32(nearest));
        } else {
            level0 = _mm256_cvttps_epi32(_mm256_roundscale_ps(d, _MM_FROUND_TO_NEG_INF));
            level1 = _mm256_min_epi32(_mm256_add_epi32(level0, _mm256_set1_epi32(1)), last);
            fraction = _mm256_sub_ps(d, _mm256_cvtepi32_ps(level0));
            if (c.fixed)
                fraction = _mm256_div_ps(_mm256_roundscale_ps(_mm256_mul_ps(fraction, _mm256_set1_ps(kFixedScale)),
                                                              _MM_FROUND_TO_NEG_INF),
                                         _mm256_set1_ps(kFixedScale));
        }
    }
    const __m256i first = _mm256_set1_epi32(c.first);
    level0 = _mm256_mask_mov_epi32(level0, magnify, first);
    level1 = _mm256_mask_mov_epi32(level1, magnify, first);
    fraction = _mm256_mask_mov_ps(fraction, magnify, _mm256_setzero_ps());
    const __m256i minify_linear = _mm256_set1_epi32(c.min == Filter::Linear ? 1 : 0);
    const __m256i magnify_linear = _mm256_set1_epi32(c.mag == Filter::Linear ? 1 : 0);
    const __m256i filter = _mm256_mask_mov_epi32(minify_linear, magnify, magnify_linear);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(l0.data()), _mm256_castsi256_si128(level0));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(l1.data()), _mm256_castsi256_si128(level1));
    _mm_storeu_ps(frac.data(), _mm256_castps256_ps128(fraction));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(linear.data()), _mm256_castsi256_si128(filter));
}

// An anisotropic lookup on the block path: the per-lane set-up (quad_lookups(), scalar: four
// quads a batch), then each probe of every lane filtered 16 lanes at once by block_lookup() and
// summed per lane in lookup()'s order. A lane of a single probe is that probe's value.
SM2_AVX512 void block_sample_anisotropic(const Context& c, const BlockLevels& levels, const emu::TextureRequest& request,
                                         unsigned quads, std::array<emu::FloatLanes, 4>& texels) {
    std::array<QuadLookups, emu::kBatchQuads> quad;
    std::array<LevelChoice, emu::kBatchLanes> choice;
    unsigned most = 1;
    for (unsigned q = 0; q < quads; ++q) {
        quad[q] = quad_lookups(c, request, q);
        for (unsigned i = 0; i < 4; ++i) {
            choice[4 * q + i] = choose_levels(c, quad[q].lod[i]);
            most = std::max(most, quad[q].lod[i].probes);
        }
    }
    std::array<Float4, emu::kBatchLanes> sum{};
    BlockLanes lanes;
    std::array<emu::FloatLanes, 4> probe_texels;
    for (unsigned probe = 0; probe < most; ++probe) {
        __mmask16 active = 0;
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            // Lanes without a pixel or past their last probe read level c.first at (0, 0).
            lanes.u[l] = lanes.v[l] = lanes.w[l] = lanes.frac[l] = 0.0f;
            lanes.l0[l] = lanes.l1[l] = c.first;
            lanes.linear[l] = lanes.face[l] = 0;
            const unsigned q = l / 4, i = l % 4;
            if (q >= quads || probe >= quad[q].lod[i].probes) continue;
            active = static_cast<__mmask16>(active | 1u << l);
            const std::array<float, 3> at = probe_position(quad[q].p[i], quad[q].axis[i], probe, quad[q].lod[i].probes);
            lanes.u[l] = at[0];
            lanes.v[l] = at[1];
            lanes.w[l] = at[2];
            lanes.face[l] = quad[q].face[i];
            lanes.l0[l] = choice[l].l0;
            lanes.l1[l] = choice[l].l1;
            lanes.frac[l] = choice[l].frac;
            lanes.linear[l] = choice[l].filter == Filter::Linear ? 1 : 0;
        }
        block_lookup(c, levels, lanes, active, probe_texels);
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            if (!(active >> l & 1u)) continue;
            const Float4 texel{probe_texels[0][l], probe_texels[1][l], probe_texels[2][l], probe_texels[3][l]};
            if (quad[l / 4].lod[l % 4].probes <= 1) sum[l] = texel;
            else accumulate(sum[l], texel, 1.0f);
        }
    }
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        Float4 r{0, 0, 0, 1};  // lanes without a lookup
        if (l < 4 * quads) {
            r = sum[l];
            const unsigned probes = quad[l / 4].lod[l % 4].probes;
            if (probes > 1)
                for (float& v : r) v /= static_cast<float>(probes);
        }
        for (unsigned k = 0; k < 4; ++k) texels[k][l] = r[k];
    }
}

// sample() for a stage the block path covers: each lane's (u, v) (divided by w for texldp),
// per quad the texel-space lengths of the coarse derivatives (TR - TL, BL - TL) and one level
// choice (texldb lanes with a bias choose their own; a batch whose lengths are the stage's last
// batch's takes its choices from `memo`), then block_lookup().
SM2_AVX512 void block_sample(const Context& c, const BlockLevels& levels, const emu::TextureRequest& request, unsigned quads,
                             TextureSampler::BatchLevelMemo& memo, std::array<emu::FloatLanes, 4>& texels) {
    static_assert(emu::kBatchQuads == 4, "block_coordinates() holds 4 quads' lengths");
    if (c.anisotropic) return block_sample_anisotropic(c, levels, request, quads, texels);
    const auto& in = *request.coordinates;
    const bool biased = request.variant == emu::TextureVariant::Bias;
    BlockLanes lanes;
    std::array<double, 8> squares;
    block_coordinates(c, request, lanes, squares);
    const bool matters = lod_matters(c);  // (anisotropic lookups have returned above)
    // The lengths are a function of their squares: a batch with the last batch's squares (every
    // batch of a screen-aligned pass) skips the roots too. Where the LOD does not matter, every
    // batch's choice is the same (the first level, the magnification filter), whatever its
    // lengths: the memo's first one serves them all.
    const bool stale = matters && std::memcmp(memo.squares.data(), squares.data(), sizeof squares) != 0;
    if (!memo.valid || stale) {
        memo.lengths = block_lengths(squares);
        block_choose_levels(c, matters, memo.lengths, memo.l0, memo.l1, memo.frac, memo.linear);
        memo.squares = squares;
        memo.valid = true;
    }
    const auto& lengths = memo.lengths;
    const auto& l0 = memo.l0;
    const auto& l1 = memo.l1;
    const auto& frac = memo.frac;
    const auto& linear = memo.linear;
    const auto used = static_cast<__mmask16>((1u << (4 * quads)) - 1u);
    block_spread_choices(l0, l1, frac, linear, used, c.first, lanes);
    if (biased && matters) {
        // texldb lanes with a bias choose their own levels.
        for (unsigned l = 0; l < 4 * quads; ++l) {
            const float bias = in[3][l];
            if (bias == 0.0f) continue;
            const unsigned q = l / 4;
            const LevelChoice choice = choose_levels(c, compute_lod(c, lengths[q], lengths[4 + q], bias));
            lanes.l0[l] = choice.l0;
            lanes.l1[l] = choice.l1;
            lanes.frac[l] = choice.frac;
            lanes.linear[l] = choice.filter == Filter::Linear ? 1 : 0;
        }
    }
    block_lookup(c, levels, lanes, used, texels);
}

SM2_AVX512_CODE_END
#undef SM2_AVX512

}  // namespace

TextureSampler::LodInfo TextureSampler::level_of_detail(unsigned stage, const std::array<float, 3>& ddx_texels,
                                                        const std::array<float, 3>& ddy_texels, float lod_bias) const {
    const Stage& s = stages_.at(stage);
    if (s.texture == nullptr || s.texture->levels() == 0) return {};
    const Context c = make_context(*s.texture, s.state, precision_);
    const Lod lod = compute_lod(c, length(ddx_texels), length(ddy_texels), lod_bias);
    return {lod.lambda, lod.probes, lod.magnify};
}

Float4 TextureSampler::sample_gradient(unsigned stage, const std::array<float, 3>& coord, const std::array<float, 3>& ddx,
                                       const std::array<float, 3>& ddy, float lod_bias) const {
    const Stage& s = stages_.at(stage);
    if (s.texture == nullptr || s.texture->levels() == 0) return {0, 0, 0, 1};
    const Context c = make_context(*s.texture, s.state, precision_);
    std::array<float, 3> p = coord, px = ddx, py = ddy;
    int face = 0;
    if (c.cube) {
        const Dir d = cube_direction(coord[0], coord[1], coord[2]);
        face = d.face;
        const Dir dx = project_to_face(coord[0] + ddx[0], coord[1] + ddx[1], coord[2] + ddx[2], face);
        const Dir dy = project_to_face(coord[0] + ddy[0], coord[1] + ddy[1], coord[2] + ddy[2], face);
        p = {d.u, d.v, 0};
        px = {dx.u - d.u, dx.v - d.v, 0};
        py = {dy.u - d.u, dy.v - d.v, 0};
    }
    const Lod lod = compute_lod(c, length(to_texels(c, px)), length(to_texels(c, py)), lod_bias);
    return lookup_any(c, p[0], p[1], p[2], face, lod, lod.major_axis == 0 ? px : py);
}

std::shared_ptr<const TextureSampler::BlockLevels> TextureSampler::block_levels_for(unsigned stage) const {
    const Stage& s = stages_.at(stage);
    if (!block_enabled_ || s.texture == nullptr || s.texture->levels() == 0) return nullptr;
    auto levels = std::make_shared<BlockLevels>();
    if (!block_supported(make_context(*s.texture, s.state, precision_), *levels)) return nullptr;
    if (block_64bit_addresses_) levels->offsets32 = false;
    return levels;
}

void TextureSampler::prepare_stage(unsigned stage) {
    block_levels_.at(stage) = block_levels_for(stage);
    level_memo_[stage].valid = false;
    prepared_[stage] = true;
}

void TextureSampler::prepare() {
    for (unsigned stage = 0; stage < kStages; ++stage) prepare_stage(stage);
}

bool TextureSampler::block_path_applies(unsigned stage) const { return block_levels_for(stage) != nullptr; }

void TextureSampler::sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) {
    const unsigned quads = std::min(request.quad_count, emu::kBatchQuads);
    static constexpr emu::FloatLanes kZero{}, kOne = [] {
        emu::FloatLanes one{};
        one.fill(1.0f);
        return one;
    }();
    if (request.sampler < kStages && request.coordinates != nullptr) {
        if (!prepared_[request.sampler]) prepare_stage(request.sampler);
        const BlockLevels* levels_ptr = block_levels_[request.sampler].get();
        if (levels_ptr != nullptr) return block_sample(levels_ptr->context, *levels_ptr, request, quads, level_memo_[request.sampler], texels);
    }
    texels = {kZero, kZero, kZero, kOne};  // what lanes without a lookup read: (0, 0, 0, 1)
    if (request.sampler >= kStages || request.coordinates == nullptr) return;
    const Stage& s = stages_[request.sampler];
    if (s.texture == nullptr || s.texture->levels() == 0) return;  // unbound or empty: (0, 0, 0, 1)
    const Context c = make_context(*s.texture, s.state, precision_);
    for (unsigned q = 0; q < quads; ++q) {
        const QuadLookups set = quad_lookups(c, request, q);
        for (unsigned i = 0; i < 4; ++i) {
            const Float4 r = lookup_any(c, set.p[i][0], set.p[i][1], set.p[i][2], set.face[i], set.lod[i], set.axis[i]);
            for (unsigned k = 0; k < 4; ++k) texels[k][4 * q + i] = r[k];
        }
    }
}

}  // namespace sm2::runtime
