// Tokens of the assembly text after the minimal preprocessor (#define, #undef, #line).
// Newlines are not tokens: a statement ends where its operands end (as in Wine's grammar);
// each token knows whether it is the first on its physical line, which the parser uses to
// recover after an error.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/assembler/diagnostics.h"

namespace sm2::assembler::detail {

enum class TokenKind : uint8_t {
    Identifier,  // [A-Za-z_][A-Za-z0-9_]*
    Number,      // 12, 1., .5, 1.5e-3, 2f, 0x7FC00000 (sign is a separate token)
    Comma,
    Dot,
    LBracket,
    RBracket,
    Plus,
    Minus,
    Bang,
    Invalid,     // a run of characters that start no token
    End,
};

struct Token {
    TokenKind kind = TokenKind::End;
    std::string_view text;
    uint32_t line = 0;      // reported line (after #line)
    uint32_t column = 0;    // 1-based byte column
    uint32_t physical = 0;  // physical line index (0-based) for recovery and ordering
    uint32_t file = 0;      // index into Reporter::files
    bool first_on_line = false;
    bool space_before = false;  // whitespace or a comment separates it from the previous token
};

// Collects diagnostics; they are sorted into source order when taken.
class Reporter {
public:
    explicit Reporter(std::string file_name) { files.push_back(std::move(file_name)); }

    void error(const Token& at, std::string message) { add(at.file, at.line, at.column, at.physical, std::move(message)); }
    void error_at(uint32_t file, uint32_t line, uint32_t column, uint32_t physical, std::string message) {
        add(file, line, column, physical, std::move(message));
    }
    void error_whole(std::string message) {
        add(0, 0, 0, UINT32_MAX, std::move(message));
    }
    [[nodiscard]] size_t error_count() const { return entries_.size(); }
    // Sorted by position; at most max_errors errors, then a note.
    [[nodiscard]] std::vector<Diagnostic> take(size_t max_errors);

    std::deque<std::string> files;  // [0] = the caller's name; more from #line "name"

private:
    struct Entry {
        uint32_t physical;
        uint32_t column;
        Diagnostic diagnostic;
    };
    void add(uint32_t file, uint32_t line, uint32_t column, uint32_t physical, std::string message);
    std::vector<Entry> entries_;
};

// Lexes and preprocesses the whole text.
[[nodiscard]] std::vector<Token> tokenize(std::string_view text, Reporter& reporter);

}  // namespace sm2::assembler::detail
