// The JIT's routines for the draw (DeviceOptions::engine = Engine::Jit): one compiled shader per
// distinct executable, shared by every Device of the process, so a benchmark's repeated runs or
// a test's many devices compile each shader once.
#pragma once

#include <memory>

#include "sm2/emu/executable.h"
#include "sm2/emu/jit.h"

namespace sm2::runtime {

struct CompiledLookup {
    std::shared_ptr<const emu::jit::CompiledShader> shader;  // null: run the interpreter
    bool compiled_now = false;                                // this call compiled it
    double compile_seconds = 0;                               // when compiled_now
    bool from_cache = false;  // when compiled_now: loaded from the JIT cache (jit.h)
};

// The compiled form of `executable`, compiling it on first use. Null when this build or CPU has
// no JIT or the compilation failed (the draw then interprets; the result is the same).
[[nodiscard]] CompiledLookup compiled_shader(const emu::Executable& executable);

}  // namespace sm2::runtime
