// Fixed-function state rules (runtime/include/sm2/runtime/fixed_function.h, docs/fixed-function.md).
#include "sm2/runtime/fixed_function.h"

#include <algorithm>

namespace sm2::runtime {

namespace {

// D3DFVF_* bits (d3d9types.h).
constexpr uint32_t kFvfPositionMask = 0x400E;
constexpr uint32_t kFvfXyz = 0x002, kFvfXyzRhw = 0x004, kFvfXyzB1 = 0x006, kFvfXyzB5 = 0x00E, kFvfXyzW = 0x4002;
constexpr uint32_t kFvfNormal = 0x010, kFvfPSize = 0x020, kFvfDiffuse = 0x040, kFvfSpecular = 0x080;
constexpr uint32_t kFvfTexCountMask = 0xF00, kFvfTexCountShift = 8;
constexpr uint32_t kFvfLastBetaUByte4 = 0x1000, kFvfLastBetaD3DColor = 0x8000;
constexpr uint32_t kFvfTexCoordSizeShift = 16;
constexpr uint32_t kFvfKnownBits = kFvfPositionMask | kFvfNormal | kFvfPSize | kFvfDiffuse | kFvfSpecular |
                                   kFvfTexCountMask | kFvfLastBetaUByte4 | kFvfLastBetaD3DColor | 0xFFFF0000u;

// D3DDECLUSAGE values.
constexpr uint8_t kUsagePosition = 0, kUsageBlendWeight = 1, kUsageBlendIndices = 2, kUsageNormal = 3, kUsagePSize = 4,
                  kUsageTexCoord = 5, kUsagePositionT = 9, kUsageColor = 10;

}  // namespace

Matrix4 identity_matrix() {
    return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
    Matrix4 m{};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            float sum = 0;
            for (int k = 0; k < 4; ++k) sum += a[static_cast<size_t>(row * 4 + k)] * b[static_cast<size_t>(k * 4 + col)];
            m[static_cast<size_t>(row * 4 + col)] = sum;
        }
    return m;
}

FvfLayout fvf_layout(uint32_t fvf) {
    FvfLayout layout;
    if ((fvf & ~kFvfKnownBits) != 0) {
        layout.error = "FVF bits " + std::to_string(fvf & ~kFvfKnownBits) + " are not D3DFVF flags";
        return layout;
    }
    uint16_t offset = 0;
    auto add = [&](DeclType type, uint8_t usage, uint8_t usage_index) {
        layout.elements.push_back(VertexElement{0, offset, static_cast<uint8_t>(type), 0, usage, usage_index});
        offset = static_cast<uint16_t>(offset + decl_type_size(type));
    };
    const uint32_t position = fvf & kFvfPositionMask;
    const bool last_beta = (fvf & (kFvfLastBetaUByte4 | kFvfLastBetaD3DColor)) != 0;
    if ((fvf & kFvfLastBetaUByte4) && (fvf & kFvfLastBetaD3DColor)) {
        layout.error = "LASTBETA_UBYTE4 and LASTBETA_D3DCOLOR together";
        return layout;
    }
    if (position == kFvfXyz) {
        add(DeclType::FLOAT3, kUsagePosition, 0);
    } else if (position == kFvfXyzRhw) {
        add(DeclType::FLOAT4, kUsagePositionT, 0);
    } else if (position == kFvfXyzW) {
        add(DeclType::FLOAT4, kUsagePosition, 0);
    } else if (position >= kFvfXyzB1 && position <= kFvfXyzB5 && (position & 1) == 0 && (position & 0x4000) == 0) {
        // XYZBn: n floats after the position; with LASTBETA the last one is the blend indices.
        add(DeclType::FLOAT3, kUsagePosition, 0);
        const unsigned betas = (position - kFvfXyzB1) / 2 + 1;
        const unsigned weights = last_beta ? betas - 1 : betas;
        if (weights > 4) {
            // No declaration type holds 5 floats; D3D9 blends with at most 4 matrices anyway.
            layout.error = "XYZB5 without LASTBETA: 5 blend weights do not fit one vertex element";
            return layout;
        }
        if (weights > 0) add(static_cast<DeclType>(weights - 1), kUsageBlendWeight, 0);
        if (last_beta)
            add((fvf & kFvfLastBetaUByte4) ? DeclType::UBYTE4 : DeclType::D3DCOLOR, kUsageBlendIndices, 0);
    } else if (position != 0) {
        layout.error = "FVF position bits " + std::to_string(position) + " are not one D3DFVF position type";
        return layout;
    }
    if (last_beta && !(position >= kFvfXyzB1 && position <= kFvfXyzB5)) {
        layout.error = "LASTBETA without an XYZBn position";
        return layout;
    }
    if (fvf & kFvfNormal) add(DeclType::FLOAT3, kUsageNormal, 0);
    if (fvf & kFvfPSize) add(DeclType::FLOAT1, kUsagePSize, 0);
    if (fvf & kFvfDiffuse) add(DeclType::D3DCOLOR, kUsageColor, 0);
    if (fvf & kFvfSpecular) add(DeclType::D3DCOLOR, kUsageColor, 1);
    const uint32_t texture_sets = (fvf & kFvfTexCountMask) >> kFvfTexCountShift;
    if (texture_sets > 8) {
        layout.error = "TEX" + std::to_string(texture_sets) + " (at most TEX8)";
        return layout;
    }
    for (uint32_t set = 0; set < texture_sets; ++set) {
        // D3DFVF_TEXCOORDSIZEn(set): 0 = 2 floats, 1 = 3, 2 = 4, 3 = 1.
        static constexpr DeclType kSizes[] = {DeclType::FLOAT2, DeclType::FLOAT3, DeclType::FLOAT4, DeclType::FLOAT1};
        add(kSizes[(fvf >> (kFvfTexCoordSizeShift + 2 * set)) & 3], kUsageTexCoord, static_cast<uint8_t>(set));
    }
    layout.stride = offset;
    return layout;
}

Matrix4* FixedFunctionState::transform(uint32_t state) {
    if (state == kTransformView) return &view;
    if (state == kTransformProjection) return &projection;
    if (state >= kTransformTexture0 && state < kTransformTexture0 + kMaxTextureStages)
        return &texture[state - kTransformTexture0];
    if (state >= kTransformWorld && state < kTransformWorld + kMaxWorldMatrices) return &world[state - kTransformWorld];
    return nullptr;
}

std::optional<std::string> FixedFunctionState::set_light(uint32_t index, const Light& light) {
    const auto type = static_cast<uint32_t>(light.type);
    if (type < static_cast<uint32_t>(LightType::Point) || type > static_cast<uint32_t>(LightType::Directional))
        return "light type " + std::to_string(type) + " is not POINT, SPOT or DIRECTIONAL";
    // A point or spot light's range cannot be negative (wined3d's SetLight check; D3DLIGHT9).
    if (light.type != LightType::Directional && !(light.range >= 0))
        return "a point or spot light's range " + std::to_string(light.range) + " is negative";
    lights[index] = light;
    return std::nullopt;
}

std::optional<std::string> FixedFunctionState::light_enable(uint32_t index, bool enable) {
    const auto at = std::find(enabled_lights.begin(), enabled_lights.end(), index);
    if (!enable) {
        if (at != enabled_lights.end()) enabled_lights.erase(at);
        return std::nullopt;
    }
    if (at != enabled_lights.end()) return std::nullopt;
    if (enabled_lights.size() >= kMaxActiveLights)
        return "light " + std::to_string(index) + ": " + std::to_string(kMaxActiveLights) +
               " lights are enabled already (MaxActiveLights)";
    lights.try_emplace(index);  // a light never set is the default light
    enabled_lights.push_back(index);
    return std::nullopt;
}

bool FixedFunctionState::light_enabled(uint32_t index) const {
    return std::find(enabled_lights.begin(), enabled_lights.end(), index) != enabled_lights.end();
}

std::optional<std::string> FixedFunctionState::set_texture_stage_state(uint32_t stage, uint32_t type, uint32_t value) {
    if (stage >= kMaxTextureStages)
        return "stage " + std::to_string(stage) + " out of range (0 to " + std::to_string(kMaxTextureStages - 1) + ")";
    static constexpr uint32_t kTypes[] = {kTssColorOp, kTssColorArg1, kTssColorArg2, kTssAlphaOp, kTssAlphaArg1,
                                          kTssAlphaArg2, kTssBumpEnvMat00, kTssBumpEnvMat01, kTssBumpEnvMat10,
                                          kTssBumpEnvMat11, kTssTexCoordIndex, kTssBumpEnvLScale, kTssBumpEnvLOffset,
                                          kTssTextureTransformFlags, kTssColorArg0, kTssAlphaArg0, kTssResultArg,
                                          kTssConstant};
    if (std::find(std::begin(kTypes), std::end(kTypes), type) == std::end(kTypes))
        return "state " + std::to_string(type) + " is not a D3DTEXTURESTAGESTATETYPE";
    stages[stage][type] = value;
    return std::nullopt;
}

std::array<std::array<uint32_t, kTextureStageStateCount>, kMaxTextureStages> FixedFunctionState::default_stages() {
    // D3DTEXTURESTAGESTATETYPE's documented defaults: stage 0 modulates the texture with the
    // diffuse colour and selects the texture's alpha; every later stage is disabled.
    std::array<std::array<uint32_t, kTextureStageStateCount>, kMaxTextureStages> all{};
    for (uint32_t stage = 0; stage < kMaxTextureStages; ++stage) {
        auto& s = all[stage];
        s[kTssColorOp] = stage == 0 ? kTopModulate : kTopDisable;
        s[kTssAlphaOp] = stage == 0 ? kTopSelectArg1 : kTopDisable;
        s[kTssColorArg1] = s[kTssAlphaArg1] = kTaTexture;
        s[kTssColorArg2] = s[kTssAlphaArg2] = kTaCurrent;
        s[kTssColorArg0] = s[kTssAlphaArg0] = s[kTssResultArg] = kTaCurrent;
        s[kTssTexCoordIndex] = stage;
    }
    return all;
}

}  // namespace sm2::runtime
