// Vertex fetch: D3DVERTEXELEMENT9 declarations with every D3DDECLTYPE (pipeline.md §1), several
// streams, 16/32-bit indices and BaseVertexIndex, into the vertex shader's v# lanes of an
// emu::Batch. Every read is bounds-checked: a read past a buffer is an error, never a crash.
//
//   plan   = plan_fetch(declaration, shader_inputs)        // once per (declaration, shader)
//   ids    = read_indices(index_buffer, ...) or sequential_vertices(start, count)
//   unique = deduplicate(ids)                               // post-transform cache: shade once
//   fetch(plan, streams, unique.vertices[i .. i+16), batch) // per batch of 16 vertices
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/isa/program.h"

namespace sm2::runtime {

// D3DDECLTYPE (the D3DDECLTYPE_ names without prefix, like Format's)
enum class DeclType : uint8_t {
    FLOAT1 = 0, FLOAT2 = 1, FLOAT3 = 2, FLOAT4 = 3, D3DCOLOR = 4, UBYTE4 = 5, SHORT2 = 6,
    SHORT4 = 7, UBYTE4N = 8, SHORT2N = 9, SHORT4N = 10, USHORT2N = 11, USHORT4N = 12,
    UDEC3 = 13, DEC3N = 14, FLOAT16_2 = 15, FLOAT16_4 = 16, UNUSED = 17,
};
constexpr unsigned kMaxVertexStreams = 16;
// Our D3DCAPS9.MaxVertexIndex + 1: the most vertices one draw may read (a bad stream cannot
// make a draw allocate without bound).
constexpr uint32_t kMaxDrawVertices = 1u << 24;
constexpr unsigned kMaxDeclElements = 64;  // MAXD3DDECLLENGTH

// Bytes one element of `type` occupies (0 for UNUSED / unknown values).
[[nodiscard]] unsigned decl_type_size(DeclType type);
// Expands one element to float4 per §1.1 ((0,0,0,1) fill for missing components). `data` must
// hold decl_type_size(type) bytes.
[[nodiscard]] std::array<float, 4> decode_element(DeclType type, const std::byte* data);

// D3DVERTEXELEMENT9. The D3DDECL_END() element (stream 0xFF, type UNUSED) ends an array; it
// may be present or left off.
struct VertexElement {
    uint16_t stream = 0;
    uint16_t offset = 0;
    uint8_t type = 0;     // DeclType value (raw so that bad values can be reported)
    uint8_t method = 0;   // D3DDECLMETHOD_DEFAULT = 0
    uint8_t usage = 0;    // D3DDECLUSAGE value
    uint8_t usage_index = 0;
    friend bool operator==(const VertexElement&, const VertexElement&) = default;
};

// A vs input register declared by the shader: dcl_<usage><index> v<reg>.
struct ShaderInput {
    unsigned reg = 0;  // v#
    isa::DeclUsage usage = isa::DeclUsage::Position;
    uint8_t usage_index = 0;
};
// The v# declarations of a vertex shader program, in order.
[[nodiscard]] std::vector<ShaderInput> shader_inputs(const isa::Program& program);

// One element to fetch into one register.
struct FetchEntry {
    unsigned stream = 0;
    uint32_t offset = 0;
    DeclType type = DeclType::FLOAT4;
    unsigned reg = 0;  // v#
};
struct FetchPlan {
    std::vector<FetchEntry> entries;
    uint16_t streams_used = 0;  // bit s = stream s is read
    // Shader inputs the declaration does not provide: they read (0,0,0,1) (pipeline.md §1:
    // "a safe choice" for an application error).
    std::vector<ShaderInput> missing;
};
struct FetchPlanResult {
    std::optional<FetchPlan> plan;
    std::string error;  // "element 2: type 18 is not a D3DDECLTYPE"
};
// Checks a declaration (types, streams, methods, usages, duplicate usage pairs, POSITIONT) and
// binds its elements to the shader's inputs by (usage, usage index). Elements no input reads
// are left out of the plan.
[[nodiscard]] FetchPlanResult plan_fetch(std::span<const VertexElement> declaration,
                                         std::span<const ShaderInput> inputs);

// SetStreamSource(stream, buffer, OffsetInBytes, Stride).
struct VertexStream {
    std::span<const std::byte> data;  // the whole vertex buffer
    uint32_t offset = 0;              // OffsetInBytes
    uint32_t stride = 0;
};

enum class IndexFormat : uint8_t { Index16, Index32 };

// Vertex numbers (buffer vertex = index + base_vertex) of `count` indices starting at
// start_index. Errors: indices past the buffer, a negative or overflowing vertex number.
struct IndexResult {
    std::vector<uint32_t> vertices;
    std::string error;
    [[nodiscard]] bool ok() const { return error.empty(); }
};
[[nodiscard]] IndexResult read_indices(std::span<const std::byte> index_buffer, IndexFormat format,
                                       uint32_t start_index, uint32_t count,
                                       int32_t base_vertex_index);
// DrawPrimitive: vertices start_vertex .. start_vertex + count - 1. Both functions reject more
// than kMaxDrawVertices.
[[nodiscard]] IndexResult sequential_vertices(uint32_t start_vertex, uint32_t count);

// The post-transform cache: each distinct vertex once, in first-use order, and for every
// position of the draw the slot of its shaded vertex.
struct UniqueVertices {
    std::vector<uint32_t> vertices;  // distinct buffer vertex numbers, to fetch and shade
    std::vector<uint32_t> slots;     // per draw vertex: index into `vertices`
};
[[nodiscard]] UniqueVertices deduplicate(std::span<const uint32_t> draw_vertices);

// Fetches vertices[0 .. n) (n <= kBatchLanes) into lanes 0 .. n-1 of batch's v# registers
// (registers the plan does not write keep their (0,0,0,1) reset value); sets lane_count.
// Returns an error (nothing guaranteed about the batch) when any read leaves its buffer.
[[nodiscard]] std::string fetch(const FetchPlan& plan,
                                std::span<const VertexStream> streams,
                                std::span<const uint32_t> vertices, emu::Batch& batch);

}  // namespace sm2::runtime
