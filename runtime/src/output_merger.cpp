// The output merger (pipeline.md §7, §10, §12, §13). See output_merger.h for the order.
#include "sm2/runtime/output_merger.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "format_layout.h"
#include "half.h"
#include "quad_rows.h"
#include "unorm8_avx512.h"

namespace sm2::runtime {

// The 8-bit fast path: render targets whose stored channels are each an 8-bit UNORM in its own
// byte of a 4-byte texel (A8R8G8B8, X8R8G8B8, A8B8G8R8, X8B8G8R8), read and written in place.
// Channels the format lacks read as their layout says (X8: alpha 1) and store nothing (the
// byte stays 0, as layout::encode leaves it).
// valid: every stored channel an 8-bit UNORM in its own byte (the compiler-vectorized path and
// the AVX-512 one); wide: every stored channel a UNORM field of up to 16 bits within one 32-bit
// word, none shared (A2B10G10R10, A2R10G10B10, G16R16 and the 8-byte A16B16G16R16 too; the
// AVX-512 path only).
struct Unorm8Texel {
    bool valid = false, wide = false;
    // Every bit of the texel lies in a field (no X bits, which a write clears): writing back the
    // values read gives the same bytes.
    bool full = false;
    unsigned words = 1;              // 32-bit words per texel: 1 or 2
    std::array<int8_t, 4> shift{};   // lowest bit of the channel's field in the texel; -1: not stored
    std::array<uint32_t, 4> mask{};  // 2^n - 1 of the channel's field
    Vec4 missing{};                  // value read for a channel that is not stored
};

// Float targets: every stored channel a 32-bit float in its own 4 bytes (R32F, G32R32F,
// A32B32G32R32F), which layout::decode and encode copy bit for bit, or a half in its own 2
// bytes (R16F, G16R16F, A16B16G16R16F: `half`, half.h's conversions), and no other bytes.
// Without blending a merge of 32-bit floats then copies each written channel's shader value
// into place; a masked channel would store the bits it read, so it is left as it is.
struct FloatTexel {
    bool valid = false;
    bool half = false;
    unsigned bytes = 0;
    std::array<int8_t, 4> offset{};  // the channel's byte in the texel; -1: not stored
    Vec4 missing{};                  // value read for a channel that is not stored
};

namespace {

constexpr unsigned kLanes = emu::kBatchLanes;
constexpr auto kLaneBit = [] {  // bit l of a LaneMask (a table: loops over lanes vectorize)
    std::array<emu::LaneMask, kLanes> bit{};
    for (unsigned l = 0; l < kLanes; ++l) bit[l] = emu::LaneMask{1} << l;
    return bit;
}();

// One channel of every lane of a batch. The blend rules below are templates over the value
// type: the generic path runs them on one float per pixel, the 8-bit fast path on whole
// batches (one switch per batch instead of one per pixel, and loops the compiler vectorizes).
struct Lanes {
    std::array<float, kLanes> v;
    Lanes() = default;
    explicit Lanes(float x) { v.fill(x); }
};
// The lane operations on a GCC vector of 16 floats, copied in and out of the array: the
// compiler emits whole-register instructions for the target (four SSE or one AVX-512 register)
// instead of re-vectorizing each loop. Same IEEE operation per lane.
// (Vectors never cross a function boundary by value: their ABI differs between the clones.)
typedef float Vector16 __attribute__((vector_size(4 * kLanes)));
[[gnu::always_inline]] inline void load(Vector16& r, const Lanes& a) { std::memcpy(&r, a.v.data(), sizeof r); }
[[gnu::always_inline]] inline Lanes lanes_of(const Vector16& x) {
    Lanes r;
    std::memcpy(r.v.data(), &x, sizeof x);
    return r;
}
[[gnu::always_inline]] inline Lanes operator+(const Lanes& a, const Lanes& b) {
    Vector16 x, y;
    load(x, a);
    load(y, b);
    return lanes_of(x + y);
}
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a, const Lanes& b) {
    Vector16 x, y;
    load(x, a);
    load(y, b);
    return lanes_of(x - y);
}
[[gnu::always_inline]] inline Lanes operator-(float a, const Lanes& b) {
    Vector16 y;
    load(y, b);
    return lanes_of(a - y);
}
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, const Lanes& b) {
    Vector16 x, y;
    load(x, a);
    load(y, b);
    return lanes_of(x * y);
}
// std::min / std::max, lane by lane (same NaN behaviour: the first argument unless the
// comparison holds).
float min_of(float a, float b) { return std::min(a, b); }
float max_of(float a, float b) { return std::max(a, b); }
[[gnu::always_inline]] inline Lanes min_of(const Lanes& a, const Lanes& b) {
    Vector16 x, y;
    load(x, a);
    load(y, b);
    return lanes_of(y < x ? y : x);
}
[[gnu::always_inline]] inline Lanes max_of(const Lanes& a, const Lanes& b) {
    Vector16 x, y;
    load(x, a);
    load(y, b);
    return lanes_of(x < y ? y : x);
}

// A float target's blended NaN is stored as the one positive quiet NaN, the rule of every result
// the shader stores (emu numerics.h): which NaN an operation on two NaNs returns (a NaN colour
// blended onto a NaN texel) depends on the operand order the compiler gave it, and the per-pixel
// and the batch paths are compiled apart.
float canonical_nan(float v) { return v != v ? std::numeric_limits<float>::quiet_NaN() : v; }
[[gnu::always_inline]] inline void canonical_nan(Lanes& x) {
    Vector16 v;
    load(v, x);
    const Vector16 nan = Vector16{} + std::numeric_limits<float>::quiet_NaN();
    x = lanes_of(v != v ? nan : v);
}

// Clamp to [0, 1]; NaN and -0 -> +0.
float saturate(float v) {
    const float c = v > 0.0f ? v : 0.0f;
    return c < 1.0f ? c : 1.0f;
}
[[gnu::always_inline]] inline void saturate(Lanes& x) {
    Vector16 v;
    load(v, x);
    const Vector16 zero{}, one = zero + 1.0f;
    const Vector16 c = v > zero ? v : zero;
    x = lanes_of(c < one ? c : one);
}

template <typename T>
using Rgba = std::array<T, 4>;

// A shader colour output of 16 lanes as the batch holds it (oC#'s register), read in place.
using ShaderColor = emu::Batch::Register;

// Channel c (0-2 colour, 3 alpha) of blend factor f (§12) for source s, destination d and
// BLENDFACTOR k.
template <typename T>
[[gnu::always_inline]] inline T factor(Blend f, unsigned c, const Rgba<T>& s, const Rgba<T>& d, const Vec4& k) {
    switch (f) {
    case Blend::Zero: return T(0.0f);
    case Blend::One: return T(1.0f);
    case Blend::SrcColor: return s[c];
    case Blend::InvSrcColor: return 1.0f - s[c];
    case Blend::SrcAlpha: case Blend::BothSrcAlpha: return s[3];
    case Blend::InvSrcAlpha: case Blend::BothInvSrcAlpha: return 1.0f - s[3];
    case Blend::DestAlpha: return d[3];
    case Blend::InvDestAlpha: return 1.0f - d[3];
    case Blend::DestColor: return d[c];
    case Blend::InvDestColor: return 1.0f - d[c];
    case Blend::SrcAlphaSat: return c < 3 ? min_of(s[3], 1.0f - d[3]) : T(1.0f);  // (f, f, f, 1)
    case Blend::BlendFactor: return T(k[c]);
    case Blend::InvBlendFactor: return T(1.0f - k[c]);
    }
    return T(0.0f);
}

template <typename T>
[[gnu::always_inline]] inline T combine(BlendOp op, const T& s, const T& fs, const T& d, const T& fd) {
    switch (op) {
    case BlendOp::Add: return s * fs + d * fd;
    case BlendOp::Subtract: return s * fs - d * fd;
    case BlendOp::RevSubtract: return d * fd - s * fs;
    case BlendOp::Min: return min_of(s, d);
    case BlendOp::Max: return max_of(s, d);
    }
    return s;
}

// §12 without the clamps: colour with SRCBLEND/DESTBLEND/BLENDOP, alpha with the alpha ones.
template <typename T>
[[gnu::always_inline]] inline Rgba<T> blend_unclamped(const BlendState& b, const Rgba<T>& s, const Rgba<T>& d) {
    Rgba<T> r;
    for (unsigned c = 0; c < 3; ++c)
        r[c] = combine(b.op, s[c], factor(b.src, c, s, d, b.factor), d[c], factor(b.dst, c, s, d, b.factor));
    r[3] = combine(b.op_alpha, s[3], factor(b.src_alpha, 3, s, d, b.factor), d[3],
                   factor(b.dst_alpha, 3, s, d, b.factor));
    return r;
}

Unorm8Texel unorm8_layout(const FormatInfo& info) {
    Unorm8Texel t;
    const layout::Layout lay = layout::layout_of(info.format);
    if (!lay.valid || (info.bytes != 4 && info.bytes != 8) || info.kind != FormatKind::Color) return t;
    uint64_t used = 0;
    bool bytes = true;
    for (unsigned c = 0; c < 4; ++c) {
        const layout::Channel ch = lay.rgba[c];
        t.shift[c] = -1;
        if (ch.type == layout::Type::Zero || ch.type == layout::Type::One) {
            t.missing[c] = ch.type == layout::Type::One ? 1.0f : 0.0f;
            continue;
        }
        if (ch.type != layout::Type::Unorm || ch.bits == 0 || ch.bits > 16 || ch.shift % 32 + ch.bits > 32) return t;
        const uint64_t field = ((uint64_t{1} << ch.bits) - 1u) << ch.shift;
        if (used & field) return t;  // one field for several channels (luminance)
        used |= field;
        t.shift[c] = static_cast<int8_t>(ch.shift);
        t.mask[c] = (1u << ch.bits) - 1u;
        bytes = bytes && ch.bits == 8 && ch.shift % 8 == 0;
    }
    t.wide = true;
    t.words = info.bytes / 4;
    t.full = used == (info.bytes == 8 ? ~uint64_t{0} : 0xFFFFFFFFull);
    t.valid = bytes && t.words == 1;
    return t;
}

// The fast-path layout of a format_table() entry, worked out once per format.
const Unorm8Texel& unorm8_texel(const FormatInfo& info) {
    static const std::vector<Unorm8Texel> table = [] {
        std::vector<Unorm8Texel> t;
        for (const FormatInfo& f : format_table()) t.push_back(unorm8_layout(f));
        return t;
    }();
    return table[static_cast<size_t>(&info - format_table().data())];
}

FloatTexel float_layout(const FormatInfo& info) {
    FloatTexel t;
    const layout::Layout lay = layout::layout_of(info.format);
    if (!lay.valid || info.kind != FormatKind::Color) return t;
    bool floats = false, halves = false;
    for (unsigned c = 0; c < 4; ++c) {
        const layout::Channel ch = lay.rgba[c];
        t.offset[c] = -1;
        if (ch.type == layout::Type::Zero || ch.type == layout::Type::One) {
            t.missing[c] = ch.type == layout::Type::One ? 1.0f : 0.0f;
            continue;
        }
        const bool float32 = ch.type == layout::Type::Float && ch.bits == 32;
        const bool half = ch.type == layout::Type::Half && ch.bits == 16;
        if (!(float32 || half) || ch.shift % 8 != 0) return t;
        floats |= float32;
        halves |= half;
        for (unsigned d = 0; d < c; ++d)
            if (t.offset[d] == static_cast<int8_t>(ch.shift / 8)) return t;  // one field for two channels
        t.offset[c] = static_cast<int8_t>(ch.shift / 8);
    }
    if (floats && halves) return t;
    t.half = halves;
    t.bytes = info.bytes;
    t.valid = true;
    return t;
}

const FloatTexel& float_texel(const FormatInfo& info) {
    static const std::vector<FloatTexel> table = [] {
        std::vector<FloatTexel> t;
        for (const FormatInfo& f : format_table()) t.push_back(float_layout(f));
        return t;
    }();
    return table[static_cast<size_t>(&info - format_table().data())];
}

// layout::decode of an 8-bit UNORM: v / 255 in float.
float decode_unorm8(uint32_t v) { return static_cast<float>(v) / 255.0f; }

// layout::encode of an 8-bit UNORM, floor(clamp(double(v) * 255, 0, 255) + 0.5) with NaN -> 0,
// for values already clamped in float (four lanes an instruction, not two): double(v) * 255 is
// exact (24 + 8 significant bits), so clamping it gives exactly double(saturate(v)) * 255. The
// sum lies in [0.5, 255.5], where truncation (which vectorizes without SSE4.1) equals floor.
// Writes bits [shift, shift + 8) of each lane's texel.
void encode_unorm8(const Lanes& unit, unsigned shift, std::array<uint32_t, kLanes>& texel) {
    for (unsigned l = 0; l < kLanes; ++l)
        texel[l] |= static_cast<uint32_t>(static_cast<int32_t>(static_cast<double>(unit.v[l]) * 255.0 + 0.5)) << shift;
}

// Whether the lanes' pixel keys are pairwise different. The fast path reads every texel before
// it writes any; the per-pixel path would let a later lane see an earlier lane's store, so a
// batch with a repeated pixel (which the rasterizer never makes) takes that path. quad_order:
// every lane's pixel has the parity of its place in its 2x2 quad (interpolate()'s order), so
// only lanes at the same place in different quads can share a pixel.
bool distinct_pixels(const std::array<uint32_t, kLanes>& key, bool quad_order) {
    unsigned same = 0;
    if (quad_order) {
        for (unsigned a = 0; a < kLanes; a += 4)
            for (unsigned b = a + 4; b < kLanes; b += 4)
                for (unsigned i = 0; i < 4; ++i) same += key[a + i] == key[b + i] ? 1u : 0u;
        return same == 0;
    }
    for (unsigned i = 0; i < kLanes; ++i)
        for (unsigned j = 0; j < kLanes; ++j) same += key[i] == key[j] ? 1u : 0u;
    return same == kLanes;
}

// Each lane's texel's byte offset in `surface` (texels of `texel_bytes`), for merge_unorm8() and
// merge_float(); only the lanes they write are read.
std::array<size_t, kLanes> texel_offsets(const PixelLanes& lanes, const Surface& surface, size_t texel_bytes) {
    std::array<size_t, kLanes> offset;
    for (unsigned l = 0; l < kLanes; ++l)
        offset[l] = static_cast<size_t>(lanes.y[l]) * surface.row_pitch() + static_cast<size_t>(lanes.x[l]) * texel_bytes;
    return offset;
}

// Blending, write mask and store for the lanes in `write` of one fast-path target (every lane
// inside the surface). src: the shader colour of each lane.
// srgb: an sRGB write (render target 0 under SRGBWRITEENABLE): the colour channels blend in
// linear space (each stored byte through srgb_to_linear_table(), srgb_to_linear's values) and
// store linear_to_srgb's byte (linear_to_srgb_byte(), exact by its thresholds); alpha as without.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void merge_unorm8(const BlendState& b, const Unorm8Texel& fmt, Surface& surface, uint32_t mask,
                  const ShaderColor& src, const std::array<size_t, kLanes>& offset, emu::LaneMask write, bool srgb) {
    std::byte* const bytes = surface.bytes().data();
    Rgba<Lanes> dst, linear, blended;
    if (b.enable || mask != 0xF) {
        std::array<uint32_t, kLanes> stored{};
        for (unsigned l = 0; l < kLanes; ++l)
            if (write >> l & 1u) std::memcpy(&stored[l], bytes + offset[l], 4);
        // (The sRGB tables only where they are read: each is a guarded static.)
        const std::array<float, 256>* to_linear = srgb ? &srgb_to_linear_table() : nullptr;
        for (unsigned c = 0; c < 4; ++c) {
            if (fmt.shift[c] < 0) {
                dst[c] = linear[c] = Lanes(fmt.missing[c]);
                continue;
            }
            const auto shift = static_cast<unsigned>(fmt.shift[c]);
            for (unsigned l = 0; l < kLanes; ++l) dst[c].v[l] = decode_unorm8(stored[l] >> shift & 0xFFu);
            linear[c] = dst[c];
            if (srgb && c < 3)
                for (unsigned l = 0; l < kLanes; ++l) linear[c].v[l] = (*to_linear)[stored[l] >> shift & 0xFFu];
        }
    }
    Rgba<Lanes> clamped;
    for (unsigned c = 0; c < 4; ++c) {
        clamped[c].v = src[c];
        saturate(clamped[c]);
    }
    if (b.enable) {
        blended = blend_unclamped(b, clamped, linear);
        for (Lanes& c : blended) saturate(c);
    }
    const Rgba<Lanes>& out = b.enable ? blended : clamped;  // in [0, 1], as is dst
    std::array<uint32_t, kLanes> packed{};
    const std::array<float, 256>* thresholds = srgb ? &linear_to_srgb_byte_thresholds() : nullptr;
    for (unsigned c = 0; c < 4; ++c) {
        if (fmt.shift[c] < 0) continue;
        const auto shift = static_cast<unsigned>(fmt.shift[c]);
        if (srgb && c < 3 && (mask >> c & 1u)) {
            for (unsigned l = 0; l < kLanes; ++l) packed[l] |= linear_to_srgb_byte(out[c].v[l], *thresholds) << shift;
            continue;
        }
        // A masked channel stores what it read (which encodes back to the same byte).
        encode_unorm8(mask >> c & 1u ? out[c] : dst[c], shift, packed);
    }
    for (unsigned l = 0; l < kLanes; ++l)
        if (write >> l & 1u) std::memcpy(bytes + offset[l], &packed[l], 4);
}

// half.h's conversions for 16 lanes at once, the same bits: GCC vectors of 16 32-bit lanes
// (one AVX-512 register, two AVX2 ones in the clones below), branch-free.
typedef uint32_t Words16 __attribute__((vector_size(4 * kLanes)));

// half_to_float() of the halves in the low 16 bits of each lane: normal values rebiased,
// infinities and NaNs with their payload as it is, denormals as their exact value m * 2^-24.
[[gnu::always_inline]] inline void halves_to_floats(const Words16& h, Vector16& r) {
    const Words16 magnitude = h & 0x7FFFu, sign = (h & 0x8000u) << 16, shifted = magnitude << 13;
    Words16 bits = shifted + (112u << 23);
    bits = magnitude >= 0x7C00u ? shifted | 0x7F800000u : bits;
    const Vector16 tiny = __builtin_convertvector(magnitude, Vector16) * 0x1p-24f;
    Words16 tiny_bits;
    std::memcpy(&tiny_bits, &tiny, sizeof tiny);
    bits = magnitude < 0x400u ? tiny_bits : bits;
    bits |= sign;
    std::memcpy(&r, &bits, sizeof r);
}

// float_to_half() of each lane (round to nearest even; overflow to infinity; a NaN kept quiet
// with the top of its payload), in the low 16 bits.
[[gnu::always_inline]] inline void floats_to_halves(const Vector16& f, Words16& result) {
    Words16 bits;
    std::memcpy(&bits, &f, sizeof bits);
    const Words16 sign = (bits >> 16) & 0x8000u, x = bits & 0x7FFFFFFFu, exponent = x >> 23;
    const Words16 mantissa = x & 0x7FFFFFu;
    // Normal halves (exponent 113-142): the rebiased bits cut to 10 mantissa bits, rounded to
    // nearest even on the 13 bits cut (a carry may reach the exponent, or infinity).
    Words16 normal = (x - (112u << 23)) >> 13;
    const Words16 rest = x & 0x1FFFu;
    normal += (rest > 0x1000u) | ((rest == 0x1000u) & (normal & 1u)) ? Words16{} + 1u : Words16{};
    // Denormal halves (exponent 102-112): the 24-bit mantissa shifted by 126 - exponent (14-24).
    const Words16 shift = 126u - exponent, full = mantissa | 0x800000u;
    const Words16 safe_shift = exponent >= 102u && exponent <= 112u ? shift : Words16{} + 14u;
    Words16 denormal = full >> safe_shift;
    const Words16 one = Words16{} + 1u;
    const Words16 below = full & ((one << safe_shift) - 1u), halfway = one << (safe_shift - 1u);
    denormal += (below > halfway) | ((below == halfway) & (denormal & 1u)) ? one : Words16{};
    Words16 r = exponent >= 113u ? normal : exponent >= 102u ? denormal : Words16{};
    r = exponent >= 143u ? Words16{} + 0x7C00u : r;                              // overflow (and infinity)
    r = x > 0x7F800000u ? 0x7C00u | 0x200u | (mantissa >> 13) : r;               // NaN
    result = r | sign;
}

// A float target's merge (TargetPath::FloatMerge) for the lanes in `write`, at pixels `offset`
// (pairwise different): the stored texels decoded as layout::decode does (a half by
// half_to_float, a float as its bits), blend_unclamped() on the whole batch (float targets
// clamp neither the source nor the result), and each lane's texel encoded as layout::encode
// does (a masked channel stores what it read). The per-pixel path's operations, so its bytes
// (output_merger_fast_test).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void merge_float(const BlendState& b, const FloatTexel& fmt, Surface& surface, uint32_t mask, const ShaderColor& src,
                 const std::array<size_t, kLanes>& offset, emu::LaneMask write) {
    std::byte* const bytes = surface.bytes().data();
    Rgba<Lanes> dst, in, blended;
    for (unsigned c = 0; c < 4; ++c) {
        in[c].v = src[c];
        dst[c] = Lanes(fmt.missing[c]);
    }
    if (b.enable || mask != 0xF) {
        for (unsigned c = 0; c < 4; ++c) {
            if (fmt.offset[c] < 0) continue;
            std::array<uint32_t, kLanes> field{};  // the bits of the lanes in `write`
            const std::byte* const at = bytes + fmt.offset[c];
            // (Constant sizes: a copy of a size known at run time is a call to memcpy.)
            for (unsigned l = 0; l < kLanes; ++l) {
                if (!(write >> l & 1u)) continue;
                if (fmt.half) std::memcpy(&field[l], at + offset[l], 2);
                else std::memcpy(&field[l], at + offset[l], 4);
            }
            if (fmt.half) {
                Words16 h;
                Vector16 v;
                std::memcpy(&h, field.data(), sizeof h);
                halves_to_floats(h, v);
                dst[c] = lanes_of(v);
            } else {
                std::memcpy(dst[c].v.data(), field.data(), sizeof field);
            }
        }
    }
    if (b.enable) {
        blended = blend_unclamped(b, in, dst);
        for (Lanes& c : blended) canonical_nan(c);
    }
    const Rgba<Lanes>& out = b.enable ? blended : in;
    for (unsigned c = 0; c < 4; ++c) {
        if (fmt.offset[c] < 0) continue;
        const Lanes& value = mask >> c & 1u ? out[c] : dst[c];
        std::array<uint32_t, kLanes> field;
        if (fmt.half) {
            Vector16 v;
            load(v, value);
            Words16 h;
            floats_to_halves(v, h);
            std::memcpy(field.data(), &h, sizeof h);
        } else {
            std::memcpy(field.data(), value.v.data(), sizeof field);
        }
        std::byte* const at = bytes + fmt.offset[c];
        for (unsigned l = 0; l < kLanes; ++l) {
            if (!(write >> l & 1u)) continue;
            if (fmt.half) std::memcpy(at + offset[l], &field[l], 2);
            else std::memcpy(at + offset[l], &field[l], 4);
        }
    }
}

// Blending of a whole batch, then the fixed-point clamp: the templates above inlined into one
// function the compiler vectorizes (AVX-512 where the CPU has it).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void blend_batch(const BlendState& b, const Rgba<Lanes>& src, const Rgba<Lanes>& dst, Rgba<Lanes>& out) {
    out = blend_unclamped(b, src, dst);
    for (Lanes& c : out) saturate(c);
}

// The lanes of `live` inside a width x height target, and whether their pixels are pairwise
// different (distinct_pixels()), as lane_places_block() (output_merger_block.inc) finds them in
// vector registers: the keys, the quad-order test and, for batches in quad order, the two
// comparisons with the keys rotated by one and by two quads.
struct LanePlaces {
    emu::LaneMask write = 0;
    bool distinct = false;
};

// The classic "source over" blend (SRCALPHA, INVSRCALPHA, ADD for colour and alpha), which
// merge_unorm8_block() does in registers.
bool source_over(const BlendState& b) {
    return b.src == Blend::SrcAlpha && b.dst == Blend::InvSrcAlpha && b.op == BlendOp::Add &&
           b.src_alpha == Blend::SrcAlpha && b.dst_alpha == Blend::InvSrcAlpha && b.op_alpha == BlendOp::Add;
}

// Additive blending (ONE, ONE, ADD for colour and alpha): s * 1 + d * 1 is s + d exactly.
bool additive(const BlendState& b) {
    return b.src == Blend::One && b.dst == Blend::One && b.op == BlendOp::Add && b.src_alpha == Blend::One &&
           b.dst_alpha == Blend::One && b.op_alpha == BlendOp::Add;
}

// The 8-bit block kernel's instance for blend state `b` (MergePlan::blend).
KernelBlend kernel_blend(const BlendState& b) {
    return !b.enable ? KernelBlend::Off : source_over(b) ? KernelBlend::SourceOver : additive(b) ? KernelBlend::Additive : KernelBlend::Any;
}


}  // namespace

}  // namespace sm2::runtime

// The block kernels, once per instruction set (block_instances.inc).
#define SM2_BLOCK_KERNELS "output_merger_block.inc"
#include "block_instances.inc"

namespace sm2::runtime {

OutputMergerState output_merger_state(const RenderState& rs) {
    OutputMergerState s;
    s.fog_enable = rs.fog_enable;
    s.fog_table_mode = rs.fog_table_mode;
    s.fog_start = rs.fog_start;
    s.fog_end = rs.fog_end;
    s.fog_density = rs.fog_density;
    s.fog_color = color_to_float4(rs.fog_color);
    s.alpha_test = rs.alpha_test_enable;
    s.alpha_func = rs.alpha_func;
    s.alpha_ref = static_cast<float>(rs.alpha_ref & 0xFFu) / 255.0f;
    s.depth_stencil = depth_stencil_state(rs);
    s.blend.enable = rs.alpha_blend_enable;
    s.blend.src = rs.src_blend;
    s.blend.dst = rs.dest_blend;
    s.blend.op = rs.blend_op;
    // BOTHSRCALPHA / BOTHINVSRCALPHA as SRCBLEND force the destination factor.
    if (rs.src_blend == Blend::BothSrcAlpha) s.blend.dst = Blend::InvSrcAlpha;
    if (rs.src_blend == Blend::BothInvSrcAlpha) s.blend.dst = Blend::SrcAlpha;
    if (rs.separate_alpha_blend_enable) {
        s.blend.src_alpha = rs.src_blend_alpha;
        s.blend.dst_alpha = rs.dest_blend_alpha;
        s.blend.op_alpha = rs.blend_op_alpha;
        if (rs.src_blend_alpha == Blend::BothSrcAlpha) s.blend.dst_alpha = Blend::InvSrcAlpha;
        if (rs.src_blend_alpha == Blend::BothInvSrcAlpha) s.blend.dst_alpha = Blend::SrcAlpha;
    } else {
        s.blend.src_alpha = s.blend.src;
        s.blend.dst_alpha = s.blend.dst;
        s.blend.op_alpha = s.blend.op;
    }
    s.blend.factor = color_to_float4(rs.blend_factor);
    s.write_mask = rs.color_write_enable;
    s.srgb_write = rs.srgb_write_enable;
    return s;
}

bool is_float_target(Format f) {
    switch (f) {
    case Format::R16F: case Format::G16R16F: case Format::A16B16G16R16F: case Format::R32F:
    case Format::G32R32F: case Format::A32B32G32R32F: return true;
    default: return false;
    }
}

float fog_factor(const OutputMergerState& s, float vertex_fog, float depth) {
    float f = vertex_fog;
    const double d = depth;
    switch (s.fog_table_mode) {
    case FogMode::None: break;
    case FogMode::Linear: {
        const double range = static_cast<double>(s.fog_end) - s.fog_start;
        // FOGEND == FOGSTART: a step at the fog end (the limit of the formula).
        f = range != 0.0 ? static_cast<float>((s.fog_end - d) / range) : (d < s.fog_end ? 1.0f : 0.0f);
        break;
    }
    case FogMode::Exp: f = static_cast<float>(std::exp(-(d * s.fog_density))); break;
    case FogMode::Exp2: {
        const double x = d * s.fog_density;
        f = static_cast<float>(std::exp(-(x * x)));
        break;
    }
    }
    return saturate(f);
}

bool alpha_test_passes(const OutputMergerState& s, float alpha, bool target_clamps) {
    if (std::isnan(alpha)) return s.alpha_func == CompareFunc::Always;
    return compare(s.alpha_func, target_clamps ? saturate(alpha) : alpha, s.alpha_ref);
}

Vec4 blend(const BlendState& b, const Vec4& src_in, const Vec4& dst, bool fixed_point) {
    Vec4 src = src_in;
    if (fixed_point)
        for (float& c : src) c = saturate(c);
    Vec4 r = blend_unclamped(b, src, dst);
    for (float& c : r) c = fixed_point ? saturate(c) : canonical_nan(c);
    return r;
}

MergePlan merge_plan(const OutputMergerState& s, const RenderTargets& targets, const MergeInput& in) {
    MergePlan plan;
    // The 16-lane kernels' instance this CPU runs (output_merger_block.inc), if any.
    plan.avx512_block = cpu_has_avx512() && !in.block_avx2;
    plan.block = plan.avx512_block || cpu_has_avx2();
    plan.alpha_clamps = !(targets.color[0] && is_float_target(targets.color[0]->format()));
    plan.blend = kernel_blend(s.blend);
    for (unsigned t = 0; t < kMaxRenderTargets; ++t) {
        const Surface* surface = targets.color[t];
        TargetPlan& target = plan.targets[t];
        // A target the shader does not write keeps its contents; an oC# without a target is dropped.
        if (!surface || !(in.color_outputs >> t & 1u)) continue;
        target.mask = s.write_mask[t] & 0xFu;
        if (target.mask == 0) continue;
        const FormatInfo* info = format_info(surface->format());
        if (!info || !info->render_target || surface->depth() != 1) continue;  // not a target
        target.info = info;
        target.fixed = !is_float_target(surface->format());
        target.srgb = t == 0 && s.srgb_write && info->srgb;
        target.path = TargetPath::PerPixel;
        if (in.generic_path) continue;
        target.unorm8 = &unorm8_texel(*info);
        target.floats = &float_texel(*info);
        if (target.srgb) {
            // sRGB writes of 8-bit fields: merge_unorm8()'s sRGB conversions.
            if (target.unorm8->valid) target.path = TargetPath::Unorm8Lanes;
            continue;
        }
        // (32-bit offsets in the 16-lane kernels.)
        const bool block = plan.block && surface->bytes().size() <= size_t{INT32_MAX};
        const Unorm8Texel& unorm = *target.unorm8;
        if (unorm.wide && block) {
            target.path = unorm.words == 2 ? TargetPath::Unorm8Block8 : TargetPath::Unorm8Block;
            target.bytes = unorm.valid;
            // Source over with an alpha that saturates to +0: every channel, blended or masked,
            // is d = s * 0 + d * 1 (s saturated first, d in [0, 1]), which encodes back to the
            // same field; where every bit of the texel is a field's (Unorm8Texel::full; a write
            // clears X bits) the bytes stay as they are. Nothing to read or write (the
            // transparent parts of blended slices and sprites).
            target.transparent_skips = unorm.full && s.blend.enable && source_over(s.blend);
        } else if (unorm.valid) {
            target.path = TargetPath::Unorm8Lanes;
        } else if (const FloatTexel& floats = *target.floats; floats.valid) {
            target.path = s.blend.enable || floats.half ? TargetPath::FloatMerge
                          : block                       ? TargetPath::FloatBlock
                                                        : TargetPath::FloatLanes;
        }
    }
    return plan;
}

emu::LaneMask merge(const OutputMergerState& s, const RenderTargets& targets, const MergeInput& in) {
    return merge(s, targets, in, merge_plan(s, targets, in));
}

// (Not target_clones, unlike the internal functions above: clang 14 does not multiversion a
// function whose header declaration lacks the attribute; it compiled this one for x86-64-v4
// alone, an illegal instruction on CPUs without AVX-512.)
emu::LaneMask merge(const OutputMergerState& s, const RenderTargets& targets, const MergeInput& in,
                    const MergePlan& plan) {
    const emu::Batch& batch = *in.batch;
    const PixelLanes& lanes = *in.lanes;
    emu::LaneMask live = in.live & ~batch.killed;
    const bool avx512_block = plan.avx512_block;
    if (lanes.quad_count * 4 < kLanes) live &= (emu::LaneMask{1} << (lanes.quad_count * 4)) - 1;

    // Depth of each lane: oDepth (no bias) or the interpolated, biased depth. The depth test
    // clamps it to [0, 1] (quantize_depth()) as saturate does; fog reads a saturated copy.
    const std::array<float, kLanes>& unclamped_depth = in.shader_depth ? batch.depth()[0] : lanes.depth;

    // oC0 after fog (§7 step 2): the batch's register itself where there is no fog.
    ShaderColor fogged;
    const ShaderColor* color0_in = &batch.render_target(0);
    if (s.fog_enable) {
        std::array<float, kLanes> depth = unclamped_depth;
        for (float& z : depth) z = saturate(z);
        std::array<float, kLanes> f;
        for (unsigned l = 0; l < kLanes; ++l)
            f[l] = fog_factor(s, lanes.fog[l], s.table_fog_of_w ? lanes.fog[l] : depth[l]);
        fogged = batch.render_target(0);
        for (unsigned c = 0; c < 3; ++c)
            for (unsigned l = 0; l < kLanes; ++l)
                fogged[c][l] = f[l] * fogged[c][l] + (1.0f - f[l]) * s.fog_color[c];
        color0_in = &fogged;
    }
    const ShaderColor& color0 = *color0_in;
    // Alpha test (§10): failing pixels never reach the stencil stage. The alpha is clamped only
    // where render target 0 clamps: a float target tests what the shader wrote.
    if (s.alpha_test) {
        for (unsigned l = 0; l < kLanes; ++l)
            if ((live >> l & 1u) && !alpha_test_passes(s, color0[3][l], plan.alpha_clamps)) live &= ~(emu::LaneMask{1} << l);
    }
    // Stencil, depth, stencil update (§11).
    if (!in.depth_stencil_done)
        live = depth_stencil_test(s.depth_stencil, targets.depth_stencil, lanes.x, lanes.y, unclamped_depth, live,
                                  lanes.clockwise, in.generic_path);

    for (unsigned t = 0; t < kMaxRenderTargets; ++t) {
        const TargetPlan& target = plan.targets[t];
        if (target.path == TargetPath::Skip) continue;
        Surface* const surface = targets.color[t];
        const uint32_t mask = target.mask;
        const bool fixed = target.fixed, srgb = target.srgb;
        const ShaderColor& src = t == 0 ? color0 : batch.render_target(t);
        // (transparent_skips: a block path, so plan.block. Tested on `live`, a superset of the
        // lanes written.)
        if (target.transparent_skips &&
            (avx512_block ? avx512::transparent_block(src, live) : avx2::transparent_block(src, live)))
            continue;
        // The live lanes inside the surface, and a key per lane that differs between pixels (one
        // vectorized loop: no branches).
        emu::LaneMask write = 0;
        bool distinct = false;
        const uint32_t width = surface->width(), height = surface->height();
        if (plan.block) {
            const LanePlaces places = avx512_block ? avx512::lane_places_block(lanes, live, width, height)
                                                   : avx2::lane_places_block(lanes, live, width, height);
            write = places.write;
            distinct = places.distinct;
        } else {
            std::array<uint32_t, kLanes> key;
            uint32_t misplaced = 0;  // a lane not at its place in a 2x2 quad (see distinct_pixels)
            for (unsigned l = 0; l < kLanes; ++l) {
                // Negative coordinates wrap to values above any size.
                const auto x = static_cast<uint32_t>(lanes.x[l]), y = static_cast<uint32_t>(lanes.y[l]);
                const bool inside = ((live & kLaneBit[l]) != 0) & (x < width) & (y < height);
                write |= inside ? kLaneBit[l] : 0u;
                key[l] = inside ? y * width + x : 0x80000000u | l;  // outside: unlike every pixel (16384^2 < 2^31)
                misplaced |= inside && ((x & 1u) | (y & 1u) << 1) != (l & 3u) ? 1u : 0u;
            }
            distinct = distinct_pixels(key, misplaced == 0);
        }
        if (!write) continue;

        // The 8-bit paths blend the batch's texels at once: a pixel two lanes write (not
        // `distinct`) goes pixel by pixel, where the later lane blends onto the earlier one.
        TargetPath path = target.path;
        if (!distinct && (path == TargetPath::Unorm8Block || path == TargetPath::Unorm8Block8 || path == TargetPath::Unorm8Lanes ||
                          path == TargetPath::FloatMerge))
            path = TargetPath::PerPixel;
        switch (path) {
        case TargetPath::Unorm8Block:
        case TargetPath::Unorm8Block8: {
            const Unorm8Texel& fmt = *target.unorm8;
            // Side by side in one quad row (see kRowLane), all 16 pixels inside the surface?
            bool run = lanes.quad_count == 4 && lanes.x[0] >= 0 && lanes.y[0] >= 0 &&
                       static_cast<uint32_t>(lanes.x[0]) + 8 <= width && static_cast<uint32_t>(lanes.y[0]) + 2 <= height;
            for (unsigned q = 1; q < 4; ++q)
                run = run && lanes.x[4 * q] == lanes.x[0] + static_cast<int32_t>(2 * q) && lanes.y[4 * q] == lanes.y[0];
            const auto run_kernel = [&](auto kernel) { kernel(s.blend, fmt, *surface, mask, src, lanes, run, write); };
            if (path == TargetPath::Unorm8Block8) avx512_block ? run_kernel(avx512::merge_unorm8_block<2, false>) : run_kernel(avx2::merge_unorm8_block<2, false>);
            else if (target.bytes) {
                switch (plan.blend) {
                case KernelBlend::Off: avx512_block ? run_kernel(avx512::merge_unorm8_block<1, true, KernelBlend::Off>) : run_kernel(avx2::merge_unorm8_block<1, true, KernelBlend::Off>); break;
                case KernelBlend::SourceOver: avx512_block ? run_kernel(avx512::merge_unorm8_block<1, true, KernelBlend::SourceOver>) : run_kernel(avx2::merge_unorm8_block<1, true, KernelBlend::SourceOver>); break;
                case KernelBlend::Additive: avx512_block ? run_kernel(avx512::merge_unorm8_block<1, true, KernelBlend::Additive>) : run_kernel(avx2::merge_unorm8_block<1, true, KernelBlend::Additive>); break;
                case KernelBlend::Any: avx512_block ? run_kernel(avx512::merge_unorm8_block<1, true>) : run_kernel(avx2::merge_unorm8_block<1, true>); break;
                }
            }
            else avx512_block ? run_kernel(avx512::merge_unorm8_block<1, false>) : run_kernel(avx2::merge_unorm8_block<1, false>);
            continue;
        }
        case TargetPath::Unorm8Lanes:
            merge_unorm8(s.blend, *target.unorm8, *surface, mask, src, texel_offsets(lanes, *surface, 4), write, srgb);
            continue;
        case TargetPath::FloatMerge: {
            const FloatTexel& fmt = *target.floats;
            merge_float(s.blend, fmt, *surface, mask, src, texel_offsets(lanes, *surface, fmt.bytes), write);
            continue;
        }
        case TargetPath::FloatBlock:
            if (avx512_block) avx512::copy_float_block(*target.floats, *surface, mask, src, lanes, write);
            else avx2::copy_float_block(*target.floats, *surface, mask, src, lanes, write);
            continue;
        case TargetPath::FloatLanes: {
            const FloatTexel& fmt = *target.floats;
            std::byte* const bytes = surface->bytes().data();
            for (unsigned l = 0; l < kLanes; ++l) {
                if (!(write >> l & 1u)) continue;  // lane order: a repeated pixel keeps the later lane
                std::byte* const texel = bytes + static_cast<size_t>(lanes.y[l]) * surface->row_pitch() +
                                         static_cast<size_t>(lanes.x[l]) * fmt.bytes;
                for (unsigned c = 0; c < 4; ++c)
                    if (fmt.offset[c] >= 0 && (mask >> c & 1u)) std::memcpy(texel + fmt.offset[c], &src[c][l], 4);
            }
            continue;
        }
        case TargetPath::Skip:
        case TargetPath::PerPixel: break;
        }

        // Every other target: one pixel at a time through the surface's texel conversions.
        for (unsigned l = 0; l < kLanes; ++l) {
            if (!(write >> l & 1u)) continue;
            const auto px = static_cast<uint32_t>(lanes.x[l]), py = static_cast<uint32_t>(lanes.y[l]);
            const Vec4 lane_src{src[0][l], src[1][l], src[2][l], src[3][l]};
            const bool need_dst = s.blend.enable || mask != 0xF;
            Vec4 stored{};
            if (need_dst) stored = surface->read(px, py, 0);
            Vec4 out = lane_src;
            if (s.blend.enable) {
                Vec4 dst = stored;
                if (srgb)
                    for (unsigned c = 0; c < 3; ++c) dst[c] = srgb_to_linear(dst[c]);
                out = blend(s.blend, lane_src, dst, fixed);
            }
            if (srgb)
                for (unsigned c = 0; c < 3; ++c) out[c] = linear_to_srgb(saturate(out[c]));
            for (unsigned c = 0; c < 4; ++c)
                if (!(mask >> c & 1u)) out[c] = stored[c];
            surface->write(px, py, 0, out);
        }
    }
    return live;
}

}  // namespace sm2::runtime
