// Real compiler output (tests/assembler/compiled, provenance in its README.md): every blob
// disassembles and reassembles to the identical bytes, its constant table decodes to the
// registers fxc's own header comment lists, fxc's listing assembles to its instructions, and
// the slot count is the one fxc printed.
#include <algorithm>
#include <cctype>
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

// fxc's level-9 output (vs_4_0_level_9_1, ps_4_0_level_9_1) is a DXBC container; its 'Aon9'
// chunk holds the vs_2_0/ps_2_0 program: after the tag and chunk size, a header whose third and
// fourth DWORDs are the program's size and its offset from the header's start, in bytes.
Tokens level9_program(const Tokens& container) {
    constexpr uint32_t kAon9 = 0x396E6F41;  // 'A' 'o' 'n' '9'
    const auto tag = std::find(container.begin(), container.end(), kAon9);
    const size_t header = static_cast<size_t>(tag - container.begin()) + 2;
    if (header + 4 > container.size()) return {};
    const size_t size = container[header + 2] / 4;
    const size_t offset = container[header + 3] / 4;
    if (header + offset + size > container.size()) return {};
    return Tokens(container.begin() + static_cast<std::ptrdiff_t>(header + offset),
                  container.begin() + static_cast<std::ptrdiff_t>(header + offset + size));
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
        constexpr uint32_t kDxbc = 0x43425844;  // 'D' 'X' 'B' 'C'
        if (!b.tokens.empty() && b.tokens[0] == kDxbc) b.tokens = level9_program(b.tokens);
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
    ASSERT_GE(blobs.size(), 15u);
    size_t vertex = 0;
    for (const Blob& b : blobs) vertex += !b.tokens.empty() && b.tokens[0] == 0xFFFE0200;
    EXPECT_GE(vertex, 5u);
    EXPECT_GE(blobs.size() - vertex, 10u);
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

// fxc's own listing of each blob, read by the assembler, gives the blob's bytes (its comment
// blocks aside: a listing shows the constant table as comments only).
TEST(CompiledCorpus, TheCompilersListingAssemblesToTheBlob) {
    size_t checked = 0;
    for (const Blob& b : corpus()) {
        if (b.listing.empty()) continue;
        SCOPED_TRACE(b.source);
        isa::Program without_comments = *isa::decode(b.tokens).program;
        std::erase_if(without_comments.instructions,
                      [](const isa::Instruction& ins) { return ins.opcode == isa::Opcode::Comment; });
        std::string listing;
        for (const std::string& line : b.listing) listing += line + "\n";
        const AssembleResult r = assemble(listing);
        ASSERT_TRUE(r.ok()) << listing << diagnostics_text(r);
        EXPECT_EQ(hex(r.tokens), hex(isa::encode(without_comments))) << listing;
        ++checked;
    }
    EXPECT_GE(checked, 12u);
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
