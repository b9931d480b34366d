// The text form of command streams: parser and canonical printer (docs/command-stream.md).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "half.h"
#include "sm2/runtime/file_io.h"
#include "sm2/runtime/command_stream.h"

namespace sm2::runtime::cs {

namespace {

constexpr int kMaxTupleDepth = 16;

struct BlobTypeInfo {
    BlobType type;
    std::string_view name;
    size_t element_size;
    size_t per_row;
};
constexpr BlobTypeInfo kBlobTypes[] = {
    {BlobType::U8, "u8", 1, 16},   {BlobType::U16, "u16", 2, 16}, {BlobType::U32, "u32", 4, 8},
    {BlobType::I16, "i16", 2, 16}, {BlobType::I32, "i32", 4, 8},  {BlobType::F32, "f32", 4, 8},
    {BlobType::F16, "f16", 2, 8},  {BlobType::Hex, "hex", 4, 8},
};

const BlobTypeInfo* find_blob_type(std::string_view name) {
    for (const auto& t : kBlobTypes)
        if (t.name == name) return &t;
    return nullptr;
}
const BlobTypeInfo& blob_info(BlobType type) {
    for (const auto& t : kBlobTypes)
        if (t.type == type) return t;
    return kBlobTypes[0];
}

uint32_t float_bits(float f) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
}
float bits_float(uint32_t b) {
    float f;
    std::memcpy(&f, &b, 4);
    return f;
}

// Shortest text that reads back to the same bits, always recognisable as a float.
std::string format_float(uint32_t bits) {
    const float f = bits_float(bits);
    if (std::isnan(f)) {
        if (bits == 0x7FC00000u) return "nan";
        char buf[24];
        std::snprintf(buf, sizeof buf, "nan:0x%08X", bits);
        return buf;
    }
    if (std::isinf(f)) return f > 0 ? "inf" : "-inf";
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, f);
    std::string s(buf, end);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

std::string format_integer(const Value& v) {
    if (v.hex) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "0x%08X", static_cast<uint32_t>(v.integer));
        return buf;
    }
    return std::to_string(v.integer);
}

template <typename T>
T load(const std::byte* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

std::string format_element(BlobType type, const std::byte* p) {
    switch (type) {
    case BlobType::U8: return std::to_string(load<uint8_t>(p));
    case BlobType::U16: return std::to_string(load<uint16_t>(p));
    case BlobType::U32: {
        char buf[16];
        std::snprintf(buf, sizeof buf, "0x%08X", load<uint32_t>(p));
        return buf;
    }
    case BlobType::I16: return std::to_string(load<int16_t>(p));
    case BlobType::I32: return std::to_string(load<int32_t>(p));
    case BlobType::F32: return format_float(load<uint32_t>(p));
    case BlobType::F16: return format_float(float_bits(half_to_float(load<uint16_t>(p))));
    case BlobType::Hex: {
        char buf[16];
        const auto* b = reinterpret_cast<const unsigned char*>(p);
        std::snprintf(buf, sizeof buf, "%02x%02x%02x%02x", b[0], b[1], b[2], b[3]);
        return buf;
    }
    }
    return "?";
}

void print_value(const Value& v, std::string& out);

void print_blob(const Value& v, std::string& out) {
    const BlobTypeInfo& info = blob_info(v.blob_type);
    out += info.name;
    out += '[';
    const size_t size = v.bytes.size();
    // Hex blobs print whole 4-byte groups and then the remaining bytes.
    std::vector<std::string> elements;
    size_t i = 0;
    for (; i + info.element_size <= size; i += info.element_size)
        elements.push_back(format_element(v.blob_type, v.bytes.data() + i));
    if (v.blob_type == BlobType::Hex && i < size) {
        std::string tail;
        for (; i < size; ++i) {
            char buf[4];
            std::snprintf(buf, sizeof buf, "%02x", static_cast<unsigned>(v.bytes[i]));
            tail += buf;
        }
        elements.push_back(tail);
    }
    if (elements.size() <= info.per_row) {
        for (const auto& e : elements) out += ' ' + e;
        out += " ]";
        return;
    }
    for (size_t k = 0; k < elements.size(); ++k) {
        out += k % info.per_row == 0 ? "\n  " : " ";
        out += elements[k];
    }
    out += "\n]";
}

std::string quote(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') q += '\\';
        q += c;
    }
    return q + '"';
}

void print_value(const Value& v, std::string& out) {
    switch (v.kind) {
    case Value::Kind::Integer: out += format_integer(v); break;
    case Value::Kind::Float: out += format_float(v.float_bits); break;
    case Value::Kind::Identifier: out += v.text; break;
    case Value::Kind::String: out += quote(v.text); break;
    case Value::Kind::Tuple:
        out += '{';
        for (const auto& item : v.items) {
            out += ' ';
            print_value(item, out);
        }
        out += " }";
        break;
    case Value::Kind::Blob: print_blob(v, out); break;
    case Value::Kind::SideFile: out += '@' + quote(v.text); break;
    case Value::Kind::Heredoc:
        out += (v.language == Value::Language::Hlsl ? "hlsl<<" : "asm<<") + v.text + '\n';
        out.append(reinterpret_cast<const char*>(v.bytes.data()), v.bytes.size());
        out += v.text;
        break;
    }
}

class Parser {
public:
    Parser(std::string_view text, const TextOptions& options) : text_(text), options_(options) {}

    ParseResult run() {
        Stream stream;
        if (!parse_header(stream)) return failure();
        while (pos_ < text_.size()) {
            Statement st;
            st.line = line_;
            if (!parse_statement(st)) return failure();
            stream.statements.push_back(std::move(st));
        }
        return ParseResult{std::move(stream), std::nullopt};
    }

private:
    ParseResult failure() { return ParseResult{std::nullopt, error_}; }

    bool fail(std::string message) {
        if (!error_) error_ = ParseError{options_.file_name, line_, column(), pos_, std::move(message)};
        return false;
    }
    uint32_t column() const { return static_cast<uint32_t>(pos_ - line_start_ + 1); }
    bool at_end() const { return pos_ >= text_.size(); }
    char peek(size_t ahead = 0) const {
        return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
    }
    void advance() {
        if (at_end()) return;
        if (text_[pos_] == '\n') {
            ++line_;
            line_start_ = pos_ + 1;
        }
        ++pos_;
    }
    void skip_blanks() {
        while (!at_end() && (peek() == ' ' || peek() == '\t' || peek() == '\r')) advance();
    }
    // Blanks and line breaks (inside tuples and blobs).
    void skip_space() {
        while (!at_end() && std::isspace(static_cast<unsigned char>(peek()))) advance();
    }
    bool at_line_end() const { return at_end() || peek() == '\n'; }
    void end_line() {
        if (!at_end()) advance();  // the '\n'
    }

    static bool is_ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
    static bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

    std::string_view word() {
        const size_t start = pos_;
        while (!at_end() && is_ident_char(peek())) advance();
        return text_.substr(start, pos_ - start);
    }

    bool parse_header(Stream& stream) {
        skip_blanks();
        if (word() != "sm2cs") return fail("a command stream starts with 'sm2cs VERSION'");
        skip_blanks();
        const size_t start = pos_;
        while (!at_end() && std::isdigit(static_cast<unsigned char>(peek()))) advance();
        uint32_t version = 0;
        const auto digits = text_.substr(start, pos_ - start);
        if (digits.empty() || std::from_chars(digits.data(), digits.data() + digits.size(), version).ec != std::errc{})
            return fail("expected the format version after 'sm2cs'");
        if (version != kFormatVersion)
            return fail("unsupported command-stream version " + std::to_string(version) + " (this build reads " +
                        std::to_string(kFormatVersion) + ")");
        stream.version = version;
        skip_blanks();
        if (!at_line_end()) return fail("unexpected text after the version");
        end_line();
        return true;
    }

    bool parse_statement(Statement& st) {
        skip_blanks();
        if (at_line_end()) {
            st.kind = Statement::Kind::Blank;
            end_line();
            return true;
        }
        if (peek() == '#') {
            st.kind = Statement::Kind::Comment;
            advance();
            st.name = rest_of_line();
            end_line();
            return true;
        }
        if (!is_ident_start(peek())) return fail("expected a call name");
        const uint32_t name_column = column();
        st.name = std::string(word());
        if (!call_id(st.name)) {
            error_ = ParseError{options_.file_name, line_, name_column, pos_, "unknown call '" + st.name + "'"};
            return false;
        }
        while (true) {
            skip_blanks();
            if (at_line_end()) break;
            if (peek() == '#') {
                advance();
                st.trailing_comment = rest_of_line();
                break;
            }
            Value v;
            if (!parse_value(v, 0)) return false;
            const bool heredoc = v.kind == Value::Kind::Heredoc;
            st.arguments.push_back(std::move(v));
            if (heredoc) return true;  // a heredoc ends its statement
            if (!at_line_end() && peek() != ' ' && peek() != '\t' && peek() != '\r' && peek() != '#')
                return fail("expected a blank between arguments");
        }
        end_line();
        return true;
    }

    std::string rest_of_line() {
        const size_t start = pos_;
        while (!at_line_end()) advance();
        std::string s(text_.substr(start, pos_ - start));
        while (!s.empty() && s.back() == '\r') s.pop_back();  // CRLF files; canonical text has none
        return s;
    }

    bool parse_value(Value& v, int depth) {
        const char c = peek();
        if (c == '{') return parse_tuple(v, depth);
        if (c == '"') {
            v.kind = Value::Kind::String;
            return parse_string(v.text);
        }
        if (c == '@') {
            const uint32_t col = column();
            advance();
            if (peek() != '"') return fail("expected a quoted file name after '@'");
            v.kind = Value::Kind::SideFile;
            if (!parse_string(v.text)) return false;
            std::string why = "side files are not read here";
            auto bytes = options_.side_files ? options_.side_files(options_.root_dir.empty() ? options_.base_dir
                                                                                             : options_.root_dir,
                                                                   options_.base_dir, v.text, why)
                                             : std::nullopt;
            if (!bytes) {
                error_ = ParseError{options_.file_name, line_, col, pos_,
                                    "cannot read side file '" + v.text + "': " + why};
                return false;
            }
            v.bytes = std::move(*bytes);
            return true;
        }
        if (c == '-' || c == '+' || c == '.' || std::isdigit(static_cast<unsigned char>(c))) return parse_number(v);
        if (is_ident_start(c)) {
            const size_t start = pos_;
            const uint32_t word_column = column();
            const std::string_view w = word();
            if (w == "inf" || w == "nan") {
                pos_ = start;  // re-read the word as a number (same line)
                return parse_number(v);
            }
            if (peek() == '[') {
                const BlobTypeInfo* info = find_blob_type(w);
                if (!info) return fail("unknown blob type '" + std::string(w) + "'");
                return parse_blob(v, *info);
            }
            if ((w == "asm" || w == "hlsl") && peek() == '<' && peek(1) == '<') {
                if (depth > 0) {
                    error_ = ParseError{options_.file_name, line_, word_column, pos_,
                                        "a heredoc can only be a call's last argument, not inside '{ }'"};
                    return false;
                }
                v.language = w == "hlsl" ? Value::Language::Hlsl : Value::Language::Asm;
                return parse_heredoc(v, word_column);
            }
            v.kind = Value::Kind::Identifier;
            v.text = std::string(w);
            return true;
        }
        return fail(std::string("unexpected character '") + c + "'");
    }

    bool parse_tuple(Value& v, int depth) {
        if (depth >= kMaxTupleDepth) return fail("tuples nested too deeply");
        v.kind = Value::Kind::Tuple;
        advance();  // '{'
        while (true) {
            skip_space();
            if (at_end()) return fail("unterminated '{'");
            if (peek() == '}') {
                advance();
                return true;
            }
            Value item;
            if (!parse_value(item, depth + 1)) return false;
            v.items.push_back(std::move(item));
        }
    }

    bool parse_string(std::string& out) {
        advance();  // '"'
        while (true) {
            if (at_line_end()) return fail("unterminated string");
            char c = peek();
            if (c == '"') {
                advance();
                return true;
            }
            if (c == '\\') {
                advance();
                c = peek();
                if (c != '"' && c != '\\') return fail("only \\\" and \\\\ escapes are allowed in strings");
            }
            out += c;
            advance();
        }
    }

    // One number token: decimal or hex integer, or a float (with '.', exponent, inf, nan).
    std::string_view number_token() {
        const size_t start = pos_;
        while (!at_end() && (is_ident_char(peek()) || peek() == '.' || peek() == '-' || peek() == '+' || peek() == ':'))
            advance();
        return text_.substr(start, pos_ - start);
    }

    bool parse_number(Value& v) {
        const uint32_t col = column();
        const std::string_view tok = number_token();
        auto bad = [&](const std::string& why) {
            error_ = ParseError{options_.file_name, line_, col, pos_, why + " '" + std::string(tok) + "'"};
            return false;
        };
        if (auto i = parse_integer(tok)) {
            v.kind = Value::Kind::Integer;
            v.integer = i->first;
            v.hex = i->second;
            if (v.integer < INT32_MIN || v.integer > static_cast<int64_t>(UINT32_MAX))
                return bad("integer out of 32-bit range");
            return true;
        }
        if (auto f = parse_float(tok)) {
            v.kind = Value::Kind::Float;
            v.float_bits = *f;
            return true;
        }
        return bad("not a number");
    }

    // (value, written in hex)
    static std::optional<std::pair<int64_t, bool>> parse_integer(std::string_view tok) {
        bool negative = false;
        std::string_view t = tok;
        if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
            negative = t[0] == '-';
            t.remove_prefix(1);
        }
        const bool hex = t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X');
        if (hex) t.remove_prefix(2);
        if (t.empty() || t.size() > 16) return std::nullopt;
        uint64_t value = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value, hex ? 16 : 10);
        if (ec != std::errc{} || end != t.data() + t.size()) return std::nullopt;
        if (value > 0xFFFFFFFFull) return std::pair<int64_t, bool>{INT64_MAX, hex};
        const auto signed_value = static_cast<int64_t>(value);
        return std::pair<int64_t, bool>{negative ? -signed_value : signed_value, hex};
    }

    static std::optional<uint32_t> parse_float(std::string_view tok) {
        if (tok == "inf" || tok == "+inf") return 0x7F800000u;
        if (tok == "-inf") return 0xFF800000u;
        if (tok == "nan") return 0x7FC00000u;
        if (tok.rfind("nan:0x", 0) == 0) {
            uint32_t bits = 0;
            const auto hex = tok.substr(6);
            auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), bits, 16);
            if (ec != std::errc{} || end != hex.data() + hex.size() || hex.size() > 8) return std::nullopt;
            if (!std::isnan(bits_float(bits))) return std::nullopt;
            return bits;
        }
        std::string_view t = tok;
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        float f = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), f);
        if (ec != std::errc{} || end != t.data() + t.size()) return std::nullopt;
        return float_bits(f);
    }

    bool parse_blob(Value& v, const BlobTypeInfo& info) {
        v.kind = Value::Kind::Blob;
        v.blob_type = info.type;
        advance();  // '['
        while (true) {
            skip_space();
            if (at_end()) return fail("unterminated blob");
            if (peek() == ']') {
                advance();
                return true;
            }
            if (!parse_element(v, info)) return false;
        }
    }

    template <typename T>
    void store(Value& v, T value) {
        const auto* p = reinterpret_cast<const std::byte*>(&value);
        v.bytes.insert(v.bytes.end(), p, p + sizeof value);
    }

    bool parse_element(Value& v, const BlobTypeInfo& info) {
        const uint32_t col = column();
        const size_t start = pos_;
        while (!at_end() && !std::isspace(static_cast<unsigned char>(peek())) && peek() != ']') advance();
        const std::string_view tok = text_.substr(start, pos_ - start);
        auto bad = [&](const char* why) {
            error_ = ParseError{options_.file_name, line_, col, pos_,
                                std::string(why) + " '" + std::string(tok) + "' in " + std::string(info.name) + " blob"};
            return false;
        };
        if (info.type == BlobType::Hex) {
            if (tok.size() % 2 != 0) return bad("odd number of hex digits");
            for (size_t i = 0; i < tok.size(); i += 2) {
                unsigned byte = 0;
                auto [end, ec] = std::from_chars(tok.data() + i, tok.data() + i + 2, byte, 16);
                if (ec != std::errc{} || end != tok.data() + i + 2) return bad("bad hex digits");
                v.bytes.push_back(static_cast<std::byte>(byte));
            }
            return true;
        }
        if (info.type == BlobType::F32 || info.type == BlobType::F16) {
            std::optional<uint32_t> bits = parse_float(tok);
            if (!bits) {
                if (auto i = parse_integer(tok); i && !i->second && i->first >= INT32_MIN && i->first <= INT32_MAX)
                    bits = float_bits(static_cast<float>(i->first));
            }
            if (!bits) return bad("not a float");
            if (info.type == BlobType::F32) store(v, *bits);
            else store(v, float_to_half(bits_float(*bits)));
            return true;
        }
        auto i = parse_integer(tok);
        if (!i) return bad("not an integer");
        const int64_t x = i->first;
        switch (info.type) {
        case BlobType::U8:
            if (x < 0 || x > 255) return bad("out of range");
            store(v, static_cast<uint8_t>(x));
            return true;
        case BlobType::U16:
            if (x < 0 || x > 65535) return bad("out of range");
            store(v, static_cast<uint16_t>(x));
            return true;
        case BlobType::U32:
            if (x < 0 || x > static_cast<int64_t>(UINT32_MAX)) return bad("out of range");
            store(v, static_cast<uint32_t>(x));
            return true;
        case BlobType::I16:
            if (x < INT16_MIN || x > INT16_MAX) return bad("out of range");
            store(v, static_cast<int16_t>(x));
            return true;
        case BlobType::I32:
            if (x < INT32_MIN || x > INT32_MAX) return bad("out of range");
            store(v, static_cast<int32_t>(x));
            return true;
        default:
            return bad("unsupported element");
        }
    }

    bool parse_heredoc(Value& v, uint32_t start_column) {
        const uint32_t start_line = line_;
        advance();
        advance();  // "<<"
        if (!is_ident_start(peek())) return fail("expected a terminator name after '<<'");
        v.kind = Value::Kind::Heredoc;
        v.text = std::string(word());
        skip_blanks();
        if (!at_line_end()) return fail("a heredoc's text starts on the next line");
        end_line();
        std::string body;
        while (!at_end()) {
            std::string line = rest_of_line();
            end_line();
            if (line == v.text) {
                v.bytes.resize(body.size());
                if (!body.empty()) std::memcpy(v.bytes.data(), body.data(), body.size());
                return true;
            }
            body += line;
            body += '\n';
        }
        error_ = ParseError{options_.file_name, start_line, start_column, pos_,
                            "heredoc '" + v.text + "' is never terminated"};
        return false;
    }

    std::string_view text_;
    const TextOptions& options_;
    size_t pos_ = 0;
    size_t line_start_ = 0;
    uint32_t line_ = 1;
    std::optional<ParseError> error_;
};

}  // namespace

float Value::as_float() const {
    if (kind == Kind::Float) return bits_float(float_bits);
    if (kind == Kind::Integer) return static_cast<float>(integer);
    return 0.0f;
}

std::string ParseError::to_string() const {
    std::string s = file.empty() ? "<input>" : file;
    if (line > 0) s += ':' + std::to_string(line) + ':' + std::to_string(column);
    else s += ": byte " + std::to_string(byte_offset);
    return s + ": error: " + message;
}

std::optional<std::vector<std::byte>> read_side_file(const std::string& root_dir, const std::string& base_dir,
                                                     const std::string& path, std::string& error) {
    const auto full = resolve_inside(root_dir, base_dir, path, error);
    if (!full) return std::nullopt;
    std::string why;
    auto bytes = read_file_limited(*full, kMaxInputFileBytes, why);
    if (!bytes) {
        // read_file_limited names the resolved path; the stream's own spelling is already in
        // the message, so keep only the reason.
        const std::string prefix = *full + ": ";
        error = why.compare(0, prefix.size(), prefix) == 0 ? why.substr(prefix.size()) : why;
    }
    return bytes;
}

ParseResult parse_text(std::string_view text, const TextOptions& options) {
    return Parser(text, options).run();
}

std::string to_text(const Stream& stream) {
    std::string out = "sm2cs " + std::to_string(stream.version) + '\n';
    for (const Statement& st : stream.statements) {
        switch (st.kind) {
        case Statement::Kind::Blank: break;
        case Statement::Kind::Comment: out += '#' + st.name; break;
        case Statement::Kind::Call:
            out += st.name;
            for (const Value& v : st.arguments) {
                out += ' ';
                print_value(v, out);
            }
            if (!st.trailing_comment.empty() &&
                !(st.arguments.size() && st.arguments.back().kind == Value::Kind::Heredoc))
                out += "  #" + st.trailing_comment;
            break;
        }
        out += '\n';
    }
    return out;
}

}  // namespace sm2::runtime::cs
