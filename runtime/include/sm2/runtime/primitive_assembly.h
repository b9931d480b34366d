// Primitive assembly (pipeline.md §2): the vertices of each point, line and triangle of a draw,
// as positions in the draw's vertex list, with the provoking vertex for flat shading. Strip
// triangles with odd k are flipped so every triangle keeps the first one's winding.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sm2::runtime {

// D3DPRIMITIVETYPE
enum class PrimitiveType : uint8_t {
    PointList = 1, LineList = 2, LineStrip = 3, TriangleList = 4, TriangleStrip = 5,
    TriangleFan = 6,
};

// Our D3DCAPS9.MaxPrimitiveCount (a common hardware value): larger draws are rejected.
constexpr uint32_t kMaxPrimitiveCount = 0x555555;

struct Primitive {
    std::array<uint32_t, 3> v{};  // draw vertex numbers; points use v[0], lines v[0..1]
    uint32_t provoking = 0;       // the vertex flat shading takes colours from
};

// Vertices per primitive (1, 2 or 3).
[[nodiscard]] unsigned primitive_vertex_count(PrimitiveType type);
// Vertices a draw of `primitive_count` primitives reads (§2 table); nullopt for a bad type or
// a count whose vertex count overflows 32 bits.
[[nodiscard]] std::optional<uint32_t> vertices_for(PrimitiveType type, uint32_t primitive_count);
// A D3DPRIMITIVETYPE value, checked.
[[nodiscard]] std::optional<PrimitiveType> primitive_type_from(uint32_t value);

struct AssemblyResult {
    std::vector<Primitive> primitives;
    std::string error;
    [[nodiscard]] bool ok() const { return error.empty(); }
};
// The primitives of a draw. `vertex_count` is how many draw vertices exist (the index count of
// an indexed draw): asking for more primitives than they make, or more than
// kMaxPrimitiveCount, is an error.
[[nodiscard]] AssemblyResult assemble(PrimitiveType type, uint32_t primitive_count,
                                      uint32_t vertex_count);

}  // namespace sm2::runtime
