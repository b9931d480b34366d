// The sampler's 16-lane path (its AVX-512 instance and its AVX2 one, whichever the CPU runs)
// against its per-lane path: the same texels, bit for bit, over random textures, sampler states,
// coordinates (special values included) and texld variants. The per-lane path is the reference whose values sampler_test.cpp derives by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "sm2/runtime/sampler.h"
#include "sm2/runtime/texture.h"
#include "unorm8_avx512.h"  // cpu_has_avx512, cpu_has_avx2

namespace sm2::runtime {
namespace {

// Whether this CPU runs a block path at all (sampler.cpp's instances: AVX-512 or AVX2).
bool cpu_runs_block_path() { return cpu_has_avx512() || cpu_has_avx2(); }

// The instances to check: the CPU's own, and on an AVX-512 CPU the AVX2 one forced as well.
std::vector<bool> forced_avx2_choices() {
    if (cpu_has_avx512()) return {false, true};
    return {false};
}

// d = 0: a 2D texture; d > 0: a volume of depth d; cube: a cube map of side w.
Texture random_texture(std::mt19937& rng, Format format, uint32_t w, uint32_t h, uint32_t levels, uint32_t d = 0,
                       bool cube = false) {
    Texture t = cube     ? Texture::create_cube(format, w, levels)
                : d == 0 ? Texture::create_2d(format, w, h, levels)
                         : Texture::create_volume(format, w, h, d, levels);
    for (uint32_t f = 0; f < t.faces(); ++f)
        for (uint32_t l = 0; l < t.levels(); ++l) {
            auto& bytes = t.surface(l, f).bytes();
            for (auto& b : bytes) b = static_cast<std::byte>(rng() & 0xFFu);
        }
    return t;
}

float special_or(std::mt19937& rng, float ordinary) {
    switch (rng() % 24) {
    case 0: return std::numeric_limits<float>::quiet_NaN();
    case 1: return std::numeric_limits<float>::infinity();
    case 2: return -std::numeric_limits<float>::infinity();
    case 3: return 1e30f;
    case 4: return -1e12f;
    case 5: return -0.0f;
    case 6: return 0x1p-140f;  // denormal
    default: return ordinary;
    }
}

SamplerState random_state(std::mt19937& rng) {
    static constexpr TextureAddress kModes[] = {TextureAddress::Wrap,   TextureAddress::Clamp,  TextureAddress::Wrap,
                                                TextureAddress::Clamp,  TextureAddress::Mirror, TextureAddress::Border,
                                                TextureAddress::MirrorOnce};
    static constexpr TextureFilter kFilters[] = {TextureFilter::Point, TextureFilter::Linear, TextureFilter::Linear,
                                                 TextureFilter::None, TextureFilter::Anisotropic};
    SamplerState s;
    s.address_u = kModes[rng() % std::size(kModes)];
    s.address_v = kModes[rng() % std::size(kModes)];
    s.address_w = kModes[rng() % std::size(kModes)];
    s.mag_filter = kFilters[rng() % 4];
    s.min_filter = kFilters[rng() % 5];
    s.mip_filter = kFilters[rng() % 4];
    s.max_mip_level = rng() % 4 == 0 ? rng() % 5 : 0;
    s.mip_lod_bias = rng() % 3 == 0 ? static_cast<float>(static_cast<int>(rng() % 400) - 200) / 64.0f : 0.0f;
    s.max_anisotropy = rng() % 2 ? 1 + rng() % 4 : 1 + rng() % 16;
    s.border_color = static_cast<uint32_t>(rng());
    s.srgb_texture = rng() % 4 == 0;  // honoured by the 8-bit RGB formats only
    return s;
}

// A format and size for random_texture() (d = 0: a 2D texture).
struct TextureCase {
    Format format;
    uint32_t w, h, d;
};

// `block` and `lanes` on `texture` at stage 0: the first with the block path the CPU allows, the
// second with the per-lane path (the reference).
void bind_block_and_lanes(TextureSampler& block, TextureSampler& lanes, const Texture& texture) {
    block.set_texture(0, &texture);
    lanes.set_texture(0, &texture);
    lanes.set_block_path(false);
}

// A random state and filter precision on stage 0 of both samplers; returns the state.
SamplerState set_random_state(std::mt19937& rng, TextureSampler& block, TextureSampler& lanes) {
    const SamplerState state = random_state(rng);
    const FilterPrecision precision = rng() % 4 == 0 ? FilterPrecision::Exact : FilterPrecision::Fixed8;
    for (TextureSampler* s : {&block, &lanes}) {
        s->set_state(0, state);
        s->set_precision(precision);
    }
    return state;
}

// Samples `request` through both samplers: success where every channel of every lane has the
// same bits (where `nans_alike`, any two NaNs count as the same: which NaN a sum of two gives
// depends on the operand order a compiler picks), else the first lane that differs.
::testing::AssertionResult same_texels(TextureSampler& block, TextureSampler& lanes, const emu::TextureRequest& request,
                                       bool nans_alike) {
    std::array<emu::FloatLanes, 4> a, b;
    block.sample(request, a);
    lanes.sample(request, b);
    for (unsigned c = 0; c < 4; ++c)
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            if (nans_alike && std::isnan(a[c][l]) && std::isnan(b[c][l])) continue;
            if (std::bit_cast<uint32_t>(a[c][l]) != std::bit_cast<uint32_t>(b[c][l]))
                return ::testing::AssertionFailure() << "channel " << c << " lane " << l << ": " << a[c][l] << " (0x"
                                                     << std::hex << std::bit_cast<uint32_t>(a[c][l]) << ") vs "
                                                     << b[c][l] << " (0x" << std::bit_cast<uint32_t>(b[c][l]) << ")"
                                                     << std::dec;
        }
    return ::testing::AssertionSuccess();
}

// Quads around a random point with random per-quad derivatives (minification, magnification
// and everything between), some lanes replaced by special values.
emu::TextureRequest random_request(std::mt19937& rng, std::array<emu::FloatLanes, 4>& coords) {
    std::uniform_real_distribution<float> centre(-3.0f, 3.0f), scale(-10.0f, 2.0f), unit(-1.0f, 1.0f);
    // Half the requests give every quad the same derivatives (a screen-aligned pass: the
    // sampler reuses the previous quad's level choice); the others differ per quad.
    const bool shared = rng() % 2 == 0;
    float du = 0, dv = 0, eu = 0, ev = 0;
    for (unsigned q = 0; q < emu::kBatchQuads; ++q) {
        const float u = shared ? 0.3f : centre(rng), v = shared ? 0.7f : centre(rng);  // shared: equal lengths
        if (!shared || q == 0) {
            du = std::exp2(scale(rng)) * unit(rng);
            dv = std::exp2(scale(rng)) * unit(rng);
            eu = std::exp2(scale(rng)) * unit(rng);
            ev = std::exp2(scale(rng)) * unit(rng);
        }
        for (unsigned i = 0; i < 4; ++i) {
            const unsigned l = 4 * q + i;
            const float x = static_cast<float>(i & 1u), y = static_cast<float>(i >> 1);
            const float su = u + x * du + y * eu, sv = v + x * dv + y * ev;
            coords[0][l] = shared ? su : special_or(rng, su);
            coords[1][l] = shared ? sv : special_or(rng, sv);
            // (volumes: a third coordinate varying like the first in shared requests)
            coords[2][l] = shared ? 0.45f + x * du + y * eu : special_or(rng, unit(rng));
            coords[3][l] = shared ? 1.0f : rng() % 2 ? special_or(rng, unit(rng) * 4.0f) : 1.0f;
        }
    }
    emu::TextureRequest r;
    r.sampler = 0;
    r.variant = static_cast<emu::TextureVariant>(rng() % 3);
    r.coordinates = &coords;
    r.quad_count = 1 + rng() % emu::kBatchQuads;
    return r;
}

// `states` random sampler states set on both samplers (every other one prepared, the draw's way:
// tables built once), each with 20 random requests compared by same_texels() (any two NaNs
// alike: random R32F texels include NaNs, and the engine stores every NaN as one pattern);
// `count(state, applies)` is called for each request. The first difference fails it.
template <typename Count>
::testing::AssertionResult same_random_lookups(std::mt19937& rng, TextureSampler& block, TextureSampler& lanes,
                                               unsigned states, Count count) {
    for (unsigned s = 0; s < states; ++s) {
        const SamplerState state = set_random_state(rng, block, lanes);
        if (s % 2) block.prepare();
        if (lanes.block_path_applies(0)) return ::testing::AssertionFailure() << "the per-lane sampler took the block path";
        const bool applies = block.block_path_applies(0);
        for (unsigned k = 0; k < 20; ++k) {
            std::array<emu::FloatLanes, 4> coords;
            const emu::TextureRequest request = random_request(rng, coords);
            count(state, applies);
            if (auto same = same_texels(block, lanes, request, true); !same)
                return same << " (state " << s << ", request " << k << ", block path " << applies << ")";
        }
    }
    return ::testing::AssertionSuccess();
}

TEST(SamplerBlockPath, SameBitsAsThePerLanePath) {
    std::mt19937 rng(20261124);
    // 8-, 4-, 2- and 1-byte texels; a quarter of the textures are volumes, a quarter cube maps.
    const Format formats[] = {Format::A8R8G8B8,  Format::X8R8G8B8, Format::A8B8G8R8,  Format::R5G6B5,
                              Format::X8B8G8R8,  Format::A2B10G10R10, Format::A2R10G10B10, Format::G16R16,
                              Format::R32F,      Format::A4R4G4B4, Format::A1R5G5B5,  Format::L8,
                              Format::A8L8,      Format::A8,       Format::L16,       Format::R3G3B2,
                              Format::A8R3G3B2,  Format::A16B16G16R16, Format::G32R32F, Format::R16F,
                              Format::G16R16F,   Format::A16B16G16R16F, Format::V8U8, Format::L6V5U5,
                              Format::X8L8V8U8,  Format::Q8W8V8U8, Format::V16U16, Format::A2W10V10U10,
                              Format::Q16W16V16U16};
    unsigned block_requests = 0, total = 0, volume_block_requests = 0, narrow_block_requests = 0, wide_block_requests = 0;
    unsigned cube_block_requests = 0, anisotropic_block_requests = 0, half_block_requests = 0, signed_block_requests = 0;
    unsigned srgb_block_requests = 0, periodic_block_requests = 0;
    for (unsigned round = 0; round < 450; ++round) {
        const Format format = formats[rng() % std::size(formats)];
        const bool pow2 = rng() % 4 != 0;
        const unsigned kind = rng() % 4;
        const bool volume = kind == 0, cube = kind == 1;
        const uint32_t side = volume ? 6 : 8, odd = volume ? 20 : 70;
        const uint32_t w = pow2 ? 1u << (rng() % side) : 1 + rng() % odd, h = pow2 ? 1u << (rng() % side) : 1 + rng() % odd;
        const uint32_t d = !volume ? 0 : pow2 ? 1u << (rng() % 5) : 1 + rng() % 9;
        const Texture texture = random_texture(rng, format, w, h, pow2 ? 0 : 1, d, cube);
        const bool narrow = format_info(format)->bytes < 4, wide = format_info(format)->bytes == 8;
        // The block path with 32-bit offsets or with 64-bit addresses (which one a texture gets
        // depends on where its levels were allocated), against the per-lane path.
        TextureSampler block, lanes;
        block.set_texture(0, &texture);
        block.set_block_64bit_addresses(round % 2 == 1);
        block.set_block_avx2(round % 3 == 2);  // on an AVX-512 CPU, a third of the rounds run the AVX2 instance
        lanes.set_texture(0, &texture);
        lanes.set_block_path(false);
        const auto count = [&](const SamplerState& state, bool applies) {
            ++total;
            block_requests += applies ? 1 : 0;
            volume_block_requests += applies && volume ? 1 : 0;
            narrow_block_requests += applies && narrow ? 1 : 0;
            wide_block_requests += applies && wide ? 1 : 0;
            cube_block_requests += applies && cube ? 1 : 0;
            half_block_requests += applies && (format == Format::R16F || format == Format::G16R16F ||
                                               format == Format::A16B16G16R16F) ? 1 : 0;
            const bool is_signed = format == Format::V8U8 || format == Format::L6V5U5 || format == Format::X8L8V8U8 ||
                                   format == Format::Q8W8V8U8 || format == Format::V16U16 ||
                                   format == Format::A2W10V10U10 || format == Format::Q16W16V16U16;
            signed_block_requests += applies && is_signed ? 1 : 0;
            srgb_block_requests += applies && state.srgb_texture && format_info(format)->srgb ? 1 : 0;
            // WRAP or MIRROR on a size that is not a power of two: the remainder's addressing.
            const auto periodic = [](TextureAddress m) { return m == TextureAddress::Wrap || m == TextureAddress::Mirror; };
            periodic_block_requests += applies && !cube && !(std::has_single_bit(w) && std::has_single_bit(h)) &&
                                               (periodic(state.address_u) || periodic(state.address_v))
                                           ? 1
                                           : 0;
            anisotropic_block_requests +=
                applies && state.min_filter == TextureFilter::Anisotropic && state.max_anisotropy > 1 ? 1 : 0;
        };
        ASSERT_TRUE(same_random_lookups(rng, block, lanes, 8, count))
            << "round " << round << " (" << w << "x" << h << ")";
    }
    // Without a block path the comparison is trivially equal; with one, a good share must have
    // taken it for the test to mean anything.
    if (cpu_runs_block_path()) {
        EXPECT_GT(block_requests, total / 5);
        EXPECT_GT(volume_block_requests, total / 20);
        EXPECT_GT(narrow_block_requests, total / 10);
        EXPECT_GT(wide_block_requests, total / 40);
        EXPECT_GT(cube_block_requests, total / 20);
        EXPECT_GT(anisotropic_block_requests, total / 20);
        EXPECT_GT(half_block_requests, total / 40);
        EXPECT_GT(signed_block_requests, total / 40);
        EXPECT_GT(srgb_block_requests, total / 100);
        EXPECT_GT(periodic_block_requests, total / 40);
    }
}

// LINEAR lookups at texel centres, whose fixed8 weights are all 0 (a screen-space pass over a
// texture of the target's size, a blur's centre tap): where every decoded value is finite and
// none is -0 (UNORM and SNORM fields) the block path reads tap t00 alone, which must be the
// per-lane path's 2x2 sum; float and half formats, whose taps beside t00 may be infinities or
// NaNs (times 0: NaN) and whose t00 may be -0 (plus +0: +0), must still sum all four. A third of
// the requests have every lane centred, a third only u centred, a third only v; BORDER lanes
// from the centres just outside the level.
TEST(SamplerBlockPath, TexelCentreLookupsMatchThePerLanePath) {
    std::mt19937 rng(20261203);
    const Format formats[] = {Format::A16B16G16R16, Format::A8R8G8B8, Format::R5G6B5,  Format::L8,
                              Format::A4R4G4B4,     Format::V8U8,     Format::V16U16,  Format::Q16W16V16U16,
                              Format::A2B10G10R10,  Format::R32F,     Format::G32R32F, Format::A16B16G16R16F,
                              Format::R16F,         Format::G16R16F};
    unsigned block_requests = 0, total = 0;
    for (unsigned round = 0; round < 120; ++round) {
        const Format format = formats[round % std::size(formats)];
        const uint32_t w = 1u << (1 + rng() % 5), h = 1u << (rng() % 5);
        const Texture texture = random_texture(rng, format, w, h, 1);
        TextureSampler block, lanes;
        bind_block_and_lanes(block, lanes, texture);
        block.set_block_avx2(round % 3 == 2);
        SamplerState state = random_state(rng);
        state.mag_filter = state.min_filter = TextureFilter::Linear;
        state.mip_filter = TextureFilter::None;
        const FilterPrecision precision = rng() % 4 == 0 ? FilterPrecision::Exact : FilterPrecision::Fixed8;
        for (TextureSampler* s : {&block, &lanes}) {
            s->set_state(0, state);
            s->set_precision(precision);
        }
        for (unsigned k = 0; k < 30; ++k) {
            std::array<emu::FloatLanes, 4> coords{};
            const unsigned centred = k % 3;  // 0: u and v, 1: u only, 2: v only
            const int x0 = static_cast<int>(rng() % (w + 4)) - 2, y0 = static_cast<int>(rng() % (h + 4)) - 2;
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                // The batch's 2x2 quads side by side, a texel a pixel (derivatives of one texel).
                const int x = x0 + static_cast<int>(2 * (l / 4) + (l & 1u)), y = y0 + static_cast<int>(l >> 1 & 1u);
                const float off = 0.25f + 0.5f * static_cast<float>(rng() % 2);
                coords[0][l] = (static_cast<float>(x) + (centred == 2 ? off : 0.5f)) / static_cast<float>(w);
                coords[1][l] = (static_cast<float>(y) + (centred == 1 ? off : 0.5f)) / static_cast<float>(h);
            }
            emu::TextureRequest r;
            r.coordinates = &coords;
            ++total;
            block_requests += block.block_path_applies(0) ? 1 : 0;
            ASSERT_TRUE(same_texels(block, lanes, r, true))
                << format_info(format)->name << " " << w << "x" << h << ", request " << k << " (round " << round << ")";
        }
    }
    if (cpu_runs_block_path()) {
        EXPECT_GT(block_requests, total / 2);
    }
}

// DXTn textures: the block path reads their texels decoded to A8R8G8B8 (Texture::decoded_dxt())
// and must give the per-lane path's bits, which decodes each tap from its block and sums the taps
// in float: 2D, cube and volume textures of random blocks (every bit pattern is a valid block:
// DXT1's three-colour blocks and DXT5's six-alpha ones included), random states (sRGB reads too).
TEST(SamplerBlockPath, DxtTexturesMatchThePerLanePath) {
    std::mt19937 rng(20261203);
    const Format formats[] = {Format::DXT1, Format::DXT2, Format::DXT3, Format::DXT4, Format::DXT5};
    unsigned block_requests = 0, total = 0;
    for (unsigned round = 0; round < 60; ++round) {
        const Format format = formats[round % std::size(formats)];
        const unsigned kind = rng() % 4;
        const bool volume = kind == 0, cube = kind == 1, pow2 = rng() % 4 != 0;
        // DXTn sizes are multiples of 4; the levels below 4 texels keep a whole block.
        const uint32_t w = pow2 ? 4u << (rng() % 5) : 4 * (1 + rng() % 9), h = cube ? w : pow2 ? 4u << (rng() % 5) : 4 * (1 + rng() % 9);
        const uint32_t d = volume ? (pow2 ? 1u << (rng() % 4) : 1 + rng() % 5) : 0;
        const Texture texture = random_texture(rng, format, w, h, pow2 ? 0 : 1, d, cube);
        TextureSampler block, lanes;
        bind_block_and_lanes(block, lanes, texture);
        block.set_block_avx2(round % 3 == 2);
        const auto count = [&](const SamplerState&, bool applies) {
            ++total;
            block_requests += applies ? 1 : 0;
        };
        ASSERT_TRUE(same_random_lookups(rng, block, lanes, 6, count)) << "round " << round << " (" << w << "x" << h << ")";
    }
    if (cpu_runs_block_path()) {
        EXPECT_GT(block_requests, total / 2);
    }
}

// A write access to a DXTn texture drops its decoded copy: the next draw's block path reads the
// new blocks. Level 0 of a 4x4 DXT1 texture, sampled POINT at its texel (1, 2), first all red
// blocks (c0 = c1 = 0xF800, indices 0), then all blue (0x001F): (1, 0, 0, 1), then (0, 0, 1, 1).
TEST(SamplerBlockPath, DxtWritesReachTheDecodedTexels) {
    Texture texture = Texture::create_2d(Format::DXT1, 4, 4, 1);
    const auto fill = [&](uint16_t colour) {
        auto& bytes = texture.surface(0).bytes();
        std::fill(bytes.begin(), bytes.end(), std::byte{0});
        for (unsigned c = 0; c < 2; ++c) {
            bytes[2 * c] = static_cast<std::byte>(colour & 0xFFu);
            bytes[2 * c + 1] = static_cast<std::byte>(colour >> 8);
        }
    };
    TextureSampler sampler;
    sampler.set_texture(0, &texture);
    std::array<emu::FloatLanes, 4> coords{}, out{};
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        coords[0][l] = 1.5f / 4.0f;
        coords[1][l] = 2.5f / 4.0f;
        coords[3][l] = 1.0f;
    }
    emu::TextureRequest request;
    request.sampler = 0;
    request.coordinates = &coords;
    request.quad_count = emu::kBatchQuads;
    const std::array<std::array<float, 4>, 2> expected = {{{1, 0, 0, 1}, {0, 0, 1, 1}}};
    const uint16_t colours[2] = {0xF800, 0x001F};
    for (unsigned step = 0; step < 2; ++step) {
        fill(colours[step]);
        sampler.prepare();  // as each draw does
        EXPECT_EQ(sampler.block_path_applies(0), cpu_runs_block_path());
        sampler.sample(request, out);
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) ASSERT_EQ(out[c][l], expected[step][c]) << step << " " << c << " " << l;
    }
}

// The decoded copies have a budget: a DXTn texture whose copy would pass it is read by the
// per-lane path (the same bits), and a copy let go gives its bytes back. A 64x64 DXT5 texture
// with its chain decodes to 4 (64^2 + 32^2 + ... + 1) = 21 844 bytes.
TEST(SamplerBlockPath, DxtCopiesBeyondTheirBudgetLeaveTheLookupsToThePerLanePath) {
    std::mt19937 rng(3);
    Texture texture = random_texture(rng, Format::DXT5, 64, 64, 0);
    const Texture second = random_texture(rng, Format::DXT5, 64, 64, 0);
    const uint64_t previous = Texture::set_decoded_dxt_budget(21843);
    EXPECT_EQ(std::as_const(texture).decoded_dxt(), nullptr);
    TextureSampler block, lanes;
    bind_block_and_lanes(block, lanes, texture);
    SamplerState state;
    state.mag_filter = state.min_filter = state.mip_filter = TextureFilter::Linear;
    block.set_state(0, state);
    lanes.set_state(0, state);
    block.prepare();
    EXPECT_FALSE(block.block_path_applies(0));
    std::array<emu::FloatLanes, 4> coords;
    EXPECT_TRUE(same_texels(block, lanes, random_request(rng, coords), true));
    Texture::set_decoded_dxt_budget(21844);
    std::shared_ptr<const Texture> copy = std::as_const(texture).decoded_dxt();
    ASSERT_NE(copy, nullptr);
    EXPECT_EQ(copy->format(), Format::A8R8G8B8);
    EXPECT_EQ(second.decoded_dxt(), nullptr);  // the first copy holds the whole budget
    (void)texture.surface(0);                  // a write access drops the texture's reference,
    EXPECT_EQ(second.decoded_dxt(), nullptr);  // while `copy` keeps it alive
    copy.reset();                              // the last owner lets it go: its bytes are free
    EXPECT_NE(second.decoded_dxt(), nullptr);
    Texture::set_decoded_dxt_budget(previous);
}

// Fixed8 LINEAR on UNORM fields of at most 8 bits is the exact bilinear sum of the taps' integer
// values with weights in 1/256 units, rounded once (docs/texturing.md): each result must be the
// float nearest the exact value, which the test works out in double from the texel bytes (the
// exact value has at most 24 + 24 significant bits, so the double quotient is within 2^-53 of
// it, far closer than the half ulp of float the check needs). Both paths, 8-, 5/6- and 4-bit
// fields, random coordinates, CLAMP.
// Fixed-mode levels of detail near every step of 1/256 in log2(rho), where the block path's short
// series (block_fixed_lod()) must either settle floor(256 log2 rho) as lod_log2()'s series does
// or hand the quad to that series: each quad's x derivative is the float nearest 2^(k / 256)
// texels a pixel or one of its neighbours a few ulps away (t = 256 log2 rho steps 4.4e-5 an ulp,
// and the short series' error reaches 5.5e-6), its y derivative half that, so the x length is
// rho exactly. Trilinear on a texture of random levels: a fraction off by 1/256 changes the texels.
TEST(SamplerBlockPath, TrilinearLevelsAtEveryLodStepMatchThePerLanePath) {
    std::mt19937 rng(20261130);
    const Texture texture = random_texture(rng, Format::A8R8G8B8, 256, 256, 0);
    TextureSampler block, lanes;
    bind_block_and_lanes(block, lanes, texture);
    SamplerState state;
    state.mag_filter = state.min_filter = state.mip_filter = TextureFilter::Linear;
    for (TextureSampler* s : {&block, &lanes}) s->set_state(0, state);
    block.prepare();
    if (!block.block_path_applies(0)) GTEST_SKIP() << "no block path on this CPU";
    unsigned compared = 0;
    // Steps from rho = 1/4 to 2^9 (past the last level): k / 256 in log2, every third step, each
    // quad of a batch a different ulp offset.
    for (int k = -512; k <= 9 * 256; k += 3)
        for (int first_offset = -6; first_offset <= 6; first_offset += 4) {
            std::array<emu::FloatLanes, 4> coords{};
            for (unsigned q = 0; q < emu::kBatchQuads; ++q) {
                float du = static_cast<float>(std::exp2(k / 256.0) / 256.0);
                for (int i = 0; i < first_offset + static_cast<int>(q); ++i) du = std::nextafter(du, 1.0f);
                for (int i = 0; i > first_offset + static_cast<int>(q); --i) du = std::nextafter(du, 0.0f);
                for (unsigned i = 0; i < 4; ++i) {
                    // (u, v) = (0, 0) at the top-left lane: the differences are du and du / 2 exactly.
                    coords[0][4 * q + i] = (i & 1u) ? du : 0.0f;
                    coords[1][4 * q + i] = (i >> 1) ? du * 0.5f : 0.0f;
                }
            }
            emu::TextureRequest r;
            r.coordinates = &coords;
            // (Quad q's offset: first_offset + q ulps.)
            ASSERT_TRUE(same_texels(block, lanes, r, false)) << "step " << k << ", first offset " << first_offset << " ulps";
            ++compared;
        }
    // Diagonal derivatives (d, d) of powers of two: squares 2 d^2 that are odd powers of two, whose
    // roots (rho = sqrt(2) d, log2 rho within rounding of an odd multiple of 1/2) only the series settles.
    for (int n = 1; n <= 14; ++n) {
        std::array<emu::FloatLanes, 4> coords{};
        const float d = std::ldexp(1.0f, -n);
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            coords[0][l] = (l & 1u) ? d : 0.0f;
            coords[1][l] = (l & 1u) ? d : (l & 2u) ? d * 0.25f : 0.0f;
        }
        emu::TextureRequest r;
        r.coordinates = &coords;
        ASSERT_TRUE(same_texels(block, lanes, r, false)) << "2^-" << n;
        ++compared;
    }
    EXPECT_EQ(compared, 939u * 4u + 14u);
}

// Cube lookups of finite directions, the common case that the random requests above seldom draw
// (one of their coordinates in 12 is a NaN or an infinity, and a batch has 48): quads round
// directions on every face, across the edges and corners between faces, on the ties between axes
// (|x| = |y|, |y| = |z|), with -0 components and the zero vector, and batches whose only special
// values are infinite components, and coherent batches (every lane on one face and level, whose
// tables' entries the filter broadcasts); magnified and minified, LINEAR and POINT, exact and
// fixed-point filtering, 32-bit offsets and 64-bit addresses, with and without texldp's divide.
TEST(SamplerBlockPath, CubeLookupsOnEveryFaceMatchThePerLanePath) {
    std::mt19937 rng(20261130);
    const Texture texture = random_texture(rng, Format::A8R8G8B8, 32, 32, 0, 0, true);
    TextureSampler block, lanes;
    block.set_texture(0, &texture);
    lanes.set_texture(0, &texture);
    lanes.set_block_path(false);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), scale(-9.0f, 1.0f), length(-3.0f, 3.0f);
    unsigned compared = 0;
    for (unsigned round = 0; round < 400; ++round) {
        SamplerState state;
        state.mag_filter = round % 4 == 3 ? TextureFilter::Point : TextureFilter::Linear;
        state.min_filter = round % 8 == 5 ? TextureFilter::Point : TextureFilter::Linear;
        state.mip_filter = round % 3 == 0 ? TextureFilter::Point : TextureFilter::Linear;
        const FilterPrecision precision = round % 2 ? FilterPrecision::Exact : FilterPrecision::Fixed8;
        for (TextureSampler* s : {&block, &lanes}) {
            s->set_state(0, state);
            s->set_precision(precision);
        }
        block.set_block_64bit_addresses(round % 4 >= 2);
        block.prepare();
        if (!block.block_path_applies(0)) GTEST_SKIP() << "no block path on this CPU";
        std::array<emu::FloatLanes, 4> coords{};
        // A third of the batches coherent, as a surface's: every quad near the first one's direction.
        const bool coherent = round % 3 == 1;
        const float shared[3] = {gauss(rng), gauss(rng), gauss(rng)};
        for (unsigned q = 0; q < emu::kBatchQuads; ++q) {
            float p[3] = {gauss(rng), gauss(rng), gauss(rng)};
            if (coherent)
                for (unsigned c = 0; c < 3; ++c) p[c] = shared[c] + 0.01f * p[c];
            switch (coherent ? 6 : rng() % 6) {
            case 0: p[1] = std::copysign(p[0], unit(rng)); break;  // an x-y edge: |x| = |y|
            case 1: p[2] = std::copysign(p[1], unit(rng)); break;  // a y-z edge
            case 2: p[0] = p[1] = std::copysign(p[2], unit(rng)); break;  // a corner
            case 3: p[rng() % 3] = rng() % 2 ? -0.0f : 0.0f; break;
            case 4: if (q == 0 && round % 16 == 0) p[0] = p[1] = p[2] = 0.0f; break;  // no direction at all
            case 5:
                if (round % 4 == 1) {  // infinite components, one or two (and no NaN in the batch)
                    const unsigned first = rng() % 3;
                    p[first] = std::copysign(std::numeric_limits<float>::infinity(), unit(rng));
                    if (rng() % 2) p[(first + 1 + rng() % 2) % 3] = std::copysign(std::numeric_limits<float>::infinity(), unit(rng));
                }
                break;
            default: break;
            }
            const float size = coherent ? 1.0f : std::exp2(length(rng));
            // (Coherent batches: small derivatives, so that every lane reads the first level.)
            float d[2][3];
            for (auto& axis : d)
                for (float& c : axis) c = std::exp2(coherent ? -14.0f : scale(rng)) * unit(rng);
            for (unsigned i = 0; i < 4; ++i) {
                const float x = static_cast<float>(i & 1u), y = static_cast<float>(i >> 1);
                for (unsigned c = 0; c < 3; ++c) coords[c][4 * q + i] = size * p[c] + x * d[0][c] + y * d[1][c];
                coords[3][4 * q + i] = round % 5 == 4 ? 0.5f + static_cast<float>(rng() % 4) : 1.0f;
            }
        }
        emu::TextureRequest r;
        r.coordinates = &coords;
        r.variant = round % 5 == 4 ? emu::TextureVariant::Projected : emu::TextureVariant::Plain;
        ASSERT_TRUE(same_texels(block, lanes, r, false)) << "round " << round;
        ++compared;
    }
    EXPECT_EQ(compared, 400u);
}

// BORDER with a transparent BORDERCOLOR (0x00000000, the default), where the filter gives a
// tap outside the level a weight of 0 instead of BORDERCOLOR's 0 as its value
// (BlockLevels::zero_border): volumes and 2D levels, footprints across every edge and wholly
// outside, POINT lanes beside LINEAR ones (MAGFILTER POINT, MINFILTER LINEAR, derivatives
// either side of one texel a pixel), against the per-lane path. Besides the UNORM formats, the
// kinds the rule must not take: signed fields (a negative value times 0 is -0, where the
// border's product is +0), floats (NaN and infinity times 0 are NaN), and a border whose
// alpha alone is not 0.
TEST(SamplerBlockPath, TransparentBorderMatchesThePerLanePath) {
    std::mt19937 rng(20261201);
    const Format formats[] = {Format::A4R4G4B4, Format::A8R8G8B8, Format::L8,  Format::A8,   Format::R5G6B5,
                              Format::A1R5G5B5, Format::A16B16G16R16, Format::V8U8, Format::R32F, Format::R16F};
    std::uniform_real_distribution<float> centre(-0.4f, 1.4f), scale(-4.0f, 2.0f), unit(-1.0f, 1.0f);
    unsigned compared = 0;
    for (unsigned round = 0; round < 240; ++round) {
        const Format format = formats[round % std::size(formats)];
        const bool volume = round % 2 == 0;
        const uint32_t w = 1u + rng() % 9, h = 1u + rng() % 9, d = volume ? 1u + rng() % 5 : 0u;
        const Texture texture = random_texture(rng, format, w, h, 1, d);
        TextureSampler block, lanes;
        block.set_texture(0, &texture);
        block.set_block_64bit_addresses(round % 4 >= 2);
        lanes.set_texture(0, &texture);
        lanes.set_block_path(false);
        SamplerState state;
        state.address_u = state.address_v = state.address_w = TextureAddress::Border;
        if (round % 5 == 3) state.address_v = TextureAddress::Clamp;  // (one axis not BORDER)
        state.border_color = round % 6 == 5 ? 0x01000000u : 0u;
        state.mag_filter = round % 3 == 0 ? TextureFilter::Point : TextureFilter::Linear;
        state.min_filter = TextureFilter::Linear;
        state.mip_filter = TextureFilter::None;
        state.srgb_texture = round % 7 == 6;
        const FilterPrecision precision = round % 4 == 1 ? FilterPrecision::Exact : FilterPrecision::Fixed8;
        for (TextureSampler* s : {&block, &lanes}) {
            s->set_state(0, state);
            s->set_precision(precision);
        }
        block.prepare();
        if (!block.block_path_applies(0)) GTEST_SKIP() << "no block path on this CPU";
        for (unsigned k = 0; k < 12; ++k) {
            std::array<emu::FloatLanes, 4> coords{};
            for (unsigned q = 0; q < emu::kBatchQuads; ++q) {
                const float u = centre(rng), v = centre(rng), z = centre(rng);
                // Per quad: about one texel a pixel, so that under a POINT MAGFILTER some quads
                // magnify (POINT) and others minify (LINEAR).
                const float du = std::exp2(scale(rng)) * unit(rng) / static_cast<float>(w);
                const float dv = std::exp2(scale(rng)) * unit(rng) / static_cast<float>(h);
                for (unsigned i = 0; i < 4; ++i) {
                    const float x = static_cast<float>(i & 1u), y = static_cast<float>(i >> 1);
                    coords[0][4 * q + i] = u + x * du;
                    coords[1][4 * q + i] = v + y * dv;
                    coords[2][4 * q + i] = z + x * du;
                    coords[3][4 * q + i] = 1.0f;
                }
            }
            emu::TextureRequest r;
            r.coordinates = &coords;
            ASSERT_TRUE(same_texels(block, lanes, r, false)) << "round " << round << " " << w << "x" << h << "x" << d;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 240u * 12u);
}

// The alpha gate (TextureSampler::set_alpha_gate): a lookup may leave red, green and blue +0
// where its alpha is +-0 or NaN on every lane that shades (the request's quads, helper lanes
// aside); the block path does so for volume lookups of one level. Anything else it returns is
// the ungated lookup's, bit for bit.
namespace alpha_gate {

// A 4x4x4 A4R4G4B4 volume: slices z = 0, 1 transparent, z = 2, 3 opaque; every colour field
// non-zero, (x + 1, y + 1, z + 1) / 15.
Texture volume(uint32_t levels) {
    Texture t = Texture::create_volume(Format::A4R4G4B4, 4, 4, 4, levels);
    for (uint32_t l = 0; l < levels; ++l) {
        Surface& s = t.surface(l);
        for (uint32_t z = 0; z < s.depth(); ++z)
            for (uint32_t y = 0; y < s.height(); ++y)
                for (uint32_t x = 0; x < s.width(); ++x) {
                    // Level 0 as above; every smaller level opaque.
                    const float alpha = l == 0 && z < 2 ? 0.0f : 1.0f;
                    s.write(x, y, z, {(x + 1) / 15.0f, (y + 1) / 15.0f, (z + 1) / 15.0f, alpha});
                }
    }
    return t;
}

// 16 lanes at w (volume depth), u and v spread over the texture; lanes in `opaque` at w = 0.9.
std::array<emu::FloatLanes, 4> coordinates(float w, emu::LaneMask opaque, float step = 0.05f) {
    std::array<emu::FloatLanes, 4> c{};
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        const unsigned q = l / 4, i = l % 4;
        c[0][l] = 0.2f + 0.15f * static_cast<float>(q) + step * static_cast<float>(i & 1u);
        c[1][l] = 0.3f + 0.1f * static_cast<float>(q) + step * static_cast<float>(i >> 1);
        c[2][l] = opaque >> l & 1u ? 0.9f : w;
        c[3][l] = 1.0f;
    }
    return c;
}

struct Lookups {
    std::array<emu::FloatLanes, 4> gated, ungated;
};

Lookups sample_both(const Texture& t, const SamplerState& state, const emu::TextureRequest& request, bool avx2) {
    TextureSampler gated, ungated;
    for (TextureSampler* s : {&gated, &ungated}) {
        s->set_texture(0, &t);
        s->set_state(0, state);
        s->set_block_avx2(avx2);
        s->prepare();
    }
    gated.set_alpha_gate(0, true);
    Lookups r;
    gated.sample(request, r.gated);
    ungated.sample(request, r.ungated);
    return r;
}

bool same_bits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

}  // namespace alpha_gate

TEST(SamplerBlockPath, AlphaGateLeavesTheColourWhereEveryShadingLaneIsTransparent) {
    using namespace alpha_gate;
    if (!cpu_runs_block_path()) GTEST_SKIP() << "no block path on this CPU";
    const Texture one_level = volume(1);
    SamplerState state;
    state.mag_filter = state.min_filter = TextureFilter::Linear;
    state.address_u = state.address_v = state.address_w = TextureAddress::Clamp;
    for (const bool avx2 : forced_avx2_choices()) {
        SCOPED_TRACE(avx2 ? "AVX2 instance" : "the CPU's instance");
        // w = 0.2: texel-space z 0.8 - 0.5 = 0.3, slices 0 and 1, both transparent.
        const auto transparent = coordinates(0.2f, 0);
        emu::TextureRequest request;
        request.coordinates = &transparent;
        Lookups r = sample_both(one_level, state, request, avx2);
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            EXPECT_TRUE(same_bits(r.gated[3][l], 0.0f)) << l;
            EXPECT_TRUE(same_bits(r.ungated[3][l], 0.0f)) << l;
            // The ungated lookup has its colour (red >= 1/15: every field is non-zero), the gated +0.
            EXPECT_GE(r.ungated[0][l], 1.0f / 15.0f) << l;
            for (unsigned c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(r.gated[c][l], 0.0f)) << c << " " << l;
        }
        // One opaque lane (w = 0.9: slices 3 and 3 clamped, alpha 1): every value as ungated.
        const auto one_opaque = coordinates(0.2f, 1u << 5);
        request.coordinates = &one_opaque;
        r = sample_both(one_level, state, request, avx2);
        EXPECT_EQ(r.ungated[3][5], 1.0f);
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) EXPECT_TRUE(same_bits(r.gated[c][l], r.ungated[c][l])) << c << " " << l;
        // The same lane as a helper lane (killed: it shades nothing): the gate holds.
        request.helper_lanes = 1u << 5;
        r = sample_both(one_level, state, request, avx2);
        EXPECT_EQ(r.gated[3][5], 1.0f);
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            for (unsigned c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(r.gated[c][l], 0.0f)) << c << " " << l;
        // Opaque lanes beyond the request's quads count neither.
        const auto beyond = coordinates(0.2f, 0xFFF0u);
        request.coordinates = &beyond;
        request.helper_lanes = 0;
        request.quad_count = 1;
        r = sample_both(one_level, state, request, avx2);
        for (unsigned l = 0; l < 4; ++l)
            for (unsigned c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(r.gated[c][l], 0.0f)) << c << " " << l;
        request.quad_count = emu::kBatchQuads;

        // Trilinear between level 0 (transparent here) and level 1 (opaque): the second level's
        // alpha is blended in after the first level's lookup, so no gate. Quads 0.35 apart per
        // pixel: 1.4 texels of level 0, LOD log2(1.4) = 0.49, between the two.
        const Texture two_levels = volume(2);
        SamplerState mipmapped = state;
        mipmapped.mip_filter = TextureFilter::Linear;
        const auto blended = coordinates(0.2f, 0, 0.35f);
        request.coordinates = &blended;
        r = sample_both(two_levels, mipmapped, request, avx2);
        EXPECT_GT(r.ungated[3][0], 0.0f);  // the second level blended in
        for (unsigned c = 0; c < 4; ++c)
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) EXPECT_TRUE(same_bits(r.gated[c][l], r.ungated[c][l])) << c << " " << l;
    }
}

// Random volumes (most alphas zero), states, coordinates and helper lanes: every gated lookup is
// the ungated one, or the ungated one with red, green and blue +0 where its alpha is +-0 or NaN
// on every lane of the request's quads but the helper lanes.
TEST(SamplerBlockPath, AlphaGateChangesNothingButTheColourOfTransparentLookups) {
    using namespace alpha_gate;
    if (!cpu_runs_block_path()) GTEST_SKIP() << "no block path on this CPU";
    std::mt19937 rng(20261204);
    std::uniform_real_distribution<float> unit(-0.2f, 1.2f);
    unsigned gated_lookups = 0, lookups = 0;
    for (unsigned round = 0; round < 120; ++round) {
        const Format format = round % 2 ? Format::A8R8G8B8 : Format::A4R4G4B4;
        Texture texture = random_texture(rng, format, 1u + rng() % 6, 1u + rng() % 6, 1, 1u + rng() % 6);
        // Most texels transparent: the alpha field (the top 4 of 16 bits, the top 8 of 32) zeroed.
        const unsigned alpha_byte = format == Format::A8R8G8B8 ? 3 : 1, stride = format == Format::A8R8G8B8 ? 4 : 2;
        auto& bytes = texture.surface(0).bytes();
        for (size_t i = alpha_byte; i < bytes.size(); i += stride)
            if (rng() % 8 != 0) bytes[i] &= static_cast<std::byte>(format == Format::A8R8G8B8 ? 0x00u : 0x0Fu);
        const SamplerState state = random_state(rng);
        for (unsigned k = 0; k < 10; ++k) {
            std::array<emu::FloatLanes, 4> coords{};
            const float u = unit(rng), v = unit(rng), w = unit(rng);
            const float du = unit(rng) * 0.2f, dv = unit(rng) * 0.2f;
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                const float x = static_cast<float>(l & 1u) + static_cast<float>(l / 4), y = static_cast<float>((l >> 1) & 1u);
                coords[0][l] = u + x * du;
                coords[1][l] = v + y * dv;
                coords[2][l] = w + x * du;
                coords[3][l] = 1.0f;
            }
            emu::TextureRequest request;
            request.coordinates = &coords;
            request.quad_count = 1 + rng() % emu::kBatchQuads;
            request.helper_lanes = rng() % 3 == 0 ? static_cast<emu::LaneMask>(rng() & 0xFFFFu) : 0;
            const Lookups r = sample_both(texture, state, request, rng() % 2 == 0);
            bool differs = false, colour_zero = true, alpha_same = true;
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                for (unsigned c = 0; c < 4; ++c) differs |= !same_bits(r.gated[c][l], r.ungated[c][l]);
                for (unsigned c = 0; c < 3; ++c) colour_zero &= same_bits(r.gated[c][l], 0.0f);
                alpha_same &= same_bits(r.gated[3][l], r.ungated[3][l]);
            }
            ++lookups;
            if (!differs) continue;
            ++gated_lookups;
            ASSERT_TRUE(colour_zero && alpha_same) << "round " << round << " lookup " << k;
            for (unsigned l = 0; l < 4 * request.quad_count; ++l) {
                if (request.helper_lanes >> l & 1u) continue;
                const float alpha = r.ungated[3][l];
                ASSERT_TRUE(alpha == 0.0f || std::isnan(alpha)) << "round " << round << " lookup " << k << " lane " << l;
            }
        }
    }
    // Both kinds met (counted over this seed: the gate is not a test that cannot fail).
    EXPECT_GT(gated_lookups, 50u);
    EXPECT_LT(gated_lookups, lookups);
}

// 1- and 2-byte texels are read as the 32-bit word at their offset (block_narrow_words()), so
// the word of a level's last texel reaches up to 3 bytes past the level: into the slack of its
// storage (CacheLineAllocator::kReadSlack). Levels of whole cache lines (64 and 128 bytes, no
// rounding to hide a missing slack), read at their last texels by POINT and LINEAR (CLAMP:
// both taps of the edge lanes on the last texel), must give the per-lane path's values; under
// AddressSanitizer (scripts/test.sh's second pass) a word past the allocation fails the test.
TEST(SamplerBlockPath, NarrowTexelsAtTheStoragesEndMatchThePerLanePath) {
    std::mt19937 rng(20261202);
    const TextureCase cases[] = {{Format::L8, 64, 1, 0},       {Format::A8, 32, 2, 0}, {Format::A8L8, 32, 1, 0},
                                 {Format::A4R4G4B4, 32, 2, 0}, {Format::L8, 4, 4, 4},  {Format::R5G6B5, 4, 2, 4},
                                 {Format::A8L8, 2, 4, 4}};
    unsigned compared = 0;
    for (const TextureCase& t : cases) {
        const Texture texture = random_texture(rng, t.format, t.w, t.h, 1, t.d);
        const auto& level = texture.surface(0).bytes();
        ASSERT_EQ(level.size() % 64, 0u) << "the level must end on a line for the test to mean anything";
        for (const TextureFilter filter : {TextureFilter::Point, TextureFilter::Linear}) {
            TextureSampler block, lanes;
            bind_block_and_lanes(block, lanes, texture);
            SamplerState state;
            state.address_u = state.address_v = state.address_w = TextureAddress::Clamp;
            state.mag_filter = state.min_filter = filter;
            state.mip_filter = TextureFilter::None;
            for (TextureSampler* s : {&block, &lanes}) s->set_state(0, state);
            block.prepare();
            if (!block.block_path_applies(0)) GTEST_SKIP() << "no block path on this CPU";
            std::uniform_real_distribution<float> jitter(-0.6f, 0.6f);
            for (unsigned k = 0; k < 16; ++k) {
                // Every lane near the last texel (x w - 1, y h - 1, z d - 1) or past it (clamped).
                std::array<emu::FloatLanes, 4> coords{};
                for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                    const auto near_end = [&](uint32_t n) {
                        return n == 0 ? 0.5f : (static_cast<float>(n) - 0.5f + jitter(rng)) / static_cast<float>(n);
                    };
                    coords[0][l] = near_end(t.w);
                    coords[1][l] = near_end(t.h);
                    coords[2][l] = near_end(t.d);
                    coords[3][l] = 1.0f;
                }
                emu::TextureRequest r;
                r.coordinates = &coords;
                ASSERT_TRUE(same_texels(block, lanes, r, false))
                    << format_info(t.format)->name << " " << t.w << "x" << t.h << "x" << t.d;
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, std::size(cases) * 2u * 16u);
}

TEST(SamplerFilter, Fixed8BilinearOfNarrowUnormIsTheCorrectlyRoundedExactSum) {
    std::mt19937 rng(11);
    struct Field { Format format; unsigned channel, shift, bits; };
    const Field fields[] = {{Format::A8R8G8B8, 0, 16, 8}, {Format::A8R8G8B8, 3, 24, 8}, {Format::R5G6B5, 0, 11, 5},
                            {Format::R5G6B5, 1, 5, 6},     {Format::A4R4G4B4, 3, 12, 4}};
    for (const Field& f : fields) {
        const uint32_t w = 13, h = 7;
        const Texture texture = random_texture(rng, f.format, w, h, 1);
        const Surface& level = texture.surface(0);
        const unsigned bpp = f.format == Format::A8R8G8B8 ? 4 : 2;
        auto value = [&](int64_t x, int64_t y) {
            x = std::clamp<int64_t>(x, 0, w - 1);
            y = std::clamp<int64_t>(y, 0, h - 1);
            uint32_t word = 0;
            std::memcpy(&word, level.bytes().data() + static_cast<size_t>(y) * level.row_pitch() + static_cast<size_t>(x) * bpp, bpp);
            return static_cast<double>(word >> f.shift & ((1u << f.bits) - 1u));
        };
        for (const bool block : {true, false}) {
            TextureSampler s;
            s.set_texture(0, &texture);
            s.set_block_path(block);
            SamplerState st;
            st.address_u = st.address_v = TextureAddress::Clamp;
            st.mag_filter = st.min_filter = TextureFilter::Linear;
            st.mip_filter = TextureFilter::None;
            s.set_state(0, st);
            s.prepare();
            for (unsigned round = 0; round < 200; ++round) {
                std::array<emu::FloatLanes, 4> coords{};
                for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                    coords[0][l] = std::uniform_real_distribution<float>(-0.1f, 1.1f)(rng);
                    coords[1][l] = std::uniform_real_distribution<float>(-0.1f, 1.1f)(rng);
                }
                emu::TextureRequest r;
                r.coordinates = &coords;
                std::array<emu::FloatLanes, 4> texels;
                s.sample(r, texels);
                for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                    // Taps and 8-bit weights as docs/texturing.md states them.
                    const auto x = static_cast<int64_t>(std::floor((coords[0][l] * w - 0.5f) * 256.0f));
                    const auto y = static_cast<int64_t>(std::floor((coords[1][l] * h - 0.5f) * 256.0f));
                    const double ax = static_cast<double>(x & 255) / 256, ay = static_cast<double>(y & 255) / 256;
                    const int64_t x0 = x >> 8, y0 = y >> 8;
                    const double exact = ((value(x0, y0) * (1 - ax) + value(x0 + 1, y0) * ax) * (1 - ay) +
                                          (value(x0, y0 + 1) * (1 - ax) + value(x0 + 1, y0 + 1) * ax) * ay) /
                                         static_cast<double>((1u << f.bits) - 1u);
                    const float got = texels[f.channel][l];
                    const double error = std::abs(static_cast<double>(got) - exact);
                    ASSERT_LE(error, std::abs(static_cast<double>(std::nextafter(got, 2.0f)) - exact))
                        << "block " << block << " format " << static_cast<int>(f.format) << " lane " << l;
                    ASSERT_LE(error, std::abs(static_cast<double>(std::nextafter(got, -1.0f)) - exact))
                        << "block " << block << " format " << static_cast<int>(f.format) << " lane " << l;
                }
            }
        }
    }
}

// A hand-checked case through the block path: a 2x2 A8R8G8B8 texture, bilinear, CLAMP, at the
// centre (u, v) = (0.5, 0.5): texel space (1, 1) - 0.5 = (0.5, 0.5), taps 0 and 1 with weight
// 128/256 each, so every texel weighs 1/4. Red bytes 0, 255, 255, 255 -> 765/4/255 = 0.75.
TEST(SamplerBlockPath, BilinearCentreOfA2x2Texture) {
    Texture t = Texture::create_2d(Format::A8R8G8B8, 2, 2, 1);
    t.surface(0).write(0, 0, 0, {0.0f, 0.0f, 0.0f, 1.0f});
    t.surface(0).write(1, 0, 0, {1.0f, 0.0f, 0.0f, 1.0f});
    t.surface(0).write(0, 1, 0, {1.0f, 0.0f, 0.0f, 1.0f});
    t.surface(0).write(1, 1, 0, {1.0f, 1.0f, 0.0f, 0.0f});
    TextureSampler s;
    s.set_texture(0, &t);
    SamplerState st;
    st.address_u = st.address_v = TextureAddress::Clamp;
    st.mag_filter = st.min_filter = TextureFilter::Linear;
    s.set_state(0, st);
    std::array<emu::FloatLanes, 4> coords{};
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) coords[0][l] = coords[1][l] = 0.5f;
    emu::TextureRequest r;
    r.coordinates = &coords;
    std::array<emu::FloatLanes, 4> texels;
    s.sample(r, texels);
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        EXPECT_FLOAT_EQ(texels[0][l], 0.75f);   // red
        EXPECT_FLOAT_EQ(texels[1][l], 0.25f);   // green: one texel of 255
        EXPECT_FLOAT_EQ(texels[2][l], 0.0f);
        EXPECT_FLOAT_EQ(texels[3][l], 0.75f);   // alpha: three of 255
    }
}

// Calls check(block, lanes, label) for `texture` sampled at stage 0 with `filter` as MIN and MAG
// filter and `mip` as MIP filter (none unless given), under CLAMP and WRAP, with 32-bit offsets
// and with 64-bit addresses, in each instance the CPU runs: `block` on the block path, `lanes` on
// the per-lane path (the reference), `label` naming the set-up for a failure's message.
template <typename Check>
void for_each_level_setup(const Texture& texture, TextureFilter filter, Check&& check,
                          TextureFilter mip = TextureFilter::None) {
    for (const bool addresses64 : {false, true})
        for (const bool avx2 : forced_avx2_choices()) {
            TextureSampler block, lanes;
            block.set_texture(0, &texture);
            block.set_block_64bit_addresses(addresses64);
            block.set_block_avx2(avx2);
            lanes.set_texture(0, &texture);
            lanes.set_block_path(false);
            SamplerState state;
            state.mag_filter = state.min_filter = filter;
            state.mip_filter = mip;
            for (const TextureAddress mode : {TextureAddress::Clamp, TextureAddress::Wrap}) {
                state.address_u = state.address_v = mode;
                for (TextureSampler* s : {&block, &lanes}) s->set_state(0, state);
                block.prepare();
                if (cpu_runs_block_path()) {
                    ASSERT_TRUE(block.block_path_applies(0));
                }
                const std::string label = std::string(mode == TextureAddress::Wrap ? "WRAP" : "CLAMP") +
                                          (addresses64 ? " (64-bit addresses)" : "") + (avx2 ? " (AVX2 instance)" : "");
                check(block, lanes, label);
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
}

// A screen-space pass reads one texel a pixel: POINT lookups at the texel centres of batches of
// 4 quads side by side, whose 16 texels the block path reads as two runs of 8 from the rows of
// the level where they lie in it (and by a gather where they do not: at the right and bottom
// edges under CLAMP, at odd offsets, under WRAP past the edge). The same bits as the per-lane
// path, with 32-bit offsets and with 64-bit addresses.
TEST(SamplerBlockPath, PointLookupsOfScreenAlignedBatchesReadTheirTexelRows) {
    std::mt19937 rng(20261129);
    for (const Format format : {Format::A8R8G8B8, Format::R32F, Format::A2B10G10R10}) {
        const Texture texture = random_texture(rng, format, 64, 32, 1);  // powers of two: WRAP too
        for_each_level_setup(texture, TextureFilter::Point, [&](TextureSampler& block, TextureSampler& lanes, const std::string& label) {
            // Batches at every column and every other row, to the edges and past them.
            for (int y0 = -3; y0 < 34; y0 += 2)
                for (int x0 = -3; x0 < 66; ++x0) {
                    std::array<emu::FloatLanes, 4> coords{};
                    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                        const int x = x0 + static_cast<int>(2 * (l / 4) + (l & 1u)), y = y0 + static_cast<int>((l >> 1) & 1u);
                        coords[0][l] = (static_cast<float>(x) + 0.5f) / 64.0f;
                        coords[1][l] = (static_cast<float>(y) + 0.5f) / 32.0f;
                    }
                    emu::TextureRequest request;
                    request.coordinates = &coords;
                    ASSERT_TRUE(same_texels(block, lanes, request, true))
                        << format_info(format)->name << " at " << x0 << ", " << y0 << " " << label;
                }
        });
    }
}

// Bilinear lookups of 8x2-pixel batches at pixel steps of 0.5 to 2.5 texels, forwards and
// mirrored, screen-aligned and sheared (v growing along the batch's rows too), at every column
// and row of the level and past its edges: the AVX-512 instance reads the texels of such
// batches from a window of four rows (block_window_taps; steps of 1.8 and 2 put a lane's taps
// two rows below lane 0's), clipped at the level's right edge and last rows, and the others by
// loads; both must give the per-lane path's bits.
TEST(SamplerBlockPath, BilinearLookupsOfScreenAlignedBatchesReadTheirTexelWindow) {
    std::mt19937 rng(20261202);
    const Texture texture = random_texture(rng, Format::A8R8G8B8, 64, 32, 1);  // powers of two: WRAP too
    for_each_level_setup(texture, TextureFilter::Linear, [&](TextureSampler& block, TextureSampler& lanes, const std::string& label) {
        for (const float step : {0.5f, 1.0f, 1.25f, 1.8f, 2.0f, -1.0f, 2.5f})
            for (const float shear : {0.0f, 0.3f})
                for (int y0 = -3; y0 < 34; y0 += 3)
                    for (int x0 = -3; x0 < 66; ++x0) {
                        std::array<emu::FloatLanes, 4> coords{};
                        // A sub-texel offset per batch, so that the taps' weights vary.
                        const float fraction = static_cast<float>(rng() % 256) / 256.0f;
                        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                            const float px = static_cast<float>(2 * (l / 4) + (l & 1u)), py = static_cast<float>((l >> 1) & 1u);
                            coords[0][l] = (static_cast<float>(x0) + fraction + px * step) / 64.0f;
                            coords[1][l] = (static_cast<float>(y0) + fraction + py * std::abs(step) + px * shear) / 32.0f;
                        }
                        emu::TextureRequest request;
                        request.coordinates = &coords;
                        ASSERT_TRUE(same_texels(block, lanes, request, true))
                            << "step " << step << " shear " << shear << " at " << x0 << ", " << y0 << " " << label;
                    }
    });
}

// Trilinear lookups of screen-aligned batches between two levels on every lane, at 1.1 to 3.6
// texels a pixel of level 0 (LOD fractions of levels 0-1 and 1-2), from every position of the
// level and past its edges, with and without shear: the AVX-512 instance sums both levels of
// such batches at once (block_exact_levels<2>(), with 32-bit offsets), each level's taps from its
// window or lane by lane; the same bits as the per-lane path, and as two filter calls (64-bit
// addresses, the AVX2 instance).
TEST(SamplerBlockPath, TrilinearLookupsOfScreenAlignedBatchesMatchThePerLanePath) {
    std::mt19937 rng(20261206);
    const Texture texture = random_texture(rng, Format::A8R8G8B8, 64, 32, 0);  // every level
    for_each_level_setup(
        texture, TextureFilter::Linear,
        [&](TextureSampler& block, TextureSampler& lanes, const std::string& label) {
            for (const float step : {1.1f, 1.5f, 1.9f, 2.3f, 3.6f})
                for (const float shear : {0.0f, 0.4f})
                    for (int y0 = -5; y0 < 36; y0 += 4)
                        for (int x0 = -5; x0 < 68; x0 += 2) {
                            std::array<emu::FloatLanes, 4> coords{};
                            const float fraction = static_cast<float>(rng() % 256) / 256.0f;
                            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                                const float px = static_cast<float>(2 * (l / 4) + (l & 1u));
                                const float py = static_cast<float>((l >> 1) & 1u);
                                coords[0][l] = (static_cast<float>(x0) + fraction + px * step) / 64.0f;
                                coords[1][l] = (static_cast<float>(y0) + fraction + py * step + px * shear) / 32.0f;
                            }
                            emu::TextureRequest request;
                            request.coordinates = &coords;
                            ASSERT_TRUE(same_texels(block, lanes, request, true))
                                << "step " << step << " shear " << shear << " at " << x0 << ", " << y0 << " " << label;
                        }
        },
        TextureFilter::Linear);
}

// Trilinear volume lookups of 8x2-pixel batches stepping through the volume along a tilted
// direction, as slices drawn across a volume read it, at 0.15 to 1.3 texels a pixel, from
// every position of the level and past its faces: the AVX-512 instance reads the 2-byte texels
// of such batches from a 4x4x4 window (block_volume_window), moved inside the level, where every
// tap inside the level lies in it, and the others (larger steps, levels under 4 texels deep,
// taps clamped or wrapped away from the rest, 1-byte texels) by gathers; both must give the
// per-lane path's bits, under BORDER (transparent and not), CLAMP and WRAP.
TEST(SamplerBlockPath, TrilinearVolumeLookupsOfSliceBatchesReadTheirTexelWindow) {
    std::mt19937 rng(20261205);
    const TextureCase cases[] = {{Format::A4R4G4B4, 8, 8, 8}, {Format::R5G6B5, 7, 5, 6}, {Format::A1R5G5B5, 8, 4, 3},
                                 {Format::L8, 8, 6, 5}, {Format::A8, 5, 4, 4}};
    std::uniform_real_distribution<float> fraction(0.0f, 1.0f);
    unsigned compared = 0;
    for (const TextureCase& c : cases) {
        const Texture texture = random_texture(rng, c.format, c.w, c.h, 1, c.d);
        for (const bool avx2 : forced_avx2_choices())
            for (const TextureAddress mode : {TextureAddress::Border, TextureAddress::Clamp, TextureAddress::Wrap})
                for (const uint32_t border : {0u, 0x80FF4020u}) {
                    if (mode != TextureAddress::Border && border != 0) continue;
                    TextureSampler block, lanes;
                    bind_block_and_lanes(block, lanes, texture);
                    block.set_block_avx2(avx2);
                    SamplerState state;
                    state.address_u = state.address_v = state.address_w = mode;
                    state.border_color = border;
                    state.mag_filter = state.min_filter = TextureFilter::Linear;
                    state.mip_filter = TextureFilter::None;
                    for (TextureSampler* s : {&block, &lanes}) s->set_state(0, state);
                    block.prepare();
                    if (!block.block_path_applies(0)) GTEST_SKIP() << "no block path on this CPU";
                    for (const float step : {0.15f, 0.4f, 0.75f, 1.3f})
                        for (int z0 = -2; z0 < static_cast<int>(c.d) + 2; ++z0)
                            for (int y0 = -2; y0 < static_cast<int>(c.h) + 2; ++y0)
                                for (int x0 = -2; x0 < static_cast<int>(c.w) + 2; ++x0) {
                                    std::array<emu::FloatLanes, 4> coords{};
                                    const float u = static_cast<float>(x0) + fraction(rng);
                                    const float v = static_cast<float>(y0) + fraction(rng);
                                    const float w = static_cast<float>(z0) + fraction(rng);
                                    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                                        // Pixel (px, py) of the batch: x across the volume's x and
                                        // z, y across its y and x (a slice turned about two axes).
                                        const float px = static_cast<float>(2 * (l / 4) + (l & 1u));
                                        const float py = static_cast<float>((l >> 1) & 1u);
                                        coords[0][l] = (u + step * (0.8f * px - 0.3f * py)) / static_cast<float>(c.w);
                                        coords[1][l] = (v + step * (0.2f * px + 0.9f * py)) / static_cast<float>(c.h);
                                        coords[2][l] = (w + step * (-0.55f * px + 0.3f * py)) / static_cast<float>(c.d);
                                    }
                                    emu::TextureRequest request;
                                    request.coordinates = &coords;
                                    ASSERT_TRUE(same_texels(block, lanes, request, false))
                                        << format_info(c.format)->name << " step " << step << " at " << x0 << ", "
                                        << y0 << ", " << z0 << " address " << static_cast<int>(mode) << " border 0x"
                                        << std::hex << border << std::dec << (avx2 ? " (AVX2 instance)" : "");
                                    ++compared;
                                }
                }
    }
    EXPECT_GT(compared, 10000u);
}

// A texture of `count` texels, `width` a row, texel v holding texel(v) in its bytes, POINT-
// sampled at every texel centre (the block path's instances where the CPU runs one): channel `channel`
// of texel v must read with the bits expected(v).
template <typename TexelOf, typename ExpectedOf>
void expect_every_texel(Format format, uint32_t count, uint32_t width, unsigned channel, TexelOf texel_of,
                        ExpectedOf expected_of) {
    const uint32_t height = count / width;
    const unsigned texel_bytes = format_info(format)->bytes;
    Texture t = Texture::create_2d(format, width, height, 1);
    auto& bytes = t.surface(0).bytes();
    const size_t pitch = t.surface(0).row_pitch();
    for (uint32_t v = 0; v < count; ++v) {
        const uint64_t texel = texel_of(v);
        std::memcpy(bytes.data() + (v / width) * pitch + (v % width) * texel_bytes, &texel, texel_bytes);
    }
    for (const bool avx2 : forced_avx2_choices()) {
        TextureSampler s;
        s.set_texture(0, &t);
        s.set_block_avx2(avx2);
        SamplerState st;
        st.address_u = st.address_v = TextureAddress::Clamp;
        st.mag_filter = st.min_filter = TextureFilter::Point;
        st.mip_filter = TextureFilter::None;
        s.set_state(0, st);
        s.prepare();
        if (cpu_runs_block_path()) {
            ASSERT_TRUE(s.block_path_applies(0)) << format_info(format)->name;
        }
        for (uint32_t first = 0; first < count; first += emu::kBatchLanes) {
            std::array<emu::FloatLanes, 4> coords{};
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                const uint32_t v = std::min(first + l, count - 1);
                coords[0][l] = (static_cast<float>(v % width) + 0.5f) / static_cast<float>(width);
                coords[1][l] = (static_cast<float>(v / width) + 0.5f) / static_cast<float>(height);
            }
            emu::TextureRequest r;
            r.coordinates = &coords;
            std::array<emu::FloatLanes, 4> texels;
            s.sample(r, texels);
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                const uint32_t v = std::min(first + l, count - 1);
                ASSERT_EQ(std::bit_cast<uint32_t>(texels[channel][l]), expected_of(v))
                    << format_info(format)->name << " texel value 0x" << std::hex << texel_of(v)
                    << (avx2 ? " (AVX2 instance)" : "");
            }
        }
    }
}

// The block path decodes UNORM fields without a division (the product by a reciprocal split in
// two parts, unorm8::quotient_by()): every value of a field must read exactly v / (2^n - 1) as
// IEEE division gives it.
void expect_every_field_value(Format format, unsigned bits, unsigned shift, unsigned channel) {
    const uint32_t count = 1u << bits;
    const float max = static_cast<float>(count - 1);
    expect_every_texel(format, count, std::min(count, 4096u), channel, [&](uint32_t v) { return uint64_t{v} << shift; },
                       [&](uint32_t v) {
                           volatile float value = static_cast<float>(v);
                           return std::bit_cast<uint32_t>(value / max);
                       });
}

// Every binary16 value of an R16F texture reads as its IEEE value: sign * mantissa * 2^-24 for
// denormals, sign * (1 + m / 1024) * 2^(e - 15) otherwise, infinities as infinities, and NaNs
// with their payload as the texture holds it (sign | 0x7F800000 | m << 13: the per-lane
// decoder's rule, not quieted).
TEST(SamplerBlockPath, EveryHalfDecodesToItsValue) {
    expect_every_texel(Format::R16F, 65536, 256, 0, [](uint32_t h) { return h; }, [](uint32_t h) {
        const uint32_t e = h >> 10 & 0x1Fu, m = h & 0x3FFu;
        const float sign = h & 0x8000u ? -1.0f : 1.0f;
        if (e == 31 && m != 0) return (h & 0x8000u) << 16 | 0x7F800000u | m << 13;
        if (e == 31) return std::bit_cast<uint32_t>(sign * std::numeric_limits<float>::infinity());
        if (e == 0) return std::bit_cast<uint32_t>(sign * std::ldexp(static_cast<float>(m), -24));
        return std::bit_cast<uint32_t>(sign * std::ldexp(1.0f + static_cast<float>(m) / 1024.0f, static_cast<int>(e) - 15));
    });
}

// Every value of a signed (two's complement) field reads as D3D9's SNORM rule: s / (2^(n-1) - 1)
// as IEEE division gives it, and -1 for s = -2^(n-1). The U field of L6V5U5 (5 bits), V8U8 (8),
// A2W10V10U10 (10) and V16U16 (16).
void expect_every_signed_value(Format format, unsigned bits) {
    const uint32_t count = 1u << bits;
    const float max = static_cast<float>((1u << (bits - 1)) - 1u);
    expect_every_texel(format, count, std::min(count, 256u), 0, [](uint32_t v) { return v; }, [&](uint32_t v) {
        const int32_t s = v >= count / 2 ? static_cast<int32_t>(v) - static_cast<int32_t>(count) : static_cast<int32_t>(v);
        volatile float value = static_cast<float>(s);
        return std::bit_cast<uint32_t>(s == -static_cast<int32_t>(count / 2) ? -1.0f : value / max);
    });
}

TEST(SamplerBlockPath, EverySignedFieldValueDecodesAsTheDivision) {
    expect_every_signed_value(Format::L6V5U5, 5);
    expect_every_signed_value(Format::V8U8, 8);
    expect_every_signed_value(Format::A2W10V10U10, 10);
    expect_every_signed_value(Format::V16U16, 16);
}

TEST(SamplerBlockPath, EveryUnorm8ByteDecodesAsTheDivision) {
    expect_every_field_value(Format::A8R8G8B8, 8, 16, 0);  // red
    expect_every_field_value(Format::A8R8G8B8, 8, 8, 1);   // green
    expect_every_field_value(Format::A8R8G8B8, 8, 0, 2);   // blue
    expect_every_field_value(Format::A8R8G8B8, 8, 24, 3);  // alpha
}

TEST(SamplerBlockPath, EveryTenAndTwoBitFieldDecodesAsTheDivision) {
    expect_every_field_value(Format::A2B10G10R10, 10, 0, 0);   // red
    expect_every_field_value(Format::A2B10G10R10, 10, 20, 2);  // blue
    expect_every_field_value(Format::A2B10G10R10, 2, 30, 3);   // alpha
}

TEST(SamplerBlockPath, EverySixteenBitFieldDecodesAsTheDivision) {
    expect_every_field_value(Format::G16R16, 16, 0, 0);
    expect_every_field_value(Format::G16R16, 16, 16, 1);
    // A16B16G16R16's instance decodes each field by unorm8::decode16, not the corrected quotient.
    for (unsigned k = 0; k < 4; ++k) expect_every_field_value(Format::A16B16G16R16, 16, 16 * k, k);
}

// The exact bilinear sums S of fixed8 filtering (an integer below 2^24 for fields of n <= 8
// bits; for A2B10G10R10's 10-bit fields the float nearest it) become S / (max * 65536) through
// unorm8::quotient with the 2^-16 folded into its constants: every S of every field width must
// give IEEE division's float, bit for bit.
// (GCC 12's AVX-512 headers trip -Wuninitialized on their own _mm512_undefined_*() self-init.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
SM2_AVX512 void expect_every_bilinear_sum_divides_exactly(uint32_t bits) {
    const uint32_t max = (1u << bits) - 1u;
    const uint32_t largest = max * 65536u;  // every tap at max, weights summing to 65536
    const __m512i step = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    alignas(64) std::array<float, emu::kBatchLanes> got;
    for (uint32_t first = 0; first <= largest; first += emu::kBatchLanes) {
        const __m512 sum = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(static_cast<int32_t>(first)), step));
        _mm512_store_ps(got.data(), unorm8::quotient(sum, static_cast<float>(max), 1.0f / 65536.0f));
        for (unsigned l = 0; l < emu::kBatchLanes && first + l <= largest; ++l) {
            volatile float numerator = static_cast<float>(first + l);
            const float expected = numerator / static_cast<float>(largest);
            ASSERT_EQ(std::bit_cast<uint32_t>(got[l]), std::bit_cast<uint32_t>(expected)) << bits << "-bit sum " << first + l;
        }
    }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

TEST(SamplerBlockPath, EveryFixed8BilinearSumDividesAsTheDivision) {
    if (!cpu_has_avx512()) GTEST_SKIP() << "no AVX-512 on this CPU";
    for (const uint32_t bits : {10u, 8u, 6u, 5u, 4u, 2u, 1u}) expect_every_bilinear_sum_divides_exactly(bits);
}

}  // namespace
}  // namespace sm2::runtime

// The same for the AVX2 instance of unorm8::quotient (after every use of the real intrinsics:
// avx512_on_avx2.h takes their names).
#include "avx512_on_avx2.h"

namespace sm2::runtime::avx2 {
namespace {

SM2_AVX2 void expect_every_bilinear_sum_divides_exactly(uint32_t bits) {
    const uint32_t max = (1u << bits) - 1u;
    const uint32_t largest = max * 65536u;
    const Ints512 step = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    alignas(64) std::array<float, emu::kBatchLanes> got;
    for (uint32_t first = 0; first <= largest; first += emu::kBatchLanes) {
        const Floats512 sum = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(static_cast<int32_t>(first)), step));
        _mm512_store_ps(got.data(), unorm8::quotient(sum, static_cast<float>(max), 1.0f / 65536.0f));
        for (unsigned l = 0; l < emu::kBatchLanes && first + l <= largest; ++l) {
            volatile float numerator = static_cast<float>(first + l);
            const float expected = numerator / static_cast<float>(largest);
            ASSERT_EQ(std::bit_cast<uint32_t>(got[l]), std::bit_cast<uint32_t>(expected)) << bits << "-bit sum " << first + l;
        }
    }
}

TEST(SamplerBlockPath, EveryFixed8BilinearSumDividesAsTheDivisionInTheAvx2Instance) {
    if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 and FMA on this CPU";
    for (const uint32_t bits : {10u, 8u, 6u, 5u, 4u, 2u, 1u}) expect_every_bilinear_sum_divides_exactly(bits);
}

// The AVX2 stand-in for VPERMT2W (which block_volume_window() names; the AVX2 instance never
// takes that path): each 16-bit index's low 6 bits choose one of the 64 words of {a, b}.
SM2_AVX2 void expect_sixteen_bit_permutes_pick_their_words() {
    alignas(64) uint16_t table[64], index[32], got[32];
    for (unsigned i = 0; i < 64; ++i) table[i] = static_cast<uint16_t>(0x1000 + 7 * i);
    std::mt19937 rng(5);
    for (unsigned round = 0; round < 100; ++round) {
        for (auto& i : index) i = static_cast<uint16_t>(rng());
        _mm512_store_si512(got, _mm512_permutex2var_epi16(_mm512_load_si512(table), _mm512_load_si512(index),
                                                          _mm512_load_si512(table + 32)));
        for (unsigned l = 0; l < 32; ++l) ASSERT_EQ(got[l], 0x1000 + 7 * (index[l] & 63u)) << "index " << index[l];
    }
}

TEST(SamplerBlockPath, SixteenBitPermutesInTheAvx2InstancePickTheirWords) {
    if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 and FMA on this CPU";
    expect_sixteen_bit_permutes_pick_their_words();
}

}  // namespace
}  // namespace sm2::runtime::avx2
