// The output merger (pipeline.md §7, §10, §12, §13): every blend factor and operation with
// exactly representable colours, separate alpha, BLENDFACTOR, write masks per target, multiple
// render targets, alpha test, fog, sRGB write, texkill, and each render-target format's
// rounding on store. Expected values are worked out in the comments.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "sm2/assembler/assembler.h"
#include "sm2/emu/engine.h"
#include "sm2/runtime/output_merger.h"
#include "sm2/runtime/primitive_assembly.h"
#include "sm2/runtime/vertex_fetch.h"

namespace sm2::runtime {
namespace {

// S and D with exact binary fractions.
const Vec4 S{0.5f, 0.25f, 1.0f, 0.75f};
const Vec4 D{0.25f, 0.5f, 0.0f, 0.375f};

Vec4 src_only(Blend f, uint32_t blend_factor = 0xFFFFFFFFu) {
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.src_blend = f;
    rs.dest_blend = Blend::Zero;
    rs.blend_factor = blend_factor;
    return blend(output_merger_state(rs).blend, S, D, true);
}

TEST(OutputMerger, EverySourceFactor) {
    // result = S * Fs (DESTBLEND ZERO, ADD); alpha uses the same factor's alpha.
    EXPECT_EQ(src_only(Blend::Zero), (Vec4{0, 0, 0, 0}));
    EXPECT_EQ(src_only(Blend::One), S);
    EXPECT_EQ(src_only(Blend::SrcColor), (Vec4{0.25f, 0.0625f, 1, 0.5625f}));        // S*S
    EXPECT_EQ(src_only(Blend::InvSrcColor), (Vec4{0.25f, 0.1875f, 0, 0.1875f}));     // S*(1-S)
    EXPECT_EQ(src_only(Blend::SrcAlpha), (Vec4{0.375f, 0.1875f, 0.75f, 0.5625f}));   // S*0.75
    EXPECT_EQ(src_only(Blend::InvSrcAlpha), (Vec4{0.125f, 0.0625f, 0.25f, 0.1875f}));  // S*0.25
    EXPECT_EQ(src_only(Blend::DestAlpha), (Vec4{0.1875f, 0.09375f, 0.375f, 0.28125f}));  // S*0.375
    EXPECT_EQ(src_only(Blend::InvDestAlpha), (Vec4{0.3125f, 0.15625f, 0.625f, 0.46875f}));  // S*0.625
    EXPECT_EQ(src_only(Blend::DestColor), (Vec4{0.125f, 0.125f, 0, 0.28125f}));     // S*D
    EXPECT_EQ(src_only(Blend::InvDestColor), (Vec4{0.375f, 0.125f, 1, 0.46875f}));  // S*(1-D)
    // SRCALPHASAT: f = min(As, 1 - Ad) = min(0.75, 0.625) = 0.625; factor (f, f, f, 1).
    EXPECT_EQ(src_only(Blend::SrcAlphaSat), (Vec4{0.3125f, 0.15625f, 0.625f, 0.75f}));
    // BLENDFACTOR 0xFF00FF00 = (R 0, G 1, B 0, A 1); INVBLENDFACTOR = (1, 0, 1, 0).
    EXPECT_EQ(src_only(Blend::BlendFactor, 0xFF00FF00u), (Vec4{0, 0.25f, 0, 0.75f}));
    EXPECT_EQ(src_only(Blend::InvBlendFactor, 0xFF00FF00u), (Vec4{0.5f, 0, 1, 0}));
    // BOTHSRCALPHA: S*As + D*(1-As) = S*0.75 + D*0.25
    //   = (0.375 + 0.0625, 0.1875 + 0.125, 0.75 + 0, 0.5625 + 0.09375).
    EXPECT_EQ(src_only(Blend::BothSrcAlpha), (Vec4{0.4375f, 0.3125f, 0.75f, 0.65625f}));
    // BOTHINVSRCALPHA: S*0.25 + D*0.75 = (0.125 + 0.1875, 0.0625 + 0.375, 0.25, 0.1875 + 0.28125).
    EXPECT_EQ(src_only(Blend::BothInvSrcAlpha), (Vec4{0.3125f, 0.4375f, 0.25f, 0.46875f}));
}

TEST(OutputMerger, DestinationFactors) {
    // SRCBLEND ZERO: result = D * Fd. DESTBLEND SRCCOLOR: D*S = (0.125, 0.125, 0, 0.28125);
    // INVSRCALPHA: D*0.25 = (0.0625, 0.125, 0, 0.09375).
    BlendState b;
    b.enable = true;
    b.src = b.src_alpha = Blend::Zero;
    b.dst = b.dst_alpha = Blend::SrcColor;
    EXPECT_EQ(blend(b, S, D, true), (Vec4{0.125f, 0.125f, 0, 0.28125f}));
    b.dst = b.dst_alpha = Blend::InvSrcAlpha;
    EXPECT_EQ(blend(b, S, D, true), (Vec4{0.0625f, 0.125f, 0, 0.09375f}));
}

TEST(OutputMerger, EveryBlendOp) {
    BlendState b;
    b.enable = true;
    b.src = b.dst = b.src_alpha = b.dst_alpha = Blend::One;
    auto with = [&](BlendOp op, bool fixed) {
        b.op = b.op_alpha = op;
        return blend(b, S, D, fixed);
    };
    // ADD: S + D = (0.75, 0.75, 1, 1.125): alpha clamps to 1 for fixed-point targets only.
    EXPECT_EQ(with(BlendOp::Add, true), (Vec4{0.75f, 0.75f, 1, 1}));
    EXPECT_EQ(with(BlendOp::Add, false), (Vec4{0.75f, 0.75f, 1, 1.125f}));
    // SUBTRACT: S - D = (0.25, -0.25 -> 0, 1, 0.375).
    EXPECT_EQ(with(BlendOp::Subtract, true), (Vec4{0.25f, 0, 1, 0.375f}));
    EXPECT_EQ(with(BlendOp::Subtract, false), (Vec4{0.25f, -0.25f, 1, 0.375f}));
    // REVSUBTRACT: D - S = (-0.25, 0.25, -1, -0.375) -> (0, 0.25, 0, 0).
    EXPECT_EQ(with(BlendOp::RevSubtract, true), (Vec4{0, 0.25f, 0, 0}));
    // MIN / MAX ignore the factors (set them to ZERO to show it).
    b.src = b.dst = b.src_alpha = b.dst_alpha = Blend::Zero;
    EXPECT_EQ(with(BlendOp::Min, true), (Vec4{0.25f, 0.25f, 0, 0.375f}));
    EXPECT_EQ(with(BlendOp::Max, true), (Vec4{0.5f, 0.5f, 1, 0.75f}));
}

TEST(OutputMerger, SeparateAlphaAndSourceClamp) {
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.separate_alpha_blend_enable = true;
    rs.src_blend_alpha = Blend::Zero;
    rs.dest_blend_alpha = Blend::One;  // colour ONE/ZERO, alpha ZERO/ONE: (S.rgb, D.a)
    EXPECT_EQ(blend(output_merger_state(rs).blend, S, D, true), (Vec4{0.5f, 0.25f, 1, 0.375f}));
    rs.separate_alpha_blend_enable = false;  // alpha states ignored: (S.rgb, S.a)
    EXPECT_EQ(blend(output_merger_state(rs).blend, S, D, true), S);
    // A fixed-point target clamps the shader colour before blending: 1.5 * 0.5 -> 0.5.
    BlendState b;
    b.enable = true;
    b.src = b.src_alpha = Blend::DestColor;
    const Vec4 bright{1.5f, -1, 0, 0};
    const Vec4 half{0.5f, 0.5f, 0.5f, 0.5f};
    EXPECT_EQ(blend(b, bright, half, true), (Vec4{0.5f, 0, 0, 0}));
    EXPECT_EQ(blend(b, bright, half, false), (Vec4{0.75f, -0.5f, 0, 0}));
}

TEST(OutputMerger, AlphaTestAndFogFactor) {
    RenderState rs;
    rs.alpha_test_enable = true;
    rs.alpha_ref = 0x180;  // only the low 8 bits: 0x80 -> 128/255 = 0.50196
    rs.alpha_func = CompareFunc::GreaterEqual;
    const auto s = output_merger_state(rs);
    EXPECT_FALSE(alpha_test_passes(s, 0.5f, true));
    EXPECT_TRUE(alpha_test_passes(s, 0.51f, true));
    EXPECT_TRUE(alpha_test_passes(s, 7.0f, true));  // clamped to 1
    EXPECT_FALSE(alpha_test_passes(s, std::nanf(""), true));
    EXPECT_FALSE(alpha_test_passes(s, std::nanf(""), false));
    // Float targets do not clamp: GREATER 255 (1.0) passes 1.5 there, not on a clamping target;
    // LESS 0 passes -0.25 there.
    RenderState greater = rs;
    greater.alpha_ref = 255;
    greater.alpha_func = CompareFunc::Greater;
    EXPECT_TRUE(alpha_test_passes(output_merger_state(greater), 1.5f, false));
    EXPECT_FALSE(alpha_test_passes(output_merger_state(greater), 1.5f, true));
    EXPECT_FALSE(alpha_test_passes(output_merger_state(greater), 1.0f, false));
    RenderState less = rs;
    less.alpha_ref = 0;
    less.alpha_func = CompareFunc::Less;
    EXPECT_TRUE(alpha_test_passes(output_merger_state(less), -0.25f, false));
    EXPECT_FALSE(alpha_test_passes(output_merger_state(less), -0.25f, true));

    OutputMergerState f;
    f.fog_table_mode = FogMode::None;
    EXPECT_EQ(fog_factor(f, 0.25f, 0.9f), 0.25f);  // oFog, depth ignored
    EXPECT_EQ(fog_factor(f, 1.5f, 0.9f), 1.0f);    // clamped
    f.fog_table_mode = FogMode::Linear;            // (end - d) / (end - start): start 0, end 1
    EXPECT_EQ(fog_factor(f, 0.0f, 0.25f), 0.75f);
    f.fog_start = 0.5f;                            // d before the start: 1.6 -> 1
    EXPECT_EQ(fog_factor(f, 0.0f, 0.2f), 1.0f);
    f.fog_table_mode = FogMode::Exp;               // 1 / e^(d * density): d 0.5, density 2 -> 1/e
    f.fog_density = 2.0f;
    EXPECT_FLOAT_EQ(fog_factor(f, 0.0f, 0.5f), static_cast<float>(std::exp(-1.0)));
    f.fog_table_mode = FogMode::Exp2;              // 1 / e^((0.5 * 2)^2) = 1/e
    EXPECT_FLOAT_EQ(fog_factor(f, 0.0f, 0.5f), static_cast<float>(std::exp(-1.0)));
}

// A render-target pixel and a one-lane pixel batch at (1, 2).
struct Scene {
    Surface target;
    emu::Batch batch;
    PixelLanes lanes;
    RenderTargets targets;
    explicit Scene(Format f) : target(f, 4, 4) {
        targets.color[0] = &target;
        lanes.quad_count = 1;
        lanes.x[0] = 1;
        lanes.y[0] = 2;
        lanes.depth[0] = 0.5f;
    }
    void colour(unsigned rt, Vec4 c) { batch.set(batch.render_target(rt), 0, c[0], c[1], c[2], c[3]); }
    emu::LaneMask run(const RenderState& rs, uint8_t outputs = 1) {
        MergeInput in;
        in.batch = &batch;
        in.lanes = &lanes;
        in.live = 1;
        in.color_outputs = outputs;
        return merge(output_merger_state(rs), targets, in);
    }
    template <typename T>
    T stored(const Surface& s) const {
        T v;
        std::memcpy(&v, s.bytes().data() + 2 * s.row_pitch() + sizeof(T), sizeof(T));
        return v;
    }
    template <typename T>
    void store(T v) { std::memcpy(target.bytes().data() + 2 * target.row_pitch() + sizeof(T), &v, sizeof(T)); }
};

TEST(OutputMerger, A8R8G8B8RoundingAndClamping) {
    // (0.5, 0.2, 1.2, -0.1): R round(127.5) = 0x80, G round(51.00000076) = 0x33, B clamps to
    // 0xFF, A clamps to 0.
    Scene sc(Format::A8R8G8B8);
    sc.colour(0, {0.5f, 0.2f, 1.2f, -0.1f});
    EXPECT_EQ(sc.run(RenderState{}), 1u);
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0x008033FFu);
}

TEST(OutputMerger, OtherTargetFormatsRounding) {
    {  // R5G6B5 (1, 0.5, 0): R 31, G round(31.5) = 32, B 0 -> 31<<11 | 32<<5 = 0xFC00.
        Scene sc(Format::R5G6B5);
        sc.colour(0, {1, 0.5f, 0, 1});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint16_t>(sc.target), 0xFC00u);
    }
    {  // A1R5G5B5 (0, 0, 1, 0.6): A round(0.6) = 1, B 31 -> 0x8000 | 0x1F = 0x801F.
        Scene sc(Format::A1R5G5B5);
        sc.colour(0, {0, 0, 1, 0.6f});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint16_t>(sc.target), 0x801Fu);
    }
    {  // A2R10G10B10 (1, 0.5, 0, 1/3): R 1023, G round(511.5) = 512, B 0, A round(1.0000000298) = 1
       // -> 1<<30 | 1023<<20 | 512<<10 = 0x7FF80000.
        Scene sc(Format::A2R10G10B10);
        sc.colour(0, {1, 0.5f, 0, 1.0f / 3});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0x7FF80000u);
    }
    {  // G16R16 (0.5, 1, x, x): R round(32767.5) = 0x8000 (low half), G 0xFFFF.
        Scene sc(Format::G16R16);
        sc.colour(0, {0.5f, 1, 0.3f, 0.3f});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xFFFF8000u);
    }
    {  // R16F 0.1 -> the nearest half 0x2E66 (0.0999755859375); float targets are not clamped.
        Scene sc(Format::R16F);
        sc.colour(0, {0.1f, 0, 0, 0});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint16_t>(sc.target), 0x2E66u);
        sc.colour(0, {-3.5f, 0, 0, 0});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint16_t>(sc.target), 0xC300u);  // -3.5 = -1.75 * 2^1
    }
    {  // R32F keeps the float: 2.5 even with blending ONE/ONE on 0.25 -> 2.75.
        Scene sc(Format::R32F);
        sc.store<float>(0.25f);
        RenderState rs;
        rs.alpha_blend_enable = true;
        rs.dest_blend = Blend::One;
        sc.colour(0, {2.5f, 0, 0, 0});
        (void)sc.run(rs);
        EXPECT_EQ(sc.stored<float>(sc.target), 2.75f);
    }
}

TEST(OutputMerger, RemainingTargetFormats) {
    {  // X8R8G8B8 (0.5, 0.2, 1.2, 0.3): colour bytes as A8R8G8B8 (R 0x80, G 0x33, B 0xFF).
        Scene sc(Format::X8R8G8B8);
        sc.colour(0, {0.5f, 0.2f, 1.2f, 0.3f});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint32_t>(sc.target) & 0x00FFFFFFu, 0x008033FFu);
    }
    {  // A2B10G10R10 (1, 0.5, 0, 1/3): R 1023 (bits 0-9), G 512 (10-19), B 0, A 1 (30-31)
       // -> 0x3FF | 512<<10 | 1<<30 = 0x400803FF.
        Scene sc(Format::A2B10G10R10);
        sc.colour(0, {1, 0.5f, 0, 1.0f / 3});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0x400803FFu);
    }
    {  // A16B16G16R16 (0.5, 0, 1, 0.25): R round(32767.5) = 0x8000, G 0, B 0xFFFF,
       // A round(16383.75) = 0x4000 -> 0x4000'FFFF'0000'8000.
        Scene sc(Format::A16B16G16R16);
        sc.colour(0, {0.5f, 0, 1, 0.25f});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint64_t>(sc.target), 0x4000FFFF00008000ull);
    }
    {  // G16R16F (0.5, -2): R half 0x3800 (low), G half 0xC000.
        Scene sc(Format::G16R16F);
        sc.colour(0, {0.5f, -2, 0, 0});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xC0003800u);
    }
    {  // A16B16G16R16F (1, 0.5, -0.25, 65504): halves 0x3C00, 0x3800, 0xB400, 0x7BFF.
        Scene sc(Format::A16B16G16R16F);
        sc.colour(0, {1, 0.5f, -0.25f, 65504});
        (void)sc.run(RenderState{});
        EXPECT_EQ(sc.stored<uint64_t>(sc.target), 0x7BFFB40038003C00ull);
    }
    {  // G32R32F and A32B32G32R32F store the floats unchanged (no clamping).
        Scene sc(Format::G32R32F);
        sc.colour(0, {0.1f, 1e30f, 5, 5});
        (void)sc.run(RenderState{});
        std::array<float, 2> g{};
        std::memcpy(g.data(), sc.target.bytes().data() + 2 * sc.target.row_pitch() + 8, 8);
        EXPECT_EQ(g, (std::array<float, 2>{0.1f, 1e30f}));
        Scene sa(Format::A32B32G32R32F);
        sa.colour(0, {-1, 2, 3e-3f, 1e20f});
        (void)sa.run(RenderState{});
        std::array<float, 4> a{};
        std::memcpy(a.data(), sa.target.bytes().data() + 2 * sa.target.row_pitch() + 16, 16);
        EXPECT_EQ(a, (std::array<float, 4>{-1, 2, 3e-3f, 1e20f}));
    }
}

TEST(OutputMerger, BlendingThroughTheTarget) {
    // Stored opaque black; src (1, 1, 1, 0.5) with SRCALPHA / INVSRCALPHA:
    // rgb = 1*0.5 + 0*0.5 = 0.5 -> round(127.5) = 0x80; a = 0.5*0.5 + 1*0.5 = 0.75 -> 191.25 -> 0xBF.
    Scene sc(Format::A8R8G8B8);
    sc.store<uint32_t>(0xFF000000u);
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.src_blend = Blend::SrcAlpha;
    rs.dest_blend = Blend::InvSrcAlpha;
    sc.colour(0, {1, 1, 1, 0.5f});
    (void)sc.run(rs);
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xBF808080u);
    // X8R8G8B8 reads alpha 1: SRCBLEND ZERO, DESTBLEND DESTALPHA gives D * 1 = D, so the
    // colour bytes 0x336699 stay (the X byte is the format's business).
    Scene sx(Format::X8R8G8B8);
    sx.store<uint32_t>(0x00336699u);
    rs.src_blend = Blend::Zero;
    rs.dest_blend = Blend::DestAlpha;
    sx.colour(0, {1, 1, 1, 1});
    (void)sx.run(rs);
    EXPECT_EQ(sx.stored<uint32_t>(sx.target) & 0x00FFFFFFu, 0x00336699u);
}

TEST(OutputMerger, ColourWriteMask) {
    // Stored 0x11223344, src white, COLORWRITEENABLE RED|ALPHA: A, R -> 0xFF; G, B kept.
    Scene sc(Format::A8R8G8B8);
    sc.store<uint32_t>(0x11223344u);
    RenderState rs;
    rs.color_write_enable[0] = kWriteRed | kWriteAlpha;
    sc.colour(0, {1, 1, 1, 1});
    (void)sc.run(rs);
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xFFFF3344u);
    rs.color_write_enable[0] = 0;  // nothing
    sc.colour(0, {0, 0, 0, 0});
    (void)sc.run(rs);
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xFFFF3344u);
}

TEST(OutputMerger, MultipleRenderTargets) {
    Scene sc(Format::A8R8G8B8);
    Surface rt1(Format::R32F, 4, 4), rt2(Format::A8R8G8B8, 4, 4), rt3(Format::A8R8G8B8, 4, 4);
    sc.targets.color[1] = &rt1;
    sc.targets.color[2] = &rt2;
    sc.targets.color[3] = &rt3;
    RenderState rs;
    rs.color_write_enable[3] = kWriteBlue;  // per target
    sc.colour(0, {1, 0, 0, 1});
    sc.colour(1, {2.5f, 0, 0, 0});
    sc.colour(2, {0, 1, 0, 1});
    sc.colour(3, {1, 1, 1, 1});
    (void)sc.run(rs, 0xB);  // oC0, oC1, oC3 written; oC2 not
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xFFFF0000u);
    EXPECT_EQ(sc.stored<float>(rt1), 2.5f);
    EXPECT_EQ(sc.stored<uint32_t>(rt2), 0u);     // no oC2: untouched
    EXPECT_EQ(sc.stored<uint32_t>(rt3), 0xFFu);  // blue only
}

TEST(OutputMerger, AlphaTestFogSrgbAndKill) {
    {  // ALPHAREF 0x80 GREATEREQUAL: 0.5 fails (nothing written), 0.51 passes.
        Scene sc(Format::A8R8G8B8);
        RenderState rs;
        rs.alpha_test_enable = true;
        rs.alpha_ref = 0x80;
        rs.alpha_func = CompareFunc::GreaterEqual;
        sc.colour(0, {1, 1, 1, 0.5f});
        EXPECT_EQ(sc.run(rs), 0u);
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0u);
        sc.colour(0, {1, 1, 1, 0.51f});
        EXPECT_EQ(sc.run(rs), 1u);
    }
    {  // Fog: f = oFog 0.25, colour red: rgb = 0.25*(0, 0, 1) + 0.75*(1, 0, 0) = (0.75, 0, 0.25)
       // -> R round(191.25) = 0xBF, B round(63.75) = 0x40; alpha untouched 0xFF.
        Scene sc(Format::A8R8G8B8);
        RenderState rs;
        rs.fog_enable = true;
        rs.fog_color = 0x00FF0000u;
        sc.lanes.fog[0] = 0.25f;
        sc.colour(0, {0, 0, 1, 1});
        (void)sc.run(rs);
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0xFFBF0040u);
    }
    {  // sRGB write: 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357 -> round(187.516) = 0xBC;
       // alpha stays linear: 0.5 -> 0x80.
        Scene sc(Format::A8R8G8B8);
        RenderState rs;
        rs.srgb_write_enable = true;
        sc.colour(0, {0.5f, 0, 1, 0.5f});
        (void)sc.run(rs);
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0x80BC00FFu);
    }
    {  // A surface that cannot be a render target (DXT1) is skipped, not written.
        Surface dxt(Format::DXT1, 4, 4);
        Scene sc(Format::A8R8G8B8);
        sc.targets.color[0] = &dxt;
        sc.colour(0, {1, 1, 1, 1});
        (void)sc.run(RenderState{});
        for (std::byte b : dxt.bytes()) EXPECT_EQ(b, std::byte{0});
    }
    {  // A lane killed by texkill writes nothing.
        Scene sc(Format::A8R8G8B8);
        sc.colour(0, {1, 1, 1, 1});
        sc.batch.killed = 1;
        EXPECT_EQ(sc.run(RenderState{}), 0u);
        EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0u);
    }
}

TEST(OutputMerger, DepthOrderAndShaderDepth) {
    Scene sc(Format::A8R8G8B8);
    auto ds = DepthStencilSurface::create(Format::D16, 4, 4);
    ASSERT_TRUE(ds.surface);
    sc.targets.depth_stencil = &*ds.surface;
    ds.surface->set_depth(1, 2, 0.5f);
    RenderState rs = RenderState::defaults(true);  // ZENABLE TRUE, LESSEQUAL, write on
    sc.colour(0, {1, 1, 1, 1});
    sc.lanes.depth[0] = 0.75f;  // 0.75 <= 0.5 fails: no colour
    EXPECT_EQ(sc.run(rs), 0u);
    EXPECT_EQ(sc.stored<uint32_t>(sc.target), 0u);
    // oDepth 0.25 replaces the interpolated depth: passes and stores round(0.25*65535) = 16384.
    sc.batch.set(sc.batch.depth(), 0, 0.25f, 0, 0, 0);
    MergeInput in;
    in.batch = &sc.batch;
    in.lanes = &sc.lanes;
    in.live = 1;
    in.shader_depth = true;
    EXPECT_EQ(merge(output_merger_state(rs), sc.targets, in), 1u);
    EXPECT_EQ(ds.surface->stored_depth(1, 2), 16384u);
    // Alpha test failures never reach the stencil stage: no stencil update.
    auto dss = DepthStencilSurface::create(Format::D24S8, 4, 4);
    sc.targets.depth_stencil = &*dss.surface;
    rs.stencil_enable = true;
    rs.stencil.pass = rs.stencil.fail = rs.stencil.zfail = StencilOp::Incr;
    rs.alpha_test_enable = true;
    rs.alpha_func = CompareFunc::Never;
    (void)sc.run(rs);
    EXPECT_EQ(dss.surface->stencil(1, 2), 0u);
    rs.alpha_test_enable = false;
    (void)sc.run(rs);
    EXPECT_EQ(dss.surface->stencil(1, 2), 1u);
    // An early depth/stencil test already ran: merge does not run it again.
    in.shader_depth = false;
    in.depth_stencil_done = true;
    (void)merge(output_merger_state(rs), sc.targets, in);
    EXPECT_EQ(dss.surface->stencil(1, 2), 1u);
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

TEST(RenderStateTable, DefaultsFollowTheSpec) {
    const RenderState rs;
    // pipeline.md §16, one line per state with a non-zero or enum default.
    EXPECT_EQ(get_render_state(rs, 7), 0u);            // ZENABLE: no auto depth-stencil
    EXPECT_EQ(get_render_state(RenderState::defaults(true), 7), 1u);
    EXPECT_EQ(get_render_state(rs, 8), 3u);            // FILLMODE SOLID
    EXPECT_EQ(get_render_state(rs, 9), 2u);            // SHADEMODE GOURAUD
    EXPECT_EQ(get_render_state(rs, 14), 1u);           // ZWRITEENABLE
    EXPECT_EQ(get_render_state(rs, 16), 1u);           // LASTPIXEL
    EXPECT_EQ(get_render_state(rs, 19), 2u);           // SRCBLEND ONE
    EXPECT_EQ(get_render_state(rs, 20), 1u);           // DESTBLEND ZERO
    EXPECT_EQ(get_render_state(rs, 22), 3u);           // CULLMODE CCW
    EXPECT_EQ(get_render_state(rs, 23), 4u);           // ZFUNC LESSEQUAL
    EXPECT_EQ(get_render_state(rs, 25), 8u);           // ALPHAFUNC ALWAYS
    EXPECT_EQ(get_render_state(rs, 37), 0x3F800000u);  // FOGEND 1.0f
    EXPECT_EQ(get_render_state(rs, 38), 0x3F800000u);  // FOGDENSITY 1.0f
    EXPECT_EQ(get_render_state(rs, 53), 1u);           // STENCILFAIL KEEP
    EXPECT_EQ(get_render_state(rs, 56), 8u);           // STENCILFUNC ALWAYS
    EXPECT_EQ(get_render_state(rs, 58), 0xFFFFFFFFu);  // STENCILMASK
    EXPECT_EQ(get_render_state(rs, 59), 0xFFFFFFFFu);  // STENCILWRITEMASK
    EXPECT_EQ(get_render_state(rs, 136), 1u);          // CLIPPING
    EXPECT_EQ(get_render_state(rs, 154), 0x3F800000u); // POINTSIZE 1.0f (Wine)
    EXPECT_EQ(get_render_state(rs, 155), 0x3F800000u); // POINTSIZE_MIN 1.0f
    EXPECT_EQ(get_render_state(rs, 166), 0x42800000u); // POINTSIZE_MAX 64.0f
    EXPECT_EQ(get_render_state(rs, 158), 0x3F800000u); // POINTSCALE_A 1.0f
    EXPECT_EQ(get_render_state(rs, 168), 0xFu);        // COLORWRITEENABLE
    EXPECT_EQ(get_render_state(rs, 192), 0xFu);        // COLORWRITEENABLE3
    EXPECT_EQ(get_render_state(rs, 171), 1u);          // BLENDOP ADD
    EXPECT_EQ(get_render_state(rs, 189), 8u);          // CCW_STENCILFUNC ALWAYS
    EXPECT_EQ(get_render_state(rs, 193), 0xFFFFFFFFu); // BLENDFACTOR
    EXPECT_EQ(get_render_state(rs, 207), 2u);          // SRCBLENDALPHA ONE
    EXPECT_EQ(get_render_state(rs, 208), 1u);          // DESTBLENDALPHA ZERO
    EXPECT_EQ(get_render_state(rs, 209), 1u);          // BLENDOPALPHA ADD
    EXPECT_EQ(get_render_state(rs, 162), 0xFFFFFFFFu); // MULTISAMPLEMASK
    EXPECT_EQ(get_render_state(rs, 60), 0xFFFFFFFFu);  // TEXTUREFACTOR
}

TEST(RenderStateTable, SetGetAndBadValues) {
    RenderState rs;
    EXPECT_TRUE(set_render_state(rs, 22, 1).ok);  // CULLMODE NONE
    EXPECT_EQ(rs.cull_mode, CullMode::None);
    EXPECT_TRUE(set_render_state(rs, 195, 0x3E800000u).ok);  // DEPTHBIAS 0.25f
    EXPECT_EQ(rs.depth_bias, 0.25f);
    EXPECT_EQ(get_render_state(rs, 195), 0x3E800000u);
    EXPECT_TRUE(set_render_state(rs, 191, 5).ok);  // COLORWRITEENABLE2
    EXPECT_EQ(rs.color_write_enable[2], 5u);
    EXPECT_TRUE(set_render_state(rs, 203, 3).ok);  // WRAP13
    EXPECT_EQ(rs.wrap[13], 3u);
    EXPECT_EQ(get_render_state(rs, 203), 3u);
    EXPECT_TRUE(set_render_state(rs, 189, 3).ok);  // CCW_STENCILFUNC EQUAL
    EXPECT_EQ(rs.ccw_stencil.func, CompareFunc::Equal);
    // Bad values leave the state unchanged.
    const RenderState before = rs;
    const auto bad = set_render_state(rs, 22, 7);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.error.find("CULLMODE"), std::string::npos);
    EXPECT_FALSE(set_render_state(rs, 19, 16).ok);  // SRCCOLOR2: D3D9Ex only
    EXPECT_FALSE(set_render_state(rs, 19, 0).ok);
    EXPECT_FALSE(set_render_state(rs, 171, 6).ok);
    EXPECT_FALSE(set_render_state(rs, 56, 9).ok);
    EXPECT_FALSE(set_render_state(rs, 53, 0).ok);
    EXPECT_FALSE(set_render_state(rs, 35, 4).ok);
    EXPECT_FALSE(set_render_state(rs, 7, 3).ok);
    EXPECT_FALSE(set_render_state(rs, 8, 0).ok);
    EXPECT_FALSE(set_render_state(rs, 1000, 0).ok);  // not a state
    EXPECT_FALSE(set_render_state(rs, 10, 0).ok);    // a gap in the enum
    EXPECT_EQ(rs, before);
    // Fixed-function states are accepted and ignored.
    const auto ff = set_render_state(rs, 137, 0);  // LIGHTING
    EXPECT_TRUE(ff.ok);
    EXPECT_TRUE(ff.ignored);
    EXPECT_EQ(rs, before);
    EXPECT_FALSE(get_render_state(rs, 137));
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

// Every stage in a row, the way the draw loop will chain them, with the shaders replaced by
// copies (vs: oPos = v0, oD0 = v1; ps: oC0 = v0). The docs' two triangles, flat shaded from
// their provoking vertices: red (0,0),(5,0),(5,5) and green (0,5),(0,0),(5,5), sharing the
// diagonal: 15 red and 10 green pixels, the other 39 of the 8x8 target keep the clear colour.
TEST(PipelineScene, TwoFlatTrianglesThroughEveryStage) {
    struct Vertex { float x, y, z, w; uint32_t colour; };
    auto v = [](float X, float Y, uint32_t c) { return Vertex{X / 4 - 1, 1 - Y / 4, 0.5f, 1, c}; };
    const Vertex vb[] = {v(0, 0, 0xFFFF0000u), v(5, 0, 0xFF0000FFu), v(5, 5, 0xFF0000FFu), v(0, 5, 0xFF00FF00u)};
    const uint16_t ib[] = {0, 1, 2, 3, 0, 2};
    const VertexElement decl[] = {{0, 0, 3, 0, 0, 0}, {0, 16, 4, 0, 10, 0}};
    const ShaderInput inputs[] = {{0, isa::DeclUsage::Position, 0}, {1, isa::DeclUsage::Color, 0}};

    RenderState rs = RenderState::defaults(true);
    rs.shade_mode = ShadeMode::Flat;
    rs.z_func = CompareFunc::Less;
    const Viewport viewport{0, 0, 8, 8, 0.0f, 1.0f};
    Surface target(Format::A8R8G8B8, 8, 8);
    auto ds = DepthStencilSurface::create(Format::D24S8, 8, 8);
    ASSERT_TRUE(ds.surface);
    ds.surface->clear(PixelRect{0, 0, 8, 8}, true, 1.0f, true, 0);
    RenderTargets targets;
    targets.color[0] = &target;
    targets.depth_stencil = &*ds.surface;

    // Per draw: plain state structs.
    const auto plan = plan_fetch(decl, inputs);
    ASSERT_TRUE(plan.plan);
    ClipState clip;
    clip.guard = guard_band(viewport);
    const SetupState setup = make_setup_state(rs, viewport, 8, 8, PixelRect{});
    const OutputMergerState om = output_merger_state(rs);

    auto draw = [&]() {
        const auto indices = read_indices(std::as_bytes(std::span(ib)), IndexFormat::Index16, 0, 6, 0);
        ASSERT_TRUE(indices.ok());
        const auto unique = deduplicate(indices.vertices);
        ASSERT_EQ(unique.vertices.size(), 4u);  // the post-transform cache: 4 shaded, not 6
        emu::Batch vs;
        const VertexStream stream{std::as_bytes(std::span(vb)), 0, sizeof(Vertex)};
        ASSERT_EQ(fetch(*plan.plan, std::span(&stream, 1), unique.vertices, vs), "");
        vs.position() = vs.input(0);   // the "vertex shader"
        vs.color_out(0) = vs.input(1);
        std::vector<ClipVertex> shaded;
        for (unsigned l = 0; l < unique.vertices.size(); ++l) shaded.push_back(vertex_from_batch(vs, l, false));
        const auto prims = assemble(PrimitiveType::TriangleList, 2, 6);
        ASSERT_TRUE(prims.ok());
        for (const Primitive& p : prims.primitives) {
            const ClipVertex& a = shaded[unique.slots[p.v[0]]];
            const ClipVertex& b = shaded[unique.slots[p.v[1]]];
            const ClipVertex& c = shaded[unique.slots[p.v[2]]];
            ClippedPolygon poly;
            ASSERT_EQ(clip_triangle(a, b, c, clip, poly), ClipResult::Inside);
            PrimitiveSetup prim;
            ASSERT_TRUE(setup_triangle(a, b, c, shaded[unique.slots[p.provoking]], setup, prim));
            std::vector<Quad> quads;
            rasterize(prim, tile_rect(0, 0), quads);
            for (size_t q = 0; q < quads.size(); q += emu::kBatchQuads) {
                const size_t n = std::min<size_t>(emu::kBatchQuads, quads.size() - q);
                emu::Batch ps;
                PixelLanes lanes;
                interpolate(prim, std::span(quads).subspan(q, n), kAllVaryings, ps, lanes);
                ps.render_target(0) = ps.input(0);  // the "pixel shader"
                MergeInput in;
                in.batch = &ps;
                in.lanes = &lanes;
                in.live = lanes.coverage;
                (void)merge(om, targets, in);
            }
        }
    };
    draw();
    int red = 0, green = 0, clear = 0;
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            uint32_t argb;
            std::memcpy(&argb, target.bytes().data() + y * target.row_pitch() + 4 * x, 4);
            if (argb == 0xFFFF0000u) ++red;
            else if (argb == 0xFF00FF00u) ++green;
            else if (argb == 0u) ++clear;
        }
    EXPECT_EQ(red, 15);
    EXPECT_EQ(green, 10);
    EXPECT_EQ(clear, 39);
    // Depth 0.5 stored for the 25 covered pixels (round(0.5 * (2^24 - 1)) = 8388608).
    EXPECT_EQ(ds.surface->stored_depth(4, 4), 8388608u);
    EXPECT_EQ(ds.surface->stored_depth(5, 5), quantize_depth(ds.surface->info(), 1.0f));
    // Drawing again with LESS: 0.5 < 0.5 fails everywhere; the image does not change.
    const auto before = target.bytes();
    draw();
    EXPECT_EQ(target.bytes(), before);
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

emu::Executable build(const char* text) {
    auto a = assembler::assemble(text);
    EXPECT_TRUE(a.ok());
    auto created = emu::Shader::create(*a.program);
    EXPECT_TRUE(created.shader) << created.error;
    auto lowered = emu::lower(*created.shader, {});
    EXPECT_TRUE(lowered.executable) << lowered.error;
    return std::move(*lowered.executable);
}

// The same chain with real vs_2_0 / ps_2_0 shaders run by the engine: one triangle with
// w = 1, 3, 1 at screen (0,0), (8,0), (0,8) of a 16x16 R32F target, texcoord u = 0, 1, 0,
// pixel shader oC0 = t0. At pixel (4, 0) the screen barycentric of v1 is 0.5, so
//   u = (0.5 * 1/3) / (0.5 * 1 + 0.5 * 1/3) = 0.25;
// at (0, 4) (b2 = 0.5, rhw2 = 1): u = 0; at (2, 2) b1 = b2 = 0.25, rhw = (1, 1/3, 1):
//   u = (0.25 / 3) / (0.5 * 1 + 0.25 / 3 + 0.25 * 1) = (1/12) / (10/12) = 0.1.
TEST(PipelineScene, RealShadersPerspectiveTexcoord) {
    const auto vs = build("vs_2_0\ndcl_position v0\ndcl_texcoord v1\nmov oPos, v0\nmov oT0, v1\n");
    const auto ps = build("ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, r0\n");
    struct Vertex { float x, y, z, w, u; };
    auto v = [](float X, float Y, float w, float u) { return Vertex{(X / 8 - 1) * w, (1 - Y / 8) * w, 0.5f * w, w, u}; };
    const Vertex vb[] = {v(0, 0, 1, 0), v(8, 0, 3, 1), v(0, 8, 1, 0)};
    const VertexElement decl[] = {{0, 0, 3, 0, 0, 0}, {0, 16, 0, 0, 5, 0}};  // FLOAT4, FLOAT1
    const auto plan = plan_fetch(decl, std::vector<ShaderInput>{{0, isa::DeclUsage::Position, 0},
                                                                {1, isa::DeclUsage::TexCoord, 0}});
    ASSERT_TRUE(plan.plan);
    emu::Batch vsb;
    const VertexStream stream{std::as_bytes(std::span(vb)), 0, sizeof(Vertex)};
    const auto ids = sequential_vertices(0, 3);
    ASSERT_EQ(fetch(*plan.plan, std::span(&stream, 1), ids.vertices, vsb), "");
    emu::execute(vs, vs.bind_constants(), vsb);
    const Viewport viewport{0, 0, 16, 16, 0.0f, 1.0f};
    RenderState rs;
    rs.cull_mode = CullMode::None;
    SetupState setup = make_setup_state(rs, viewport, 16, 16, PixelRect{});
    PrimitiveSetup prim;
    const ClipVertex a = vertex_from_batch(vsb, 0, false), b = vertex_from_batch(vsb, 1, false),
                     c = vertex_from_batch(vsb, 2, false);
    ASSERT_TRUE(setup_triangle(a, b, c, a, setup, prim));
    Surface target(Format::R32F, 16, 16);
    RenderTargets targets;
    targets.color[0] = &target;
    std::vector<Quad> quads;
    rasterize(prim, tile_rect(0, 0), quads);
    for (size_t q = 0; q < quads.size(); q += emu::kBatchQuads) {
        emu::Batch psb;
        PixelLanes lanes;
        interpolate(prim, std::span(quads).subspan(q, std::min<size_t>(emu::kBatchQuads, quads.size() - q)),
                    kAllVaryings, psb, lanes);
        emu::execute(ps, ps.bind_constants(), psb);
        MergeInput in;
        in.batch = &psb;
        in.lanes = &lanes;
        in.live = lanes.coverage;
        (void)merge(output_merger_state(rs), targets, in);
    }
    auto at = [&](uint32_t x, uint32_t y) {
        float f;
        std::memcpy(&f, target.bytes().data() + y * target.row_pitch() + 4 * x, 4);
        return f;
    };
    EXPECT_FLOAT_EQ(at(4, 0), 0.25f);
    EXPECT_EQ(at(0, 4), 0.0f);
    EXPECT_FLOAT_EQ(at(2, 2), 0.1f);
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

// Clipping at the near plane, end to end: a full-viewport quad on an 8x8 target whose depth
// runs z = x/2 + 1/4 (w = 1), so z < 0 left of x = -0.5, i.e. screen X < 2. The near plane cuts
// both triangles at X = 2 exactly (t = 0.75 on the cut edges: x = 0.25*1 + 0.75*(-1) = -0.5);
// that edge goes up the screen, a left edge, so column 2 is drawn: columns 2..7 of all 8 rows
// = 48 pixels, each once; columns 0 and 1 keep the clear colour. Depth Zs = X/8 - 1/4 in
// screen space: column 2 -> 0, column 4 -> 0.25 (D16: round(16383.75) = 16384), column 6 ->
// 0.5 (32768).
TEST(PipelineScene, NearPlaneClipping) {
    auto corner = [](float x, float y) {
        ClipVertex v;
        v.position = {x, y, 0.5f * x + 0.25f, 1.0f};
        v.varyings[kVaryingColor0] = {1, 1, 1, 1};
        return v;
    };
    const ClipVertex quad[4] = {corner(-1, 1), corner(1, 1), corner(1, -1), corner(-1, -1)};
    const Viewport viewport{0, 0, 8, 8, 0.0f, 1.0f};
    RenderState rs = RenderState::defaults(true);
    rs.z_func = CompareFunc::Always;
    const SetupState setup = make_setup_state(rs, viewport, 8, 8, PixelRect{});
    ClipState clip;
    clip.guard = guard_band(viewport);
    Surface target(Format::A8R8G8B8, 8, 8);
    auto ds = DepthStencilSurface::create(Format::D16, 8, 8);
    ds.surface->clear(PixelRect{0, 0, 8, 8}, true, 1.0f, false, 0);
    RenderTargets targets;
    targets.color[0] = &target;
    targets.depth_stencil = &*ds.surface;
    int written = 0;
    const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& t : tris) {
        ClippedPolygon poly;
        ASSERT_EQ(clip_triangle(quad[t[0]], quad[t[1]], quad[t[2]], clip, poly), ClipResult::Clipped);
        for (unsigned i = 1; i + 1 < poly.count; ++i) {
            PrimitiveSetup prim;
            if (!setup_triangle(poly.vertices[0], poly.vertices[i], poly.vertices[i + 1], quad[t[0]], setup, prim))
                continue;
            std::vector<Quad> quads;
            rasterize(prim, tile_rect(0, 0), quads);
            for (size_t q = 0; q < quads.size(); q += emu::kBatchQuads) {
                emu::Batch ps;
                PixelLanes lanes;
                interpolate(prim, std::span(quads).subspan(q, std::min<size_t>(emu::kBatchQuads, quads.size() - q)),
                            kAllVaryings, ps, lanes);
                ps.render_target(0) = ps.input(0);
                MergeInput in;
                in.batch = &ps;
                in.lanes = &lanes;
                in.live = lanes.coverage;
                written += std::popcount(merge(output_merger_state(rs), targets, in));
            }
        }
    }
    EXPECT_EQ(written, 48);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            uint32_t argb;
            std::memcpy(&argb, target.bytes().data() + y * target.row_pitch() + 4 * x, 4);
            EXPECT_EQ(argb, x >= 2 ? 0xFFFFFFFFu : 0u) << x << "," << y;
        }
    EXPECT_EQ(ds.surface->stored_depth(2, 5), 0u);
    EXPECT_EQ(ds.surface->stored_depth(4, 1), 16384u);
    EXPECT_EQ(ds.surface->stored_depth(6, 7), 32768u);
    EXPECT_EQ(ds.surface->stored_depth(1, 1), 65535u);  // not drawn
}

}  // namespace
}  // namespace sm2::runtime
