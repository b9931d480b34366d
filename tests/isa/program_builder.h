// A tiny text-to-Program helper for the isa tests (not the assembler, which lives in its own
// room and is not used here). One statement per line; the first line is the version
// ("vs_2_0" / "ps_2_0"); blank lines and lines starting with "//" are skipped. The n-th
// statement line becomes Program::instructions[n], with its 1-based text line as location.
//
// Accepted forms (enough for tests, not the full grammar):
//   mnemonic[_sat][_pp][_centroid][_x2] dest, src, ...
//   dcl_<usage>[N] v#[.mask]  |  dcl[_pp][_centroid] v#/t#[.mask]  |  dcl[_2d|_cube|_volume|_1d] s#
//   def c#, f, f, f, f (f may be raw bits 0x...)  |  defi i#, n, n, n, n  |  defb b#, true|false
//   #comment            (an Opcode::Comment with an empty payload)
// Sources: [-|!]reg[_abs|_bx2|...][[a0.c + n] | [aL]][.swizzle]  and  c[a0.x + n], c[aL].
// Registers are resolved through the isa register table (registers.h).
#pragma once

#include <bit>
#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/isa/opcodes.h"
#include "sm2/isa/program.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/version.h"

namespace sm2::isa::builder {

inline std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

inline std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    for (size_t i = 0; i <= s.size(); ++i)
        if (i == s.size() || s[i] == sep) {
            parts.push_back(trim(s.substr(start, i - start)));
            start = i + 1;
        }
    return parts;
}

[[noreturn]] inline void fail(const std::string& what, std::string_view text) {
    throw std::runtime_error("program_builder: " + what + ": '" + std::string(text) + "'");
}

inline int component(char c) {
    switch (c) {
    case 'x': case 'r': return 0;
    case 'y': case 'g': return 1;
    case 'z': case 'b': return 2;
    case 'w': case 'a': return 3;
    default: return -1;
    }
}

inline uint8_t parse_mask(std::string_view letters) {
    uint8_t mask = 0;
    for (char c : letters) {
        const int k = component(c);
        if (k < 0) fail("bad mask", letters);
        mask |= static_cast<uint8_t>(1u << k);
    }
    return mask;
}

inline uint8_t parse_swizzle(std::string_view letters) {
    if (letters.empty() || letters.size() > 4) fail("bad swizzle", letters);
    uint8_t swizzle = 0;
    for (int i = 0; i < 4; ++i) {
        const int k = component(letters[std::min<size_t>(static_cast<size_t>(i), letters.size() - 1)]);
        if (k < 0) fail("bad swizzle", letters);
        swizzle |= static_cast<uint8_t>(k << (2 * i));
    }
    return swizzle;
}

// "r5" -> (Temp, 5); "oPos" -> (RastOut, 0); "a0" -> (Address, 0); "c" -> (Const, 0).
// Names the profile lacks are looked up in the other 2.0 profile (s0 in a vertex shader),
// and p0 is always known, so that tests can build invalid programs.
inline std::pair<RegisterType, uint16_t> parse_register(ShaderVersion v, std::string_view text) {
    if (text == "p0") return {RegisterType::Predicate, 0};
    const ShaderVersion other{v.is_vertex() ? ShaderType::Pixel : ShaderType::Vertex, 2, 0};
    for (ShaderVersion version : {v, other}) {
        if (const RegisterFile* f = find_register_file(version, text); f && !f->numbered)
            return {f->type, f->first};
        size_t digits = text.size();
        while (digits > 0 && std::isdigit(static_cast<unsigned char>(text[digits - 1]))) --digits;
        if (const RegisterFile* f = find_register_file(version, text.substr(0, digits));
            f && f->numbered) {
            const std::string number(text.substr(digits));
            return {f->type, static_cast<uint16_t>(number.empty() ? 0 : std::stoul(number))};
        }
    }
    fail("unknown register", text);
}

inline DestinationParameter parse_dest(ShaderVersion v, std::string_view text) {
    DestinationParameter d;
    const size_t dot = text.find('.');
    const auto [type, index] = parse_register(v, text.substr(0, dot));
    d.type = type;
    d.index = index;
    d.write_mask = dot == std::string_view::npos ? kMaskAll : parse_mask(text.substr(dot + 1));
    return d;
}

inline SourceParameter parse_source(ShaderVersion v, std::string_view text) {
    SourceParameter s;
    if (text.starts_with("-")) s.modifier = SourceModifier::Negate, text.remove_prefix(1);
    else if (text.starts_with("!")) s.modifier = SourceModifier::Not, text.remove_prefix(1);
    else if (text.starts_with("1-")) s.modifier = SourceModifier::Complement, text.remove_prefix(2);
    std::string_view base = text, rel, swizzle;
    if (const size_t open = text.find('['); open != std::string_view::npos) {
        const size_t close = text.find(']', open);
        if (close == std::string_view::npos) fail("missing ]", text);
        base = text.substr(0, open);
        rel = text.substr(open + 1, close - open - 1);
        const std::string_view after = text.substr(close + 1);
        if (after.starts_with(".")) swizzle = after.substr(1);
    } else if (const size_t dot = text.find('.'); dot != std::string_view::npos) {
        base = text.substr(0, dot);
        swizzle = text.substr(dot + 1);
    }
    static constexpr std::pair<std::string_view, SourceModifier> kSuffixes[] = {
        {"_abs", SourceModifier::Abs}, {"_bx2", SourceModifier::Sign},
        {"_bias", SourceModifier::Bias}, {"_x2", SourceModifier::X2},
        {"_dz", SourceModifier::DivideZ}, {"_dw", SourceModifier::DivideW}};
    for (const auto& [suffix, modifier] : kSuffixes)
        if (base.ends_with(suffix)) {
            base.remove_suffix(suffix.size());
            s.modifier = modifier;
        }
    const auto [type, index] = parse_register(v, base);
    s.type = type;
    s.index = index;
    if (!swizzle.empty()) s.swizzle = parse_swizzle(swizzle);
    if (!rel.empty()) {
        RelativeAddress r;
        for (std::string_view term : split(rel, '+')) {
            if (!term.empty() && std::isdigit(static_cast<unsigned char>(term[0]))) {
                s.index = static_cast<uint16_t>(s.index + std::stoul(std::string(term)));
            } else if (term == "aL") {
                r.type = RegisterType::Loop;
                r.swizzle = kSwizzleIdentity;
            } else if (term.starts_with("a0")) {
                r.type = RegisterType::Address;
                r.swizzle = term.size() > 3 ? parse_swizzle(term.substr(3)) : kSwizzleIdentity;
            } else {
                const auto [rtype, rindex] = parse_register(v, term);  // e.g. r0: invalid index
                (void)rindex;
                r.type = rtype;
            }
        }
        s.relative = r;
    }
    return s;
}

// "0.5" -> float bits; "0x3F000000" -> the bits as written.
inline uint32_t float_bits(std::string_view text) {
    if (text.starts_with("0x")) return static_cast<uint32_t>(std::stoul(std::string(text), nullptr, 16));
    return std::bit_cast<uint32_t>(std::stof(std::string(text)));
}

inline Instruction parse_instruction(ShaderVersion v, std::string_view line) {
    Instruction ins;
    if (line.starts_with("#")) {
        ins.opcode = Opcode::Comment;
        return ins;
    }
    const size_t space = line.find(' ');
    const std::string_view head = line.substr(0, space);
    const std::string_view rest = space == std::string_view::npos ? "" : trim(line.substr(space + 1));
    const std::vector<std::string_view> parts = split(head, '_');
    const OpcodeInfo* info = find_mnemonic(parts[0]);
    if (!info) fail("unknown mnemonic", head);
    ins.opcode = info->opcode;
    ins.control = info->control;
    std::vector<std::string_view> operands;
    if (!rest.empty()) operands = split(rest, ',');

    DestinationParameter flags;
    for (size_t k = 1; k < parts.size(); ++k) {
        const std::string_view m = parts[k];
        if (m == "sat") flags.saturate = true;
        else if (m == "pp") flags.partial_precision = true;
        else if (m == "centroid") flags.centroid = true;
        else if (m == "x2") flags.shift = 1;
        else if (ins.opcode == Opcode::Dcl) {
            static constexpr std::pair<std::string_view, TextureType> kTypes[] = {
                {"1d", TextureType::Texture1D}, {"2d", TextureType::Texture2D},
                {"cube", TextureType::Cube}, {"volume", TextureType::Volume}};
            static constexpr std::string_view kUsages[] = {
                "position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
                "binormal", "tessfactor", "positiont", "color", "fog", "depth", "sample"};
            bool known = false;
            for (const auto& [name, type] : kTypes)
                if (m == name) ins.declaration.texture_type = type, known = true;
            for (size_t u = 0; u < std::size(kUsages) && !known; ++u)
                if (m.starts_with(kUsages[u])) {
                    const std::string_view digits = m.substr(kUsages[u].size());
                    if (!digits.empty() && !std::isdigit(static_cast<unsigned char>(digits[0])))
                        continue;  // "positiont" is not "position" + "t"
                    ins.declaration.usage = static_cast<DeclUsage>(u);
                    ins.declaration.usage_index =
                        static_cast<uint8_t>(digits.empty() ? 0 : std::stoul(std::string(digits)));
                    known = true;
                }
            if (!known) fail("unknown dcl suffix", m);
        } else {
            fail("unknown modifier", m);
        }
    }

    switch (info->layout) {
    case OperandLayout::Declaration:
        if (operands.size() != 1) fail("dcl takes one register", line);
        ins.dest = parse_dest(v, operands[0]);
        break;
    case OperandLayout::FloatDef:
    case OperandLayout::IntDef:
        if (operands.size() != 5) fail("def takes a register and four values", line);
        ins.dest = parse_dest(v, operands[0]);
        for (int k = 0; k < 4; ++k)
            ins.constant_bits[k] = info->layout == OperandLayout::FloatDef
                                       ? float_bits(operands[k + 1])
                                       : static_cast<uint32_t>(std::stol(std::string(operands[k + 1])));
        break;
    case OperandLayout::BoolDef:
        if (operands.size() != 2) fail("defb takes a register and a value", line);
        ins.dest = parse_dest(v, operands[0]);
        ins.constant_bits[0] = operands[1] == "true" ? 1u : 0u;
        break;
    case OperandLayout::Standard: {
        size_t first = 0;
        if (info->has_dest()) {
            if (operands.empty()) fail("missing destination", line);
            ins.dest = parse_dest(v, operands[0]);
            first = 1;
        }
        for (size_t k = first; k < operands.size(); ++k)
            ins.sources.push_back(parse_source(v, operands[k]));
        break;
    }
    }
    if (ins.dest) {
        ins.dest->saturate = flags.saturate;
        ins.dest->partial_precision = flags.partial_precision;
        ins.dest->centroid = flags.centroid;
        ins.dest->shift = flags.shift;
    }
    return ins;
}

// The whole text: first statement line is the version.
inline Program parse_program(std::string_view text) {
    Program program;
    bool have_version = false;
    uint32_t line_number = 0;
    for (std::string_view raw : split(text, '\n')) {
        ++line_number;
        const std::string_view line = trim(raw);
        if (line.empty() || line.starts_with("//")) continue;
        if (!have_version) {
            const Profile* p = find_profile(line);
            if (!p) fail("unknown version", line);
            program.version = p->version;
            have_version = true;
            continue;
        }
        Instruction ins = parse_instruction(program.version, line);
        ins.location = {line_number, 1};
        program.instructions.push_back(std::move(ins));
    }
    if (!have_version) fail("no version line", text);
    return program;
}

}  // namespace sm2::isa::builder
