// Program -> text the assembler reads back into the same bytes.
#include "sm2/assembler/disassembler.h"

#include <algorithm>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/isa/bytecode.h"

#include "sm2/isa/opcodes.h"
#include "sm2/isa/registers.h"
#include "syntax.h"

namespace sm2::assembler {

namespace {

using isa::RegisterType;
using isa::SourceModifier;

std::string register_text(isa::ShaderVersion version, RegisterType type, uint32_t index) {
    return isa::register_name(version, type, index);
}

// The file name without the number, for c[a0.x + n].
std::string register_base_name(isa::ShaderVersion version, RegisterType type, uint32_t index) {
    if (const isa::RegisterFile* f = isa::find_register_file(version, type, index))
        return std::string(f->name);
    // Out-of-table index: still print something recognisable.
    std::string name = isa::register_name(version, type, 0);
    while (!name.empty() && name.back() >= '0' && name.back() <= '9') name.pop_back();
    return name;
}

std::string destination_text(isa::ShaderVersion version, const isa::DestinationParameter& d) {
    std::string s = register_text(version, d.type, d.index);
    const isa::RegisterFile* f = isa::find_register_file(version, d.type, d.index);
    if (f && f->scalar && d.write_mask == isa::kMaskAll) return s;
    const std::string mask = syntax::format_write_mask(d.write_mask);
    if (!mask.empty()) s += "." + mask;
    return s;
}

std::string source_text(isa::ShaderVersion version, const isa::SourceParameter& src) {
    std::string s;
    std::string suffix;
    switch (src.modifier) {
    case SourceModifier::None: break;
    case SourceModifier::Negate: s = "-"; break;
    case SourceModifier::Not: s = "!"; break;
    // Not SM2 (the assembler rejects them); printed in the ps_1_x notation for reading.
    case SourceModifier::Bias: suffix = "_bias"; break;
    case SourceModifier::BiasNegate: s = "-"; suffix = "_bias"; break;
    case SourceModifier::Sign: suffix = "_bx2"; break;
    case SourceModifier::SignNegate: s = "-"; suffix = "_bx2"; break;
    case SourceModifier::Complement: s = "1-"; break;
    case SourceModifier::X2: suffix = "_x2"; break;
    case SourceModifier::X2Negate: s = "-"; suffix = "_x2"; break;
    case SourceModifier::DivideZ: suffix = "_dz"; break;
    case SourceModifier::DivideW: suffix = "_dw"; break;
    case SourceModifier::Abs: suffix = "_abs"; break;
    case SourceModifier::AbsNegate: s = "-"; suffix = "_abs"; break;
    }
    if (src.relative) {
        s += register_base_name(version, src.type, src.index);
        s += '[';
        s += src.relative->type == RegisterType::Loop ? "aL" : "a0";
        const std::string rel_swizzle = syntax::format_swizzle(src.relative->swizzle);
        if (!rel_swizzle.empty()) s += "." + rel_swizzle;
        if (src.index != 0) s += " + " + std::to_string(src.index);
        s += ']';
    } else {
        s += register_text(version, src.type, src.index);
    }
    s += suffix;
    const std::string swizzle = syntax::format_swizzle(src.swizzle);
    if (!swizzle.empty()) s += "." + swizzle;
    return s;
}

std::string result_modifiers(const isa::DestinationParameter& d) {
    std::string s;
    if (d.saturate) s += "_sat";
    if (d.partial_precision) s += "_pp";
    if (d.centroid) s += "_centroid";
    switch (d.shift) {
    case 0: break;
    case 1: s += "_x2"; break;
    case 2: s += "_x4"; break;
    case 3: s += "_x8"; break;
    case 13: s += "_d8"; break;
    case 14: s += "_d4"; break;
    case 15: s += "_d2"; break;
    default: s += "_shift" + std::to_string(d.shift); break;
    }
    return s;
}

std::string comparison_suffix(uint8_t control) {
    static constexpr const char* kNames[] = {"", "_gt", "_eq", "_ge", "_lt", "_ne", "_le", ""};
    return kNames[control & 7];
}

std::string format_dcl(isa::ShaderVersion version, const isa::Instruction& ins) {
    const isa::DestinationParameter d = ins.dest.value_or(isa::DestinationParameter{});
    std::string s = "dcl";
    if (d.type == RegisterType::Sampler) {
        const std::string_view type = syntax::texture_type_name(ins.declaration.texture_type);
        if (!type.empty()) s += "_" + std::string(type);
    } else if (version.is_vertex() || ins.declaration.usage != isa::DeclUsage::Position ||
               ins.declaration.usage_index != 0) {
        s += "_" + std::string(syntax::usage_name(ins.declaration.usage));
        if (ins.declaration.usage_index != 0) s += std::to_string(ins.declaration.usage_index);
    }
    s += result_modifiers(d);
    s += " " + destination_text(version, d);
    return s;
}

}  // namespace

std::string format_instruction(isa::ShaderVersion version, const isa::Instruction& ins) {
    if (ins.opcode == isa::Opcode::Comment)
        return "// comment: " + std::to_string(ins.comment.size()) + " DWORDs";
    const isa::OpcodeInfo* info = ins.info();
    if (!info) return "// unknown opcode " + std::to_string(static_cast<unsigned>(ins.opcode));
    switch (info->layout) {
    case isa::OperandLayout::Declaration:
        return format_dcl(version, ins);
    case isa::OperandLayout::FloatDef:
    case isa::OperandLayout::IntDef:
    case isa::OperandLayout::BoolDef: {
        const isa::DestinationParameter d = ins.dest.value_or(isa::DestinationParameter{});
        std::string s = std::string(info->mnemonic) + " " + register_text(version, d.type, d.index);
        if (info->layout == isa::OperandLayout::BoolDef)
            return s + ", " + (ins.constant_bits[0] != 0 ? "true" : "false");
        for (uint32_t bits : ins.constant_bits) {
            s += ", ";
            if (info->layout == isa::OperandLayout::FloatDef)
                s += syntax::format_float_literal(bits);
            else
                s += std::to_string(static_cast<int32_t>(bits));
        }
        return s;
    }
    case isa::OperandLayout::Standard:
        break;
    }
    std::string s(info->mnemonic);
    if (ins.opcode == isa::Opcode::Ifc || ins.opcode == isa::Opcode::BreakC ||
        ins.opcode == isa::Opcode::SetP)
        s += comparison_suffix(ins.control);
    if (ins.dest) s += result_modifiers(*ins.dest);
    std::string operands;
    if (ins.dest) operands = destination_text(version, *ins.dest);
    for (const isa::SourceParameter& src : ins.sources) {
        if (!operands.empty()) operands += ", ";
        operands += source_text(version, src);
    }
    if (ins.predicate) s = "(" + source_text(version, *ins.predicate) + ") " + s;
    if (!operands.empty()) s += " " + operands;
    return s;
}

std::string disassemble(const isa::Program& program) {
    std::string out = program.version.name() + "\n";
    for (const isa::Instruction& ins : program.instructions) {
        out += format_instruction(program.version, ins);
        out += '\n';
    }
    return out;
}

namespace {

// The token slice of each statement but comment blocks: [token_offset, next statement's offset).
std::vector<std::vector<uint32_t>> statement_tokens(const isa::Program& program, const std::vector<uint32_t>& tokens,
                                                    std::vector<size_t>* indices) {
    std::vector<std::vector<uint32_t>> out;
    const auto& ins = program.instructions;
    for (size_t i = 0; i < ins.size(); ++i) {
        const size_t begin = ins[i].token_offset;
        const size_t end = i + 1 < ins.size() ? ins[i + 1].token_offset : tokens.size() - 1;  // END
        if (ins[i].opcode == isa::Opcode::Comment) continue;
        out.emplace_back(tokens.begin() + static_cast<std::ptrdiff_t>(std::min(begin, tokens.size())),
                         tokens.begin() + static_cast<std::ptrdiff_t>(std::min(std::max(begin, end), tokens.size())));
        if (indices) indices->push_back(i);
    }
    return out;
}

}  // namespace

CheckedDisassembly disassemble_checked(const isa::Program& program) {
    CheckedDisassembly result;
    result.text = disassemble(program);
    const auto& ins = program.instructions;
    auto fail_at = [&](size_t i, const std::string& why) {
        const uint32_t offset = i < ins.size() ? ins[i].token_offset : 0;
        const std::string text = i < ins.size() ? format_instruction(program.version, ins[i]) : std::string();
        result.error = DisassemblyError{offset, "'" + text + "' " + why};
        return result;
    };
    AssembleOptions options;
    options.validate = false;
    const AssembleResult again = assemble(result.text, options);
    if (!again.ok()) {
        // Line 1 is the version; statement i is on line i + 2.
        for (const Diagnostic& d : again.diagnostics)
            if (d.line >= 2 && d.line - 2 < ins.size())
                return fail_at(d.line - 2, "does not assemble: " + d.message);
        result.error = DisassemblyError{0, "the text does not assemble"};
        return result;
    }
    std::vector<size_t> indices;
    const auto original = statement_tokens(program, isa::encode(program), &indices);
    // Token offsets come from the decoder (an assembled Program does not carry them).
    const isa::DecodeResult decoded = isa::decode(again.tokens);
    if (!decoded.ok()) {
        result.error = DisassemblyError{0, "the text assembles to bytecode that does not decode"};
        return result;
    }
    const auto back = statement_tokens(*decoded.program, again.tokens, nullptr);
    for (size_t k = 0; k < original.size(); ++k) {
        if (k >= back.size() || original[k] != back[k])
            return fail_at(indices[k], "assembles to different bytes (a value or register text cannot express, or "
                                       "a statement the assembler would place elsewhere)");
    }
    if (back.size() != original.size()) result.error = DisassemblyError{0, "the text assembles to more statements"};
    return result;
}

}  // namespace sm2::assembler
