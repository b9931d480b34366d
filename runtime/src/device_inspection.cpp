// Device::inspect(): what is bound and set, read without changing anything (sm2 state, sm2 replay
// --snapshot).
#include "sm2/runtime/device_inspection.h"

#include "device_internal.h"
#include "sm2/runtime/d3d9_names.h"

namespace sm2::runtime {

namespace {

using Resource = Device::Resource;

const char* kind_name(const Resource& r) {
    switch (r.kind) {
    case Resource::Kind::VertexBuffer: return "vertex buffer";
    case Resource::Kind::IndexBuffer: return "index buffer";
    case Resource::Kind::Texture:
        switch (r.texture.type()) {
        case TextureType::Cube: return "cube texture";
        case TextureType::Volume: return "volume texture";
        case TextureType::Texture2D: break;
        }
        return "texture";
    case Resource::Kind::RenderTarget: return r.offscreen_plain ? "offscreen plain surface" : "render target";
    case Resource::Kind::DepthStencil: return "depth stencil";
    case Resource::Kind::Declaration: return "vertex declaration";
    case Resource::Kind::VertexShader: return "vertex shader";
    case Resource::Kind::PixelShader: return "pixel shader";
    case Resource::Kind::StateBlock: return "state block";
    }
    return "resource";
}

}  // namespace

DeviceInspection Device::inspect() const {
    // Bindings hold the resource, not its name: the name is the one the resource map has for it.
    auto describe = [this](const std::shared_ptr<Resource>& r) {
        ResourceDescription d;
        for (const auto& [name, resource] : resources_)
            if (resource == r) {
                d.name = name;
                break;
            }
        d.kind = kind_name(*r);
        d.pool = r->pool_of();
        d.render_target_usage = r->render_target_usage;
        d.dynamic_usage = r->dynamic_usage;
        switch (r->kind) {
        case Resource::Kind::Texture:
            d.width = r->texture.width();
            d.height = r->texture.height();
            d.depth = r->texture.depth();
            d.levels = r->texture.levels();
            d.format = r->texture.format();
            break;
        case Resource::Kind::RenderTarget:
            d.width = r->surface.width();
            d.height = r->surface.height();
            d.depth = 1;
            d.levels = 1;
            d.format = r->surface.format();
            break;
        case Resource::Kind::DepthStencil:
            d.pool = Pool::Default;  // depth-stencil surfaces are DEFAULT-pool, whatever the field says
            if (r->depth) {
                d.width = r->depth->width();
                d.height = r->depth->height();
                d.depth = 1;
                d.levels = 1;
                d.format = r->depth->format();
            }
            break;
        default: d.bytes = r->bytes.size(); break;
        }
        return d;
    };

    DeviceInspection in;
    for (unsigned i = 0; i < kMaxRenderTargets; ++i) {
        in.render_targets[i] = render_target_surface(i);
        if (render_targets_[i]) in.render_target_resources[i] = describe(render_targets_[i]);
    }
    if (depth_stencil_ && depth_stencil_->depth) {
        in.depth_stencil = &*depth_stencil_->depth;
        in.depth_stencil_resource = describe(depth_stencil_);
    }
    for (unsigned s = 0; s < kMaxSamplers; ++s)
        if (textures_[s]) in.textures[s] = describe(textures_[s]);
    for (unsigned s = 0; s < kMaxVertexStreams; ++s)
        if (streams_[s].buffer) in.streams[s] = StreamInspection{describe(streams_[s].buffer), streams_[s].offset, streams_[s].stride};
    if (indices_) {
        in.indices = describe(indices_);
        in.index_format = indices_->index_format;
    }
    if (declaration_) {
        in.declaration = describe(declaration_);
        in.declaration_elements = declaration_->elements;
    }
    auto shader = [&describe](const std::shared_ptr<Resource>& r) -> std::optional<ShaderInspection> {
        if (!r) return std::nullopt;
        ShaderInspection s{describe(r), nullptr};
        if (r->shader && r->shader->shader) s.program = &r->shader->shader->program();
        return s;
    };
    in.vertex_shader = shader(vertex_shader_);
    in.pixel_shader = shader(pixel_shader_);
    // The same reading as a state block's capture: the modelled states, then the accepted ones.
    for (const auto& info : render_states()) {
        std::optional<uint32_t> value = get_render_state(render_state_, info.id);
        if (!value)
            if (auto it = other_render_states_.find(info.id); it != other_render_states_.end()) value = it->second;
        in.render_states.emplace_back(info.id, value.value_or(0));
    }
    in.samplers = sampler_states_;
    in.fixed_function = &fixed_function_;
    in.viewport = viewport_;
    in.scissor = scissor_;
    in.vertex_constants_f = &vs_f_;
    in.pixel_constants_f = &ps_f_;
    in.vertex_flow = &vs_flow_;
    in.pixel_flow = &ps_flow_;
    in.back_buffer = back_buffer_ ? &back_buffer_->surface : nullptr;
    in.frames_presented = frame_;
    in.in_scene = in_scene_;
    return in;
}

}  // namespace sm2::runtime
