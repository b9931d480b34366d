// The CTAB parser against Wine's d3dx9 test table (whose expected descriptions Wine checks
// against native D3DX) and against malformed tables, which must give errors, never crashes.
#include <gtest/gtest.h>

#include <bit>
#include <string>
#include <vector>

#include "sm2/isa/bytecode.h"
#include "sm2/isa/constant_table.h"

namespace sm2::isa {
namespace {

// Wine dlls/d3dx9_36/tests/shader.c, ctab_matrices2 (vs_2_0): the comment payload.
const std::vector<uint32_t> kWineMatrices2 = {
    0x42415443, 0x0000001c, 0x0000012b, 0xfffe0200, 0x00000006, 0x0000001c, 0x00000100, 0x00000124,
    0x00000094, 0x00070002, 0x00000003, 0x0000009c, 0x00000000,  // c2x3
    0x000000ac, 0x000d0002, 0x00000002, 0x000000b4, 0x00000000,  // c3x2
    0x000000c4, 0x000a0002, 0x00000003, 0x000000cc, 0x00000000,  // c3x3
    0x000000dc, 0x000f0002, 0x00000002, 0x000000e4, 0x00000000,  // r2x3
    0x000000f4, 0x00040002, 0x00000003, 0x000000fc, 0x00000000,  // r3x2
    0x0000010c, 0x00000002, 0x00000004, 0x00000114, 0x00000000,  // r4x4
    0x33783263, 0xababab00, 0x00030003, 0x00030002, 0x00000001, 0x00000000,
    0x32783363, 0xababab00, 0x00030003, 0x00020003, 0x00000001, 0x00000000,
    0x33783363, 0xababab00, 0x00030003, 0x00030003, 0x00000001, 0x00000000,
    0x33783272, 0xababab00, 0x00030002, 0x00030002, 0x00000001, 0x00000000,
    0x32783372, 0xababab00, 0x00030002, 0x00020003, 0x00000001, 0x00000000,
    0x34783472, 0xababab00, 0x00030002, 0x00040004, 0x00000001, 0x00000000,
    0x325f7376, 0x4100305f, 0x41414141, 0x00414141};

TEST(ConstantTable, WineMatrices) {
    const ConstantTableResult r = parse_constant_table(kWineMatrices2);
    ASSERT_TRUE(r.ok()) << r.error;
    const ConstantTable& t = *r.table;
    EXPECT_EQ(t.target, "vs_2_0");
    EXPECT_EQ(t.creator, "AAAAAAAA");
    EXPECT_EQ(t.version, 0xFFFE0200u);
    EXPECT_EQ(t.flags, 0x100u);
    ASSERT_EQ(t.constants.size(), 6u);
    // Wine's ctab_matrices2_expected: name, register index, count, class, rows, columns.
    struct Expected {
        const char* name;
        uint16_t index, count, parameter_class, rows, columns;
        const char* type;
    };
    const Expected expected[] = {
        {"c2x3", 7, 3, 3, 2, 3, "float2x3"},  {"c3x2", 13, 2, 3, 3, 2, "float3x2"},
        {"c3x3", 10, 3, 3, 3, 3, "float3x3"}, {"r2x3", 15, 2, 2, 2, 3, "row_major float2x3"},
        {"r3x2", 4, 3, 2, 3, 2, "row_major float3x2"}, {"r4x4", 0, 4, 2, 4, 4, "row_major float4x4"}};
    for (size_t i = 0; i < 6; ++i) {
        const ConstantInfo& c = t.constants[i];
        SCOPED_TRACE(expected[i].name);
        EXPECT_EQ(c.name, expected[i].name);
        EXPECT_EQ(c.register_set, ConstantRegisterSet::Float4);
        EXPECT_EQ(c.register_index, expected[i].index);
        EXPECT_EQ(c.register_count, expected[i].count);
        EXPECT_EQ(c.type.parameter_class, expected[i].parameter_class);
        EXPECT_EQ(c.type.parameter_type, 3);  // D3DXPT_FLOAT
        EXPECT_EQ(c.type.rows, expected[i].rows);
        EXPECT_EQ(c.type.columns, expected[i].columns);
        EXPECT_EQ(c.type.elements, 1);
        EXPECT_EQ(constant_type_name(c.type), expected[i].type);
        EXPECT_TRUE(c.default_value.empty());
    }
    EXPECT_EQ(find_constant(t, "r3x2"), &t.constants[4]);
    EXPECT_EQ(find_constant(t, "R3X2"), nullptr);

    // find_constant_table finds it in a program: version, comment, END. (Wine's blob gives the
    // comment 88 DWORDs where its table has 78; the token here counts them.)
    std::vector<uint32_t> blob = {0xFFFE0200, 0x004EFFFE};
    blob.insert(blob.end(), kWineMatrices2.begin(), kWineMatrices2.end());
    blob.push_back(0x0000FFFF);
    const DecodeResult d = decode(blob);
    ASSERT_TRUE(d.ok()) << d.error->to_string();
    const auto found = find_constant_table(*d.program);
    ASSERT_TRUE(found && found->ok());
    EXPECT_EQ(found->table->constants.size(), 6u);
}

// Wine's ctab_with_default_values (vs_2_0), payload only: Wine's expected default values (checked
// against native D3DX) are the table's raw registers, 4 floats each.
TEST(ConstantTable, WineDefaultValues) {
    const std::vector<uint32_t> payload = {
        0x42415443, 0x0000001c, 0x000001b7, 0xfffe0200, 0x00000005, 0x0000001c, 0x00000100, 0x000001b0,
        0x00000080, 0x00080002, 0x00000003, 0x00000084, 0x00000094,  // arr
        0x000000c4, 0x000c0002, 0x00000001, 0x000000c8, 0x000000d8,  // flt
        0x000000e8, 0x00040002, 0x00000004, 0x000000f0, 0x00000100,  // mat3
        0x00000140, 0x00000002, 0x00000004, 0x000000f0, 0x00000148,  // mat4
        0x00000188, 0x000b0002, 0x00000001, 0x00000190, 0x000001a0,  // vec4
        0x00727261, 0x00030000, 0x00010001, 0x00000003, 0x00000000,
        0x42c80000, 0x00000000, 0x00000000, 0x00000000, 0x43480000, 0x00000000, 0x00000000, 0x00000000,
        0x43960000, 0x00000000, 0x00000000, 0x00000000,
        0x00746c66, 0x00030000, 0x00010001, 0x00000001, 0x00000000,
        0x411fd70a, 0x00000000, 0x00000000, 0x00000000,
        0x3374616d, 0xababab00, 0x00030003, 0x00040004, 0x00000001, 0x00000000,
        0x41300000, 0x425c0000, 0x42c60000, 0x44a42000, 0x41b00000, 0x42840000, 0x447c8000, 0x44b0c000,
        0x42040000, 0x429a0000, 0x448ae000, 0x44bd6000, 0x42300000, 0x42b00000, 0x44978000, 0x44ca0000,
        0x3474616d, 0xababab00,
        0x3f800000, 0x40a00000, 0x41100000, 0x41500000, 0x40000000, 0x40c00000, 0x41200000, 0x41600000,
        0x40400000, 0x40e00000, 0x41300000, 0x41700000, 0x40800000, 0x41000000, 0x41400000, 0x41800000,
        0x34636576, 0xababab00, 0x00030001, 0x00040001, 0x00000001, 0x00000000,
        0x41200000, 0x41a00000, 0x41f00000, 0x42200000,
        0x325f7376, 0x4d004141, 0x41414141, 0x00000000};
    const ConstantTableResult r = parse_constant_table(payload);
    ASSERT_TRUE(r.ok()) << r.error;
    auto floats = [](const ConstantInfo* c) {
        std::vector<float> f;
        for (uint32_t bits : c->default_value) f.push_back(std::bit_cast<float>(bits));
        return f;
    };
    const ConstantTable& t = *r.table;
    ASSERT_EQ(t.constants.size(), 5u);
    EXPECT_EQ(floats(find_constant(t, "mat4")),
              (std::vector<float>{1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 4, 8, 12, 16}));
    EXPECT_EQ(floats(find_constant(t, "mat3")),
              (std::vector<float>{11, 55, 99, 1313, 22, 66, 1010, 1414, 33, 77, 1111, 1515, 44, 88, 1212, 1616}));
    EXPECT_EQ(floats(find_constant(t, "arr")), (std::vector<float>{100, 0, 0, 0, 200, 0, 0, 0, 300, 0, 0, 0}));
    EXPECT_EQ(floats(find_constant(t, "vec4")), (std::vector<float>{10, 20, 30, 40}));
    EXPECT_EQ(floats(find_constant(t, "flt")), (std::vector<float>{9.99f, 0, 0, 0}));
    EXPECT_EQ(constant_type_name(find_constant(t, "arr")->type), "float[3]");
    EXPECT_EQ(find_constant(t, "mat3")->register_index, 4);
    EXPECT_EQ(find_constant(t, "vec4")->register_index, 11);
}

// A hand-built table (offsets worked out below) with a struct, an array and default values.
//   header at 0 (28 bytes), 2 constants at 28 (40 bytes), strings and types after; 180 bytes.
std::vector<uint32_t> struct_table() {
    return {
        kFourccCtab,
        28, 0, 0xFFFF0200, 2, 28, 0, 0,   // size, creator none, version, count, info at 28, flags, target none
        // constant 0 at 28: name at 68, Float4 c3 x2, type at 76, default at 144
        68, 0x00030002, 2, 76, 144,
        // constant 1 at 48: name at 72, Bool b1 x1, type at 92, default at 176
        72, 0x00010000, 1, 92, 176,
        0x00006C4C, 0x00006767,  // 68: "Ll", 72: "gg"
        // 76: struct type, 2 elements, 2 members at 108
        0x00000005, 0x00010001, 0x00020002, 108,
        // 92: bool scalar
        0x00010000, 0x00010001, 0x00000001, 0,
        // 108: members: name at 124 type at 128, name at 126 type at 92
        124, 128, 126, 92,
        0x00620061,  // 124: "a", 126: "b"
        // 128: float4 vector
        0x00030001, 0x00040001, 0x00000001, 0,
        // 144: defaults for c3..c4 (8 floats), 176: defaults for b1 (1 DWORD)
        0x3F800000, 0, 0, 0x3F800000, 0x40000000, 0, 0, 0xBF800000, 1};
}

TEST(ConstantTable, StructsArraysAndDefaults) {
    const ConstantTableResult r = parse_constant_table(struct_table());
    ASSERT_TRUE(r.ok()) << r.error;
    const ConstantTable& t = *r.table;
    EXPECT_EQ(t.creator, "");
    ASSERT_EQ(t.constants.size(), 2u);
    const ConstantInfo& s = t.constants[0];
    EXPECT_EQ(s.name, "Ll");
    EXPECT_EQ(constant_type_name(s.type), "struct[2]");
    ASSERT_EQ(s.type.members.size(), 2u);
    EXPECT_EQ(s.type.members[0].name, "a");
    EXPECT_EQ(constant_type_name(s.type.members[0].type), "float4");
    EXPECT_EQ(s.type.members[1].name, "b");
    EXPECT_EQ(constant_type_name(s.type.members[1].type), "bool");
    EXPECT_EQ(s.default_value, (std::vector<uint32_t>{0x3F800000, 0, 0, 0x3F800000, 0x40000000, 0, 0, 0xBF800000}));
    const ConstantInfo& b = t.constants[1];
    EXPECT_EQ(b.register_set, ConstantRegisterSet::Bool);
    EXPECT_STREQ(register_set_prefix(b.register_set), "b");
    EXPECT_EQ(b.default_value, (std::vector<uint32_t>{1}));
}

TEST(ConstantTable, MalformedTablesAreErrors) {
    auto error_of = [](std::vector<uint32_t> payload) {
        const ConstantTableResult r = parse_constant_table(payload);
        EXPECT_FALSE(r.ok());
        return r.error;
    };
    EXPECT_EQ(error_of({}), "the block does not start with 'CTAB'");
    EXPECT_EQ(error_of({0x54584554, 28}), "the block does not start with 'CTAB'");
    EXPECT_EQ(error_of({kFourccCtab, 28}),
              "the CTAB header at byte offset 0x0 (28 bytes) lies outside the 4 bytes after 'CTAB'");

    auto broken = [](size_t word, uint32_t value) {
        std::vector<uint32_t> t = struct_table();
        t[word] = value;
        return t;
    };
    EXPECT_EQ(error_of(broken(1, 32)), "the CTAB header gives its size as 32 bytes, not 28");
    EXPECT_EQ(error_of(broken(2, 0x10000)),
              "the creator string at byte offset 0x10000 (1 bytes) lies outside the 180 bytes after 'CTAB'");
    // An absurd constant count is refused before anything is allocated.
    EXPECT_EQ(error_of(broken(4, 0xFFFFFFFF)), "4294967295 constants cannot fit in the 180 bytes after 'CTAB'");
    EXPECT_EQ(error_of(broken(5, 180)),
              "the constant list at byte offset 0xb4 (40 bytes) lies outside the 180 bytes after 'CTAB'");
    EXPECT_EQ(error_of(broken(9, 0x00030004)), "constant 0 ('Ll') has register set 4 (0..3 exist)");
    EXPECT_EQ(error_of(broken(16, 0x1000)),
              "constant 1 ('gg')'s type at byte offset 0x1000 (16 bytes) lies outside the 180 bytes after 'CTAB'");
    // A member whose type is the struct itself: a cycle, cut at the nesting limit.
    const std::string cycle = error_of(broken(29, 76));
    EXPECT_EQ(cycle.rfind("constant 0 ('Ll').a.a.a", 0), 0u) << cycle;
    EXPECT_NE(cycle.find(": struct members nest more than 16 deep (a cycle?)"), std::string::npos) << cycle;
    // A name running to the end of the block without a NUL.
    std::vector<uint32_t> unterminated = struct_table();
    unterminated[8] = 176;  // constant 0's name: the last word
    unterminated.back() = 0x41414141;
    EXPECT_EQ(error_of(unterminated),
              "constant 0's name at byte offset 0xb0 has no terminating NUL before the end of the block");
    // A default value offset past the end; one that starts inside is cut at the end.
    EXPECT_EQ(error_of(broken(12, 180)),
              "constant 0's default value at byte offset 0xb4 (4 bytes) lies outside the 180 bytes after 'CTAB'");
    const ConstantTableResult cut = parse_constant_table(broken(12, 172));
    ASSERT_TRUE(cut.ok()) << cut.error;
    EXPECT_EQ(cut.table->constants[0].default_value, (std::vector<uint32_t>{0xBF800000, 1}));
}

// serialize_constant_table: one float4 with a default, laid out by hand (offsets from the header,
// which starts after the FOURCC): header 0-27, constant info 28-47, name "k" 48, type info 52-67,
// default 68-83, creator "ab" 84, target "ps_2_0" 88-94, padded to 96 bytes.
TEST(ConstantTableWriter, LayoutOfOneVectorWithADefault) {
    ConstantTable table;
    table.creator = "ab";
    table.version = 0xFFFF0200;
    table.target = "ps_2_0";
    ConstantInfo k;
    k.name = "k";
    k.register_index = 3;
    k.register_count = 1;
    k.type = {parameter_class::Vector, parameter_type::Float, 1, 4, 1, {}};
    k.default_value = {0x3F800000, 0x40000000, 0, 0xBF800000};  // 1, 2, 0, -1
    table.constants.push_back(k);
    const std::vector<uint32_t> expected = {
        kFourccCtab,
        0x1c, 0x54, 0xFFFF0200, 1, 0x1c, 0, 0x58,       // size, creator@84, version, count, info@28, flags, target@88
        0x30, 0x00030002, 0x00000001, 0x34, 0x44,       // name@48, set 2 (c) index 3, count 1, type@52, default@68
        0x0000006b,                                     // "k"
        0x00030001, 0x00040001, 0x00000001, 0,          // vector float, 1 row 4 columns, 1 element, no members
        0x3F800000, 0x40000000, 0, 0xBF800000,          // default
        0x00006261,                                     // "ab"
        0x325f7370, 0x0000305f};                        // "ps_2_0"
    EXPECT_EQ(serialize_constant_table(table), expected);
}

// Structs (members nest), arrays, the bool set and defaults survive a write and a read.
TEST(ConstantTableWriter, ParsedTablesWriteBackToTheSameTable) {
    const ConstantTableResult first = parse_constant_table(struct_table());
    ASSERT_TRUE(first.ok()) << first.error;
    const ConstantTableResult second = parse_constant_table(serialize_constant_table(*first.table));
    ASSERT_TRUE(second.ok()) << second.error;
    const ConstantTable& a = *first.table;
    const ConstantTable& b = *second.table;
    EXPECT_EQ(b.creator, a.creator);
    EXPECT_EQ(b.target, a.target);
    EXPECT_EQ(b.version, a.version);
    ASSERT_EQ(b.constants.size(), a.constants.size());
    for (size_t i = 0; i < a.constants.size(); ++i) {
        EXPECT_EQ(b.constants[i].name, a.constants[i].name);
        EXPECT_EQ(b.constants[i].register_set, a.constants[i].register_set);
        EXPECT_EQ(b.constants[i].register_index, a.constants[i].register_index);
        EXPECT_EQ(b.constants[i].register_count, a.constants[i].register_count);
        EXPECT_EQ(constant_type_name(b.constants[i].type), constant_type_name(a.constants[i].type));
        EXPECT_EQ(b.constants[i].default_value, a.constants[i].default_value);
        ASSERT_EQ(b.constants[i].type.members.size(), a.constants[i].type.members.size());
        for (size_t m = 0; m < a.constants[i].type.members.size(); ++m) {
            EXPECT_EQ(b.constants[i].type.members[m].name, a.constants[i].type.members[m].name);
            EXPECT_EQ(constant_type_name(b.constants[i].type.members[m].type),
                      constant_type_name(a.constants[i].type.members[m].type));
        }
    }
}

}  // namespace
}  // namespace sm2::isa
