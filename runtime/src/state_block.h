// State blocks (IDirect3DStateBlock9): which device states a block holds (StateSelection) and
// their captured values (StateSnapshot). The lists of D3DSBT_PIXELSTATE / D3DSBT_VERTEXSTATE /
// D3DSBT_ALL follow the D3D9 documentation ("Saving Pixel/Vertex/All Device States with a
// StateBlock"); state_block.cpp holds them and the Device methods.
#pragma once

#include <array>
#include <bitset>
#include <memory>
#include <vector>

#include "device_internal.h"

namespace sm2::runtime {

constexpr unsigned kRenderStateSlots = 256;  // D3DRENDERSTATETYPE values are below 256
constexpr unsigned kSamplerStateSlots = 14;  // D3DSAMPLERSTATETYPE 1..13
// Transforms by slot: VIEW, PROJECTION, TEXTURE0..7, WORLDMATRIX(0..255).
constexpr unsigned kTransformSlots = 2 + kMaxTextureStages + kMaxWorldMatrices;
// The slot of a D3DTRANSFORMSTATETYPE FixedFunctionState::transform accepts.
[[nodiscard]] constexpr unsigned transform_slot(uint32_t state) {
    if (state == kTransformView) return 0;
    if (state == kTransformProjection) return 1;
    if (state >= kTransformWorld) return 2 + kMaxTextureStages + (state - kTransformWorld);
    return 2 + (state - kTransformTexture0);
}

struct Device::StateSelection {
    std::bitset<kRenderStateSlots> render_states;
    std::array<std::bitset<kSamplerStateSlots>, kMaxSamplers> sampler_states;
    std::bitset<kMaxSamplers> textures;
    std::bitset<kMaxVertexStreams> streams;
    std::bitset<kMaxUserClipPlanes> clip_planes;
    std::bitset<kMaxVertexShaderConstantsF> vs_float;
    std::bitset<kMaxPixelShaderConstantsF> ps_float;
    std::bitset<kMaxConstantsI> vs_int, ps_int;
    std::bitset<kMaxConstantsB> vs_bool, ps_bool;
    bool vertex_shader = false, pixel_shader = false, declaration = false, indices = false;
    bool viewport = false, scissor = false;
    // Fixed-function state: the transforms and material (ALL), the lights (ALL and VERTEXSTATE;
    // all of them, with the enabled list, as one state), texture stage states (PIXELSTATE;
    // TEXCOORDINDEX and TEXTURETRANSFORMFLAGS VERTEXSTATE too) and the FVF (with the declaration).
    std::array<std::bitset<kTextureStageStateCount>, kMaxTextureStages> stage_states;
    std::bitset<kTransformSlots> transforms;  // transform_slot() order
    bool material = false, lights = false, fvf = false;

    void merge(const StateSelection& other);
    [[nodiscard]] static StateSelection for_type(StateBlockType type);
};

struct Device::StateSnapshot {
    std::array<uint32_t, kRenderStateSlots> render_states{};
    std::array<std::array<uint32_t, kSamplerStateSlots>, kMaxSamplers> sampler_states{};
    std::array<std::shared_ptr<Resource>, kMaxSamplers> textures{};
    std::array<std::shared_ptr<Resource>, kMaxVertexStreams> stream_buffers{};
    std::array<uint32_t, kMaxVertexStreams> stream_offsets{}, stream_strides{};
    std::array<Vec4, kMaxUserClipPlanes> clip_planes{};
    std::vector<std::array<float, 4>> vs_float, ps_float;
    emu::StaticFlowConstants vs_flow{}, ps_flow{};
    std::shared_ptr<Resource> vertex_shader, pixel_shader, declaration, indices;
    Viewport viewport{};
    PixelRect scissor{};
    FixedFunctionState fixed_function;  // the selected parts
};

struct StateBlockObject {
    Device::StateSelection selection;
    Device::StateSnapshot snapshot;
};

}  // namespace sm2::runtime
