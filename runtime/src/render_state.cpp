// SetRenderState / GetRenderState over the RenderState struct (pipeline.md §16).
#include "sm2/runtime/render_state.h"

#include "sm2/runtime/d3d9_names.h"

#include <bit>
#include <string_view>

namespace sm2::runtime {
namespace {

float as_float(uint32_t bits) { return std::bit_cast<float>(bits); }
uint32_t as_bits(float f) { return std::bit_cast<uint32_t>(f); }

template <typename E>
bool in_range(uint32_t v, uint32_t lo, uint32_t hi, E& out) {
    if (v < lo || v > hi) return false;
    out = static_cast<E>(v);
    return true;
}

}  // namespace

std::array<float, 4> color_to_float4(uint32_t argb) {
    return {static_cast<float>((argb >> 16) & 0xFF) / 255.0f,
            static_cast<float>((argb >> 8) & 0xFF) / 255.0f,
            static_cast<float>(argb & 0xFF) / 255.0f,
            static_cast<float>((argb >> 24) & 0xFF) / 255.0f};
}

RenderStateResult set_render_state(RenderState& st, uint32_t type, uint32_t value) {
    RenderStateResult r;
    const StateInfo* name = find_render_state(type);
    if (!name) {
        r.ok = false;
        r.error = "render state " + std::to_string(type) + " is not a D3DRENDERSTATETYPE";
        return r;
    }
    if (name->fixed_function) {
        r.ignored = true;
        return r;
    }
    bool valid = true;
    const char* enum_name = "";
    auto cmp = [&](CompareFunc& f) { enum_name = "D3DCMPFUNC"; valid = in_range(value, 1, 8, f); };
    auto sop = [&](StencilOp& o) { enum_name = "D3DSTENCILOP"; valid = in_range(value, 1, 8, o); };
    auto blend = [&](Blend& b) { enum_name = "D3DBLEND"; valid = in_range(value, 1, 15, b); };
    auto bop = [&](BlendOp& o) { enum_name = "D3DBLENDOP"; valid = in_range(value, 1, 5, o); };
    auto fog = [&](FogMode& m) { enum_name = "D3DFOGMODE"; valid = in_range(value, 0, 3, m); };
    const bool flag = value != 0;
    switch (type) {
    case 7: enum_name = "D3DZBUFFERTYPE"; valid = in_range(value, 0, 2, st.z_enable); break;
    case 8: enum_name = "D3DFILLMODE"; valid = in_range(value, 1, 3, st.fill_mode); break;
    case 9: enum_name = "D3DSHADEMODE"; valid = in_range(value, 1, 3, st.shade_mode); break;
    case 14: st.z_write_enable = flag; break;
    case 15: st.alpha_test_enable = flag; break;
    case 16: st.last_pixel = flag; break;
    case 19: blend(st.src_blend); break;
    case 20: blend(st.dest_blend); break;
    case 22: enum_name = "D3DCULL"; valid = in_range(value, 1, 3, st.cull_mode); break;
    case 23: cmp(st.z_func); break;
    case 24: st.alpha_ref = value; break;
    case 25: cmp(st.alpha_func); break;
    case 26: st.dither_enable = flag; break;
    case 27: st.alpha_blend_enable = flag; break;
    case 28: st.fog_enable = flag; break;
    case 29: st.specular_enable = flag; break;
    case 34: st.fog_color = value; break;
    case 35: fog(st.fog_table_mode); break;
    case 36: st.fog_start = as_float(value); break;
    case 37: st.fog_end = as_float(value); break;
    case 38: st.fog_density = as_float(value); break;
    case 48: st.range_fog_enable = flag; break;
    case 52: st.stencil_enable = flag; break;
    case 53: sop(st.stencil.fail); break;
    case 54: sop(st.stencil.zfail); break;
    case 55: sop(st.stencil.pass); break;
    case 56: cmp(st.stencil.func); break;
    case 57: st.stencil_ref = value; break;
    case 58: st.stencil_mask = value; break;
    case 59: st.stencil_write_mask = value; break;
    case 60: st.texture_factor = value; break;
    case 136: st.clipping = flag; break;
    case 140: fog(st.fog_vertex_mode); break;
    case 152: st.clip_plane_enable = value; break;
    case 154: st.point_size = as_float(value); break;
    case 155: st.point_size_min = as_float(value); break;
    case 156: st.point_sprite_enable = flag; break;
    case 157: st.point_scale_enable = flag; break;
    case 158: st.point_scale_a = as_float(value); break;
    case 159: st.point_scale_b = as_float(value); break;
    case 160: st.point_scale_c = as_float(value); break;
    case 161: st.multisample_antialias = flag; break;
    case 162: st.multisample_mask = value; break;
    case 166: st.point_size_max = as_float(value); break;
    case 168: st.color_write_enable[0] = value; break;
    case 171: bop(st.blend_op); break;
    case 174: st.scissor_test_enable = flag; break;
    case 175: st.slope_scale_depth_bias = as_float(value); break;
    case 176: st.antialiased_line_enable = flag; break;
    case 185: st.two_sided_stencil_mode = flag; break;
    case 186: sop(st.ccw_stencil.fail); break;
    case 187: sop(st.ccw_stencil.zfail); break;
    case 188: sop(st.ccw_stencil.pass); break;
    case 189: cmp(st.ccw_stencil.func); break;
    case 190: case 191: case 192: st.color_write_enable[type - 189] = value; break;
    case 193: st.blend_factor = value; break;
    case 194: st.srgb_write_enable = flag; break;
    case 195: st.depth_bias = as_float(value); break;
    case 206: st.separate_alpha_blend_enable = flag; break;
    case 207: blend(st.src_blend_alpha); break;
    case 208: blend(st.dest_blend_alpha); break;
    case 209: bop(st.blend_op_alpha); break;
    default:
        if (type >= 128 && type <= 135) st.wrap[type - 128] = value;
        else if (type >= 198 && type <= 205) st.wrap[type - 198 + 8] = value;
        break;
    }
    if (!valid) {
        r.ok = false;
        r.error = "render state " + std::to_string(type) + " (" + std::string(name->name) +
                  "): value " + std::to_string(value) + " is not a " + enum_name;
    }
    return r;
}

std::optional<uint32_t> get_render_state(const RenderState& st, uint32_t type) {
    auto e = [](auto v) { return static_cast<uint32_t>(v); };
    switch (type) {
    case 7: return e(st.z_enable);
    case 8: return e(st.fill_mode);
    case 9: return e(st.shade_mode);
    case 14: return e(st.z_write_enable);
    case 15: return e(st.alpha_test_enable);
    case 16: return e(st.last_pixel);
    case 19: return e(st.src_blend);
    case 20: return e(st.dest_blend);
    case 22: return e(st.cull_mode);
    case 23: return e(st.z_func);
    case 24: return st.alpha_ref;
    case 25: return e(st.alpha_func);
    case 26: return e(st.dither_enable);
    case 27: return e(st.alpha_blend_enable);
    case 28: return e(st.fog_enable);
    case 29: return e(st.specular_enable);
    case 34: return st.fog_color;
    case 35: return e(st.fog_table_mode);
    case 36: return as_bits(st.fog_start);
    case 37: return as_bits(st.fog_end);
    case 38: return as_bits(st.fog_density);
    case 48: return e(st.range_fog_enable);
    case 52: return e(st.stencil_enable);
    case 53: return e(st.stencil.fail);
    case 54: return e(st.stencil.zfail);
    case 55: return e(st.stencil.pass);
    case 56: return e(st.stencil.func);
    case 57: return st.stencil_ref;
    case 58: return st.stencil_mask;
    case 59: return st.stencil_write_mask;
    case 60: return st.texture_factor;
    case 136: return e(st.clipping);
    case 140: return e(st.fog_vertex_mode);
    case 152: return st.clip_plane_enable;
    case 154: return as_bits(st.point_size);
    case 155: return as_bits(st.point_size_min);
    case 156: return e(st.point_sprite_enable);
    case 157: return e(st.point_scale_enable);
    case 158: return as_bits(st.point_scale_a);
    case 159: return as_bits(st.point_scale_b);
    case 160: return as_bits(st.point_scale_c);
    case 161: return e(st.multisample_antialias);
    case 162: return st.multisample_mask;
    case 166: return as_bits(st.point_size_max);
    case 168: return st.color_write_enable[0];
    case 171: return e(st.blend_op);
    case 174: return e(st.scissor_test_enable);
    case 175: return as_bits(st.slope_scale_depth_bias);
    case 176: return e(st.antialiased_line_enable);
    case 185: return e(st.two_sided_stencil_mode);
    case 186: return e(st.ccw_stencil.fail);
    case 187: return e(st.ccw_stencil.zfail);
    case 188: return e(st.ccw_stencil.pass);
    case 189: return e(st.ccw_stencil.func);
    case 190: case 191: case 192: return st.color_write_enable[type - 189];
    case 193: return st.blend_factor;
    case 194: return e(st.srgb_write_enable);
    case 195: return as_bits(st.depth_bias);
    case 206: return e(st.separate_alpha_blend_enable);
    case 207: return e(st.src_blend_alpha);
    case 208: return e(st.dest_blend_alpha);
    case 209: return e(st.blend_op_alpha);
    default:
        if (type >= 128 && type <= 135) return st.wrap[type - 128];
        if (type >= 198 && type <= 205) return st.wrap[type - 198 + 8];
        return std::nullopt;
    }
}

}  // namespace sm2::runtime
