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

struct Device::Resource {
    enum class Kind : uint8_t {
        VertexBuffer, IndexBuffer, Texture, RenderTarget, DepthStencil, Declaration, VertexShader, PixelShader,
    };
    Kind kind = Kind::VertexBuffer;
    std::vector<std::byte> bytes;                  // vertex / index buffers
    IndexFormat index_format = IndexFormat::Index16;
    Texture texture;                               // textures
    bool render_target_usage = false;
    Surface surface;                               // render targets
    std::optional<DepthStencilSurface> depth;      // depth-stencil surfaces
    std::vector<VertexElement> elements;           // declarations
    std::shared_ptr<ShaderObject> shader;          // shaders
    uint64_t memory_bytes = 0;                     // counted against the memory limit while named
};

}  // namespace sm2::runtime
