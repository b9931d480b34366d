// Real compiler output (tests/assembler/compiled, provenance in its README.md): every blob
// disassembles and reassembles to the identical bytes, its constant table decodes to the
// registers fxc's own header comment lists, and its instructions read as fxc's listing does.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "helpers.h"
#include "sm2/isa/constant_table.h"
#include "sm2/isa/validator.h"

namespace sm2::assembler::test {
namespace {

struct Blob {
    std::string source;  // file and array name, for messages
    Tokens tokens;
    std::vector<std::string> registers;  // "name reg size" from the header's Registers table
    std::vector<std::string> listing;    // the header's instructions, one per entry
    std::string slots;                   // "approximately N instruction slots used (...)"
};

std::string read_text(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::string trim(std::string s) {
    const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
    s.erase(s.begin(), std::find_if_not(s.begin(), s.end(), space));
    s.erase(std::find_if_not(s.rbegin(), s.rend(), space).base(), s.end());
    return s;
}

std::vector<std::string> split_words(const std::string& s) {
    std::istringstream in(s);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

// The numbers between the braces of `TYPE name[] = { ... };`, BYTEs packed little-endian.
Tokens array_tokens(const std::string& body, bool bytes) {
    Tokens out;
    std::vector<uint32_t> values;
    std::string item;
    std::istringstream in(body);
    while (std::getline(in, item, ',')) {
        item = trim(item);
        if (!item.empty()) values.push_back(static_cast<uint32_t>(std::stoul(item, nullptr, 0)));
    }
    if (!bytes) return values;
    for (size_t i = 0; i + 3 < values.size(); i += 4)
        out.push_back(values[i] | values[i + 1] << 8 | values[i + 2] << 16 | values[i + 3] << 24);
    return out;
}

// fxc /Fh headers: the comment table and listing inside `#if 0`, then one BYTE array.
// Other files: every DWORD array, with no listing or table.
std::vector<Blob> blobs_of(const std::filesystem::path& file) {
    const std::string text = read_text(file);
    std::vector<std::string> registers;
    std::vector<std::string> listing;
    std::string slots;
    std::istringstream lines(text);
    enum class Section { None, Registers, Listing } section = Section::None;
    for (std::string line; std::getline(lines, line);) {
        line = trim(line);
        if (line == "// Registers:") {
            section = Section::Registers;
        } else if (section == Section::Registers) {
            if (line == "//" && !registers.empty()) section = Section::None;
            const auto words = split_words(line.size() > 2 ? line.substr(2) : "");
            if (words.size() == 3 && words[0] != "Name" && words[0][0] != '-')
                registers.push_back(words[0] + " " + words[1] + " " + words[2]);
        } else if (line == "vs_2_0" || line == "ps_2_0") {
            section = Section::Listing;
            listing.push_back(line);
        } else if (section == Section::Listing) {
            if (line.starts_with("// approximately")) slots = line.substr(3);
            if (line.starts_with("//") || line == "#endif") section = Section::None;
            else if (!line.empty()) listing.push_back(line);
        }
    }
    std::vector<Blob> blobs;
    for (size_t at = text.find("[] ="); at != std::string::npos; at = text.find("[] =", at + 1)) {
        const size_t name_start = text.rfind(' ', at) + 1;
        const size_t line_start = text.rfind('\n', at) + 1;
        const bool bytes = text.substr(line_start, at - line_start).find("BYTE") != std::string::npos;
        const size_t open = text.find('{', at);
        const size_t close = text.find('}', open);
        Blob b;
        b.source = file.filename().string() + ":" + text.substr(name_start, at - name_start);
        b.tokens = array_tokens(text.substr(open + 1, close - open - 1), bytes);
        b.registers = registers;
        b.listing = listing;
        b.slots = slots;
        blobs.push_back(std::move(b));
    }
    return blobs;
}

std::vector<Blob> corpus() {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SM2_SOURCE_DIR) /
                                                             "tests/assembler/compiled"))
        if (e.path().extension() == ".h" || e.path().extension() == ".c") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<Blob> all;
    for (const auto& f : files)
        for (Blob& b : blobs_of(f)) all.push_back(std::move(b));
    return all;
}

std::vector<std::string> table_registers(const isa::ConstantTable& table) {
    std::vector<std::string> out;
    for (const isa::ConstantInfo& c : table.constants)
        out.push_back(c.name + " " + isa::register_set_prefix(c.register_set) + std::to_string(c.register_index) +
                      " " + std::to_string(c.register_count));
    return out;
}

TEST(CompiledCorpus, HasBothProfiles) {
    const auto blobs = corpus();
    ASSERT_GE(blobs.size(), 13u);
    size_t vertex = 0;
    for (const Blob& b : blobs) vertex += !b.tokens.empty() && b.tokens[0] == 0xFFFE0200;
    EXPECT_GE(vertex, 4u);
    EXPECT_GE(blobs.size() - vertex, 9u);
}

TEST(CompiledCorpus, DisassemblyReassemblesToTheIdenticalBytes) {
    for (const Blob& b : corpus()) {
        SCOPED_TRACE(b.source);
        const isa::DecodeResult decoded = isa::decode(b.tokens);
        ASSERT_TRUE(decoded.ok()) << decoded.error->to_string();
        const CheckedDisassembly dis = disassemble_checked(*decoded.program);
        EXPECT_FALSE(dis.error) << dis.error->message;
        EXPECT_EQ(hex(assemble_tokens(dis.text)), hex(b.tokens)) << dis.text;
        // With validation too: compiler output is valid vs_2_0 / ps_2_0.
        EXPECT_TRUE(assemble(dis.text).ok()) << dis.text;
    }
}

TEST(CompiledCorpus, ConstantTablesNameTheRegistersTheHeadersList) {
    size_t checked = 0;
    for (const Blob& b : corpus()) {
        if (b.registers.empty()) continue;
        SCOPED_TRACE(b.source);
        const isa::DecodeResult decoded = isa::decode(b.tokens);
        ASSERT_TRUE(decoded.ok());
        const auto table = isa::find_constant_table(*decoded.program);
        ASSERT_TRUE(table && table->ok()) << (table ? table->error : "no CTAB");
        auto expected = b.registers;
        auto got = table_registers(*table->table);
        std::sort(expected.begin(), expected.end());
        std::sort(got.begin(), got.end());
        EXPECT_EQ(got, expected);
        EXPECT_EQ(table->table->target, std::string(decoded.program->version.name()));
        EXPECT_TRUE(table->table->creator.starts_with("Microsoft (R) HLSL Shader Compiler"));
        // The readable decoding names each of them next to the directive.
        const std::string text = disassemble(*decoded.program);
        for (const isa::ConstantInfo& c : table->table->constants)
            EXPECT_NE(text.find("//   " + c.name), std::string::npos) << text;
        ++checked;
    }
    EXPECT_GE(checked, 10u);
}

// SDL2's blobs come without fxc's comment table; their HLSL source (quoted in the file) binds
// theTextureY/U/V to t0/t1/t2, which fxc names "theSampler+theTexture?" on s0/s1/s2.
TEST(CompiledCorpus, ConstantTablesOfTheSdl2Blobs) {
    size_t checked = 0;
    for (const Blob& b : corpus()) {
        if (!b.source.starts_with("sdl2_")) continue;
        SCOPED_TRACE(b.source);
        const auto table = isa::find_constant_table(*isa::decode(b.tokens).program);
        ASSERT_TRUE(table && table->ok());
        EXPECT_EQ(table_registers(*table->table),
                  (std::vector<std::string>{"theSampler+theTextureU s1 1", "theSampler+theTextureV s2 1",
                                            "theSampler+theTextureY s0 1"}));
        EXPECT_EQ(isa::constant_type_name(table->table->constants[0].type), "texture2D");
        EXPECT_EQ(table->table->creator, "Microsoft (R) HLSL Shader Compiler 6.3.9600.16384");
        ++checked;
    }
    EXPECT_EQ(checked, 3u);
}

// `def` values compare as floats (fxc prints 0.99609375 where the shortest text is shorter).
bool same_statement(const std::string& ours, const std::string& theirs) {
    if (ours == theirs) return true;
    if (!ours.starts_with("def ") || !theirs.starts_with("def ")) return false;
    std::vector<std::string> a;
    std::vector<std::string> b;
    std::string item;
    for (std::istringstream in(ours); std::getline(in, item, ',');) a.push_back(trim(item));
    for (std::istringstream in(theirs); std::getline(in, item, ',');) b.push_back(trim(item));
    if (a.size() != 5 || b.size() != 5 || a[0] != b[0]) return false;
    for (size_t k = 1; k < 5; ++k)
        if (std::bit_cast<uint32_t>(std::strtof(a[k].c_str(), nullptr)) !=
            std::bit_cast<uint32_t>(std::strtof(b[k].c_str(), nullptr)))
            return false;
    return true;
}

TEST(CompiledCorpus, InstructionsReadAsTheCompilersListing) {
    size_t checked = 0;
    for (const Blob& b : corpus()) {
        if (b.listing.empty()) continue;
        SCOPED_TRACE(b.source);
        const std::string text = disassemble(*isa::decode(b.tokens).program);
        std::vector<std::string> ours;
        std::istringstream lines(text);
        bool in_comment = false;
        for (std::string line; std::getline(lines, line);) {
            // Skip the comment block: its directive and the words continuing it.
            if (line.starts_with("comment")) in_comment = true;
            else if (!line.starts_with(" ")) in_comment = false;
            if (!in_comment && !line.starts_with("//")) ours.push_back(line);
        }
        ASSERT_EQ(ours.size(), b.listing.size()) << text;
        for (size_t i = 0; i < ours.size(); ++i)
            EXPECT_TRUE(same_statement(ours[i], b.listing[i])) << ours[i] << " vs fxc: " << b.listing[i];
        ++checked;
    }
    EXPECT_GE(checked, 10u);
}

}  // namespace
}  // namespace sm2::assembler::test

namespace sm2::assembler::test {
namespace {

// fxc's own slot count, printed under its listing, against the validator's.
TEST(CompiledCorpus, SlotCountsAreFxcs) {
    size_t checked = 0;
    for (const Blob& b : corpus()) {
        if (b.slots.empty()) continue;
        SCOPED_TRACE(b.source);
        EXPECT_EQ(isa::slot_summary(isa::count_slots(*isa::decode(b.tokens).program)), b.slots);
        ++checked;
    }
    EXPECT_GE(checked, 10u);
}

}  // namespace
}  // namespace sm2::assembler::test
