// Fixed-function vertex and pixel processing as generated shader programs (docs/fixed-function.md):
// from the fixed-function state at draw time, a vs_2_0 and a ps_2_0 isa::Program that the engine
// lowers, runs and compiles like an application's shader. Everything a program's *shape* depends
// on is in its key; values that can change without changing the shape (matrices, TFACTOR, the
// viewport mapping of XYZRHW vertices, stage constants) go to constant registers filled per draw.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/isa/program.h"
#include "sm2/runtime/fixed_function.h"
#include "sm2/runtime/render_state.h"
#include "sm2/runtime/vertex_fetch.h"

namespace sm2::runtime {

struct FixedFunctionProgram {
    std::optional<isa::Program> program;           // unset: refused, see error
    std::string key;                               // the program as text: equal keys, equal programs
    std::vector<std::array<float, 4>> constants;   // c0.. for this draw
    std::string error;
    // Vertex program: table fog is W-fog (D3D9 "Eye-Relative vs. Z-based Depth": a perspective
    // projection makes table fog a function of the eye-space depth, FOGSTART/FOGEND in camera
    // units): oFog carries camera-space z, and the merger's table fog reads it instead of the
    // pixel's depth.
    bool w_fog = false;
};

// The vertex program for a draw without a vertex shader, reading the declaration's elements.
// The fixed-function render states RenderState does not hold, at D3D9's defaults.
struct VertexProcessingStates {
    bool lighting = true;              // LIGHTING
    uint32_t ambient = 0;              // AMBIENT, D3DCOLOR
    bool color_vertex = true;          // COLORVERTEX
    bool local_viewer = true;          // LOCALVIEWER
    bool normalize_normals = false;    // NORMALIZENORMALS
    uint32_t diffuse_source = 1, specular_source = 2, ambient_source = 0, emissive_source = 0;  // D3DMCS_*
    uint32_t vertex_blend = 0;         // VERTEXBLEND
    bool indexed_vertex_blend = false; // INDEXEDVERTEXBLENDENABLE
    float tween_factor = 0.0f;         // TWEENFACTOR
};

[[nodiscard]] FixedFunctionProgram fixed_function_vertex_program(const FixedFunctionState& ff, const RenderState& rs,
                                                                 const VertexProcessingStates& states,
                                                                 const Viewport& viewport,
                                                                 std::span<const VertexElement> declaration);

// The pixel program for a draw without a pixel shader: the texture stage cascade, specular add.
// `textures[s]`: the type of the texture bound to stage s (nullopt: none).
[[nodiscard]] FixedFunctionProgram fixed_function_pixel_program(
    const FixedFunctionState& ff, const RenderState& rs,
    const std::array<std::optional<isa::TextureType>, kMaxTextureStages>& textures);

}  // namespace sm2::runtime
