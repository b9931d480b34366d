// TextureSampler::transparent_border() and outside_border(): the coordinates where a lookup
// reads BORDERCOLOR alone, so that its alpha is +0 where BORDERCOLOR's is 0 (a draw skips the
// batches whose alpha lookups all lie there: draw.cpp's outside_cull).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "sm2/runtime/sampler.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
float below(float x) { return std::nextafter(x, -kInf); }
float above(float x) { return std::nextafter(x, kInf); }

SamplerState border_state(uint32_t border_color = 0x00FF8040) {
    SamplerState s;
    s.address_u = s.address_v = s.address_w = TextureAddress::Border;
    s.border_color = border_color;
    s.mag_filter = s.min_filter = s.mip_filter = TextureFilter::Linear;
    return s;
}

std::optional<TextureSampler::BorderBox> box_of(const Texture* texture, const SamplerState& state) {
    TextureSampler sampler;
    sampler.set_texture(0, texture);
    sampler.set_state(0, state);
    return sampler.transparent_border(0);
}

// A texel of margin on the smallest level, per axis, rounded outward to floats.
TEST(SamplerBorderBox, ATexelOfTheSmallestLevelBeyondEachBorderAxis) {
    // 8x4 with two levels: the smallest is 4x2, a texel 1/4 of u and 1/2 of v.
    const Texture two_levels = Texture::create_2d(Format::A8R8G8B8, 8, 4, 2);
    SamplerState state = border_state();
    auto box = box_of(&two_levels, state);
    ASSERT_TRUE(box);
    EXPECT_EQ(box->axes, 3u);
    EXPECT_EQ(box->low[0], below(-0.25f));
    EXPECT_EQ(box->high[0], above(1.25f));
    EXPECT_EQ(box->low[1], below(-0.5f));
    EXPECT_EQ(box->high[1], above(1.5f));
    // The full chain ends at 1x1: a whole texture of margin.
    const Texture chain = Texture::create_2d(Format::A8R8G8B8, 8, 4, 0);
    box = box_of(&chain, state);
    ASSERT_TRUE(box);
    EXPECT_EQ(box->low[0], below(-1.0f));
    EXPECT_EQ(box->high[1], above(2.0f));
    // v alone BORDER (u CLAMP): one axis.
    state.address_u = TextureAddress::Clamp;
    box = box_of(&two_levels, state);
    ASSERT_TRUE(box);
    EXPECT_EQ(box->axes, 2u);
    // A 3-wide volume of one level, w alone BORDER: 1/3 of a texture, rounded outward.
    const Texture volume = Texture::create_volume(Format::A4R4G4B4, 4, 4, 3, 1);
    state.address_v = TextureAddress::Wrap;
    box = box_of(&volume, state);
    ASSERT_TRUE(box);
    EXPECT_EQ(box->axes, 4u);
    EXPECT_LE(static_cast<double>(box->low[2]), -1.0 / 3.0);
    EXPECT_GT(static_cast<double>(box->low[2]), -1.0 / 3.0 - 1e-6);
    EXPECT_GE(static_cast<double>(box->high[2]), 4.0 / 3.0);
    EXPECT_LT(static_cast<double>(box->high[2]), 4.0 / 3.0 + 1e-6);
    // POINT filters take the same box.
    state.mag_filter = state.min_filter = TextureFilter::Point;
    state.mip_filter = TextureFilter::None;
    EXPECT_TRUE(box_of(&volume, state));
}

TEST(SamplerBorderBox, NoneWhereABorderLookupCanBeOpaque) {
    const Texture texture = Texture::create_2d(Format::A8R8G8B8, 8, 8, 1);
    EXPECT_TRUE(box_of(&texture, border_state()));
    EXPECT_FALSE(box_of(&texture, border_state(0x01000000)));  // BORDERCOLOR's alpha 1/255
    EXPECT_FALSE(box_of(nullptr, border_state()));             // unbound: (0, 0, 0, 1)
    SamplerState state = border_state();
    state.min_filter = TextureFilter::Anisotropic;  // probes spread over the footprint
    EXPECT_FALSE(box_of(&texture, state));
    state = border_state();
    state.mag_filter = TextureFilter::Anisotropic;
    EXPECT_FALSE(box_of(&texture, state));
    state = border_state();
    state.address_u = state.address_v = TextureAddress::Clamp;  // w is not an axis of a 2D texture
    EXPECT_FALSE(box_of(&texture, state));
    const Texture cube = Texture::create_cube(Format::A8R8G8B8, 8, 1);
    EXPECT_FALSE(box_of(&cube, border_state()));
}

// Random textures (alpha mostly non-zero), states, levels and coordinates, some lanes put
// outside the box on one of its axes (just past a bound, far, infinite): outside_border() marks
// exactly the lanes outside, and both the block path and the per-lane path sample alpha +-0 on
// every one of them.
TEST(SamplerBorderBox, LookupsOutsideTheBoxReadAlphaZeroOnEveryPath) {
    std::mt19937 rng(20261205);
    const Format formats[] = {Format::A8R8G8B8, Format::A4R4G4B4, Format::X8R8G8B8, Format::L8,
                              Format::A16B16G16R16F, Format::A32B32G32R32F, Format::A8, Format::R5G6B5};
    const TextureAddress others[] = {TextureAddress::Clamp, TextureAddress::Wrap, TextureAddress::Mirror,
                                     TextureAddress::MirrorOnce};
    const TextureFilter filters[] = {TextureFilter::Point, TextureFilter::Linear};
    std::uniform_real_distribution<float> unit(-0.3f, 1.3f);
    unsigned outside_lanes = 0, inside_lanes = 0;
    for (unsigned round = 0; round < 300; ++round) {
        const bool volume = round % 2 == 1;
        const Format format = formats[rng() % std::size(formats)];
        // Powers of two take mipmaps; other sizes one level.
        const bool pow2 = rng() % 2 == 0;
        const auto size = [&] { return pow2 ? 1u << (rng() % 4) : 1u + rng() % 9; };
        const uint32_t w = size(), h = size(), d = volume ? size() : 0;
        const uint32_t levels = pow2 && rng() % 2 ? 0 : 1;  // the full chain or one level
        Texture texture = volume ? Texture::create_volume(format, w, h, d, levels) : Texture::create_2d(format, w, h, levels);
        for (uint32_t l = 0; l < texture.levels(); ++l)
            for (auto& b : texture.surface(l).bytes()) b = static_cast<std::byte>(rng() & 0xFFu);
        SamplerState state;
        state.address_u = rng() % 2 ? TextureAddress::Border : others[rng() % 4];
        state.address_v = rng() % 2 ? TextureAddress::Border : others[rng() % 4];
        state.address_w = rng() % 2 ? TextureAddress::Border : others[rng() % 4];
        if (state.address_u != TextureAddress::Border && state.address_v != TextureAddress::Border)
            state.address_u = TextureAddress::Border;
        state.border_color = static_cast<uint32_t>(rng()) & 0x00FFFFFFu;
        state.mag_filter = filters[rng() % 2];
        state.min_filter = filters[rng() % 2];
        state.mip_filter = rng() % 3 == 0 ? TextureFilter::None : filters[rng() % 2];
        state.max_mip_level = rng() % 4 == 0 ? rng() % 3 : 0;
        state.mip_lod_bias = rng() % 3 == 0 ? static_cast<float>(static_cast<int>(rng() % 200) - 100) / 32.0f : 0.0f;
        const std::optional<TextureSampler::BorderBox> box = box_of(&texture, state);
        ASSERT_TRUE(box) << "round " << round;

        std::array<emu::FloatLanes, 4> coordinates{};
        emu::LaneMask expected = 0;
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            for (unsigned a = 0; a < 3; ++a) coordinates[a][l] = unit(rng);
            coordinates[3][l] = 1.0f;
            if (rng() % 4 == 0) continue;  // inside on every axis (or outside by chance)
            unsigned axis = rng() % 3;
            while (!(box->axes >> axis & 1u)) axis = rng() % 3;
            const float low = box->low[axis], high = box->high[axis];
            float& c = coordinates[axis][l];
            switch (rng() % 8) {
            case 0: c = high; break;
            case 1: c = above(above(high)); break;
            case 2: c = below(low); break;
            case 3: c = below(below(low)); break;
            case 4: c = high + unit(rng) * 3.0f + 0.5f; break;
            case 5: c = low - unit(rng) * 3.0f - 0.5f; break;
            case 6: c = rng() % 2 ? 1e30f : -1e30f; break;
            default: c = rng() % 2 ? kInf : -kInf; break;
            }
        }
        // The lanes outside, by the box's definition.
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            for (unsigned a = 0; a < 3; ++a)
                if ((box->axes >> a & 1u) && (coordinates[a][l] < box->low[a] || coordinates[a][l] >= box->high[a]))
                    expected |= emu::LaneMask{1} << l;
        // Every instance: the CPU's (AVX-512 here), AVX2 forced, and lane by lane.
        for (unsigned instance = 0; instance < 3; ++instance) {
            TextureSampler sampler;
            sampler.set_block_avx2(instance == 1);
            sampler.set_block_path(instance != 2);
            EXPECT_EQ(sampler.outside_border(*box, {coordinates[0].data(), coordinates[1].data(), coordinates[2].data()}),
                      expected)
                << "round " << round << " instance " << instance;
        }
        for (const bool block : {true, false}) {
            TextureSampler sampler;
            sampler.set_texture(0, &texture);
            sampler.set_state(0, state);
            sampler.set_block_path(block);
            sampler.set_precision(rng() % 4 == 0 ? FilterPrecision::Exact : FilterPrecision::Fixed8);
            emu::TextureRequest request;
            request.coordinates = &coordinates;
            std::array<emu::FloatLanes, 4> texels{};
            sampler.sample(request, texels);
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                if (expected >> l & 1u) {
                    EXPECT_EQ(texels[3][l], 0.0f) << "round " << round << (block ? " block" : " per lane") << " lane " << l;
                }
            }
        }
        outside_lanes += static_cast<unsigned>(std::popcount(expected));
        inside_lanes += emu::kBatchLanes - static_cast<unsigned>(std::popcount(expected));
    }
    EXPECT_GT(outside_lanes, 3000u);
    EXPECT_GT(inside_lanes, 1000u);
}

}  // namespace
}  // namespace sm2::runtime
