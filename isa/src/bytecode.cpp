// Whole-stream decoding and encoding (bytecode.md §1, §12).
#include "sm2/isa/bytecode.h"

#include <cstdio>
#include <cstring>

#include "sm2/isa/tokens.h"

namespace sm2::isa {

std::string DecodeError::to_string() const {
    char where[64];
    std::snprintf(where, sizeof where, "token %zu (byte 0x%zx): ", token_index, token_index * 4);
    return where + message;
}

bool Instruction::same_as(const Instruction& o) const {
    return opcode == o.opcode && control == o.control && dest == o.dest &&
           predicate == o.predicate && sources == o.sources && declaration == o.declaration &&
           constant_bits == o.constant_bits && comment == o.comment;
}

namespace {

class Decoder {
public:
    explicit Decoder(std::span<const uint32_t> tokens) : tokens_(tokens) {}

    DecodeResult run() {
        if (tokens_.empty()) return failure(0, "empty stream: no version token");
        const auto version = ShaderVersion::from_token(tokens_[0]);
        if (!version) return failure(0, hex("not a shader version token", tokens_[0]));
        if (!find_profile(*version))
            return failure(0, "unsupported shader version " + version->name() +
                                  " (supported: vs_2_0, ps_2_0)");
        Program program;
        program.version = *version;

        size_t i = 1;
        while (true) {
            if (i >= tokens_.size()) return failure(i, "stream ends without the END token");
            const uint32_t t = tokens_[i];
            if (t == tokens::kEnd) {
                if (i + 1 != tokens_.size())
                    return failure(i + 1, "data after the END token");
                return DecodeResult{std::move(program), std::nullopt};
            }
            if (tokens::is_comment(t)) {
                const size_t size = tokens::comment_size(t);
                if (size > tokens_.size() - i - 1)
                    return failure(i, "comment of " + std::to_string(size) +
                                          " DWORDs runs past the end of the stream");
                Instruction c;
                c.opcode = Opcode::Comment;
                c.token_offset = static_cast<uint32_t>(i);
                c.comment.assign(tokens_.begin() + static_cast<ptrdiff_t>(i + 1),
                                 tokens_.begin() + static_cast<ptrdiff_t>(i + 1 + size));
                program.instructions.push_back(std::move(c));
                i += 1 + size;
                continue;
            }
            Instruction ins;
            if (auto err = decode_instruction(program.version, i, ins))
                return failure(err->token_index, err->message);
            i += 1 + tokens::decode_instruction(t).length;
            program.instructions.push_back(std::move(ins));
        }
    }

private:
    static std::string hex(const char* what, uint32_t token) {
        char buf[24];
        std::snprintf(buf, sizeof buf, " 0x%08X", token);
        return what + std::string(buf);
    }

    DecodeResult failure(size_t index, std::string message) const {
        return DecodeResult{std::nullopt, DecodeError{index, std::move(message)}};
    }

    std::optional<DecodeError> decode_instruction(ShaderVersion version, size_t at,
                                                  Instruction& ins) const {
        const uint32_t t = tokens_[at];
        const auto fields = tokens::decode_instruction(t);
        if (fields.high_bit)
            return DecodeError{at, hex("expected an instruction token, found parameter token", t)};
        if (fields.reserved) return DecodeError{at, "reserved bit 29 of the instruction token is set"};
        if (fields.coissue) return DecodeError{at, "co-issue bit is set (ps_1_x only)"};
        const OpcodeInfo* info = find_opcode(fields.opcode, fields.control);
        if (!info) {
            const OpcodeInfo* any = find_opcode(fields.opcode, 0);
            if (any && any->opcode == Opcode::Tex)
                return DecodeError{at, "unknown texld control " + std::to_string(fields.control)};
            return DecodeError{at, "unknown or non-SM2 opcode " + std::to_string(fields.opcode)};
        }
        const bool comparison = info->opcode == Opcode::Ifc || info->opcode == Opcode::BreakC ||
                                info->opcode == Opcode::SetP;
        if (comparison ? (fields.control < 1 || fields.control > 6)
                       : (info->opcode != Opcode::Tex && fields.control != 0))
            return DecodeError{at, "invalid control bits " + std::to_string(fields.control) +
                                       " for " + std::string(info->mnemonic)};
        const size_t length = fields.length;
        if (length > tokens_.size() - at - 1)
            return DecodeError{at, "instruction length " + std::to_string(length) +
                                       " runs past the end of the stream"};
        ins.opcode = info->opcode;
        ins.control = fields.control;
        ins.token_offset = static_cast<uint32_t>(at);
        const size_t body = at + 1;
        const size_t end = body + length;
        std::string error;
        auto want_length = [&](size_t n) -> std::optional<DecodeError> {
            if (length != n)
                return DecodeError{at, std::string(info->mnemonic) + " needs length " +
                                           std::to_string(n) + ", token says " +
                                           std::to_string(length)};
            return std::nullopt;
        };
        auto read_dest = [&](size_t pos) -> std::optional<DecodeError> {
            auto d = tokens::decode_destination(tokens_[pos], &error);
            if (!d) return DecodeError{pos, error};
            ins.dest = *d;
            return std::nullopt;
        };

        if (fields.predicated && info->layout != OperandLayout::Standard)
            return DecodeError{at, std::string(info->mnemonic) + " cannot be predicated"};
        switch (info->layout) {
        case OperandLayout::Declaration: {
            if (auto e = want_length(2)) return e;
            auto decl = tokens::decode_declaration(tokens_[body], &error);
            if (!decl) return DecodeError{body, error};
            ins.declaration = *decl;
            return read_dest(body + 1);
        }
        case OperandLayout::FloatDef:
        case OperandLayout::IntDef:
            if (auto e = want_length(5)) return e;
            if (auto e = read_dest(body)) return e;
            for (int k = 0; k < 4; ++k) ins.constant_bits[k] = tokens_[body + 1 + k];
            return std::nullopt;
        case OperandLayout::BoolDef:
            if (auto e = want_length(2)) return e;
            if (auto e = read_dest(body)) return e;
            ins.constant_bits[0] = tokens_[body + 1];
            return std::nullopt;
        case OperandLayout::Standard:
            break;
        }

        size_t pos = body;
        if (info->has_dest()) {
            if (pos >= end) return DecodeError{at, std::string(info->mnemonic) + " is missing its destination"};
            if (auto e = read_dest(pos)) return e;
            ++pos;
        }
        if (fields.predicated) {
            if (pos >= end) return DecodeError{at, "predicated instruction is missing its predicate token"};
            bool rel = false;
            auto p = tokens::decode_source(tokens_[pos], &rel, &error);
            if (!p) return DecodeError{pos, error};
            if (rel) return DecodeError{pos, "predicate token cannot be relatively addressed"};
            ins.predicate = *p;
            ++pos;
        }
        while (pos < end) {
            bool rel = false;
            auto s = tokens::decode_source(tokens_[pos], &rel, &error);
            if (!s) return DecodeError{pos, error};
            ++pos;
            if (rel) {
                if (pos >= end)
                    return DecodeError{pos - 1, "relative source is missing its address token"};
                auto r = tokens::decode_relative(tokens_[pos], &error);
                if (!r) return DecodeError{pos, error};
                s->relative = *r;
                ++pos;
            }
            ins.sources.push_back(*s);
            if (ins.sources.size() > info->num_sources)
                return DecodeError{at, std::string(info->mnemonic) + " has more than " +
                                           std::to_string(info->num_sources) + " sources"};
        }
        if (ins.sources.size() < info->min_sources)
            return DecodeError{at, std::string(info->mnemonic) + " has " +
                                       std::to_string(ins.sources.size()) + " sources, needs " +
                                       std::to_string(info->min_sources)};
        (void)version;
        return std::nullopt;
    }

    std::span<const uint32_t> tokens_;
};

}  // namespace

DecodeResult decode(std::span<const uint32_t> tokens) { return Decoder(tokens).run(); }

DecodeResult decode_bytes(std::span<const std::byte> bytes) {
    if (bytes.size() % 4 != 0)
        return DecodeResult{std::nullopt,
                            DecodeError{bytes.size() / 4, "size " + std::to_string(bytes.size()) +
                                                              " bytes is not a whole number of DWORDs"}};
    std::vector<uint32_t> tokens(bytes.size() / 4);
    for (size_t i = 0; i < tokens.size(); ++i) {
        const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + 4 * i);
        tokens[i] = static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 |
                    static_cast<uint32_t>(b[2]) << 16 | static_cast<uint32_t>(b[3]) << 24;
    }
    return decode(tokens);
}

std::vector<uint32_t> encode(const Program& program) {
    std::vector<uint32_t> out;
    out.push_back(program.version.token());
    for (const Instruction& ins : program.instructions) {
        if (ins.opcode == Opcode::Comment) {
            out.push_back(tokens::encode_comment(static_cast<uint32_t>(ins.comment.size())));
            out.insert(out.end(), ins.comment.begin(), ins.comment.end());
            continue;
        }
        const OpcodeInfo* info = ins.info();
        const OperandLayout layout = info ? info->layout : OperandLayout::Standard;
        const auto op = static_cast<uint16_t>(ins.opcode);
        const DestinationParameter dest = ins.dest.value_or(DestinationParameter{});
        switch (layout) {
        case OperandLayout::Declaration:
            out.push_back(tokens::encode_instruction(op, 0, 2));
            out.push_back(tokens::encode_declaration(ins.declaration));
            out.push_back(tokens::encode_destination(dest));
            continue;
        case OperandLayout::FloatDef:
        case OperandLayout::IntDef:
            out.push_back(tokens::encode_instruction(op, 0, 5));
            out.push_back(tokens::encode_destination(dest));
            out.insert(out.end(), ins.constant_bits.begin(), ins.constant_bits.end());
            continue;
        case OperandLayout::BoolDef:
            out.push_back(tokens::encode_instruction(op, 0, 2));
            out.push_back(tokens::encode_destination(dest));
            out.push_back(ins.constant_bits[0]);
            continue;
        case OperandLayout::Standard:
            break;
        }
        size_t length = (ins.dest ? 1 : 0) + (ins.predicate ? 1 : 0);
        for (const auto& s : ins.sources) length += s.relative ? 2 : 1;
        out.push_back(tokens::encode_instruction(op, ins.control, static_cast<uint8_t>(length),
                                                 ins.predicate.has_value()));
        if (ins.dest) out.push_back(tokens::encode_destination(*ins.dest));
        if (ins.predicate) out.push_back(tokens::encode_source(*ins.predicate));
        for (const auto& s : ins.sources) {
            out.push_back(tokens::encode_source(s));
            if (s.relative) out.push_back(tokens::encode_relative(*s.relative));
        }
    }
    out.push_back(tokens::kEnd);
    return out;
}

std::vector<std::byte> to_bytes(std::span<const uint32_t> tokens) {
    std::vector<std::byte> bytes(tokens.size() * 4);
    for (size_t i = 0; i < tokens.size(); ++i)
        for (int k = 0; k < 4; ++k)
            bytes[4 * i + k] = static_cast<std::byte>((tokens[i] >> (8 * k)) & 0xFF);
    return bytes;
}

bool looks_like_bytecode(std::span<const std::byte> bytes) {
    if (bytes.size() < 4) return false;
    const auto b2 = static_cast<unsigned char>(bytes[2]);
    const auto b3 = static_cast<unsigned char>(bytes[3]);
    return b3 == 0xFF && (b2 == 0xFE || b2 == 0xFF);
}

}  // namespace sm2::isa
