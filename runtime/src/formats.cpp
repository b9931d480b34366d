// The D3DFORMAT table and the texel codecs: every uncompressed format is described once, as the
// bit range and numeric type of each of its channels (pipeline.md §15, names list channels from
// the most significant bit, memory is little-endian), and the decoders/encoders are generated
// from that description. DXTn blocks are decoded in dxt.cpp.
#include "sm2/runtime/formats.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "dxt.h"
#include "format_layout.h"
#include "half.h"

namespace sm2::runtime {

namespace {

using enum Format;
constexpr FormatKind C = FormatKind::Color;
constexpr FormatKind S = FormatKind::Signed;
constexpr FormatKind X = FormatKind::Compressed;
constexpr FormatKind D = FormatKind::Depth;
constexpr FormatKind I = FormatKind::Index;

// format, name, kind, bytes, render target, texture, srgb, depth bits, stencil bits
constexpr FormatInfo kFormats[] = {
    {R8G8B8, "R8G8B8", C, 3, false, true, true, 0, 0},
    {A8R8G8B8, "A8R8G8B8", C, 4, true, true, true, 0, 0},
    {X8R8G8B8, "X8R8G8B8", C, 4, true, true, true, 0, 0},
    {R5G6B5, "R5G6B5", C, 2, true, true, false, 0, 0},
    {X1R5G5B5, "X1R5G5B5", C, 2, true, true, false, 0, 0},
    {A1R5G5B5, "A1R5G5B5", C, 2, true, true, false, 0, 0},
    {A4R4G4B4, "A4R4G4B4", C, 2, true, true, false, 0, 0},
    {R3G3B2, "R3G3B2", C, 1, false, true, false, 0, 0},
    {A8, "A8", C, 1, false, true, false, 0, 0},
    {A8R3G3B2, "A8R3G3B2", C, 2, false, true, false, 0, 0},
    {X4R4G4B4, "X4R4G4B4", C, 2, true, true, false, 0, 0},
    {A2B10G10R10, "A2B10G10R10", C, 4, true, true, false, 0, 0},
    {A8B8G8R8, "A8B8G8R8", C, 4, true, true, true, 0, 0},
    {X8B8G8R8, "X8B8G8R8", C, 4, true, true, true, 0, 0},
    {G16R16, "G16R16", C, 4, true, true, false, 0, 0},
    {A2R10G10B10, "A2R10G10B10", C, 4, true, true, false, 0, 0},
    {A16B16G16R16, "A16B16G16R16", C, 8, true, true, false, 0, 0},
    {L8, "L8", C, 1, false, true, true, 0, 0},
    {A8L8, "A8L8", C, 2, false, true, true, 0, 0},
    {A4L4, "A4L4", C, 1, false, true, false, 0, 0},
    {V8U8, "V8U8", S, 2, false, true, false, 0, 0},
    {L6V5U5, "L6V5U5", S, 2, false, true, false, 0, 0},
    {X8L8V8U8, "X8L8V8U8", S, 4, false, true, false, 0, 0},
    {Q8W8V8U8, "Q8W8V8U8", S, 4, false, true, false, 0, 0},
    {V16U16, "V16U16", S, 4, false, true, false, 0, 0},
    {A2W10V10U10, "A2W10V10U10", S, 4, false, true, false, 0, 0},
    {D16_LOCKABLE, "D16_LOCKABLE", D, 2, false, false, false, 16, 0},
    {D32, "D32", D, 4, false, false, false, 32, 0},
    {D15S1, "D15S1", D, 2, false, false, false, 15, 1},
    {D24S8, "D24S8", D, 4, false, false, false, 24, 8},
    {D24X8, "D24X8", D, 4, false, false, false, 24, 0},
    {D24X4S4, "D24X4S4", D, 4, false, false, false, 24, 4},
    {D16, "D16", D, 2, false, false, false, 16, 0},
    {L16, "L16", C, 2, false, true, false, 0, 0},
    {D32F_LOCKABLE, "D32F_LOCKABLE", D, 4, false, false, false, 32, 0},
    {D24FS8, "D24FS8", D, 4, false, false, false, 24, 8},
    {INDEX16, "INDEX16", I, 2, false, false, false, 0, 0},
    {INDEX32, "INDEX32", I, 4, false, false, false, 0, 0},
    {Q16W16V16U16, "Q16W16V16U16", S, 8, false, true, false, 0, 0},
    {R16F, "R16F", C, 2, true, true, false, 0, 0},
    {G16R16F, "G16R16F", C, 4, true, true, false, 0, 0},
    {A16B16G16R16F, "A16B16G16R16F", C, 8, true, true, false, 0, 0},
    {R32F, "R32F", C, 4, true, true, false, 0, 0},
    {G32R32F, "G32R32F", C, 8, true, true, false, 0, 0},
    {A32B32G32R32F, "A32B32G32R32F", C, 16, true, true, false, 0, 0},
    {DXT1, "DXT1", X, 8, false, true, true, 0, 0},
    {DXT2, "DXT2", X, 16, false, true, true, 0, 0},
    {DXT3, "DXT3", X, 16, false, true, true, 0, 0},
    {DXT4, "DXT4", X, 16, false, true, true, 0, 0},
    {DXT5, "DXT5", X, 16, false, true, true, 0, 0},
};

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
        if (lower(a[i]) != lower(b[i])) return false;
    }
    return true;
}

// Generated decoders, one per layout-described format, in table order.
template <Format F>
Float4 decode_fn(const std::byte* texel) {
    return layout::decode<F>(texel);
}

// The layout is a constant here, so each format gets its own encoder; the bytewise 8-bit ones
// take a direct path with the same rounding as layout::encode (round(clamp(v) * 255), halves up,
// NaN -> 0, in double).
template <size_t I>
void encode_fn(const Float4& value, std::byte* texel) {
    constexpr layout::Layout Lay = layout::layout_of(kFormats[I].format);
    constexpr unsigned kBytes = kFormats[I].bytes;
    if constexpr (layout::bytewise_unorm8(Lay) && kBytes <= 4) {
        uint32_t packed = 0;
        for (unsigned i = 0; i < 4; ++i) {
            if (Lay.rgba[i].type != layout::Type::Unorm) continue;
            const double scaled = static_cast<double>(value[i]) * 255.0;
            const double clamped = !(scaled > 0.0) ? 0.0 : scaled > 255.0 ? 255.0 : scaled;
            packed |= layout::round_to_uint(clamped) << Lay.rgba[i].shift;
        }
        std::memcpy(texel, &packed, kBytes);  // little-endian, as the layouts are
    } else {
        layout::encode(Lay, kBytes, value, texel);
    }
}

template <size_t... Is>
constexpr std::array<TexelEncoder, sizeof...(Is)> make_encoders(std::index_sequence<Is...>) {
    return {(layout::layout_of(kFormats[Is].format).valid ? &encode_fn<Is> : nullptr)...};
}

template <size_t... Is>
constexpr std::array<TexelDecoder, sizeof...(Is)> make_decoders(std::index_sequence<Is...>) {
    return {(layout::layout_of(kFormats[Is].format).valid ? &decode_fn<kFormats[Is].format> : nullptr)...};
}

constexpr size_t kFormatCount = std::size(kFormats);
constexpr auto kDecoders = make_decoders(std::make_index_sequence<kFormatCount>{});
constexpr auto kEncoders = make_encoders(std::make_index_sequence<kFormatCount>{});

// Every format value below 256 (all but the FOURCC codes) indexes this table directly: the
// output merger and the sampler look a format up per batch.
constexpr size_t kDirectFormats = 256;
static_assert(kFormatCount < 256, "table indices fit a byte");
constexpr auto kDirectIndex = [] {
    std::array<uint8_t, kDirectFormats> index{};
    index.fill(static_cast<uint8_t>(kFormatCount));
    for (size_t i = 0; i < kFormatCount; ++i) {
        const auto value = static_cast<uint32_t>(kFormats[i].format);
        if (value < kDirectFormats && index[value] == kFormatCount) index[value] = static_cast<uint8_t>(i);
    }
    return index;
}();

size_t table_index(Format format) {
    const auto value = static_cast<uint32_t>(format);
    if (value < kDirectFormats) return kDirectIndex[value];
    for (size_t i = 0; i < kFormatCount; ++i)
        if (kFormats[i].format == format) return i;
    return kFormatCount;
}

[[noreturn]] void unsupported(const char* what, Format format) {
    throw std::invalid_argument(std::string(what) + ": format " +
                                std::to_string(static_cast<uint32_t>(format)) + " has no texel layout");
}

}  // namespace

std::span<const FormatInfo> format_table() { return kFormats; }

const FormatInfo* format_info(Format format) {
    const size_t i = table_index(format);
    return i < kFormatCount ? &kFormats[i] : nullptr;
}

const FormatInfo* find_format(std::string_view name) {
    if (name.size() > 7 && iequals(name.substr(0, 7), "D3DFMT_")) name.remove_prefix(7);
    for (const FormatInfo& info : kFormats)
        if (iequals(info.name, name)) return &info;
    return nullptr;
}

TexelDecoder texel_decoder(Format format) {
    const size_t i = table_index(format);
    return i < kFormatCount ? kDecoders[i] : nullptr;
}

Float4 decode_texel(Format format, const std::byte* texel) {
    const TexelDecoder decoder = texel_decoder(format);
    if (decoder == nullptr) unsupported("decode_texel", format);
    return decoder(texel);
}

TexelEncoder texel_encoder(Format format) {
    const size_t i = table_index(format);
    return i < kFormatCount ? kEncoders[i] : nullptr;
}

void encode_texel(Format format, const Float4& value, std::byte* texel) {
    const TexelEncoder encoder = texel_encoder(format);
    if (encoder == nullptr) unsupported("encode_texel", format);
    encoder(value, texel);
}

void decode_block(Format format, const std::byte* block, std::array<Float4, 16>& texels) {
    if (!dxt::is_dxt(format)) unsupported("decode_block", format);
    std::array<dxt::Rgba8, 16> rgba;
    dxt::decode_block(format, block, rgba);
    for (size_t i = 0; i < 16; ++i) texels[i] = dxt::to_float(rgba[i]);
}

namespace {
struct SrgbTable {
    std::array<float, 256> to_linear{};
    SrgbTable() {
        for (unsigned i = 0; i < 256; ++i) to_linear[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    }
};
}  // namespace

float srgb_to_linear(float c) {
    // pipeline.md §12: c <= 0.04045 ? c/12.92 : ((c + 0.055)/1.055)^2.4, evaluated in double.
    const double d = c;
    if (!(d > 0.04045)) return static_cast<float>(d / 12.92);  // NaN stays NaN
    return static_cast<float>(std::pow((d + 0.055) / 1.055, 2.4));
}

float linear_to_srgb(float c) {
    const double d = c;
    if (!(d > 0.0031308)) return static_cast<float>(12.92 * d);
    return static_cast<float>(1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

const std::array<float, 256>& srgb_to_linear_table() {
    static const SrgbTable table;
    return table.to_linear;
}

const std::array<float, 256>& linear_to_srgb_byte_thresholds() {
    static const std::array<float, 256> thresholds = [] {
        // layout::encode's 8-bit UNORM store of linear_to_srgb(v).
        const auto byte = [](float v) {
            const double scaled = static_cast<double>(linear_to_srgb(v)) * 255.0;
            return std::floor((!(scaled > 0.0) ? 0.0 : scaled > 255.0 ? 255.0 : scaled) + 0.5);
        };
        std::array<float, 256> t{};
        for (unsigned k = 1; k < 256; ++k) {
            // The least bit pattern in [0, 1.0f] whose byte reaches k (floats in [0, 1] order as
            // their bits do).
            uint32_t low = 0, high = 0x3F800000u;
            while (low < high) {
                const uint32_t mid = low + (high - low) / 2;
                if (byte(std::bit_cast<float>(mid)) >= k) high = mid;
                else low = mid + 1;
            }
            t[k] = std::bit_cast<float>(low);
        }
        return t;
    }();
    return thresholds;
}

}  // namespace sm2::runtime
