// D3D9 enum names and values (d3d9types.h; pipeline.md §1, §2, §16-§18).
#include "sm2/runtime/d3d9_names.h"

#include <array>

namespace sm2::runtime {

namespace {

using F = EnumFamily;
using K = StateValueKind;

struct Name {
    uint32_t value;
    std::string_view name;
};

struct Family {
    EnumFamily family;
    std::string_view prefix;
    std::span<const Name> names;
    std::span<const uint32_t> fields = {};
};

constexpr Name kPrimitiveTypes[] = {{1, "POINTLIST"}, {2, "LINELIST"}, {3, "LINESTRIP"},
                                    {4, "TRIANGLELIST"}, {5, "TRIANGLESTRIP"}, {6, "TRIANGLEFAN"}};
constexpr Name kDeclTypes[] = {
    {0, "FLOAT1"}, {1, "FLOAT2"}, {2, "FLOAT3"}, {3, "FLOAT4"}, {4, "D3DCOLOR"}, {5, "UBYTE4"},
    {6, "SHORT2"}, {7, "SHORT4"}, {8, "UBYTE4N"}, {9, "SHORT2N"}, {10, "SHORT4N"},
    {11, "USHORT2N"}, {12, "USHORT4N"}, {13, "UDEC3"}, {14, "DEC3N"}, {15, "FLOAT16_2"},
    {16, "FLOAT16_4"}, {17, "UNUSED"}};
constexpr Name kDeclMethods[] = {{0, "DEFAULT"}, {1, "PARTIALU"}, {2, "PARTIALV"}, {3, "CROSSUV"},
                                 {4, "UV"}, {5, "LOOKUP"}, {6, "LOOKUPPRESAMPLED"}};
constexpr Name kDeclUsages[] = {
    {0, "POSITION"}, {1, "BLENDWEIGHT"}, {2, "BLENDINDICES"}, {3, "NORMAL"}, {4, "PSIZE"},
    {5, "TEXCOORD"}, {6, "TANGENT"}, {7, "BINORMAL"}, {8, "TESSFACTOR"}, {9, "POSITIONT"},
    {10, "COLOR"}, {11, "FOG"}, {12, "DEPTH"}, {13, "SAMPLE"}};
constexpr Name kZBufferTypes[] = {{0, "FALSE"}, {1, "TRUE"}, {2, "USEW"}};
constexpr Name kFillModes[] = {{1, "POINT"}, {2, "WIREFRAME"}, {3, "SOLID"}};
constexpr Name kShadeModes[] = {{1, "FLAT"}, {2, "GOURAUD"}, {3, "PHONG"}};
constexpr Name kBlends[] = {
    {1, "ZERO"}, {2, "ONE"}, {3, "SRCCOLOR"}, {4, "INVSRCCOLOR"}, {5, "SRCALPHA"},
    {6, "INVSRCALPHA"}, {7, "DESTALPHA"}, {8, "INVDESTALPHA"}, {9, "DESTCOLOR"},
    {10, "INVDESTCOLOR"}, {11, "SRCALPHASAT"}, {12, "BOTHSRCALPHA"}, {13, "BOTHINVSRCALPHA"},
    {14, "BLENDFACTOR"}, {15, "INVBLENDFACTOR"}, {16, "SRCCOLOR2"}, {17, "INVSRCCOLOR2"}};
constexpr Name kBlendOps[] = {{1, "ADD"}, {2, "SUBTRACT"}, {3, "REVSUBTRACT"}, {4, "MIN"}, {5, "MAX"}};
constexpr Name kCulls[] = {{1, "NONE"}, {2, "CW"}, {3, "CCW"}};
constexpr Name kCmps[] = {{1, "NEVER"}, {2, "LESS"}, {3, "EQUAL"}, {4, "LESSEQUAL"},
                          {5, "GREATER"}, {6, "NOTEQUAL"}, {7, "GREATEREQUAL"}, {8, "ALWAYS"}};
constexpr Name kStencilOps[] = {{1, "KEEP"}, {2, "ZERO"}, {3, "REPLACE"}, {4, "INCRSAT"},
                                {5, "DECRSAT"}, {6, "INVERT"}, {7, "INCR"}, {8, "DECR"}};
constexpr Name kFogModes[] = {{0, "NONE"}, {1, "EXP"}, {2, "EXP2"}, {3, "LINEAR"}};
constexpr Name kTextureAddresses[] = {{1, "WRAP"}, {2, "MIRROR"}, {3, "CLAMP"}, {4, "BORDER"},
                                      {5, "MIRRORONCE"}};
constexpr Name kTextureFilters[] = {{0, "NONE"}, {1, "POINT"}, {2, "LINEAR"}, {3, "ANISOTROPIC"},
                                    {6, "PYRAMIDALQUAD"}, {7, "GAUSSIANQUAD"}, {8, "CONVOLUTIONMONO"}};
constexpr Name kClearFlags[] = {{1, "TARGET"}, {2, "ZBUFFER"}, {4, "STENCIL"}};
constexpr Name kColorWrites[] = {{1, "RED"}, {2, "GREEN"}, {4, "BLUE"}, {8, "ALPHA"}};
constexpr Name kBools[] = {{0, "FALSE"}, {1, "TRUE"}};
constexpr Name kPools[] = {{0, "DEFAULT"}, {1, "MANAGED"}, {2, "SYSTEMMEM"}, {3, "SCRATCH"}};
constexpr Name kStateBlockTypes[] = {{1, "ALL"}, {2, "PIXELSTATE"}, {3, "VERTEXSTATE"}};
constexpr Name kCubeFaces[] = {{0, "POSITIVE_X"}, {1, "NEGATIVE_X"}, {2, "POSITIVE_Y"},
                               {3, "NEGATIVE_Y"}, {4, "POSITIVE_Z"}, {5, "NEGATIVE_Z"}};

constexpr Name kTransformStates[] = {
    {2, "VIEW"}, {3, "PROJECTION"}, {16, "TEXTURE0"}, {17, "TEXTURE1"}, {18, "TEXTURE2"}, {19, "TEXTURE3"},
    {20, "TEXTURE4"}, {21, "TEXTURE5"}, {22, "TEXTURE6"}, {23, "TEXTURE7"},
    {256, "WORLD"}, {257, "WORLD1"}, {258, "WORLD2"}, {259, "WORLD3"}};
constexpr Name kLightTypes[] = {{1, "POINT"}, {2, "SPOT"}, {3, "DIRECTIONAL"}};
constexpr Name kTextureOps[] = {
    {1, "DISABLE"}, {2, "SELECTARG1"}, {3, "SELECTARG2"}, {4, "MODULATE"},
    {5, "MODULATE2X"}, {6, "MODULATE4X"}, {7, "ADD"}, {8, "ADDSIGNED"},
    {9, "ADDSIGNED2X"}, {10, "SUBTRACT"}, {11, "ADDSMOOTH"}, {12, "BLENDDIFFUSEALPHA"},
    {13, "BLENDTEXTUREALPHA"}, {14, "BLENDFACTORALPHA"}, {15, "BLENDTEXTUREALPHAPM"}, {16, "BLENDCURRENTALPHA"},
    {17, "PREMODULATE"}, {18, "MODULATEALPHA_ADDCOLOR"}, {19, "MODULATECOLOR_ADDALPHA"}, {20, "MODULATEINVALPHA_ADDCOLOR"},
    {21, "MODULATEINVCOLOR_ADDALPHA"}, {22, "BUMPENVMAP"}, {23, "BUMPENVMAPLUMINANCE"}, {24, "DOTPRODUCT3"},
    {25, "MULTIPLYADD"}, {26, "LERP"},
};
constexpr Name kTextureArgs[] = {{0, "DIFFUSE"}, {1, "CURRENT"}, {2, "TEXTURE"}, {3, "TFACTOR"}, {4, "SPECULAR"},
                                 {5, "TEMP"}, {6, "CONSTANT"}, {0x10, "COMPLEMENT"}, {0x20, "ALPHAREPLICATE"}};
constexpr Name kTexCoordIndexes[] = {{0, "PASSTHRU"}, {0x10000, "CAMERASPACENORMAL"}, {0x20000, "CAMERASPACEPOSITION"},
                                     {0x30000, "CAMERASPACEREFLECTIONVECTOR"}, {0x40000, "SPHEREMAP"}};
constexpr Name kTextureTransforms[] = {{0, "DISABLE"}, {1, "COUNT1"}, {2, "COUNT2"}, {3, "COUNT3"}, {4, "COUNT4"},
                                       {0x100, "PROJECTED"}};
// D3DFVF_TEXCOORDSIZEn(k) is written TEXCOORDSIZEn_k.
constexpr Name kFvfs[] = {
    {0x002, "XYZ"}, {0x004, "XYZRHW"}, {0x006, "XYZB1"}, {0x008, "XYZB2"},
    {0x00A, "XYZB3"}, {0x00C, "XYZB4"}, {0x00E, "XYZB5"}, {0x4002, "XYZW"},
    {0x010, "NORMAL"}, {0x020, "PSIZE"}, {0x040, "DIFFUSE"}, {0x080, "SPECULAR"},
    {0x0, "TEX0"}, {0x100, "TEX1"}, {0x200, "TEX2"}, {0x300, "TEX3"},
    {0x400, "TEX4"}, {0x500, "TEX5"}, {0x600, "TEX6"}, {0x700, "TEX7"},
    {0x800, "TEX8"}, {0x1000, "LASTBETA_UBYTE4"}, {0x8000, "LASTBETA_D3DCOLOR"}, {0x30000, "TEXCOORDSIZE1_0"},
    {0x0, "TEXCOORDSIZE2_0"}, {0x10000, "TEXCOORDSIZE3_0"}, {0x20000, "TEXCOORDSIZE4_0"}, {0xC0000, "TEXCOORDSIZE1_1"},
    {0x0, "TEXCOORDSIZE2_1"}, {0x40000, "TEXCOORDSIZE3_1"}, {0x80000, "TEXCOORDSIZE4_1"}, {0x300000, "TEXCOORDSIZE1_2"},
    {0x0, "TEXCOORDSIZE2_2"}, {0x100000, "TEXCOORDSIZE3_2"}, {0x200000, "TEXCOORDSIZE4_2"}, {0xC00000, "TEXCOORDSIZE1_3"},
    {0x0, "TEXCOORDSIZE2_3"}, {0x400000, "TEXCOORDSIZE3_3"}, {0x800000, "TEXCOORDSIZE4_3"}, {0x3000000, "TEXCOORDSIZE1_4"},
    {0x0, "TEXCOORDSIZE2_4"}, {0x1000000, "TEXCOORDSIZE3_4"}, {0x2000000, "TEXCOORDSIZE4_4"}, {0xC000000, "TEXCOORDSIZE1_5"},
    {0x0, "TEXCOORDSIZE2_5"}, {0x4000000, "TEXCOORDSIZE3_5"}, {0x8000000, "TEXCOORDSIZE4_5"}, {0x30000000, "TEXCOORDSIZE1_6"},
    {0x0, "TEXCOORDSIZE2_6"}, {0x10000000, "TEXCOORDSIZE3_6"}, {0x20000000, "TEXCOORDSIZE4_6"}, {0xC0000000, "TEXCOORDSIZE1_7"},
    {0x0, "TEXCOORDSIZE2_7"}, {0x40000000, "TEXCOORDSIZE3_7"}, {0x80000000, "TEXCOORDSIZE4_7"},
};

// Fields of the bit families: a name whose value lies inside a field is one choice of it (D3DTA's
// selector, the FVF's position type); every other name is a single bit.
constexpr uint32_t kTextureArgFields[] = {0xF};
constexpr uint32_t kTexCoordIndexFields[] = {0xFFFF0000u};
constexpr uint32_t kTextureTransformFields[] = {0xFF};
constexpr uint32_t kFvfFields[] = {0x400E, 0xF00, 3u << 16, 3u << 18, 3u << 20, 3u << 22,
                                   3u << 24, 3u << 26, 3u << 28, 3u << 30};

// clang-format off
constexpr StateInfo kRenderStates[] = {
    {7, "ZENABLE", K::Enum, F::ZBufferType},       {8, "FILLMODE", K::Enum, F::FillMode},
    {9, "SHADEMODE", K::Enum, F::ShadeMode},       {14, "ZWRITEENABLE", K::Bool, F::Bool},
    {15, "ALPHATESTENABLE", K::Bool, F::Bool},     {16, "LASTPIXEL", K::Bool, F::Bool},
    {19, "SRCBLEND", K::Enum, F::Blend},           {20, "DESTBLEND", K::Enum, F::Blend},
    {22, "CULLMODE", K::Enum, F::Cull},            {23, "ZFUNC", K::Enum, F::Cmp},
    {24, "ALPHAREF", K::Integer, F::Bool},         {25, "ALPHAFUNC", K::Enum, F::Cmp},
    {26, "DITHERENABLE", K::Bool, F::Bool},        {27, "ALPHABLENDENABLE", K::Bool, F::Bool},
    {28, "FOGENABLE", K::Bool, F::Bool},           {29, "SPECULARENABLE", K::Bool, F::Bool},
    {34, "FOGCOLOR", K::Color, F::Bool},           {35, "FOGTABLEMODE", K::Enum, F::FogMode},
    {36, "FOGSTART", K::Float, F::Bool},           {37, "FOGEND", K::Float, F::Bool},
    {38, "FOGDENSITY", K::Float, F::Bool},         {48, "RANGEFOGENABLE", K::Bool, F::Bool},
    {52, "STENCILENABLE", K::Bool, F::Bool},       {53, "STENCILFAIL", K::Enum, F::StencilOp},
    {54, "STENCILZFAIL", K::Enum, F::StencilOp},   {55, "STENCILPASS", K::Enum, F::StencilOp},
    {56, "STENCILFUNC", K::Enum, F::Cmp},          {57, "STENCILREF", K::Integer, F::Bool},
    {58, "STENCILMASK", K::Bits, F::Bool},         {59, "STENCILWRITEMASK", K::Bits, F::Bool},
    {60, "TEXTUREFACTOR", K::Color, F::Bool},
    {128, "WRAP0", K::Bits, F::Bool}, {129, "WRAP1", K::Bits, F::Bool}, {130, "WRAP2", K::Bits, F::Bool},
    {131, "WRAP3", K::Bits, F::Bool}, {132, "WRAP4", K::Bits, F::Bool}, {133, "WRAP5", K::Bits, F::Bool},
    {134, "WRAP6", K::Bits, F::Bool}, {135, "WRAP7", K::Bits, F::Bool},
    {136, "CLIPPING", K::Bool, F::Bool},           {137, "LIGHTING", K::Bool, F::Bool, true},
    {139, "AMBIENT", K::Color, F::Bool, true},           {140, "FOGVERTEXMODE", K::Enum, F::FogMode},
    {141, "COLORVERTEX", K::Bool, F::Bool, true},        {142, "LOCALVIEWER", K::Bool, F::Bool, true},
    {143, "NORMALIZENORMALS", K::Bool, F::Bool, true},
    {145, "DIFFUSEMATERIALSOURCE", K::Integer, F::Bool, true},
    {146, "SPECULARMATERIALSOURCE", K::Integer, F::Bool, true},
    {147, "AMBIENTMATERIALSOURCE", K::Integer, F::Bool, true},
    {148, "EMISSIVEMATERIALSOURCE", K::Integer, F::Bool, true},
    {151, "VERTEXBLEND", K::Integer, F::Bool, true},    {152, "CLIPPLANEENABLE", K::Bits, F::Bool},
    {154, "POINTSIZE", K::Float, F::Bool},         {155, "POINTSIZE_MIN", K::Float, F::Bool},
    {156, "POINTSPRITEENABLE", K::Bool, F::Bool},  {157, "POINTSCALEENABLE", K::Bool, F::Bool},
    {158, "POINTSCALE_A", K::Float, F::Bool},      {159, "POINTSCALE_B", K::Float, F::Bool},
    {160, "POINTSCALE_C", K::Float, F::Bool},      {161, "MULTISAMPLEANTIALIAS", K::Bool, F::Bool},
    {162, "MULTISAMPLEMASK", K::Bits, F::Bool},    {163, "PATCHEDGESTYLE", K::Integer, F::Bool, true},
    {165, "DEBUGMONITORTOKEN", K::Integer, F::Bool, true}, {166, "POINTSIZE_MAX", K::Float, F::Bool},
    {167, "INDEXEDVERTEXBLENDENABLE", K::Bool, F::Bool, true},
    {168, "COLORWRITEENABLE", K::Bits, F::ColorWrite}, {170, "TWEENFACTOR", K::Float, F::Bool, true},
    {171, "BLENDOP", K::Enum, F::BlendOp},
    {172, "POSITIONDEGREE", K::Integer, F::Bool, true}, {173, "NORMALDEGREE", K::Integer, F::Bool, true},
    {174, "SCISSORTESTENABLE", K::Bool, F::Bool},  {175, "SLOPESCALEDEPTHBIAS", K::Float, F::Bool},
    {176, "ANTIALIASEDLINEENABLE", K::Bool, F::Bool},
    {178, "MINTESSELLATIONLEVEL", K::Float, F::Bool, true}, {179, "MAXTESSELLATIONLEVEL", K::Float, F::Bool, true},
    {180, "ADAPTIVETESS_X", K::Float, F::Bool, true}, {181, "ADAPTIVETESS_Y", K::Float, F::Bool, true},
    {182, "ADAPTIVETESS_Z", K::Float, F::Bool, true}, {183, "ADAPTIVETESS_W", K::Float, F::Bool, true},
    {184, "ENABLEADAPTIVETESSELLATION", K::Bool, F::Bool, true},
    {185, "TWOSIDEDSTENCILMODE", K::Bool, F::Bool},
    {186, "CCW_STENCILFAIL", K::Enum, F::StencilOp}, {187, "CCW_STENCILZFAIL", K::Enum, F::StencilOp},
    {188, "CCW_STENCILPASS", K::Enum, F::StencilOp}, {189, "CCW_STENCILFUNC", K::Enum, F::Cmp},
    {190, "COLORWRITEENABLE1", K::Bits, F::ColorWrite}, {191, "COLORWRITEENABLE2", K::Bits, F::ColorWrite},
    {192, "COLORWRITEENABLE3", K::Bits, F::ColorWrite}, {193, "BLENDFACTOR", K::Color, F::Bool},
    {194, "SRGBWRITEENABLE", K::Bool, F::Bool},    {195, "DEPTHBIAS", K::Float, F::Bool},
    {198, "WRAP8", K::Bits, F::Bool}, {199, "WRAP9", K::Bits, F::Bool}, {200, "WRAP10", K::Bits, F::Bool},
    {201, "WRAP11", K::Bits, F::Bool}, {202, "WRAP12", K::Bits, F::Bool}, {203, "WRAP13", K::Bits, F::Bool},
    {204, "WRAP14", K::Bits, F::Bool}, {205, "WRAP15", K::Bits, F::Bool},
    {206, "SEPARATEALPHABLENDENABLE", K::Bool, F::Bool}, {207, "SRCBLENDALPHA", K::Enum, F::Blend},
    {208, "DESTBLENDALPHA", K::Enum, F::Blend},    {209, "BLENDOPALPHA", K::Enum, F::BlendOp},
};

constexpr StateInfo kSamplerStates[] = {
    {1, "ADDRESSU", K::Enum, F::TextureAddress},  {2, "ADDRESSV", K::Enum, F::TextureAddress},
    {3, "ADDRESSW", K::Enum, F::TextureAddress},  {4, "BORDERCOLOR", K::Color, F::Bool},
    {5, "MAGFILTER", K::Enum, F::TextureFilter},  {6, "MINFILTER", K::Enum, F::TextureFilter},
    {7, "MIPFILTER", K::Enum, F::TextureFilter},  {8, "MIPMAPLODBIAS", K::Float, F::Bool},
    {9, "MAXMIPLEVEL", K::Integer, F::Bool},      {10, "MAXANISOTROPY", K::Integer, F::Bool},
    {11, "SRGBTEXTURE", K::Bool, F::Bool},        {12, "ELEMENTINDEX", K::Integer, F::Bool},
    {13, "DMAPOFFSET", K::Integer, F::Bool},
};

constexpr StateInfo kTextureStageStates[] = {
    {1, "COLOROP", K::Enum, F::TextureOp},           {2, "COLORARG1", K::Bits, F::TextureArg},
    {3, "COLORARG2", K::Bits, F::TextureArg},        {4, "ALPHAOP", K::Enum, F::TextureOp},
    {5, "ALPHAARG1", K::Bits, F::TextureArg},        {6, "ALPHAARG2", K::Bits, F::TextureArg},
    {7, "BUMPENVMAT00", K::Float, F::Bool},          {8, "BUMPENVMAT01", K::Float, F::Bool},
    {9, "BUMPENVMAT10", K::Float, F::Bool},          {10, "BUMPENVMAT11", K::Float, F::Bool},
    {11, "TEXCOORDINDEX", K::Bits, F::TexCoordIndex}, {22, "BUMPENVLSCALE", K::Float, F::Bool},
    {23, "BUMPENVLOFFSET", K::Float, F::Bool},       {24, "TEXTURETRANSFORMFLAGS", K::Bits, F::TextureTransform},
    {26, "COLORARG0", K::Bits, F::TextureArg},       {27, "ALPHAARG0", K::Bits, F::TextureArg},
    {28, "RESULTARG", K::Bits, F::TextureArg},       {32, "CONSTANT", K::Color, F::Bool},
};
// clang-format on

constexpr std::array<Name, 0> kNoNames{};

const Family kFamilies[] = {
    {F::RenderState, "D3DRS_", kNoNames},
    {F::SamplerState, "D3DSAMP_", kNoNames},
    {F::PrimitiveType, "D3DPT_", kPrimitiveTypes},
    {F::DeclType, "D3DDECLTYPE_", kDeclTypes},
    {F::DeclMethod, "D3DDECLMETHOD_", kDeclMethods},
    {F::DeclUsage, "D3DDECLUSAGE_", kDeclUsages},
    {F::ZBufferType, "D3DZB_", kZBufferTypes},
    {F::FillMode, "D3DFILL_", kFillModes},
    {F::ShadeMode, "D3DSHADE_", kShadeModes},
    {F::Blend, "D3DBLEND_", kBlends},
    {F::BlendOp, "D3DBLENDOP_", kBlendOps},
    {F::Cull, "D3DCULL_", kCulls},
    {F::Cmp, "D3DCMP_", kCmps},
    {F::StencilOp, "D3DSTENCILOP_", kStencilOps},
    {F::FogMode, "D3DFOG_", kFogModes},
    {F::TextureAddress, "D3DTADDRESS_", kTextureAddresses},
    {F::TextureFilter, "D3DTEXF_", kTextureFilters},
    {F::ClearFlags, "D3DCLEAR_", kClearFlags},
    {F::ColorWrite, "D3DCOLORWRITEENABLE_", kColorWrites},
    {F::CubeFace, "D3DCUBEMAP_FACE_", kCubeFaces},
    {F::Bool, "", kBools},
    {F::Pool, "D3DPOOL_", kPools},
    {F::StateBlockType, "D3DSBT_", kStateBlockTypes},
    {F::TextureStageState, "D3DTSS_", kNoNames},
    {F::TransformState, "D3DTS_", kTransformStates},
    {F::LightType, "D3DLIGHT_", kLightTypes},
    {F::TextureOp, "D3DTOP_", kTextureOps},
    {F::TextureArg, "D3DTA_", kTextureArgs, kTextureArgFields},
    {F::TexCoordIndex, "D3DTSS_TCI_", kTexCoordIndexes, kTexCoordIndexFields},
    {F::TextureTransform, "D3DTTFF_", kTextureTransforms, kTextureTransformFields},
    {F::Fvf, "D3DFVF_", kFvfs, kFvfFields},
};

const Family& family_of(EnumFamily family) {
    for (const Family& f : kFamilies)
        if (f.family == family) return f;
    return kFamilies[0];
}

std::string_view strip(std::string_view name, std::string_view prefix) {
    if (!prefix.empty() && name.substr(0, prefix.size()) == prefix) name.remove_prefix(prefix.size());
    return name;
}

const StateInfo* find_state(std::span<const StateInfo> table, std::string_view prefix,
                            std::string_view name) {
    name = strip(name, prefix);
    for (const StateInfo& s : table)
        if (s.name == name) return &s;
    return nullptr;
}

const StateInfo* find_state(std::span<const StateInfo> table, uint32_t id) {
    for (const StateInfo& s : table)
        if (s.id == id) return &s;
    return nullptr;
}

}  // namespace

std::span<const StateInfo> render_states() { return kRenderStates; }
std::span<const StateInfo> sampler_states() { return kSamplerStates; }
const StateInfo* find_render_state(std::string_view name) {
    return find_state(kRenderStates, "D3DRS_", name);
}
const StateInfo* find_render_state(uint32_t id) { return find_state(kRenderStates, id); }
const StateInfo* find_sampler_state(std::string_view name) {
    return find_state(kSamplerStates, "D3DSAMP_", name);
}
const StateInfo* find_sampler_state(uint32_t id) { return find_state(kSamplerStates, id); }
std::span<const StateInfo> texture_stage_states() { return kTextureStageStates; }
const StateInfo* find_texture_stage_state(std::string_view name) {
    return find_state(kTextureStageStates, "D3DTSS_", name);
}
const StateInfo* find_texture_stage_state(uint32_t id) { return find_state(kTextureStageStates, id); }

namespace {
constexpr std::string_view kWorldMatrix = "WORLDMATRIX";
constexpr uint32_t kWorldMatrixBase = 256, kWorldMatrixCount = 256;
}  // namespace

std::optional<uint32_t> transform_state_value(std::string_view name) {
    name = strip(name, "D3DTS_");
    for (const Name& n : kTransformStates)
        if (n.name == name) return n.value;
    if (name.substr(0, kWorldMatrix.size()) != kWorldMatrix) return std::nullopt;
    const std::string_view digits = name.substr(kWorldMatrix.size());
    if (digits.empty() || digits.size() > 3 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
    uint32_t index = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') return std::nullopt;
        index = index * 10 + static_cast<uint32_t>(c - '0');
    }
    if (index >= kWorldMatrixCount) return std::nullopt;
    return kWorldMatrixBase + index;
}

std::string transform_state_name(uint32_t value) {
    for (const Name& n : kTransformStates)
        if (n.value == value) return std::string(n.name);
    if (value >= kWorldMatrixBase && value < kWorldMatrixBase + kWorldMatrixCount)
        return std::string(kWorldMatrix) + std::to_string(value - kWorldMatrixBase);
    return {};
}

std::vector<std::string_view> enum_names(EnumFamily family) {
    std::vector<std::string_view> names;
    std::span<const StateInfo> states;
    if (family == EnumFamily::RenderState) states = kRenderStates;
    if (family == EnumFamily::SamplerState) states = kSamplerStates;
    if (family == EnumFamily::TextureStageState) states = kTextureStageStates;
    for (const StateInfo& s : states) names.push_back(s.name);
    for (const Name& n : family_of(family).names) names.push_back(n.name);
    return names;
}

std::vector<std::string> flag_names(EnumFamily family, uint32_t value) {
    const Family& f = family_of(family);
    std::vector<std::string> names;
    uint32_t covered = 0, all_fields = 0;
    for (const uint32_t field : f.fields) all_fields |= field;
    for (const uint32_t field : f.fields) {
        covered |= field;
        const uint32_t choice = value & field;
        // A family of one field names its zero choice (DIFFUSE, PASSTHRU, DISABLE); the FVF's
        // zero choices (TEX0, TEXCOORDSIZE2_k) are the absence of bits and are left out.
        if (choice == 0 && f.fields.size() > 1) continue;
        const Name* found = nullptr;
        for (const Name& n : f.names)
            if (n.value == choice && (n.value & ~field) == 0) {
                found = &n;
                break;
            }
        if (found) names.emplace_back(found->name);
        else covered &= ~field;  // no name: left in the number
    }
    uint32_t rest = value & ~covered;
    for (const Name& n : f.names) {
        const bool single_bit = n.value != 0 && (n.value & (n.value - 1)) == 0;
        if (single_bit && (n.value & all_fields) == 0 && (rest & n.value) != 0) {
            names.emplace_back(n.name);
            rest &= ~n.value;
        }
    }
    if (rest != 0 || names.empty()) names.push_back(std::to_string(rest));
    return names;
}

std::optional<uint32_t> enum_value(EnumFamily family, std::string_view name) {
    if (family == EnumFamily::RenderState) {
        const StateInfo* s = find_render_state(name);
        return s ? std::optional<uint32_t>(s->id) : std::nullopt;
    }
    if (family == EnumFamily::SamplerState) {
        const StateInfo* s = find_sampler_state(name);
        return s ? std::optional<uint32_t>(s->id) : std::nullopt;
    }
    if (family == EnumFamily::TextureStageState) {
        const StateInfo* s = find_texture_stage_state(name);
        return s ? std::optional<uint32_t>(s->id) : std::nullopt;
    }
    if (family == EnumFamily::TransformState) return transform_state_value(name);
    const Family& f = family_of(family);
    name = strip(name, f.prefix);
    for (const Name& n : f.names)
        if (n.name == name) return n.value;
    return std::nullopt;
}

std::string_view enum_name(EnumFamily family, uint32_t value) {
    if (family == EnumFamily::RenderState) {
        const StateInfo* s = find_render_state(value);
        return s ? s->name : std::string_view{};
    }
    if (family == EnumFamily::SamplerState) {
        const StateInfo* s = find_sampler_state(value);
        return s ? s->name : std::string_view{};
    }
    if (family == EnumFamily::TextureStageState) {
        const StateInfo* s = find_texture_stage_state(value);
        return s ? s->name : std::string_view{};
    }
    for (const Name& n : family_of(family).names)
        if (n.value == value) return n.name;
    return {};
}

std::string_view enum_prefix(EnumFamily family) { return family_of(family).prefix; }

}  // namespace sm2::runtime
