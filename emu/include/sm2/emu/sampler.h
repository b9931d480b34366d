// The engine's view of texturing: an abstract sampler the runtime implements. The engine hands
// over a whole batch of 2x2 quads at once, so the sampler can compute level of detail from the
// differences inside each quad.
#pragma once

#include <array>
#include <cstdint>

#include "sm2/emu/batch.h"

namespace sm2::emu {

// texld (plain), texldp (projected: the sampler divides .xyz by .w), texldb (bias: the sampler
// adds .w to the level of detail).
enum class TextureVariant : uint8_t { Plain = 0, Projected = 1, Bias = 2 };

using FloatLanes = std::array<float, kBatchLanes>;

struct TextureRequest {
    unsigned sampler = 0;                   // s#
    TextureVariant variant = TextureVariant::Plain;
    // Coordinates exactly as the shader computed them (.x .y .z .w), not yet projected.
    // Lanes 4q .. 4q+3 are quad q in the order top-left, top-right, bottom-left, bottom-right.
    const std::array<FloatLanes, 4>* coordinates = nullptr;
    unsigned quad_count = kBatchQuads;      // quads in use (lanes beyond are don't-care)
    LaneMask helper_lanes = 0;              // killed lanes: sampled only for their quad's derivatives
};

class Sampler {
public:
    virtual ~Sampler() = default;
    // Writes one float4 per lane into `texels` (.x .y .z .w = r g b a).
    virtual void sample(const TextureRequest& request, std::array<FloatLanes, 4>& texels) = 0;
};

}  // namespace sm2::emu
