// The shader engine's public interface.
//
//   auto shader = Shader::create(program);          // once per shader: structure checked
//   auto lowered = lower(*shader.shader, flow);       // once per shader.flow_key(flow)
//   ConstantFile constants = lowered.executable->bind_constants(app_constants);  // per draw
//   Batch batch; ... fill inputs ...; execute(*lowered.executable, constants, batch, &sampler);
//
// An Executable is immutable: any number of threads may execute it at once, each with its own
// Batch.
//
// Lowering resolves all static flow control (if b#, loop/rep i#, call/callnz/ret) into one
// straight list of steps, turns c[aL + n] into fixed constants, expands matrix macros into dot
// products and removes every step no output depends on. Execution runs each step over a whole
// batch of lanes.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sm2/emu/batch.h"
#include "sm2/emu/executable.h"
#include "sm2/emu/precision.h"
#include "sm2/emu/sampler.h"
#include "sm2/isa/program.h"

namespace sm2::emu {

using Float4 = std::array<float, 4>;
using Int4 = std::array<int32_t, 4>;

constexpr unsigned kBoolConstants = 16;  // b0..b15
constexpr unsigned kIntConstants = 16;   // i0..i15

// The application's b# and i# values (SetVertexShaderConstantB/I) that decide static flow
// control. D3D9 defaults: FALSE and (0,0,0,0). A shader's defb/defi override them.
struct StaticFlowConstants {
    std::array<bool, kBoolConstants> booleans{};
    std::array<Int4, kIntConstants> integers{};
    friend bool operator==(const StaticFlowConstants&, const StaticFlowConstants&) = default;
};

// A decoded shader whose structure the engine understands: blocks matched, subroutines found,
// def/defi/defb collected. Built once when the shader is created.
struct ShaderCreateResult;

class Shader {
public:
    [[nodiscard]] static ShaderCreateResult create(isa::Program program);

    [[nodiscard]] const isa::Program& program() const { return program_; }
    [[nodiscard]] isa::ShaderVersion version() const { return program_.version; }
    // Which b#/i# the shader reads (bit n = register n) and does not define itself: only these
    // belong in a pipeline key.
    [[nodiscard]] uint16_t booleans_read() const { return booleans_read_; }
    [[nodiscard]] uint16_t integers_read() const { return integers_read_; }
    // The flow constants lowering uses: the application's, overridden by defb/defi.
    [[nodiscard]] StaticFlowConstants effective_flow(const StaticFlowConstants& application) const;
    // effective_flow() with every b#/i# the shader never reads set to FALSE / 0: two draws
    // whose keys are equal lower to the same executable (the pipeline cache's key part).
    [[nodiscard]] StaticFlowConstants flow_key(const StaticFlowConstants& application) const;

    // Structure found by create() (indices into program().instructions).
    struct Definitions {
        std::vector<std::pair<unsigned, Float4>> floats;  // def c#: register, value (last wins)
        std::vector<std::pair<unsigned, Int4>> integers;  // defi
        std::vector<std::pair<unsigned, bool>> booleans;  // defb
    };
    [[nodiscard]] const Definitions& definitions() const { return definitions_; }
    // For if/else/rep/loop: the index of the matching else/endif/endrep/endloop; for else: its
    // endif. Other instructions: SIZE_MAX.
    [[nodiscard]] size_t partner(size_t instruction) const { return partner_[instruction]; }
    // The main program is [0, main_end); subroutine l# starts after its label.
    [[nodiscard]] size_t main_end() const { return main_end_; }
    [[nodiscard]] std::optional<size_t> label_position(unsigned label) const;

private:
    Shader() = default;
    isa::Program program_;
    Definitions definitions_;
    std::vector<size_t> partner_;
    std::vector<std::pair<unsigned, size_t>> labels_;
    size_t main_end_ = 0;
    uint16_t booleans_read_ = 0;
    uint16_t integers_read_ = 0;
    uint16_t booleans_used_ = 0;  // read by if/callnz, defined or not
    uint16_t integers_used_ = 0;  // read by rep/loop
};

struct ShaderCreateResult {
    std::optional<Shader> shader;
    std::string error;  // "instruction 7 (else): else without a matching if"
};

struct LoweringOptions {
    PrecisionOptions precision;
    // D3DCAPS9.MaxVShaderInstructionsExecuted / MaxPShaderInstructionsExecuted (at least 65535).
    // Counts every instruction executed after loops are unrolled and calls inlined.
    uint32_t max_executed_instructions = 65535;
    // Constant registers the application can set (D3DCAPS9.MaxVertexShaderConst; ps_2_0: 32).
    // 0 = the profile's documented count. Relative reads outside [0, count) return (0,0,0,0).
    unsigned constant_count = 0;
    // Output slots the next stage reads (bit s - slot::kPosition); outputs outside the mask
    // are not computed. Default: all.
    uint32_t outputs_read = ~0u;
    // Keep steps no output depends on (for tests that look at temps).
    bool keep_dead_code = false;
    // Move the steps whose sources are the same on every lane into the executable's prelude,
    // computed once per draw by bind_constants() (hoist_uniform_steps()). Not with
    // keep_dead_code (the debugger shows every step), fp64, or constants read relatively.
    bool hoist_uniform_steps = false;
};

struct LowerResult {
    std::optional<Executable> executable;
    std::string error;
};

[[nodiscard]] LowerResult lower(const Shader& shader, const StaticFlowConstants& flow,
                                const LoweringOptions& options = {});

// `executable` with its uniform steps moved to a prelude that bind_constants() runs once per
// draw: a step all of whose sources are constants, or components of temporaries that only such
// steps wrote, computes the same value on every lane, so each later step that reads such a
// temporary reads a derived constant instead (the value the prelude leaves in it at that
// point), and the uniform steps nothing else reads are removed (`outputs_read` as in
// LoweringOptions). The same bits on every lane, in every mode but fp64 (whose temporaries hold
// doubles, which a float constant cannot): returned unchanged there, with a relatively
// addressed constant (the derived registers would lie in its range), or with nothing to hoist.
[[nodiscard]] Executable hoist_uniform_steps(const Executable& executable, uint32_t outputs_read = ~0u);

// Runs every step of `executable` over all lanes of `batch`. `sampler` may be null for shaders
// without texture instructions. A float batch runs fp32/fp24/fp16 executables; an fp64
// executable needs a ReferenceBatch (std::invalid_argument otherwise).
void execute(const Executable& executable, const ConstantFile& constants, Batch& batch,
             Sampler* sampler = nullptr);
void execute(const Executable& executable, const ConstantFile& constants, ReferenceBatch& batch,
             Sampler* sampler = nullptr);

// The same, calling `observer(step_index, step)` after each step, with the batch as that step
// left it (tracing: sm2 run --trace). The plain overloads above pay nothing for this.
using StepObserver = std::function<void(size_t, const Step&)>;
void execute(const Executable& executable, const ConstantFile& constants, Batch& batch, Sampler* sampler,
             const StepObserver& observer);
void execute(const Executable& executable, const ConstantFile& constants, ReferenceBatch& batch,
             Sampler* sampler, const StepObserver& observer);

}  // namespace sm2::emu
