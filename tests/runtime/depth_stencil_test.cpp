// The depth/stencil stage (pipeline.md §9, §11): quantization per depth format, every compare
// function, every stencil operation, masks, two-sided stencil, write enables.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "sm2/runtime/depth_stencil.h"

namespace sm2::runtime {
namespace {

using Lanes = std::array<int32_t, emu::kBatchLanes>;
using Depths = std::array<float, emu::kBatchLanes>;

DepthStencilSurface make(Format f, uint32_t w = 4, uint32_t h = 4) {
    auto r = DepthStencilSurface::create(f, w, h);
    EXPECT_TRUE(r.surface) << r.error;
    return std::move(*r.surface);
}

TEST(DepthStencil, QuantizationPerFormat) {
    const DepthFormatInfo d16{16, 0, false}, d24{24, 8, false}, d32{32, 0, false}, f32{32, 0, true};
    // round(z * (2^n - 1)), halves up:
    EXPECT_EQ(quantize_depth(d16, 0.5f), 32768u);       // 32767.5 -> 32768
    EXPECT_EQ(quantize_depth(d16, 0.25f), 16384u);      // 16383.75 -> 16384
    EXPECT_EQ(quantize_depth(d16, 1.0f / 3.0f), 21845u);  // 21845.00065 (float 1/3 is 0.33333334)
    EXPECT_EQ(quantize_depth(d16, 1.0f), 65535u);
    EXPECT_EQ(quantize_depth(d24, 0.5f), 8388608u);     // 8388607.5 -> 8388608
    EXPECT_EQ(quantize_depth(d24, 1.0f), 16777215u);
    EXPECT_EQ(quantize_depth(d32, 0.5f), 2147483648u);  // 2147483647.5 -> 2^31
    EXPECT_EQ(quantize_depth(d32, 1.0f), 4294967295u);
    // 2^-30 * (2^32 - 1) = 4 - 2^-30 -> 4 (needs more than float or double precision).
    EXPECT_EQ(quantize_depth(d32, 1.0f / 1073741824.0f), 4u);
    // 2^-33 * (2^32 - 1) = 0.5 - 2^-33 -> 0.
    EXPECT_EQ(quantize_depth(d32, 1.0f / 8589934592.0f), 0u);
    // Clamped to [0, 1]; NaN stores 0.
    EXPECT_EQ(quantize_depth(d16, -0.5f), 0u);
    EXPECT_EQ(quantize_depth(d16, 2.0f), 65535u);
    EXPECT_EQ(quantize_depth(d16, std::numeric_limits<float>::quiet_NaN()), 0u);
    // Float depth keeps the value.
    EXPECT_EQ(quantize_depth(f32, 0.1f), std::bit_cast<uint32_t>(0.1f));
    EXPECT_EQ(dequantize_depth(f32, std::bit_cast<uint32_t>(0.1f)), 0.1f);
    EXPECT_EQ(dequantize_depth(d16, 65535u), 1.0f);
}

// Every 97th float of [0, 1] (normals and denormals) against round(z * (2^n - 1)) worked out in
// double, where the product is exact for 16 and 24 bits (24 + 24 significant bits) and the
// fraction test does the rounding without adding 0.5 in floating point.
TEST(DepthStencil, QuantizationMatchesExactRoundingOverFloats) {
    const DepthFormatInfo d16{16, 0, false}, d24{24, 8, false};
    const uint32_t one = std::bit_cast<uint32_t>(1.0f);
    for (const DepthFormatInfo& info : {d16, d24}) {
        const double max = static_cast<double>((uint64_t{1} << info.depth_bits) - 1);
        unsigned checked = 0;
        for (uint32_t bits = 0; bits <= one; bits += bits < 4096 ? 1 : 97) {
            const float z = std::bit_cast<float>(bits);
            const double p = static_cast<double>(z) * max;
            const double whole = std::floor(p);
            const auto expected = static_cast<uint32_t>(whole) + (p - whole >= 0.5 ? 1u : 0u);
            ASSERT_EQ(quantize_depth(info, z), expected) << "z = " << z << " (bits " << bits << ")";
            ++checked;
        }
        EXPECT_GT(checked, 10000000u);
    }
}

TEST(DepthStencil, FormatsAndCreation) {
    EXPECT_EQ(depth_format_info(Format::D24S8)->stencil_bits, 8);
    EXPECT_EQ(depth_format_info(Format::D24X8)->stencil_bits, 0);
    EXPECT_EQ(depth_format_info(Format::D16)->depth_bits, 16);
    EXPECT_EQ(depth_format_info(Format::D32)->depth_bits, 32);
    EXPECT_TRUE(depth_format_info(Format::D32F_LOCKABLE)->float_depth);
    EXPECT_FALSE(depth_format_info(Format::A8R8G8B8));
    EXPECT_FALSE(DepthStencilSurface::create(Format::A8R8G8B8, 4, 4).surface);
    EXPECT_FALSE(DepthStencilSurface::create(Format::D16, 0, 4).surface);
    EXPECT_FALSE(DepthStencilSurface::create(Format::D16, 4, 100000).surface);
    auto s = make(Format::D24S8);
    s.clear(PixelRect{1, 1, 10, 10}, true, 0.5f, true, 0x1FF);  // clipped; stencil to 8 bits
    EXPECT_EQ(s.stored_depth(0, 0), 0u);
    EXPECT_EQ(s.stored_depth(3, 3), 8388608u);
    EXPECT_EQ(s.stencil(3, 3), 0xFFu);
}

// One pixel at (1, 2) in lane 0.
emu::LaneMask test_one(const DepthStencilState& st, DepthStencilSurface& s, float z, bool cw = true) {
    Lanes x{}, y{};
    Depths d{};
    x[0] = 1;
    y[0] = 2;
    d[0] = z;
    return depth_stencil_test(st, &s, x, y, d, 1u, cw);
}

TEST(DepthStencil, EveryDepthCompareFunction) {
    // Stored 0.5 (D16: 32768). Incoming 0.25 (16384), 0.5 (32768), 0.75 (49151.25 -> 49151).
    struct Row { CompareFunc f; bool less, equal, greater; };
    const Row rows[] = {
        {CompareFunc::Never, false, false, false},   {CompareFunc::Less, true, false, false},
        {CompareFunc::Equal, false, true, false},    {CompareFunc::LessEqual, true, true, false},
        {CompareFunc::Greater, false, false, true},  {CompareFunc::NotEqual, true, false, true},
        {CompareFunc::GreaterEqual, false, true, true}, {CompareFunc::Always, true, true, true},
    };
    for (const Row& r : rows) {
        DepthStencilState st;
        st.depth_enable = true;
        st.depth_write = false;
        st.depth_func = r.f;
        auto s = make(Format::D16);
        s.set_depth(1, 2, 0.5f);
        EXPECT_EQ(test_one(st, s, 0.25f) == 1u, r.less) << static_cast<int>(r.f);
        EXPECT_EQ(test_one(st, s, 0.5f) == 1u, r.equal) << static_cast<int>(r.f);
        EXPECT_EQ(test_one(st, s, 0.75f) == 1u, r.greater) << static_cast<int>(r.f);
        EXPECT_EQ(s.stored_depth(1, 2), 32768u);  // ZWRITEENABLE FALSE: never written
    }
}

TEST(DepthStencil, ComparesInStoredPrecision) {
    // D16: 0.5 and 0.500005 both store 32768 (32767.5 and 32767.83 round to it), so EQUAL passes.
    DepthStencilState st;
    st.depth_enable = true;
    st.depth_func = CompareFunc::Equal;
    auto s = make(Format::D16);
    s.set_depth(1, 2, 0.5f);
    EXPECT_EQ(test_one(st, s, 0.500005f), 1u);
    // D32F compares floats: the two differ.
    auto f = make(Format::D32F_LOCKABLE);
    f.set_depth(1, 2, 0.5f);
    EXPECT_EQ(test_one(st, f, 0.500005f), 0u);
}

TEST(DepthStencil, DepthWriteAndDisabled) {
    DepthStencilState st;
    st.depth_enable = true;  // LESSEQUAL, write on
    auto s = make(Format::D24X8);
    s.set_depth(1, 2, 1.0f);
    EXPECT_EQ(test_one(st, s, 0.5f), 1u);
    EXPECT_EQ(s.stored_depth(1, 2), 8388608u);
    EXPECT_EQ(test_one(st, s, 0.75f), 0u);  // fails, nothing written
    EXPECT_EQ(s.stored_depth(1, 2), 8388608u);
    EXPECT_EQ(test_one(st, s, 2.0f), 0u);   // clamped to 1: 1 <= 0.5 fails
    st.depth_enable = false;                // disabled: passes, writes nothing
    EXPECT_EQ(test_one(st, s, 0.9f), 1u);
    EXPECT_EQ(s.stored_depth(1, 2), 8388608u);
    // No surface: passes. Lanes outside the surface: fail.
    Lanes x{}, y{};
    Depths d{};
    x[1] = 4;
    st.depth_enable = true;
    EXPECT_EQ(depth_stencil_test(st, nullptr, x, y, d, 3u, true), 3u);
    EXPECT_EQ(depth_stencil_test(st, &s, x, y, d, 3u, true), 1u);
}

TEST(DepthStencil, EveryStencilOp) {
    // 8-bit stencil (max 255), REF 9: from stored 5 and from the extremes 0 and 255.
    struct Row { StencilOp op; uint32_t from5, from0, from255; };
    const Row rows[] = {
        {StencilOp::Keep, 5, 0, 255},    {StencilOp::Zero, 0, 0, 0},
        {StencilOp::Replace, 9, 9, 9},   {StencilOp::IncrSat, 6, 1, 255},
        {StencilOp::DecrSat, 4, 0, 254}, {StencilOp::Invert, 250, 255, 0},
        {StencilOp::Incr, 6, 1, 0},      {StencilOp::Decr, 4, 255, 254},
    };
    for (const Row& r : rows) {
        EXPECT_EQ(apply_stencil_op(r.op, 5, 9, 255), r.from5) << static_cast<int>(r.op);
        EXPECT_EQ(apply_stencil_op(r.op, 0, 9, 255), r.from0) << static_cast<int>(r.op);
        EXPECT_EQ(apply_stencil_op(r.op, 255, 9, 255), r.from255) << static_cast<int>(r.op);
        // Through the stage: STENCILPASS = op, stencil ALWAYS, depth off.
        DepthStencilState st;
        st.stencil_enable = true;
        st.front.pass = r.op;
        st.ref = 9;
        auto s = make(Format::D24S8);
        s.set_stencil(1, 2, 5);
        EXPECT_EQ(test_one(st, s, 0.5f), 1u);
        EXPECT_EQ(s.stencil(1, 2), r.from5);
    }
}

TEST(DepthStencil, FailZFailPassSelectTheOp) {
    DepthStencilState st;
    st.stencil_enable = true;
    st.depth_enable = true;
    st.depth_func = CompareFunc::Less;
    st.front = {StencilOp::Replace, StencilOp::Incr, StencilOp::Zero, CompareFunc::Equal};
    st.ref = 7;
    auto s = make(Format::D24S8);
    s.set_depth(1, 2, 0.5f);
    s.set_stencil(1, 2, 3);
    EXPECT_EQ(test_one(st, s, 0.25f), 0u);  // 7 == 3 fails: FAIL op REPLACE -> 7, dropped
    EXPECT_EQ(s.stencil(1, 2), 7u);
    EXPECT_EQ(test_one(st, s, 0.75f), 0u);  // stencil passes, depth 0.75 < 0.5 fails: ZFAIL INCR -> 8
    EXPECT_EQ(s.stencil(1, 2), 8u);
    s.set_stencil(1, 2, 7);
    EXPECT_EQ(test_one(st, s, 0.25f), 1u);  // both pass: PASS ZERO -> 0, depth written
    EXPECT_EQ(s.stencil(1, 2), 0u);
    EXPECT_EQ(s.stored_depth(1, 2), quantize_depth(s.info(), 0.25f));
}

TEST(DepthStencil, MasksAndReferenceOnTheLeft) {
    DepthStencilState st;
    st.stencil_enable = true;
    auto s = make(Format::D24S8);
    // (REF & MASK) LESS (stored & MASK): REF 0x12, MASK 0x0F, stored 0x35: 2 < 5 passes; with
    // GREATER it fails (the reference is on the left).
    st.ref = 0x12;
    st.mask = 0x0F;
    st.front.func = CompareFunc::Less;
    s.set_stencil(1, 2, 0x35);
    EXPECT_EQ(test_one(st, s, 0), 1u);
    st.front.func = CompareFunc::Greater;
    EXPECT_EQ(test_one(st, s, 0), 0u);
    // Write mask: stored 0xF0, REPLACE with REF 0x0F, WRITEMASK 0x3C:
    // (0xF0 & ~0x3C) | (0x0F & 0x3C) = 0xC0 | 0x0C = 0xCC.
    st.front = {StencilOp::Keep, StencilOp::Keep, StencilOp::Replace, CompareFunc::Always};
    st.ref = 0x0F;
    st.mask = 0xFF;
    st.write_mask = 0x3C;
    s.set_stencil(1, 2, 0xF0);
    EXPECT_EQ(test_one(st, s, 0), 1u);
    EXPECT_EQ(s.stencil(1, 2), 0xCCu);
}

TEST(DepthStencil, TwoSided) {
    RenderState rs;
    rs.stencil_enable = true;
    rs.stencil.pass = StencilOp::Incr;
    rs.ccw_stencil.pass = StencilOp::Decr;
    auto s = make(Format::D24S8);
    s.set_stencil(1, 2, 10);
    // Two-sided off: both windings use the clockwise set.
    DepthStencilState st = depth_stencil_state(rs);
    (void)test_one(st, s, 0, false);
    EXPECT_EQ(s.stencil(1, 2), 11u);
    rs.two_sided_stencil_mode = true;
    st = depth_stencil_state(rs);
    (void)test_one(st, s, 0, true);   // clockwise: INCR -> 12
    EXPECT_EQ(s.stencil(1, 2), 12u);
    (void)test_one(st, s, 0, false);  // counter-clockwise: DECR -> 11
    EXPECT_EQ(s.stencil(1, 2), 11u);
}

TEST(DepthStencil, NoStencilBitsReadZero) {
    // D24X8 has no stencil: stored reads 0, nothing is written. REF 0 EQUAL 0 passes.
    DepthStencilState st;
    st.stencil_enable = true;
    st.front = {StencilOp::Keep, StencilOp::Keep, StencilOp::Replace, CompareFunc::Equal};
    st.ref = 0;
    auto s = make(Format::D24X8);
    EXPECT_EQ(test_one(st, s, 0), 1u);
    EXPECT_EQ(s.stencil(1, 2), 0u);
    st.ref = 1;
    EXPECT_EQ(test_one(st, s, 0), 0u);
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

// A depth value for the 16-lane path's quantization: random in [0, 1], a rounding tie of the
// format's code (k + 0.5) / (2^n - 1) or a float next to one, or a special value.
float random_depth(std::mt19937& rng, unsigned bits) {
    const double codes = std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
    std::uniform_int_distribution<int> kind(0, 9);
    switch (kind(rng)) {
    case 0: case 1: case 2: return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    case 3: case 4: case 5: {
        const double k = std::floor(std::uniform_real_distribution<double>(0.0, codes)(rng));
        const auto tie = static_cast<float>((k + 0.5) / codes);
        const int step = std::uniform_int_distribution<int>(-2, 2)(rng);
        return step < 0 ? std::nextafter(tie, -1.0f) : step > 0 ? std::nextafter(tie, 2.0f) : tie;
    }
    case 6: return std::uniform_real_distribution<float>(-1.0f, 2.0f)(rng);
    case 7: return std::numeric_limits<float>::denorm_min() * static_cast<float>(std::uniform_int_distribution<int>(0, 100)(rng));
    case 8: return std::uniform_int_distribution<int>(0, 1)(rng) ? 0.0f : -0.0f;
    default: {
        const float special[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                 -std::numeric_limits<float>::infinity(), 1.0f, std::nextafter(1.0f, 0.0f), 0x1p-24f,
                                 // 0.5 is every integer format's one exact tie (z (2^n - 1) = k + 1/2)
                                 0.5f, 0.5f, std::nextafter(0.5f, 0.0f), std::nextafter(0.5f, 1.0f)};
        return special[std::uniform_int_distribution<size_t>(0, std::size(special) - 1)(rng)];
    }
    }
}

// The 16-lane depth/stencil test against the lane-by-lane loop: the same lanes pass and the
// same depth and stencil values are stored, for every format, compare function, write enable
// and (in half the trials) stencil state (both faces, every operation, reference, masks), with
// lanes outside the surface, lanes off, repeated pixels, batches in one quad row and depth
// values on the formats' rounding ties.
TEST(DepthStencil, SixteenLanePathMatchesTheLaneByLaneLoop) {
    std::mt19937 rng(20261128);
    const Format formats[] = {Format::D16, Format::D16_LOCKABLE, Format::D24S8, Format::D24X8, Format::D15S1,
                              Format::D24X4S4, Format::D32F_LOCKABLE, Format::D24FS8, Format::D32};
    const CompareFunc funcs[] = {CompareFunc::Never, CompareFunc::Less, CompareFunc::Equal, CompareFunc::LessEqual,
                                 CompareFunc::Greater, CompareFunc::NotEqual, CompareFunc::GreaterEqual, CompareFunc::Always};
    unsigned passed_lanes = 0, failed_lanes = 0;
    for (unsigned trial = 0; trial < 8000; ++trial) {
        const Format f = formats[trial % std::size(formats)];
        DepthStencilSurface a = make(f, 12, 9);
        const unsigned bits = a.info().float_depth ? 24 : a.info().depth_bits;
        // Stored values: the quantized codes of random depths (some equal to what comes next).
        for (uint32_t y = 0; y < 9; ++y)
            for (uint32_t x = 0; x < 12; ++x) {
                a.set_depth(x, y, random_depth(rng, bits));
                a.set_stencil(x, y, rng() % 4 == 0 ? a.stencil_max() : rng() % 4 == 0 ? 0 : rng());
            }
        DepthStencilSurface b = a;
        DepthStencilState st;
        st.depth_enable = true;
        st.depth_write = rng() % 4 != 0;
        st.depth_func = funcs[rng() % std::size(funcs)];
        const bool clockwise = rng() % 2 != 0;
        if (trial % 2 == 1) {
            const StencilOp ops[] = {StencilOp::Keep, StencilOp::Zero, StencilOp::Replace, StencilOp::IncrSat,
                                     StencilOp::DecrSat, StencilOp::Invert, StencilOp::Incr, StencilOp::Decr};
            st.stencil_enable = true;
            st.depth_enable = rng() % 4 != 0;
            st.two_sided = rng() % 2 != 0;
            for (StencilFace* face : {&st.front, &st.back})
                *face = StencilFace{ops[rng() % 8], ops[rng() % 8], ops[rng() % 8], funcs[rng() % std::size(funcs)]};
            st.ref = rng() % 2 ? rng() % 4 : rng();
            st.mask = rng() % 2 ? 0xFFFFFFFFu : rng();
            st.write_mask = rng() % 2 ? 0xFFFFFFFFu : rng();
        }
        Lanes x{}, y{};
        Depths d{};
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            x[l] = std::uniform_int_distribution<int32_t>(-2, 13)(rng);
            y[l] = std::uniform_int_distribution<int32_t>(-2, 10)(rng);
            d[l] = random_depth(rng, bits);
            // Half the lanes at a stored pixel's own value.
            if (rng() % 2 && x[l] >= 0 && x[l] < 12 && y[l] >= 0 && y[l] < 9)
                d[l] = dequantize_depth(a.info(), a.stored_depth(static_cast<uint32_t>(x[l]), static_cast<uint32_t>(y[l])));
        }
        if (trial % 5 != 0) {
            // Four 2x2 quads at distinct places, lanes in quad order, as a rasterized batch has
            // (the 16-lane path's case); some quads partly or wholly outside the surface, and
            // in every seventh trial two quads at the same place (the lane-by-lane loop's case).
            std::array<std::pair<int32_t, int32_t>, 4> quad{};
            for (unsigned q = 0; q < 4; ++q) {
                bool repeated = true;
                while (repeated) {
                    quad[q] = {2 * std::uniform_int_distribution<int32_t>(-1, 5)(rng),
                               2 * std::uniform_int_distribution<int32_t>(-1, 4)(rng)};
                    repeated = false;
                    for (unsigned o = 0; o < q; ++o) repeated = repeated || quad[o] == quad[q];
                }
            }
            if (trial % 7 == 0) quad[3] = quad[1];
            // In every fifth trial the four quads side by side in one quad row (quad_rows.h), as
            // most batches of a rasterized triangle lie: inside the surface the 16-lane path
            // reads and writes them by rows; at x0 = -2 or 6 or y0 = -2 or 8 they cross its edge.
            if (trial % 5 == 1) {
                const int32_t x0 = 2 * std::uniform_int_distribution<int32_t>(-1, 3)(rng);
                const int32_t y0 = 2 * std::uniform_int_distribution<int32_t>(-1, 4)(rng);
                for (unsigned q = 0; q < 4; ++q) quad[q] = {x0 + 2 * static_cast<int32_t>(q), y0};
                if (rng() % 3 == 0) quad[1 + rng() % 3].second += 2;  // a step down: not one row
            }
            for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
                x[l] = quad[l / 4].first + static_cast<int32_t>(l & 1u);
                y[l] = quad[l / 4].second + static_cast<int32_t>(l >> 1 & 1u);
            }
        }
        const auto live = static_cast<emu::LaneMask>(rng() & 0xFFFF);
        const emu::LaneMask vector = depth_stencil_test(st, &a, x, y, d, live, clockwise, false);
        const emu::LaneMask reference = depth_stencil_test(st, &b, x, y, d, live, clockwise, true);
        ASSERT_EQ(vector, reference) << "trial " << trial;
        for (uint32_t py = 0; py < 9; ++py)
            for (uint32_t px = 0; px < 12; ++px) {
                ASSERT_EQ(a.stored_depth(px, py), b.stored_depth(px, py)) << "trial " << trial << " at " << px << "," << py;
                ASSERT_EQ(a.stencil(px, py), b.stencil(px, py)) << "trial " << trial << " at " << px << "," << py;
            }
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            if (!(live >> l & 1u)) continue;
            if (reference >> l & 1u) ++passed_lanes;
            else ++failed_lanes;
        }
    }
    // Both outcomes are well represented.
    EXPECT_GT(passed_lanes, 10000u);
    EXPECT_GT(failed_lanes, 10000u);
}

}  // namespace
}  // namespace sm2::runtime
