// Primitive assembly (pipeline.md §2).
#include "sm2/runtime/primitive_assembly.h"

namespace sm2::runtime {

unsigned primitive_vertex_count(PrimitiveType type) {
    switch (type) {
    case PrimitiveType::PointList: return 1;
    case PrimitiveType::LineList: case PrimitiveType::LineStrip: return 2;
    default: return 3;
    }
}

std::optional<PrimitiveType> primitive_type_from(uint32_t value) {
    if (value < 1 || value > 6) return std::nullopt;
    return static_cast<PrimitiveType>(value);
}

std::optional<uint32_t> vertices_for(PrimitiveType type, uint32_t n) {
    uint64_t v = 0;
    switch (type) {
    case PrimitiveType::PointList: v = n; break;
    case PrimitiveType::LineList: v = 2ull * n; break;
    case PrimitiveType::LineStrip: v = n == 0 ? 0 : n + 1ull; break;
    case PrimitiveType::TriangleList: v = 3ull * n; break;
    case PrimitiveType::TriangleStrip:
    case PrimitiveType::TriangleFan: v = n == 0 ? 0 : n + 2ull; break;
    default: return std::nullopt;
    }
    if (v > 0xFFFFFFFFull) return std::nullopt;
    return static_cast<uint32_t>(v);
}

AssemblyResult assemble(PrimitiveType type, uint32_t n, uint32_t vertex_count) {
    AssemblyResult r;
    const auto needed = vertices_for(type, n);
    if (!needed) {
        r.error = "primitive type " + std::to_string(static_cast<unsigned>(type)) +
                  " with " + std::to_string(n) + " primitives is not a valid draw";
        return r;
    }
    if (n > kMaxPrimitiveCount) {
        r.error = std::to_string(n) + " primitives: more than MaxPrimitiveCount (" +
                  std::to_string(kMaxPrimitiveCount) + ")";
        return r;
    }
    if (*needed > vertex_count) {
        r.error = std::to_string(n) + " primitives need " + std::to_string(*needed) +
                  " vertices, the draw has " + std::to_string(vertex_count);
        return r;
    }
    r.primitives.resize(n);
    for (uint32_t k = 0; k < n; ++k) {
        Primitive& p = r.primitives[k];
        switch (type) {
        case PrimitiveType::PointList: p.v = {k, k, k}; break;
        case PrimitiveType::LineList: p.v = {2 * k, 2 * k + 1, 2 * k + 1}; break;
        case PrimitiveType::LineStrip: p.v = {k, k + 1, k + 1}; break;
        case PrimitiveType::TriangleList: p.v = {3 * k, 3 * k + 1, 3 * k + 2}; break;
        case PrimitiveType::TriangleStrip:
            p.v = (k & 1u) ? std::array<uint32_t, 3>{k, k + 2, k + 1}
                           : std::array<uint32_t, 3>{k, k + 1, k + 2};
            break;
        case PrimitiveType::TriangleFan: p.v = {k + 1, k + 2, 0}; break;
        }
        // Provoking vertex (D3DSHADEMODE page): list 3k, strip k, fan k+1, line first: always
        // the first vertex in the order above.
        p.provoking = p.v[0];
    }
    return r;
}

}  // namespace sm2::runtime
