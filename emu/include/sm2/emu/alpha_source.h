// Which texture lookup decides whether a pixel shader's colour is transparent.
#pragma once

#include <cstddef>
#include <optional>

#include "sm2/emu/executable.h"

namespace sm2::emu {

// The sampler s# of the texld whose result's alpha (.w) decides the pixel shader's oC0.w this
// way: on every lane where that alpha is +0, -0 or NaN, oC0.w is one of them too, so it
// saturates to +0. The value reaches oC0.w through mov and mul steps alone (any swizzle, negate,
// _sat, rounding), mul by D3D9's rule that 0 times anything is +0 (numerics.h). nullopt where no
// texld does, or where s# is read by another texld too (a sampler stage stands for one lookup).
// A draw that skips transparent batches lets that stage's lookups leave red, green and blue
// unset where the alpha is transparent on every lane (draw.cpp, TextureSampler::set_alpha_gate).
[[nodiscard]] std::optional<unsigned> alpha_source_sampler(const Executable& pixel_shader);
// The index in pixel_shader.steps() of that texld (its sampler is alpha_source_sampler()'s): a
// draw reads its coordinate source to find batches whose lookups lie outside the texture.
[[nodiscard]] std::optional<size_t> alpha_source_texld(const Executable& pixel_shader);

}  // namespace sm2::emu
