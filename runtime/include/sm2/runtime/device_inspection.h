// A read-only view of everything a Device has bound and set (sm2 state, sm2 replay --snapshot):
// Device::inspect() fills it in device_inspection.cpp. The pointers point into the device and
// stay valid until its next call.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sm2/runtime/device.h"

namespace sm2::runtime {

// A bound resource as CreateX described it. `name` is the stream's handle; empty when the
// resource was released while bound (the binding keeps it alive).
struct ResourceDescription {
    std::string name;
    std::string kind;  // "texture", "cube texture", "volume texture", "render target", "depth stencil",
                       // "vertex buffer", "index buffer", "vertex declaration", "vertex shader", "pixel shader"
    uint32_t width = 0, height = 0, depth = 0, levels = 0;
    Format format = Format::Unknown;
    Pool pool = Pool::Default;
    bool render_target_usage = false, dynamic_usage = false;
    uint64_t bytes = 0;  // buffers: their size
};

struct StreamInspection {
    ResourceDescription buffer;
    uint32_t offset = 0, stride = 0;
};

struct ShaderInspection {
    ResourceDescription resource;
    const isa::Program* program = nullptr;  // null for a shader that failed to create (never bound)
};

struct DeviceInspection {
    // SetRenderTarget 0..3 and SetDepthStencilSurface: the surfaces draws write now.
    std::array<const Surface*, kMaxRenderTargets> render_targets{};
    std::array<std::optional<ResourceDescription>, kMaxRenderTargets> render_target_resources;
    const DepthStencilSurface* depth_stencil = nullptr;
    std::optional<ResourceDescription> depth_stencil_resource;
    std::array<std::optional<ResourceDescription>, kMaxSamplers> textures;
    std::array<std::optional<StreamInspection>, kMaxVertexStreams> streams;
    std::optional<ResourceDescription> indices;
    IndexFormat index_format = IndexFormat::Index16;
    std::optional<ResourceDescription> declaration;
    std::vector<VertexElement> declaration_elements;
    std::optional<ShaderInspection> vertex_shader, pixel_shader;
    // Every render state of d3d9_names' table with its DWORD now (floats as their bits).
    std::vector<std::pair<uint32_t, uint32_t>> render_states;
    std::array<SamplerState, kMaxSamplers> samplers{};
    const FixedFunctionState* fixed_function = nullptr;
    Viewport viewport{};
    PixelRect scissor{};
    const std::vector<std::array<float, 4>>* vertex_constants_f = nullptr;
    const std::vector<std::array<float, 4>>* pixel_constants_f = nullptr;
    const emu::StaticFlowConstants* vertex_flow = nullptr;
    const emu::StaticFlowConstants* pixel_flow = nullptr;
    const Surface* back_buffer = nullptr;  // what Present shows
    uint32_t frames_presented = 0;
    bool in_scene = false;
};

}  // namespace sm2::runtime
