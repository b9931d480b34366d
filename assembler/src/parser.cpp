// The statement parser. Every operand rule that Wine's assembler enforces while parsing is
// enforced here; the documented limits beyond that (register counts, swizzle rules, operand
// classes, ...) are the validator's job.
//
// Accepted syntax (a superset of what Wine's D3DAssemble reads for vs_2_0 / ps_2_0):
//   program    := version statement*          version: vs_2_0 | vs.2.0 | ps_2_0 | ps.2.0
//   statement  := mnemonic[_mod...] operands  (newlines are not significant, as in Wine;
//                                               one statement per line is the usual layout)
//   dest       := reg[.mask]                   mask: xyzw/rgba letters, in order, no repeats
//   source     := [-|!]reg[index][.swizzle]    swizzle: 1-4 letters, the last one repeats
//   index      := '[' term ('+' term)* ']'     term: a0[.swizzle] | aL | decimal number
//   dcl        := dcl[_usage[N]|_2d|_cube|_volume|_1d][_pp|_centroid|_sat] reg[.mask]
//   def        := def c#, f, f, f, f  |  defi i#, n, n, n, n  |  defb b#, true|false
//   comment    := comment [word {, word}]      word: 0x and 1-8 hex digits (a raw comment block)
// Extensions beyond Wine (all documented in the assembler's report):
//   * mnemonics, modifiers, registers, swizzles, usages, true/false in any letter case;
//   * def floats with an exponent (1.5e-3) and raw IEEE-754 bit patterns (0x7FC00000), the
//     latter so that NaN and infinity round-trip through the disassembler;
//   * ps sincos with either one source (Wine) or three (Microsoft's documented form).
#include "parser.h"

#include <algorithm>
#include <string>

#include "sm2/isa/opcodes.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/version.h"
#include "syntax.h"

namespace sm2::assembler::detail {

namespace {

using isa::RegisterType;

struct Failure {};

std::string quote(std::string_view s) {
    constexpr size_t kMax = 40;
    std::string out = "'";
    size_t n = 0;
    for (char c : s) {
        if (n++ == kMax) {
            out += "...";
            break;
        }
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u >= 0x7F) {
            static constexpr char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else {
            out += c;
        }
    }
    return out + "'";
}

std::string describe(const Token& t) {
    switch (t.kind) {
    case TokenKind::End: return "end of input";
    case TokenKind::Invalid: return "unexpected character(s) " + quote(t.text);
    default: return quote(t.text);
    }
}

bool all_digits(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Value of a decimal digit string, saturating at `cap`.
uint32_t decimal_value(std::string_view digits, uint32_t cap) {
    uint64_t v = 0;
    for (char c : digits) {
        v = v * 10 + static_cast<uint64_t>(c - '0');
        if (v > cap) return cap;
    }
    return static_cast<uint32_t>(v);
}

// Instructions Wine's ps_2_0 writer encodes although the documents (and so the opcode table)
// do not allow them in ps_2_0 (spec README item 3); the validator rejects them.
bool wine_extra_in_ps_2_0(isa::Opcode op) {
    return op == isa::Opcode::ExpP || op == isa::Opcode::LogP || op == isa::Opcode::DefI ||
           op == isa::Opcode::DefB;
}

struct RegisterRef {
    const isa::RegisterFile* file = nullptr;
    uint16_t index = 0;
    std::optional<isa::RelativeAddress> relative;
    Token token;
};

class Parser {
public:
    Parser(const std::vector<Token>& tokens, Reporter& reporter)
        : tokens_(tokens), reporter_(reporter) {}

    ParseOutput run() {
        ParseOutput out;
        if (peek().kind == TokenKind::End) {
            reporter_.error_whole("empty input: expected a shader version line (vs_2_0 or ps_2_0)");
            return out;
        }
        try {
            parse_version();
        } catch (const Failure&) {
            return out;  // nothing can be parsed without knowing the profile
        }
        out.version = version_;
        while (peek().kind != TokenKind::End) {
            const size_t start = pos_;
            try {
                Statement s = parse_statement();
                check_statement_end();
                out.statements.push_back(std::move(s));
            } catch (const Failure&) {
                recover(start);
            }
        }
        return out;
    }

private:
    // --- token access -------------------------------------------------------------------
    const Token& peek(size_t ahead = 0) const {
        const size_t i = std::min(pos_ + ahead, tokens_.size() - 1);
        return tokens_[i];
    }
    const Token& advance() {
        const Token& t = tokens_[pos_];
        if (pos_ + 1 < tokens_.size()) ++pos_;
        return t;
    }
    bool accept(TokenKind kind) {
        if (peek().kind != kind) return false;
        advance();
        return true;
    }
    [[noreturn]] void fail(const Token& at, std::string message) {
        reporter_.error(at, std::move(message));
        throw Failure{};
    }
    const Token& expect(TokenKind kind, const char* what) {
        if (peek().kind != kind) fail(peek(), std::string("expected ") + what + ", found " + describe(peek()));
        return advance();
    }

    // Skip to the first token of a later line (or the offending token itself when it starts a
    // line), so that one bad statement costs one diagnostic.
    void recover(size_t start) {
        size_t i = std::max(pos_, start + 1);
        if (i >= tokens_.size()) i = tokens_.size() - 1;
        while (tokens_[i].kind != TokenKind::End && !tokens_[i].first_on_line) ++i;
        pos_ = i;
    }

    void check_statement_end() {
        const Token& t = peek();
        if (t.kind == TokenKind::End || t.first_on_line) return;
        // Wine's grammar needs no newline between statements; allow the next one to follow.
        if (t.kind == TokenKind::Identifier) {
            const std::string lower = syntax::to_lower(t.text);
            if (isa::find_mnemonic(lower.substr(0, lower.find('_')))) return;
        }
        // describe() already says "unexpected character(s)" for an invalid token.
        fail(t, (t.kind == TokenKind::Invalid ? describe(t) : "unexpected " + describe(t)) +
                    " after the end of the statement");
    }

    // --- version ------------------------------------------------------------------------
    // The text of a token and the tokens glued to it on the same line ("vs.2.0" is several).
    std::string glued_text() {
        std::string s(advance().text);
        while (!peek().space_before && !peek().first_on_line &&
               (peek().kind == TokenKind::Identifier || peek().kind == TokenKind::Number ||
                peek().kind == TokenKind::Dot))
            s += advance().text;
        return s;
    }

    static bool looks_like_version(std::string_view lower) {
        return lower == "vs" || lower == "ps" || lower.starts_with("vs_") ||
               lower.starts_with("ps_");
    }

    void parse_version() {
        const Token t = peek();
        if (t.kind != TokenKind::Identifier)
            fail(t, "expected the shader version (vs_2_0 or ps_2_0) as the first statement, found " +
                        describe(t));
        const std::string lower = syntax::to_lower(t.text);
        if (!looks_like_version(lower))
            fail(t, "expected the shader version (vs_2_0 or ps_2_0) as the first statement, found " +
                        describe(t));
        const std::string name = syntax::to_lower(glued_text());
        const isa::Profile* profile = isa::find_profile(name);
        if (!profile) fail(t, "unsupported shader version " + quote(name) + " (supported: vs_2_0, ps_2_0)");
        version_ = profile->version;
        check_statement_end();
    }

    // --- statements -----------------------------------------------------------------------
    Statement parse_statement() {
        const Token mnemonic = peek();
        if (mnemonic.kind != TokenKind::Identifier)
            fail(mnemonic, "expected an instruction, found " + describe(mnemonic));
        advance();
        const std::string lower = syntax::to_lower(mnemonic.text);
        if (looks_like_version(lower))
            fail(mnemonic, "the shader version may appear only once, as the first statement");
        if (lower == "comment") return parse_comment(mnemonic);
        const size_t underscore = lower.find('_');
        const std::string base = lower.substr(0, underscore);
        std::vector<std::string> parts;
        if (underscore != std::string::npos) {
            size_t i = underscore + 1;
            while (true) {
                const size_t next = lower.find('_', i);
                parts.push_back(lower.substr(i, next == std::string::npos ? std::string::npos : next - i));
                if (next == std::string::npos) break;
                i = next + 1;
            }
        }
        const isa::OpcodeInfo* info = isa::find_mnemonic(base);
        if (!info) fail(mnemonic, "unknown instruction " + quote(mnemonic.text));
        const bool wine_extra = version_.is_pixel() && version_.major == 2 &&
                                version_.minor == 0 && wine_extra_in_ps_2_0(info->opcode);
        if (!info->allowed_in(version_) && !wine_extra)
            fail(mnemonic, quote(base) + " is not available in " + version_.name());
        for (const std::string& p : parts)
            if (p.empty()) fail(mnemonic, "empty modifier in " + quote(mnemonic.text));

        Statement s;
        s.file = mnemonic.file;
        isa::Instruction& ins = s.instruction;
        ins.opcode = info->opcode;
        ins.control = info->control;
        ins.location = isa::SourceLocation{mnemonic.line, mnemonic.column};

        switch (info->layout) {
        case isa::OperandLayout::Declaration:
            s.group = parse_dcl(mnemonic, parts, ins);
            return s;
        case isa::OperandLayout::FloatDef:
        case isa::OperandLayout::IntDef:
        case isa::OperandLayout::BoolDef:
            if (!parts.empty())
                fail(mnemonic, quote(base) + " takes no modifiers");
            s.group = parse_def(*info, ins);
            return s;
        case isa::OperandLayout::Standard:
            break;
        }
        s.group = Group::Code;

        isa::DestinationParameter modifiers;
        for (const std::string& p : parts) {
            if (!apply_result_modifier(mnemonic, p, modifiers)) {
                if (p == "x2" || p == "x4" || p == "x8" || p == "d2" || p == "d4" || p == "d8")
                    fail(mnemonic, "result shift '_" + p + "' is not available in shader model 2");
                fail(mnemonic, "unknown instruction modifier '_" + p + "'");
            }
        }
        if (!info->has_dest() && !parts.empty())
            fail(mnemonic, quote(base) + " has no destination, so it takes no modifiers");

        if (info->has_dest()) {
            isa::DestinationParameter d = parse_destination(info->dest);
            d.saturate = modifiers.saturate;
            d.partial_precision = modifiers.partial_precision;
            d.centroid = modifiers.centroid;
            ins.dest = d;
        }
        size_t extra_sources = 0;
        if (info->num_sources > 0) {
            constexpr size_t kMaxOperands = 4;
            if (!info->has_dest()) ins.sources.push_back(parse_source());
            // Operands past the fourth are parsed and counted (for the message), not kept.
            while (peek().kind == TokenKind::Comma) {
                advance();
                isa::SourceParameter src = parse_source();
                if (ins.sources.size() < kMaxOperands) ins.sources.push_back(src);
                else ++extra_sources;
            }
        }
        const size_t n = ins.sources.size() + extra_sources;
        // ps sincos: Wine writes the one-source form, Microsoft the documented three-source
        // form; both are accepted in pixel shaders (vertex shaders need all three).
        const bool short_form_ok = version_.is_pixel() && info->min_sources < info->num_sources;
        if (n != info->num_sources && !(short_form_ok && n == info->min_sources)) {
            std::string expected = std::to_string(info->num_sources);
            if (short_form_ok) expected = std::to_string(info->min_sources) + " or " + expected;
            fail(mnemonic, quote(base) + " takes " + expected + " source operand" +
                               (info->num_sources == 1 && !short_form_ok ? "" : "s") + ", found " +
                               std::to_string(n));
        }
        return s;
    }

    bool apply_result_modifier(const Token& at, const std::string& p,
                               isa::DestinationParameter& d) {
        if (p == "sat") {
            d.saturate = true;
            return true;
        }
        if (p != "pp" && p != "centroid") return false;
        if (!version_.is_pixel())
            fail(at, "'_" + p + "' is only available in pixel shaders");
        if (p == "pp") d.partial_precision = true;
        else d.centroid = true;
        return true;
    }

    // --- registers ------------------------------------------------------------------------
    struct Match {
        const isa::RegisterFile* file = nullptr;
        bool has_number = false;
        uint32_t index = 0;
    };

    Match match_register(std::string_view lower) const {
        Match best;
        size_t best_length = 0;
        for (const isa::RegisterFile& f : isa::register_files()) {
            if (f.shader != version_.type || !f.versions.contains(version_.number())) continue;
            const std::string name = syntax::to_lower(f.name);
            if (!lower.starts_with(name) || name.size() < best_length) continue;
            const std::string_view rest = lower.substr(name.size());
            if (f.numbered) {
                if (!rest.empty() && !all_digits(rest)) continue;
                best = Match{&f, !rest.empty(), rest.empty() ? 0 : decimal_value(rest, 0xFFFFu)};
            } else {
                if (!rest.empty()) continue;
                best = Match{&f, true, f.first};
            }
            best_length = name.size();
        }
        return best;
    }

    static bool is_known_register_anywhere(std::string_view lower) {
        for (const isa::RegisterFile& f : isa::register_files()) {
            const std::string name = syntax::to_lower(f.name);
            if (!lower.starts_with(name)) continue;
            const std::string_view rest = lower.substr(name.size());
            if (f.numbered ? (rest.empty() || all_digits(rest)) : rest.empty()) return true;
        }
        // Registers of other shader models that are easy to mistype into a 2.0 shader.
        return lower == "p0" || lower == "vpos" || lower == "vface" ||
               (lower.size() > 1 && lower[0] == 'o' && all_digits(lower.substr(1)));
    }

    std::string range_text(const isa::RegisterFile& f) const {
        const std::string name(f.name);
        if (f.encodable <= 1) return name + "0";
        return name + std::to_string(f.first) + ".." + name + std::to_string(f.first + f.encodable - 1);
    }

    RegisterRef parse_register(bool allow_relative, const char* role) {
        const Token t = peek();
        if (t.kind != TokenKind::Identifier)
            fail(t, std::string("expected a ") + role + " register, found " + describe(t));
        advance();
        const std::string lower = syntax::to_lower(t.text);
        const size_t underscore = lower.find('_');
        if (underscore != std::string::npos && underscore > 0 &&
            match_register(lower.substr(0, underscore)).file)
            fail(t, "register modifier " + quote(t.text.substr(underscore)) +
                        " is not available in shader model 2");
        const Match m = match_register(lower);
        if (!m.file) {
            if (is_known_register_anywhere(lower))
                fail(t, "register " + quote(t.text) + " does not exist in " + version_.name());
            fail(t, std::string("expected a ") + role + " register, found " + describe(t));
        }
        RegisterRef ref;
        ref.file = m.file;
        ref.token = t;
        uint32_t index = m.index;
        if (peek().kind == TokenKind::LBracket) {
            if (!allow_relative) fail(peek(), "relative addressing is not allowed here");
            if (!m.file->numbered) fail(peek(), "register " + quote(t.text) + " cannot be indexed");
            advance();
            index += parse_index(ref);
            if (ref.relative && !m.file->relative_addressing) {
                if (version_.is_pixel())
                    fail(t, "relative addressing is not available in " + version_.name());
                fail(t, "only constant registers (c#) can be relatively addressed");
            }
        } else if (!m.has_number) {
            fail(t, "register " + quote(t.text) + " needs a number");
        }
        if (m.file->numbered && (index < m.file->first || index >= m.file->first + m.file->encodable))
            fail(t, "register " + std::string(m.file->name) + std::to_string(index) +
                        " does not exist in " + version_.name() + " (" + range_text(*m.file) + ")");
        ref.index = static_cast<uint16_t>(index);
        return ref;
    }

    // After '[': terms separated by '+', at most one of them a0[.c] or aL. Returns the sum of
    // the numbers.
    uint32_t parse_index(RegisterRef& ref) {
        uint32_t offset = 0;
        while (true) {
            const Token t = peek();
            if (t.kind == TokenKind::Number) {
                if (!all_digits(t.text)) fail(t, "an index offset must be a whole decimal number, found " + describe(t));
                offset = std::min<uint32_t>(offset + decimal_value(t.text, 0xFFFFu), 0xFFFFu);
                advance();
            } else if (t.kind == TokenKind::Identifier) {
                const std::string lower = syntax::to_lower(t.text);
                const Match m = match_register(lower);
                if (!m.file || (m.file->type != RegisterType::Address && m.file->type != RegisterType::Loop)) {
                    if (version_.is_pixel() && (lower == "a0" || lower == "al"))
                        fail(t, "relative addressing is not available in " + version_.name());
                    fail(t, "expected a0, aL or a number inside '[ ]', found " + describe(t));
                }
                if (ref.relative) fail(t, "only one address register may index a register");
                advance();
                isa::RelativeAddress rel;
                rel.type = m.file->type;
                rel.swizzle = isa::kSwizzleIdentity;
                if (peek().kind == TokenKind::Dot && rel.type == RegisterType::Loop)
                    fail(peek(), "aL takes no swizzle");
                if (accept(TokenKind::Dot)) rel.swizzle = parse_swizzle_letters();
                ref.relative = rel;
            } else {
                fail(t, "expected a0, aL or a number inside '[ ]', found " + describe(t));
            }
            if (accept(TokenKind::Plus)) continue;
            if (accept(TokenKind::RBracket)) return offset;
            if (peek().kind == TokenKind::Minus)
                fail(peek(), "negative index offsets are not supported (write c[a0.x + n])");
            fail(peek(), "expected '+' or ']', found " + describe(peek()));
        }
    }

    uint8_t parse_swizzle_letters() {
        const Token t = peek();
        if (t.kind != TokenKind::Identifier) fail(t, "expected a swizzle after '.', found " + describe(t));
        advance();
        const auto swizzle = syntax::parse_swizzle(t.text);
        if (!swizzle) fail(t, "invalid swizzle " + quote(t.text) + " (1 to 4 of x, y, z, w or r, g, b, a)");
        return *swizzle;
    }

    uint8_t parse_mask_letters() {
        const Token t = peek();
        if (t.kind != TokenKind::Identifier) fail(t, "expected a write mask after '.', found " + describe(t));
        advance();
        const auto mask = syntax::parse_write_mask(t.text);
        if (!mask)
            fail(t, "invalid write mask " + quote(t.text) +
                        " (letters of x, y, z, w or r, g, b, a in that order, each at most once)");
        return *mask;
    }

    isa::DestinationParameter parse_destination(isa::DestKind kind) {
        if (peek().kind == TokenKind::Minus || peek().kind == TokenKind::Bang)
            fail(peek(), "a destination cannot have a source modifier");
        const RegisterRef r = parse_register(false, "destination");
        const RegisterType type = r.file->type;
        if (kind == isa::DestKind::Tested) {
            if (type != RegisterType::Temp && type != RegisterType::Texture && type != RegisterType::Input)
                fail(r.token, "texkill tests a temporary or texture register, not " + quote(r.token.text));
        } else if (!r.file->writable) {
            fail(r.token, "register " + quote(r.token.text) + " cannot be written");
        }
        isa::DestinationParameter d;
        d.type = type;
        d.index = r.index;
        if (accept(TokenKind::Dot)) d.write_mask = parse_mask_letters();
        if (r.file->scalar) d.write_mask = isa::kMaskAll;  // oFog / oPts (spec README item 4)
        return d;
    }

    isa::SourceParameter parse_source() {
        isa::SourceParameter s;
        const Token first = peek();
        if (accept(TokenKind::Minus)) s.modifier = isa::SourceModifier::Negate;
        else if (accept(TokenKind::Bang)) s.modifier = isa::SourceModifier::Not;
        if (first.kind == TokenKind::Number && first.text == "1" && peek(1).kind == TokenKind::Minus)
            fail(first, "the complement modifier '1-' is not available in shader model 2");
        const RegisterRef r = parse_register(true, "source");
        if (!r.file->readable) fail(r.token, "register " + quote(r.token.text) + " cannot be read");
        if (s.modifier == isa::SourceModifier::Not && r.file->type != RegisterType::ConstBool)
            fail(first, "'!' applies only to boolean registers (b#)");
        s.type = r.file->type;
        s.index = r.index;
        s.relative = r.relative;
        if (accept(TokenKind::Dot)) s.swizzle = parse_swizzle_letters();
        return s;
    }

    // --- dcl ----------------------------------------------------------------------------
    Group parse_dcl(const Token& mnemonic, const std::vector<std::string>& parts,
                    isa::Instruction& ins) {
        std::optional<isa::DeclUsage> usage;
        uint8_t usage_index = 0;
        std::optional<isa::TextureType> texture;
        isa::DestinationParameter modifiers;
        for (const std::string& p : parts) {
            if (auto tt = syntax::find_texture_type(p)) {
                if (texture) fail(mnemonic, "more than one texture type in " + quote(mnemonic.text));
                texture = tt;
                continue;
            }
            if (apply_result_modifier(mnemonic, p, modifiers)) continue;
            const size_t digits = p.find_first_of("0123456789");
            const std::string name = p.substr(0, digits);
            const std::string number = digits == std::string::npos ? "" : p.substr(digits);
            const auto u = syntax::find_usage(name);
            if (!u || (!number.empty() && !all_digits(number)))
                fail(mnemonic, "unknown declaration suffix '_" + p + "'");
            if (usage) fail(mnemonic, "more than one usage in " + quote(mnemonic.text));
            const uint32_t index = number.empty() ? 0 : decimal_value(number, 1000);
            if (index > 15) fail(mnemonic, "usage index " + number + " is out of range (0..15)");
            usage = u;
            usage_index = static_cast<uint8_t>(index);
        }

        const RegisterRef r = parse_register(false, "declared");
        isa::DestinationParameter d;
        d.type = r.file->type;
        d.index = r.index;
        d.saturate = modifiers.saturate;
        d.partial_precision = modifiers.partial_precision;
        d.centroid = modifiers.centroid;
        const bool has_mask = peek().kind == TokenKind::Dot;
        if (accept(TokenKind::Dot)) d.write_mask = parse_mask_letters();
        ins.dest = d;

        if (d.type == RegisterType::Sampler) {
            if (usage)
                fail(mnemonic, "a sampler declaration takes a texture type (dcl_2d, dcl_cube, "
                               "dcl_volume), not a usage");
            if (has_mask) fail(r.token, "sampler declarations take no write mask");
            ins.declaration.texture_type = texture.value_or(isa::TextureType::Unknown);
            return Group::SamplerDcl;
        }
        if (texture)
            fail(mnemonic, "texture type '_" + std::string(syntax::texture_type_name(*texture)) +
                               "' applies only to sampler registers (s#)");
        if (version_.is_vertex()) {
            if (d.type != RegisterType::Input)
                fail(r.token, version_.name() + " declares only input registers (v#)");
            if (!usage)
                fail(mnemonic, "declaration of " + quote(r.token.text) +
                                   " needs a usage, e.g. dcl_position " + std::string(r.token.text));
            ins.declaration.usage = *usage;
            ins.declaration.usage_index = usage_index;
        } else {
            if (d.type != RegisterType::Input && d.type != RegisterType::Texture)
                fail(r.token, version_.name() + " declares only v#, t# and s# registers");
            if (usage)
                fail(mnemonic, "usage semantics are not allowed on " + version_.name() +
                                   " input declarations (write 'dcl " + std::string(r.token.text) + "')");
        }
        return Group::InputDcl;
    }

    // --- comment block ------------------------------------------------------------------
    // `comment [0xHHHHHHHH {, 0xHHHHHHHH}]`: a comment token and its payload, word for word.
    // The words may continue over several lines (a statement never starts with a number).
    Statement parse_comment(const Token& directive) {
        Statement s;
        s.file = directive.file;
        s.group = Group::Code;
        isa::Instruction& ins = s.instruction;
        ins.opcode = isa::Opcode::Comment;
        ins.location = isa::SourceLocation{directive.line, directive.column};
        if (peek().kind != TokenKind::Number) return s;
        while (true) {
            const Token t = expect(TokenKind::Number, "a DWORD (0xHHHHHHHH)");
            std::string error;
            const auto word = syntax::parse_hex_dword(t.text, &error);
            if (!word) fail(t, "comment words are written 0x and 1 to 8 hex digits, found " + describe(t));
            if (ins.comment.size() == kMaxCommentWords)
                fail(t, "a comment block holds at most " + std::to_string(kMaxCommentWords) + " DWORDs");
            ins.comment.push_back(*word);
            if (!accept(TokenKind::Comma)) return s;
        }
    }
    static constexpr size_t kMaxCommentWords = 0x7FFF;  // the comment token's 15-bit size field

    // --- def / defi / defb --------------------------------------------------------------
    Group parse_def(const isa::OpcodeInfo& info, isa::Instruction& ins) {
        RegisterType want = RegisterType::Const;
        const char* name = "a constant register c#";
        Group group = Group::Def;
        if (info.layout == isa::OperandLayout::IntDef) {
            want = RegisterType::ConstInt;
            name = "an integer constant register i#";
            group = Group::DefI;
        } else if (info.layout == isa::OperandLayout::BoolDef) {
            want = RegisterType::ConstBool;
            name = "a boolean constant register b#";
            group = Group::DefB;
        }
        const RegisterRef r = parse_register(false, "constant");
        if (r.file->type != want)
            fail(r.token, std::string(info.mnemonic) + " defines " + name + ", not " + quote(r.token.text));
        if (peek().kind == TokenKind::Dot) fail(peek(), "a constant definition takes no write mask");
        isa::DestinationParameter d;
        d.type = want;
        d.index = r.index;
        ins.dest = d;
        const int count = info.layout == isa::OperandLayout::BoolDef ? 1 : 4;
        for (int k = 0; k < count; ++k) {
            expect(TokenKind::Comma, "','");
            switch (info.layout) {
            case isa::OperandLayout::FloatDef: ins.constant_bits[k] = parse_float_value(); break;
            case isa::OperandLayout::IntDef: ins.constant_bits[k] = parse_int_value(); break;
            default: ins.constant_bits[k] = parse_bool_value(); break;
            }
        }
        return group;
    }

    uint32_t parse_float_value() {
        const Token first = peek();
        bool negative = false;
        if (accept(TokenKind::Minus)) negative = true;
        else accept(TokenKind::Plus);
        const Token t = peek();
        if (t.kind != TokenKind::Number) fail(t, "expected a number, found " + describe(t));
        advance();
        std::string error;
        const auto bits = syntax::parse_float_literal(negative, t.text, &error);
        if (!bits) fail(first, error);
        return *bits;
    }

    uint32_t parse_int_value() {
        bool negative = false;
        if (accept(TokenKind::Minus)) negative = true;
        else accept(TokenKind::Plus);
        const Token t = peek();
        if (t.kind != TokenKind::Number) fail(t, "expected an integer, found " + describe(t));
        if (!all_digits(t.text)) fail(t, "defi takes whole decimal numbers, found " + describe(t));
        advance();
        const uint32_t magnitude = decimal_value(t.text, 0xFFFFFFFFu);
        if (negative ? magnitude > 0x80000000u : (magnitude == 0xFFFFFFFFu && t.text != "4294967295"))
            fail(t, "integer " + quote(t.text) + " does not fit in 32 bits");
        return negative ? 0u - magnitude : magnitude;
    }

    uint32_t parse_bool_value() {
        const Token t = peek();
        const std::string lower = t.kind == TokenKind::Identifier ? syntax::to_lower(t.text) : "";
        if (lower != "true" && lower != "false")
            fail(t, "expected true or false, found " + describe(t));
        advance();
        return lower == "true" ? 1u : 0u;
    }

    const std::vector<Token>& tokens_;
    Reporter& reporter_;
    size_t pos_ = 0;
    isa::ShaderVersion version_;
};

}  // namespace

ParseOutput parse(const std::vector<Token>& tokens, Reporter& reporter) {
    return Parser(tokens, reporter).run();
}

}  // namespace sm2::assembler::detail
