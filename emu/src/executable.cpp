// Executable: binding the draw's constants, and a readable listing of the steps.
#include "sm2/emu/executable.h"

#include <string>

#include "sm2/emu/batch.h"
#include "sm2/emu/instruction_trace.h"
#include "uniform_steps.h"

namespace sm2::emu {

ConstantFile Executable::bind_constants(std::span<const std::array<float, 4>> application) const {
    ConstantFile file;
    file.registers.reserve(constant_count());
    file.registers.assign(constant_count_, std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f});
    for (size_t i = 0; i < application.size() && i < file.registers.size(); ++i)
        file.registers[i] = application[i];
    // def values hold while the shader is bound, over whatever the application set.
    for (const auto& [index, value] : defs_)
        if (index < file.registers.size()) file.registers[index] = value;
    bind_derived_constants(prelude_, transcendentals_, file);
    return file;
}

void Executable::summarize_register_use() {
    for (const Step& step : steps_) {
        for (unsigned k = 0; k < step.source_count; ++k) {
            const StepSource& source = step.sources[k];
            if (source.kind != OperandKind::Lanes || source.index >= kSlotCount) continue;
            for (unsigned c = 0; c < 4; ++c)
                if ((source.channels >> c) & 1u)
                    components_read_[source.index] = static_cast<uint8_t>(
                        components_read_[source.index] | (1u << ((source.swizzle >> (2 * c)) & 3u)));
        }
        if (step.opcode != isa::Opcode::TexKill && !step.dest.address && step.dest.slot < kSlotCount)
            components_written_[step.dest.slot] = static_cast<uint8_t>(components_written_[step.dest.slot] | step.dest.mask);
    }
}

std::string slot_name(unsigned s) {
    struct Range {
        unsigned first, count;
        const char* name;
        bool numbered;
    };
    static constexpr Range kRanges[] = {
        {slot::kTempFirst, slot::kTempCount, "r", true},
        {slot::kInputFirst, slot::kInputCount, "v", true},
        {slot::kTexCoordFirst, slot::kTexCoordCount, "t", true},
        {slot::kPosition, 1, "oPos", false},
        {slot::kFog, 1, "oFog", false},
        {slot::kPointSize, 1, "oPts", false},
        {slot::kColorOutFirst, slot::kColorOutCount, "oD", true},
        {slot::kTexCoordOutFirst, slot::kTexCoordOutCount, "oT", true},
        {slot::kRenderTargetFirst, slot::kRenderTargetCount, "oC", true},
        {slot::kDepth, 1, "oDepth", false},
    };
    for (const Range& range : kRanges)
        if (s >= range.first && s < range.first + range.count)
            return range.name + (range.numbered ? std::to_string(s - range.first) : std::string());
    return "slot" + std::to_string(s);
}

namespace {

std::string mask_text(uint8_t mask) {
    if (mask == 0xF) return "";
    std::string s = ".";
    for (int c = 0; c < 4; ++c)
        if ((mask >> c) & 1) s += "xyzw"[c];
    return s;
}

std::string swizzle_text(uint8_t swizzle) {
    if (swizzle == 0xE4) return "";
    std::string s = ".";
    for (int c = 0; c < 4; ++c) s += "xyzw"[(swizzle >> (2 * c)) & 3];
    return s;
}

std::string source_text(const StepSource& s) {
    std::string text = s.negate ? "-" : "";
    switch (s.kind) {
    case OperandKind::Lanes: text += slot_name(s.index); break;
    case OperandKind::Constant: text += "c" + std::to_string(s.index); break;
    case OperandKind::RelativeConstant:
        text += "c[a0." + std::string(1, "xyzw"[s.address_component]) + " + " + std::to_string(s.index) + "]";
        break;
    case OperandKind::Zero: text += "zero"; break;
    }
    return text + swizzle_text(s.swizzle);
}

}  // namespace

std::string Executable::describe() const {
    std::string out;
    for (const Step& step : steps_) {
        const auto* info = isa::find_opcode(step.opcode, step.control);
        out += info ? std::string(info->mnemonic) : "?";
        if (step.dest.saturate) out += "_sat";
        if (step.opcode != isa::Opcode::TexKill)
            out += " " + (step.dest.address ? std::string("a0") : slot_name(step.dest.slot)) +
                   mask_text(step.dest.mask) + ",";
        for (unsigned k = 0; k < step.source_count; ++k)
            out += std::string(k ? ", " : " ") + source_text(step.sources[k]);
        if (step.opcode == isa::Opcode::Tex) out += ", sampler" + std::to_string(step.sampler);
        out += "\n";
    }
    return out;
}

}  // namespace sm2::emu
