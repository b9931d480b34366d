// The output merger (pipeline.md §7, §10, §12, §13). See output_merger.h for the order.
#include "sm2/runtime/output_merger.h"

#include <algorithm>
#include <cmath>

namespace sm2::runtime {
namespace {

float saturate(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }  // NaN -> 0

Vec4 factor(Blend f, const Vec4& s, const Vec4& d, const Vec4& constant) {
    switch (f) {
    case Blend::Zero: return {0.0f, 0.0f, 0.0f, 0.0f};
    case Blend::One: return {1.0f, 1.0f, 1.0f, 1.0f};
    case Blend::SrcColor: return s;
    case Blend::InvSrcColor: return {1.0f - s[0], 1.0f - s[1], 1.0f - s[2], 1.0f - s[3]};
    case Blend::SrcAlpha: case Blend::BothSrcAlpha: return {s[3], s[3], s[3], s[3]};
    case Blend::InvSrcAlpha: case Blend::BothInvSrcAlpha: {
        const float a = 1.0f - s[3];
        return {a, a, a, a};
    }
    case Blend::DestAlpha: return {d[3], d[3], d[3], d[3]};
    case Blend::InvDestAlpha: {
        const float a = 1.0f - d[3];
        return {a, a, a, a};
    }
    case Blend::DestColor: return d;
    case Blend::InvDestColor: return {1.0f - d[0], 1.0f - d[1], 1.0f - d[2], 1.0f - d[3]};
    case Blend::SrcAlphaSat: {
        const float f2 = std::min(s[3], 1.0f - d[3]);
        return {f2, f2, f2, 1.0f};
    }
    case Blend::BlendFactor: return constant;
    case Blend::InvBlendFactor:
        return {1.0f - constant[0], 1.0f - constant[1], 1.0f - constant[2], 1.0f - constant[3]};
    }
    return {0.0f, 0.0f, 0.0f, 0.0f};
}

float combine(BlendOp op, float s, float fs, float d, float fd) {
    switch (op) {
    case BlendOp::Add: return s * fs + d * fd;
    case BlendOp::Subtract: return s * fs - d * fd;
    case BlendOp::RevSubtract: return d * fd - s * fs;
    case BlendOp::Min: return std::min(s, d);
    case BlendOp::Max: return std::max(s, d);
    }
    return s;
}

}  // namespace

OutputMergerState output_merger_state(const RenderState& rs) {
    OutputMergerState s;
    s.fog_enable = rs.fog_enable;
    s.fog_table_mode = rs.fog_table_mode;
    s.fog_start = rs.fog_start;
    s.fog_end = rs.fog_end;
    s.fog_density = rs.fog_density;
    s.fog_color = color_to_float4(rs.fog_color);
    s.alpha_test = rs.alpha_test_enable;
    s.alpha_func = rs.alpha_func;
    s.alpha_ref = static_cast<float>(rs.alpha_ref & 0xFFu) / 255.0f;
    s.depth_stencil = depth_stencil_state(rs);
    s.blend.enable = rs.alpha_blend_enable;
    s.blend.src = rs.src_blend;
    s.blend.dst = rs.dest_blend;
    s.blend.op = rs.blend_op;
    // BOTHSRCALPHA / BOTHINVSRCALPHA as SRCBLEND force the destination factor.
    if (rs.src_blend == Blend::BothSrcAlpha) s.blend.dst = Blend::InvSrcAlpha;
    if (rs.src_blend == Blend::BothInvSrcAlpha) s.blend.dst = Blend::SrcAlpha;
    if (rs.separate_alpha_blend_enable) {
        s.blend.src_alpha = rs.src_blend_alpha;
        s.blend.dst_alpha = rs.dest_blend_alpha;
        s.blend.op_alpha = rs.blend_op_alpha;
        if (rs.src_blend_alpha == Blend::BothSrcAlpha) s.blend.dst_alpha = Blend::InvSrcAlpha;
        if (rs.src_blend_alpha == Blend::BothInvSrcAlpha) s.blend.dst_alpha = Blend::SrcAlpha;
    } else {
        s.blend.src_alpha = s.blend.src;
        s.blend.dst_alpha = s.blend.dst;
        s.blend.op_alpha = s.blend.op;
    }
    s.blend.factor = color_to_float4(rs.blend_factor);
    s.write_mask = rs.color_write_enable;
    s.srgb_write = rs.srgb_write_enable;
    return s;
}

bool is_float_target(Format f) {
    switch (f) {
    case Format::R16F: case Format::G16R16F: case Format::A16B16G16R16F: case Format::R32F:
    case Format::G32R32F: case Format::A32B32G32R32F: return true;
    default: return false;
    }
}

float fog_factor(const OutputMergerState& s, float vertex_fog, float depth) {
    float f = vertex_fog;
    const double d = depth;
    switch (s.fog_table_mode) {
    case FogMode::None: break;
    case FogMode::Linear: {
        const double range = static_cast<double>(s.fog_end) - s.fog_start;
        // FOGEND == FOGSTART: a step at the fog end (the limit of the formula).
        f = range != 0.0 ? static_cast<float>((s.fog_end - d) / range) : (d < s.fog_end ? 1.0f : 0.0f);
        break;
    }
    case FogMode::Exp: f = static_cast<float>(std::exp(-(d * s.fog_density))); break;
    case FogMode::Exp2: {
        const double x = d * s.fog_density;
        f = static_cast<float>(std::exp(-(x * x)));
        break;
    }
    }
    return saturate(f);
}

bool alpha_test_passes(const OutputMergerState& s, float alpha) {
    if (std::isnan(alpha)) return s.alpha_func == CompareFunc::Always;
    return compare(s.alpha_func, saturate(alpha), s.alpha_ref);
}

Vec4 blend(const BlendState& b, const Vec4& src_in, const Vec4& dst, bool fixed_point) {
    Vec4 src = src_in;
    if (fixed_point)
        for (float& c : src) c = saturate(c);
    const Vec4 fs = factor(b.src, src, dst, b.factor), fd = factor(b.dst, src, dst, b.factor);
    const Vec4 fsa = factor(b.src_alpha, src, dst, b.factor), fda = factor(b.dst_alpha, src, dst, b.factor);
    Vec4 r;
    for (unsigned c = 0; c < 3; ++c) r[c] = combine(b.op, src[c], fs[c], dst[c], fd[c]);
    r[3] = combine(b.op_alpha, src[3], fsa[3], dst[3], fda[3]);
    if (fixed_point)
        for (float& c : r) c = saturate(c);
    return r;
}

emu::LaneMask merge(const OutputMergerState& s, RenderTargets& targets, const MergeInput& in) {
    const emu::Batch& batch = *in.batch;
    const PixelLanes& lanes = *in.lanes;
    emu::LaneMask live = in.live & ~batch.killed;
    if (lanes.quad_count * 4 < emu::kBatchLanes) live &= (emu::LaneMask{1} << (lanes.quad_count * 4)) - 1;

    // Depth of each lane: oDepth (no bias) or the interpolated, biased depth.
    std::array<float, emu::kBatchLanes> depth = lanes.depth;
    if (in.shader_depth)
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) depth[l] = batch.depth()[0][l];
    for (float& z : depth) z = saturate(z);

    // oC0 after fog (§7 step 2).
    std::array<Vec4, emu::kBatchLanes> color0;
    for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
        for (unsigned c = 0; c < 4; ++c) color0[l][c] = batch.render_target(0)[c][l];
        if (s.fog_enable) {
            const float f = fog_factor(s, lanes.fog[l], depth[l]);
            for (unsigned c = 0; c < 3; ++c) color0[l][c] = f * color0[l][c] + (1.0f - f) * s.fog_color[c];
        }
    }
    // Alpha test (§10): failing pixels never reach the stencil stage.
    if (s.alpha_test)
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            if ((live >> l & 1u) && !alpha_test_passes(s, color0[l][3])) live &= ~(emu::LaneMask{1} << l);
    // Stencil, depth, stencil update (§11).
    if (!in.depth_stencil_done)
        live = depth_stencil_test(s.depth_stencil, targets.depth_stencil, lanes.x, lanes.y, depth, live,
                                  lanes.clockwise);

    for (unsigned t = 0; t < kMaxRenderTargets; ++t) {
        Surface* surface = targets.color[t];
        // A target the shader does not write keeps its contents; an oC# without a target is dropped.
        if (!surface || !(in.color_outputs >> t & 1u)) continue;
        const uint32_t mask = s.write_mask[t] & 0xFu;
        if (mask == 0) continue;
        const FormatInfo* info = format_info(surface->format());
        if (!info || !info->render_target || surface->depth() != 1) continue;  // not a target
        const bool fixed = !is_float_target(surface->format());
        const bool srgb = t == 0 && s.srgb_write && info->srgb;
        for (unsigned l = 0; l < emu::kBatchLanes; ++l) {
            if (!(live >> l & 1u)) continue;
            if (lanes.x[l] < 0 || lanes.y[l] < 0 || static_cast<uint32_t>(lanes.x[l]) >= surface->width() ||
                static_cast<uint32_t>(lanes.y[l]) >= surface->height())
                continue;
            const auto px = static_cast<uint32_t>(lanes.x[l]), py = static_cast<uint32_t>(lanes.y[l]);
            Vec4 src;
            if (t == 0) src = color0[l];
            else
                for (unsigned c = 0; c < 4; ++c) src[c] = batch.render_target(t)[c][l];
            const bool need_dst = s.blend.enable || mask != 0xF;
            Vec4 stored{};
            if (need_dst) stored = surface->read(px, py, 0);
            Vec4 out = src;
            if (s.blend.enable) {
                Vec4 dst = stored;
                if (srgb)
                    for (unsigned c = 0; c < 3; ++c) dst[c] = srgb_to_linear(dst[c]);
                out = blend(s.blend, src, dst, fixed);
            }
            if (srgb)
                for (unsigned c = 0; c < 3; ++c) out[c] = linear_to_srgb(saturate(out[c]));
            for (unsigned c = 0; c < 4; ++c)
                if (!(mask >> c & 1u)) out[c] = stored[c];
            surface->write(px, py, 0, out);
        }
    }
    return live;
}

}  // namespace sm2::runtime
