// The executable form of a shader for one draw: a straight list of steps with every operand
// resolved to a lane slot, a constant, or a relatively addressed constant. No branches remain.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sm2/emu/precision.h"
#include "sm2/isa/opcodes.h"
#include "sm2/isa/version.h"

namespace sm2::emu {

// Number of lane slots (slot::kCount in batch.h; repeated here so this header stands alone).
constexpr unsigned kSlotCount = 74;

enum class OperandKind : uint8_t {
    Lanes,             // a per-lane register: index = slot
    Constant,          // c#: index = constant register (c[aL + n] is resolved to this)
    RelativeConstant,  // c[a0.? + n]: index = n, address_component = ?; chosen per lane
    Zero,              // a constant read outside the constant file: (0,0,0,0)
};

struct StepSource {
    OperandKind kind = OperandKind::Lanes;
    uint16_t index = 0;
    uint8_t swizzle = 0xE4;          // component read for result channel c: (swizzle >> 2c) & 3
    bool negate = false;
    uint8_t address_component = 0;   // RelativeConstant: which component of a0
    uint8_t channels = 0xF;          // result channels this source is read for (bit c)
    friend bool operator==(const StepSource&, const StepSource&) = default;
};

struct StepDest {
    uint16_t slot = 0;               // lane slot written (unused for texkill)
    uint8_t mask = 0xF;
    bool saturate = false;
    bool address = false;            // mova: writes a0 instead of a slot
    ResultRounding rounding = ResultRounding::None;
    friend bool operator==(const StepDest&, const StepDest&) = default;
};

struct Step {
    isa::Opcode opcode = isa::Opcode::Nop;  // matrix macros appear as dp3/dp4 steps
    uint8_t control = 0;                    // texld variant (isa::kTexLd*)
    uint8_t source_count = 0;
    uint8_t sampler = 0;                    // texld: s#
    StepDest dest;
    std::array<StepSource, 3> sources{};
    uint32_t origin = 0;                    // index of the instruction in the Program
    friend bool operator==(const Step&, const Step&) = default;
};

// The steps of an executable whose every source holds one value on all lanes (constants, and
// temporaries only such steps wrote), run once per draw by bind_constants() instead of once per
// batch (uniform_steps.cpp). A snapshot is a temporary as the first `after` steps leave it: the
// derived constant that the executable's steps read in its place.
struct UniformSnapshot {
    uint16_t slot = 0;
    uint32_t after = 0;
    friend bool operator==(const UniformSnapshot&, const UniformSnapshot&) = default;
};
struct UniformPrelude {
    std::vector<Step> steps;
    std::vector<UniformSnapshot> snapshots;  // derived constant j is constant register count + j
    friend bool operator==(const UniformPrelude&, const UniformPrelude&) = default;
};

// Float constants as one draw sees them: the application's values with the shader's def
// values written over them (the application's stored values are not changed).
struct ConstantFile {
    std::vector<std::array<float, 4>> registers;
};

class Executable {
public:
    Executable(isa::ShaderVersion version, Precision precision, unsigned constant_count,
               std::vector<Step> steps, std::vector<std::pair<unsigned, std::array<float, 4>>> defs,
               uint32_t executed_instructions, Transcendentals transcendentals = Transcendentals::Exact,
               UniformPrelude prelude = {})
        : version_(version), precision_(precision), transcendentals_(transcendentals),
          constant_count_(constant_count), steps_(std::move(steps)), defs_(std::move(defs)),
          executed_instructions_(executed_instructions), prelude_(std::move(prelude)) {
        summarize_register_use();
    }

    [[nodiscard]] isa::ShaderVersion version() const { return version_; }
    [[nodiscard]] Precision precision() const { return precision_; }
    [[nodiscard]] Transcendentals transcendentals() const { return transcendentals_; }
    [[nodiscard]] std::span<const Step> steps() const { return steps_; }
    // The constant file's size: the application's registers, then the derived constants of the
    // prelude's snapshots.
    [[nodiscard]] unsigned constant_count() const {
        return constant_count_ + static_cast<unsigned>(prelude_.snapshots.size());
    }
    // The application's constant registers alone (D3DCAPS9's count for the profile).
    [[nodiscard]] unsigned application_constant_count() const { return constant_count_; }
    // The uniform steps bind_constants() runs once (empty unless lowering hoisted some).
    [[nodiscard]] const UniformPrelude& prelude() const { return prelude_; }
    // Instructions the original shader executes for this draw (the limit lowering checked).
    [[nodiscard]] uint32_t executed_instructions() const { return executed_instructions_; }
    // Per lane slot (slot::k*), the components the steps read / write (bit c = component c).
    // Tells the runtime which vertex attributes to fetch and which interpolants to set up
    // (inputs), and which outputs the shader produces.
    [[nodiscard]] const std::array<uint8_t, kSlotCount>& components_read() const { return components_read_; }
    [[nodiscard]] const std::array<uint8_t, kSlotCount>& components_written() const { return components_written_; }
    // The shader's def values (register, value), in the order bind_constants() applies them.
    [[nodiscard]] const std::vector<std::pair<unsigned, std::array<float, 4>>>& defs() const { return defs_; }
    // Once per draw: the application's constants (missing ones read (0,0,0,0)) with the
    // shader's def values on top, then the prelude's derived constants.
    [[nodiscard]] ConstantFile bind_constants(std::span<const std::array<float, 4>> application = {}) const;
    // One line per step ("dp4 oPos.x, v0, c0"), for tests and debugging.
    [[nodiscard]] std::string describe() const;

private:
    void summarize_register_use();

    isa::ShaderVersion version_;
    Precision precision_;
    Transcendentals transcendentals_;
    unsigned constant_count_;
    std::vector<Step> steps_;
    std::vector<std::pair<unsigned, std::array<float, 4>>> defs_;
    uint32_t executed_instructions_;
    UniformPrelude prelude_;
    std::array<uint8_t, kSlotCount> components_read_{};
    std::array<uint8_t, kSlotCount> components_written_{};
};

}  // namespace sm2::emu
