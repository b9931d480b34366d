// The constant table (CTAB comment) sm2::hlsl::compile writes, read back with the isa parser; every
// field is worked out by hand from the declarations (registers at register(cN) or in declaration
// order from c0 past the explicit ones, samplers at register(sN) or the lowest free s#).
#include <gtest/gtest.h>

#include <bit>
#include <string>
#include <vector>

#include "sm2/hlsl/compiler.h"
#include "sm2/isa/constant_table.h"

namespace {

using sm2::isa::ConstantInfo;
using sm2::isa::ConstantRegisterSet;
namespace parameter_class = sm2::isa::parameter_class;
namespace parameter_type = sm2::isa::parameter_type;

constexpr const char* kUniforms =
    "float4 tint = float4(1, 0.5, 0.25, -2);\n"  // c0
    "row_major float3x4 bones;\n"                 // c1..c3: one register per row
    "float4x3 normals;\n"                         // c4..c6: one register per column (column_major)
    "float scale : register(c20) = 0.5f;\n"       // c20, as placed
    "float4 palette[2];\n"                        // c7..c8: on from c7, where normals ended
    "float2x2 skew = {1, 2, 3, 4};\n"             // c9..c10: columns (1,3) and (2,4)
    "sampler2D diffuse : register(s1);\n"         // s1
    "samplerCUBE env;\n"                          // s0, the lowest free
    "float4 main(float2 uv : TEXCOORD0, float3 n : TEXCOORD1) : COLOR {\n"
    "  return tex2D(diffuse, uv) * tint * scale + texCUBE(env, n) + palette[1]\n"
    "       + float4(mul(bones, float4(n, 1)), 1) + float4(mul(float4(n, 1), normals), 0);\n"
    "}\n";

struct Expected {
    const char* name;
    ConstantRegisterSet set;
    uint16_t index, count;
    uint16_t parameter_class, parameter_type, rows, columns, elements;
    std::vector<float> defaults;  // 4 per register; empty: none
};

std::string messages(const sm2::hlsl::CompileResult& result) {
    std::string text;
    for (const auto& d : result.diagnostics) text += sm2::hlsl::format_fxc(d) + "\n";
    return text;
}

std::vector<uint32_t> bits(const std::vector<float>& values) {
    std::vector<uint32_t> words;
    for (float v : values) words.push_back(std::bit_cast<uint32_t>(v));
    return words;
}

void expect_constant(const sm2::isa::ConstantTable& table, const Expected& e) {
    const ConstantInfo* c = sm2::isa::find_constant(table, e.name);
    ASSERT_NE(c, nullptr) << e.name;
    SCOPED_TRACE(e.name);
    EXPECT_EQ(c->register_set, e.set);
    EXPECT_EQ(c->register_index, e.index);
    EXPECT_EQ(c->register_count, e.count);
    EXPECT_EQ(c->type.parameter_class, e.parameter_class);
    EXPECT_EQ(c->type.parameter_type, e.parameter_type);
    EXPECT_EQ(c->type.rows, e.rows);
    EXPECT_EQ(c->type.columns, e.columns);
    EXPECT_EQ(c->type.elements, e.elements);
    EXPECT_TRUE(c->type.members.empty());
    EXPECT_EQ(c->default_value, bits(e.defaults));
}

}  // namespace

TEST(HlslConstantTable, NamesEveryUniformAndSamplerWithItsRegisters) {
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Pixel;
    const auto result = sm2::hlsl::compile(kUniforms, options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value());
    ASSERT_TRUE(found->ok()) << found->error;
    const sm2::isa::ConstantTable& table = *found->table;
    EXPECT_EQ(table.target, "ps_2_0");
    EXPECT_EQ(table.version, 0xFFFF0200u);
    EXPECT_EQ(table.creator, "sm2emu sm2 compile (glslang HLSL, SPIRV-Tools, sm2 back end)");
    EXPECT_EQ(table.constants.size(), 8u);
    const auto F4 = ConstantRegisterSet::Float4;
    const auto S = ConstantRegisterSet::Sampler;
    expect_constant(table, {"tint", F4, 0, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {1, 0.5f, 0.25f, -2}});
    expect_constant(table, {"bones", F4, 1, 3, parameter_class::MatrixRows, parameter_type::Float, 3, 4, 1, {}});
    expect_constant(table, {"normals", F4, 4, 3, parameter_class::MatrixColumns, parameter_type::Float, 4, 3, 1, {}});
    expect_constant(table, {"scale", F4, 20, 1, parameter_class::Scalar, parameter_type::Float, 1, 1, 1, {0.5f, 0, 0, 0}});
    expect_constant(table, {"palette", F4, 7, 2, parameter_class::Vector, parameter_type::Float, 1, 4, 2, {}});
    expect_constant(table, {"skew", F4, 9, 2, parameter_class::MatrixColumns, parameter_type::Float, 2, 2, 1,
                            {1, 3, 0, 0, 2, 4, 0, 0}});
    expect_constant(table, {"diffuse", S, 1, 1, parameter_class::Object, parameter_type::Sampler2D, 1, 1, 1, {}});
    expect_constant(table, {"env", S, 0, 1, parameter_class::Object, parameter_type::SamplerCube, 1, 1, 1, {}});
    // The registers the table names are the ones the code reads: tint is c0, scale c20, and the
    // literals' defs come after the last uniform register (c21).
    EXPECT_NE(result.assembly.find("c0"), std::string::npos);
    EXPECT_NE(result.assembly.find("c20.x"), std::string::npos) << result.assembly;
    EXPECT_EQ(result.assembly.find("def c1,"), std::string::npos) << result.assembly;
}

TEST(HlslConstantTable, VertexShaderTableAndRowMajorDefaults) {
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Vertex;
    const auto result = sm2::hlsl::compile(
        "row_major float2x3 m = float2x3(1, 2, 3, 4, 5, 6);\n"  // c0 = (1,2,3), c1 = (4,5,6)
        "float4 offset = 7;\n"                                  // c2: a scalar fills the vector
        "float4 main(float4 p : POSITION) : POSITION { return float4(mul(m, p.xyz), 0, 1) + offset; }\n",
        options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value() && found->ok());
    EXPECT_EQ(found->table->target, "vs_2_0");
    EXPECT_EQ(found->table->version, 0xFFFE0200u);
    ASSERT_EQ(found->table->constants.size(), 2u);
    const auto F4 = ConstantRegisterSet::Float4;
    expect_constant(*found->table, {"m", F4, 0, 2, parameter_class::MatrixRows, parameter_type::Float, 2, 3, 1,
                                    {1, 2, 3, 0, 4, 5, 6, 0}});
    expect_constant(*found->table, {"offset", F4, 2, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {7, 7, 7, 7}});
}

TEST(HlslConstantTable, InitializersThatAreNotLiteralsGiveNoDefault) {
    sm2::hlsl::CompileOptions options;
    const auto result = sm2::hlsl::compile(
        "float4 k = 2 * float4(1, 1, 1, 1);\n"
        "#define ONE 1\n"
        "float4 j = float4(ONE, 2, 3, 4);\n"  // the text is read without the preprocessor
        "float4 main() : COLOR { return k + j; }\n",
        options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value() && found->ok());
    expect_constant(*found->table, {"k", ConstantRegisterSet::Float4, 0, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"j", ConstantRegisterSet::Float4, 1, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
}

TEST(HlslConstantTable, BoolAndIntUniformsTakeFloatRegisters) {
    // glslang stores a bool member as an unsigned int; the table names it bool, from the source.
    // Defaults are floats, as in any c# register: true = 1, 3 = 3.
    sm2::hlsl::CompileOptions options;
    const auto result = sm2::hlsl::compile(
        "bool flag = true;\nint count = 3;\nfloat4 tint;\nfloat4 main() : COLOR { return tint; }\n", options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value() && found->ok());
    const auto F4 = ConstantRegisterSet::Float4;
    expect_constant(*found->table, {"flag", F4, 0, 1, parameter_class::Scalar, parameter_type::Bool, 1, 1, 1, {1, 0, 0, 0}});
    expect_constant(*found->table, {"count", F4, 1, 1, parameter_class::Scalar, parameter_type::Int, 1, 1, 1, {3, 0, 0, 0}});
    expect_constant(*found->table, {"tint", F4, 2, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
}

// register(cN) places a uniform (as the sample scenes' HLSL twins need: the streams set fixed
// registers); the others fill the registers left free, in declaration order.
TEST(HlslConstantTable, ExplicitConstantRegistersAreHonoured) {
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Vertex;
    const auto result = sm2::hlsl::compile(
        "float4 a;\n"                                   // c0
        "row_major float4x4 m : register(c1);\n"        // c1..c4
        "float4 b;\n"                                   // c5: after c0, c1..c4 are taken
        "row_major float3x4 bones[2] : register( c10 );\n"  // c10..c15
        "float4 c : register(C7);\n"                    // c7 (upper case, as fxc accepts)
        "float4 d;\n"                                   // c6, the lowest free from c6 on
        "float4 e[2];\n"                                // c8..c9: c7 is taken, c8..c9 are free
        "float4 main(float4 p : POSITION) : POSITION {\n"
        "  return mul(m, p) + a + b + c + d + e[1] + float4(mul(bones[1], p), 1);\n}\n",
        options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value() && found->ok());
    const auto F4 = ConstantRegisterSet::Float4;
    expect_constant(*found->table, {"a", F4, 0, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"m", F4, 1, 4, parameter_class::MatrixRows, parameter_type::Float, 4, 4, 1, {}});
    expect_constant(*found->table, {"b", F4, 5, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"bones", F4, 10, 6, parameter_class::MatrixRows, parameter_type::Float, 3, 4, 2, {}});
    expect_constant(*found->table, {"c", F4, 7, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"d", F4, 6, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"e", F4, 8, 2, parameter_class::Vector, parameter_type::Float, 1, 4, 2, {}});
    // The code reads the placed registers: m's rows c1..c4, bones[1]'s rows c13..c15, e[1] = c9.
    for (const char* reg : {"c1\n", "c4\n", "c5", "c6", "c7", "c9", "c13\n", "c15\n"})
        EXPECT_NE(result.assembly.find(reg), std::string::npos) << reg << "\n" << result.assembly;
}

TEST(HlslConstantTable, ExplicitConstantRegistersThatOverlapOrRunPastTheLastAreErrors) {
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Pixel;
    const auto overlap = sm2::hlsl::compile("float4x4 m : register(c0);\nfloat4 k : register(c3);\n"
                                            "float4 main() : COLOR { return m[0] + k; }\n", options);
    EXPECT_FALSE(overlap.ok());
    EXPECT_NE(messages(overlap).find("'k' at register(c3) overlaps another uniform's registers c0..c3"), std::string::npos)
        << messages(overlap);
    const auto past = sm2::hlsl::compile("float4 k[2] : register(c31);\nfloat4 main() : COLOR { return k[1]; }\n", options);
    EXPECT_FALSE(past.ok());
    EXPECT_NE(messages(past).find("'k' at register(c31) runs past c31, the last constant register of ps_2_0"), std::string::npos)
        << messages(past);
}

TEST(HlslConstantTable, FlowControlUniformsTakeBoolAndIntRegisters) {
    // vs_2_0: a bool deciding an `if` lives in b#, an int counting a loop in i#, in declaration order
    // and without a c# register, so the float after them is c0. No defaults for b#/i#.
    sm2::hlsl::CompileOptions options;
    options.stage = sm2::isa::ShaderType::Vertex;
    const auto result = sm2::hlsl::compile(
        "bool first = true;\nint count = 3;\nfloat4 tint;\nbool second;\n"
        "float4 main(float4 pos : POSITION) : POSITION {\n"
        "  float4 acc = pos;\n"
        "  for (int i = 0; i < count; i++) acc += tint;\n"
        "  if (second) acc *= 2;\n  if (first) acc += 1;\n"
        "  return acc;\n}\n",
        options);
    ASSERT_TRUE(result.ok()) << messages(result);
    const auto found = sm2::isa::find_constant_table(*result.program);
    ASSERT_TRUE(found.has_value() && found->ok());
    expect_constant(*found->table, {"first", ConstantRegisterSet::Bool, 0, 1, parameter_class::Scalar, parameter_type::Bool, 1, 1, 1, {}});
    expect_constant(*found->table, {"count", ConstantRegisterSet::Int4, 0, 1, parameter_class::Scalar, parameter_type::Int, 1, 1, 1, {}});
    expect_constant(*found->table, {"tint", ConstantRegisterSet::Float4, 0, 1, parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}});
    expect_constant(*found->table, {"second", ConstantRegisterSet::Bool, 1, 1, parameter_class::Scalar, parameter_type::Bool, 1, 1, 1, {}});
}
