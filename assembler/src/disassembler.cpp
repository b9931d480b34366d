// Program -> text the assembler reads back into the same bytes.
#include "sm2/assembler/disassembler.h"

#include <algorithm>
#include <cstdio>
#include <string_view>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/constant_table.h"
#include "sm2/isa/line_table.h"

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

std::string hex_dword(uint32_t word) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08x", word);
    return buf;
}

// Printable ASCII as is, anything else as \xHH, so that a string from the block can never end
// the `//` line it is printed on.
std::string printable(std::string_view s) {
    std::string out;
    for (char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u < 0x7F) {
            out += c;
        } else {
            static constexpr char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        }
    }
    return out;
}

std::string fourcc_text(uint32_t word) {
    std::string s;
    for (int k = 0; k < 4; ++k) s += static_cast<char>((word >> (8 * k)) & 0xFF);
    return s;
}

bool is_printable_fourcc(uint32_t word) {
    for (int k = 0; k < 4; ++k) {
        const uint32_t c = (word >> (8 * k)) & 0xFF;
        if (c < 0x20 || c >= 0x7F) return false;
    }
    return true;
}

std::string padded(std::string s, size_t width) {
    if (s.size() < width) s.append(width - s.size(), ' ');
    return s;
}

std::string default_value_text(const isa::ConstantInfo& c) {
    std::string s;
    const size_t per_register = c.register_set == isa::ConstantRegisterSet::Bool ? 1 : 4;
    for (size_t i = 0; i < c.default_value.size(); ++i) {
        s += i % per_register == 0 ? (i == 0 ? "{" : "}, {") : ", ";
        const uint32_t v = c.default_value[i];
        s += c.register_set == isa::ConstantRegisterSet::Float4 ? syntax::format_float_literal(v)
                                                               : std::to_string(static_cast<int32_t>(v));
    }
    return s.empty() ? s : s + "}";
}

void append_members(const std::vector<isa::ConstantMember>& members, const std::string& indent, std::string& out) {
    for (const isa::ConstantMember& m : members) {
        out += "//" + indent + "." + printable(m.name) + "  " + isa::constant_type_name(m.type) + "\n";
        append_members(m.type.members, indent + "  ", out);
    }
}

// The HLSL line table sm2 compile --debug-info writes: each instruction's line, by instruction
// (counted without comments, from 0), then the lines' text.
std::string describe_line_table(const std::vector<uint32_t>& payload, const std::string& size) {
    const isa::LineTableResult parsed = isa::parse_line_table(payload);
    if (!parsed.ok()) return "// SM2L HLSL line table, " + size + ", not decoded: " + printable(parsed.error) + "\n";
    const isa::LineTable& t = *parsed.table;
    std::string out = "// SM2L HLSL line table, " + size + ": " + std::to_string(t.entries.size()) + " instruction" +
                      (t.entries.size() == 1 ? "" : "s") + " from " + std::to_string(t.lines.size()) + " line" +
                      (t.lines.size() == 1 ? "" : "s") + "\n";
    for (const auto& l : t.lines) {
        std::string instructions;
        for (const auto& e : t.entries)
            if (e.file == l.file && e.line == l.line)
                instructions += (instructions.empty() ? "" : ",") + std::to_string(e.instruction);
        out += "//   " + printable(t.files[l.file]) + ":" + std::to_string(l.line) + " (instructions " + instructions +
               "): " + printable(l.text) + "\n";
    }
    return out;
}

// `//` lines that say what a comment block holds: a constant table decoded, or its FOURCC.
std::string describe_comment(const std::vector<uint32_t>& payload) {
    const std::string size = std::to_string(payload.size()) + " DWORD" + (payload.size() == 1 ? "" : "s");
    if (payload.empty()) return "// empty comment block\n";
    if (payload[0] == isa::kFourccLineTable) return describe_line_table(payload, size);
    if (payload[0] != isa::kFourccCtab) {
        if (!is_printable_fourcc(payload[0])) return "// comment block, " + size + "\n";
        return "// comment block '" + printable(fourcc_text(payload[0])) + "', " + size + "\n";
    }
    const isa::ConstantTableResult parsed = isa::parse_constant_table(payload);
    if (!parsed.ok()) return "// CTAB constant table, " + size + ", not decoded: " + printable(parsed.error) + "\n";
    const isa::ConstantTable& table = *parsed.table;
    std::string out = "// CTAB constant table, " + size + ": target " + printable(table.target) + ", creator \"" +
                      printable(table.creator) + "\", version " + hex_dword(table.version) + ", flags " +
                      hex_dword(table.flags) + "\n";
    size_t name_width = 4;
    size_t type_width = 4;
    for (const isa::ConstantInfo& c : table.constants) {
        name_width = std::max(name_width, printable(c.name).size());
        type_width = std::max(type_width, isa::constant_type_name(c.type).size());
    }
    if (!table.constants.empty())
        out += "//   " + padded("name", name_width) + "  " + padded("type", type_width) + "  register  count\n";
    for (const isa::ConstantInfo& c : table.constants) {
        std::string line = "//   " + padded(printable(c.name), name_width) + "  " +
                           padded(isa::constant_type_name(c.type), type_width) + "  " +
                           padded(isa::register_set_prefix(c.register_set) + std::to_string(c.register_index), 8) +
                           "  " + std::to_string(c.register_count);
        const std::string defaults = default_value_text(c);
        if (!defaults.empty()) line += "  default " + defaults;
        out += line + "\n";
        append_members(c.type.members, "     ", out);
    }
    return out;
}

// The `comment` directive with the block's words, eight to a line.
std::string comment_directive(const std::vector<uint32_t>& payload, bool wrap) {
    std::string s = "comment";
    constexpr size_t kWordsPerLine = 8;
    for (size_t i = 0; i < payload.size(); ++i) {
        if (i == 0) s += ' ';
        else if (wrap && i % kWordsPerLine == 0) s += ",\n        ";
        else s += ", ";
        s += hex_dword(payload[i]);
    }
    return s;
}

}  // namespace

std::string format_instruction(isa::ShaderVersion version, const isa::Instruction& ins) {
    if (ins.opcode == isa::Opcode::Comment) return comment_directive(ins.comment, false);
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

namespace {

// The listing, and for each instruction the 1-based line its statement starts on.
std::string listing(const isa::Program& program, std::vector<uint32_t>* statement_lines) {
    std::string out = program.version.name() + "\n";
    uint32_t line = 2;
    for (const isa::Instruction& ins : program.instructions) {
        std::string text;
        if (ins.opcode == isa::Opcode::Comment) {
            const std::string description = describe_comment(ins.comment);
            line += static_cast<uint32_t>(std::count(description.begin(), description.end(), '\n'));
            out += description;
            text = comment_directive(ins.comment, true);
        } else {
            text = format_instruction(program.version, ins);
        }
        if (statement_lines) statement_lines->push_back(line);
        line += 1 + static_cast<uint32_t>(std::count(text.begin(), text.end(), '\n'));
        out += text;
        out += '\n';
    }
    return out;
}

}  // namespace

std::string disassemble(const isa::Program& program) { return listing(program, nullptr); }

namespace {

// The token slice of each statement: [token_offset, next statement's offset).
std::vector<std::vector<uint32_t>> statement_tokens(const isa::Program& program, const std::vector<uint32_t>& tokens) {
    std::vector<std::vector<uint32_t>> out;
    const auto& ins = program.instructions;
    for (size_t i = 0; i < ins.size(); ++i) {
        const size_t begin = ins[i].token_offset;
        const size_t end = i + 1 < ins.size() ? ins[i + 1].token_offset : tokens.size() - 1;  // END
        out.emplace_back(tokens.begin() + static_cast<std::ptrdiff_t>(std::min(begin, tokens.size())),
                         tokens.begin() + static_cast<std::ptrdiff_t>(std::min(std::max(begin, end), tokens.size())));
    }
    return out;
}

}  // namespace

CheckedDisassembly disassemble_checked(const isa::Program& program) {
    CheckedDisassembly result;
    std::vector<uint32_t> statement_lines;
    result.text = listing(program, &statement_lines);
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
        // The statement whose lines hold the first located diagnostic (line 1 is the version).
        for (const Diagnostic& d : again.diagnostics) {
            const auto after = std::upper_bound(statement_lines.begin(), statement_lines.end(), d.line);
            if (after != statement_lines.begin())
                return fail_at(static_cast<size_t>(after - statement_lines.begin()) - 1,
                               "does not assemble: " + d.message);
        }
        result.error = DisassemblyError{0, "the text does not assemble"};
        return result;
    }
    const auto original = statement_tokens(program, isa::encode(program));
    // Token offsets come from the decoder (an assembled Program does not carry them).
    const isa::DecodeResult decoded = isa::decode(again.tokens);
    if (!decoded.ok()) {
        result.error = DisassemblyError{0, "the text assembles to bytecode that does not decode"};
        return result;
    }
    const auto back = statement_tokens(*decoded.program, again.tokens);
    for (size_t k = 0; k < original.size(); ++k) {
        if (k >= back.size() || original[k] != back[k])
            return fail_at(k, "assembles to different bytes (a value or register text cannot express)");
    }
    if (back.size() != original.size()) result.error = DisassemblyError{0, "the text assembles to more statements"};
    return result;
}

}  // namespace sm2::assembler
