// Sampler states (D3DSAMP_*, pipeline.md §17) and the TextureSampler: the one implementation of
// the shader engine's emu::Sampler (texld, texldp, texldb), over up to 16 bound
// (texture, sampler state) pairs. Rules, conventions and precision: docs/texturing.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "sm2/emu/sampler.h"
#include "sm2/runtime/formats.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {

// D3DSAMPLERSTATETYPE
enum class SamplerStateType : uint32_t {
    AddressU = 1, AddressV = 2, AddressW = 3, BorderColor = 4, MagFilter = 5, MinFilter = 6,
    MipFilter = 7, MipMapLodBias = 8, MaxMipLevel = 9, MaxAnisotropy = 10, SrgbTexture = 11,
    ElementIndex = 12, DMapOffset = 13,
};

// D3DTEXTUREADDRESS
enum class TextureAddress : uint32_t { Wrap = 1, Mirror = 2, Clamp = 3, Border = 4, MirrorOnce = 5 };

// D3DTEXTUREFILTERTYPE
enum class TextureFilter : uint32_t {
    None = 0, Point = 1, Linear = 2, Anisotropic = 3, PyramidalQuad = 6, GaussianQuad = 7,
};

struct SamplerState {
    TextureAddress address_u = TextureAddress::Wrap;
    TextureAddress address_v = TextureAddress::Wrap;
    TextureAddress address_w = TextureAddress::Wrap;
    uint32_t border_color = 0;                     // D3DCOLOR 0xAARRGGBB
    TextureFilter mag_filter = TextureFilter::Point;
    TextureFilter min_filter = TextureFilter::Point;
    TextureFilter mip_filter = TextureFilter::None;
    float mip_lod_bias = 0.0f;                     // stored as float bits in the DWORD
    uint32_t max_mip_level = 0;
    uint32_t max_anisotropy = 1;
    bool srgb_texture = false;
    uint32_t element_index = 0;
    uint32_t dmap_offset = 0;

    // SetSamplerState with the raw DWORD (floats as their bits). Any value is stored as given,
    // like D3D9; the sampler interprets out-of-range values as documented in docs/texturing.md.
    // Returns false (and changes nothing) for a state type that does not exist.
    bool set(uint32_t type, uint32_t value);
    // The raw DWORD of a state; nullopt for a state type that does not exist.
    [[nodiscard]] std::optional<uint32_t> get(uint32_t type) const;

    bool operator==(const SamplerState&) const = default;
};

// Bilinear/trilinear/anisotropic weights: 8-bit sub-texel fractions (hardware of the era, the
// default), or exact float (the reference).
enum class FilterPrecision : uint8_t { Fixed8, Exact };

class TextureSampler final : public emu::Sampler {
public:
    static constexpr unsigned kStages = 16;

    // The texture is not owned: it must outlive its binding. nullptr unbinds; an unbound stage
    // samples (0, 0, 0, 1).
    void set_texture(unsigned stage, const Texture* texture);
    void set_state(unsigned stage, const SamplerState& state);
    [[nodiscard]] const Texture* texture(unsigned stage) const { return stages_.at(stage).texture; }
    [[nodiscard]] const SamplerState& state(unsigned stage) const { return stages_.at(stage).state; }
    // A state changed through this reference is seen by the next prepare().
    [[nodiscard]] SamplerState& state(unsigned stage) {
        prepared_.at(stage) = false;
        return stages_.at(stage).state;
    }

    void set_precision(FilterPrecision precision) {
        precision_ = precision;
        forget_prepared();
    }
    // The 16-lane path for 2D and volume lookups of the formats and states it covers
    // (sampler.cpp, block_supported; on by default where the CPU has AVX-512 or AVX2 with FMA);
    // off, every lookup takes the per-lane path. Both give the same bits.
    void set_block_path(bool enabled) {
        block_enabled_ = enabled;
        forget_prepared();
    }
    // The block path reads texels through 32-bit offsets when a texture's levels lie within 2^31
    // bytes of each other, else through 64-bit addresses; true forces the 64-bit reads (tests:
    // which one a texture gets depends on where the allocator put its levels).
    void set_block_64bit_addresses(bool forced) {
        block_64bit_addresses_ = forced;
        forget_prepared();
    }
    // The block path's AVX2 instance even where the CPU has AVX-512 (tests: both instances give
    // the per-lane path's bits).
    void set_block_avx2(bool forced) {
        block_avx2_ = forced;
        forget_prepared();
    }
    // The alpha gate (a draw sets it where alpha_source_sampler() names the stage and the draw
    // writes nothing where the shader's alpha saturates to +0: draw.cpp): a lookup of the stage
    // whose alpha is +0, -0 or NaN on every lane that shades (not a helper lane) may leave red,
    // green and blue +0 instead of their values. The block path's volume lookups of one level
    // do, which skips three quarters of their decoding and sums; every other lookup ignores it.
    void set_alpha_gate(unsigned stage, bool gated) { alpha_gates_.at(stage) = gated; }
    [[nodiscard]] bool alpha_gate(unsigned stage) const { return alpha_gates_.at(stage); }
    // Where the stage's lookups read BORDERCOLOR alone and so return alpha +0: per axis (u, v,
    // w) of a 2D or volume texture addressed BORDER, the coordinates from `low` up, below
    // `high`, outside which every POINT or LINEAR tap of every level lies outside the texture
    // (a texel of margin on the smallest level). A lane outside on one such axis sums
    // BORDERCOLOR's alpha 0 times finite weights: +0.
    // nullopt where no axis is BORDER, BORDERCOLOR's alpha is not 0, no texture is bound, or
    // the filter is not POINT or LINEAR (anisotropic probes spread over the pixel's footprint).
    struct BorderBox {
        unsigned axes = 0;                   // bit a: axis a is addressed BORDER
        std::array<float, 3> low{}, high{};  // per axis in `axes`
    };
    [[nodiscard]] std::optional<BorderBox> transparent_border(unsigned stage) const;
    // The lanes of a batch whose coordinates (u, v, w: 16 lanes each) lie outside `box` on one
    // of its axes: the lanes whose lookups return alpha +0. Computed by the CPU's 16-lane
    // instance (AVX2 where set_block_avx2() forces it), or lane by lane where the block path is
    // off or the CPU has neither AVX-512 nor AVX2.
    [[nodiscard]] emu::LaneMask outside_border(const BorderBox& box, const std::array<const float*, 3>& coordinates) const;
    // Whether sample() takes the 16-lane path for this stage's texture and state.
    [[nodiscard]] bool block_path_applies(unsigned stage) const;
    // Decides the block path and builds its level tables for every stage now, once (a draw calls
    // it on its own copy after binding everything; sample() prepares a stage it finds
    // unprepared). Any later set_* call forgets what was prepared for the stages it touches.
    void prepare();
    void prepare_stage(unsigned stage);  // prepare() for one stage (sample() does it on first use)

    struct BlockLevels;  // the block path's per-texture tables (sampler.cpp)
    // The block path's last level choice per stage: the 4 quads' squared derivative lengths of
    // the last batch, their lengths and the levels they gave (a function of the squares for a
    // prepared stage, so a batch with the same squares, as every batch of a screen-aligned pass,
    // reuses them).
    struct BatchLevelMemo {
        bool valid = false;
        std::array<double, 8> squares{}, lengths{};
        std::array<int32_t, 4> l0{}, l1{}, linear{};
        std::array<float, 4> frac{};
    };

    [[nodiscard]] FilterPrecision precision() const { return precision_; }

    // emu::Sampler: one float4 per lane; LOD per 2x2 quad (see docs/texturing.md).
    void sample(const emu::TextureRequest& request, std::array<emu::FloatLanes, 4>& texels) override;

    // One lookup with explicit derivatives of the normalized coordinates (u, v, w) per pixel
    // step in x and y (cube maps: derivatives of the direction), plus an extra LOD bias.
    [[nodiscard]] Float4 sample_gradient(unsigned stage, const std::array<float, 3>& coord,
                                         const std::array<float, 3>& ddx, const std::array<float, 3>& ddy,
                                         float lod_bias = 0.0f) const;

    // The level of detail lambda (before MAXMIPLEVEL clamping, with both biases) and anisotropy
    // probe count the sampler would use for these texel-space derivatives; for tests and tools.
    struct LodInfo {
        float lambda = 0;       // log2(rho) + biases (NaN-free, clamped to [-64, 64])
        unsigned probes = 1;    // anisotropic probes
        bool magnify = true;
    };
    [[nodiscard]] LodInfo level_of_detail(unsigned stage, const std::array<float, 3>& ddx_texels,
                                          const std::array<float, 3>& ddy_texels, float lod_bias = 0.0f) const;

private:
    struct Stage {
        const Texture* texture = nullptr;
        SamplerState state;
    };
    std::array<Stage, kStages> stages_{};
    FilterPrecision precision_ = FilterPrecision::Fixed8;
    bool block_enabled_ = true;
    bool block_64bit_addresses_ = false;
    bool block_avx2_ = false;
    // prepare()'s result per stage: whether it ran, and the tables (null: no block path).
    std::array<bool, kStages> prepared_{};
    std::array<std::shared_ptr<const BlockLevels>, kStages> block_levels_{};
    std::array<BatchLevelMemo, kStages> level_memo_{};  // valid only while the stage stays prepared
    std::array<bool, kStages> alpha_gates_{};
    // The stage's block-path tables, or null where the block path does not apply.
    [[nodiscard]] std::shared_ptr<const BlockLevels> block_levels_for(unsigned stage) const;
    // sample() for a request the block path does not take: lane by lane.
    void sample_lanes(const emu::TextureRequest& request, unsigned quads, std::array<emu::FloatLanes, 4>& texels) const;
    void forget_prepared() {
        prepared_.fill(false);
    }
};

}  // namespace sm2::runtime
