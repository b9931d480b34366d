// The output merger's fast paths (8-bit and wider UNORM targets without sRGB write, blended a
// batch at a time on the stored bytes; 32-bit float targets without blending, copied into
// place; half and blended float targets, a batch at a time) against the per-pixel path
// through Surface::read/write (MergeInput::generic_path): random states and batches must leave
// the same bytes in every target and in the depth/stencil surface. Plus worked examples.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "sm2/runtime/output_merger.h"

namespace sm2::runtime {
namespace {

constexpr unsigned kLanes = emu::kBatchLanes;

// One merge() call's inputs: up to four colour targets, an optional D24S8 surface, the state.
struct Case {
    std::array<std::optional<Surface>, kMaxRenderTargets> color;
    std::optional<DepthStencilSurface> depth;
    OutputMergerState state;
    emu::Batch batch;
    PixelLanes lanes;
    MergeInput input;

    // Runs merge() on copies of the surfaces; returns the live mask and leaves the copies in `out`.
    emu::LaneMask run(bool generic, Case& out) const {
        out.color = color;
        out.depth = depth;
        RenderTargets targets;
        for (unsigned t = 0; t < kMaxRenderTargets; ++t) targets.color[t] = out.color[t] ? &*out.color[t] : nullptr;
        targets.depth_stencil = out.depth ? &*out.depth : nullptr;
        MergeInput in = input;
        in.batch = &batch;
        in.lanes = &lanes;
        in.generic_path = generic;
        return merge(state, targets, in);
    }
};

// Runs `c` both ways and checks every stored byte; returns false (with a message) on a mismatch.
::testing::AssertionResult same_both_ways(const Case& c) {
    Case fast, generic;
    const emu::LaneMask a = c.run(false, fast), b = c.run(true, generic);
    if (a != b) return ::testing::AssertionFailure() << "live mask " << a << " vs " << b;
    for (unsigned t = 0; t < kMaxRenderTargets; ++t) {
        if (!c.color[t]) continue;
        const auto& fb = fast.color[t]->bytes();
        const auto& gb = generic.color[t]->bytes();
        for (size_t i = 0; i < fb.size(); ++i)
            if (fb[i] != gb[i])
                return ::testing::AssertionFailure()
                       << "target " << t << " (format " << static_cast<uint32_t>(c.color[t]->format()) << ") byte "
                       << i << ": fast " << static_cast<unsigned>(fb[i]) << ", generic "
                       << static_cast<unsigned>(gb[i]);
    }
    if (c.depth)
        for (uint32_t y = 0; y < c.depth->height(); ++y)
            for (uint32_t x = 0; x < c.depth->width(); ++x)
                if (fast.depth->stored_depth(x, y) != generic.depth->stored_depth(x, y) ||
                    fast.depth->stencil(x, y) != generic.depth->stencil(x, y))
                    return ::testing::AssertionFailure() << "depth/stencil at " << x << "," << y;
    return ::testing::AssertionSuccess();
}

class Random {
public:
    explicit Random(uint32_t seed) : rng_(seed) {}
    uint32_t below(uint32_t n) { return std::uniform_int_distribution<uint32_t>(0, n - 1)(rng_); }
    bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
    uint32_t bits() { return static_cast<uint32_t>(rng_()); }

    // A colour channel: ordinary values, values beside the 8-bit rounding boundaries, and
    // specials (NaN of either sign, infinities, zeros, huge, denormal, any bit pattern).
    float colour() {
        switch (below(8)) {
        case 0: case 1: return uniform(0.0f, 1.0f);
        case 2: return uniform(-2.0f, 3.0f);
        case 3: return static_cast<float>(below(256)) / 255.0f;
        case 4: {  // (k + 0.5) / 255 give or take a few ulps
            float v = (static_cast<float>(below(256)) + 0.5f) / 255.0f;
            for (int steps = static_cast<int>(below(9)) - 4; steps != 0; steps += steps > 0 ? -1 : 1)
                v = std::nextafter(v, steps > 0 ? 2.0f : -2.0f);
            return v;
        }
        case 5: {
            static const float kSpecial[] = {
                std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
                std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                0.0f, -0.0f, 1.0f, -1.0f, 1e30f, -1e30f, 1e-40f, std::numeric_limits<float>::max(),
                std::nextafter(1.0f, 2.0f), std::nextafter(1.0f, 0.0f), std::nextafter(0.0f, 1.0f), 0.5f};
            return kSpecial[below(std::size(kSpecial))];
        }
        case 6: return std::bit_cast<float>(bits());
        default: return uniform(0.9f, 1.1f);
        }
    }
    template <typename E>
    E pick(uint32_t first, uint32_t last) { return static_cast<E>(first + below(last - first + 1)); }

private:
    std::mt19937 rng_;
};

// Render-target colour formats, with the fast paths' 8-bit, 32-bit float and half ones weighted up.
std::vector<Format> target_formats() {
    std::vector<Format> formats;
    for (const FormatInfo& info : format_table())
        if (info.render_target && info.kind == FormatKind::Color) formats.push_back(info.format);
    for (int i = 0; i < 3; ++i)
        formats.insert(formats.end(), {Format::A8R8G8B8, Format::A8R8G8B8, Format::X8R8G8B8, Format::A8B8G8R8,
                                       Format::X8B8G8R8, Format::R32F, Format::G32R32F, Format::A32B32G32R32F,
                                       Format::R16F, Format::G16R16F, Format::A16B16G16R16F});
    return formats;
}

Surface random_surface(Random& r, Format f, uint32_t w, uint32_t h) {
    Surface s(f, w, h);
    for (std::byte& b : s.bytes()) b = static_cast<std::byte>(r.below(256));
    if (is_float_target(f) && r.chance(0.7))  // random bits are mostly NaN or huge
        s.fill({r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1)});
    return s;
}

RenderState random_state(Random& r) {
    RenderState rs;
    rs.alpha_blend_enable = r.chance(0.7);
    rs.src_blend = r.pick<Blend>(1, 15);
    rs.dest_blend = r.pick<Blend>(1, 15);
    rs.blend_op = r.pick<BlendOp>(1, 5);
    rs.separate_alpha_blend_enable = r.chance(0.4);
    rs.src_blend_alpha = r.pick<Blend>(1, 15);
    rs.dest_blend_alpha = r.pick<Blend>(1, 15);
    rs.blend_op_alpha = r.pick<BlendOp>(1, 5);
    rs.blend_factor = r.chance(0.3) ? 0xFFFFFFFFu : r.bits();
    if (r.chance(0.2)) {  // "source over", which the 8-bit block path blends in registers
        rs.src_blend = Blend::SrcAlpha;
        rs.dest_blend = Blend::InvSrcAlpha;
        rs.blend_op = BlendOp::Add;
        rs.separate_alpha_blend_enable = r.chance(0.2);
        rs.src_blend_alpha = Blend::SrcAlpha;
        rs.dest_blend_alpha = Blend::InvSrcAlpha;
        rs.blend_op_alpha = BlendOp::Add;
    }
    if (r.chance(0.15)) {  // additive (ONE, ONE, ADD), which the block path also blends in registers
        rs.src_blend = rs.dest_blend = Blend::One;
        rs.blend_op = BlendOp::Add;
        rs.separate_alpha_blend_enable = r.chance(0.2);
        rs.src_blend_alpha = rs.dest_blend_alpha = Blend::One;
        rs.blend_op_alpha = BlendOp::Add;
    }
    for (uint32_t& m : rs.color_write_enable) m = r.chance(0.5) ? 0xF : r.below(16);
    rs.fog_enable = r.chance(0.3);
    rs.fog_table_mode = r.pick<FogMode>(0, 3);
    rs.fog_start = r.uniform(-0.5f, 0.5f);
    rs.fog_end = r.chance(0.1) ? rs.fog_start : r.uniform(0.5f, 1.5f);
    rs.fog_density = r.uniform(0.0f, 4.0f);
    rs.fog_color = r.bits();
    rs.alpha_test_enable = r.chance(0.3);
    rs.alpha_func = r.pick<CompareFunc>(1, 8);
    rs.alpha_ref = r.bits();
    rs.srgb_write_enable = r.chance(0.15);
    rs.z_enable = r.chance(0.5) ? ZBufferType::True : ZBufferType::False;
    rs.z_func = r.pick<CompareFunc>(1, 8);
    rs.z_write_enable = r.chance(0.5);
    rs.stencil_enable = r.chance(0.3);
    rs.stencil.func = r.pick<CompareFunc>(1, 8);
    rs.stencil.pass = r.pick<StencilOp>(1, 8);
    rs.stencil.fail = r.pick<StencilOp>(1, 8);
    rs.stencil.zfail = r.pick<StencilOp>(1, 8);
    rs.stencil_ref = r.below(256);
    return rs;
}

Case random_case(Random& r, const std::vector<Format>& formats) {
    Case c;
    const uint32_t w = 4 + r.below(9), h = 4 + r.below(9);
    for (unsigned t = 0; t < kMaxRenderTargets; ++t)
        if (t == 0 || r.chance(0.25))
            c.color[t] = random_surface(r, formats[r.below(static_cast<uint32_t>(formats.size()))], w, h);
    if (r.chance(0.4)) {
        c.depth = std::move(DepthStencilSurface::create(Format::D24S8, w, h).surface);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                c.depth->set_stored_depth(x, y, r.below(1u << 24));
                c.depth->set_stencil(x, y, r.below(256));
            }
    }
    c.state = output_merger_state(random_state(r));

    PixelLanes& l = c.lanes;
    l.quad_count = 1 + r.below(4);
    l.clockwise = r.chance(0.5);
    const bool repeats = r.chance(0.05);        // lanes anywhere, pixels may repeat
    const bool repeated_quads = r.chance(0.05);  // quads may repeat
    // 4 quads side by side in one quad row, as the rasterizer makes them inside a primitive
    // (the block path reads and writes such a batch as two rows), sometimes over an edge.
    const bool side_by_side = !repeats && !repeated_quads && r.chance(0.3);
    if (side_by_side) {
        l.quad_count = 4;
        const int32_t x0 = 2 * static_cast<int32_t>(r.below(w / 2 + 1)) - (r.chance(0.1) ? 2 : 0);
        const int32_t y0 = 2 * static_cast<int32_t>(r.below(h / 2 + 1)) - (r.chance(0.1) ? 2 : 0);
        for (unsigned i = 0; i < kLanes; ++i) {
            l.x[i] = x0 + static_cast<int32_t>(2 * (i / 4) + (i & 1u));
            l.y[i] = y0 + static_cast<int32_t>(i >> 1 & 1u);
        }
    }
    for (unsigned q = 0; q < (side_by_side ? 0 : l.quad_count); ++q) {
        // 2x2 quads at distinct even positions, some hanging over an edge.
        int32_t qx = 0, qy = 0;
        for (bool fresh = false; !fresh;) {
            if (repeated_quads) {
                qx = 2 * static_cast<int32_t>(r.below(2));
                qy = 0;
                break;
            }
            qx = 2 * static_cast<int32_t>(r.below(w / 2 + 2)) - 2;
            qy = 2 * static_cast<int32_t>(r.below(h / 2 + 2)) - 2;
            fresh = true;
            for (unsigned p = 0; p < q; ++p) fresh &= !(l.x[4 * p] == qx && l.y[4 * p] == qy);
        }
        for (unsigned i = 0; i < 4; ++i) {
            l.x[4 * q + i] = repeats ? static_cast<int32_t>(r.below(w + 1)) - 1 : qx + static_cast<int32_t>(i & 1u);
            l.y[4 * q + i] = repeats ? static_cast<int32_t>(r.below(3)) : qy + static_cast<int32_t>(i >> 1);
        }
    }
    for (unsigned i = 0; i < kLanes; ++i) {
        l.depth[i] = r.uniform(-0.2f, 1.2f);
        l.fog[i] = r.chance(0.1) ? r.colour() : r.uniform(-0.2f, 1.2f);
        for (unsigned t = 0; t < kMaxRenderTargets; ++t)
            c.batch.set(c.batch.render_target(t), i, r.colour(), r.colour(), r.colour(), r.colour());
        c.batch.depth()[0][i] = r.uniform(-0.2f, 1.2f);
    }
    c.batch.killed = r.chance(0.2) ? r.below(1u << kLanes) : 0;
    c.input.live = r.chance(0.6) ? emu::kAllLanes : r.below(1u << kLanes);
    c.input.color_outputs = static_cast<uint8_t>(1u | r.below(16));
    c.input.shader_depth = r.chance(0.2);
    c.input.depth_stencil_done = r.chance(0.1);
    // On a CPU with AVX-512, a third of the cases run the kernels' AVX2 instance (a CPU without
    // it runs that instance anyway).
    c.input.block_avx2 = r.chance(0.33);
    return c;
}

// Four quads side by side in quad row 0 from x = 0 (8x2 pixels), every lane a pixel of them.
void side_by_side_quads(PixelLanes& lanes) {
    lanes.quad_count = 4;
    for (unsigned i = 0; i < kLanes; ++i) {
        lanes.x[i] = static_cast<int32_t>(2 * (i / 4) + (i & 1u));
        lanes.y[i] = static_cast<int32_t>(i >> 1 & 1u);
    }
}

TEST(OutputMergerFast, RandomBatchesMatchThePerPixelPath) {
    const std::vector<Format> formats = target_formats();
    Random r(20240611);
    for (int i = 0; i < 20000; ++i) {
        const Case c = random_case(r, formats);
        ASSERT_TRUE(same_both_ways(c)) << "case " << i;
    }
}

// The floats within `ulps` either side of every rounding boundary (k + 0.5) / max of a field.
void add_rounding_boundaries(std::vector<float>& values, int max, int ulps) {
    for (int k = 0; k <= max; ++k) {
        float up = (static_cast<float>(k) + 0.5f) / static_cast<float>(max), down = up;
        for (int s = 0; s < ulps; ++s) {
            values.push_back(up);
            values.push_back(down);
            up = std::nextafter(up, 2.0f);
            down = std::nextafter(down, -2.0f);
        }
    }
}

// Blending off, every channel written: the store's rounding (unorm8::encode_field() in float
// against the per-pixel path's double) for a sweep over [-0.5, 1.5] in steps of 2^-18 and for
// the floats either side of every rounding boundary (k + 0.5) / max of 8-, 10- and 16-bit fields.
TEST(OutputMergerFast, EncodeMatchesOverASweep) {
    std::vector<float> sweep;
    for (int i = -(1 << 17); i <= 3 << 17; ++i) sweep.push_back(static_cast<float>(i) / static_cast<float>(1 << 18));
    std::vector<float> bytes = sweep, ten_bits = sweep, sixteen_bits = sweep;
    add_rounding_boundaries(bytes, 255, 64);
    add_rounding_boundaries(ten_bits, 1023, 32);
    add_rounding_boundaries(sixteen_bits, 65535, 3);
    const std::pair<Format, const std::vector<float>*> targets[] = {
        {Format::A8R8G8B8, &bytes},        {Format::X8R8G8B8, &bytes},         {Format::A8B8G8R8, &bytes},
        {Format::A2R10G10B10, &ten_bits},  {Format::A2B10G10R10, &ten_bits},   {Format::G16R16, &sixteen_bits},
        {Format::A16B16G16R16, &sixteen_bits}};
    for (const auto& [f, list] : targets) {
        const std::vector<float>& values = *list;
        Case c;
        c.color[0] = Surface(f, 8, 2);
        side_by_side_quads(c.lanes);
        c.input.live = emu::kAllLanes;
        for (size_t at = 0; at < values.size(); at += 4 * kLanes) {
            for (unsigned i = 0; i < 4 * kLanes; ++i) {
                const float v = values[(at + i) % values.size()];
                c.batch.render_target(0)[i % 4][i / 4] = v;
            }
            ASSERT_TRUE(same_both_ways(c)) << "format " << static_cast<uint32_t>(f) << ", values from " << at;
        }
    }
}

// Half targets convert a batch at a time (floats_to_halves, halves_to_floats): the per-pixel
// path's half.h bits for every half read back (all 65 536 patterns, NaNs and denormals included,
// in the masked channels of A16B16G16R16F texels, which store what they read) and for the floats
// at and beside every rounding boundary of the stores: each midpoint between two neighbouring
// halves (a tie, rounded to the even one), its float neighbours either side, the denormal range
// and the overflow to infinity at 65520.
TEST(OutputMergerFast, HalfTargetsConvertEveryHalfAndEveryRoundingBoundary) {
    Case c;
    c.color[0] = Surface(Format::A16B16G16R16F, 8, 2);
    side_by_side_quads(c.lanes);
    c.input.live = emu::kAllLanes;
    RenderState rs;
    rs.color_write_enable[0] = 0x1;  // red written, green, blue and alpha read and stored back
    c.state = output_merger_state(rs);
    for (uint32_t first = 0; first < 65536; first += 4 * kLanes) {
        auto& bytes = c.color[0]->bytes();
        for (uint32_t i = 0; i < 4 * kLanes; ++i) {
            const auto h = static_cast<uint16_t>(first + i);
            std::memcpy(bytes.data() + 2 * i, &h, 2);
        }
        ASSERT_TRUE(same_both_ways(c)) << "halves from " << first;
    }
    std::vector<float> values;
    for (uint32_t h = 0; h < 0x7C00; ++h) {
        uint16_t a = static_cast<uint16_t>(h), b = static_cast<uint16_t>(h + 1);
        float fa, fb;
        {
            // The two neighbours' values through the per-pixel path's own decoder.
            Surface one(Format::R16F, 2, 1);
            std::memcpy(one.bytes().data(), &a, 2);
            std::memcpy(one.bytes().data() + 2, &b, 2);
            fa = one.read(0, 0, 0)[0];
            fb = one.read(1, 0, 0)[0];
        }
        const float mid = fa + (fb - fa) / 2;  // exact: two neighbouring halves' midpoint has 12 bits
        for (const float v : {mid, std::nextafter(mid, 0.0f), std::nextafter(mid, 1e9f), fa})
            for (const float sign : {1.0f, -1.0f}) values.push_back(sign * v);
    }
    for (const float v : {65519.0f, 65520.0f, 65535.0f, 65536.0f, 1e-8f, 2.9e-8f, 3e-8f, 5.96e-8f, 1e-40f, 0.0f})
        values.push_back(v);
    rs.color_write_enable[0] = 0xF;
    c.state = output_merger_state(rs);
    for (size_t at = 0; at < values.size(); at += 4 * kLanes) {
        for (unsigned i = 0; i < 4 * kLanes; ++i) c.batch.render_target(0)[i % 4][i / 4] = values[(at + i) % values.size()];
        ASSERT_TRUE(same_both_ways(c)) << "values from " << at;
    }
}

// sRGB writes (render target 0, SRGBWRITEENABLE) on 8-bit targets store linear_to_srgb's byte
// by thresholds (linear_to_srgb_byte()): the per-pixel path's bytes for the colours at and
// a few ulps either side of every threshold, found here by bisecting the per-pixel path's own
// stores (a one-pixel merge through the generic path), and over a sweep of [-0.5, 1.5]; with
// and without blending (source over onto random bytes, read linear).
TEST(OutputMergerFast, SrgbWritesMatchThePerPixelPathAtEveryByteBoundary) {
    // The byte the per-pixel path stores for red = v (no blending).
    const auto stored_red = [](float v) {
        Case one;
        one.color[0] = Surface(Format::A8R8G8B8, 2, 2);
        RenderState rs;
        rs.srgb_write_enable = true;
        one.state = output_merger_state(rs);
        one.lanes.quad_count = 1;
        for (unsigned i = 0; i < 4; ++i) {
            one.lanes.x[i] = static_cast<int32_t>(i & 1u);
            one.lanes.y[i] = static_cast<int32_t>(i >> 1);
            one.batch.set(one.batch.render_target(0), i, v, 0, 0, 1);
        }
        one.input.live = 0xF;
        Case out;
        one.run(true, out);
        return static_cast<unsigned>(out.color[0]->bytes()[2]);  // A8R8G8B8: red is byte 2
    };
    std::vector<float> values;
    for (unsigned k = 1; k < 256; ++k) {
        uint32_t low = 0, high = 0x3F800000u;  // the least float in [0, 1] stored as k or more
        while (low < high) {
            const uint32_t mid = low + (high - low) / 2;
            if (stored_red(std::bit_cast<float>(mid)) >= k) high = mid;
            else low = mid + 1;
        }
        ASSERT_EQ(stored_red(std::bit_cast<float>(low)), k);
        ASSERT_EQ(stored_red(std::bit_cast<float>(low - 1)), k - 1);
        for (int d = -3; d <= 3; ++d) values.push_back(std::bit_cast<float>(static_cast<uint32_t>(static_cast<int64_t>(low) + d)));
    }
    for (int i = -(1 << 12); i <= 3 << 12; ++i) values.push_back(static_cast<float>(i) / static_cast<float>(1 << 13));
    Random r(20261203);
    for (const Format f : {Format::A8R8G8B8, Format::X8R8G8B8}) {
        for (const bool blend : {false, true}) {
            Case c;
            c.color[0] = random_surface(r, f, 8, 2);
            RenderState rs;
            rs.srgb_write_enable = true;
            rs.alpha_blend_enable = blend;
            rs.src_blend = Blend::SrcAlpha;
            rs.dest_blend = Blend::InvSrcAlpha;
            c.state = output_merger_state(rs);
            side_by_side_quads(c.lanes);
            c.input.live = emu::kAllLanes;
            for (size_t at = 0; at < values.size(); at += 4 * kLanes) {
                for (unsigned i = 0; i < 4 * kLanes; ++i)
                    c.batch.render_target(0)[i % 4][i / 4] = i % 4 == 3 && blend ? r.uniform(0, 1) : values[(at + i) % values.size()];
                ASSERT_TRUE(same_both_ways(c)) << "format " << static_cast<uint32_t>(f) << " blend " << blend << ", values from " << at;
            }
        }
    }
}

// "Source over" (SRCALPHA, INVSRCALPHA, ADD), which the block path blends in registers, at the
// blends that land next to a rounding boundary of the store: for stored bytes d and alphas a,
// sources s within a few ulps of ((k + 0.5) / 255 - d (1 - a)) / a, where one rounding more or
// less (a fused multiply-add) changes the byte.
TEST(OutputMergerFast, SourceOverMatchesThePerPixelPathAtRoundingBoundaries) {
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.src_blend = Blend::SrcAlpha;
    rs.dest_blend = Blend::InvSrcAlpha;
    Case c;
    c.state = output_merger_state(rs);
    c.color[0] = Surface(Format::A8R8G8B8, 8, 2);
    side_by_side_quads(c.lanes);
    c.input.live = emu::kAllLanes;
    Random r(7);
    for (int round = 0; round < 4000; ++round) {
        auto& bytes = c.color[0]->bytes();
        for (auto& b : bytes) b = static_cast<std::byte>(r.below(256));
        for (unsigned i = 0; i < kLanes; ++i) {
            const float a = static_cast<float>(1 + r.below(254)) / 255.0f + r.uniform(-1e-4f, 1e-4f);
            const auto* texel = bytes.data() + static_cast<size_t>(c.lanes.y[i]) * c.color[0]->row_pitch() +
                                static_cast<size_t>(c.lanes.x[i]) * 4;
            std::array<float, 4> colour{};
            for (unsigned ch = 0; ch < 3; ++ch) {
                const float d = static_cast<float>(std::to_integer<unsigned>(texel[2 - ch])) / 255.0f;  // B G R A
                const float boundary = (static_cast<float>(r.below(255)) + 0.5f) / 255.0f;
                float s = (boundary - d * (1.0f - a)) / a;
                for (int step = static_cast<int>(r.below(9)) - 4; step != 0; step += step < 0 ? 1 : -1)
                    s = std::nextafter(s, step < 0 ? -2.0f : 2.0f);
                colour[ch] = s;
            }
            colour[3] = a;
            c.batch.set(c.batch.render_target(0), i, colour[0], colour[1], colour[2], colour[3]);
        }
        ASSERT_TRUE(same_both_ways(c)) << "round " << round;
    }
}

// Source over ("SRCALPHA, INVSRCALPHA") with a source alpha that saturates to +0 on every lane
// (0, -0, negatives, -inf, NaN) writes s * 0 + d * 1 = d: the bytes of a UNORM target whose
// every bit is a field's stay as they were, whatever the colour (NaN and infinities saturate
// first) and the write mask, and the fast paths (which read and write nothing then) agree with
// the per-pixel path; X8R8G8B8's writes clear its X byte (the fast path must still write).
// Batches with one lane of alpha 0.3 must blend that lane as before.
TEST(OutputMergerFast, TransparentSourceOverLeavesEveryTexel) {
    static const float kTransparent[] = {0.0f, -0.0f, -0.5f, -std::numeric_limits<float>::infinity(),
                                         std::numeric_limits<float>::quiet_NaN(), -1e-40f};
    const Format formats[] = {Format::A8R8G8B8, Format::X8R8G8B8, Format::A8B8G8R8, Format::A2R10G10B10,
                              Format::A16B16G16R16, Format::R5G6B5, Format::A8R8G8B8, Format::A8R8G8B8};
    Random r(20261203);
    unsigned changed = 0;
    for (int round = 0; round < 3000; ++round) {
        RenderState rs;
        rs.alpha_blend_enable = true;
        rs.src_blend = Blend::SrcAlpha;
        rs.dest_blend = Blend::InvSrcAlpha;
        rs.color_write_enable[0] = r.chance(0.5) ? 0xF : r.below(16);
        const Format format = formats[r.below(std::size(formats))];
        Case c = random_case(r, {format});
        c.state = output_merger_state(rs);
        c.input.color_outputs = 1;
        for (unsigned t = 1; t < kMaxRenderTargets; ++t) c.color[t].reset();
        const bool one_opaque_lane = round % 4 == 3;
        for (unsigned i = 0; i < kLanes; ++i) {
            const float alpha = one_opaque_lane && i == round % kLanes ? 0.3f : kTransparent[r.below(std::size(kTransparent))];
            c.batch.set(c.batch.render_target(0), i, r.colour(), r.colour(), r.colour(), alpha);
        }
        ASSERT_TRUE(same_both_ways(c)) << "round " << round;
        Case after;
        c.run(false, after);
        const bool same = after.color[0]->bytes() == c.color[0]->bytes();
        if (!one_opaque_lane && format != Format::X8R8G8B8) {
            ASSERT_TRUE(same) << "round " << round << ": a transparent batch changed the target";
        }
        changed += same ? 0 : 1;
    }
    EXPECT_GT(changed, 100u);  // the lanes of alpha 0.3 blended
}

// One lane at (1, 1) of a 4x4 target whose texel there holds `stored`; returns the texel after.
uint32_t merge_one(Format f, uint32_t stored, const RenderState& rs, const Vec4& colour, bool generic) {
    Surface target(f, 4, 4);
    std::memcpy(target.bytes().data() + target.row_pitch() + 4, &stored, 4);
    emu::Batch batch;
    batch.set(batch.render_target(0), 0, colour[0], colour[1], colour[2], colour[3]);
    PixelLanes lanes;
    lanes.quad_count = 1;
    lanes.x[0] = lanes.y[0] = 1;
    RenderTargets targets;
    targets.color[0] = &target;
    MergeInput in;
    in.batch = &batch;
    in.lanes = &lanes;
    in.live = 1;
    in.generic_path = generic;
    EXPECT_EQ(merge(output_merger_state(rs), targets, in), 1u);
    uint32_t texel;
    std::memcpy(&texel, target.bytes().data() + target.row_pitch() + 4, 4);
    return texel;
}

TEST(OutputMergerFast, SrcAlphaOverA8R8G8B8) {
    // Stored 0xFF0080FF: (r, g, b, a) = (0, 128/255, 1, 1). Source (1, 0.5, 0, 0.5), SRCALPHA /
    // INVSRCALPHA, so both factors are 0.5:
    //   r = 1 * 0.5 + 0 * 0.5 = 0.5               -> 127.5 + 0.5 = 128 -> 0x80 (halves round up)
    //   g = 0.25 + (128/255) * 0.5 = 0.500980...  -> 127.75 + 0.5      -> 128 -> 0x80
    //   b = 0 * 0.5 + 1 * 0.5 = 0.5               -> 0x80
    //   a = 0.5 * 0.5 + 1 * 0.5 = 0.75            -> 191.25 + 0.5      -> 191 -> 0xBF
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.src_blend = Blend::SrcAlpha;
    rs.dest_blend = Blend::InvSrcAlpha;
    const Vec4 colour{1.0f, 0.5f, 0.0f, 0.5f};
    EXPECT_EQ(merge_one(Format::A8R8G8B8, 0xFF0080FFu, rs, colour, false), 0xBF808080u);
    EXPECT_EQ(merge_one(Format::A8R8G8B8, 0xFF0080FFu, rs, colour, true), 0xBF808080u);
}

TEST(OutputMergerFast, DestAlphaOfX8R8G8B8IsOneAndXIsCleared) {
    // X8R8G8B8 reads alpha 1, so DESTALPHA / INVDESTALPHA gives source * 1 + dest * 0. Source
    // (0.25, 0.75, 1, 0): r 63.75 + 0.5 -> 64 (0x40), g 191.25 + 0.5 -> 191 (0xBF), b 255;
    // the X byte (0xAB before) is stored as 0.
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.src_blend = Blend::DestAlpha;
    rs.dest_blend = Blend::InvDestAlpha;
    const Vec4 colour{0.25f, 0.75f, 1.0f, 0.0f};
    EXPECT_EQ(merge_one(Format::X8R8G8B8, 0xAB102030u, rs, colour, false), 0x0040BFFFu);
    EXPECT_EQ(merge_one(Format::X8R8G8B8, 0xAB102030u, rs, colour, true), 0x0040BFFFu);
}

TEST(OutputMergerFast, WriteMaskAndOutOfRangeColourOnA8B8G8R8) {
    // A8B8G8R8 stores R in the low byte: 0x44332211 is (r, g, b, a) = (0x11, 0x22, 0x33, 0x44).
    // No blending, COLORWRITEENABLE R|G|A, source (2, NaN, -1, 0.5): r clamps to 0xFF, NaN
    // stores 0, b keeps 0x33, a = 127.5 + 0.5 -> 128 (0x80).
    RenderState rs;
    rs.color_write_enable[0] = kWriteRed | kWriteGreen | kWriteAlpha;
    const Vec4 colour{2.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.5f};
    EXPECT_EQ(merge_one(Format::A8B8G8R8, 0x44332211u, rs, colour, false), 0x803300FFu);
    EXPECT_EQ(merge_one(Format::A8B8G8R8, 0x44332211u, rs, colour, true), 0x803300FFu);
}

TEST(OutputMergerFast, RepeatedPixelSeesTheEarlierLane) {
    // Two lanes on one pixel, ONE / ONE ADD over 0: lane 0 stores 0.25 -> 63.75 + 0.5 -> 64;
    // lane 1 reads 64/255 = 0.25098 and adds 0.25: 0.50098 -> 127.75 + 0.5 -> 128 (0x80).
    RenderState rs;
    rs.alpha_blend_enable = true;
    rs.dest_blend = Blend::One;
    for (const bool generic : {false, true}) {
        Surface target(Format::A8R8G8B8, 4, 4);
        emu::Batch batch;
        for (unsigned l = 0; l < 2; ++l) batch.set(batch.render_target(0), l, 0.25f, 0.25f, 0.25f, 0.25f);
        PixelLanes lanes;
        lanes.quad_count = 1;
        RenderTargets targets;
        targets.color[0] = &target;
        MergeInput in;
        in.batch = &batch;
        in.lanes = &lanes;
        in.live = 3;
        in.generic_path = generic;
        EXPECT_EQ(merge(output_merger_state(rs), targets, in), 3u);
        uint32_t texel;
        std::memcpy(&texel, target.bytes().data(), 4);
        EXPECT_EQ(texel, 0x80808080u) << (generic ? "generic" : "fast");
    }
}

}  // namespace
}  // namespace sm2::runtime
