#include "compiled_shaders.h"

#include <algorithm>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace sm2::runtime {

namespace {

struct Entry {
    emu::Executable executable;
    std::shared_ptr<const emu::jit::CompiledShader> shader;
};

bool same_program(const emu::Executable& a, const emu::Executable& b) {
    return a.version() == b.version() && a.precision() == b.precision() && a.transcendentals() == b.transcendentals() &&
           a.constant_count() == b.constant_count() && std::ranges::equal(a.steps(), b.steps()) &&
           a.defs() == b.defs();  // the compiled code holds the def values
}

}  // namespace

CompiledLookup compiled_shader(const emu::Executable& executable) {
    static std::mutex mutex;
    // Keyed by the steps' text; entries with the same text are told apart by their steps.
    static std::unordered_map<std::string, std::vector<Entry>> cache;
    if (!emu::jit::available() || executable.precision() == emu::Precision::Fp64) return {};
    const std::string key = executable.describe();
    std::lock_guard lock(mutex);
    auto& bucket = cache[key];
    for (const Entry& e : bucket)
        if (same_program(e.executable, executable)) return {e.shader, false, 0};
    CompiledLookup result;
    result.shader = emu::jit::compile(executable);
    result.compiled_now = true;
    result.compile_seconds = result.shader ? result.shader->compile_seconds() : 0.0;
    result.from_cache = result.shader && result.shader->from_cache();
    bucket.push_back({executable, result.shader});  // a failure is remembered too: not retried
    return result;
}

}  // namespace sm2::runtime
