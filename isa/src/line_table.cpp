// The 'SM2L' HLSL line table (line_table.h): writing and bounds-checked reading.
#include "sm2/isa/line_table.h"

#include <algorithm>
#include <cstring>

namespace sm2::isa {

namespace {

void put_string(std::vector<uint32_t>& out, const std::string& s) {
    out.push_back(static_cast<uint32_t>(s.size()));
    const size_t first = out.size();
    out.resize(first + (s.size() + 3) / 4, 0);
    if (!s.empty()) std::memcpy(out.data() + first, s.data(), s.size());
}

class Reader {
public:
    explicit Reader(std::span<const uint32_t> words) : words_(words) {}
    bool u32(uint32_t& v) {
        if (pos_ >= words_.size()) return false;
        v = words_[pos_++];
        return true;
    }
    bool string(std::string& s) {
        uint32_t size = 0;
        if (!u32(size)) return false;
        const size_t dwords = (size_t{size} + 3) / 4;
        if (dwords > words_.size() - pos_) return false;
        s.resize(size);
        if (size) std::memcpy(s.data(), words_.data() + pos_, size);
        pos_ += dwords;
        return true;
    }
    // A count of records of at least `min_words` each that fits in what is left.
    bool count(uint32_t& n, size_t min_words) {
        return u32(n) && size_t{n} * min_words <= words_.size() - pos_;
    }

private:
    std::span<const uint32_t> words_;
    size_t pos_ = 0;
};

}  // namespace

const LineTable::Entry* LineTable::entry(uint32_t instruction) const {
    auto it = std::lower_bound(entries.begin(), entries.end(), instruction,
                               [](const Entry& e, uint32_t i) { return e.instruction < i; });
    return it != entries.end() && it->instruction == instruction ? &*it : nullptr;
}

const std::string* LineTable::text(uint32_t file, uint32_t line) const {
    for (const auto& l : lines)
        if (l.file == file && l.line == line) return &l.text;
    return nullptr;
}

std::vector<uint32_t> serialize_line_table(const LineTable& table) {
    std::vector<uint32_t> out{kFourccLineTable, kLineTableVersion};
    out.push_back(static_cast<uint32_t>(table.files.size()));
    for (const auto& f : table.files) put_string(out, f);
    out.push_back(static_cast<uint32_t>(table.lines.size()));
    for (const auto& l : table.lines) {
        out.push_back(l.file);
        out.push_back(l.line);
        put_string(out, l.text);
    }
    out.push_back(static_cast<uint32_t>(table.entries.size()));
    for (const auto& e : table.entries) out.insert(out.end(), {e.instruction, e.file, e.line, e.column});
    return out;
}

LineTableResult parse_line_table(std::span<const uint32_t> payload) {
    LineTableResult result;
    Reader in(payload);
    uint32_t fourcc = 0, version = 0, n = 0;
    if (!in.u32(fourcc) || fourcc != kFourccLineTable) return {std::nullopt, "not an 'SM2L' block"};
    if (!in.u32(version) || version != kLineTableVersion)
        return {std::nullopt, "line table version " + std::to_string(version) + " (this reader knows 1)"};
    LineTable t;
    if (!in.count(n, 1)) return {std::nullopt, "file count past the end of the block"};
    t.files.resize(n);
    for (auto& f : t.files)
        if (!in.string(f)) return {std::nullopt, "file name past the end of the block"};
    if (!in.count(n, 3)) return {std::nullopt, "source line count past the end of the block"};
    t.lines.resize(n);
    for (auto& l : t.lines) {
        if (!in.u32(l.file) || !in.u32(l.line) || !in.string(l.text))
            return {std::nullopt, "source line past the end of the block"};
        if (l.file >= t.files.size()) return {std::nullopt, "source line names file " + std::to_string(l.file)};
    }
    if (!in.count(n, 4)) return {std::nullopt, "entry count past the end of the block"};
    t.entries.resize(n);
    for (size_t k = 0; k < t.entries.size(); ++k) {
        auto& e = t.entries[k];
        (void)(in.u32(e.instruction) && in.u32(e.file) && in.u32(e.line) && in.u32(e.column));
        if (e.file >= t.files.size()) return {std::nullopt, "entry names file " + std::to_string(e.file)};
        if (k > 0 && e.instruction <= t.entries[k - 1].instruction)
            return {std::nullopt, "entries not in ascending instruction order"};
    }
    result.table = std::move(t);
    return result;
}

std::optional<LineTableResult> find_line_table(const Program& program) {
    for (const auto& ins : program.instructions)
        if (ins.opcode == Opcode::Comment && !ins.comment.empty() && ins.comment[0] == kFourccLineTable)
            return parse_line_table(ins.comment);
    return std::nullopt;
}

std::vector<int64_t> instruction_ordinals(const Program& program) {
    std::vector<int64_t> out;
    out.reserve(program.instructions.size());
    int64_t next = 0;
    for (const auto& ins : program.instructions) out.push_back(ins.opcode == Opcode::Comment ? -1 : next++);
    return out;
}

}  // namespace sm2::isa
