// The fixed-function state of a D3D9 device: the FVF, transforms, material, lights and texture
// stage states (docs/fixed-function.md). One value type, so that a state block can capture and
// apply all of it with one assignment. The rules that check and change it live here
// (fixed_function.cpp); Device holds one FixedFunctionState and forwards its calls.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/runtime/vertex_fetch.h"

namespace sm2::runtime {

// D3DMATRIX, row-major (_11 _12 _13 _14 _21 ... _44): D3D9 transforms row vectors, v' = v M.
using Matrix4 = std::array<float, 16>;
[[nodiscard]] Matrix4 identity_matrix();
// a times b (row-major), D3D9's order for v a b.
[[nodiscard]] Matrix4 multiply(const Matrix4& a, const Matrix4& b);

// D3DCOLORVALUE and D3DVECTOR.
struct ColorValue {
    float r = 0, g = 0, b = 0, a = 0;
    bool operator==(const ColorValue&) const = default;
};
struct Vector3 {
    float x = 0, y = 0, z = 0;
    bool operator==(const Vector3&) const = default;
};

// D3DMATERIAL9; D3D9's initial material is all zero.
struct Material {
    ColorValue diffuse, ambient, specular, emissive;
    float power = 0;
    bool operator==(const Material&) const = default;
};

// D3DLIGHTTYPE.
enum class LightType : uint32_t { Point = 1, Spot = 2, Directional = 3 };

// D3DLIGHT9. The default is the light LightEnable creates for an index no SetLight has named
// (D3D9 docs, LightEnable): directional, white diffuse, pointing down +z.
struct Light {
    LightType type = LightType::Directional;
    ColorValue diffuse{1, 1, 1, 0}, specular, ambient;
    Vector3 position, direction{0, 0, 1};
    float range = 0, falloff = 0, attenuation0 = 0, attenuation1 = 0, attenuation2 = 0, theta = 0, phi = 0;
    bool operator==(const Light&) const = default;
};

// D3DTRANSFORMSTATETYPE values.
constexpr uint32_t kTransformView = 2, kTransformProjection = 3, kTransformTexture0 = 16, kTransformWorld = 256;
constexpr unsigned kMaxTextureStages = 8;    // D3DCAPS9.MaxTextureBlendStages
constexpr unsigned kMaxWorldMatrices = 256;  // D3DTS_WORLDMATRIX(0..255)
constexpr unsigned kMaxActiveLights = 8;     // our D3DCAPS9.MaxActiveLights

// D3DTEXTURESTAGESTATETYPE values (d3d9types.h).
enum TextureStageStateType : uint32_t {
    kTssColorOp = 1, kTssColorArg1 = 2, kTssColorArg2 = 3, kTssAlphaOp = 4, kTssAlphaArg1 = 5, kTssAlphaArg2 = 6,
    kTssBumpEnvMat00 = 7, kTssBumpEnvMat01 = 8, kTssBumpEnvMat10 = 9, kTssBumpEnvMat11 = 10, kTssTexCoordIndex = 11,
    kTssBumpEnvLScale = 22, kTssBumpEnvLOffset = 23, kTssTextureTransformFlags = 24, kTssColorArg0 = 26,
    kTssAlphaArg0 = 27, kTssResultArg = 28, kTssConstant = 32,
};
constexpr uint32_t kTextureStageStateCount = 33;  // values are indexed by type, 0..32

// D3DTEXTUREOP values used by the defaults, and D3DTA_* argument selectors.
constexpr uint32_t kTopDisable = 1, kTopSelectArg1 = 2, kTopModulate = 4;
constexpr uint32_t kTaDiffuse = 0, kTaCurrent = 1, kTaTexture = 2;

// What SetFVF hands to vertex fetch: the FVF's vertex elements, all in stream 0, in D3D9's order
// (position, blend weights, blend indices, normal, point size, diffuse, specular, texture
// coordinates), or the reason the FVF is not one D3D9 accepts.
struct FvfLayout {
    std::vector<VertexElement> elements;
    uint32_t stride = 0;
    std::string error;
};
[[nodiscard]] FvfLayout fvf_layout(uint32_t fvf);

struct FixedFunctionState {
    uint32_t fvf = 0;  // the last SetFVF (0: none, or a declaration set since)
    Matrix4 view = identity_matrix(), projection = identity_matrix();
    std::array<Matrix4, kMaxTextureStages> texture = make_identities<kMaxTextureStages>();
    std::array<Matrix4, kMaxWorldMatrices> world = make_identities<kMaxWorldMatrices>();
    Material material;
    std::map<uint32_t, Light> lights;     // every index SetLight (or LightEnable) has named
    std::vector<uint32_t> enabled_lights;  // in the order they were enabled, at most kMaxActiveLights
    std::array<std::array<uint32_t, kTextureStageStateCount>, kMaxTextureStages> stages = default_stages();

    // SetTransform / MultiplyTransform: nullopt, or why the state type is refused.
    [[nodiscard]] Matrix4* transform(uint32_t state);
    [[nodiscard]] std::optional<std::string> set_light(uint32_t index, const Light& light);
    [[nodiscard]] std::optional<std::string> light_enable(uint32_t index, bool enable);
    [[nodiscard]] std::optional<std::string> set_texture_stage_state(uint32_t stage, uint32_t type, uint32_t value);
    [[nodiscard]] bool light_enabled(uint32_t index) const;

private:
    template <size_t N>
    static std::array<Matrix4, N> make_identities() {
        std::array<Matrix4, N> all;
        all.fill(identity_matrix());
        return all;
    }
    static std::array<std::array<uint32_t, kTextureStageStateCount>, kMaxTextureStages> default_stages();
};

}  // namespace sm2::runtime
