// Lexer and minimal preprocessor.
#include "lexer.h"

#include <algorithm>
#include <map>

namespace sm2::assembler::detail {

void Reporter::add(uint32_t file, uint32_t line, uint32_t column, uint32_t physical,
                   std::string message) {
    // Bound memory on pathological input; take() reports at most max_errors anyway.
    if (entries_.size() >= 100000) return;
    Diagnostic d;
    d.severity = Severity::Error;
    d.file = file < files.size() ? files[file] : files[0];
    d.line = line;
    d.column = line > 0 ? column : 0;
    d.message = std::move(message);
    entries_.push_back(Entry{physical, column, std::move(d)});
}

std::vector<Diagnostic> Reporter::take(size_t max_errors) {
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
        return a.physical != b.physical ? a.physical < b.physical : a.column < b.column;
    });
    std::vector<Diagnostic> out;
    const size_t limit = max_errors == 0 ? entries_.size() : max_errors;
    for (size_t i = 0; i < entries_.size() && i < limit; ++i)
        out.push_back(std::move(entries_[i].diagnostic));
    if (entries_.size() > limit) {
        Diagnostic note;
        note.severity = Severity::Note;
        note.file = files[0];
        note.message = "too many errors (" + std::to_string(entries_.size()) +
                       "); only the first " + std::to_string(limit) + " are shown";
        out.push_back(std::move(note));
    }
    entries_.clear();
    return out;
}

namespace {

bool is_ident_start(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_ident_char(char c) { return is_ident_start(c) || is_digit(c); }
bool is_hex_digit(char c) {
    return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

enum class RawKind : uint8_t { Token, Newline, Hash, String, End };

struct Raw {
    RawKind kind = RawKind::End;
    Token token;
};

class Scanner {
public:
    Scanner(std::string_view text, Reporter& reporter) : text_(text), reporter_(reporter) {
        if (text_.starts_with("\xEF\xBB\xBF")) pos_ = line_start_ = 3;  // UTF-8 byte order mark
    }

    Raw next() {
        bool space = false;
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (is_space(c)) {
                ++pos_;
                space = true;
            } else if (c == '\\' && (peek(1) == '\n' || (peek(1) == '\r' && peek(2) == '\n'))) {
                // Line splice: the statement (or #define) continues on the next line.
                pos_ += peek(1) == '\r' ? 2 : 1;
                newline();
                ++pos_;
                space = true;
            } else if (c == ';' || (c == '/' && peek(1) == '/')) {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
                space = true;
            } else if (c == '/' && peek(1) == '*') {
                const Token start = make(TokenKind::Invalid, pos_, 2, false);
                pos_ += 2;
                bool closed = false;
                while (pos_ < text_.size()) {
                    if (text_[pos_] == '*' && peek(1) == '/') {
                        pos_ += 2;
                        closed = true;
                        break;
                    }
                    if (text_[pos_] == '\n') newline();
                    ++pos_;
                }
                if (!closed) reporter_.error(start, "unterminated /* comment");
                space = true;
            } else {
                break;
            }
        }
        Raw raw;
        if (pos_ >= text_.size()) {
            raw.kind = RawKind::End;
            raw.token = make(TokenKind::End, pos_, 0, space);
            return raw;
        }
        const size_t start = pos_;
        const char c = text_[pos_];
        if (c == '\n') {
            raw.kind = RawKind::Newline;
            raw.token = make(TokenKind::End, pos_, 1, space);
            newline();
            ++pos_;
            return raw;
        }
        raw.kind = RawKind::Token;
        TokenKind kind = TokenKind::Invalid;
        if (is_ident_start(c)) {
            while (pos_ < text_.size() && is_ident_char(text_[pos_])) ++pos_;
            kind = TokenKind::Identifier;
        } else if (is_digit(c) || (c == '.' && is_digit(peek(1)))) {
            scan_number();
            kind = TokenKind::Number;
        } else if (c == '"') {
            ++pos_;
            while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') ++pos_;
            if (pos_ < text_.size() && text_[pos_] == '"') ++pos_;
            raw.kind = RawKind::String;
        } else {
            ++pos_;
            switch (c) {
            case ',': kind = TokenKind::Comma; break;
            case '.': kind = TokenKind::Dot; break;
            case '[': kind = TokenKind::LBracket; break;
            case ']': kind = TokenKind::RBracket; break;
            case '+': kind = TokenKind::Plus; break;
            case '-': kind = TokenKind::Minus; break;
            case '!': kind = TokenKind::Bang; break;
            case '#': raw.kind = RawKind::Hash; break;
            default:
                // A run of characters that start nothing, reported once.
                while (pos_ < text_.size() && !starts_token(text_[pos_])) ++pos_;
                break;
            }
        }
        raw.token = make(kind, start, pos_ - start, space);
        return raw;
    }

private:
    static bool starts_token(char c) {
        return is_ident_start(c) || is_digit(c) || is_space(c) || c == '\n' || c == ',' ||
               c == '.' || c == '[' || c == ']' || c == '+' || c == '-' || c == '!' ||
               c == '#' || c == ';' || c == '/' || c == '"' || c == '\\';
    }

    char peek(size_t ahead) const {
        return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
    }

    void scan_number() {
        if (text_[pos_] == '0' && (peek(1) == 'x' || peek(1) == 'X') && is_hex_digit(peek(2))) {
            pos_ += 2;
            while (pos_ < text_.size() && is_hex_digit(text_[pos_])) ++pos_;
            return;
        }
        while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
        if (pos_ < text_.size() && text_[pos_] == '.') {
            ++pos_;
            while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
        }
        if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
            const size_t sign = (peek(1) == '+' || peek(1) == '-') ? 1 : 0;
            if (is_digit(peek(1 + sign))) {
                pos_ += 1 + sign;
                while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
            }
        }
        if (pos_ < text_.size() && (text_[pos_] == 'f' || text_[pos_] == 'F') &&
            !is_ident_char(peek(1)))
            ++pos_;
    }

    void newline() {
        ++physical_;
        line_start_ = pos_ + 1;
    }

    Token make(TokenKind kind, size_t start, size_t length, bool space) const {
        Token t;
        t.kind = kind;
        t.text = text_.substr(start, length);
        t.physical = physical_;
        t.line = static_cast<uint32_t>(static_cast<int64_t>(physical_) + 1 + line_delta);
        t.column = static_cast<uint32_t>(start - line_start_ + 1);
        t.file = file;
        t.space_before = space;
        return t;
    }

public:
    int64_t line_delta = 0;  // #line: reported = physical + 1 + delta
    uint32_t file = 0;

private:
    std::string_view text_;
    Reporter& reporter_;
    size_t pos_ = 0;
    size_t line_start_ = 0;
    uint32_t physical_ = 0;
};

class Preprocessor {
public:
    Preprocessor(std::string_view text, Reporter& reporter)
        : scanner_(text, reporter), reporter_(reporter) {}

    std::vector<Token> run() {
        bool line_start = true;
        while (true) {
            Raw raw = scanner_.next();
            if (raw.kind == RawKind::End) {
                Token end = raw.token;
                end.first_on_line = true;
                out_.push_back(end);
                return std::move(out_);
            }
            if (raw.kind == RawKind::Newline) {
                line_start = true;
                continue;
            }
            if (raw.kind == RawKind::Hash && line_start) {
                directive(raw.token);
                line_start = true;  // the directive consumed its newline
                continue;
            }
            raw.token.first_on_line = line_start;
            line_start = false;
            if (raw.kind != RawKind::Token) raw.token.kind = TokenKind::Invalid;
            emit(raw.token, raw.token, 0);
        }
    }

private:
    static constexpr size_t kMaxExpandedTokens = 1u << 20;
    static constexpr int kMaxExpansionDepth = 64;

    void emit(const Token& token, const Token& use, int depth) {
        if (token.kind == TokenKind::Identifier) {
            auto it = macros_.find(token.text);
            if (it != macros_.end() &&
                std::find(active_.begin(), active_.end(), token.text) == active_.end()) {
                if (depth >= kMaxExpansionDepth || expanded_ >= kMaxExpandedTokens) {
                    if (!expansion_reported_)
                        reporter_.error(use, "macro expansion of '" + std::string(token.text) +
                                                 "' is too large or too deep");
                    expansion_reported_ = true;
                    return;
                }
                active_.push_back(token.text);
                bool first = true;
                for (const Token& body : it->second) {
                    ++expanded_;
                    Token t = body;
                    t.line = use.line;
                    t.column = use.column;
                    t.physical = use.physical;
                    t.file = use.file;
                    t.first_on_line = use.first_on_line && first;
                    t.space_before = first ? use.space_before : body.space_before;
                    first = false;
                    emit(t, use, depth + 1);
                }
                active_.pop_back();
                return;
            }
        }
        out_.push_back(token);
    }

    // Reads the rest of the directive's line.
    std::vector<Raw> rest_of_line() {
        std::vector<Raw> items;
        while (true) {
            Raw raw = scanner_.next();
            if (raw.kind == RawKind::Newline || raw.kind == RawKind::End) break;
            items.push_back(raw);
        }
        return items;
    }

    void directive(const Token& hash) {
        std::vector<Raw> items = rest_of_line();
        if (items.empty()) return;  // null directive
        const Token& name = items[0].token;
        if (items[0].kind != RawKind::Token || name.kind != TokenKind::Identifier) {
            reporter_.error(name, "expected a preprocessor directive name after '#'");
            return;
        }
        if (name.text == "define") {
            if (items.size() < 2 || items[1].kind != RawKind::Token ||
                items[1].token.kind != TokenKind::Identifier) {
                reporter_.error(items.size() < 2 ? name : items[1].token,
                                "#define needs a macro name");
                return;
            }
            const Token& macro = items[1].token;
            if (items.size() > 2 && !items[2].token.space_before &&
                items[2].token.text.starts_with('(')) {
                reporter_.error(items[2].token, "function-like macros are not supported");
                return;
            }
            std::vector<Token> body;
            for (size_t i = 2; i < items.size(); ++i) {
                Token t = items[i].token;
                if (items[i].kind != RawKind::Token) t.kind = TokenKind::Invalid;
                body.push_back(t);
            }
            macros_[macro.text] = std::move(body);
        } else if (name.text == "undef") {
            if (items.size() != 2 || items[1].token.kind != TokenKind::Identifier) {
                reporter_.error(name, "#undef needs exactly one macro name");
                return;
            }
            macros_.erase(items[1].token.text);
        } else if (name.text == "line") {
            line_directive(name, items);
        } else {
            reporter_.error(hash, "unsupported preprocessor directive '#" +
                                      std::string(name.text) +
                                      "' (only #define, #undef and #line are supported)");
        }
    }

    void line_directive(const Token& name, const std::vector<Raw>& items) {
        if (items.size() < 2 || items[1].kind != RawKind::Token ||
            items[1].token.kind != TokenKind::Number ||
            items[1].token.text.find_first_not_of("0123456789") != std::string_view::npos ||
            items[1].token.text.size() > 9) {
            reporter_.error(items.size() < 2 ? name : items[1].token,
                            "#line needs a decimal line number");
            return;
        }
        uint32_t number = 0;
        for (char c : items[1].token.text) number = number * 10 + static_cast<uint32_t>(c - '0');
        if (items.size() > 3 || (items.size() == 3 && items[2].kind != RawKind::String)) {
            reporter_.error(items.back().token, "#line takes a line number and an optional \"file name\"");
            return;
        }
        if (items.size() == 3) {
            std::string_view quoted = items[2].token.text;
            if (quoted.size() < 2 || quoted.back() != '"') {
                reporter_.error(items[2].token, "unterminated file name in #line");
                return;
            }
            reporter_.files.emplace_back(quoted.substr(1, quoted.size() - 2));
            scanner_.file = static_cast<uint32_t>(reporter_.files.size() - 1);
        }
        // The line after the directive gets `number`.
        const int64_t next_physical = static_cast<int64_t>(name.physical) + 1;
        scanner_.line_delta = static_cast<int64_t>(number) - (next_physical + 1);
    }

    Scanner scanner_;
    Reporter& reporter_;
    std::map<std::string_view, std::vector<Token>, std::less<>> macros_;
    std::vector<std::string_view> active_;
    std::vector<Token> out_;
    size_t expanded_ = 0;
    bool expansion_reported_ = false;
};

}  // namespace

std::vector<Token> tokenize(std::string_view text, Reporter& reporter) {
    return Preprocessor(text, reporter).run();
}

}  // namespace sm2::assembler::detail
