// Pixel history (sm2 pixel): what one watched pixel went through in each draw, recorded by the
// draw itself (draw.cpp) when Device::watch_pixel has set a watch. Off, a draw tests one pointer.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "sm2/runtime/formats.h"

namespace sm2::runtime {

class Surface;

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
};

// One draw while the watch was set.
struct PixelDraw {
    const Surface* target = nullptr;  // render target 0 of the draw
    bool inside = false;              // the pixel is inside render target 0
    std::vector<PixelFragment> fragments;
    // The recording gave the pixel the value the draw itself gave it (always, unless a bug).
    bool consistent = true;
};

struct PixelWatch {
    uint32_t x = 0, y = 0;
    std::vector<PixelDraw> draws;  // one per draw while the watch is set
};

}  // namespace sm2::runtime
