// The HLSL listings of the source documents (../shared/seeds: 000's Programs 2.1-3.5, 002's
// listings 4.2-4.4), as samples/shaders/documents/*.hlsl keeps them with the documents' mistakes
// corrected (each file's header says what was changed), compile with their entry points, and use
// the instruction slots counted here (docs/hlsl.md, "The documents' listings"). The documents give
// no slot count of their own for any listing, only the profiles' limits (000 l.1197: 256
// vertex-shader instructions; l.2963: 96 pixel-shader instructions, at most 64 arithmetic and 32
// texture), which every listing stays under.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sm2/hlsl/compiler.h"
#include "sm2/isa/validator.h"

namespace {

const std::filesystem::path kListings = std::filesystem::path(SM2_SOURCE_DIR) / "samples" / "shaders" / "documents";

struct Listing {
    const char* file;
    const char* entry;
    unsigned slots, texture_slots;
};

const Listing kListingTable[] = {
    {"000_program_2_1.vs.hlsl", "vmain", 4, 0},
    {"000_program_2_2.vs.hlsl", "vmain", 7, 0},
    {"000_program_2_3.vs.hlsl", "vmain", 26, 0},
    // 9 before the loop, rep 3, a body of 23 instructions (nrm and pow 3 slots each) 27, endrep 2,
    // 9 after (the spec's slot table, instructions.md).
    {"000_program_2_4.vs.hlsl", "vmain", 50, 0},
    {"000_program_3_1.ps.hlsl", "PShader", 1, 0},
    {"000_program_3_2.vs.hlsl", "VShader", 12, 0},
    {"000_program_3_3.ps.hlsl", "PShader", 25, 0},
    {"000_program_3_4.vs.hlsl", "VShader", 13, 0},
    {"000_program_3_5.ps.hlsl", "PShader", 20, 4},
    {"002_listing_4_2.ps.hlsl", "main", 24, 1},
    {"002_listings_4_3_4_4.ps.hlsl", "main", 36, 2},
};

void PrintTo(const Listing& listing, std::ostream* os) { *os << listing.file; }

class DocumentListing : public ::testing::TestWithParam<Listing> {};

TEST_P(DocumentListing, CompilesWithTheSlotsCounted) {
    const Listing& l = GetParam();
    std::ifstream in(kListings / l.file);
    ASSERT_TRUE(in) << l.file;
    std::stringstream text;
    text << in.rdbuf();
    sm2::hlsl::CompileOptions options;
    options.file_name = l.file;
    options.entry_point = l.entry;
    const bool vertex = std::string(l.file).find(".vs.") != std::string::npos;
    options.stage = vertex ? sm2::isa::ShaderType::Vertex : sm2::isa::ShaderType::Pixel;
    const auto result = sm2::hlsl::compile(text.str(), options);
    std::string messages;
    for (const auto& d : result.diagnostics) messages += sm2::hlsl::format_fxc(d) + "\n";
    ASSERT_TRUE(result.ok()) << messages;
    const sm2::isa::SlotCount slots = sm2::isa::count_slots(*result.program);
    EXPECT_EQ(slots.total, l.slots) << sm2::isa::slot_summary(slots) << "\n" << result.assembly;
    EXPECT_EQ(slots.texture, l.texture_slots) << sm2::isa::slot_summary(slots);
    EXPECT_LE(slots.total, vertex ? 256u : 96u);
}

INSTANTIATE_TEST_SUITE_P(Documents, DocumentListing, ::testing::ValuesIn(kListingTable),
                         [](const ::testing::TestParamInfo<Listing>& param) {
                             std::string name = param.param.file;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(DocumentListings, EveryFileHasARow) {
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(kListings)) files += entry.path().extension() == ".hlsl";
    EXPECT_EQ(files, std::size(kListingTable));
}

// Program 2.4 (000 l.1687, per-vertex Phong over n_lights lights) loops to a uniform count (`rep
// i0`) and indexes lights[i] with the counter: a float temp counts along, and each member is read
// at c[a0.x + m] after `mova a0.x, i * 4` (a T_LIGHT takes 4 registers). Run with chosen inputs in
// cli_tests HlslFlow.Program24IndexesTheLightsWithTheLoopCounter.
TEST(DocumentListings, Program24CompilesWithRelativeAddressing) {
    std::ifstream in(kListings / "000_program_2_4.vs.hlsl");
    ASSERT_TRUE(in);
    std::stringstream source;
    source << in.rdbuf();
    sm2::hlsl::CompileOptions options;
    options.entry_point = "vmain";
    options.stage = sm2::isa::ShaderType::Vertex;
    const auto result = sm2::hlsl::compile(source.str(), options);
    ASSERT_TRUE(result.ok()) << (result.diagnostics.empty() ? std::string() : result.diagnostics[0].message);
    // The entry point's name is 5 letters: its inputs are still v0, v1, v2 (the interface list
    // after the name was once found only after names of 4n letters, and every input read v0).
    for (const char* wanted : {"rep i0", "mova a0.x", "c[a0.x + 1]", "c[a0.x + 2]", "c[a0.x + 3]", "dcl_texcoord1 v1", "dcl_texcoord2 v2"})
        EXPECT_NE(result.assembly.find(wanted), std::string::npos) << wanted << "\n" << result.assembly;
}

}  // namespace
