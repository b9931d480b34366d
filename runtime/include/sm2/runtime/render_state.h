// Render state: every D3DRS_* that matters with vs_2_0/ps_2_0 bound (pipeline.md §16), with its
// D3D9 default, as one plain struct a draw reads. Enums carry their d3d9types.h values. Also the
// two pieces of per-draw device state that are not render states: the viewport and the scissor
// rectangle.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace sm2::runtime {

// D3DZBUFFERTYPE
enum class ZBufferType : uint32_t { False = 0, True = 1, UseW = 2 };
// D3DFILLMODE
enum class FillMode : uint32_t { Point = 1, Wireframe = 2, Solid = 3 };
// D3DSHADEMODE (Phong is accepted and treated as Gouraud, as drivers do)
enum class ShadeMode : uint32_t { Flat = 1, Gouraud = 2, Phong = 3 };
// D3DCULL
enum class CullMode : uint32_t { None = 1, CW = 2, CCW = 3 };
// D3DCMPFUNC: every test reads "incoming FUNC reference" (pipeline.md §9)
enum class CompareFunc : uint32_t {
    Never = 1, Less = 2, Equal = 3, LessEqual = 4, Greater = 5, NotEqual = 6, GreaterEqual = 7,
    Always = 8,
};
// D3DSTENCILOP
enum class StencilOp : uint32_t {
    Keep = 1, Zero = 2, Replace = 3, IncrSat = 4, DecrSat = 5, Invert = 6, Incr = 7, Decr = 8,
};
// D3DBLEND (SrcColor2/InvSrcColor2 are D3D9Ex only: rejected)
enum class Blend : uint32_t {
    Zero = 1, One = 2, SrcColor = 3, InvSrcColor = 4, SrcAlpha = 5, InvSrcAlpha = 6,
    DestAlpha = 7, InvDestAlpha = 8, DestColor = 9, InvDestColor = 10, SrcAlphaSat = 11,
    BothSrcAlpha = 12, BothInvSrcAlpha = 13, BlendFactor = 14, InvBlendFactor = 15,
};
// D3DBLENDOP
enum class BlendOp : uint32_t { Add = 1, Subtract = 2, RevSubtract = 3, Min = 4, Max = 5 };
// D3DFOGMODE
enum class FogMode : uint32_t { None = 0, Exp = 1, Exp2 = 2, Linear = 3 };

// D3DCOLORWRITEENABLE bits
constexpr uint32_t kWriteRed = 1, kWriteGreen = 2, kWriteBlue = 4, kWriteAlpha = 8;
constexpr unsigned kMaxRenderTargets = 4;
constexpr unsigned kMaxUserClipPlanes = 6;

// D3DRENDERSTATETYPE values of the states modelled here (and the fixed-function ones that are
// accepted and ignored while shaders are bound).
enum class RenderStateType : uint32_t {
    ZEnable = 7, FillMode = 8, ShadeMode = 9, ZWriteEnable = 14, AlphaTestEnable = 15,
    LastPixel = 16, SrcBlend = 19, DestBlend = 20, CullMode = 22, ZFunc = 23, AlphaRef = 24,
    AlphaFunc = 25, DitherEnable = 26, AlphaBlendEnable = 27, FogEnable = 28,
    SpecularEnable = 29, FogColor = 34, FogTableMode = 35, FogStart = 36, FogEnd = 37,
    FogDensity = 38, RangeFogEnable = 48, StencilEnable = 52, StencilFail = 53,
    StencilZFail = 54, StencilPass = 55, StencilFunc = 56, StencilRef = 57, StencilMask = 58,
    StencilWriteMask = 59, TextureFactor = 60, Wrap0 = 128, Wrap7 = 135, Clipping = 136,
    Lighting = 137, Ambient = 139, FogVertexMode = 140, ColorVertex = 141, LocalViewer = 142,
    NormalizeNormals = 143, DiffuseMaterialSource = 145, EmissiveMaterialSource = 148,
    VertexBlend = 151, ClipPlaneEnable = 152, PointSize = 154, PointSizeMin = 155,
    PointSpriteEnable = 156, PointScaleEnable = 157, PointScaleA = 158, PointScaleB = 159,
    PointScaleC = 160, MultisampleAntialias = 161, MultisampleMask = 162,
    PatchEdgeStyle = 163, DebugMonitorToken = 165, PointSizeMax = 166,
    IndexedVertexBlendEnable = 167, ColorWriteEnable = 168, TweenFactor = 170, BlendOp = 171,
    PositionDegree = 172, NormalDegree = 173, ScissorTestEnable = 174,
    SlopeScaleDepthBias = 175, AntialiasedLineEnable = 176, MinTessellationLevel = 178,
    MaxTessellationLevel = 179, AdaptiveTessX = 180, AdaptiveTessW = 183,
    EnableAdaptiveTessellation = 184, TwoSidedStencilMode = 185, CcwStencilFail = 186,
    CcwStencilZFail = 187, CcwStencilPass = 188, CcwStencilFunc = 189,
    ColorWriteEnable1 = 190, ColorWriteEnable2 = 191, ColorWriteEnable3 = 192,
    BlendFactor = 193, SrgbWriteEnable = 194, DepthBias = 195, Wrap8 = 198, Wrap15 = 205,
    SeparateAlphaBlendEnable = 206, SrcBlendAlpha = 207, DestBlendAlpha = 208,
    BlendOpAlpha = 209,
};

struct StencilFace {
    StencilOp fail = StencilOp::Keep;
    StencilOp zfail = StencilOp::Keep;
    StencilOp pass = StencilOp::Keep;
    CompareFunc func = CompareFunc::Always;
    friend bool operator==(const StencilFace&, const StencilFace&) = default;
};

// Every render state a draw with shaders reads, at its D3D9 default. Float states are floats
// here (the DWORD carries their bits); BOOL states are bool.
struct RenderState {
    // ZENABLE's default depends on the device: TRUE with an automatic depth-stencil surface.
    // The struct starts at FALSE; RenderState::defaults(true) gives the other device's value.
    ZBufferType z_enable = ZBufferType::False;
    FillMode fill_mode = FillMode::Solid;
    ShadeMode shade_mode = ShadeMode::Gouraud;
    bool z_write_enable = true;
    bool alpha_test_enable = false;
    bool last_pixel = true;
    Blend src_blend = Blend::One;
    Blend dest_blend = Blend::Zero;
    CullMode cull_mode = CullMode::CCW;
    CompareFunc z_func = CompareFunc::LessEqual;
    uint32_t alpha_ref = 0;  // low 8 bits used
    CompareFunc alpha_func = CompareFunc::Always;
    bool dither_enable = false;
    bool alpha_blend_enable = false;
    bool fog_enable = false;
    bool specular_enable = false;  // fixed function only
    uint32_t fog_color = 0;        // D3DCOLOR 0xAARRGGBB
    FogMode fog_table_mode = FogMode::None;
    float fog_start = 0.0f;
    float fog_end = 1.0f;
    float fog_density = 1.0f;
    bool range_fog_enable = false;
    bool stencil_enable = false;
    StencilFace stencil{};  // STENCILFAIL/ZFAIL/PASS/FUNC (clockwise faces, lines, points)
    uint32_t stencil_ref = 0;
    uint32_t stencil_mask = 0xFFFFFFFFu;
    uint32_t stencil_write_mask = 0xFFFFFFFFu;
    uint32_t texture_factor = 0xFFFFFFFFu;  // fixed function only
    std::array<uint32_t, 16> wrap{};        // WRAP0..15 (D3DWRAPCOORD bits)
    bool clipping = true;
    FogMode fog_vertex_mode = FogMode::None;  // ignored with a vertex shader
    uint32_t clip_plane_enable = 0;           // bit i: D3DCLIPPLANEi
    float point_size = 1.0f;                  // driver-provided; Wine's 1.0f
    float point_size_min = 1.0f;
    bool point_sprite_enable = false;
    bool point_scale_enable = false;          // fixed function only
    float point_scale_a = 1.0f, point_scale_b = 0.0f, point_scale_c = 0.0f;
    bool multisample_antialias = true;
    uint32_t multisample_mask = 0xFFFFFFFFu;
    float point_size_max = 64.0f;
    std::array<uint32_t, kMaxRenderTargets> color_write_enable{0xF, 0xF, 0xF, 0xF};
    BlendOp blend_op = BlendOp::Add;
    bool scissor_test_enable = false;
    float slope_scale_depth_bias = 0.0f;
    bool antialiased_line_enable = false;
    bool two_sided_stencil_mode = false;
    StencilFace ccw_stencil{};  // CCW_STENCIL* (counter-clockwise faces in two-sided mode)
    uint32_t blend_factor = 0xFFFFFFFFu;  // D3DCOLOR
    bool srgb_write_enable = false;
    float depth_bias = 0.0f;
    bool separate_alpha_blend_enable = false;
    Blend src_blend_alpha = Blend::One;
    Blend dest_blend_alpha = Blend::Zero;
    BlendOp blend_op_alpha = BlendOp::Add;

    [[nodiscard]] static RenderState defaults(bool auto_depth_stencil) {
        RenderState s;
        s.z_enable = auto_depth_stencil ? ZBufferType::True : ZBufferType::False;
        return s;
    }
    friend bool operator==(const RenderState&, const RenderState&) = default;
};

// SetRenderState(type, value). Modelled states are stored; fixed-function and tessellator states
// are accepted and ignored; an unknown state or a value outside its enum is an error (message,
// state unchanged), so a bad stream leaves the device usable.
struct RenderStateResult {
    bool ok = true;
    bool ignored = false;  // a known state that shaders make irrelevant
    std::string error;     // "render state 22 (CULLMODE): value 7 is not a D3DCULL"
};
[[nodiscard]] RenderStateResult set_render_state(RenderState& state, uint32_t type, uint32_t value);
// GetRenderState for a modelled state: the DWORD (float states as their bits); nullopt for
// states that are not modelled.
[[nodiscard]] std::optional<uint32_t> get_render_state(const RenderState& state, uint32_t type);

// D3DVIEWPORT9
struct Viewport {
    uint32_t x = 0, y = 0, width = 0, height = 0;
    float min_z = 0.0f, max_z = 1.0f;
    friend bool operator==(const Viewport&, const Viewport&) = default;
};

// A pixel rectangle [left, right) x [top, bottom) (a RECT as SetScissorRect takes it).
struct PixelRect {
    int32_t left = 0, top = 0, right = 0, bottom = 0;
    [[nodiscard]] bool empty() const { return right <= left || bottom <= top; }
    [[nodiscard]] PixelRect intersect(const PixelRect& o) const {
        PixelRect r{left > o.left ? left : o.left, top > o.top ? top : o.top,
                    right < o.right ? right : o.right, bottom < o.bottom ? bottom : o.bottom};
        if (r.empty()) r = PixelRect{};
        return r;
    }
    friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

// D3DCOLOR 0xAARRGGBB -> (R, G, B, A) / 255.
[[nodiscard]] std::array<float, 4> color_to_float4(uint32_t argb);

}  // namespace sm2::runtime
