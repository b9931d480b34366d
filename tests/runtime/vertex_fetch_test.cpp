// Vertex fetch (pipeline.md §1): every D3DDECLTYPE expanded by hand from its bytes, streams
// with offsets and strides, indices with BaseVertexIndex, the post-transform cache, and every
// bad-input path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "sm2/runtime/render_state.h"
#include "sm2/runtime/vertex_fetch.h"

namespace sm2::runtime {
namespace {

template <typename T>
std::vector<std::byte> bytes_of(std::initializer_list<T> values) {
    std::vector<std::byte> out(values.size() * sizeof(T));
    size_t at = 0;
    for (T v : values) {
        std::memcpy(out.data() + at, &v, sizeof(T));
        at += sizeof(T);
    }
    return out;
}

using F4 = std::array<float, 4>;

F4 decode(DeclType t, const std::vector<std::byte>& b) {
    EXPECT_EQ(b.size(), decl_type_size(t));
    return decode_element(t, b.data());
}

TEST(VertexFetch, FloatTypesFillMissingComponentsWith0001) {
    EXPECT_EQ(decode(DeclType::FLOAT1, bytes_of<float>({1.5f})), (F4{1.5f, 0, 0, 1}));
    EXPECT_EQ(decode(DeclType::FLOAT2, bytes_of<float>({1.5f, -2})), (F4{1.5f, -2, 0, 1}));
    EXPECT_EQ(decode(DeclType::FLOAT3, bytes_of<float>({1, 2, 3})), (F4{1, 2, 3, 1}));
    EXPECT_EQ(decode(DeclType::FLOAT4, bytes_of<float>({1, 2, 3, 4})), (F4{1, 2, 3, 4}));
}

TEST(VertexFetch, D3DColorIsBgraBytesToRgba) {
    // Memory bytes B=0x10, G=0x20, R=0x30, A=0x40 -> (R, G, B, A) / 255 = (48, 32, 16, 64) / 255.
    const auto v = decode(DeclType::D3DCOLOR, bytes_of<uint8_t>({0x10, 0x20, 0x30, 0x40}));
    EXPECT_EQ(v, (F4{48.0f / 255, 32.0f / 255, 16.0f / 255, 64.0f / 255}));
    // The DWORD 0xFF0000FF (opaque blue) -> (0, 0, 1, 1).
    EXPECT_EQ(decode(DeclType::D3DCOLOR, bytes_of<uint32_t>({0xFF0000FFu})), (F4{0, 0, 1, 1}));
}

TEST(VertexFetch, ByteTypes) {
    EXPECT_EQ(decode(DeclType::UBYTE4, bytes_of<uint8_t>({1, 2, 3, 255})), (F4{1, 2, 3, 255}));
    // 0/255, 51/255 = 0.2, 255/255 = 1, 128/255.
    EXPECT_EQ(decode(DeclType::UBYTE4N, bytes_of<uint8_t>({0, 51, 255, 128})),
              (F4{0, 51.0f / 255, 1, 128.0f / 255}));
}

TEST(VertexFetch, ShortTypesAreNotClamped) {
    EXPECT_EQ(decode(DeclType::SHORT2, bytes_of<int16_t>({-2, 300})), (F4{-2, 300, 0, 1}));
    EXPECT_EQ(decode(DeclType::SHORT4, bytes_of<int16_t>({-32768, 32767, 0, -1})), (F4{-32768, 32767, 0, -1}));
    // D3D9 divides by 32767 without clamping: -32768 -> -32768/32767, slightly below -1.
    const auto n2 = decode(DeclType::SHORT2N, bytes_of<int16_t>({-32768, 16384}));
    EXPECT_EQ(n2, (F4{-32768.0f / 32767, 16384.0f / 32767, 0, 1}));
    EXPECT_LT(n2[0], -1.0f);
    EXPECT_EQ(decode(DeclType::SHORT4N, bytes_of<int16_t>({32767, -32767, 0, 1})),
              (F4{1, -1, 0, 1.0f / 32767}));
    EXPECT_EQ(decode(DeclType::USHORT2N, bytes_of<uint16_t>({65535, 0})), (F4{1, 0, 0, 1}));
    EXPECT_EQ(decode(DeclType::USHORT4N, bytes_of<uint16_t>({65535, 0, 1, 32768})),
              (F4{1, 0, 1.0f / 65535, 32768.0f / 65535}));
}

TEST(VertexFetch, Dec3Types) {
    // x = 1 (bits 0-9), y = 2 (10-19), z = 1023 (20-29), bits 30-31 set and ignored.
    const uint32_t udec = 1u | 2u << 10 | 1023u << 20 | 3u << 30;
    EXPECT_EQ(decode(DeclType::UDEC3, bytes_of<uint32_t>({udec})), (F4{1, 2, 1023, 1}));
    // Signed 10-bit: 511 -> 511/511 = 1; 0x200 = -512 -> -512/511; 0x3FF = -1 -> -1/511.
    const uint32_t dec = 511u | 0x200u << 10 | 0x3FFu << 20 | 1u << 30;
    EXPECT_EQ(decode(DeclType::DEC3N, bytes_of<uint32_t>({dec})), (F4{1, -512.0f / 511, -1.0f / 511, 1}));
}

TEST(VertexFetch, HalfTypes) {
    // 0x3C00 = 1.0, 0xC000 = -2.0.
    EXPECT_EQ(decode(DeclType::FLOAT16_2, bytes_of<uint16_t>({0x3C00, 0xC000})), (F4{1, -2, 0, 1}));
    // 0x3800 = 0.5, 0x7BFF = 65504 (largest half), 0x0001 = 2^-24 (smallest denormal), 0x8000 = -0.
    const auto v = decode(DeclType::FLOAT16_4, bytes_of<uint16_t>({0x3800, 0x7BFF, 0x0001, 0x8000}));
    EXPECT_EQ(v[0], 0.5f);
    EXPECT_EQ(v[1], 65504.0f);
    EXPECT_EQ(v[2], 1.0f / 16777216.0f);
    EXPECT_EQ(v[3], 0.0f);
    EXPECT_TRUE(std::signbit(v[3]));
}

TEST(VertexFetch, TypeSizes) {
    const unsigned sizes[] = {4, 8, 12, 16, 4, 4, 4, 8, 4, 4, 8, 4, 8, 4, 4, 4, 8, 0};
    for (unsigned t = 0; t <= 17; ++t) EXPECT_EQ(decl_type_size(static_cast<DeclType>(t)), sizes[t]) << t;
}

constexpr uint8_t kPosition = 0, kColor = 10;
constexpr VertexElement kEnd{0xFF, 0, 17, 0, 0, 0};

TEST(VertexFetch, TwoStreamsWithOffsetStrideIndicesAndBaseVertex) {
    // Stream 0: stride 16, SetStreamSource offset 4; FLOAT3 position at element offset 0.
    // Vertex n's position is at byte 4 + 16n: (n, 10n, 100n).
    std::vector<float> s0(1 + 4 * 4, -1.0f);
    for (int n = 0; n < 4; ++n) {
        s0[1 + 4 * n] = static_cast<float>(n);
        s0[2 + 4 * n] = 10.0f * n;
        s0[3 + 4 * n] = 100.0f * n;
    }
    // Stream 1: stride 4, D3DCOLOR; vertex n = 0xFF0000nn -> blue channel n/255.
    std::vector<uint32_t> s1 = {0xFF000000u, 0xFF000001u, 0xFF000002u, 0xFF000003u};
    const VertexElement decl[] = {{0, 0, 2, 0, kPosition, 0}, {1, 0, 4, 0, kColor, 0}, kEnd};
    const ShaderInput inputs[] = {{0, isa::DeclUsage::Position, 0}, {3, isa::DeclUsage::Color, 0},
                                  {5, isa::DeclUsage::TexCoord, 2}};
    const auto plan = plan_fetch(decl, inputs);
    ASSERT_TRUE(plan.plan) << plan.error;
    EXPECT_EQ(plan.plan->streams_used, 3);
    ASSERT_EQ(plan.plan->missing.size(), 1u);  // TEXCOORD2 is not in the declaration
    EXPECT_EQ(plan.plan->missing[0].reg, 5u);

    // 16-bit indices {2, 0} at StartIndex 1 of {9, 2, 0}, BaseVertexIndex 1 -> vertices 3, 1.
    const auto ib = bytes_of<uint16_t>({9, 2, 0});
    const auto idx = read_indices(ib, IndexFormat::Index16, 1, 2, 1);
    ASSERT_TRUE(idx.ok()) << idx.error;
    EXPECT_EQ(idx.vertices, (std::vector<uint32_t>{3, 1}));

    std::array<VertexStream, 2> streams;
    streams[0] = {std::as_bytes(std::span(s0)), 4, 16};
    streams[1] = {std::as_bytes(std::span(s1)), 0, 4};
    emu::Batch batch;
    ASSERT_EQ(fetch(*plan.plan, streams, idx.vertices, batch), "");
    EXPECT_EQ(batch.lane_count, 2u);
    // Lane 0 = vertex 3: (3, 30, 300, 1); lane 1 = vertex 1: (1, 10, 100, 1).
    EXPECT_EQ(batch.input(0)[0][0], 3.0f);
    EXPECT_EQ(batch.input(0)[1][0], 30.0f);
    EXPECT_EQ(batch.input(0)[2][0], 300.0f);
    EXPECT_EQ(batch.input(0)[3][0], 1.0f);
    EXPECT_EQ(batch.input(0)[0][1], 1.0f);
    EXPECT_EQ(batch.input(3)[2][0], 3.0f / 255);  // blue of vertex 3
    EXPECT_EQ(batch.input(3)[3][1], 1.0f);
    // The missing input reads (0, 0, 0, 1).
    EXPECT_EQ(batch.input(5)[0][0], 0.0f);
    EXPECT_EQ(batch.input(5)[3][0], 1.0f);
}

TEST(VertexFetch, ThirtyTwoBitIndices) {
    const auto ib = bytes_of<uint32_t>({70000u, 5u});
    const auto idx = read_indices(ib, IndexFormat::Index32, 0, 2, -5);
    ASSERT_TRUE(idx.ok());
    EXPECT_EQ(idx.vertices, (std::vector<uint32_t>{69995u, 0u}));
}

TEST(VertexFetch, BadIndexReads) {
    const auto ib = bytes_of<uint16_t>({1, 2, 3});
    EXPECT_FALSE(read_indices(ib, IndexFormat::Index16, 2, 2, 0).ok());        // index 3 is past 6 bytes
    EXPECT_FALSE(read_indices(ib, IndexFormat::Index32, 1, 1, 0).ok());        // bytes 4..8 of 6
    EXPECT_FALSE(read_indices(ib, IndexFormat::Index16, 0xFFFFFFFFu, 2, 0).ok());  // no overflow
    EXPECT_FALSE(read_indices(ib, IndexFormat::Index16, 0, 1, -2).ok());       // 1 - 2 < 0
    EXPECT_TRUE(read_indices(ib, IndexFormat::Index16, 3, 0, 0).ok());         // empty is fine
    EXPECT_FALSE(sequential_vertices(0xFFFFFFFFu, 2).ok());
    EXPECT_FALSE(sequential_vertices(0, kMaxDrawVertices + 1).ok());  // no unbounded allocation
    EXPECT_FALSE(read_indices(ib, IndexFormat::Index16, 0, 0xFFFFFFFFu, 0).ok());
    EXPECT_EQ(sequential_vertices(5, 3).vertices, (std::vector<uint32_t>{5, 6, 7}));
}

TEST(VertexFetch, ReadPastTheVertexBufferIsAnError) {
    std::vector<float> data(6, 0.0f);  // 24 bytes: two FLOAT3 vertices at stride 12
    const VertexElement decl[] = {{0, 0, 2, 0, kPosition, 0}};
    const ShaderInput inputs[] = {{0, isa::DeclUsage::Position, 0}};
    const auto plan = plan_fetch(decl, inputs);
    ASSERT_TRUE(plan.plan);
    std::array<VertexStream, 1> streams{VertexStream{std::as_bytes(std::span(data)), 0, 12}};
    emu::Batch batch;
    const uint32_t ok[] = {0, 1};
    EXPECT_EQ(fetch(*plan.plan, streams, ok, batch), "");
    const uint32_t bad[] = {0, 2};  // vertex 2: bytes 24..36 of 24
    EXPECT_NE(fetch(*plan.plan, streams, bad, batch), "");
    const uint32_t huge[] = {0xFFFFFFFFu};  // 64-bit address arithmetic: no wrap-around
    EXPECT_NE(fetch(*plan.plan, streams, huge, batch), "");
    streams[0].offset = 4;  // SetStreamSource offset moves vertex 1 to bytes 16..28
    EXPECT_NE(fetch(*plan.plan, streams, ok, batch), "");
    std::array<VertexStream, 1> none{};
    EXPECT_NE(fetch(*plan.plan, none, ok, batch), "");  // no buffer bound
    std::vector<uint32_t> seventeen(17, 0);
    EXPECT_NE(fetch(*plan.plan, streams, seventeen, batch), "");
}

TEST(VertexFetch, BadDeclarations) {
    const ShaderInput inputs[] = {{0, isa::DeclUsage::Position, 0}};
    auto error = [&](std::initializer_list<VertexElement> d) {
        const std::vector<VertexElement> v(d);
        return plan_fetch(v, inputs).error;
    };
    EXPECT_NE(error({{0, 0, 18, 0, kPosition, 0}}), "");      // type 18
    EXPECT_NE(error({{16, 0, 2, 0, kPosition, 0}}), "");      // stream 16
    EXPECT_NE(error({{0, 0, 2, 1, kPosition, 0}}), "");       // tessellator method
    EXPECT_NE(error({{0, 0, 2, 0, 14, 0}}), "");              // usage 14
    EXPECT_NE(error({{0, 0, 2, 0, kPosition, 16}}), "");      // usage index 16
    EXPECT_NE(error({{0, 0, 2, 0, kPosition, 0}, {0, 12, 2, 0, kPosition, 0}}), "");  // twice
    std::vector<VertexElement> long_decl;
    // 65 distinct (usage, index) pairs: usages 0..4 x indices 0..15.
    for (unsigned i = 0; i < 65; ++i)
        long_decl.push_back({0, 0, 0, 0, static_cast<uint8_t>(i / 16), static_cast<uint8_t>(i % 16)});
    EXPECT_NE(plan_fetch(long_decl, inputs).error.find("64"), std::string::npos);
    long_decl.pop_back();
    EXPECT_TRUE(plan_fetch(long_decl, inputs).plan);  // 64 is allowed
    const ShaderInput bad_reg[] = {{16, isa::DeclUsage::Position, 0}};
    const VertexElement ok[] = {{0, 0, 2, 0, kPosition, 0}, kEnd, {0, 0, 99, 0, 0, 0}};
    EXPECT_NE(plan_fetch(ok, bad_reg).error, "");
    EXPECT_TRUE(plan_fetch(ok, inputs).plan);  // elements after D3DDECL_END are not read
}

TEST(VertexFetch, PostTransformCacheShadesEachVertexOnce) {
    const uint32_t draw[] = {7, 3, 7, 9, 3, 7};
    const auto u = deduplicate(draw);
    EXPECT_EQ(u.vertices, (std::vector<uint32_t>{7, 3, 9}));
    EXPECT_EQ(u.slots, (std::vector<uint32_t>{0, 1, 0, 2, 1, 0}));
}

}  // namespace
}  // namespace sm2::runtime
