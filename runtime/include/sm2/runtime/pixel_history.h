// Pixel history (sm2 pixel): what one watched pixel went through in each draw, recorded by the
// draw itself (draw.cpp) when Device::watch_pixel has set a watch. Off, a draw tests one pointer.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "sm2/emu/instruction_trace.h"
#include "sm2/isa/program.h"
#include "sm2/runtime/formats.h"

namespace sm2::runtime {

class Surface;

// A shader as it ran for the watched pixel's quad or the watched vertex (sm2 debug), recorded
// only when asked for: the interpreter runs the draw's shader again on the inputs the draw gave
// it, one source instruction at a time (emu::trace_instructions).
struct ShaderDebug {
    std::shared_ptr<const isa::Program> program;  // what the instructions' indices index
    bool fixed_function = false;                  // generated from the fixed-function state
    unsigned lanes = 0;                           // lanes traced: 4 (the pixel's 2x2 quad) or 1 (a vertex)
    unsigned watched_lane = 0;                    // the lane of the watched pixel or vertex
    emu::LaneMask covered = 0;                    // quad lanes inside the primitive (others: helper lanes)
    std::vector<emu::InstructionWrite> inputs;    // v#, t# as interpolated or fetched; mask: those read
    std::vector<std::pair<uint16_t, Float4>> constants;  // c# read by name (not c[a0.x + n]), def values included
    std::vector<emu::InstructionTrace> steps;
};

// One primitive of a draw that covers the watched pixel, in draw order.
struct PixelFragment {
    uint32_t primitive = 0;  // the primitive's index in the draw (as assembled, before clipping)
    bool scissored = false;  // covered, but outside the scissor rectangle: nothing else ran
    bool early_depth_stencil = false;            // the depth/stencil test ran before the shader
    std::optional<bool> depth_stencil_passed;    // nullopt: disabled, or not reached
    bool shaded = false;                         // the pixel shader ran for it
    bool killed = false;                         // texkill
    std::optional<bool> alpha_test_passed;       // nullopt: ALPHATESTENABLE off, or not reached
    bool written = false;                        // past every test: colour (and depth) written
    std::array<Float4, 4> shader_color{};        // oC0..oC3 as the shader wrote them
    float depth = 0.0f;                          // the depth tested: interpolated (and biased), or oDepth
    std::array<Float4, 4> color_before{}, color_after{};  // render targets 0..3 at the pixel, as stored
    float depth_before = 0.0f, depth_after = 0.0f;
    uint32_t stencil_before = 0, stencil_after = 0;
    // The pixel shader's inputs at the pixel (v0, v1, t0..t7 that it reads), as interpolated.
    std::vector<std::pair<uint16_t, Float4>> inputs;  // (emu lane slot, value)
    std::shared_ptr<const ShaderDebug> shader_debug;  // PixelWatch::debug_shaders only
};

// One draw while the watch was set.
struct PixelDraw {
    std::array<const Surface*, 4> targets{};  // render targets 0..3 of the draw (null: none bound)
    bool inside = false;                      // the pixel is inside render target 0
    std::vector<PixelFragment> fragments;
    // The recording gave the pixel the value the draw itself gave it (always, unless a bug).
    bool consistent = true;
};

struct PixelWatch {
    uint32_t x = 0, y = 0;
    bool debug_shaders = false;    // also trace each fragment's pixel shader (ShaderDebug)
    std::vector<PixelDraw> draws;  // one per draw while the watch is set
};

struct VertexWatch {
    uint32_t index = 0;  // the vertex number fetched (an index buffer's value plus BaseVertexIndex)
    // One per draw while the watch is set; null when the draw does not fetch vertex `index`.
    std::vector<std::shared_ptr<const ShaderDebug>> draws;
};

}  // namespace sm2::runtime
