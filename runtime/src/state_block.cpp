// State blocks: CreateStateBlock, BeginStateBlock/EndStateBlock, Capture, Apply (state_block.h).
//
// Recording follows D3D9: the Set* calls between BeginStateBlock and EndStateBlock go into the
// block, not the device. The device executes them as usual and remembers what they select; at
// EndStateBlock the block captures the selected values and the device gets back the whole state
// it had at BeginStateBlock.
#include "state_block.h"

#include <initializer_list>

#include "sm2/runtime/d3d9_names.h"

namespace sm2::runtime {

namespace {

// D3DRS_* values of the render states of pixel state ("Saving Pixel State With a StateBlock"):
// ZENABLE, FILLMODE, SHADEMODE, ZWRITEENABLE, ALPHATESTENABLE, LASTPIXEL, SRCBLEND, DESTBLEND,
// ZFUNC, ALPHAREF, ALPHAFUNC, DITHERENABLE, ALPHABLENDENABLE, SPECULARENABLE, FOGSTART, FOGEND,
// FOGDENSITY, STENCIL*, TEXTUREFACTOR, WRAP0..7, LOCALVIEWER, the four *MATERIALSOURCE,
// COLORWRITEENABLE, BLENDOP, SCISSORTESTENABLE, SLOPESCALEDEPTHBIAS, ANTIALIASEDLINEENABLE,
// TWOSIDEDSTENCILMODE, CCW_STENCIL*, COLORWRITEENABLE1..3, BLENDFACTOR, SRGBWRITEENABLE,
// DEPTHBIAS, WRAP8..15, SEPARATEALPHABLENDENABLE, SRCBLENDALPHA, DESTBLENDALPHA, BLENDOPALPHA.
constexpr std::initializer_list<uint32_t> kPixelRenderStates = {
    7,   8,   9,   14,  15,  16,  19,  20,  23,  24,  25,  26,  27,  29,  36,  37,  38,  52,  53,  54,
    55,  56,  57,  58,  59,  60,  128, 129, 130, 131, 132, 133, 134, 135, 142, 145, 146, 147, 148, 168,
    171, 174, 175, 176, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 198, 199, 200, 201, 202,
    203, 204, 205, 206, 207, 208, 209,
};

// Render states of vertex state ("Saving Vertex States With a StateBlock"): SHADEMODE,
// CULLMODE, FOGENABLE, SPECULARENABLE, FOGCOLOR, FOGTABLEMODE, FOGSTART, FOGEND, FOGDENSITY,
// RANGEFOGENABLE, CLIPPING, LIGHTING, AMBIENT, FOGVERTEXMODE, COLORVERTEX, LOCALVIEWER,
// NORMALIZENORMALS, the four *MATERIALSOURCE, VERTEXBLEND, CLIPPLANEENABLE, the point states,
// MULTISAMPLEANTIALIAS, MULTISAMPLEMASK, PATCHEDGESTYLE, POINTSIZE_MAX,
// INDEXEDVERTEXBLENDENABLE, TWEENFACTOR, POSITIONDEGREE, NORMALDEGREE and the tessellation
// states (MINTESSELLATIONLEVEL ... ENABLEADAPTIVETESSELLATION).
constexpr std::initializer_list<uint32_t> kVertexRenderStates = {
    9,   22,  28,  29,  34,  35,  36,  37,  38,  48,  136, 137, 139, 140, 141, 142, 143, 145, 146, 147,
    148, 151, 152, 154, 155, 156, 157, 158, 159, 160, 161, 162, 163, 166, 167, 170, 172, 173, 178, 179,
    180, 181, 182, 183, 184,
};

// Copies the selected fixed-function parts from `from` to `to` (capture and apply alike).
void capture_fixed_function(const Device::StateSelection& selection, const FixedFunctionState& from,
                            FixedFunctionState& to) {
    for (unsigned t = 0; t < kMaxTextureStages; ++t)
        for (uint32_t type = 0; type < kTextureStageStateCount; ++type)
            if (selection.stage_states[t].test(type)) to.stages[t][type] = from.stages[t][type];
    const auto& transforms = selection.transforms;
    if (transforms.test(transform_slot(kTransformView))) to.view = from.view;
    if (transforms.test(transform_slot(kTransformProjection))) to.projection = from.projection;
    for (uint32_t t = 0; t < kMaxTextureStages; ++t)
        if (transforms.test(transform_slot(kTransformTexture0 + t))) to.texture[t] = from.texture[t];
    for (uint32_t w = 0; w < kMaxWorldMatrices; ++w)
        if (transforms.test(transform_slot(kTransformWorld + w))) to.world[w] = from.world[w];
    if (selection.material) to.material = from.material;
    if (selection.lights) {
        to.lights = from.lights;
        to.enabled_lights = from.enabled_lights;
    }
    if (selection.fvf) to.fvf = from.fvf;
}

CallResult no_block(const char* call, const std::string& name) {
    return CallResult::fail(std::string(call) + ": '" + name + "' is not a state block");
}

}  // namespace

void Device::StateSelection::merge(const StateSelection& other) {
    render_states |= other.render_states;
    for (unsigned s = 0; s < kMaxSamplers; ++s) sampler_states[s] |= other.sampler_states[s];
    textures |= other.textures;
    streams |= other.streams;
    clip_planes |= other.clip_planes;
    vs_float |= other.vs_float;
    ps_float |= other.ps_float;
    vs_int |= other.vs_int;
    ps_int |= other.ps_int;
    vs_bool |= other.vs_bool;
    ps_bool |= other.ps_bool;
    vertex_shader |= other.vertex_shader;
    pixel_shader |= other.pixel_shader;
    declaration |= other.declaration;
    indices |= other.indices;
    viewport |= other.viewport;
    scissor |= other.scissor;
    for (unsigned t = 0; t < kMaxTextureStages; ++t) stage_states[t] |= other.stage_states[t];
    transforms |= other.transforms;
    material |= other.material;
    lights |= other.lights;
    fvf |= other.fvf;
}

Device::StateSelection Device::StateSelection::for_type(StateBlockType type) {
    StateSelection s;
    const bool all = type == StateBlockType::All;
    if (all || type == StateBlockType::PixelState) {
        for (uint32_t id : kPixelRenderStates) s.render_states.set(id);
        // Every sampler state of the pixel samplers (vertex samplers, which would be vertex
        // state, are not on this device).
        for (auto& sampler : s.sampler_states) sampler.set().reset(0);
        s.pixel_shader = true;
        s.ps_float.set();
        s.ps_int.set();
        s.ps_bool.set();
        for (auto& stage : s.stage_states) stage.set();
    }
    if (all || type == StateBlockType::VertexState) {
        for (uint32_t id : kVertexRenderStates) s.render_states.set(id);
        s.vertex_shader = true;
        s.declaration = true;
        s.vs_float.set();
        s.vs_int.set();
        s.vs_bool.set();
        for (auto& stage : s.stage_states) stage.set(kTssTexCoordIndex).set(kTssTextureTransformFlags);
        s.lights = true;
        s.fvf = true;
    }
    if (all) {
        // Only D3DSBT_ALL ("Saving All Device States"): the textures, vertex streams, index
        // buffer, viewport, scissor rectangle and clip planes.
        s.textures.set();
        s.streams.set();
        s.indices = true;
        s.viewport = true;
        s.scissor = true;
        s.clip_planes.set();
        s.transforms.set();
        s.material = true;
    }
    return s;
}

void Device::select(uint32_t render_state) {
    if (recording_ && render_state < kRenderStateSlots) recording_->render_states.set(render_state);
}

void Device::select_sampler(uint32_t sampler, uint32_t type) {
    if (recording_ && sampler < kMaxSamplers && type < kSamplerStateSlots) recording_->sampler_states[sampler].set(type);
}

void Device::select_binding(void (*mark)(StateSelection&, uint32_t), uint32_t index) {
    if (recording_) mark(*recording_, index);
}

void Device::capture(const StateSelection& selection, StateSnapshot& snapshot) const {
    for (uint32_t id = 0; id < kRenderStateSlots; ++id) {
        if (!selection.render_states.test(id)) continue;
        if (auto value = get_render_state(render_state_, id)) {
            snapshot.render_states[id] = *value;
        } else if (auto it = other_render_states_.find(id); it != other_render_states_.end()) {
            snapshot.render_states[id] = it->second;
        }
    }
    for (unsigned s = 0; s < kMaxSamplers; ++s)
        for (uint32_t type = 1; type < kSamplerStateSlots; ++type)
            if (selection.sampler_states[s].test(type))
                snapshot.sampler_states[s][type] = sampler_states_[s].get(type).value_or(0);
    for (unsigned s = 0; s < kMaxSamplers; ++s)
        if (selection.textures.test(s)) snapshot.textures[s] = textures_[s];
    for (unsigned i = 0; i < kMaxVertexStreams; ++i)
        if (selection.streams.test(i)) {
            snapshot.stream_buffers[i] = streams_[i].buffer;
            snapshot.stream_offsets[i] = streams_[i].offset;
            snapshot.stream_strides[i] = streams_[i].stride;
        }
    for (unsigned i = 0; i < kMaxUserClipPlanes; ++i)
        if (selection.clip_planes.test(i)) snapshot.clip_planes[i] = clip_planes_[i];
    snapshot.vs_float.resize(vs_f_.size());
    snapshot.ps_float.resize(ps_f_.size());
    for (size_t r = 0; r < vs_f_.size(); ++r)
        if (selection.vs_float.test(r)) snapshot.vs_float[r] = vs_f_[r];
    for (size_t r = 0; r < ps_f_.size(); ++r)
        if (selection.ps_float.test(r)) snapshot.ps_float[r] = ps_f_[r];
    for (unsigned r = 0; r < kMaxConstantsI; ++r) {
        if (selection.vs_int.test(r)) snapshot.vs_flow.integers[r] = vs_flow_.integers[r];
        if (selection.ps_int.test(r)) snapshot.ps_flow.integers[r] = ps_flow_.integers[r];
    }
    for (unsigned r = 0; r < kMaxConstantsB; ++r) {
        if (selection.vs_bool.test(r)) snapshot.vs_flow.booleans[r] = vs_flow_.booleans[r];
        if (selection.ps_bool.test(r)) snapshot.ps_flow.booleans[r] = ps_flow_.booleans[r];
    }
    if (selection.vertex_shader) snapshot.vertex_shader = vertex_shader_;
    if (selection.pixel_shader) snapshot.pixel_shader = pixel_shader_;
    if (selection.declaration) snapshot.declaration = declaration_;
    if (selection.indices) snapshot.indices = indices_;
    if (selection.viewport) snapshot.viewport = viewport_;
    if (selection.scissor) snapshot.scissor = scissor_;
    capture_fixed_function(selection, fixed_function_, snapshot.fixed_function);
}

void Device::apply(const StateSelection& selection, const StateSnapshot& snapshot) {
    // Values were valid when captured, so every set below succeeds; the results need no check.
    for (uint32_t id = 0; id < kRenderStateSlots; ++id)
        if (selection.render_states.test(id) && find_render_state(id)) (void)set_render_state(id, snapshot.render_states[id]);
    for (unsigned s = 0; s < kMaxSamplers; ++s)
        for (uint32_t type = 1; type < kSamplerStateSlots; ++type)
            if (selection.sampler_states[s].test(type)) (void)set_sampler_state(s, type, snapshot.sampler_states[s][type]);
    for (unsigned s = 0; s < kMaxSamplers; ++s)
        if (selection.textures.test(s)) {
            textures_[s] = snapshot.textures[s];
            sampler_.set_texture(s, textures_[s] ? &textures_[s]->texture : nullptr);
        }
    for (unsigned i = 0; i < kMaxVertexStreams; ++i)
        if (selection.streams.test(i))
            streams_[i] = StreamBinding{snapshot.stream_buffers[i], snapshot.stream_offsets[i], snapshot.stream_strides[i]};
    for (unsigned i = 0; i < kMaxUserClipPlanes; ++i)
        if (selection.clip_planes.test(i)) clip_planes_[i] = snapshot.clip_planes[i];
    for (size_t r = 0; r < vs_f_.size() && r < snapshot.vs_float.size(); ++r)
        if (selection.vs_float.test(r)) vs_f_[r] = snapshot.vs_float[r];
    for (size_t r = 0; r < ps_f_.size() && r < snapshot.ps_float.size(); ++r)
        if (selection.ps_float.test(r)) ps_f_[r] = snapshot.ps_float[r];
    for (unsigned r = 0; r < kMaxConstantsI; ++r) {
        if (selection.vs_int.test(r)) vs_flow_.integers[r] = snapshot.vs_flow.integers[r];
        if (selection.ps_int.test(r)) ps_flow_.integers[r] = snapshot.ps_flow.integers[r];
    }
    for (unsigned r = 0; r < kMaxConstantsB; ++r) {
        if (selection.vs_bool.test(r)) vs_flow_.booleans[r] = snapshot.vs_flow.booleans[r];
        if (selection.ps_bool.test(r)) ps_flow_.booleans[r] = snapshot.ps_flow.booleans[r];
    }
    if (selection.vertex_shader) vertex_shader_ = snapshot.vertex_shader;
    if (selection.pixel_shader) pixel_shader_ = snapshot.pixel_shader;
    if (selection.declaration) declaration_ = snapshot.declaration;
    if (selection.indices) indices_ = snapshot.indices;
    if (selection.viewport) viewport_ = snapshot.viewport;
    if (selection.scissor) scissor_ = snapshot.scissor;
    capture_fixed_function(selection, snapshot.fixed_function, fixed_function_);
}

CallResult Device::create_state_block(const std::string& name, StateBlockType type) {
    if (type != StateBlockType::All && type != StateBlockType::PixelState && type != StateBlockType::VertexState)
        return CallResult::fail("CreateStateBlock: type " + std::to_string(static_cast<uint32_t>(type)) +
                                " is not ALL, PIXELSTATE or VERTEXSTATE");
    if (recording_) return CallResult::fail("CreateStateBlock: a state block is being recorded");
    auto block = std::make_shared<StateBlockObject>();
    block->selection = StateSelection::for_type(type);
    capture(block->selection, block->snapshot);
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::StateBlock;
    r->state_block = std::move(block);
    return add_resource(name, std::move(r));
}

CallResult Device::begin_state_block() {
    if (recording_) return CallResult::fail("BeginStateBlock: a state block is already being recorded");
    // What the device holds now, given back at EndStateBlock.
    auto before = std::make_shared<StateBlockObject>();
    before->selection = StateSelection::for_type(StateBlockType::All);
    capture(before->selection, before->snapshot);
    state_before_recording_ = std::move(before);
    recording_ = std::make_unique<StateSelection>();
    return {};
}

CallResult Device::end_state_block(const std::string& name) {
    if (!recording_) return CallResult::fail("EndStateBlock: without BeginStateBlock");
    if (name.empty() || name == "NULL" || resources_.count(name))
        return CallResult::fail("EndStateBlock: '" + name + "' is not a free resource name");
    auto block = std::make_shared<StateBlockObject>();
    block->selection = *recording_;
    capture(block->selection, block->snapshot);
    recording_.reset();
    apply(state_before_recording_->selection, state_before_recording_->snapshot);
    state_before_recording_.reset();
    auto r = std::make_shared<Resource>();
    r->kind = Resource::Kind::StateBlock;
    r->state_block = std::move(block);
    return add_resource(name, std::move(r));
}

CallResult Device::capture_state_block(const std::string& name) {
    auto r = find(name);
    if (!r || r->kind != Resource::Kind::StateBlock) return no_block("Capture", name);
    capture(r->state_block->selection, r->state_block->snapshot);
    return {};
}

CallResult Device::apply_state_block(const std::string& name) {
    auto r = find(name);
    if (!r || r->kind != Resource::Kind::StateBlock) return no_block("Apply", name);
    // Applied while recording: the states it sets join the recorded block.
    if (recording_) recording_->merge(r->state_block->selection);
    apply(r->state_block->selection, r->state_block->snapshot);
    return {};
}

}  // namespace sm2::runtime
