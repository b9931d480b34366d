// apitrace's call-set syntax, parsed by hand with the column of the first error.
#include "call_set.h"

#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

namespace sm2::tools {

namespace {

class Parser {
public:
    explicit Parser(std::string_view text) : text_(text) {}

    // The next unsigned number, or nullopt (position unchanged).
    std::optional<uint64_t> number() {
        uint64_t value = 0;
        const char* begin = text_.data() + pos_;
        const auto [end, ec] = std::from_chars(begin, text_.data() + text_.size(), value);
        if (ec == std::errc::result_out_of_range) {
            fail("call number too large");
            return std::nullopt;
        }
        if (ec != std::errc() || end == begin) return std::nullopt;
        pos_ += static_cast<size_t>(end - begin);
        return value;
    }
    bool word(std::string_view w) {
        if (text_.substr(pos_, w.size()) != w) return false;
        const size_t after = pos_ + w.size();
        if (after < text_.size() && std::isalnum(static_cast<unsigned char>(text_[after]))) return false;
        pos_ = after;
        return true;
    }
    bool peek(char c) const { return pos_ < text_.size() && text_[pos_] == c; }
    bool accept(char c) {
        if (!peek(c)) return false;
        ++pos_;
        return true;
    }
    void skip_separators() {
        while (pos_ < text_.size() && (text_[pos_] == ',' || text_[pos_] == ';' || std::isspace(static_cast<unsigned char>(text_[pos_]))))
            ++pos_;
    }
    bool at_end() const { return pos_ >= text_.size(); }
    bool at_separator() const {
        return at_end() || text_[pos_] == ',' || text_[pos_] == ';' || std::isspace(static_cast<unsigned char>(text_[pos_]));
    }
    void fail(const std::string& what) {
        if (!error_.empty()) return;
        error_ = "column " + std::to_string(pos_ + 1) + ": " + what;
        if (!at_end()) error_ += " at '" + std::string(text_.substr(pos_, 12)) + "'";
    }
    [[nodiscard]] const std::string& error() const { return error_; }
    [[nodiscard]] size_t position() const { return pos_; }
    [[nodiscard]] std::string_view rest() const { return text_.substr(pos_); }
    void skip_to_separator() {
        while (!at_separator()) ++pos_;
    }

private:
    std::string_view text_;
    size_t pos_ = 0;
    std::string error_;
};

}  // namespace

bool is_draw_call(std::string_view name) { return name.starts_with("Draw"); }

std::optional<CallSet> CallSet::parse(std::string_view text, std::string& error) {
    CallSet set;
    Parser p(text);
    auto failed = [&]() -> std::optional<CallSet> {
        error = "call set '" + std::string(text) + "': " + p.error();
        return std::nullopt;
    };
    p.skip_separators();
    if (p.at_end()) {
        p.fail("empty: expected a call number, a range, '*', 'frame', 'draw' or '@FILE'");
        return failed();
    }
    while (!p.at_end()) {
        if (p.accept('@')) {
            const size_t start = p.position();
            p.skip_to_separator();
            const std::string file(text.substr(start, p.position() - start));
            std::ifstream in(file);
            if (file.empty() || !in) {
                p.fail("cannot read the call-set file '" + file + "'");
                return failed();
            }
            std::stringstream contents;
            contents << in.rdbuf();
            std::string inner_error;
            const auto inner = parse(contents.str(), inner_error);
            if (!inner) {
                error = file + ": " + inner_error;
                return std::nullopt;
            }
            set.ranges_.insert(set.ranges_.end(), inner->ranges_.begin(), inner->ranges_.end());
            p.skip_separators();
            continue;
        }
        Range r;
        if (p.accept('*')) {
        } else if (p.word("frame")) {
            r.frames_only = true;
        } else if (p.word("draw")) {
            r.draws_only = true;
        } else if (auto first = p.number()) {
            r.first = *first;
            r.last = *first;
            if (p.accept('-')) {
                if (auto last = p.number()) {
                    if (*last < *first) {
                        p.fail("the range ends (" + std::to_string(*last) + ") before it starts (" +
                               std::to_string(*first) + ")");
                        return failed();
                    }
                    r.last = *last;
                } else if (p.at_separator() || p.peek('/')) {
                    r.last = UINT64_MAX;  // "20-": to the end
                } else {
                    p.fail("expected a call number after '-'");
                    return failed();
                }
            }
        } else {
            p.fail("expected a call number, a range, '*', 'frame', 'draw' or '@FILE'");
            return failed();
        }
        if (!p.error().empty()) return failed();
        while (p.accept('/')) {
            if (p.word("draw")) {
                r.draws_only = true;
            } else if (p.word("frame")) {
                r.frames_only = true;
            } else if (auto step = p.number()) {
                if (*step == 0) {
                    p.fail("a step must be at least 1");
                    return failed();
                }
                r.step = *step;
            } else {
                p.fail("expected a step (a number), 'draw' or 'frame' after '/'");
                return failed();
            }
        }
        if (!p.at_separator()) {
            p.fail("expected ',', a blank or the end");
            return failed();
        }
        set.ranges_.push_back(r);
        p.skip_separators();
    }
    return set;
}

bool CallSet::contains(uint64_t call, std::string_view name) const {
    for (const Range& r : ranges_) {
        if (call < r.first || call > r.last || (call - r.first) % r.step != 0) continue;
        if (r.draws_only && !is_draw_call(name)) continue;
        if (r.frames_only && name != "Present") continue;
        return true;
    }
    return false;
}

}  // namespace sm2::tools
