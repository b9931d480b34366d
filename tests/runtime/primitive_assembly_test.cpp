// Primitive assembly (pipeline.md §2): the vertex numbers of every primitive type, the strip
// flip, the fan order and the provoking vertex, from the §2 table.
#include <gtest/gtest.h>

#include "sm2/runtime/primitive_assembly.h"

namespace sm2::runtime {
namespace {

using V = std::array<uint32_t, 3>;

std::vector<V> vertices(PrimitiveType t, uint32_t n, uint32_t count) {
    const auto r = assemble(t, n, count);
    EXPECT_TRUE(r.ok()) << r.error;
    std::vector<V> out;
    for (const auto& p : r.primitives) {
        EXPECT_EQ(p.provoking, p.v[0]);
        out.push_back(p.v);
    }
    return out;
}

TEST(PrimitiveAssembly, Lists) {
    EXPECT_EQ(vertices(PrimitiveType::PointList, 2, 2), (std::vector<V>{{0, 0, 0}, {1, 1, 1}}));
    EXPECT_EQ(vertices(PrimitiveType::LineList, 2, 4), (std::vector<V>{{0, 1, 1}, {2, 3, 3}}));
    EXPECT_EQ(vertices(PrimitiveType::TriangleList, 2, 6), (std::vector<V>{{0, 1, 2}, {3, 4, 5}}));
}

TEST(PrimitiveAssembly, LineStripSharesVertices) {
    EXPECT_EQ(vertices(PrimitiveType::LineStrip, 3, 4), (std::vector<V>{{0, 1, 1}, {1, 2, 2}, {2, 3, 3}}));
}

TEST(PrimitiveAssembly, StripFlipsOddTriangles) {
    // Even k: (k, k+1, k+2); odd k: (k, k+2, k+1). Provoking vertex k.
    EXPECT_EQ(vertices(PrimitiveType::TriangleStrip, 4, 6),
              (std::vector<V>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}}));
}

TEST(PrimitiveAssembly, FanOrderAndProvokingVertex) {
    // Triangle k = (k+1, k+2, 0): the docs' "v2, v3, v1"; provoking vertex k+1.
    const auto r = assemble(PrimitiveType::TriangleFan, 3, 5);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.primitives[0].v, (V{1, 2, 0}));
    EXPECT_EQ(r.primitives[2].v, (V{3, 4, 0}));
    EXPECT_EQ(r.primitives[2].provoking, 3u);
}

TEST(PrimitiveAssembly, VertexCounts) {
    EXPECT_EQ(vertices_for(PrimitiveType::PointList, 5), 5u);
    EXPECT_EQ(vertices_for(PrimitiveType::LineList, 5), 10u);
    EXPECT_EQ(vertices_for(PrimitiveType::LineStrip, 5), 6u);
    EXPECT_EQ(vertices_for(PrimitiveType::TriangleList, 5), 15u);
    EXPECT_EQ(vertices_for(PrimitiveType::TriangleStrip, 5), 7u);
    EXPECT_EQ(vertices_for(PrimitiveType::TriangleFan, 5), 7u);
    EXPECT_EQ(vertices_for(PrimitiveType::TriangleFan, 0), 0u);
    EXPECT_FALSE(vertices_for(PrimitiveType::TriangleList, 0x60000000u));  // 3n overflows
    EXPECT_EQ(primitive_vertex_count(PrimitiveType::LineStrip), 2u);
}

TEST(PrimitiveAssembly, BadDraws) {
    EXPECT_FALSE(assemble(PrimitiveType::TriangleList, 2, 5).ok());   // needs 6
    EXPECT_FALSE(assemble(PrimitiveType::TriangleStrip, 1, 2).ok());  // needs 3
    EXPECT_FALSE(assemble(static_cast<PrimitiveType>(7), 1, 10).ok());
    EXPECT_FALSE(primitive_type_from(0));
    EXPECT_FALSE(primitive_type_from(7));
    EXPECT_EQ(primitive_type_from(6), PrimitiveType::TriangleFan);
    EXPECT_TRUE(assemble(PrimitiveType::TriangleList, 0, 0).ok());
    EXPECT_FALSE(assemble(PrimitiveType::PointList, kMaxPrimitiveCount + 1, 0xFFFFFFFFu).ok());
}

}  // namespace
}  // namespace sm2::runtime
