// Shader::create: the structure the engine needs, found once per shader: matching flow-control
// blocks, subroutine labels, the end of the main program, and the def/defi/defb values.
#include <bit>
#include <string>

#include "sm2/emu/engine.h"

namespace sm2::emu {

using isa::Opcode;
using isa::RegisterType;

std::optional<unsigned> register_slot(isa::ShaderType shader, RegisterType type, unsigned index) {
    const bool vertex = shader == isa::ShaderType::Vertex;
    auto within = [&](unsigned first, unsigned count) -> std::optional<unsigned> {
        if (index < count) return first + index;
        return std::nullopt;
    };
    switch (type) {
    case RegisterType::Temp: return within(slot::kTempFirst, slot::kTempCount);
    case RegisterType::Input: return within(slot::kInputFirst, slot::kInputCount);
    case RegisterType::Texture:  // == Address: t# in a pixel shader, a0 in a vertex shader
        if (vertex) return std::nullopt;
        return within(slot::kTexCoordFirst, slot::kTexCoordCount);
    case RegisterType::RastOut:
        if (!vertex) return std::nullopt;
        if (index == isa::kRastOutPosition) return slot::kPosition;
        if (index == isa::kRastOutFog) return slot::kFog;
        if (index == isa::kRastOutPointSize) return slot::kPointSize;
        return std::nullopt;
    case RegisterType::AttrOut:
        if (!vertex) return std::nullopt;
        return within(slot::kColorOutFirst, slot::kColorOutCount);
    case RegisterType::TexCrdOut:
        if (!vertex) return std::nullopt;
        return within(slot::kTexCoordOutFirst, slot::kTexCoordOutCount);
    case RegisterType::ColorOut:
        if (vertex) return std::nullopt;
        return within(slot::kRenderTargetFirst, slot::kRenderTargetCount);
    case RegisterType::DepthOut:
        if (vertex || index != 0) return std::nullopt;
        return slot::kDepth;
    default: return std::nullopt;
    }
}

namespace {

constexpr size_t kMaxBlockNesting = 64;

std::string where(const isa::Program& program, size_t i) {
    const auto* info = program.instructions[i].info();
    return "instruction " + std::to_string(i) + " (" +
           std::string(info ? info->mnemonic : "comment") + "): ";
}

}  // namespace

ShaderCreateResult Shader::create(isa::Program program) {
    if (program.version.major != 2 || program.version.minor != 0)
        return {std::nullopt, "unsupported shader version " + program.version.name() +
                                  " (the engine runs vs_2_0 and ps_2_0)"};
    Shader shader;
    const auto& code = program.instructions;
    shader.partner_.assign(code.size(), SIZE_MAX);
    shader.main_end_ = code.size();

    struct Open {
        size_t at;
        Opcode opcode;
    };
    std::vector<Open> open;
    uint16_t bools_defined = 0;
    uint16_t ints_defined = 0;
    uint16_t bools_used = 0;
    uint16_t ints_used = 0;
    bool in_subroutines = false;
    for (size_t i = 0; i < code.size(); ++i) {
        const isa::Instruction& ins = code[i];
        auto fail = [&](const std::string& what) {
            return ShaderCreateResult{std::nullopt, where(program, i) + what};
        };
        switch (ins.opcode) {
        case Opcode::Def: {
            if (!ins.dest) return fail("missing register");
            Float4 value{};
            for (int k = 0; k < 4; ++k) value[k] = std::bit_cast<float>(ins.constant_bits[k]);
            shader.definitions_.floats.emplace_back(ins.dest->index, value);
            break;
        }
        case Opcode::DefI: {
            if (!ins.dest || ins.dest->index >= kIntConstants) return fail("bad integer register");
            Int4 value{};
            for (int k = 0; k < 4; ++k) value[k] = static_cast<int32_t>(ins.constant_bits[k]);
            shader.definitions_.integers.emplace_back(ins.dest->index, value);
            ints_defined = static_cast<uint16_t>(ints_defined | (1u << ins.dest->index));
            break;
        }
        case Opcode::DefB:
            if (!ins.dest || ins.dest->index >= kBoolConstants) return fail("bad boolean register");
            shader.definitions_.booleans.emplace_back(ins.dest->index, ins.constant_bits[0] != 0);
            bools_defined = static_cast<uint16_t>(bools_defined | (1u << ins.dest->index));
            break;
        case Opcode::If:
        case Opcode::Rep:
        case Opcode::Loop:
            // Far beyond any legal shader (16 flow instructions in all); keeps lowering's
            // recursion shallow for hostile input.
            if (open.size() >= kMaxBlockNesting) return fail("blocks nest deeper than " + std::to_string(kMaxBlockNesting));
            open.push_back({i, ins.opcode});
            break;
        case Opcode::Else:
            if (open.empty() || open.back().opcode != Opcode::If ||
                code[open.back().at].opcode == Opcode::Else)
                return fail("else without a matching if");
            shader.partner_[open.back().at] = i;
            open.back().at = i;  // the endif closes the else
            break;
        case Opcode::EndIf:
        case Opcode::EndRep:
        case Opcode::EndLoop: {
            const Opcode opener = ins.opcode == Opcode::EndIf    ? Opcode::If
                                  : ins.opcode == Opcode::EndRep ? Opcode::Rep
                                                                 : Opcode::Loop;
            if (open.empty() || open.back().opcode != opener)
                return fail("block end without a matching start");
            shader.partner_[open.back().at] = i;
            open.pop_back();
            break;
        }
        case Opcode::Label:
            if (!open.empty()) return fail("label inside a block");
            if (ins.sources.empty()) return fail("missing label register");
            if (!in_subroutines) shader.main_end_ = i;
            in_subroutines = true;
            shader.labels_.emplace_back(ins.sources[0].index, i);
            break;
        case Opcode::Ifc: case Opcode::Break: case Opcode::BreakC: case Opcode::BreakP:
        case Opcode::SetP: case Opcode::TexLdd: case Opcode::TexLdl: case Opcode::Dsx:
        case Opcode::Dsy: case Opcode::TexCoord: case Opcode::Cnd: case Opcode::Bem:
        case Opcode::Phase:
            return fail("not a vs_2_0/ps_2_0 instruction");
        default:
            break;
        }
        if (ins.opcode != Opcode::Comment && !ins.is_setup() && ins.predicate)
            return fail("predication does not exist in vs_2_0/ps_2_0");
        if (ins.opcode == Opcode::If || ins.opcode == Opcode::CallNz) {
            const size_t b = ins.opcode == Opcode::If ? 0 : 1;
            if (ins.sources.size() <= b || ins.sources[b].index >= kBoolConstants)
                return fail("bad boolean register");
            bools_used = static_cast<uint16_t>(bools_used | (1u << ins.sources[b].index));
        }
        if (ins.opcode == Opcode::Rep || ins.opcode == Opcode::Loop) {
            const size_t n = ins.opcode == Opcode::Rep ? 0 : 1;
            if (ins.sources.size() <= n || ins.sources[n].index >= kIntConstants)
                return fail("bad integer register");
            ints_used = static_cast<uint16_t>(ints_used | (1u << ins.sources[n].index));
        }
    }
    if (!open.empty())
        return {std::nullopt, where(program, open.back().at) + "block is never closed"};
    for (const auto& [label, at] : shader.labels_)
        for (const auto& [other, other_at] : shader.labels_)
            if (label == other && at != other_at)
                return {std::nullopt, where(program, other_at) + "label defined twice"};
    shader.booleans_used_ = bools_used;
    shader.integers_used_ = ints_used;
    shader.booleans_read_ = static_cast<uint16_t>(bools_used & ~bools_defined);
    shader.integers_read_ = static_cast<uint16_t>(ints_used & ~ints_defined);
    shader.program_ = std::move(program);
    return {std::move(shader), {}};
}

StaticFlowConstants Shader::effective_flow(const StaticFlowConstants& application) const {
    StaticFlowConstants flow = application;
    for (const auto& [index, value] : definitions_.booleans) flow.booleans[index] = value;
    for (const auto& [index, value] : definitions_.integers) flow.integers[index] = value;
    return flow;
}

StaticFlowConstants Shader::flow_key(const StaticFlowConstants& application) const {
    StaticFlowConstants key = effective_flow(application);
    for (unsigned n = 0; n < kBoolConstants; ++n)
        if (!((booleans_used_ >> n) & 1u)) key.booleans[n] = false;
    for (unsigned n = 0; n < kIntConstants; ++n)
        if (!((integers_used_ >> n) & 1u)) key.integers[n] = Int4{};
    return key;
}

std::optional<size_t> Shader::label_position(unsigned label) const {
    for (const auto& [l, at] : labels_)
        if (l == label) return at;
    return std::nullopt;
}

}  // namespace sm2::emu
