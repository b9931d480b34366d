// The Device's resource and shader objects (shared by device.cpp and draw.cpp).
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "sm2/emu/engine.h"
#include "sm2/emu/jit.h"
#include "sm2/runtime/device.h"

namespace sm2::runtime {

struct Device::ShaderObject {
    std::optional<emu::Shader> shader;
    std::vector<ShaderInput> inputs;  // vertex shaders: dcl'd v# inputs
    bool texkill = false;
    // Lowered executables, one per (static flow key, outputs read): the pipeline cache.
    struct Lowered {
        emu::StaticFlowConstants flow;
        uint32_t outputs_read = 0;
        emu::Executable executable;
        // Engine::Jit: the executable as native code, looked up (or compiled) by the first draw
        // that runs it; null after that lookup when it cannot be compiled.
        bool compiled_looked_up = false;
        std::shared_ptr<const emu::jit::CompiledShader> compiled;
    };
    std::deque<Lowered> lowered;
};

struct StateBlockObject;  // state_block.h

struct Device::Resource {
    enum class Kind : uint8_t {
        VertexBuffer, IndexBuffer, Texture, RenderTarget, DepthStencil, Declaration, VertexShader, PixelShader,
        StateBlock,
    };
    Kind kind = Kind::VertexBuffer;
    std::vector<std::byte> bytes;                  // vertex / index buffers
    IndexFormat index_format = IndexFormat::Index16;
    Texture texture;                               // textures
    bool render_target_usage = false;
    bool dynamic_usage = false;                    // textures: D3DUSAGE_DYNAMIC (lockable in DEFAULT)
    Pool pool = Pool::Managed;                     // textures, off-screen plain surfaces
    bool offscreen_plain = false;                  // CreateOffscreenPlainSurface: not a render target
    Surface surface;                               // render targets, off-screen plain surfaces
    std::optional<DepthStencilSurface> depth;      // depth-stencil surfaces
    std::vector<VertexElement> elements;           // declarations
    std::shared_ptr<ShaderObject> shader;          // shaders
    std::shared_ptr<StateBlockObject> state_block; // state blocks
    uint64_t memory_bytes = 0;                     // counted against the memory limit while named

    // Render targets (CreateRenderTarget, the back buffer) are DEFAULT-pool surfaces.
    [[nodiscard]] Pool pool_of() const { return kind == Kind::RenderTarget && !offscreen_plain ? Pool::Default : pool; }
    // The surface of a texture level (face 0), a render target or an off-screen plain surface;
    // null for other kinds or a level out of range.
    [[nodiscard]] Surface* level_surface(uint32_t level) {
        if (kind == Kind::RenderTarget) return level == 0 ? &surface : nullptr;
        if (kind == Kind::Texture && texture.type() == TextureType::Texture2D && level < texture.levels())
            return &texture.surface(level, 0);
        return nullptr;
    }
};

}  // namespace sm2::runtime
