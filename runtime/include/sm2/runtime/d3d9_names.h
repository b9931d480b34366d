// D3D9's enum vocabulary as data: the names a command stream uses for render states, sampler
// states and their values, primitive types, declaration types, usages and methods. Names are
// matched with or without their D3D prefix ("CULLMODE" = "D3DRS_CULLMODE", "NONE" =
// "D3DCULL_NONE"), case-sensitively, as D3D9 spells them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sm2::runtime {

enum class EnumFamily : uint8_t {
    RenderState,     // D3DRS_*
    SamplerState,    // D3DSAMP_*
    PrimitiveType,   // D3DPT_*
    DeclType,        // D3DDECLTYPE_*
    DeclMethod,      // D3DDECLMETHOD_*
    DeclUsage,       // D3DDECLUSAGE_*
    ZBufferType,     // D3DZB_*
    FillMode,        // D3DFILL_*
    ShadeMode,       // D3DSHADE_*
    Blend,           // D3DBLEND_*
    BlendOp,         // D3DBLENDOP_*
    Cull,            // D3DCULL_*
    Cmp,             // D3DCMP_*
    StencilOp,       // D3DSTENCILOP_*
    FogMode,         // D3DFOG_*
    TextureAddress,  // D3DTADDRESS_*
    TextureFilter,   // D3DTEXF_*
    ClearFlags,      // D3DCLEAR_* (bits)
    ColorWrite,      // D3DCOLORWRITEENABLE_* (bits)
    CubeFace,        // D3DCUBEMAP_FACE_* (D3DCUBEMAP_FACES; texture.h's CubeFace values)
    Bool,            // TRUE / FALSE
    Pool,            // D3DPOOL_*
    StateBlockType,  // D3DSBT_*
    TextureStageState,  // D3DTSS_* (the SetTextureStageState types)
    TransformState,     // D3DTS_* (WORLDMATRIX(n) beyond WORLD3: transform_state_value/_name)
    LightType,          // D3DLIGHT_*
    TextureOp,          // D3DTOP_*
    TextureArg,         // D3DTA_* (a selector and the COMPLEMENT / ALPHAREPLICATE bits)
    TexCoordIndex,      // D3DTSS_TCI_* (a generation mode; the set index is a number beside it)
    TextureTransform,   // D3DTTFF_* (COUNTn and the PROJECTED bit)
    Fvf,                // D3DFVF_* (position type, TEXn, TEXCOORDSIZEn_SET and single bits)
};

// How the DWORD value of a render or sampler state is written in a command stream.
enum class StateValueKind : uint8_t {
    Enum,     // a name of `family`
    Bool,     // TRUE / FALSE
    Float,    // a float stored as its bits (FOGSTART, DEPTHBIAS, MIPMAPLODBIAS, ...)
    Color,    // a D3DCOLOR, 0xAARRGGBB
    Bits,     // a mask or flag word (STENCILMASK, CLIPPLANEENABLE, COLORWRITEENABLE, ...); with a
              // family other than Bool also a name or a tuple of names and numbers, OR-ed
    Integer,  // a plain number (ALPHAREF, STENCILREF, MAXMIPLEVEL, MAXANISOTROPY, ...)
};

struct StateInfo {
    uint32_t id;               // D3DRENDERSTATETYPE / D3DSAMPLERSTATETYPE / D3DTEXTURESTAGESTATETYPE value
    std::string_view name;     // without prefix: "CULLMODE"
    StateValueKind kind;
    EnumFamily family;         // for kind == Enum (ColorWrite/Bool otherwise unused)
    bool fixed_function = false;  // fixed-function or tessellator state: accepted, and ignored
                                  // while shaders are bound (pipeline.md §16)
};

// Render and sampler states sm2emu knows (pipeline.md §16, §17).
[[nodiscard]] std::span<const StateInfo> render_states();
[[nodiscard]] std::span<const StateInfo> sampler_states();
[[nodiscard]] const StateInfo* find_render_state(std::string_view name);
[[nodiscard]] const StateInfo* find_render_state(uint32_t id);
[[nodiscard]] const StateInfo* find_sampler_state(std::string_view name);
[[nodiscard]] const StateInfo* find_sampler_state(uint32_t id);
[[nodiscard]] std::span<const StateInfo> texture_stage_states();
[[nodiscard]] const StateInfo* find_texture_stage_state(std::string_view name);
[[nodiscard]] const StateInfo* find_texture_stage_state(uint32_t id);

// D3DTS_ names: VIEW, PROJECTION, TEXTURE0..7, WORLD, WORLD1..3 and WORLDMATRIXn (n 0..255).
[[nodiscard]] std::optional<uint32_t> transform_state_value(std::string_view name);
[[nodiscard]] std::string transform_state_name(uint32_t value);  // empty if it has none

// Every name of a family, in table order (for "expected one of" messages).
[[nodiscard]] std::vector<std::string_view> enum_names(EnumFamily family);
// A flag word of a bit family as names (each field's value, then single bits) and, for bits no
// name covers, one number: TextureArg 0x12 -> {"TEXTURE", "COMPLEMENT"}, TexCoordIndex
// 0x10001 -> {"CAMERASPACENORMAL", "1"}, Fvf 0x112 -> {"XYZ", "NORMAL", "TEX1"}. OR-ing the
// values of the names (enum_value) and the number gives `value` back.
[[nodiscard]] std::vector<std::string> flag_names(EnumFamily family, uint32_t value);

// Value of `name` in `family`; for bit families (ClearFlags, ColorWrite) a single flag name.
[[nodiscard]] std::optional<uint32_t> enum_value(EnumFamily family, std::string_view name);
// Name (without prefix) of `value` in `family`; empty if it has none.
[[nodiscard]] std::string_view enum_name(EnumFamily family, uint32_t value);
// The prefix of a family ("D3DRS_", "D3DCULL_", ...).
[[nodiscard]] std::string_view enum_prefix(EnumFamily family);

}  // namespace sm2::runtime
