// Fixed-function processing as generated programs (fixed_function_programs.h). The formulas are
// D3D9's (docs/fixed-function.md lists each with its source); only SM2 operations are used, so
// the engine's rules (precision, saturation, sampling) apply to them as to any shader.
#include "fixed_function_programs.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "sm2/runtime/device.h"

namespace sm2::runtime {

namespace {

using isa::Opcode;
using isa::RegisterType;
using isa::SourceModifier;

constexpr uint8_t kXYZ = 0x7, kW = 0x8, kXY = 0x3, kZ = 0x4;
// D3DTEXTURETRANSFORMFLAGS: COUNT1..COUNT4 in the low byte, PROJECTED.
constexpr uint32_t kTtffCountMask = 0xFF, kTtffProjected = 0x100;
constexpr uint8_t kSwizzleW = 0xFF, kSwizzleZWZW = 0xEE;

isa::SourceParameter src(RegisterType type, unsigned index, uint8_t swizzle = isa::kSwizzleIdentity,
                         SourceModifier modifier = SourceModifier::None) {
    isa::SourceParameter p;
    p.type = type;
    p.index = static_cast<uint16_t>(index);
    p.swizzle = swizzle;
    p.modifier = modifier;
    return p;
}
isa::SourceParameter negated(isa::SourceParameter p) {
    p.modifier = p.modifier == SourceModifier::Negate ? SourceModifier::None : SourceModifier::Negate;
    return p;
}
isa::SourceParameter alpha_of(isa::SourceParameter p) {
    p.swizzle = isa::replicate_swizzle(isa::swizzle_component(p.swizzle, 3));
    return p;
}
isa::DestinationParameter dst(RegisterType type, unsigned index, uint8_t mask = isa::kMaskAll, bool saturate = false) {
    isa::DestinationParameter d;
    d.type = type;
    d.index = static_cast<uint16_t>(index);
    d.write_mask = mask;
    d.saturate = saturate;
    return d;
}

// Builds a Program and, beside it, a text of every field that decides it: the cache key.
class ProgramBuilder {
public:
    explicit ProgramBuilder(isa::ShaderType type) { program_.version = isa::ShaderVersion{type, 2, 0}; }

    void dcl_input(RegisterType type, unsigned reg, isa::DeclUsage usage = isa::DeclUsage::Position,
                   uint8_t usage_index = 0, isa::TextureType texture = isa::TextureType::Unknown) {
        isa::Instruction ins;
        ins.opcode = Opcode::Dcl;
        ins.dest = dst(type, reg);
        ins.declaration.usage = usage;
        ins.declaration.usage_index = usage_index;
        ins.declaration.texture_type = texture;
        add(std::move(ins));
    }
    void op(Opcode opcode, isa::DestinationParameter d, std::initializer_list<isa::SourceParameter> sources,
            uint8_t control = 0) {
        isa::Instruction ins;
        ins.opcode = opcode;
        ins.control = control;
        ins.dest = d;
        ins.sources = sources;
        add(std::move(ins));
    }
    FixedFunctionProgram finish(std::vector<std::array<float, 4>> constants) && {
        FixedFunctionProgram out;
        out.program = std::move(program_);
        out.key = std::move(key_);
        out.constants = std::move(constants);
        return out;
    }

private:
    void add(isa::Instruction ins) {
        key_ += std::to_string(static_cast<unsigned>(ins.opcode)) + ':' + std::to_string(ins.control);
        const auto& d = *ins.dest;
        key_ += ' ' + std::to_string(static_cast<unsigned>(d.type)) + '.' + std::to_string(d.index) + '.' +
                std::to_string(d.write_mask) + (d.saturate ? "s" : "");
        for (const auto& s : ins.sources)
            key_ += ' ' + std::to_string(static_cast<unsigned>(s.type)) + '.' + std::to_string(s.index) + '.' +
                    std::to_string(s.swizzle) + '.' + std::to_string(static_cast<unsigned>(s.modifier));
        if (ins.opcode == Opcode::Dcl)
            key_ += ' ' + std::to_string(static_cast<unsigned>(ins.declaration.usage)) + '.' +
                    std::to_string(ins.declaration.usage_index) + '.' +
                    std::to_string(static_cast<unsigned>(ins.declaration.texture_type));
        key_ += '\n';
        program_.instructions.push_back(std::move(ins));
    }
    isa::Program program_;
    std::string key_;
};

FixedFunctionProgram refused(std::string why) {
    FixedFunctionProgram out;
    out.error = std::move(why);
    return out;
}

std::array<float, 4> color_of(uint32_t argb) {
    return {static_cast<float>(argb >> 16 & 0xFF) / 255.0f, static_cast<float>(argb >> 8 & 0xFF) / 255.0f,
            static_cast<float>(argb & 0xFF) / 255.0f, static_cast<float>(argb >> 24) / 255.0f};
}

// D3DDECLUSAGE values of the elements the vertex program reads.
constexpr uint8_t kUsagePosition = 0, kUsageBlendWeight = 1, kUsageBlendIndices = 2, kUsageNormal = 3, kUsagePSize = 4, kUsageTexCoord = 5, kUsagePositionT = 9, kUsageColor = 10;

// Vertex program input registers.
constexpr unsigned kInPosition = 0, kInDiffuse = 1, kInSpecular = 2, kInTexCoord0 = 3, kInNormal = 11,
                   kInBlendWeight = 12, kInBlendIndices = 13, kInPointSize = 14,
                   // Tweening's second position and normal (tweening reads no blend weights).
                   kInPosition1 = 15, kInNormal1 = kInBlendWeight;
// Vertex program constants.
constexpr unsigned kVcTransform = 0;       // c0..c3: (world x view x projection) transposed, or
                                           // c0: the XYZRHW screen -> clip mapping
constexpr unsigned kVcDefaultDiffuse = 4;  // (1, 1, 1, 1)
constexpr unsigned kVcZero = 5;            // (0, 0, 0, 0), also the default specular
constexpr unsigned kVcOne = 6;             // (1, 1, 1, 1)
constexpr unsigned kVcWorldView = 7;       // c7..c10: world x view transposed (camera space)
constexpr unsigned kVcNormal = 11;         // c11..c13: rows of the inverse of world x view's 3x3
constexpr unsigned kVcGlobalAmbient = 14;  // AMBIENT
constexpr unsigned kVcMaterial = 15;       // c15..c18: material diffuse, ambient, specular, emissive
constexpr unsigned kVcPower = 19;          // (power, 0, 0, 0)
constexpr unsigned kVcFog = 20;            // (FOGEND, 1 / (FOGEND - FOGSTART), FOGDENSITY, log2 e)
constexpr unsigned kVcHalf = 21;           // (0.5, 0.5, 0.5, 0.5): sphere map scale and offset
constexpr unsigned kVcBlendIndexScale = 22;  // indexed blending: vertex index -> palette offset
constexpr unsigned kVcTweenFactor = 22;      // tweening (no indexed blending): (TWEENFACTOR, ...)
constexpr unsigned kVcPointScale = 23;     // (POINTSCALE_A, _B, _C, viewport height)
constexpr unsigned kVcPointSize = 24;      // (POINTSIZE, 0, 0, 0)
constexpr unsigned kVcLightFirst = 25;     // kLightConstants per enabled light:
constexpr unsigned kLightDiffuse = 0, kLightSpecular = 1, kLightAmbient = 2,
                   kLightVector = 3,       // directional: direction to the light; point: position (camera space)
                   kLightAttenuation = 4,  // (attenuation0, 1, 2, range)
                   kLightSpotAxis = 5,     // spot: the reversed direction (camera space, normalized)
                   kLightSpotCone = 6,     // spot: (cos(theta/2), cos(phi/2), 1 / (cos(theta/2) - cos(phi/2)), falloff)
                   kLightConstants = 7;
// Indexed vertex blending's matrix palette, after the most the constants above can take (8 lights,
// 8 texture matrices): per WORLDMATRIX(n), world x view's columns, then with normals the rows of
// its 3x3's inverse.
constexpr unsigned kVcTextureMatrixFirst = kVcLightFirst + kLightConstants * kMaxActiveLights;  // 4 per stage
constexpr unsigned kVcPalette = kVcTextureMatrixFirst + 4 * kMaxTextureStages;
constexpr unsigned kBlendMatrixConstants = 4, kBlendNormalConstants = 3;

std::array<float, 4> rgba(const ColorValue& c) { return {c.r, c.g, c.b, c.a}; }

// A light's direction (the way it shines, in world space) into camera space by the view
// matrix's rotation, reversed and normalized: the unit vector toward the light, w = 0 (zero for
// a zero direction).
std::array<float, 4> toward_light(const Vector3& d, const Matrix4& view) {
    float v[3];
    for (unsigned k = 0; k < 3; ++k) v[k] = -(d.x * view[0 * 4 + k] + d.y * view[1 * 4 + k] + d.z * view[2 * 4 + k]);
    const float length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const float k = length > 0 ? 1.0f / length : 0.0f;
    return {v[0] * k, v[1] * k, v[2] * k, 0};
}

// The inverse of a row-major 3x3 matrix (zero for a singular one, as a degenerate world has no
// meaningful normals).
std::array<float, 9> inverse3(const std::array<float, 9>& m) {
    const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
    const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    if (det == 0) return {};
    const double k = 1.0 / det;
    return {static_cast<float>((e * i - f * h) * k), static_cast<float>((c * h - b * i) * k),
            static_cast<float>((b * f - c * e) * k), static_cast<float>((f * g - d * i) * k),
            static_cast<float>((a * i - c * g) * k), static_cast<float>((c * d - a * f) * k),
            static_cast<float>((d * h - e * g) * k), static_cast<float>((b * g - a * h) * k),
            static_cast<float>((a * e - b * d) * k)};
}

// A row-major matrix's columns: what m4x4 (dot products with c0..c3) needs for row vectors.
std::array<std::array<float, 4>, 4> columns_of(const Matrix4& m) {
    std::array<std::array<float, 4>, 4> columns{};
    for (unsigned row = 0; row < 4; ++row)
        for (unsigned col = 0; col < 4; ++col) columns[col][row] = m[row * 4 + col];
    return columns;
}

// The 3 rows m3x3 needs to take a normal through the inverse transpose of a matrix's 3x3.
std::array<std::array<float, 4>, 3> normal_rows(const Matrix4& m) {
    const auto inv = inverse3({m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]});
    std::array<std::array<float, 4>, 3> rows{};
    for (unsigned j = 0; j < 3; ++j) rows[j] = {inv[j * 3], inv[j * 3 + 1], inv[j * 3 + 2], 0};
    return rows;
}

// The number of components a vertex element supplies (the rest are fetched as (0, 0, 0, 1)).
unsigned decl_type_components(uint8_t type) {
    switch (static_cast<DeclType>(type)) {
    case DeclType::FLOAT1: return 1;
    case DeclType::FLOAT2: case DeclType::SHORT2: case DeclType::SHORT2N: case DeclType::USHORT2N:
    case DeclType::FLOAT16_2: return 2;
    case DeclType::FLOAT3: case DeclType::UDEC3: case DeclType::DEC3N: return 3;
    default: return 4;
    }
}

// A stage's texture matrix for an input of `components` components, as the 4 columns m4x4
// reads. D3D9 extends a 1- or 2-component coordinate with a 1 right after it, (u, 1, 0, 0) or
// (u, v, 1, 0), so that a 2D coordinate's translation is the matrix's third row; the fetch gives
// (u, 0, 0, 1) and (u, v, 0, 1), so that row moves to the fourth, which the 1 multiplies.
std::array<std::array<float, 4>, 4> texture_matrix_columns(const Matrix4& m, unsigned components) {
    Matrix4 adjusted = m;
    if (components <= 2)
        for (unsigned col = 0; col < 4; ++col) adjusted[12 + col] = m[components * 4 + col];
    return columns_of(adjusted);
}

}  // namespace

FixedFunctionProgram fixed_function_vertex_program(const FixedFunctionState& ff, const RenderState& rs,
                                                   const VertexProcessingStates& states, const Viewport& viewport,
                                                   std::span<const VertexElement> declaration) {
    bool has_position = false, pretransformed = false, has_diffuse = false, has_specular = false, has_normal = false;
    bool has_position1 = false, has_normal1 = false;
    std::array<bool, 8> has_texcoord{};
    std::array<unsigned, 8> texcoord_components{};
    unsigned blend_weights = 0;  // components of BLENDWEIGHT 0
    bool has_point_size = false;
    std::optional<DeclType> blend_indices;
    for (const auto& e : declaration) {
        if (e.usage == kUsageBlendWeight && e.usage_index == 0) blend_weights = decl_type_components(e.type);
        if (e.usage == kUsagePSize && e.usage_index == 0) has_point_size = true;
        if (e.usage == kUsageBlendIndices && e.usage_index == 0) blend_indices = static_cast<DeclType>(e.type);
        if (e.usage == kUsagePosition && e.usage_index == 0) has_position = true;
        if (e.usage == kUsagePositionT && e.usage_index == 0) has_position = pretransformed = true;
        if (e.usage == kUsageNormal && e.usage_index == 0) has_normal = true;
        if (e.usage == kUsagePosition && e.usage_index == 1) has_position1 = true;
        if (e.usage == kUsageNormal && e.usage_index == 1) has_normal1 = true;
        if (e.usage == kUsageColor && e.usage_index == 0) has_diffuse = true;
        if (e.usage == kUsageColor && e.usage_index == 1) has_specular = true;
        if (e.usage == kUsageTexCoord && e.usage_index < 8) {
            has_texcoord[e.usage_index] = true;
            texcoord_components[e.usage_index] = decl_type_components(e.type);
        }
    }
    if (!has_position) return refused("fixed-function vertex processing: the declaration has no POSITION or POSITIONT 0");
    const bool lighting = states.lighting && !pretransformed;
    // D3DVBF_*: DISABLE 0, 1WEIGHTS..3WEIGHTS, TWEENING 255, 0WEIGHTS 256. n weights blend n + 1
    // matrices, the last weighted 1 - (the sum of the others).
    constexpr uint32_t kVbfTweening = 255, kVbf0Weights = 256;
    // TWEENING (D3D9 "Vertex Tweening"): POSITION0 (1 - TWEENFACTOR) + POSITION1 TWEENFACTOR, and
    // the normals likewise when the vertex has NORMAL1; excludes blending with weights.
    const bool tweening = states.vertex_blend == kVbfTweening && !pretransformed;
    if (tweening && !has_position1) return refused("VERTEXBLEND TWEENING: the declaration has no POSITION 1");
    if (states.vertex_blend > 3 && states.vertex_blend != kVbf0Weights && states.vertex_blend != kVbfTweening)
        return refused("VERTEXBLEND " + std::to_string(states.vertex_blend) + " is not a D3DVERTEXBLENDFLAGS value");
    const unsigned weights = states.vertex_blend == kVbf0Weights || states.vertex_blend == kVbfTweening ? 0 : states.vertex_blend;
    const bool indexed_blend = !pretransformed && !tweening && states.indexed_vertex_blend;
    const bool blending = !pretransformed && (weights > 0 || indexed_blend);
    if (blending && weights > blend_weights)
        return refused("VERTEXBLEND " + std::to_string(weights) + " weights: the vertex has " +
                       std::to_string(blend_weights));
    if (indexed_blend && !blend_indices) return refused("INDEXEDVERTEXBLENDENABLE: the vertex has no BLENDINDICES");
    const bool vertex_fog =
        rs.fog_enable && rs.fog_table_mode == FogMode::None && !pretransformed && rs.fog_vertex_mode != FogMode::None;
    // Table fog under a perspective projection (any but a fourth column (0, 0, 0, 1), Wine's test
    // too) is W-fog: of the eye-space depth, which the program passes in oFog.
    const auto& proj = ff.projection;
    const bool w_fog = rs.fog_enable && rs.fog_table_mode != FogMode::None && !pretransformed &&
                       !(proj[3] == 0.0f && proj[7] == 0.0f && proj[11] == 0.0f && proj[15] == 1.0f);
    std::vector<const Light*> lights;
    if (lighting)
        for (uint32_t index : ff.enabled_lights) {
            lights.push_back(&ff.lights.at(index));
        }
    for (uint32_t source : {states.diffuse_source, states.specular_source, states.ambient_source, states.emissive_source})
        if (lighting && source > 2)
            return refused("fixed-function lighting: material source " + std::to_string(source) +
                           " is not MATERIAL, COLOR1 or COLOR2");
    // D3DTSS_TCI_* texture coordinate generation: PASSTHRU 0, CAMERASPACENORMAL 1,
    // CAMERASPACEPOSITION 2, CAMERASPACEREFLECTIONVECTOR 3, SPHEREMAP 4.
    constexpr uint32_t kTciPassThru = 0, kTciNormal = 1, kTciPosition = 2, kTciReflection = 3, kTciSphereMap = 4;
    bool generates_from_normal = false, generates_from_position = false;
    for (unsigned s = 0; s < kMaxTextureStages; ++s) {
        const uint32_t tci = ff.stages[s][kTssTexCoordIndex];
        const uint32_t mode = tci >> 16;
        if (mode > kTciSphereMap)
            return refused("texture stage " + std::to_string(s) + ": TEXCOORDINDEX mode " + std::to_string(mode) +
                           " is not a D3DTSS_TCI mode");
        if (mode != kTciPassThru && pretransformed)
            return refused("texture stage " + std::to_string(s) +
                           ": TEXCOORDINDEX texture coordinate generation needs untransformed (XYZ) vertices");
        generates_from_normal |= mode == kTciNormal || mode == kTciReflection || mode == kTciSphereMap;
        generates_from_position |= mode == kTciPosition || mode == kTciReflection || mode == kTciSphereMap;
        if ((tci & 0xFFFF) >= 8)
            return refused("texture stage " + std::to_string(s) + ": TEXCOORDINDEX " + std::to_string(tci & 0xFFFF) +
                           " is not a texture coordinate set (0..7)");
        const uint32_t flags = ff.stages[s][kTssTextureTransformFlags];
        if ((flags & ~(kTtffCountMask | kTtffProjected)) != 0 || (flags & kTtffCountMask) > 4)
            return refused("texture stage " + std::to_string(s) + ": TEXTURETRANSFORMFLAGS " + std::to_string(flags) +
                           " is not COUNT1..COUNT4 with or without PROJECTED");
        if (flags == (1 | kTtffProjected))
            return refused("texture stage " + std::to_string(s) +
                           ": TEXTURETRANSFORMFLAGS COUNT1 PROJECTED (a projection needs 2 to 4 components)");
    }

    ProgramBuilder b(isa::ShaderType::Vertex);
    const auto in = [](unsigned r, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Input, r, swizzle); };
    const auto c = [](unsigned r, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Const, r, swizzle); };
    const auto r = [](unsigned n, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Temp, n, swizzle); };
    const auto rd = [](unsigned n, uint8_t mask = isa::kMaskAll) { return dst(RegisterType::Temp, n, mask); };
    constexpr uint8_t kX = 0x1, kY = 0x2, kSwizzleX = 0x00, kSwizzleY = 0x55, kSwizzleZ = 0xAA;
    b.dcl_input(RegisterType::Input, kInPosition, pretransformed ? isa::DeclUsage::PositionT : isa::DeclUsage::Position);
    if (has_diffuse) b.dcl_input(RegisterType::Input, kInDiffuse, isa::DeclUsage::Color, 0);
    if (has_specular) b.dcl_input(RegisterType::Input, kInSpecular, isa::DeclUsage::Color, 1);
    for (unsigned t = 0; t < 8; ++t)
        if (has_texcoord[t])
            b.dcl_input(RegisterType::Input, kInTexCoord0 + t, isa::DeclUsage::TexCoord, static_cast<uint8_t>(t));
    const bool needs_normal = lighting || generates_from_normal;
    if (needs_normal && has_normal) b.dcl_input(RegisterType::Input, kInNormal, isa::DeclUsage::Normal, 0);
    const bool tween_normals = tweening && needs_normal && has_normal && has_normal1;
    if (tweening) b.dcl_input(RegisterType::Input, kInPosition1, isa::DeclUsage::Position, 1);
    if (tween_normals) b.dcl_input(RegisterType::Input, kInNormal1, isa::DeclUsage::Normal, 1);
    if (blending && weights > 0) b.dcl_input(RegisterType::Input, kInBlendWeight, isa::DeclUsage::BlendWeight, 0);
    if (indexed_blend) b.dcl_input(RegisterType::Input, kInBlendIndices, isa::DeclUsage::BlendIndices, 0);
    const bool point_scale = rs.point_scale_enable && !pretransformed;
    if (has_point_size) b.dcl_input(RegisterType::Input, kInPointSize, isa::DeclUsage::PointSize, 0);

    std::vector<std::array<float, 4>> constants(blending ? kMaxVertexShaderConstantsF : kVcPalette,
                                                std::array<float, 4>{0, 0, 0, 0});
    constants[kVcDefaultDiffuse] = {1, 1, 1, 1};
    constants[kVcOne] = {1, 1, 1, 1};
    const auto o_pos = [](uint8_t mask) { return dst(RegisterType::RastOut, 0, mask); };
    const Matrix4 world_view = multiply(ff.world[0], ff.view);
    if (pretransformed) {
        // XYZRHW: x, y are render-target pixels, z the depth, rhw 1/w. The clip-space position
        // ((x - X) 2/W - 1, 1 - (y - Y) 2/H, z, 1) w with w = 1/rhw is what the viewport mapping
        // (x_s = X + (x/w + 1) W/2, y_s = Y + (1 - y/w) H/2) turns back into exactly x, y, and
        // the rasterizer's 1/w into rhw (perspective-correct interpolation, as D3D9 does).
        const float w = static_cast<float>(std::max<uint32_t>(viewport.width, 1));
        const float h = static_cast<float>(std::max<uint32_t>(viewport.height, 1));
        constants[kVcTransform] = {2.0f / w, -2.0f / h, -1.0f - 2.0f * static_cast<float>(viewport.x) / w,
                                   1.0f + 2.0f * static_cast<float>(viewport.y) / h};
        b.op(Opcode::Rcp, dst(RegisterType::Temp, 0, kW), {in(kInPosition, kSwizzleW)});
        b.op(Opcode::Mad, dst(RegisterType::Temp, 1, kXY), {in(kInPosition), c(kVcTransform), c(kVcTransform, kSwizzleZWZW)});
        b.op(Opcode::Mov, dst(RegisterType::Temp, 1, kZ), {in(kInPosition)});
        b.op(Opcode::Mul, o_pos(kXYZ), {r(1), r(0, kSwizzleW)});
        b.op(Opcode::Mov, o_pos(kW), {r(0, kSwizzleW)});
    } else if (!blending) {
        // Tweening: the blended position in r9, the normal in r10, p0 + TWEENFACTOR (p1 - p0)
        // (both read before lighting, which reuses them).
        auto position = in(kInPosition), normal = in(kInNormal);
        if (tweening) {
            constants[kVcTweenFactor] = {states.tween_factor, states.tween_factor, states.tween_factor, states.tween_factor};
            // (One v# per instruction: POSITION1 through the register first.)
            b.op(Opcode::Mov, rd(9), {in(kInPosition1)});
            b.op(Opcode::Add, rd(9), {r(9), negated(in(kInPosition))});
            b.op(Opcode::Mad, rd(9), {r(9), c(kVcTweenFactor), in(kInPosition)});
            position = r(9);
            if (tween_normals) {
                b.op(Opcode::Mov, rd(10), {in(kInNormal1)});
                b.op(Opcode::Add, rd(10), {r(10), negated(in(kInNormal))});
                b.op(Opcode::Mad, rd(10), {r(10), c(kVcTweenFactor), in(kInNormal)});
                normal = r(10);
            }
        }
        // Row vectors: p' = p (World View Projection); m4x4 takes dot products with rows c0..c3,
        // so the constants hold the product's columns.
        const auto wvp = columns_of(multiply(world_view, ff.projection));
        const auto wv = columns_of(world_view);
        std::copy(wvp.begin(), wvp.end(), constants.begin() + kVcTransform);
        std::copy(wv.begin(), wv.end(), constants.begin() + kVcWorldView);
        b.op(Opcode::M4x4, o_pos(isa::kMaskAll), {position, c(kVcTransform)});
        // Camera-space position in r0 (lighting, fog and point scale read it).
        if (lighting || vertex_fog || w_fog || generates_from_position || point_scale)
            b.op(Opcode::M4x4, rd(0), {position, c(kVcWorldView)});
        // Camera-space normal in r1 (lighting and texgen read it): through the inverse transpose of
        // world x view's 3x3, normalized with NORMALIZENORMALS; (0, 0, 0) when the vertex has none.
        if (needs_normal) {
            const auto rows = normal_rows(world_view);
            std::copy(rows.begin(), rows.end(), constants.begin() + kVcNormal);
            if (has_normal) {
                // nrm may not write its own source: the transformed normal goes through r11.
                b.op(Opcode::M3x3, rd(states.normalize_normals ? 11 : 1, kXYZ), {normal, c(kVcNormal)});
                if (states.normalize_normals) b.op(Opcode::Nrm, rd(1, kXYZ), {r(11)});
            } else {
                b.op(Opcode::Mov, rd(1), {c(kVcZero)});
            }
        }
    } else {
        // Vertex blending (D3D9 "Geometry Blending", "Indexed Vertex Blending"): the camera-space
        // position sum_i w_i p (World_i View), with w_n = 1 - (w_0 + ... + w_n-1), and the normal
        // sum_i w_i n (World_i View)^-T (normalized with NORMALIZENORMALS); World_i is WORLDMATRIX(i),
        // or with INDEXEDVERTEXBLENDENABLE WORLDMATRIX(the vertex's i-th index), read from the
        // palette by relative addressing. Then oPos = P Projection.
        const bool blend_normals = needs_normal && has_normal;
        const unsigned stride = kBlendMatrixConstants + (blend_normals ? kBlendNormalConstants : 0);
        const auto store_matrix = [&](unsigned base, const Matrix4& world) {
            const Matrix4 wv = multiply(world, ff.view);
            const auto columns = columns_of(wv);
            std::copy(columns.begin(), columns.end(), constants.begin() + base);
            if (blend_normals) {
                const auto rows = normal_rows(wv);
                std::copy(rows.begin(), rows.end(), constants.begin() + base + kBlendMatrixConstants);
            }
        };
        const auto projection = columns_of(ff.projection);
        std::copy(projection.begin(), projection.end(), constants.begin() + kVcTransform);
        const unsigned matrices = weights + 1;
        if (indexed_blend) {
            // The palette holds as many matrices as the constants left take (non-indexed blending
            // puts its at most 4 matrices at the same place); an index past it
            // reads zero (relative reads outside the constant file), as docs/fixed-function.md says.
            const unsigned palette = (kMaxVertexShaderConstantsF - kVcPalette) / stride;
            for (unsigned m = 0; m < palette; ++m) store_matrix(kVcPalette + m * stride, ff.world[m]);
            // D3DCOLOR indices are fetched as (R, G, B, A) / 255, i.e. bytes 2, 1, 0, 3: .zyxw puts
            // them back in memory order, as UBYTE4 has them.
            const float scale = static_cast<float>(stride) * (*blend_indices == DeclType::D3DCOLOR ? 255.0f : 1.0f);
            constants[kVcBlendIndexScale] = {scale, scale, scale, scale};
            constexpr uint8_t kSwizzleZYXW = 0xC6;
            const auto indices = *blend_indices == DeclType::D3DCOLOR ? in(kInBlendIndices, kSwizzleZYXW) : in(kInBlendIndices);
            b.op(Opcode::Mul, rd(6), {indices, c(kVcBlendIndexScale)});
        } else {
            for (unsigned m = 0; m < matrices; ++m) store_matrix(kVcPalette + m * stride, ff.world[m]);
        }
        // r7.x: the last matrix's weight.
        b.op(Opcode::Mov, rd(7, kX), {c(kVcOne)});
        for (unsigned i = 0; i < weights; ++i)
            b.op(Opcode::Add, rd(7, kX), {r(7, kSwizzleX), negated(in(kInBlendWeight, isa::replicate_swizzle(static_cast<uint8_t>(i))))});
        b.op(Opcode::Mov, rd(0), {c(kVcZero)});
        if (needs_normal) b.op(Opcode::Mov, rd(1), {c(kVcZero)});
        if (blend_normals && states.normalize_normals) b.op(Opcode::Mov, rd(11), {c(kVcZero)});
        for (unsigned i = 0; i < matrices; ++i) {
            const auto weight = i < weights ? in(kInBlendWeight, isa::replicate_swizzle(static_cast<uint8_t>(i))) : r(7, kSwizzleX);
            const auto row = [&](unsigned k) {
                if (!indexed_blend) return c(kVcPalette + i * stride + k);
                isa::SourceParameter p = c(kVcPalette + k);
                p.relative = isa::RelativeAddress{RegisterType::Address, 0x00};
                return p;
            };
            if (indexed_blend)
                b.op(Opcode::Mova, dst(RegisterType::Address, 0, kX), {r(6, isa::replicate_swizzle(static_cast<uint8_t>(i)))});
            for (unsigned k = 0; k < 4; ++k)
                b.op(Opcode::Dp4, rd(8, static_cast<uint8_t>(1u << k)), {in(kInPosition), row(k)});
            b.op(Opcode::Mad, rd(0), {r(8), weight, r(0)});
            if (blend_normals) {
                for (unsigned k = 0; k < 3; ++k)
                    b.op(Opcode::Dp3, rd(9, static_cast<uint8_t>(1u << k)), {in(kInNormal), row(kBlendMatrixConstants + k)});
                b.op(Opcode::Mad, rd(states.normalize_normals ? 11 : 1, kXYZ),
                     {r(9), weight, r(states.normalize_normals ? 11 : 1)});
            }
        }
        if (blend_normals && states.normalize_normals) {
            // Accumulated in r11 (nrm may not write its own source).
            b.op(Opcode::Nrm, rd(1, kXYZ), {r(11)});
        }
        b.op(Opcode::M4x4, o_pos(isa::kMaskAll), {r(0), c(kVcTransform)});
    }

    if (lighting) {
        // D3D9 "Mathematics of Lighting" (camera space): colour = Ce + Ca (Ga + sum Atten La)
        // + Cd sum (Atten Ld max(N.L, 0)), specular = Cs sum (Atten Ls (N.H)^P) where N.L > 0;
        // H = norm(norm(-P) + L) with LOCALVIEWER, norm((0, 0, -1) + L) without: the direction
        // to an eye infinitely far down -z, the reverse of the reflection vector's incident
        // (0, 0, 1) below (Wine's ffp and the Windows drivers its specular tests were checked on).
        constants[kVcGlobalAmbient] = color_of(states.ambient);
        constants[kVcMaterial + 0] = rgba(ff.material.diffuse);
        constants[kVcMaterial + 1] = rgba(ff.material.ambient);
        constants[kVcMaterial + 2] = rgba(ff.material.specular);
        constants[kVcMaterial + 3] = rgba(ff.material.emissive);
        constants[kVcPower] = {ff.material.power, 0, 0, 0};
        // r1 normal, r2 direction to the eye, r3 diffuse sum, r4 specular sum, r5 ambient sum.
        if (states.local_viewer) {
            b.op(Opcode::Nrm, rd(2, kXYZ), {r(0)});
            b.op(Opcode::Mov, rd(2, kXYZ), {negated(r(2))});
        } else {
            b.op(Opcode::Mov, rd(2), {c(kVcZero)});
            b.op(Opcode::Mov, rd(2, kZ), {negated(c(kVcOne))});
        }
        for (unsigned n : {3u, 4u, 5u}) b.op(Opcode::Mov, rd(n), {c(kVcZero)});
        for (size_t i = 0; i < lights.size(); ++i) {
            const Light& light = *lights[i];
            const unsigned base = kVcLightFirst + kLightConstants * static_cast<unsigned>(i);
            constants[base + kLightDiffuse] = rgba(light.diffuse);
            constants[base + kLightSpecular] = rgba(light.specular);
            constants[base + kLightAmbient] = rgba(light.ambient);
            constants[base + kLightAttenuation] = {light.attenuation0, light.attenuation1, light.attenuation2, light.range};
            // r6.xyz direction to the light, r6.w attenuation.
            if (light.type == LightType::Directional) {
                // The direction the light shines, into camera space (the view matrix; D3D9
                // light directions are in world space), reversed and normalized.
                constants[base + kLightVector] = toward_light(light.direction, ff.view);
                b.op(Opcode::Mov, rd(6, kXYZ), {c(base + kLightVector)});
                b.op(Opcode::Mov, rd(6, kW), {c(kVcOne, kSwizzleW)});
            } else {
                // Point and spot: the position into camera space; Atten = 1 / (a0 + a1 d + a2 d^2)
                // within the range, 0 beyond it.
                const Vector3 p = light.position;
                std::array<float, 4> v{};
                for (unsigned k = 0; k < 3; ++k)
                    v[k] = p.x * ff.view[0 * 4 + k] + p.y * ff.view[1 * 4 + k] + p.z * ff.view[2 * 4 + k] + ff.view[12 + k];
                constants[base + kLightVector] = v;
                b.op(Opcode::Add, rd(6, kXYZ), {c(base + kLightVector), negated(r(0))});
                b.op(Opcode::Dp3, rd(7, kW), {r(6), r(6)});                      // d^2
                b.op(Opcode::Rsq, rd(7, kX), {r(7, kSwizzleW)});                   // 1/d
                b.op(Opcode::Mul, rd(6, kXYZ), {r(6), r(7, kSwizzleX)});
                b.op(Opcode::Mul, rd(7, kY), {r(7, kSwizzleW), r(7, kSwizzleX)});  // d
                b.op(Opcode::Mad, rd(7, kZ), {c(base + kLightAttenuation, kSwizzleY), r(7, kSwizzleY),
                                              c(base + kLightAttenuation, kSwizzleX)});
                b.op(Opcode::Mad, rd(7, kZ), {c(base + kLightAttenuation, kSwizzleZ), r(7, kSwizzleW), r(7, kSwizzleZ)});
                b.op(Opcode::Rcp, rd(6, kW), {r(7, kSwizzleZ)});
                b.op(Opcode::Sge, rd(7, kZ), {c(base + kLightAttenuation, kSwizzleW), r(7, kSwizzleY)});  // d <= range
                b.op(Opcode::Mul, rd(6, kW), {r(6, kSwizzleW), r(7, kSwizzleZ)});
                if (light.type == LightType::Spot) {
                    // D3D9 "Spotlight model": rho = L . -direction; 1 inside the inner cone
                    // (rho > cos(theta/2)), 0 outside the outer one (rho <= cos(phi/2)), else
                    // ((rho - cos(phi/2)) / (cos(theta/2) - cos(phi/2)))^falloff.
                    constants[base + kLightSpotAxis] = toward_light(light.direction, ff.view);
                    const float cos_theta = std::cos(light.theta / 2), cos_phi = std::cos(light.phi / 2);
                    // theta >= phi: no penumbra, a step at the outer cone.
                    const float scale = cos_theta > cos_phi ? 1.0f / (cos_theta - cos_phi) : 1e30f;
                    constants[base + kLightSpotCone] = {cos_theta, cos_phi, scale, light.falloff};
                    b.op(Opcode::Dp3, rd(8, kX), {r(6), c(base + kLightSpotAxis)});
                    b.op(Opcode::Add, rd(8, kY), {r(8, kSwizzleX), negated(c(base + kLightSpotCone, kSwizzleY))});
                    b.op(Opcode::Mul, rd(8, kY), {r(8, kSwizzleY), c(base + kLightSpotCone, kSwizzleZ)});
                    b.op(Opcode::Max, rd(8, kY), {r(8, kSwizzleY), c(kVcZero)});
                    b.op(Opcode::Min, rd(8, kY), {r(8, kSwizzleY), c(kVcOne)});
                    // x^falloff, and 0 outside the cone whatever pow(0, 0) gives.
                    b.op(Opcode::Slt, rd(8, kZ), {c(kVcZero), r(8, kSwizzleY)});
                    b.op(Opcode::Pow, rd(8, kY), {r(8, kSwizzleY), c(base + kLightSpotCone, kSwizzleW)});
                    b.op(Opcode::Mul, rd(8, kY), {r(8, kSwizzleY), r(8, kSwizzleZ)});
                    b.op(Opcode::Mul, rd(6, kW), {r(6, kSwizzleW), r(8, kSwizzleY)});
                }
            }
            b.op(Opcode::Dp3, rd(7, kX), {r(1), r(6)});                            // N.L
            b.op(Opcode::Max, rd(7, kX), {r(7, kSwizzleX), c(kVcZero)});
            b.op(Opcode::Mul, rd(8, kX), {r(7, kSwizzleX), r(6, kSwizzleW)});
            b.op(Opcode::Mad, rd(3, kXYZ), {c(base + kLightDiffuse), r(8, kSwizzleX), r(3)});
            b.op(Opcode::Mad, rd(5, kXYZ), {c(base + kLightAmbient), r(6, kSwizzleW), r(5)});
            b.op(Opcode::Add, rd(8, kXYZ), {r(2), r(6)});                          // H
            b.op(Opcode::Nrm, rd(9, kXYZ), {r(8)});
            b.op(Opcode::Dp3, rd(9, kX), {r(1), r(9)});                            // N.H
            b.op(Opcode::Max, rd(9, kX), {r(9, kSwizzleX), c(kVcZero)});
            b.op(Opcode::Pow, rd(9, kX), {r(9, kSwizzleX), c(kVcPower, kSwizzleX)});
            b.op(Opcode::Slt, rd(9, kY), {c(kVcZero), r(7, kSwizzleX)});             // N.L > 0
            b.op(Opcode::Mul, rd(9, kX), {r(9, kSwizzleX), r(9, kSwizzleY)});
            b.op(Opcode::Mul, rd(9, kX), {r(9, kSwizzleX), r(6, kSwizzleW)});
            b.op(Opcode::Mad, rd(4, kXYZ), {c(base + kLightSpecular), r(9, kSwizzleX), r(4)});
        }
        // Material colour sources (COLORVERTEX): a vertex colour where the vertex has it.
        const auto source = [&](uint32_t value, unsigned material) {
            if (states.color_vertex && value == 1 && has_diffuse) return in(kInDiffuse);
            if (states.color_vertex && value == 2 && has_specular) return in(kInSpecular);
            return c(kVcMaterial + material);
        };
        const auto cd = source(states.diffuse_source, 0), ca = source(states.ambient_source, 1),
                   cs = source(states.specular_source, 2), ce = source(states.emissive_source, 3);
        b.op(Opcode::Add, rd(5, kXYZ), {r(5), c(kVcGlobalAmbient)});
        b.op(Opcode::Mad, rd(5, kXYZ), {r(5), ca, ce});
        b.op(Opcode::Mad, rd(5, kXYZ), {cd, r(3), r(5)});
        b.op(Opcode::Mov, rd(5, kW), {cd});                                         // alpha: diffuse's
        b.op(Opcode::Max, rd(5), {r(5), c(kVcZero)});
        b.op(Opcode::Min, dst(RegisterType::AttrOut, 0), {r(5), c(kVcOne)});
        b.op(Opcode::Mul, rd(4, kXYZ), {r(4), cs});
        b.op(Opcode::Mov, rd(4, kW), {has_specular ? in(kInSpecular) : c(kVcZero)});
        b.op(Opcode::Max, rd(4), {r(4), c(kVcZero)});
        b.op(Opcode::Min, dst(RegisterType::AttrOut, 1), {r(4), c(kVcOne)});
    } else {
        // Lighting off: the vertex colours as given, D3D9's defaults where the vertex has none
        // (diffuse opaque white, specular 0).
        b.op(Opcode::Mov, dst(RegisterType::AttrOut, 0), {has_diffuse ? in(kInDiffuse) : c(kVcDefaultDiffuse)});
        b.op(Opcode::Mov, dst(RegisterType::AttrOut, 1), {has_specular ? in(kInSpecular) : c(kVcZero)});
    }
    constants[kVcHalf] = {0.5f, 0.5f, 0.5f, 0.5f};
    for (unsigned s = 0; s < kMaxTextureStages; ++s) {
        const uint32_t set = ff.stages[s][kTssTexCoordIndex] & 0xFFFF, mode = ff.stages[s][kTssTexCoordIndex] >> 16;
        const uint32_t flags = ff.stages[s][kTssTextureTransformFlags];
        const unsigned count = flags & kTtffCountMask;
        const auto o_t = [&](uint8_t mask) { return dst(RegisterType::TexCrdOut, s, mask); };
        if (mode == kTciPassThru && !has_texcoord[set]) continue;  // nothing to pass, transform or project
        // The stage's input coordinate: the vertex's set, or generated into r10 as (x, y, z, 1)
        // from the camera-space normal, position, the reflection of the view direction I about N,
        // R = I - 2 (N.I) N, with I = norm(P) under LOCALVIEWER and (0, 0, 1) without (D3D9
        // "Texture Coordinate Processing"; as Wine), or the sphere map coordinate of R.
        isa::SourceParameter coordinate = in(kInTexCoord0 + set);
        unsigned components = texcoord_components[set];
        if (mode != kTciPassThru) {
            coordinate = r(10);
            components = 4;
            if (mode == kTciNormal) b.op(Opcode::Mov, rd(10, kXYZ), {r(1)});
            if (mode == kTciPosition) b.op(Opcode::Mov, rd(10, kXYZ), {r(0)});
            if (mode == kTciReflection || mode == kTciSphereMap) {
                if (states.local_viewer) {
                    b.op(Opcode::Nrm, rd(8, kXYZ), {r(0)});
                } else {
                    b.op(Opcode::Mov, rd(8), {c(kVcZero)});
                    b.op(Opcode::Mov, rd(8, kZ), {c(kVcOne)});
                }
                b.op(Opcode::Dp3, rd(9, kX), {r(1), r(8)});
                b.op(Opcode::Add, rd(9, kX), {r(9, kSwizzleX), r(9, kSwizzleX)});
                b.op(Opcode::Mad, rd(10, kXYZ), {negated(r(9, kSwizzleX)), r(1), r(8)});
            }
            if (mode == kTciSphereMap) {
                // OpenGL's sphere map in D3D's camera space (the eye looks along +z, v grows
                // downwards): m = 2 |(Rx, Ry, Rz - 1)|, (u, v) = (Rx / m + 0.5, -Ry / m + 0.5), so
                // that a surface facing the eye (R = (0, 0, -1)) reads the map's centre.
                b.op(Opcode::Mov, rd(9, kXYZ), {r(10)});
                b.op(Opcode::Add, rd(9, kZ), {r(10, kSwizzleZ), negated(c(kVcOne, kSwizzleZ))});
                b.op(Opcode::Dp3, rd(9, kW), {r(9), r(9)});
                b.op(Opcode::Rsq, rd(9, kW), {r(9, kSwizzleW)});
                b.op(Opcode::Mul, rd(9, kW), {r(9, kSwizzleW), c(kVcHalf)});  // 1 / m
                b.op(Opcode::Mad, rd(10, kX), {r(10, kSwizzleX), r(9, kSwizzleW), c(kVcHalf)});
                b.op(Opcode::Mad, rd(10, kY), {negated(r(10, kSwizzleY)), r(9, kSwizzleW), c(kVcHalf)});
                b.op(Opcode::Mov, rd(10, kZ), {c(kVcZero)});
            }
            b.op(Opcode::Mov, rd(10, kW), {c(kVcOne)});
        }
        if (count != 0 && !pretransformed) {
            // TEXTURETRANSFORMFLAGS COUNTn: the coordinate through TEXTUREs's matrix; the
            // rasterizer takes its first n components (the rest are zeroed).
            const unsigned base = kVcTextureMatrixFirst + 4 * s;
            const auto columns = texture_matrix_columns(ff.texture[s], components);
            std::copy(columns.begin(), columns.end(), constants.begin() + base);
            b.op(Opcode::M4x4, rd(11), {coordinate, c(base)});
            coordinate = r(11);
            components = count;
            const auto beyond = static_cast<uint8_t>(isa::kMaskAll & ~((1u << count) - 1));
            if (beyond != 0) b.op(Opcode::Mov, rd(11, beyond), {c(kVcZero)});
        }
        b.op(Opcode::Mov, o_t(isa::kMaskAll), {coordinate});
        // D3DTTFF_PROJECTED: the lookup divides by the last of the coordinate's components (the
        // COUNTn-th; for XYZRHW vertices, which are not transformed, the set's last). The
        // pixel program divides by w (texldp), so that component goes there.
        if ((flags & kTtffProjected) != 0 && components < 4) {
            const uint8_t last = isa::replicate_swizzle(static_cast<uint8_t>(components - 1));
            coordinate.swizzle = last;
            b.op(Opcode::Mov, o_t(kW), {coordinate});
        }
    }
    const auto o_fog = dst(RegisterType::RastOut, 1);  // oFog: a scalar, no write mask
    if (vertex_fog) {
        // D3D9 "Vertex Fog": the distance d is camera-space z, or with RANGEFOGENABLE the
        // distance from the eye, |P|. LINEAR: (end - d) / (end - start); EXP: e^-(density d);
        // EXP2: e^-(density d)^2.
        constants[kVcFog] = {rs.fog_end, rs.fog_end != rs.fog_start ? 1.0f / (rs.fog_end - rs.fog_start) : 0.0f,
                             rs.fog_density, 1.4426950408889634f};
        isa::SourceParameter distance = r(0, kSwizzleZ);
        if (rs.range_fog_enable) {
            b.op(Opcode::Dp3, rd(10, kY), {r(0), r(0)});
            b.op(Opcode::Rsq, rd(10, kY), {r(10, kSwizzleY)});
            b.op(Opcode::Rcp, rd(10, kY), {r(10, kSwizzleY)});
            distance = r(10, kSwizzleY);
        }
        if (rs.fog_vertex_mode == FogMode::Linear) {
            b.op(Opcode::Add, rd(10, kX), {c(kVcFog, kSwizzleX), negated(distance)});
            b.op(Opcode::Mul, rd(10, kX), {r(10, kSwizzleX), c(kVcFog, kSwizzleY)});
        } else {
            b.op(Opcode::Mul, rd(10, kX), {distance, c(kVcFog, kSwizzleZ)});
            if (rs.fog_vertex_mode == FogMode::Exp2) b.op(Opcode::Mul, rd(10, kX), {r(10, kSwizzleX), r(10, kSwizzleX)});
            b.op(Opcode::Mul, rd(10, kX), {r(10, kSwizzleX), negated(c(kVcFog, kSwizzleW))});
            b.op(Opcode::Exp, rd(10, kX), {r(10, kSwizzleX)});
        }
        // Not clamped here: the merger clamps the interpolated factor per pixel, which for LINEAR
        // equals Wine's per-pixel factor of the interpolated distance even where a primitive
        // crosses FOGSTART or FOGEND (clamping per vertex first would bend the gradient there).
        b.op(Opcode::Mov, o_fog, {r(10, kSwizzleX)});
    } else if (rs.fog_enable && rs.fog_table_mode == FogMode::None) {
        // FOGVERTEXMODE NONE (and XYZRHW vertices): the fog factor is the specular colour's
        // alpha (D3D9, "Vertex Fog"); with no specular in the vertex, no fog (factor 1).
        b.op(Opcode::Mov, o_fog, {has_specular ? in(kInSpecular, kSwizzleW) : c(kVcOne, kSwizzleW)});
    } else if (w_fog) {
        // W-fog: the eye-space depth (w of a perspective projection), interpolated perspective-
        // correctly, hence exact per pixel; the merger applies FOGTABLEMODE to it.
        b.op(Opcode::Mov, o_fog, {r(0, kSwizzleZ)});
    }
    if (has_point_size || point_scale) {
        // oPts: the vertex's PSIZE, else POINTSIZE; with POINTSCALEENABLE (D3D9 "Point Sprites")
        // times Vh sqrt(1 / (A + B De + C De^2)), De the distance from the eye. The rasterizer
        // clamps it to POINTSIZE_MIN..POINTSIZE_MAX as for a shader's oPts.
        constants[kVcPointSize] = {rs.point_size, 0, 0, 0};
        const auto size = has_point_size ? in(kInPointSize, kSwizzleX) : c(kVcPointSize, kSwizzleX);
        const auto o_pts = dst(RegisterType::RastOut, 2);  // a scalar, no write mask
        if (point_scale) {
            constants[kVcPointScale] = {rs.point_scale_a, rs.point_scale_b, rs.point_scale_c,
                                        static_cast<float>(viewport.height)};
            b.op(Opcode::Dp3, rd(8, kZ), {r(0), r(0)});                      // De^2
            b.op(Opcode::Rsq, rd(8, kW), {r(8, kSwizzleZ)});
            b.op(Opcode::Rcp, rd(8, kW), {r(8, kSwizzleW)});                   // De
            b.op(Opcode::Mad, rd(8, kY), {c(kVcPointScale, kSwizzleY), r(8, kSwizzleW), c(kVcPointScale, kSwizzleX)});
            b.op(Opcode::Mad, rd(8, kY), {c(kVcPointScale, kSwizzleZ), r(8, kSwizzleZ), r(8, kSwizzleY)});
            b.op(Opcode::Rsq, rd(8, kY), {r(8, kSwizzleY)});
            b.op(Opcode::Mul, rd(8, kY), {r(8, kSwizzleY), c(kVcPointScale, kSwizzleW)});
            b.op(Opcode::Mul, o_pts, {size, r(8, kSwizzleY)});
        } else {
            b.op(Opcode::Mov, o_pts, {size});
        }
    }
    FixedFunctionProgram out = std::move(b).finish(std::move(constants));
    out.w_fog = w_fog;
    return out;
}

namespace {

// D3DTOP values.
enum TextureOp : uint32_t {
    kDisable = 1, kSelectArg1, kSelectArg2, kModulate, kModulate2x, kModulate4x, kAdd, kAddSigned, kAddSigned2x,
    kSubtract, kAddSmooth, kBlendDiffuseAlpha, kBlendTextureAlpha, kBlendFactorAlpha, kBlendTextureAlphaPm,
    kBlendCurrentAlpha, kPremodulate, kModulateAlphaAddColor, kModulateColorAddAlpha, kModulateInvAlphaAddColor,
    kModulateInvColorAddAlpha, kBumpEnvMap, kBumpEnvMapLuminance, kDotProduct3, kMultiplyAdd, kLerp,
};
// D3DTA selectors and modifiers.
constexpr uint32_t kTaSelectMask = 0xF, kTaSpecular = 4, kTaTFactor = 3, kTaTemp = 5, kTaConstant = 6,
                   kTaComplement = 0x10, kTaAlphaReplicate = 0x20;

// Pixel program registers.
constexpr unsigned kRCurrent = 0, kRTemp = 1, kRTexture = 2, kRArgFirst = 3, kRScratch = 6, kRScratch2 = 7,
                   kRBumpCoordinate = 8, kRBumpLuminance = 9;
constexpr unsigned kPcTFactor = 0, kPcOne = 1, kPcMinusHalf = 2, kPcFour = 3, kPcStageConstant0 = 4,
                   kPcZero = kPcStageConstant0 + kMaxTextureStages,
                   // Per stage, BUMPENVMAT's rows with the luminance parameters beside them (two
                   // constants: ps_2_0 swizzles cannot pick .zw out of one): (M00, M01, LSCALE, 0),
                   // (M10, M11, LOFFSET, 0).
                   kPcBumpRow0 = kPcZero + 1, kPcBumpRow1 = kPcBumpRow0 + kMaxTextureStages;

bool is_bump(uint32_t op) { return op == kBumpEnvMap || op == kBumpEnvMapLuminance; }

bool op_reads_texture(uint32_t op, std::array<uint32_t, 3> args) {
    if (op == kBlendTextureAlpha || op == kBlendTextureAlphaPm) return true;
    const bool arg0 = op == kMultiplyAdd || op == kLerp;
    const bool arg2 = op != kSelectArg1 && op != kPremodulate;
    const bool arg1 = op != kSelectArg2;
    return (arg0 && (args[0] & kTaSelectMask) == kTaTexture) || (arg1 && (args[1] & kTaSelectMask) == kTaTexture) ||
           (arg2 && (args[2] & kTaSelectMask) == kTaTexture);
}

std::optional<std::string> check_op(unsigned stage, const char* which, uint32_t op) {
    const std::string where = "texture stage " + std::to_string(stage) + " " + which + " ";
    if (op < kDisable || op > kLerp) return where + std::to_string(op) + " is not a D3DTEXTUREOP";
    if (is_bump(op) && std::string(which) == "ALPHAOP")
        return where + "BUMPENVMAP/BUMPENVMAPLUMINANCE is a colour operation only";
    return std::nullopt;
}
std::optional<std::string> check_arg(unsigned stage, uint32_t arg) {
    if ((arg & kTaSelectMask) > kTaConstant || (arg & ~(kTaSelectMask | kTaComplement | kTaAlphaReplicate)) != 0)
        return "texture stage " + std::to_string(stage) + ": " + std::to_string(arg) + " is not a D3DTA argument";
    return std::nullopt;
}

}  // namespace

FixedFunctionProgram fixed_function_pixel_program(const FixedFunctionState& ff, const RenderState& rs,
                                                  const std::array<std::optional<isa::TextureType>, kMaxTextureStages>& textures) {
    const auto c = [](unsigned n, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Const, n, swizzle); };
    const auto r = [](unsigned n, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Temp, n, swizzle); };
    const auto rd = [](unsigned n, uint8_t mask = isa::kMaskAll) { return dst(RegisterType::Temp, n, mask); };
    const isa::SourceParameter diffuse = src(RegisterType::Input, 0), specular = src(RegisterType::Input, 1);

    // The stages in use: up to the first whose COLOROP is DISABLE.
    unsigned stage_count = 0;
    while (stage_count < kMaxTextureStages && ff.stages[stage_count][kTssColorOp] != kDisable) ++stage_count;
    for (unsigned s = 0; s < stage_count; ++s) {
        const auto& st = ff.stages[s];
        if (auto e = check_op(s, "COLOROP", st[kTssColorOp])) return refused(*e);
        if (auto e = check_op(s, "ALPHAOP", st[kTssAlphaOp])) return refused(*e);
        for (uint32_t type : {kTssColorArg0, kTssColorArg1, kTssColorArg2, kTssAlphaArg0, kTssAlphaArg1, kTssAlphaArg2})
            if (auto e = check_arg(s, st[type])) return refused(*e);
        if (st[kTssResultArg] != kTaCurrent && st[kTssResultArg] != kTaTemp)
            return refused("texture stage " + std::to_string(s) + ": RESULTARG must be CURRENT or TEMP");
        if (s > 0 && is_bump(ff.stages[s - 1][kTssColorOp]) && (st[kTssTextureTransformFlags] & kTtffProjected) != 0)
            return refused("texture stage " + std::to_string(s) +
                           ": a projected lookup perturbed by BUMPENVMAP is not emulated");
    }

    ProgramBuilder b(isa::ShaderType::Pixel);
    b.dcl_input(RegisterType::Input, 0);
    b.dcl_input(RegisterType::Input, 1);
    // PREMODULATE (D3DTEXTUREOP: "modulate this texture stage with the next texture stage"): the
    // stage's result is its ARG1, as SELECTARG1; the next enabled stage multiplies that result
    // (colour for COLOROP PREMODULATE, alpha for ALPHAOP PREMODULATE) by its own TEXTURE before
    // its operations read anything, whether or not they read TEXTURE. The last enabled stage has
    // no next texture: it is SELECTARG1.
    const auto premodulates = [&](unsigned s) {
        const auto& st = ff.stages[s];
        const bool color = st[kTssColorOp] == kPremodulate;
        const bool alpha = st[kTssAlphaOp] == kPremodulate && st[kTssColorOp] != kDotProduct3;
        return static_cast<uint8_t>((color ? kXYZ : 0) | (alpha ? kW : 0));
    };
    std::array<bool, kMaxTextureStages> samples{};
    for (unsigned s = 0; s < stage_count; ++s) {
        const auto& st = ff.stages[s];
        samples[s] = textures[s] &&
                     ((s > 0 && premodulates(s - 1) != 0) || is_bump(st[kTssColorOp]) || op_reads_texture(st[kTssColorOp], {st[kTssColorArg0], st[kTssColorArg1], st[kTssColorArg2]}) ||
                      (st[kTssAlphaOp] != kDisable &&
                       op_reads_texture(st[kTssAlphaOp], {st[kTssAlphaArg0], st[kTssAlphaArg1], st[kTssAlphaArg2]})));
        if (samples[s]) {
            b.dcl_input(RegisterType::Texture, s);
            b.dcl_input(RegisterType::Sampler, s, isa::DeclUsage::Position, 0, *textures[s]);
        }
    }

    std::vector<std::array<float, 4>> constants(kPcBumpRow1 + kMaxTextureStages, std::array<float, 4>{0, 0, 0, 0});
    constants[kPcTFactor] = color_of(rs.texture_factor);
    constants[kPcOne] = {1, 1, 1, 1};
    constants[kPcMinusHalf] = {-0.5f, -0.5f, -0.5f, -0.5f};
    constants[kPcFour] = {4, 4, 4, 4};
    for (unsigned s = 0; s < kMaxTextureStages; ++s) {
        const auto& st = ff.stages[s];
        constants[kPcStageConstant0 + s] = color_of(st[kTssConstant]);
        const auto f = [&](uint32_t type) { return std::bit_cast<float>(st[type]); };
        constants[kPcBumpRow0 + s] = {f(kTssBumpEnvMat00), f(kTssBumpEnvMat01), f(kTssBumpEnvLScale), 0};
        constants[kPcBumpRow1 + s] = {f(kTssBumpEnvMat10), f(kTssBumpEnvMat11), f(kTssBumpEnvLOffset), 0};
    }

    // CURRENT starts as the diffuse colour (stage 0's CURRENT is DIFFUSE), TEMP as 0.
    b.op(Opcode::Mov, rd(kRCurrent), {diffuse});
    b.op(Opcode::Mov, rd(kRTemp), {c(kPcZero)});

    for (unsigned s = 0; s < stage_count; ++s) {
        const auto& st = ff.stages[s];
        // A stage without a texture reads TEXTURE as opaque white: D3D9's default stage 0
        // (MODULATE TEXTURE, CURRENT) draws an untextured primitive in its diffuse colour.
        const uint32_t previous_op = s > 0 ? ff.stages[s - 1][kTssColorOp] : kDisable;
        if (samples[s] && is_bump(previous_op)) {
            // After a BUMPENVMAP stage (D3D9 "Bump Mapping Formulas"; ps_1_x's texbem/texbeml):
            // (u, v) + (M00 du + M10 dv, M01 du + M11 dv), du dv = that stage's texture .rg (still
            // in the texture register), a dependent read; with LUMINANCE the result times
            // saturate(its .b LSCALE + LOFFSET).
            const unsigned row0 = kPcBumpRow0 + s - 1, row1 = kPcBumpRow1 + s - 1;
            constexpr uint8_t kSwizzleXXXX = 0x00, kSwizzleYYYY = 0x55, kSwizzleZZZZ = 0xAA;
            b.op(Opcode::Mov, rd(kRBumpCoordinate), {src(RegisterType::Texture, s)});
            b.op(Opcode::Mad, rd(kRBumpCoordinate, kXY), {r(kRTexture, kSwizzleXXXX), c(row0), r(kRBumpCoordinate)});
            b.op(Opcode::Mad, rd(kRBumpCoordinate, kXY), {r(kRTexture, kSwizzleYYYY), c(row1), r(kRBumpCoordinate)});
            if (previous_op == kBumpEnvMapLuminance)
                b.op(Opcode::Mad, dst(RegisterType::Temp, kRBumpLuminance, isa::kMaskAll, true),
                     {r(kRTexture, kSwizzleZZZZ), c(row0, kSwizzleZZZZ), c(row1, kSwizzleZZZZ)});
            b.op(Opcode::Tex, rd(kRTexture), {r(kRBumpCoordinate), src(RegisterType::Sampler, s)});
            if (previous_op == kBumpEnvMapLuminance) b.op(Opcode::Mul, rd(kRTexture), {r(kRTexture), r(kRBumpLuminance)});
        } else if (samples[s]) {
            // D3DTTFF_PROJECTED: the vertex program put the divisor in w; texldp divides by it.
            const bool projected = (st[kTssTextureTransformFlags] & kTtffProjected) != 0;
            b.op(Opcode::Tex, rd(kRTexture), {src(RegisterType::Texture, s), src(RegisterType::Sampler, s)},
                 projected ? isa::kTexLdProject : 0);
        } else {
            b.op(Opcode::Mov, rd(kRTexture), {c(kPcOne)});
        }
        if (const uint8_t mask = s > 0 ? premodulates(s - 1) : uint8_t{0}; mask != 0) {
            // The previous stage's PREMODULATE: its result times this stage's TEXTURE (1 when no
            // texture is bound, which leaves it as it is).
            const unsigned previous = ff.stages[s - 1][kTssResultArg] == kTaTemp ? kRTemp : kRCurrent;
            if (samples[s]) b.op(Opcode::Mul, rd(previous, mask), {r(previous), r(kRTexture)});
        }
        const unsigned result = st[kTssResultArg] == kTaTemp ? kRTemp : kRCurrent;

        // One operation (colour: mask .xyz, alpha: .w) into `result`.
        auto emit = [&](uint32_t op, std::array<uint32_t, 3> arg_values, uint8_t mask, bool alpha) {
            // The arguments, with COMPLEMENT (1 - x) and ALPHAREPLICATE (x.aaaa) applied.
            std::array<isa::SourceParameter, 3> a;
            for (unsigned i = 0; i < 3; ++i) {
                const uint32_t v = arg_values[i];
                isa::SourceParameter base;
                switch (v & kTaSelectMask) {
                case kTaDiffuse: base = diffuse; break;
                case kTaCurrent: base = r(kRCurrent); break;
                case kTaTexture: base = r(kRTexture); break;
                case kTaTFactor: base = c(kPcTFactor); break;
                case kTaSpecular: base = specular; break;
                case kTaTemp: base = r(kRTemp); break;
                default: base = c(kPcStageConstant0 + s); break;
                }
                if (v & kTaAlphaReplicate || alpha) base = alpha_of(base);
                if (v & kTaComplement) {
                    b.op(Opcode::Add, rd(kRArgFirst + i, mask), {c(kPcOne), negated(base)});
                    base = r(kRArgFirst + i);
                }
                a[i] = base;
            }
            const auto out = dst(RegisterType::Temp, result, mask, true);
            const auto tmp = rd(kRScratch, mask);
            const isa::SourceParameter t = r(kRScratch);
            switch (op) {
            case kSelectArg1:
            case kPremodulate: b.op(Opcode::Mov, out, {a[1]}); break;
            case kSelectArg2: b.op(Opcode::Mov, out, {a[2]}); break;
            case kModulate: b.op(Opcode::Mul, out, {a[1], a[2]}); break;
            case kModulate2x:
                b.op(Opcode::Mul, tmp, {a[1], a[2]});
                b.op(Opcode::Add, out, {t, t});
                break;
            case kModulate4x:
                b.op(Opcode::Mul, tmp, {a[1], a[2]});
                b.op(Opcode::Mul, out, {t, c(kPcFour)});
                break;
            case kAdd: b.op(Opcode::Add, out, {a[1], a[2]}); break;
            case kAddSigned:
                b.op(Opcode::Add, tmp, {a[1], a[2]});
                b.op(Opcode::Add, out, {t, c(kPcMinusHalf)});
                break;
            case kAddSigned2x:
                b.op(Opcode::Add, tmp, {a[1], a[2]});
                b.op(Opcode::Add, tmp, {t, c(kPcMinusHalf)});
                b.op(Opcode::Add, out, {t, t});
                break;
            case kSubtract: b.op(Opcode::Add, out, {a[1], negated(a[2])}); break;
            case kAddSmooth:  // a1 + a2 - a1 a2 = a1 + a2 (1 - a1)
                b.op(Opcode::Mad, tmp, {negated(a[1]), a[2], a[2]});
                b.op(Opcode::Add, out, {t, a[1]});
                break;
            case kBlendDiffuseAlpha: b.op(Opcode::Lrp, out, {alpha_of(diffuse), a[1], a[2]}); break;
            case kBlendTextureAlpha: b.op(Opcode::Lrp, out, {r(kRTexture, kSwizzleW), a[1], a[2]}); break;
            case kBlendFactorAlpha: b.op(Opcode::Lrp, out, {c(kPcTFactor, kSwizzleW), a[1], a[2]}); break;
            case kBlendCurrentAlpha: b.op(Opcode::Lrp, out, {r(kRCurrent, kSwizzleW), a[1], a[2]}); break;
            case kBlendTextureAlphaPm:  // a1 + a2 (1 - texture alpha)
                b.op(Opcode::Add, rd(kRScratch2, mask), {c(kPcOne), negated(r(kRTexture, kSwizzleW))});
                b.op(Opcode::Mad, out, {a[2], r(kRScratch2), a[1]});
                break;
            case kModulateAlphaAddColor:  // a1.rgb + a1.a a2.rgb (alpha op: as MODULATE, D3D9 has none)
                if (alpha) b.op(Opcode::Mul, out, {a[1], a[2]});
                else b.op(Opcode::Mad, out, {alpha_of(a[1]), a[2], a[1]});
                break;
            case kModulateColorAddAlpha:  // a1.rgb a2.rgb + a1.a
                if (alpha) b.op(Opcode::Mul, out, {a[1], a[2]});
                else b.op(Opcode::Mad, out, {a[1], a[2], alpha_of(a[1])});
                break;
            case kModulateInvAlphaAddColor:  // (1 - a1.a) a2.rgb + a1.rgb
                b.op(Opcode::Add, rd(kRScratch2, mask), {c(kPcOne), negated(alpha_of(a[1]))});
                b.op(Opcode::Mad, out, {r(kRScratch2), a[2], a[1]});
                break;
            case kModulateInvColorAddAlpha:  // (1 - a1.rgb) a2.rgb + a1.a
                b.op(Opcode::Add, rd(kRScratch2, mask), {c(kPcOne), negated(a[1])});
                b.op(Opcode::Mad, out, {r(kRScratch2), a[2], alpha_of(a[1])});
                break;
            case kDotProduct3: {  // 4 ((a1 - 0.5) . (a2 - 0.5)) in every channel, alpha too
                b.op(Opcode::Add, rd(kRScratch), {a[1], c(kPcMinusHalf)});
                b.op(Opcode::Add, rd(kRScratch2), {a[2], c(kPcMinusHalf)});
                b.op(Opcode::Dp3, rd(kRScratch), {t, r(kRScratch2)});
                b.op(Opcode::Mul, dst(RegisterType::Temp, result, alpha ? kW : isa::kMaskAll, true), {t, c(kPcFour)});
                break;
            }
            case kMultiplyAdd: b.op(Opcode::Mad, out, {a[1], a[2], a[0]}); break;
            case kLerp: b.op(Opcode::Lrp, out, {a[0], a[1], a[2]}); break;
            default: break;
            }
        };
        const uint32_t color_op = st[kTssColorOp], alpha_op = st[kTssAlphaOp];
        // A BUMPENVMAP stage's colour operation only perturbs the next stage's lookup: CURRENT's
        // colour stays (its alpha operation runs as any other).
        if (!is_bump(color_op)) emit(color_op, {st[kTssColorArg0], st[kTssColorArg1], st[kTssColorArg2]}, kXYZ, false);
        // DOTPRODUCT3 as the colour operation sets alpha too (D3D9: "the result is replicated
        // to all four channels"); a disabled alpha operation keeps the previous alpha.
        if (color_op != kDotProduct3 && alpha_op != kDisable)
            emit(alpha_op, {st[kTssAlphaArg0], st[kTssAlphaArg1], st[kTssAlphaArg2]}, kW, true);
    }
    // SPECULARENABLE: the specular colour is added after the last stage, not clamped before the
    // fog blend (the target's conversion clamps): what Wine does; clamping here put 6598 pixels
    // of ff_lit_cube's frame 2 up to 16/255 off Wine's where fog blends a sum above 1.
    if (rs.specular_enable) b.op(Opcode::Add, dst(RegisterType::Temp, kRCurrent, kXYZ, false), {r(kRCurrent), specular});
    b.op(Opcode::Mov, dst(RegisterType::ColorOut, 0), {r(kRCurrent)});
    return std::move(b).finish(std::move(constants));
}

}  // namespace sm2::runtime
