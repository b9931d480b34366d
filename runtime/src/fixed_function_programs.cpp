// Fixed-function processing as generated programs (fixed_function_programs.h). The formulas are
// D3D9's (docs/fixed-function.md lists each with its source); only SM2 operations are used, so
// the engine's rules (precision, saturation, sampling) apply to them as to any shader.
#include "fixed_function_programs.h"

#include <algorithm>

namespace sm2::runtime {

namespace {

using isa::Opcode;
using isa::RegisterType;
using isa::SourceModifier;

constexpr uint8_t kXYZ = 0x7, kW = 0x8, kXY = 0x3, kZ = 0x4;
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
constexpr uint8_t kUsagePosition = 0, kUsageTexCoord = 5, kUsagePositionT = 9, kUsageColor = 10;

// Vertex program input registers.
constexpr unsigned kInPosition = 0, kInDiffuse = 1, kInSpecular = 2, kInTexCoord0 = 3;
// Vertex program constants.
constexpr unsigned kVcTransform = 0;      // c0..c3: (world x view x projection) transposed, or
                                          // c0: the XYZRHW screen -> clip mapping
constexpr unsigned kVcDefaultDiffuse = 4;  // (1, 1, 1, 1)
constexpr unsigned kVcDefaultSpecular = 5; // (0, 0, 0, 0)
constexpr unsigned kVcOne = 6;             // (1, 1, 1, 1)

}  // namespace

FixedFunctionProgram fixed_function_vertex_program(const FixedFunctionState& ff, const RenderState& rs, bool lighting,
                                                   uint32_t vertex_blend, const Viewport& viewport,
                                                   std::span<const VertexElement> declaration) {
    bool has_position = false, pretransformed = false, has_diffuse = false, has_specular = false;
    std::array<bool, 8> has_texcoord{};
    for (const auto& e : declaration) {
        if (e.usage == kUsagePosition && e.usage_index == 0) has_position = true;
        if (e.usage == kUsagePositionT && e.usage_index == 0) has_position = pretransformed = true;
        if (e.usage == kUsageColor && e.usage_index == 0) has_diffuse = true;
        if (e.usage == kUsageColor && e.usage_index == 1) has_specular = true;
        if (e.usage == kUsageTexCoord && e.usage_index < 8) has_texcoord[e.usage_index] = true;
    }
    if (!has_position) return refused("fixed-function vertex processing: the declaration has no POSITION or POSITIONT 0");
    if (!pretransformed) {
        if (lighting) return refused("fixed-function lighting is not emulated yet (set LIGHTING FALSE)");
        if (vertex_blend != 0) return refused("fixed-function vertex blending is not emulated");
    }
    const bool vertex_fog = rs.fog_enable && rs.fog_table_mode == FogMode::None;
    if (vertex_fog && !pretransformed && rs.fog_vertex_mode != FogMode::None)
        return refused("fixed-function vertex fog (FOGVERTEXMODE) is not emulated yet");
    for (unsigned s = 0; s < kMaxTextureStages; ++s) {
        const uint32_t tci = ff.stages[s][kTssTexCoordIndex];
        if (tci >> 16 != 0)
            return refused("texture stage " + std::to_string(s) +
                           ": TEXCOORDINDEX texture coordinate generation is not emulated yet");
        if ((tci & 0xFFFF) >= 8)
            return refused("texture stage " + std::to_string(s) + ": TEXCOORDINDEX " + std::to_string(tci & 0xFFFF) +
                           " is not a texture coordinate set (0..7)");
        if (ff.stages[s][kTssTextureTransformFlags] != 0 && !pretransformed)
            return refused("texture stage " + std::to_string(s) +
                           ": TEXTURETRANSFORMFLAGS (texture transforms, projection) are not emulated yet");
    }

    ProgramBuilder b(isa::ShaderType::Vertex);
    const auto in = [](unsigned r, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Input, r, swizzle); };
    const auto c = [](unsigned r, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Const, r, swizzle); };
    const auto r = [](unsigned n, uint8_t swizzle = isa::kSwizzleIdentity) { return src(RegisterType::Temp, n, swizzle); };
    b.dcl_input(RegisterType::Input, kInPosition, pretransformed ? isa::DeclUsage::PositionT : isa::DeclUsage::Position);
    if (has_diffuse) b.dcl_input(RegisterType::Input, kInDiffuse, isa::DeclUsage::Color, 0);
    if (has_specular) b.dcl_input(RegisterType::Input, kInSpecular, isa::DeclUsage::Color, 1);
    for (unsigned t = 0; t < 8; ++t)
        if (has_texcoord[t])
            b.dcl_input(RegisterType::Input, kInTexCoord0 + t, isa::DeclUsage::TexCoord, static_cast<uint8_t>(t));

    std::vector<std::array<float, 4>> constants(kVcOne + 1, std::array<float, 4>{0, 0, 0, 0});
    constants[kVcDefaultDiffuse] = {1, 1, 1, 1};
    constants[kVcOne] = {1, 1, 1, 1};
    const auto o_pos = [](uint8_t mask) { return dst(RegisterType::RastOut, 0, mask); };
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
    } else {
        // Row vectors: p' = p (World View Projection); m4x4 takes dot products with rows c0..c3,
        // so the constants hold the product's columns.
        const Matrix4 wvp = multiply(multiply(ff.world[0], ff.view), ff.projection);
        for (unsigned row = 0; row < 4; ++row)
            for (unsigned col = 0; col < 4; ++col) constants[kVcTransform + row][col] = wvp[col * 4 + row];
        b.op(Opcode::M4x4, o_pos(isa::kMaskAll), {in(kInPosition), c(kVcTransform)});
    }
    // Lighting off: the vertex colours as given, D3D9's defaults where the vertex has none
    // (diffuse opaque white, specular 0).
    b.op(Opcode::Mov, dst(RegisterType::AttrOut, 0), {has_diffuse ? in(kInDiffuse) : c(kVcDefaultDiffuse)});
    b.op(Opcode::Mov, dst(RegisterType::AttrOut, 1), {has_specular ? in(kInSpecular) : c(kVcDefaultSpecular)});
    for (unsigned s = 0; s < kMaxTextureStages; ++s) {
        const uint32_t set = ff.stages[s][kTssTexCoordIndex] & 0xFFFF;
        if (has_texcoord[set]) b.op(Opcode::Mov, dst(RegisterType::TexCrdOut, s), {in(kInTexCoord0 + set)});
    }
    // FOGVERTEXMODE NONE: the fog factor is the specular colour's alpha (D3D9, "Vertex Fog");
    // with no specular in the vertex, no fog (factor 1).
    if (vertex_fog)
        b.op(Opcode::Mov, dst(RegisterType::RastOut, 1, 0x1),
             {has_specular ? in(kInSpecular, kSwizzleW) : c(kVcOne, kSwizzleW)});
    return std::move(b).finish(std::move(constants));
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
constexpr unsigned kRCurrent = 0, kRTemp = 1, kRTexture = 2, kRArgFirst = 3, kRScratch = 6, kRScratch2 = 7;
constexpr unsigned kPcTFactor = 0, kPcOne = 1, kPcMinusHalf = 2, kPcFour = 3, kPcStageConstant0 = 4,
                   kPcZero = kPcStageConstant0 + kMaxTextureStages;

bool op_reads_texture(uint32_t op, std::array<uint32_t, 3> args) {
    if (op == kBlendTextureAlpha || op == kBlendTextureAlphaPm) return true;
    const bool arg0 = op == kMultiplyAdd || op == kLerp;
    const bool arg2 = op != kSelectArg1;
    const bool arg1 = op != kSelectArg2;
    return (arg0 && (args[0] & kTaSelectMask) == kTaTexture) || (arg1 && (args[1] & kTaSelectMask) == kTaTexture) ||
           (arg2 && (args[2] & kTaSelectMask) == kTaTexture);
}

std::optional<std::string> check_op(unsigned stage, const char* which, uint32_t op) {
    const std::string where = "texture stage " + std::to_string(stage) + " " + which + " ";
    if (op < kDisable || op > kLerp) return where + std::to_string(op) + " is not a D3DTEXTUREOP";
    if (op == kPremodulate || op == kBumpEnvMap || op == kBumpEnvMapLuminance)
        return where + (op == kPremodulate ? "PREMODULATE" : op == kBumpEnvMap ? "BUMPENVMAP" : "BUMPENVMAPLUMINANCE") +
               " is not emulated yet";
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
    }

    ProgramBuilder b(isa::ShaderType::Pixel);
    b.dcl_input(RegisterType::Input, 0);
    b.dcl_input(RegisterType::Input, 1);
    std::array<bool, kMaxTextureStages> samples{};
    for (unsigned s = 0; s < stage_count; ++s) {
        const auto& st = ff.stages[s];
        samples[s] = textures[s] &&
                     (op_reads_texture(st[kTssColorOp], {st[kTssColorArg0], st[kTssColorArg1], st[kTssColorArg2]}) ||
                      (st[kTssAlphaOp] != kDisable &&
                       op_reads_texture(st[kTssAlphaOp], {st[kTssAlphaArg0], st[kTssAlphaArg1], st[kTssAlphaArg2]})));
        if (samples[s]) {
            b.dcl_input(RegisterType::Texture, s);
            b.dcl_input(RegisterType::Sampler, s, isa::DeclUsage::Position, 0, *textures[s]);
        }
    }

    std::vector<std::array<float, 4>> constants(kPcZero + 1, std::array<float, 4>{0, 0, 0, 0});
    constants[kPcTFactor] = color_of(rs.texture_factor);
    constants[kPcOne] = {1, 1, 1, 1};
    constants[kPcMinusHalf] = {-0.5f, -0.5f, -0.5f, -0.5f};
    constants[kPcFour] = {4, 4, 4, 4};
    for (unsigned s = 0; s < kMaxTextureStages; ++s) constants[kPcStageConstant0 + s] = color_of(ff.stages[s][kTssConstant]);

    // CURRENT starts as the diffuse colour (stage 0's CURRENT is DIFFUSE), TEMP as 0.
    b.op(Opcode::Mov, rd(kRCurrent), {diffuse});
    b.op(Opcode::Mov, rd(kRTemp), {c(kPcZero)});

    for (unsigned s = 0; s < stage_count; ++s) {
        const auto& st = ff.stages[s];
        // A stage without a texture reads TEXTURE as opaque white: D3D9's default stage 0
        // (MODULATE TEXTURE, CURRENT) draws an untextured primitive in its diffuse colour.
        if (samples[s]) {
            b.op(Opcode::Tex, rd(kRTexture), {src(RegisterType::Texture, s), src(RegisterType::Sampler, s)});
        } else {
            b.op(Opcode::Mov, rd(kRTexture), {c(kPcOne)});
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
            case kSelectArg1: b.op(Opcode::Mov, out, {a[1]}); break;
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
        emit(color_op, {st[kTssColorArg0], st[kTssColorArg1], st[kTssColorArg2]}, kXYZ, false);
        // DOTPRODUCT3 as the colour operation sets alpha too (D3D9: "the result is replicated
        // to all four channels"); a disabled alpha operation keeps the previous alpha.
        if (color_op != kDotProduct3 && alpha_op != kDisable)
            emit(alpha_op, {st[kTssAlphaArg0], st[kTssAlphaArg1], st[kTssAlphaArg2]}, kW, true);
    }
    // SPECULARENABLE: the specular colour is added after the last stage.
    if (rs.specular_enable) b.op(Opcode::Add, dst(RegisterType::Temp, kRCurrent, kXYZ, true), {r(kRCurrent), specular});
    b.op(Opcode::Mov, dst(RegisterType::ColorOut, 0), {r(kRCurrent)});
    return std::move(b).finish(std::move(constants));
}

}  // namespace sm2::runtime
