// The texture sampler: addressing, point/bilinear/trilinear/anisotropic filtering, level of
// detail from the 2x2 quad, cube face selection, volume textures and sRGB reads
// (pipeline.md §14; the conventions chosen where D3D9 leaves room are in docs/texturing.md).
#include "sm2/runtime/sampler.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
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

// The scalar helpers that the block kernels' anisotropic and texldb set-up runs: inlined into
// every caller, so that inside a kernel they are compiled for its instruction set (VEX). Called
// out of line from a kernel, their SSE code ran after the kernel's zmm writes without a
// vzeroupper (GCC left it out before some of the calls) and waited on the registers' dirty
// upper halves: choose_levels() alone was a quarter of scene 10's run on the Intel machine.
#define SM2_SCALAR_HELPER [[gnu::always_inline]] inline

SM2_SCALAR_HELPER float no_nan(float v) { return std::isnan(v) ? 0.0f : v; }

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
    // The texels of a DXTn texture decoded to A8R8G8B8 (Texture::decoded_dxt(), the block
    // path's view of it): filtered as fetch<>() filters the blocks, by the float sums, never
    // by exact_bilinear()'s.
    bool decoded_dxt = false;
    // The block path's: every level's sides are powers of two, so WRAP and MIRROR address by
    // masks (else by a remainder, block_periodic_address()).
    bool pow2_levels = false;
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
    // Of the field's maximum, 2^n - 1 (Snorm: 2^(n-1) - 1), which a decode divides by
    // (unorm8::quotient_by()).
    SplitReciprocal reciprocal;
    // Unorm fields of up to 5 bits: (v & mask) / max for every 5-bit v, so that a decode is one
    // permute by the bits from the field up (the bits above it index copies of the same values)
    // instead of a mask, a conversion and a corrected quotient.
    alignas(64) std::array<float, 32> decoded{};
};
using BlockFormat = std::array<BlockChannel, 4>;

// block_filter_level()'s WideUnorm flavours (sampler_block.inc's block_tap()); 0 for the others.
constexpr unsigned kAnyWidth = 1, kSixteenBits = 2;

}  // namespace

// The levels of a texture as tables the block path's lanes index by level number, and the
// stage's context (built once per prepare(), not per lookup).
struct TextureSampler::BlockLevels {
    static constexpr unsigned kMax = 16;
    // The faces' levels measure the same: these tables hold face 0's.
    alignas(64) std::array<int32_t, kMax> width{}, height{}, depth{}, row{}, slice{};
    // Where face f's level l starts (f * kMax + l; 2D and volume textures: face 0, the first kMax
    // entries): its address, and where every level lies within 2^31 bytes of `anchor`, its
    // 32-bit offset from it, so a gather takes 16 32-bit offsets instead of two halves of 64-bit
    // addresses (offsets32 false: the 64-bit gathers).
    alignas(64) std::array<int32_t, kMax * 6> offset{};
    alignas(64) std::array<const std::byte*, kMax * 6> base{};
    const std::byte* anchor = nullptr;
    bool offsets32 = false;
    unsigned texel_bytes = 4;  // 1, 2 (narrow texels), 4 or 8 (two words)
    // texel_bytes where the level is 2D (not a volume, not a cube face) with 4- or 8-byte
    // texels, else 0: the filter's instance for that layout (block_filter_level's FlatBytes).
    unsigned flat_bytes = 0;
    Context context;
    BlockFormat format;  // how texels decode (looked up once per prepare(), not per lookup)
    // Every channel a UNORM field, all wider than 5 bits (A16B16G16R16; A8R8G8B8 under float
    // filtering) or one wider than 8 (A2B10G10R10): the filter's instance for them decodes each
    // tap inline, without block_channel()'s call and switch.
    bool wide_unorm = false;
    // wide_unorm with channel k the 16-bit field at bit 16 k (A16B16G16R16): the filter's
    // instance for them has the fields' positions and quotient in its code.
    bool unorm16 = false;
    // Every channel an 8-bit UNORM field of the first word or a constant (A8R8G8B8, X8R8G8B8,
    // A8B8G8R8, L8, A8L8, A8): the filter's instance for them has the fields' masks and
    // maximum in its code.
    bool bytes = false;
    // Every channel a UNORM field of at most 5 bits or a constant (A4R4G4B4, A1R5G5B5,
    // X4R4G4B4, A4L4): the filter's instance for them decodes each tap by its table inline.
    bool narrow = false;
    // Bit k: the filter sums channel k exactly (exact_bilinear()): fixed8 weights on a UNORM
    // field of at most 8 bits, not sRGB-decoded. Set once here, not tested per lookup.
    unsigned exact_channels = 0;
    // These levels are 2D with 4-byte texels of 8-bit fields (`bytes`) and 32-bit offsets, and
    // every filtered channel is summed exactly: block_exact_pairs() alone filters a lookup
    // without BORDER taps (the AVX-512 instance then reads its levels inline,
    // block_exact_levels()). Set once here, not tested per lookup.
    bool exact_2d = false;
    // Channel k filters to what channel copy_of[k] filters to: an earlier channel decoded from
    // the same field in the same way, with the same BORDERCOLOR channel and sRGB read (L8 and
    // A8L8 give red, green and blue from one field). Only the channels of `filtered` (those with
    // copy_of[k] = k) are filtered; block_lookup() copies the others.
    std::array<uint8_t, 4> copy_of{0, 1, 2, 3};
    unsigned filtered = 0xFu;
    // A BORDER tap adds nothing to the float sums of any filtered channel, so the filter zeroes
    // the tap's weight (four selects a 2x2 footprint) instead of replacing its decoded values by
    // BORDERCOLOR (a select per tap and channel): every filtered channel's BORDERCOLOR is +0 and
    // its decoded values are finite and non-negative (a UNORM field or a constant; sRGB reads
    // of them too), where v * 0 = +0 = 0 * w, the same product in the same place of the sum.
    bool zero_border = false;
    // Every channel decodes to a finite value other than -0 (UNORM and SNORM fields, constants;
    // BORDERCOLOR's channels are finite and non-negative): a 2x2 sum whose weights are 1, +0, +0
    // and +0 is then tap t00 as it is, which block_filter_level() reads alone (a texel-centre
    // lookup).
    bool finite_taps = false;
    // block_filter_level()'s instance for these levels in the instance set that `avx512` names
    // (block_filter_for(), sampler_block.inc), chosen once here.
    void (*filter)() = nullptr;
    // Which instance of the kernels runs: AVX-512's, or AVX2's (sampler_block.inc).
    bool avx512 = true;
    // A DXTn texture's decoded texels, which `context` and the tables read: kept alive with them.
    std::shared_ptr<const Texture> decoded_dxt;
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

SM2_SCALAR_HELPER double lod_log2(double x) {
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

SM2_SCALAR_HELPER float log2_lod(double rho, bool fixed) {
    // log2 in double, one rounding to float; 8 fractional bits in fixed mode.
    double l = rho > 0 ? lod_log2(rho) : -static_cast<double>(kLambdaLimit);
    if (!(l > -kLambdaLimit)) l = -kLambdaLimit;  // also catches NaN
    if (l > kLambdaLimit) l = kLambdaLimit;
    if (fixed) l = std::floor(l * kFixedScale) / kFixedScale;
    return static_cast<float>(l);
}

// Scales normalized derivatives to level-0 texels.
SM2_SCALAR_HELPER std::array<float, 3> to_texels(const Context& c, const std::array<float, 3>& d) {
    const Texture& t = *c.texture;
    return {d[0] * static_cast<float>(t.width()), d[1] * static_cast<float>(t.height()),
            c.volume ? d[2] * static_cast<float>(t.depth()) : 0.0f};
}

SM2_SCALAR_HELPER double length(const std::array<float, 3>& d) {
    const double x = d[0], y = d[1], z = d[2];
    const double len = std::sqrt(x * x + y * y + z * z);
    return std::isnan(len) ? 0.0 : len;  // NaN derivatives count as 0; inf stays inf
}

// LOD for texel-space derivative vectors; `bias` = texldb's bias (MIPMAPLODBIAS is added here).
SM2_SCALAR_HELPER Lod compute_lod(const Context& c, double lx, double ly, float bias) {
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
SM2_SCALAR_HELPER Dir project_to_face(float x, float y, float z, int face) {
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
SM2_SCALAR_HELPER Dir cube_direction(float x, float y, float z) {
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

SM2_SCALAR_HELPER LevelChoice choose_levels(const Context& c, const Lod& lod) {
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
SM2_SCALAR_HELPER std::array<float, 3> probe_position(const std::array<float, 3>& p, const std::array<float, 3>& axis,
                                                      unsigned probe, unsigned probes) {
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
SM2_SCALAR_HELPER bool lod_matters(const Context& c) { return c.mip != Mip::None || c.mag != c.min || c.anisotropic; }

SM2_SCALAR_HELPER std::array<float, 3> diff(const std::array<float, 3>& a, const std::array<float, 3>& b) {
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

SM2_SCALAR_HELPER QuadLookups quad_lookups(const Context& c, const emu::TextureRequest& request, unsigned q) {
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
            b.reciprocal = split_reciprocal(b.mask);
            if (b.mask < b.decoded.size())
                for (uint32_t v = 0; v < b.decoded.size(); ++v)
                    b.decoded[v] = static_cast<float>(v & b.mask) / static_cast<float>(b.mask);
            break;
        case layout::Type::Snorm:
            if (ch.bits < 2 || ch.bits > 16 || ch.shift % 32 + ch.bits > 32) return std::nullopt;
            b.kind = BlockChannel::Kind::Snorm;
            b.high = ch.shift / 32;
            b.shift = ch.shift % 32;
            b.bits = ch.bits;
            b.reciprocal = split_reciprocal((1u << (ch.bits - 1)) - 1u);
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

// Whether the 16-lane path covers this context; fills the level tables.
bool block_supported(const Context& c, BlockLevels& levels) {
    if (c.dxt) return false;
    const std::optional<BlockFormat> format = block_format(c.format);
    if (!format) return false;
    levels.format = *format;
    // (Fixed8 filtering sums fields of up to 8 bits exactly, without decoding taps: the generic
    // instance serves those; given to the wide one, bench_1024 ran 2-3% slower.)
    // A format with a field wider than 8 bits (A2B10G10R10's 2-bit alpha beside its 10-bit
    // colour) takes it too: its quotient is correctly rounded for every width (unorm8::quotient),
    // and the generic instance called block_channel() per tap and channel (scene 27's G-buffer).
    const bool all_unorm = std::all_of(format->begin(), format->end(),
                                       [](const BlockChannel& ch) { return ch.kind == BlockChannel::Kind::Unorm; });
    levels.wide_unorm =
        all_unorm && (std::all_of(format->begin(), format->end(),
                                  [&](const BlockChannel& ch) { return ch.mask > 31u && !(c.fixed && ch.mask <= 0xFFu); }) ||
                      std::any_of(format->begin(), format->end(), [](const BlockChannel& ch) { return ch.mask > 0xFFu; }));
    levels.unorm16 = true;
    for (unsigned k = 0; k < 4; ++k) {
        const BlockChannel& ch = (*format)[k];
        levels.unorm16 = levels.unorm16 && ch.kind == BlockChannel::Kind::Unorm && ch.mask == 0xFFFFu &&
                         ch.high == k / 2 && ch.shift == 16 * (k % 2);
    }
    // Every channel a constant or a UNORM field of the first word whose mask passes `fits`.
    const auto fields_or_constants = [&](auto fits) {
        return std::all_of(format->begin(), format->end(), [&](const BlockChannel& ch) {
            return (ch.kind == BlockChannel::Kind::Unorm && fits(ch.mask) && ch.high == 0) ||
                   ch.kind == BlockChannel::Kind::One || ch.kind == BlockChannel::Kind::Zero;
        });
    };
    levels.bytes = fields_or_constants([](uint32_t mask) { return mask == 0xFFu; });
    levels.narrow = fields_or_constants([](uint32_t mask) { return mask <= 31u; });
    levels.exact_channels = 0;
    for (unsigned k = 0; k < 4; ++k) {
        const BlockChannel& ch = (*format)[k];
        if (c.fixed && !c.srgb && !c.decoded_dxt && ch.kind == BlockChannel::Kind::Unorm && ch.mask <= 0xFFu)
            levels.exact_channels |= 1u << k;
    }
    const bool reads_border = std::find(std::begin(c.address), std::end(c.address), TextureAddress::Border) != std::end(c.address);
    for (unsigned k = 1; k < 4; ++k) {
        const BlockChannel& ch = (*format)[k];
        if (ch.kind == BlockChannel::Kind::Zero || ch.kind == BlockChannel::Kind::One) continue;  // (no decode to share)
        for (unsigned j = 0; j < k; ++j) {
            const BlockChannel& earlier = (*format)[j];
            const bool same_field = earlier.kind == ch.kind && earlier.high == ch.high && earlier.shift == ch.shift &&
                                    earlier.bits == ch.bits && earlier.mask == ch.mask;
            const bool same_border = !reads_border || std::bit_cast<uint32_t>(c.border[j]) == std::bit_cast<uint32_t>(c.border[k]);
            const bool same_srgb = !c.srgb || (j < 3) == (k < 3);  // (sRGB reads colour channels only)
            if (same_field && same_border && same_srgb) {
                levels.copy_of[k] = static_cast<uint8_t>(j);
                levels.filtered &= ~(1u << k);
                break;
            }
        }
    }
    levels.finite_taps = std::none_of(format->begin(), format->end(), [](const BlockChannel& ch) {
        return ch.kind == BlockChannel::Kind::Half || ch.kind == BlockChannel::Kind::Float;
    });
    levels.zero_border = reads_border;
    for (unsigned k = 0; k < 4; ++k) {
        const BlockChannel::Kind kind = (*format)[k].kind;
        const bool non_negative = kind == BlockChannel::Kind::Unorm || kind == BlockChannel::Kind::Zero || kind == BlockChannel::Kind::One;
        if ((levels.filtered >> k & 1u) && !(non_negative && std::bit_cast<uint32_t>(c.border[k]) == 0u)) levels.zero_border = false;
    }
    levels.texel_bytes = c.bpp;
    levels.flat_bytes = !c.volume && !c.cube && (c.bpp == 4 || c.bpp == 8) ? c.bpp : 0;
    if (c.texture->levels() > BlockLevels::kMax || (c.bpp != 8 && c.bpp != 4 && c.bpp != 2 && c.bpp != 1)) return false;
    if (!cpu_has_avx512() && !cpu_has_avx2()) return false;
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
        all_pow2 = all_pow2 && std::has_single_bit(s.width()) && std::has_single_bit(s.height()) &&
                   (!c.volume || std::has_single_bit(s.depth()));
    }
    for (unsigned l = count; l < BlockLevels::kMax; ++l) {  // never indexed; kept valid anyway
        levels.width[l] = levels.width[count - 1];
        levels.height[l] = levels.height[count - 1];
        levels.depth[l] = levels.depth[count - 1];
        levels.row[l] = levels.row[count - 1];
        levels.slice[l] = levels.slice[count - 1];
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
    levels.context.pow2_levels = all_pow2;
    levels.exact_2d = levels.bytes && levels.flat_bytes == 4 && levels.offsets32 && levels.exact_channels != 0 &&
                      (levels.filtered & ~levels.exact_channels) == 0;
    return true;
}

}  // namespace

}  // namespace sm2::runtime

// The block kernels, once per instruction set (block_instances.inc).
#define SM2_BLOCK_KERNELS "sampler_block.inc"
#include "block_instances.inc"

namespace sm2::runtime {

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
    Context c = make_context(*s.texture, s.state, precision_);
    if (c.dxt) {
        // The block path reads a DXTn texture's texels decoded (the same 8-bit values
        // fetch<>() decodes per tap), in the context of the DXTn texture otherwise (its sRGB
        // read, addressing and filters): A8R8G8B8's layout and decoder, no exact sums.
        levels->decoded_dxt = s.texture->decoded_dxt();
        if (!levels->decoded_dxt) return nullptr;  // past the copies' budget: the per-lane path
        c.texture = levels->decoded_dxt.get();
        c.format = Format::A8R8G8B8;
        c.decode = texel_decoder(c.format);
        c.bpp = 4;
        c.dxt = false;
        c.decoded_dxt = true;
        c.exact_channels = 0;
    }
    if (!block_supported(c, *levels)) return nullptr;
    if (block_64bit_addresses_) levels->offsets32 = false;
    levels->avx512 = cpu_has_avx512() && !block_avx2_;
    levels->filter = levels->avx512 ? avx512::block_filter_for(*levels) : avx2::block_filter_for(*levels);
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

std::optional<TextureSampler::BorderBox> TextureSampler::transparent_border(unsigned stage) const {
    const Stage& s = stages_.at(stage);
    const Texture* texture = s.texture;
    if (texture == nullptr || texture->type() == TextureType::Cube || (s.state.border_color >> 24) != 0) return std::nullopt;
    const auto point_or_linear = [](TextureFilter f) { return f == TextureFilter::Point || f == TextureFilter::Linear; };
    const bool mip_ok = s.state.mip_filter == TextureFilter::None || point_or_linear(s.state.mip_filter);
    if (!point_or_linear(s.state.min_filter) || !point_or_linear(s.state.mag_filter) || !mip_ok) return std::nullopt;
    const TextureAddress modes[3] = {s.state.address_u, s.state.address_v, s.state.address_w};
    const uint32_t last = texture->levels() - 1;
    const uint32_t smallest[3] = {texture->level_width(last), texture->level_height(last), texture->level_depth(last)};
    BorderBox box;
    const unsigned dimensions = texture->type() == TextureType::Volume ? 3 : 2;
    for (unsigned a = 0; a < dimensions; ++a) {
        if (modes[a] != TextureAddress::Border) continue;
        // On a level of n >= m texels (m: the smallest level's), u < -1/m gives u * n < -1, so
        // LINEAR's upper tap floor(u * n - 0.5) + 1 is below 0 (POINT's floor(u * n) too), and
        // u >= 1 + 1/m gives u * n - 0.5 >= n + 0.5, both taps at n or above: half a texel to
        // spare for the float rounding of u * n. Rounded outward to floats.
        const double margin = 1.0 / smallest[a];
        box.axes |= 1u << a;
        box.low[a] = std::nextafter(static_cast<float>(-margin), -std::numeric_limits<float>::infinity());
        box.high[a] = std::nextafter(static_cast<float>(1.0 + margin), std::numeric_limits<float>::infinity());
    }
    if (box.axes == 0) return std::nullopt;
    return box;
}

emu::LaneMask TextureSampler::outside_border(const BorderBox& box, const std::array<const float*, 3>& coordinates) const {
    if (block_enabled_ && cpu_has_avx512() && !block_avx2_) return avx512::block_outside_border(box, coordinates);
    if (block_enabled_ && cpu_has_avx2()) return avx2::block_outside_border(box, coordinates);
    emu::LaneMask outside = 0;
    for (unsigned a = 0; a < 3; ++a) {
        if (!(box.axes >> a & 1u)) continue;
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            const float v = coordinates[a][l];
            if (v < box.low[a] || v >= box.high[a]) outside |= emu::LaneMask{1} << l;
        }
    }
    return outside;
}

void TextureSampler::sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) {
    const unsigned quads = std::min(request.quad_count, emu::kBatchQuads);
    if (request.sampler < kStages && request.coordinates != nullptr) {
        if (!prepared_[request.sampler]) prepare_stage(request.sampler);
        const BlockLevels* levels_ptr = block_levels_[request.sampler].get();
        if (levels_ptr != nullptr) {
            const Context& c = levels_ptr->context;
            auto& memo = level_memo_[request.sampler];
            const bool gated = alpha_gates_[request.sampler];
            if (levels_ptr->avx512)
                return c.cube ? avx512::block_sample<true>(c, *levels_ptr, request, quads, gated, memo, texels)
                              : avx512::block_sample<false>(c, *levels_ptr, request, quads, gated, memo, texels);
            return c.cube ? avx2::block_sample<true>(c, *levels_ptr, request, quads, gated, memo, texels)
                          : avx2::block_sample<false>(c, *levels_ptr, request, quads, gated, memo, texels);
        }
    }
    sample_lanes(request, quads, texels);
}

// (Out of line: inlined into sample(), its frame and saved registers cost every block lookup
// about 30 instructions.)
__attribute__((noinline)) void TextureSampler::sample_lanes(const emu::TextureRequest& request, unsigned quads,
                                                            std::array<emu::FloatLanes, 4>& texels) const {
    static constexpr emu::FloatLanes kZero{}, kOne = [] {
        emu::FloatLanes one{};
        one.fill(1.0f);
        return one;
    }();
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
