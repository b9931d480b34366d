// The constant table (CTAB) that Microsoft's compilers write into a comment block: which
// uniform lives in which register. Layout (D3DXSHADER_CONSTANTTABLE, D3DXSHADER_CONSTANTINFO,
// D3DXSHADER_TYPEINFO, D3DXSHADER_STRUCTMEMBERINFO in d3dx9shader.h) follows the FOURCC 'CTAB',
// the first DWORD of the comment's payload; every offset counts bytes from the header's start.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::isa {

constexpr uint32_t kFourccCtab = 0x42415443;  // 'C' 'T' 'A' 'B', little-endian

// D3DXREGISTER_SET
enum class ConstantRegisterSet : uint16_t { Bool = 0, Int4 = 1, Float4 = 2, Sampler = 3 };

// D3DXPARAMETER_CLASS.
namespace parameter_class {
constexpr uint16_t Scalar = 0, Vector = 1, MatrixRows = 2, MatrixColumns = 3, Object = 4, Struct = 5;
}
// D3DXPARAMETER_TYPE, the values an SM2 constant table uses.
namespace parameter_type {
constexpr uint16_t Void = 0, Bool = 1, Int = 2, Float = 3, Sampler = 10, Sampler1D = 11, Sampler2D = 12,
                   Sampler3D = 13, SamplerCube = 14;
}

struct ConstantMember;

// D3DXSHADER_TYPEINFO with its struct members resolved.
struct ConstantType {
    uint16_t parameter_class = 0;  // D3DXPARAMETER_CLASS: scalar, vector, matrix rows/columns, object, struct
    uint16_t parameter_type = 0;   // D3DXPARAMETER_TYPE: void, bool, int, float, ..., sampler2D, ...
    uint16_t rows = 0;
    uint16_t columns = 0;
    uint16_t elements = 0;         // array length (1 for a non-array)
    std::vector<ConstantMember> members;
};

struct ConstantMember {
    std::string name;
    ConstantType type;
};

// D3DXSHADER_CONSTANTINFO.
struct ConstantInfo {
    std::string name;
    ConstantRegisterSet register_set = ConstantRegisterSet::Float4;
    uint16_t register_index = 0;
    uint16_t register_count = 0;
    ConstantType type;
    std::vector<uint32_t> default_value;  // raw DWORDs (empty: none); see parse_constant_table
};

struct ConstantTable {
    std::string creator;
    uint32_t version = 0;  // the shader version token it was compiled for
    uint32_t flags = 0;
    std::string target;    // "ps_2_0", ...
    std::vector<ConstantInfo> constants;
};

struct ConstantTableResult {
    std::optional<ConstantTable> table;
    std::string error;  // set when table is not: what is out of range, and where
    [[nodiscard]] bool ok() const { return table.has_value(); }
};

// Parses a comment block's payload (the DWORDs after the comment token, FOURCC first).
// Every offset, count and string is bounds-checked against the block; struct types nest at most
// 16 deep and the whole table resolves at most 4096 types, so self-referencing or absurd tables
// are errors, not hangs. Default values are read as 4 DWORDs per register (1 for the bool set),
// cut short at the end of the block.
[[nodiscard]] ConstantTableResult parse_constant_table(std::span<const uint32_t> payload);

// The payload of a CTAB comment block (FOURCC first), laid out as fxc does: header, constant
// infos, then each constant's name, type and default value, then the creator and target strings;
// parse_constant_table reads it back field for field. Default values are written as given.
[[nodiscard]] std::vector<uint32_t> serialize_constant_table(const ConstantTable& table);

// The first comment block of the program whose FOURCC is 'CTAB', parsed; nullopt when there is
// none (a malformed one gives a result with its error).
[[nodiscard]] std::optional<ConstantTableResult> find_constant_table(const Program& program);

// HLSL-like type text: "float4", "float4x4", "sampler2D", "bool", "float3[8]", "struct".
[[nodiscard]] std::string constant_type_name(const ConstantType& type);
// "b", "i", "c", "s": the register letter of a set.
[[nodiscard]] const char* register_set_prefix(ConstantRegisterSet set);
// The constant of the given name (exact, case-sensitive as in HLSL); nullptr if absent.
[[nodiscard]] const ConstantInfo* find_constant(const ConstantTable& table, std::string_view name);

}  // namespace sm2::isa
