// Vertex fetch (pipeline.md §1): declarations, D3DDECLTYPE expansion, streams, indices.
#include "sm2/runtime/vertex_fetch.h"

#include <cstring>
#include <unordered_map>

#include "half.h"

namespace sm2::runtime {
namespace {

template <typename T>
T load(const std::byte* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

float u8(const std::byte* p, unsigned i) { return static_cast<float>(std::to_integer<uint8_t>(p[i])); }
float s16(const std::byte* p, unsigned i) { return static_cast<float>(load<int16_t>(p + 2 * i)); }
float u16(const std::byte* p, unsigned i) { return static_cast<float>(load<uint16_t>(p + 2 * i)); }
float f32(const std::byte* p, unsigned i) { return load<float>(p + 4 * i); }
float f16(const std::byte* p, unsigned i) { return half_to_float(load<uint16_t>(p + 2 * i)); }

// Signed 10-bit two's-complement field.
int32_t s10(uint32_t bits) { return (bits & 0x200u) ? static_cast<int32_t>(bits) - 1024 : static_cast<int32_t>(bits); }

}  // namespace

unsigned decl_type_size(DeclType type) {
    switch (type) {
    case DeclType::FLOAT1: return 4;
    case DeclType::FLOAT2: return 8;
    case DeclType::FLOAT3: return 12;
    case DeclType::FLOAT4: return 16;
    case DeclType::D3DCOLOR: case DeclType::UBYTE4: case DeclType::SHORT2:
    case DeclType::UBYTE4N: case DeclType::SHORT2N: case DeclType::USHORT2N:
    case DeclType::UDEC3: case DeclType::DEC3N: case DeclType::FLOAT16_2: return 4;
    case DeclType::SHORT4: case DeclType::SHORT4N: case DeclType::USHORT4N:
    case DeclType::FLOAT16_4: return 8;
    case DeclType::UNUSED: return 0;
    }
    return 0;
}

std::array<float, 4> decode_element(DeclType type, const std::byte* p) {
    switch (type) {
    case DeclType::FLOAT1: return {f32(p, 0), 0.0f, 0.0f, 1.0f};
    case DeclType::FLOAT2: return {f32(p, 0), f32(p, 1), 0.0f, 1.0f};
    case DeclType::FLOAT3: return {f32(p, 0), f32(p, 1), f32(p, 2), 1.0f};
    case DeclType::FLOAT4: return {f32(p, 0), f32(p, 1), f32(p, 2), f32(p, 3)};
    case DeclType::D3DCOLOR:  // bytes B, G, R, A
        return {u8(p, 2) / 255.0f, u8(p, 1) / 255.0f, u8(p, 0) / 255.0f, u8(p, 3) / 255.0f};
    case DeclType::UBYTE4: return {u8(p, 0), u8(p, 1), u8(p, 2), u8(p, 3)};
    case DeclType::SHORT2: return {s16(p, 0), s16(p, 1), 0.0f, 1.0f};
    case DeclType::SHORT4: return {s16(p, 0), s16(p, 1), s16(p, 2), s16(p, 3)};
    case DeclType::UBYTE4N:
        return {u8(p, 0) / 255.0f, u8(p, 1) / 255.0f, u8(p, 2) / 255.0f, u8(p, 3) / 255.0f};
    case DeclType::SHORT2N:  // D3D9: / 32767 without clamping (-32768 gives < -1)
        return {s16(p, 0) / 32767.0f, s16(p, 1) / 32767.0f, 0.0f, 1.0f};
    case DeclType::SHORT4N:
        return {s16(p, 0) / 32767.0f, s16(p, 1) / 32767.0f, s16(p, 2) / 32767.0f,
                s16(p, 3) / 32767.0f};
    case DeclType::USHORT2N: return {u16(p, 0) / 65535.0f, u16(p, 1) / 65535.0f, 0.0f, 1.0f};
    case DeclType::USHORT4N:
        return {u16(p, 0) / 65535.0f, u16(p, 1) / 65535.0f, u16(p, 2) / 65535.0f,
                u16(p, 3) / 65535.0f};
    case DeclType::UDEC3: {
        const auto v = load<uint32_t>(p);
        return {static_cast<float>(v & 0x3FFu), static_cast<float>((v >> 10) & 0x3FFu),
                static_cast<float>((v >> 20) & 0x3FFu), 1.0f};
    }
    case DeclType::DEC3N: {
        const auto v = load<uint32_t>(p);
        return {static_cast<float>(s10(v & 0x3FFu)) / 511.0f,
                static_cast<float>(s10((v >> 10) & 0x3FFu)) / 511.0f,
                static_cast<float>(s10((v >> 20) & 0x3FFu)) / 511.0f, 1.0f};
    }
    case DeclType::FLOAT16_2: return {f16(p, 0), f16(p, 1), 0.0f, 1.0f};
    case DeclType::FLOAT16_4: return {f16(p, 0), f16(p, 1), f16(p, 2), f16(p, 3)};
    case DeclType::UNUSED: break;
    }
    return {0.0f, 0.0f, 0.0f, 1.0f};
}

std::vector<ShaderInput> shader_inputs(const isa::Program& program) {
    std::vector<ShaderInput> inputs;
    if (program.version.type != isa::ShaderType::Vertex) return inputs;
    for (const auto& ins : program.instructions) {
        if (ins.opcode != isa::Opcode::Dcl || !ins.dest || ins.dest->type != isa::RegisterType::Input)
            continue;
        inputs.push_back({ins.dest->index, ins.declaration.usage, ins.declaration.usage_index});
    }
    return inputs;
}

FetchPlanResult plan_fetch(std::span<const VertexElement> declaration,
                           std::span<const ShaderInput> inputs) {
    FetchPlanResult result;
    FetchPlan plan;
    auto fail = [&](size_t i, const std::string& what) {
        result.error = "element " + std::to_string(i) + ": " + what;
        return result;
    };
    std::vector<const VertexElement*> elements;
    size_t i = 0;
    for (; i < declaration.size(); ++i) {
        const VertexElement& e = declaration[i];
        if (e.stream == 0xFF && e.type == static_cast<uint8_t>(DeclType::UNUSED)) break;  // END
        if (i >= kMaxDeclElements)
            return fail(i, "more than 64 elements (MAXD3DDECLLENGTH)");
        if (e.stream >= kMaxVertexStreams)
            return fail(i, "stream " + std::to_string(e.stream) + " is not 0..15");
        if (e.type >= static_cast<uint8_t>(DeclType::UNUSED))
            return fail(i, "type " + std::to_string(e.type) + " is not a D3DDECLTYPE");
        if (e.method != 0)
            return fail(i, "method " + std::to_string(e.method) +
                               " needs the tessellator (only D3DDECLMETHOD_DEFAULT is supported)");
        if (e.usage > isa::kMaxDeclUsage)
            return fail(i, "usage " + std::to_string(e.usage) + " is not a D3DDECLUSAGE");
        if (e.usage_index > 15)
            return fail(i, "usage index " + std::to_string(e.usage_index) + " is not 0..15");
        for (const VertexElement* other : elements)
            if (other->usage == e.usage && other->usage_index == e.usage_index)
                return fail(i, "usage " + std::to_string(e.usage) + " index " +
                                   std::to_string(e.usage_index) + " appears twice");
        elements.push_back(&e);
    }
    for (const ShaderInput& in : inputs) {
        if (in.reg >= emu::slot::kInputCount) {
            result.error = "shader input v" + std::to_string(in.reg) + " is not v0..v15";
            return result;
        }
        const VertexElement* found = nullptr;
        for (const VertexElement* e : elements)
            if (e->usage == static_cast<uint8_t>(in.usage) && e->usage_index == in.usage_index) found = e;
        if (!found) {
            plan.missing.push_back(in);
            continue;
        }
        plan.entries.push_back({found->stream, found->offset, static_cast<DeclType>(found->type), in.reg});
        plan.streams_used = static_cast<uint16_t>(plan.streams_used | (1u << found->stream));
    }
    result.plan = std::move(plan);
    return result;
}

IndexResult read_indices(std::span<const std::byte> index_buffer, IndexFormat format,
                         uint32_t start_index, uint32_t count, int32_t base_vertex_index) {
    IndexResult r;
    if (count > kMaxDrawVertices) {
        r.error = std::to_string(count) + " indices: more than one draw may read (" +
                  std::to_string(kMaxDrawVertices) + ")";
        return r;
    }
    const uint64_t size = format == IndexFormat::Index16 ? 2 : 4;
    const uint64_t end = (static_cast<uint64_t>(start_index) + count) * size;
    if (end > index_buffer.size()) {
        r.error = "indices " + std::to_string(start_index) + ".." +
                  std::to_string(static_cast<uint64_t>(start_index) + count) + " read past the index buffer (" +
                  std::to_string(index_buffer.size()) + " bytes)";
        return r;
    }
    r.vertices.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        const std::byte* p = index_buffer.data() + (static_cast<uint64_t>(start_index) + i) * size;
        const int64_t index = format == IndexFormat::Index16 ? load<uint16_t>(p) : load<uint32_t>(p);
        const int64_t vertex = index + base_vertex_index;
        if (vertex < 0 || vertex > 0xFFFFFFFFll) {
            r.error = "index " + std::to_string(index) + " + BaseVertexIndex " +
                      std::to_string(base_vertex_index) + " is not a vertex number";
            r.vertices.clear();
            return r;
        }
        r.vertices[i] = static_cast<uint32_t>(vertex);
    }
    return r;
}

IndexResult sequential_vertices(uint32_t start_vertex, uint32_t count) {
    IndexResult r;
    if (count > kMaxDrawVertices) {
        r.error = std::to_string(count) + " vertices: more than one draw may read (" +
                  std::to_string(kMaxDrawVertices) + ")";
        return r;
    }
    if (static_cast<uint64_t>(start_vertex) + count > 0x100000000ull) {
        r.error = "vertices " + std::to_string(start_vertex) + " + " + std::to_string(count) +
                  " overflow 32 bits";
        return r;
    }
    r.vertices.resize(count);
    for (uint32_t i = 0; i < count; ++i) r.vertices[i] = start_vertex + i;
    return r;
}

UniqueVertices deduplicate(std::span<const uint32_t> draw_vertices) {
    UniqueVertices u;
    std::unordered_map<uint32_t, uint32_t> seen;
    seen.reserve(draw_vertices.size());
    u.slots.reserve(draw_vertices.size());
    for (uint32_t v : draw_vertices) {
        auto [it, inserted] = seen.try_emplace(v, static_cast<uint32_t>(u.vertices.size()));
        if (inserted) u.vertices.push_back(v);
        u.slots.push_back(it->second);
    }
    return u;
}

std::string fetch(const FetchPlan& plan, std::span<const VertexStream> streams,
                  std::span<const uint32_t> vertices, emu::Batch& batch) {
    if (vertices.size() > emu::kBatchLanes) return "more than 16 vertices for one batch";
    batch.lane_count = static_cast<unsigned>(vertices.size());
    for (const FetchEntry& e : plan.entries) {
        if (e.stream >= streams.size() || streams[e.stream].data.data() == nullptr)
            return "stream " + std::to_string(e.stream) + " has no vertex buffer";
        const VertexStream& s = streams[e.stream];
        const uint64_t bytes = decl_type_size(e.type);
        auto& reg = batch.input(e.reg);
        for (size_t lane = 0; lane < vertices.size(); ++lane) {
            const uint64_t at = static_cast<uint64_t>(s.offset) +
                                static_cast<uint64_t>(vertices[lane]) * s.stride + e.offset;
            if (at + bytes > s.data.size())
                return "vertex " + std::to_string(vertices[lane]) + " reads stream " +
                       std::to_string(e.stream) + " bytes " + std::to_string(at) + ".." +
                       std::to_string(at + bytes) + " past its buffer (" +
                       std::to_string(s.data.size()) + " bytes)";
            const auto v = decode_element(e.type, s.data.data() + at);
            for (unsigned c = 0; c < 4; ++c) reg[c][lane] = v[c];
        }
    }
    return {};
}

}  // namespace sm2::runtime
