// SPIR-V -> SM2 assembly. Every SSA value lives in a vec4 register (a temp, an input, a uniform or
// a `def` literal) seen through a swizzle and an optional negation, so extracts, shuffles and
// negations cost no instruction. Temps are allocated when a value is defined and freed after its
// last use; a temp is never reused within the instruction that frees it, so multi-instruction
// sequences (and nrm/pow/crs, whose dest may not be a source) are safe. vs_2_0's static flow
// control follows the structured SPIR-V in block order (analyze_flow): a phi is a temp written by
// a mov on each incoming edge, and values a loop reads stay live to its back edge.
#include "backend.h"

#include "sm2/isa/constant_table.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace sm2::hlsl {

namespace {

// SPIR-V numbers used below (SPIR-V specification, §3).
namespace op {
constexpr uint32_t Undef = 1, Name = 5, MemberName = 6, String = 7, Line = 8, ExtInst = 12, EntryPoint = 15, TypeVoid = 19,
                   TypeBool = 20, TypeInt = 21, TypeFloat = 22, TypeVector = 23, TypeMatrix = 24,
                   TypeImage = 25, TypeSampledImage = 27, TypeArray = 28, TypeStruct = 30, TypePointer = 32,
                   ConstantTrue = 41, ConstantFalse = 42, Constant = 43, ConstantComposite = 44,
                   ConstantNull = 46, Function = 54, FunctionEnd = 56, Variable = 59, Load = 61, Store = 62,
                   AccessChain = 65, InBoundsAccessChain = 66, Decorate = 71, MemberDecorate = 72,
                   VectorShuffle = 79, CompositeConstruct = 80, CompositeExtract = 81, CompositeInsert = 82, CopyObject = 83,
                   Transpose = 84, ImageSampleImplicitLod = 87, ImageSampleExplicitLod = 88,
                   ConvertSToF = 111, ConvertUToF = 112, ImageSampleProjImplicitLod = 91,
                   FNegate = 127, FAdd = 129, FSub = 131, FMul = 133, FDiv = 136, VectorTimesScalar = 142,
                   VectorTimesMatrix = 144, MatrixTimesVector = 145, Dot = 148, LogicalNot = 168,
                   Select = 169, FOrdEqual = 180, FUnordGreaterThanEqual = 191, Label = 248, Return = 253, SelectionMerge = 247, LoopMerge = 246, Branch = 249,
                   BranchConditional = 250, Kill = 252, Any = 154, Phi = 245, IAdd = 128, IEqual = 170, INotEqual = 171,
                   SGreaterThan = 173, SLessThan = 177,
                   NoLine = 317, DecorateString = 5632;
}  // namespace op
namespace decoration {
constexpr uint32_t RowMajor = 4, BuiltIn = 11, Binding = 33, UserSemantic = 5635;
}
namespace glsl {  // GLSL.std.450
constexpr uint32_t FAbs = 4, Floor = 8, Fract = 10, Sin = 13, Cos = 14, Pow = 26, Exp = 27, Log = 28, Exp2 = 29,
                   Log2 = 30, Sqrt = 31, InverseSqrt = 32, FMin = 37, FMax = 40, FClamp = 43, FMix = 46,
                   Step = 48, Fma = 50, Length = 66, Distance = 67, Cross = 68, Normalize = 69, Reflect = 71;
}
constexpr uint32_t kStorageUniformConstant = 0, kStorageInput = 1, kStorageUniform = 2, kStorageOutput = 3;
constexpr uint32_t kBuiltInPosition = 0;
constexpr int kTempCount = 12;  // r0-r11 in both vs_2_0 and ps_2_0
constexpr const char* kCreator = "sm2emu sm2 compile (glslang HLSL, SPIRV-Tools, sm2 back end)";


struct SpirvInstruction {
    uint32_t opcode = 0;
    std::vector<uint32_t> words;  // operands, without the opcode word
    isa::SourceLocation location;  // the OpLine in effect
    uint32_t file = 0;             // its OpString (0: none)
};

// A SPIR-V type, reduced to what the back end needs.
struct Type {
    uint32_t opcode = 0;
    uint32_t component_count = 1;  // vector size; matrix column count; array length
    uint32_t element = 0;          // vector: scalar type; matrix: column type; array/pointer: element
    uint32_t storage = 0;          // pointer storage class
    uint32_t image_dim = 0;        // sampled image: the image's Dim
    std::vector<uint32_t> members;  // struct
};

// How a value is held. `swizzle[p]` is the register component that dest component p reads (for a
// scalar, [0] is broadcast).
struct Value {
    enum class Kind { None, Register, Matrix, Sampler, Condition, Pointer } kind = Kind::None;
    char file = 'r';  // r, c, v, t
    int index = 0;
    std::array<uint8_t, 4> swizzle{0, 1, 2, 3};
    uint32_t count = 4;
    bool negate = false;
    // Matrix in constant registers: `vectors` registers from `index`, each one SPIR-V column when
    // `registers_are_columns`, else one row; `columns` x `rows` in SPIR-V terms.
    uint32_t columns = 0, rows = 0;
    bool registers_are_columns = true;
    // Sampler: s# and dcl type; Condition: comparison opcode and operand ids (negated by `negate`).
    int sampler = 0;
    uint32_t compare = 0, lhs = 0, rhs = 0;
    // Pointer: the variable, its storage class and the constant register reached so far.
    uint32_t variable = 0, pointee = 0, storage = 0;
    bool any = false;        // Condition: any() of a vector comparison (clip's test; only a kill reads it)
    bool row_major = false;  // Pointer into a RowMajor-decorated member
    int component = -1;      // Pointer to one component of a vector
    uint32_t dynamic_index = 0;  // Pointer into a uniform array at a run-time index (vs_2_0: the loop counter)
    int dynamic_stride = 0;      // registers per element of that array
};

struct CompileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Value component_view(const Value& v, uint32_t component) {
    if (component >= 4) throw CompileError("a vector component past .w (or an undefined shuffle component)");
    Value out = v;
    out.count = 1;
    out.swizzle = {v.swizzle[component], 0, 0, 0};
    return out;
}

std::string format_float(float f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(f));
    std::string text = buf;
    if (text.find_first_of("eni") != std::string::npos) {  // exponent, inf, nan: the raw bits
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        std::snprintf(buf, sizeof buf, "0x%08X", bits);
        text = buf;
    }
    return text;
}

const char* kComponents = "xyzw";

// The semantic name split into letters and index: "TEXCOORD3" -> ("TEXCOORD", 3).
std::pair<std::string, int> split_semantic(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); });
    size_t digits = s.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(s[digits - 1]))) --digits;
    int index = 0;
    if (digits < s.size() && s.size() - digits <= 3) index = std::stoi(s.substr(digits));
    s.resize(digits);
    if (s.rfind("SV_", 0) == 0) s = s.substr(3);
    return {s, index};
}

class Backend {
public:
    Backend(const std::vector<uint32_t>& spirv, std::string_view source, const CompileOptions& options)
        : spirv_(spirv), source_(source), options_(options), pixel_(options.stage == isa::ShaderType::Pixel) {}

    AssemblyOutput run() {
        AssemblyOutput out;
        try {
            parse();
            generate();
            finish(out);
        } catch (const CompileError& e) {
            fail(out, e.what());
        } catch (const std::exception& e) {  // a SPIR-V shape this back end did not expect
            fail(out, std::string("internal error: unsupported SPIR-V (") + e.what() + ")");
        }
        return out;
    }

private:
    void fail(AssemblyOutput& out, const std::string& message) const {
        out.text.clear();
        out.origin.clear();
        out.line_origin.clear();
        out.line_file.clear();
        out.diagnostics.push_back({assembler::Severity::Error, options_.file_name, location_.line, location_.column, message});
    }

    // ---- reading the module -------------------------------------------------------------------
    void parse() {
        if (spirv_.size() < 5) throw CompileError("internal error: empty SPIR-V module");
        entry_location_ = find_entry_location();
        location_ = entry_location_;
        isa::SourceLocation line;
        uint32_t file = 0;
        bool in_function = false;
        for (size_t i = 5; i < spirv_.size();) {
            const uint32_t count = spirv_[i] >> 16, opcode = spirv_[i] & 0xFFFF;
            if (count == 0 || i + count > spirv_.size()) throw CompileError("internal error: malformed SPIR-V");
            SpirvInstruction ins{opcode, {spirv_.begin() + static_cast<long>(i) + 1, spirv_.begin() + static_cast<long>(i + count)}, line, file};
            i += count;
            switch (opcode) {
            case op::Line:
                if (ins.words.size() >= 3 && ins.words[1] > 0) {
                    line = {ins.words[1], std::max<uint32_t>(ins.words[2], 1)};
                    file = ins.words[0];
                }
                continue;
            case op::String:
                if (ins.words.size() >= 2) strings_[ins.words[0]] = literal_string(ins.words, 1);
                continue;
            case op::NoLine: continue;
            case op::EntryPoint:
                entry_function_ = ins.words.at(1);
                // The interface ids follow the name, a nul-terminated string padded to whole words
                // ("vmain": two words; the old test for a word of zero low and high bytes only
                // found the end of names whose length is a multiple of 4, like "main").
                if (ins.words.size() > 2) {
                    const size_t k = 2 + literal_string(ins.words, 2).size() / 4 + 1;
                    if (k <= ins.words.size()) interface_.assign(ins.words.begin() + static_cast<long>(k), ins.words.end());
                }
                break;
            case op::Decorate:
                if (ins.words.size() >= 3) decorations_[ins.words[0]][ins.words[1]] = ins.words[2];
                else if (ins.words.size() == 2) decorations_[ins.words[0]][ins.words[1]] = 1;
                break;
            case op::DecorateString:
                if (ins.words.size() >= 3 && ins.words[1] == decoration::UserSemantic)
                    semantics_[ins.words[0]] = literal_string(ins.words, 2);
                break;
            case op::MemberDecorate:
                if (ins.words.size() >= 3) member_decorations_[ins.words[0]][ins.words[1]].insert(ins.words[2]);
                break;
            case op::Name:
                if (ins.words.size() >= 2) names_[ins.words[0]] = literal_string(ins.words, 1);
                break;
            case op::MemberName:
                if (ins.words.size() >= 3) member_names_[{ins.words[0], ins.words[1]}] = literal_string(ins.words, 2);
                break;
            case op::Function: in_function = ins.words.at(1) == entry_function_ || in_function; break;
            case op::FunctionEnd: in_function = false; break;
            default: break;
            }
            if (opcode >= op::TypeVoid && opcode <= op::TypePointer) read_type(ins);
            if (opcode == op::Constant || opcode == op::ConstantComposite || opcode == op::ConstantNull ||
                opcode == op::ConstantTrue || opcode == op::ConstantFalse || opcode == op::Undef)
                constants_[ins.words.at(1)] = ins;
            if (opcode == op::Variable) variables_[ins.words.at(1)] = {ins.words.at(0), ins.words.at(2)};
            if (in_function && opcode != op::Function) body_.push_back(std::move(ins));
        }
        if (body_.empty()) throw CompileError("entry point '" + options_.entry_point + "' has no body");
    }

    static std::string literal_string(const std::vector<uint32_t>& words, size_t from) {
        std::string s;
        for (size_t k = from; k < words.size(); ++k)
            for (int b = 0; b < 4; ++b) {
                const char c = static_cast<char>((words[k] >> (8 * b)) & 0xFF);
                if (c == 0) return s;
                s += c;
            }
        return s;
    }

    void read_type(const SpirvInstruction& ins) {
        Type t;
        t.opcode = ins.opcode;
        const auto& w = ins.words;
        switch (ins.opcode) {
        case op::TypeVector:
        case op::TypeMatrix: t.element = w.at(1); t.component_count = w.at(2); break;
        case op::TypeArray: t.element = w.at(1); t.component_count = constant_int(w.at(2)); break;
        case op::TypePointer: t.storage = w.at(1); t.element = w.at(2); break;
        case op::TypeStruct: t.members.assign(w.begin() + 1, w.end()); break;
        case op::TypeImage: t.image_dim = w.at(2); break;
        case op::TypeSampledImage: t.image_dim = types_.at(w.at(1)).image_dim; break;
        default: break;
        }
        types_[w.at(0)] = t;
    }

    uint32_t constant_int(uint32_t id) const {
        auto it = constants_.find(id);
        if (it == constants_.end() || it->second.opcode != op::Constant)
            throw CompileError("an index that is not a compile-time constant (SM2 has no indexing by run-time values here)");
        return it->second.words.at(2);
    }

    // Where `main(` (the entry point) is written, for errors about the whole program.
    isa::SourceLocation find_entry_location() const {
        const std::string name = options_.entry_point;
        size_t pos = 0;
        while ((pos = source_.find(name, pos)) != std::string_view::npos) {
            size_t after = pos + name.size();
            while (after < source_.size() && (source_[after] == ' ' || source_[after] == '\t')) ++after;
            const bool word_start = pos == 0 || !(std::isalnum(static_cast<unsigned char>(source_[pos - 1])) || source_[pos - 1] == '_');
            if (word_start && after < source_.size() && source_[after] == '(') {
                uint32_t line = 1, column = 1;
                for (size_t k = 0; k < pos; ++k) {
                    if (source_[k] == '\n') { ++line; column = 1; } else { ++column; }
                }
                return {line, column};
            }
            pos = after;
        }
        return {1, 1};
    }

    uint32_t type_of_value_components(uint32_t type_id) const {
        const Type& t = types_.at(type_id);
        if (t.opcode == op::TypeVector) return t.component_count;
        if (t.opcode == op::TypeFloat || t.opcode == op::TypeBool || t.opcode == op::TypeInt) return 1;
        throw CompileError("a value of a type SM2 registers cannot hold here (struct, array or matrix expression)");
    }

    // Constant registers per value of this type, HLSL/D3D9 style: one per vector, one per matrix
    // register vector, arrays element by element.
    uint32_t register_size(uint32_t type_id, bool row_major) const {
        const Type& t = types_.at(type_id);
        switch (t.opcode) {
        case op::TypeMatrix: return row_major ? types_.at(t.element).component_count : t.component_count;
        case op::TypeArray: return t.component_count * register_size(t.element, row_major);
        case op::TypeStruct: {
            uint32_t n = 0;
            for (uint32_t m : t.members) n += register_size(m, false);
            return n;
        }
        default: return 1;
        }
    }

    // ---- registers ------------------------------------------------------------------------------
    int allocate_temp() {
        // In ps_2_0 the free temp of the lowest dependent-read level is taken, one never written
        // first: the rule counts a texld into a temp written earlier, and a partial write (a
        // coordinate's .xy) into one that held a texture result, as one level deeper (isa
        // validator, rule 17), so reusing the lowest free temp made independent reads look like
        // a chain (scene 16's four noise reads, scene 20's twelve blur taps).
        if (pixel_) {
            int best = -1, best_key = 0;
            for (int r = 0; r < kTempCount; ++r) {
                if (temp_busy_[static_cast<size_t>(r)]) continue;
                const int key = temp_written_[static_cast<size_t>(r)] ? texture_level_[static_cast<size_t>(r)] : -2;
                if (best < 0 || key < best_key) { best = r; best_key = key; }
            }
            if (best >= 0) {
                temp_busy_[static_cast<size_t>(best)] = true;
                temp_holders_[best] = 0;
                max_temp_ = std::max(max_temp_, best + 1);
                return best;
            }
        }
        for (int r = 0; r < kTempCount; ++r)
            if (!temp_busy_[static_cast<size_t>(r)]) {
                temp_busy_[static_cast<size_t>(r)] = true;
                temp_holders_[r] = 0;
                max_temp_ = std::max(max_temp_, r + 1);
                return r;
            }
        throw CompileError("the shader needs more than the " + std::to_string(kTempCount) + " temporary registers r0-r" +
                           std::to_string(kTempCount - 1) + " of " + profile() + " at this point");
    }
    Value new_temp(uint32_t count) {
        Value v;
        v.kind = Value::Kind::Register;
        v.file = 'r';
        v.index = allocate_temp();
        v.count = count;
        scratch_.push_back(v.index);
        return v;
    }
    std::string profile() const { return pixel_ ? "ps_2_0" : "vs_2_0"; }

    // A literal in a `def` register: scalars share registers, four to a register.
    Value literal(float f) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        for (size_t r = 0; r < defs_.size(); ++r)
            for (uint32_t k = 0; k < def_used_[r]; ++k)
                if (std::memcmp(&defs_[r][k], &f, 4) == 0 && def_scalar_[r]) return def_view(r, k);
        if (defs_.empty() || !def_scalar_.back() || def_used_.back() == 4) {
            defs_.push_back({0, 0, 0, 0});
            def_used_.push_back(0);
            def_scalar_.push_back(true);
        }
        const size_t r = defs_.size() - 1;
        defs_[r][def_used_[r]] = f;
        return def_view(r, def_used_[r]++);
    }
    Value literal_vector(const std::array<float, 4>& values, uint32_t count) {
        for (size_t r = 0; r < defs_.size(); ++r)
            if (!def_scalar_[r] && std::memcmp(defs_[r].data(), values.data(), 16) == 0) return def_register(r, count);
        defs_.push_back(values);
        def_used_.push_back(4);
        def_scalar_.push_back(false);
        return def_register(defs_.size() - 1, count);
    }
    Value def_view(size_t r, uint32_t k) {
        Value v = def_register(r, 1);
        v.swizzle = {static_cast<uint8_t>(k), 0, 0, 0};
        return v;
    }
    Value def_register(size_t r, uint32_t count) {
        Value v;
        v.kind = Value::Kind::Register;
        v.file = 'c';
        v.index = static_cast<int>(first_def_register_ + r);
        v.count = count;
        return v;
    }

    // ---- emitting -------------------------------------------------------------------------------
    void line(const std::string& text) {
        code_.push_back(text);
        code_origin_.push_back(location_);
        code_line_.push_back({line_location_, location_file_});
        if (pixel_) track_texture_level(text);
    }

    // ps_2_0's dependent-read levels of the temps, as the validator counts them (rule 17): a
    // texld's result is one level above its coordinate and above what its destination held; an
    // arithmetic result takes its sources' highest level (a partial write keeps the old one too).
    // Temps are allocated by these levels (allocate_temp), so a read's destination or coordinate
    // is never a temp that would make an independent read look like a chain.
    static int temp_in(std::string_view token) {
        if (!token.empty() && token[0] == '-') token.remove_prefix(1);
        if (token.size() < 2 || token[0] != 'r' || !std::isdigit(static_cast<unsigned char>(token[1]))) return -1;
        return std::atoi(std::string(token.substr(1)).c_str());
    }
    void track_texture_level(const std::string& text) {
        const size_t space = text.find(' ');
        if (space == std::string::npos) return;
        const std::string mnemonic = text.substr(0, text.find_first_of("_ "));
        std::vector<std::string> operands;
        std::stringstream list(text.substr(space + 1));
        for (std::string item; std::getline(list, item, ',');) {
            const size_t first = item.find_first_not_of(' ');
            operands.push_back(first == std::string::npos ? "" : item.substr(first));
        }
        if (operands.empty() || mnemonic == "texkill") return;
        const int d = temp_in(operands[0]);
        if (d < 0 || d >= kTempCount) return;
        const auto D = static_cast<size_t>(d);
        if (mnemonic.rfind("texld", 0) == 0) {
            int order = 0;
            if (operands.size() > 1)
                if (const int c = temp_in(operands[1]); c >= 0 && c < kTempCount)
                    order = std::max(1, texture_level_[static_cast<size_t>(c)] + 1);
            if (temp_written_[D]) order = std::max(order, std::max(1, texture_level_[D] + 1));
            texture_level_[D] = order;
        } else {
            int from = -1;
            for (size_t k = 1; k < operands.size(); ++k)
                if (const int r = temp_in(operands[k]); r >= 0 && r < kTempCount)
                    from = std::max(from, texture_level_[static_cast<size_t>(r)]);
            const bool full = operands[0].find('.') == std::string::npos;
            texture_level_[D] = full ? from : std::max(texture_level_[D], from);
        }
        temp_written_[D] = true;
    }

    static bool swizzle_allowed_in_ps(const std::array<uint8_t, 4>& s) {
        static constexpr std::array<std::array<uint8_t, 4>, 4> kList = {
            {{0, 1, 2, 3}, {1, 2, 0, 3}, {2, 0, 1, 3}, {3, 2, 1, 0}}};
        if (s[0] == s[1] && s[1] == s[2] && s[2] == s[3]) return true;
        return std::find(kList.begin(), kList.end(), s) != kList.end();
    }

    // The swizzle `v` needs under write mask `mask`; components outside the mask are chosen so
    // that ps_2_0's short list can match. nullopt: ps_2_0 cannot express it.
    std::optional<std::array<uint8_t, 4>> source_swizzle(const Value& v, uint8_t mask) const {
        std::array<int, 4> need{-1, -1, -1, -1};
        for (int p = 0; p < 4; ++p)
            if (mask & (1 << p)) need[static_cast<size_t>(p)] = v.count == 1 ? v.swizzle[0] : v.swizzle[static_cast<size_t>(p)];
        // Identity first, then replicates (what one component reads best as), then the rotations.
        std::vector<std::array<uint8_t, 4>> candidates = {{0, 1, 2, 3}};
        for (uint8_t c = 0; c < 4; ++c) candidates.push_back({c, c, c, c});
        candidates.insert(candidates.end(), {{1, 2, 0, 3}, {2, 0, 1, 3}, {3, 2, 1, 0}});
        for (const auto& c : candidates) {
            bool fits = true;
            for (size_t p = 0; p < 4; ++p) fits = fits && (need[p] < 0 || need[p] == c[p]);
            if (fits) return c;
        }
        if (pixel_) return std::nullopt;
        std::array<uint8_t, 4> s{};
        int last = 0;
        for (size_t p = 0; p < 4; ++p) {  // vs: anything; fill the rest with the last component used
            if (need[p] >= 0) last = need[p];
            s[p] = static_cast<uint8_t>(need[p] >= 0 ? need[p] : last);
        }
        return s;
    }

    std::string register_name(const Value& v) const { return std::string(1, v.file) + std::to_string(v.index); }

    std::string source_text(const Value& v, const std::array<uint8_t, 4>& s) const {
        std::string text = (v.negate ? "-" : "") + register_name(v);
        if (s != std::array<uint8_t, 4>{0, 1, 2, 3}) {
            text += '.';
            if (s[0] == s[1] && s[1] == s[2] && s[2] == s[3]) {
                text += kComponents[s[0]];
            } else {
                for (uint8_t c : s) text += kComponents[c];
            }
        }
        return text;
    }

    static std::string mask_text(uint8_t mask) {
        if (mask == 0xF) return "";
        std::string text = ".";
        for (int p = 0; p < 4; ++p)
            if (mask & (1 << p)) text += kComponents[p];
        return text;
    }

    // `v` copied into a fresh temp so that its components sit where `mask` reads them, one mov per
    // component when ps_2_0's swizzle list is the obstacle.
    Value materialize(const Value& v, uint8_t mask) {
        Value t = new_temp(4);
        t.count = v.count == 1 ? 1 : 4;
        const uint8_t write = v.count == 1 ? 1 : mask;
        if (auto s = source_swizzle(v, write)) {
            line("mov r" + std::to_string(t.index) + mask_text(write) + ", " + source_text(v, *s));
        } else {
            for (int p = 0; p < 4; ++p)
                if (write & (1 << p)) {
                    const uint8_t c = v.swizzle[static_cast<size_t>(p)];
                    line("mov r" + std::to_string(t.index) + mask_text(static_cast<uint8_t>(1 << p)) + ", " +
                         source_text(v, {c, c, c, c}));
                }
        }
        if (v.count == 1) t.swizzle = {0, 0, 0, 0};
        return t;
    }

    // One instruction: `dest` with `mask`; sources legalized for swizzles and read ports.
    void emit(const std::string& mnemonic, const std::string& dest, uint8_t mask, std::vector<Value> sources,
              bool identity_sources = false) {
        // Dot products and the vector macros read their sources' components whatever the mask.
        const uint8_t read_mask = mnemonic == "dp4" ? 0xF
                                  : (mnemonic == "dp3" || mnemonic == "nrm" || mnemonic == "crs") ? 0x7
                                                                                                  : mask;
        // Read ports: at most 2 distinct c#, 1 v#, 1 t# per instruction (a source moved to a temp
        // keeps every component the instruction reads: dp3 t0, t1 reads .xyz of both).
        std::map<char, std::set<int>> seen;
        for (auto& s : sources) {
            if (s.file == 'r') continue;
            auto& set = seen[s.file];
            set.insert(s.index);
            const size_t limit = s.file == 'c' ? 2 : 1;
            if (set.size() > limit) {
                set.erase(s.index);
                s = materialize(s, read_mask);
            }
        }
        std::string text = mnemonic + " " + dest + mask_text(mask);
        // Scalar instructions read one component, named by a replicate swizzle.
        const bool scalar = mnemonic == "rcp" || mnemonic == "rsq" || mnemonic == "exp" || mnemonic == "log" ||
                            mnemonic == "pow";
        for (auto& s : sources) {
            auto swizzle = source_swizzle(s, read_mask);
            if (scalar) {
                int p = 0;
                while (p < 3 && !(mask & (1 << p))) ++p;
                const uint8_t c = s.count == 1 ? s.swizzle[0] : s.swizzle[static_cast<size_t>(p)];
                swizzle = std::array<uint8_t, 4>{c, c, c, c};
            }
            if (!swizzle || (identity_sources && *swizzle != std::array<uint8_t, 4>{0, 1, 2, 3})) {
                s = materialize(s, read_mask);
                swizzle = source_swizzle(s, read_mask);
            }
            text += ", " + source_text(s, *swizzle);
        }
        line(text);
    }

    static uint8_t mask_of(uint32_t count) { return static_cast<uint8_t>((1u << count) - 1); }
    static std::string temp_name(const Value& v) { return "r" + std::to_string(v.index); }

    // ---- the function body ----------------------------------------------------------------------
    Value& value(uint32_t id) {
        auto it = values_.find(id);
        if (it != values_.end()) return it->second;
        auto c = constants_.find(id);
        if (c == constants_.end()) throw CompileError("internal error: SPIR-V id " + std::to_string(id) + " has no value");
        values_[id] = constant_value(c->second);
        return values_[id];
    }

    Value constant_value(const SpirvInstruction& c) {
        const uint32_t type = c.words.at(0);
        const Type& t = types_.at(type);
        auto scalar_of = [&](uint32_t id) -> float {
            const SpirvInstruction& s = constants_.at(id);
            if (s.opcode != op::Constant) return 0.0f;
            if (types_.at(s.words.at(0)).opcode == op::TypeInt) return static_cast<float>(static_cast<int32_t>(s.words.at(2)));
            float f;
            std::memcpy(&f, &s.words.at(2), 4);
            return f;
        };
        if (t.opcode == op::TypeVector) {
            std::array<float, 4> values{};
            if (c.opcode == op::ConstantComposite)
                for (uint32_t k = 0; k < t.component_count && k + 2 < c.words.size(); ++k) values[k] = scalar_of(c.words[k + 2]);
            // A splat reads better (and shares a register) as a scalar, replicated by the swizzle.
            if (std::all_of(values.begin(), values.begin() + t.component_count, [&](float x) { return std::memcmp(&x, &values[0], 4) == 0; })) {
                Value splat = literal(values[0]);
                splat.swizzle.fill(splat.swizzle[0]);
                splat.count = t.component_count;
                return splat;
            }
            return literal_vector(values, t.component_count);
        }
        if (t.opcode == op::TypeBool) {
            Value v;
            v.kind = Value::Kind::Condition;
            v.compare = c.opcode == op::ConstantTrue ? 1 : 0;
            return v;
        }
        if (t.opcode == op::TypeFloat || t.opcode == op::TypeInt) return literal(c.opcode == op::Constant ? scalar_of(c.words.at(1)) : 0.0f);
        throw CompileError("a constant of a type SM2 registers cannot hold (struct, array or matrix)");
    }

    Value as_register(uint32_t id) {
        Value v = value(id);
        if (v.kind != Value::Kind::Register) throw CompileError("internal error: expected a register value");
        return v;
    }

    void define(uint32_t id, Value v) {
        if (v.kind == Value::Kind::Register && v.file == 'r') {
            ++temp_holders_[v.index];
            scratch_.erase(std::remove(scratch_.begin(), scratch_.end(), v.index), scratch_.end());
        }
        values_[id] = v;
    }

    // `id` is read again at `later` (a mul folded into an add, a comparison's operands read by the
    // select): its last use moves there, and it is released there with the instruction's own operands.
    void extend_last_use(uint32_t id, size_t later) {
        size_t& last = last_use_[id];
        if (later <= last) return;
        last = later;
        released_also_at_[later].push_back(id);
    }

    // Temps no value holds any more go back to the pool after each SPIR-V instruction.
    void release_after(size_t position, std::vector<uint32_t> used) {
        if (auto also = released_also_at_.find(position); also != released_also_at_.end())
            used.insert(used.end(), also->second.begin(), also->second.end());
        std::sort(used.begin(), used.end());
        used.erase(std::unique(used.begin(), used.end()), used.end());  // float4(x, x, x, x) holds x once
        for (uint32_t id : used) {
            auto it = last_use_.find(id);
            if (it == last_use_.end() || it->second != position) continue;
            auto v = values_.find(id);
            if (v != values_.end() && v->second.kind == Value::Kind::Register && v->second.file == 'r')
                if (--temp_holders_[v->second.index] == 0) temp_busy_[static_cast<size_t>(v->second.index)] = false;
        }
        for (int r : scratch_) temp_busy_[static_cast<size_t>(r)] = false;
        scratch_.clear();
    }

    // Ids an instruction reads (all operand words that name values); over-approximate is fine.
    std::vector<uint32_t> operand_ids(const SpirvInstruction& ins) const {
        std::vector<uint32_t> ids;
        size_t first = 2;  // result type, result id
        if (ins.opcode == op::Phi) return ids;  // counted at the predecessors' branches (incoming_uses_)
        if (ins.opcode == op::Store) first = 0;
        if (ins.opcode == op::ExtInst) first = 4;
        for (size_t k = first; k < ins.words.size(); ++k) ids.push_back(ins.words[k]);
        if (ins.opcode == op::VectorShuffle) ids.resize(std::min<size_t>(ids.size(), 2));
        if (ins.opcode == op::CompositeExtract) ids.resize(std::min<size_t>(ids.size(), 1));
        if (ins.opcode == op::CompositeInsert) ids.resize(std::min<size_t>(ids.size(), 2));
        return ids;
    }

    void generate() {
        // Blocks, uses, and the branches and loops that become if b# / rep i# (vs_2_0).
        analyze_flow();
        // Uniform registers: the $Global members at their register(cN) or in declaration order, then the literals.
        assign_uniform_registers();
        // Last uses, with a mul folded into the add that is its only user (mad) counted at the add.
        std::unordered_map<uint32_t, int> use_count;
        std::unordered_map<uint32_t, size_t> definition;
        for (size_t i = 0; i < body_.size(); ++i) {
            for (uint32_t id : operand_ids(body_[i])) {
                last_use_[id] = i;
                ++use_count[id];
            }
            for (uint32_t id : incoming_uses_[i]) {  // phi operands, moved at the predecessor's branch
                last_use_[id] = std::max(last_use_[id], i);
                ++use_count[id];
            }
            if (body_[i].words.size() >= 2) definition[body_[i].words[1]] = i;
        }
        for (size_t i = 0; i < body_.size(); ++i) {
            const auto& ins = body_[i];
            if ((ins.opcode != op::FAdd && ins.opcode != op::FSub) || ins.words.size() < 4) continue;
            for (int k = 2; k < 4; ++k) {
                const uint32_t id = ins.words[static_cast<size_t>(k)];
                auto d = definition.find(id);
                if (d == definition.end() || use_count[id] != 1 || block_of_[d->second] != block_of_[i]) continue;
                const auto& m = body_[d->second];
                if (m.opcode != op::FMul && m.opcode != op::VectorTimesScalar) continue;
                if (fused_.count(id) || fused_.count(m.words[2]) || fused_.count(m.words[3])) continue;
                fused_.insert(id);
                for (int j = 2; j < 4; ++j) extend_last_use(m.words[static_cast<size_t>(j)], i);
                break;
            }
        }
        extend_live_ranges_over_loops();
        // For the line table: the line of each value's definition. glslang's entry-point wrapper
        // stores the outputs with the line of the function's opening brace; such a store is
        // given the line of the value stored (the `return` expression's), when that has one.
        std::unordered_map<uint32_t, std::pair<isa::SourceLocation, uint32_t>> value_line;
        for (size_t i = 0; i < body_.size(); ++i) {
            const auto& ins = body_[i];
            location_ = ins.location.line ? ins.location : entry_location_;
            position_ = i;
            if (ins.location.line) {  // else the line table keeps the last known line (the optimizer dropped it)
                line_location_ = ins.location;
                location_file_ = ins.file;
                if (ins.opcode != op::Store && ins.words.size() >= 2) value_line.emplace(ins.words[1], std::pair{ins.location, ins.file});
            }
            if (ins.opcode == op::Store && ins.words.size() >= 2) {
                auto var = variables_.find(ins.words[0]);
                auto defined = value_line.find(ins.words[1]);
                if (var != variables_.end() && var->second.second == kStorageOutput && defined != value_line.end()) {
                    line_location_ = defined->second.first;
                    location_file_ = defined->second.second;
                }
            }
            if (!skip_.count(i)) translate(ins);
            if (has_result_id(ins.opcode) && ins.words.size() >= 2) code_after_[ins.words[1]] = code_.size();
            std::vector<uint32_t> used = operand_ids(ins);
            used.insert(used.end(), incoming_uses_[i].begin(), incoming_uses_[i].end());
            release_after(i, used);
            if (ins.words.size() >= 2 && !last_use_.count(ins.words[1])) {
                auto v = values_.find(ins.words[1]);
                if (v != values_.end() && v->second.kind == Value::Kind::Register && v->second.file == 'r' &&
                    --temp_holders_[v->second.index] == 0)
                    temp_busy_[static_cast<size_t>(v->second.index)] = false;
            }
        }
        location_ = entry_location_;
    }

    // ---- static flow control (vs_2_0): if b#, rep i# ------------------------------------------
    struct FlowBool {
        std::pair<uint32_t, uint32_t> member;  // ($Global struct type, member index)
        bool negate = false;
        std::vector<size_t> positions;  // the instructions that compute the condition (not translated)
    };
    struct Loop {
        std::pair<uint32_t, uint32_t> member;  // the uniform int counted by rep
        uint32_t merge = 0, header = 0;
        size_t back_edge = 0;  // the continue block's branch to the header
        int constant_count = -1;  // a [loop] with a literal count: rep on a `defi` register instead
        uint32_t counter = 0;     // the counter's id when the body reads it: a float temp counts along
    };
    struct Construct {
        bool loop = false;
        uint32_t merge = 0, else_label = 0, header = 0;
    };

    static bool has_result_id(uint32_t opcode) {
        return opcode != op::Store && opcode != op::Branch && opcode != op::BranchConditional &&
               opcode != op::SelectionMerge && opcode != op::LoopMerge && opcode != op::Label &&
               opcode != op::Return && opcode != op::FunctionEnd && opcode != op::Kill;
    }

    bool is_integer_constant(uint32_t id, uint32_t value) const {
        auto c = constants_.find(id);
        if (c == constants_.end() || types_.at(c->second.words.at(0)).opcode != op::TypeInt) return false;
        if (c->second.opcode == op::ConstantNull) return value == 0;
        return c->second.opcode == op::Constant && c->second.words.at(2) == value;
    }

    // `id` = OpLoad of one scalar integer member of the $Global block: (struct type, member), and
    // the positions of the load and its access chain.
    std::optional<std::pair<std::pair<uint32_t, uint32_t>, std::vector<size_t>>> uniform_integer_load(uint32_t id) const {
        auto d = defined_at_.find(id);
        if (d == defined_at_.end() || body_[d->second].opcode != op::Load) return std::nullopt;
        const auto& load = body_[d->second];
        if (types_.at(load.words.at(0)).opcode != op::TypeInt) return std::nullopt;
        auto a = defined_at_.find(load.words.at(2));
        if (a == defined_at_.end()) return std::nullopt;
        const auto& chain = body_[a->second];
        if ((chain.opcode != op::AccessChain && chain.opcode != op::InBoundsAccessChain) || chain.words.size() != 4)
            return std::nullopt;
        auto var = variables_.find(chain.words[2]);
        if (var == variables_.end() || var->second.second != kStorageUniform) return std::nullopt;
        const uint32_t block = types_.at(var->second.first).element;
        auto index = constants_.find(chain.words[3]);
        if (types_.at(block).opcode != op::TypeStruct || index == constants_.end() || index->second.opcode != op::Constant)
            return std::nullopt;
        return std::make_pair(std::make_pair(block, index->second.words.at(2)), std::vector<size_t>{d->second, a->second});
    }

    // A condition that is a uniform `bool` (glslang: uint != 0), possibly negated.
    std::optional<FlowBool> uniform_bool_condition(uint32_t id) const {
        auto d = defined_at_.find(id);
        if (d == defined_at_.end()) return std::nullopt;
        const auto& ins = body_[d->second];
        const bool splat = ins.opcode == op::CompositeConstruct && ins.words.size() > 2 &&
                           std::all_of(ins.words.begin() + 2, ins.words.end(), [&](uint32_t c) { return c == ins.words[2]; });
        if (ins.opcode == op::LogicalNot || splat) {  // !b, or b splat to a bool vector for a select
            auto inner = uniform_bool_condition(ins.words.at(2));
            if (!inner) return std::nullopt;
            inner->negate = inner->negate != (ins.opcode == op::LogicalNot);
            inner->positions.push_back(d->second);
            return inner;
        }
        if (ins.opcode != op::INotEqual && ins.opcode != op::IEqual) return std::nullopt;
        const uint32_t a = ins.words.at(2), b = ins.words.at(3);
        const uint32_t loaded = is_integer_constant(b, 0) ? a : is_integer_constant(a, 0) ? b : 0;
        auto load = loaded ? uniform_integer_load(loaded) : std::nullopt;
        if (!load || !declared_bool(member_name(load->first.first, load->first.second))) return std::nullopt;
        FlowBool f;
        f.member = load->first;
        f.negate = ins.opcode == op::IEqual;
        f.positions = load->second;
        f.positions.push_back(d->second);
        return f;
    }

    [[noreturn]] void fail_at(size_t position, const std::string& message) {
        location_ = body_[position].location.line ? body_[position].location : entry_location_;
        throw CompileError(message);
    }

    static constexpr const char* kLoopForm =
        "a loop whose count is not a compile-time constant must read `for (int i = 0; i < n; i++)` with n a "
        "uniform int (it becomes vs_2_0's `rep i#`), and i may only count: SM2 cannot read a loop counter as a value";

    // Blocks, uses, and (vs_2_0) the branches on uniform bools and the loops counted by uniform ints.
    void analyze_flow() {
        uint32_t block = 0;
        block_of_.assign(body_.size(), 0);
        std::map<uint32_t, std::vector<size_t>> phis;
        for (size_t i = 0; i < body_.size(); ++i) {
            const auto& ins = body_[i];
            if (ins.opcode == op::Label) {
                block = ins.words.at(0);
                label_position_[block] = i;
            }
            block_of_[i] = block;
            if (has_result_id(ins.opcode) && ins.words.size() >= 2) defined_at_[ins.words[1]] = i;
            if (ins.opcode == op::Phi) phis[block].push_back(i);
            if (ins.opcode == op::Branch || ins.opcode == op::BranchConditional) terminator_of_[block] = i;
            for (uint32_t id : operand_ids(ins)) uses_[id].push_back(i);
        }
        for (const auto& [label, positions] : phis)
            for (size_t p : positions) {
                const auto& w = body_[p].words;
                std::vector<std::pair<uint32_t, uint32_t>> incoming;
                for (size_t k = 2; k + 1 < w.size(); k += 2) {
                    auto t = terminator_of_.find(w[k + 1]);
                    if (t == terminator_of_.end()) fail_at(p, "internal error: a phi from an unknown block");
                    incoming_uses_[t->second].push_back(w[k]);
                    uses_[w[k]].push_back(p);
                    incoming.emplace_back(w[k], w[k + 1]);
                }
                phi_incoming_[w.at(1)] = std::move(incoming);
                phis_of_[label].push_back(p);
            }
        if (pixel_) {  // ps_2_0 has no flow control: the first branch the optimizer left is the error
            for (size_t i = 0; i < body_.size(); ++i) {
                if (body_[i].opcode == op::SelectionMerge && kill_branch(i)) continue;
                if (body_[i].opcode == op::SelectionMerge || body_[i].opcode == op::LoopMerge) {
                    position_ = i;
                    location_ = body_[i].location.line ? body_[i].location : entry_location_;
                    no_flow_control();
                }
            }
            return;
        }

        std::set<size_t> consumers;  // the branches and selects that read a b#/i# condition
        for (size_t i = 0; i < body_.size(); ++i) {
            const auto& ins = body_[i];
            const bool selection = ins.opcode == op::BranchConditional && i > 0 && body_[i - 1].opcode == op::SelectionMerge;
            if (selection || ins.opcode == op::Select) {
                auto f = uniform_bool_condition(ins.words.at(selection ? 0 : 2));
                if (!f) continue;
                flow_bool_members_.insert(f->member);
                skip_.insert(f->positions.begin(), f->positions.end());
                consumers.insert(i);
                bool_conditions_[i] = std::move(*f);
            } else if (ins.opcode == op::LoopMerge) {
                analyze_loop(i, consumers);
            }
        }
        // The loads and comparisons skipped above feed only those branches: a uniform in b#/i#
        // has no c# register to be read from as a value.
        for (size_t p : skip_) {
            if (!has_result_id(body_[p].opcode)) continue;
            const uint32_t id = body_[p].words.at(1);
            if (read_counters_.count(id)) continue;  // a loop counter the body reads: a float temp
            for (size_t use : uses_[id])
                if (!skip_.count(use) && !consumers.count(use)) {
                    const auto load = uniform_integer_load(id);
                    const std::string name = load ? " '" + member_name(load->first.first, load->first.second) + "'" : "";
                    fail_at(use, "the uniform" + name + " decides an `if` or counts a loop (a b# or i# register in "
                                 "vs_2_0) and cannot also be read as a value here");
                }
        }
    }

    // ps_2_0: `if (c) discard;` and clip(x) reach the back end as a selection whose one arm is a
    // block holding only OpKill. It becomes texkill of a value negative exactly when the pixel dies.
    bool kill_branch(size_t i) {
        if (i + 1 >= body_.size() || body_[i + 1].opcode != op::BranchConditional) return false;
        const uint32_t merge = body_[i].words.at(0);
        const auto& w = body_[i + 1].words;
        const uint32_t kill = w.at(1) == merge ? w.at(2) : w.at(2) == merge ? w.at(1) : 0;
        if (!kill || kill == merge) return false;
        auto at = label_position_.find(kill);
        if (at == label_position_.end() || at->second + 1 >= body_.size() || body_[at->second + 1].opcode != op::Kill)
            return false;
        kill_branches_[i + 1] = kill == w.at(2);  // kill on the false arm: the condition negated
        skip_.insert({at->second, at->second + 1});
        return true;
    }

    void analyze_loop(size_t i, std::set<size_t>& consumers) {
        const auto& merge = body_[i];
        const uint32_t header = block_of_[i], merge_label = merge.words.at(0), continue_label = merge.words.at(1);
        if (i + 1 >= body_.size() || body_[i + 1].opcode != op::BranchConditional) fail_at(i, kLoopForm);
        const auto& branch = body_[i + 1].words;
        if (branch.at(2) != merge_label || branch.at(1) == merge_label) fail_at(i, kLoopForm);
        auto c = defined_at_.find(branch.at(0));
        if (c == defined_at_.end()) fail_at(i, kLoopForm);
        const auto& compare = body_[c->second];
        uint32_t counter = 0, bound = 0;
        if (compare.opcode == op::SLessThan) {
            counter = compare.words.at(2);
            bound = compare.words.at(3);
        } else if (compare.opcode == op::SGreaterThan) {
            counter = compare.words.at(3);
            bound = compare.words.at(2);
        } else {
            fail_at(i, kLoopForm);
        }
        auto load = uniform_integer_load(bound);
        int constant_count = -1;
        if (!load) {  // [loop] keeps a constant-count loop rolled: rep on a defi
            auto b = constants_.find(bound);
            if (b == constants_.end() || b->second.opcode != op::Constant ||
                types_.at(b->second.words.at(0)).opcode != op::TypeInt)
                fail_at(i, kLoopForm);
            const auto count = static_cast<int32_t>(b->second.words.at(2));
            if (count < 0 || count > 255)
                fail_at(i, "a rolled loop's count must be 0..255 (the range of rep's i#.x), not " + std::to_string(count));
            constant_count = count;
            load = std::make_pair(std::make_pair(0u, 0u), std::vector<size_t>{});
        }
        auto k = defined_at_.find(counter);
        auto t = terminator_of_.find(continue_label);
        if (k == defined_at_.end() || body_[k->second].opcode != op::Phi || block_of_[k->second] != header ||
            t == terminator_of_.end())
            fail_at(i, kLoopForm);
        // counter = phi(0 from before the loop, counter + 1 from the continue block)
        size_t increment = 0;
        for (const auto& [value, from] : phi_incoming_.at(counter)) {
            if (from == continue_label) {
                auto d = defined_at_.find(value);
                if (d == defined_at_.end() || body_[d->second].opcode != op::IAdd) fail_at(i, kLoopForm);
                const auto& add = body_[d->second].words;
                if (!((add.at(2) == counter && is_integer_constant(add.at(3), 1)) ||
                      (add.at(3) == counter && is_integer_constant(add.at(2), 1))))
                    fail_at(i, kLoopForm);
                increment = d->second;
            } else if (!is_integer_constant(value, 0)) {
                fail_at(i, kLoopForm);
            }
        }
        if (!increment || phi_incoming_.at(counter).size() != 2) fail_at(i, kLoopForm);
        // The counter read in the body (lights[i]): a float temp holds it, 0 before rep, + 1 before endrep.
        bool counter_read = false;
        for (size_t use : uses_[counter])
            if (use != c->second && use != increment) counter_read = true;
        for (size_t use : uses_[body_[increment].words.at(1)])
            if (use != k->second) fail_at(use, kLoopForm);
        std::vector<size_t> positions = load->second;
        positions.insert(positions.end(), {k->second, increment, c->second, i + 1});
        // The header holds the phis and the test only: rep has no place for other code there.
        for (size_t p = label_position_.at(header) + 1; p < i; ++p)
            if (body_[p].opcode != op::Phi && std::find(positions.begin(), positions.end(), p) == positions.end())
                fail_at(p, kLoopForm);
        if (constant_count < 0) flow_int_members_.insert(load->first);
        skip_.insert(positions.begin(), positions.end());
        consumers.insert(i);
        if (counter_read) read_counters_.insert(counter);
        loops_[header] = Loop{load->first, merge_label, header, t->second, constant_count, counter_read ? counter : 0};
    }

    // Values read inside a loop but defined before it (and the header's phis) stay in their
    // registers until the loop's last instruction: the body runs again after their last use.
    void extend_live_ranges_over_loops() {
        for (const auto& [header, loop] : loops_) {
            const size_t start = label_position_.at(header);
            for (size_t p = start; p <= loop.back_edge; ++p) {
                std::vector<uint32_t> used = operand_ids(body_[p]);
                used.insert(used.end(), incoming_uses_[p].begin(), incoming_uses_[p].end());
                for (uint32_t id : used) {
                    auto d = defined_at_.find(id);
                    if (d == defined_at_.end() || d->second < start ||
                        (body_[d->second].opcode == op::Phi && block_of_[d->second] == header))
                        last_use_[id] = std::max(last_use_[id], loop.back_edge);
                }
            }
        }
    }

    std::string flow_register(const std::pair<uint32_t, uint32_t>& member) const {
        auto r = flow_registers_.find(member);
        if (r == flow_registers_.end()) throw CompileError("internal error: a flow-control uniform without a register");
        return r->second;
    }

    void count_static_flow(const char* what) {
        if (++static_flow_count_ > 16)
            throw CompileError(std::string("this `") + what + "` is the 17th static flow control instruction (each if, "
                               "else and rep counts one): vs_2_0 allows 16");
    }

    // OpLabel: an open if's else arm starts, or a construct's merge block ends it.
    void enter_block(uint32_t label) {
        if (open_.empty()) return;
        Construct& c = open_.back();
        if (!c.loop && c.else_label == label) {
            count_static_flow("else");
            line("else");
            c.else_label = 0;
        } else if (c.merge == label) {
            if (c.else_label) throw CompileError("internal error: an if's blocks out of order");
            if (!c.loop) line("endif");
            open_.pop_back();
        }
    }

    // The phis of `target` take their values for the edge from the current block.
    void branch_phis(uint32_t target) {
        auto phis = phis_of_.find(target);
        if (phis == phis_of_.end()) return;
        const uint32_t from = block_of_[position_];
        std::vector<std::pair<Value, Value>> moves;  // (phi register, value)
        for (size_t p : phis->second) {
            if (skip_.count(p)) continue;
            const uint32_t phi = body_[p].words.at(1);
            for (const auto& [value_id, pred] : phi_incoming_.at(phi)) {
                if (pred != from) continue;
                auto r = phi_registers_.find(phi);
                if (r == phi_registers_.end()) {
                    Value reg;
                    reg.kind = Value::Kind::Register;
                    reg.file = 'r';
                    reg.index = allocate_temp();
                    reg.count = type_of_value_components(body_[p].words.at(0));
                    if (reg.count == 1) reg.swizzle = {0, 0, 0, 0};
                    r = phi_registers_.emplace(phi, reg).first;
                }
                moves.emplace_back(r->second, as_register(value_id));
            }
        }
        // A phi's value may be another phi's register (a swap): copy those first.
        for (auto& [reg, v] : moves)
            for (const auto& [other, unused] : moves)
                if (v.file == 'r' && v.index == other.index && &other.index != &reg.index) {
                    v = materialize(v, mask_of(reg.count));
                    break;
                }
        for (const auto& [reg, v] : moves)
            if (!(v.file == 'r' && v.index == reg.index && v.swizzle == reg.swizzle && !v.negate))
                emit("mov", temp_name(reg), mask_of(reg.count), {v});
    }

    void branch_to(uint32_t target) {
        branch_phis(target);
        const bool next = position_ + 1 < body_.size() && body_[position_ + 1].opcode == op::Label &&
                          body_[position_ + 1].words.at(0) == target;
        if (!open_.empty() && open_.back().loop && target == open_.back().header) {
            if (const uint32_t counter = loops_.at(target).counter) {
                const Value r = as_register(counter);
                emit("add", temp_name(r), 1, {r, literal(1.0f)});
            }
            line("endrep");
            return;
        }
        if (!open_.empty() && !open_.back().loop && target == open_.back().merge) return;
        if (!next || std::any_of(open_.begin(), open_.end(), [&](const Construct& c) { return c.merge == target; }))
            throw CompileError("break, continue or return inside an if or loop is not supported by this compiler");
    }

    [[noreturn]] void no_flow_control() const {
        if (pixel_)
            throw CompileError("ps_2_0 has no flow control: this branch or loop depends on a value the optimizer could "
                               "not fold (vs_2_0 compiles an if on a uniform bool to `if b#` and a loop counted by a "
                               "uniform int to `rep i#`)");
        throw CompileError("flow control that depends on run-time values (an if, loop or discard the optimizer "
                           "could not flatten) is not supported by this compiler for vs_2_0, except an if on a "
                           "uniform bool (`if b#`) and a loop counted by a uniform int (`rep i#`)");
    }

    void open_if() {
        auto c = bool_conditions_.find(position_);
        if (c == bool_conditions_.end()) no_flow_control();
        const auto& w = body_[position_].words;
        const uint32_t merge = body_[position_ - 1].words.at(0);
        uint32_t first = w.at(1), second = w.at(2);
        bool negate = c->second.negate;
        if (first == merge) {
            std::swap(first, second);
            negate = !negate;
        }
        if (second == merge) branch_phis(merge);  // no else arm: the values for skipping the if
        if (first == merge) return;
        if (position_ + 1 >= body_.size() || body_[position_ + 1].opcode != op::Label || body_[position_ + 1].words.at(0) != first)
            throw CompileError("internal error: an if's blocks out of order");
        count_static_flow("if");
        line(std::string("if ") + (negate ? "!" : "") + flow_register(c->second.member));
        open_.push_back({false, merge, second == merge ? 0 : second, 0});
    }

    void open_loop() {
        auto l = loops_.find(block_of_[position_]);
        if (l == loops_.end()) no_flow_control();
        if (std::any_of(open_.begin(), open_.end(), [](const Construct& c) { return c.loop; }))
            throw CompileError("a loop counted by a uniform int inside another such loop: vs_2_0 allows one level of "
                               "rep/loop nesting");
        count_static_flow("rep");
        if (l->second.counter) {
            Value r = new_temp(1);
            r.swizzle = {0, 0, 0, 0};
            emit("mov", temp_name(r), 1, {literal(0.0f)});
            define(l->second.counter, r);
        }
        line("rep " + (l->second.constant_count >= 0 ? "i" + std::to_string(integer_defs_.at(l->second.constant_count))
                                                      : flow_register(l->second.member)));
        open_.push_back({true, l->second.merge, 0, l->second.header});
    }

    // select(uniform bool, x, y) in vs_2_0: if b# / mov / else / mov / endif.
    void select_on_bool(uint32_t result, const FlowBool& condition, const Value& x, const Value& y, uint32_t count) {
        Value d = new_temp(count);
        count_static_flow("if");
        line(std::string("if ") + (condition.negate ? "!" : "") + flow_register(condition.member));
        emit("mov", temp_name(d), mask_of(count), {x});
        count_static_flow("else");
        line("else");
        emit("mov", temp_name(d), mask_of(count), {y});
        line("endif");
        if (count == 1) d.swizzle = {0, 0, 0, 0};
        define(result, d);
    }

    void assign_uniform_registers() {
        uint32_t next = 0;
        std::set<int> bound_samplers;
        for (const auto& [id, var] : variables_) {
            const auto [pointer_type, storage] = var;
            const Type& pointee = types_.at(types_.at(pointer_type).element);
            if (storage == kStorageUniformConstant && pointee.opcode == op::TypeSampledImage) {
                auto d = decorations_.find(id);
                if (d != decorations_.end() && d->second.count(decoration::Binding))
                    bound_samplers.insert(static_cast<int>(d->second.at(decoration::Binding)));
            }
        }
        int next_sampler = 0, next_bool = 0, next_int = 0;
        for (const auto& [id, var] : variables_) {
            const auto [pointer_type, storage] = var;
            const uint32_t pointee_id = types_.at(pointer_type).element;
            const Type& pointee = types_.at(pointee_id);
            if (storage == kStorageUniform && pointee.opcode == op::TypeStruct) {
                // `: register(cN)` places a uniform at cN (as fxc does); the others follow one
                // another in declaration order from c0, skipping the registers placed ones hold.
                std::vector<std::optional<uint32_t>> placed(pointee.members.size());
                std::vector<std::pair<uint32_t, uint32_t>> taken;  // [first, end) of explicit placements
                const uint32_t limit = pixel_ ? 32u : 256u;
                for (size_t m = 0; m < pointee.members.size(); ++m) {
                    const auto member = static_cast<uint32_t>(m);
                    placed[m] = explicit_constant_register(member_name(pointee_id, member));
                    if (!placed[m]) continue;
                    const bool row_major = member_decorations_[pointee_id][member].count(decoration::RowMajor) > 0;
                    const uint32_t first = *placed[m], end = first + register_size(pointee.members[m], row_major);
                    if (end > limit)
                        throw CompileError("'" + member_name(pointee_id, member) + "' at register(c" + std::to_string(first) +
                                           ") runs past c" + std::to_string(limit - 1) + ", the last constant register of " + profile());
                    for (const auto& [f, e] : taken)
                        if (first < e && f < end)
                            throw CompileError("'" + member_name(pointee_id, member) + "' at register(c" + std::to_string(first) +
                                               ") overlaps another uniform's registers c" + std::to_string(f) + "..c" +
                                               std::to_string(e - 1));
                    taken.emplace_back(first, end);
                }
                uint32_t end_of_all = 0;
                for (size_t m = 0; m < pointee.members.size(); ++m) {
                    const auto member = static_cast<uint32_t>(m);
                    const bool flow_bool = flow_bool_members_.count({pointee_id, member}) > 0;
                    if (flow_bool || flow_int_members_.count({pointee_id, member})) {
                        // Decides an if (b#) or counts a rep (i#): that register only, no c#.
                        int& counter = flow_bool ? next_bool : next_int;
                        if (counter > 15)
                            throw CompileError(std::string("more than 16 uniform ") + (flow_bool ? "bools in if conditions (b0-b15)" : "ints counting loops (i0-i15)"));
                        isa::ConstantInfo info;
                        info.name = member_name(pointee_id, member);
                        info.register_set = flow_bool ? isa::ConstantRegisterSet::Bool : isa::ConstantRegisterSet::Int4;
                        info.register_index = static_cast<uint16_t>(counter);
                        info.register_count = 1;
                        info.type = constant_type(pointee.members[m], false);
                        if (flow_bool) info.type.parameter_type = isa::parameter_type::Bool;
                        flow_registers_[{pointee_id, member}] = (flow_bool ? "b" : "i") + std::to_string(counter++);
                        constants_table_.push_back(std::move(info));
                        continue;
                    }
                    const bool spirv_row_major = member_decorations_[pointee_id][member].count(decoration::RowMajor) > 0;
                    const uint32_t size = register_size(pointee.members[m], spirv_row_major);
                    uint32_t at = next;
                    if (placed[m]) {
                        at = *placed[m];
                    } else {
                        for (bool moved = true; moved;) {
                            moved = false;
                            for (const auto& [f, e] : taken)
                                if (next < e && f < next + size) { next = e; moved = true; }
                        }
                        at = next;
                        next += size;
                    }
                    member_register_[{pointee_id, member}] = at;
                    isa::ConstantInfo info;
                    info.name = member_name(pointee_id, member);
                    info.register_index = static_cast<uint16_t>(at);
                    info.register_count = static_cast<uint16_t>(size);
                    info.type = constant_type(pointee.members[m], spirv_row_major);
                    if (info.type.parameter_type == isa::parameter_type::Int && declared_bool(info.name))
                        info.type.parameter_type = isa::parameter_type::Bool;
                    if (auto values = literal_initializer(info.name))
                        info.default_value = default_registers(info.type, info.register_count, *values);
                    constants_table_.push_back(std::move(info));
                    end_of_all = std::max(end_of_all, at + size);
                }
                next = end_of_all;
            } else if (storage == kStorageUniformConstant && pointee.opcode == op::TypeSampledImage) {
                auto d = decorations_.find(id);
                int s;
                if (d != decorations_.end() && d->second.count(decoration::Binding)) {
                    s = static_cast<int>(d->second.at(decoration::Binding));
                } else {
                    while (bound_samplers.count(next_sampler)) ++next_sampler;
                    s = next_sampler++;
                }
                if (s > 15) throw CompileError("sampler register s" + std::to_string(s) + " is past s15");
                sampler_of_[id] = s;
                isa::ConstantInfo info;
                info.name = names_.count(id) ? names_.at(id) : "sampler" + std::to_string(s);
                info.register_set = isa::ConstantRegisterSet::Sampler;
                info.register_index = static_cast<uint16_t>(s);
                info.register_count = 1;
                info.type = constant_type(pointee_id, false);
                constants_table_.push_back(std::move(info));
            }
        }
        first_def_register_ = next;
        // Rolled loops with literal counts: one defi per count, after the uniform ints.
        for (auto& [header, loop] : loops_) {
            if (loop.constant_count < 0) continue;
            auto known = integer_defs_.find(loop.constant_count);
            if (known == integer_defs_.end()) {
                if (next_int > 15) throw CompileError("more than 16 integer registers (i0-i15) for loop counts");
                known = integer_defs_.emplace(loop.constant_count, next_int++).first;
            }
        }
    }

    // A global's initializer when the source writes it as literal numbers: `= 0.5`,
    // `= float4(1, 2, 0, -1)`, `= {1, 2, 3, 4}` (booleans as 1 and 0). glslang drops uniform
    // initializers from the SPIR-V, so the default values for the constant table are read from
    // the text; anything else (an expression, a macro) gives none.
    std::optional<std::vector<float>> literal_initializer(const std::string& name) const {
        const auto at = global_declaration(name);
        if (!at) return std::nullopt;
        const size_t end = source_.find(';', *at);
        const size_t equals = source_.find('=', *at);  // past `: register(c0)` or a semantic
        if (end == std::string_view::npos || equals > end) return std::nullopt;
        return literal_numbers(source_.substr(equals + 1, end - equals - 1));
    }

    // Where `name` first appears outside braces and parentheses (comments skipped): the global's
    // declaration, since uses are inside function bodies.
    std::optional<size_t> global_declaration(const std::string& name) const {
        int braces = 0, parentheses = 0;
        for (size_t i = 0; i < source_.size(); ++i) {
            if (source_.compare(i, 2, "//") == 0) {
                i = std::min(source_.find('\n', i), source_.size());
                continue;
            }
            if (source_.compare(i, 2, "/*") == 0) {
                i = std::min(source_.find("*/", i + 2), source_.size()) + 1;
                continue;
            }
            const char c = source_[i];
            braces += c == '{' ? 1 : c == '}' ? -1 : 0;
            parentheses += c == '(' ? 1 : c == ')' ? -1 : 0;
            if (braces == 0 && parentheses == 0 && source_.compare(i, name.size(), name) == 0 &&
                (i == 0 || !is_identifier_char(source_[i - 1])) &&
                (i + name.size() >= source_.size() || !is_identifier_char(source_[i + name.size()])))
                return i;
        }
        return std::nullopt;
    }

    // `: register(cN)` (or `register(CN)`) in a global's declaration, before its initializer.
    std::optional<uint32_t> explicit_constant_register(const std::string& name) const {
        const auto at = global_declaration(name);
        if (!at) return std::nullopt;
        const size_t end = std::min(source_.find(';', *at), source_.find('=', *at));
        const std::string_view declaration = source_.substr(*at, end == std::string_view::npos ? std::string_view::npos : end - *at);
        size_t k = declaration.find("register");
        if (k == std::string_view::npos) return std::nullopt;
        k += 8;
        auto skip_space = [&] { while (k < declaration.size() && std::isspace(static_cast<unsigned char>(declaration[k]))) ++k; };
        skip_space();
        if (k >= declaration.size() || declaration[k] != '(') return std::nullopt;
        ++k;
        skip_space();
        if (k >= declaration.size() || (declaration[k] != 'c' && declaration[k] != 'C')) return std::nullopt;
        ++k;
        uint32_t index = 0;
        const size_t digits = k;
        while (k < declaration.size() && std::isdigit(static_cast<unsigned char>(declaration[k])) && index < 100000)
            index = index * 10 + static_cast<uint32_t>(declaration[k++] - '0');
        if (k == digits) return std::nullopt;
        return index;
    }

    // glslang stores a bool uniform as a 32-bit unsigned integer; the declaration says which.
    bool declared_bool(const std::string& name) const {
        const auto at = global_declaration(name);
        if (!at) return false;
        size_t end = *at;
        while (end > 0 && std::isspace(static_cast<unsigned char>(source_[end - 1]))) --end;
        size_t begin = end;
        while (begin > 0 && is_identifier_char(source_[begin - 1])) --begin;
        return source_.substr(begin, end - begin).rfind("bool", 0) == 0;
    }

    static bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

    // "float4(1, 2, 0, -1)", "{1, 2}", "0.5f", "true": the numbers; nullopt for anything else.
    static std::optional<std::vector<float>> literal_numbers(std::string_view text) {
        std::string list(text);
        const size_t open = list.find('(');
        if (open != std::string::npos) {  // a constructor: TYPE( ... )
            const size_t close = list.rfind(')');
            const std::string type = list.substr(0, open);
            if (close == std::string::npos || close < open ||
                !std::all_of(type.begin(), type.end(), [](char c) { return is_identifier_char(c) || std::isspace(static_cast<unsigned char>(c)); }) ||
                list.find_first_not_of(" \t\r\n", close + 1) != std::string::npos)
                return std::nullopt;
            list = list.substr(open + 1, close - open - 1);
        }
        std::replace(list.begin(), list.end(), '{', ' ');
        std::replace(list.begin(), list.end(), '}', ' ');
        std::vector<float> values;
        std::istringstream items(list);
        std::string item;
        while (std::getline(items, item, ',')) {
            const size_t first = item.find_first_not_of(" \t\r\n");
            if (first == std::string::npos) return std::nullopt;
            item = item.substr(first, item.find_last_not_of(" \t\r\n") - first + 1);
            if (item == "true" || item == "false") {
                values.push_back(item == "true" ? 1.0f : 0.0f);
                continue;
            }
            if (!item.empty() && (item.back() == 'f' || item.back() == 'F' || item.back() == 'h' || item.back() == 'H'))
                item.pop_back();
            char* stop = nullptr;
            const float value = std::strtof(item.c_str(), &stop);
            if (item.empty() || stop != item.c_str() + item.size()) return std::nullopt;
            values.push_back(value);
        }
        if (values.empty()) return std::nullopt;
        return values;
    }

    // The initializer's values in register order, four DWORDs per register: a vector or scalar per
    // element; a matrix (values written row by row, as HLSL does) one row per register when
    // row_major, one column per register otherwise. A single value fills the whole type, as HLSL
    // promotes a scalar. Empty when the count does not match the type.
    static std::vector<uint32_t> default_registers(const isa::ConstantType& type, uint32_t register_count,
                                                   std::vector<float> values) {
        const bool matrix = type.parameter_class == isa::parameter_class::MatrixRows ||
                            type.parameter_class == isa::parameter_class::MatrixColumns;
        if (type.parameter_class == isa::parameter_class::Struct || type.parameter_class == isa::parameter_class::Object)
            return {};
        const size_t per_element = size_t{type.rows} * type.columns;
        const size_t wanted = per_element * type.elements;
        if (values.size() == 1) values.assign(wanted, values[0]);
        if (values.size() != wanted) return {};
        std::vector<float> registers(size_t{register_count} * 4, 0.0f);
        const size_t registers_per_element = register_count / std::max<uint32_t>(type.elements, 1);
        for (size_t e = 0; e < type.elements; ++e)
            for (size_t r = 0; r < type.rows; ++r)
                for (size_t c = 0; c < type.columns; ++c) {
                    const float value = values[e * per_element + r * type.columns + c];
                    const bool by_column = matrix && type.parameter_class == isa::parameter_class::MatrixColumns;
                    const size_t reg = e * registers_per_element + (by_column ? c : matrix ? r : 0);
                    const size_t component = by_column ? r : c;
                    registers.at(reg * 4 + component) = value;
                }
        std::vector<uint32_t> words(registers.size());
        std::memcpy(words.data(), registers.data(), words.size() * 4);
        return words;
    }

    std::string member_name(uint32_t struct_id, uint32_t member) const {
        auto it = member_names_.find({struct_id, member});
        return it != member_names_.end() && !it->second.empty() ? it->second : "member" + std::to_string(member);
    }

    // The CTAB type of a uniform. glslang turns HLSL's floatRxC into a SPIR-V matrix of R vectors
    // of C components and flips the packing: HLSL's default column_major is SPIR-V RowMajor.
    isa::ConstantType constant_type(uint32_t type_id, bool spirv_row_major) const {
        const Type& t = types_.at(type_id);
        isa::ConstantType c;
        c.rows = c.columns = c.elements = 1;
        switch (t.opcode) {
        case op::TypeBool: c.parameter_type = isa::parameter_type::Bool; break;
        case op::TypeInt: c.parameter_type = isa::parameter_type::Int; break;
        case op::TypeFloat: c.parameter_type = isa::parameter_type::Float; break;
        case op::TypeVector:
            c = constant_type(t.element, spirv_row_major);
            c.parameter_class = isa::parameter_class::Vector;
            c.columns = static_cast<uint16_t>(t.component_count);
            break;
        case op::TypeMatrix:
            c = constant_type(t.element, spirv_row_major);
            c.parameter_class = spirv_row_major ? isa::parameter_class::MatrixColumns : isa::parameter_class::MatrixRows;
            c.rows = static_cast<uint16_t>(t.component_count);
            break;
        case op::TypeArray:
            c = constant_type(t.element, spirv_row_major);
            c.elements = static_cast<uint16_t>(t.component_count);
            break;
        case op::TypeStruct:
            c.parameter_class = isa::parameter_class::Struct;
            c.parameter_type = isa::parameter_type::Void;
            c.columns = 0;
            for (size_t m = 0; m < t.members.size(); ++m) {
                const auto member = static_cast<uint32_t>(m);
                isa::ConstantMember entry{member_name(type_id, member), constant_type(t.members[m], false)};
                c.columns = static_cast<uint16_t>(c.columns + entry.type.rows * entry.type.columns * entry.type.elements);
                c.members.push_back(std::move(entry));
            }
            break;
        case op::TypeSampledImage: {
            static constexpr uint16_t kByDim[] = {isa::parameter_type::Sampler1D, isa::parameter_type::Sampler2D,
                                                  isa::parameter_type::Sampler3D, isa::parameter_type::SamplerCube};
            c.parameter_class = isa::parameter_class::Object;
            c.parameter_type = t.image_dim < 4 ? kByDim[t.image_dim] : isa::parameter_type::Sampler;
            break;
        }
        default: throw CompileError("a uniform of a type the constant table cannot describe");
        }
        return c;
    }

    Value pointer_load(const Value& p) {
        const Type& t = types_.at(p.pointee);
        if (p.storage == kStorageUniform && p.dynamic_index) {  // mova a0.x, i * stride; mov r, c[a0.x + n]
            if (t.opcode == op::TypeMatrix) throw CompileError("a matrix in a uniform array indexed at run time is not supported");
            Value i = as_register(p.dynamic_index);
            if (p.dynamic_stride != 1) {
                Value scaled = new_temp(1);
                emit("mul", temp_name(scaled), 1, {component_view(i, 0), literal(static_cast<float>(p.dynamic_stride))});
                scaled.swizzle = {0, 0, 0, 0};
                i = scaled;
            }
            emit("mova", "a0", 1, {component_view(i, 0)});
            const uint32_t count = type_of_value_components(p.pointee);
            Value d = new_temp(count);
            // One component of a member (lights[i].pos.w): that component, replicated.
            const std::string component = p.component >= 0 ? std::string(".") + kComponents[p.component] : "";
            line("mov " + temp_name(d) + mask_text(mask_of(count)) + ", c[a0.x + " + std::to_string(p.index) + "]" + component);
            if (count == 1) d.swizzle = {0, 0, 0, 0};
            return d;
        }
        if (p.storage == kStorageUniform) {
            if (t.opcode == op::TypeMatrix) {
                Value m;
                m.kind = Value::Kind::Matrix;
                m.file = 'c';
                m.index = p.index;
                m.columns = t.component_count;
                m.rows = types_.at(t.element).component_count;
                m.registers_are_columns = !p.row_major;
                return m;
            }
            Value v;
            v.kind = Value::Kind::Register;
            v.file = 'c';
            v.index = p.index;
            v.count = type_of_value_components(p.pointee);
            return p.component >= 0 ? component_view(v, static_cast<uint32_t>(p.component)) : v;
        }
        if (p.storage == kStorageInput) {
            Value v = input_register(p.variable);
            v.count = type_of_value_components(p.pointee);
            return v;
        }
        if (p.storage == kStorageUniformConstant && sampler_of_.count(p.variable)) {
            Value s;
            s.kind = Value::Kind::Sampler;
            s.sampler = sampler_of_.at(p.variable);
            samplers_used_[s.sampler] = t.image_dim;
            return s;
        }
        throw CompileError("reading this variable is not supported (local arrays indexed at run time, or a "
                           "resource type SM2 lacks)");
    }

    Value input_register(uint32_t variable) {
        const uint32_t count = type_of_value_components(types_.at(variables_.at(variable).first).element);
        auto sem = semantics_.find(variable);
        const std::string semantic = sem != semantics_.end() ? sem->second : "";
        Value v;
        v.kind = Value::Kind::Register;
        if (!pixel_) {
            const auto pos = std::find(interface_.begin(), interface_.end(), variable);
            int index = 0, same_semantic = 0;
            for (auto it = interface_.begin(); it != pos; ++it)
                if (variables_.count(*it) && variables_.at(*it).second == kStorageInput) {
                    ++index;
                    auto other = semantics_.find(*it);
                    if (other != semantics_.end() && other->second == semantic) ++same_semantic;
                }
            v.file = 'v';
            v.index = index;
            if (index > 15) throw CompileError("more than 16 vertex inputs (v0-v15)");
            static const std::map<std::string, std::string> kUsage = {
                {"POSITION", "position"}, {"BLENDWEIGHT", "blendweight"}, {"BLENDINDICES", "blendindices"},
                {"NORMAL", "normal"}, {"PSIZE", "psize"}, {"TEXCOORD", "texcoord"}, {"TANGENT", "tangent"},
                {"BINORMAL", "binormal"}, {"COLOR", "color"}, {"FOG", "fog"}, {"DEPTH", "depth"}};
            // An array input (`float w[2] : TEXCOORD1`) reaches SPIR-V as one variable per element,
            // each with the array's semantic: element k is usage index n + k, as fxc numbers them.
            auto [name, n] = split_semantic(semantic);
            n += same_semantic;
            auto u = kUsage.find(name);
            if (u == kUsage.end())
                throw CompileError("vertex input semantic '" + semantic + "' has no D3D9 usage (POSITION, NORMAL, "
                                   "TEXCOORDn, COLORn, TANGENT, BINORMAL, BLENDWEIGHT, BLENDINDICES, PSIZE, FOG)");
            declarations_[register_name(v)] = "dcl_" + u->second + (n ? std::to_string(n) : "") + " " + register_name(v);
            return v;
        }
        const auto [name, n] = split_semantic(semantic);
        if (name == "TEXCOORD" && n <= 7) {
            v.file = 't';
        } else if (name == "COLOR" && n <= 1) {
            v.file = 'v';
        } else {
            throw CompileError("pixel input semantic '" + semantic + "' has no ps_2_0 register (TEXCOORD0-7 are t0-t7, "
                               "COLOR0-1 are v0-v1)");
        }
        v.index = n;
        declarations_[register_name(v)] = "dcl " + register_name(v) + mask_text(mask_of(count));
        return v;
    }

    std::pair<std::string, uint8_t> output_register(uint32_t variable, uint32_t count) {
        auto sem = semantics_.find(variable);
        std::string semantic = sem != semantics_.end() ? sem->second : "";
        auto d = decorations_.find(variable);
        if (d != decorations_.end() && d->second.count(decoration::BuiltIn) &&
            d->second.at(decoration::BuiltIn) == kBuiltInPosition)
            semantic = "POSITION";
        const auto [name, n] = split_semantic(semantic);
        if (!pixel_) {
            if (name == "POSITION" && n == 0) return {"oPos", mask_of(count)};
            if (name == "TEXCOORD" && n <= 7) return {"oT" + std::to_string(n), mask_of(count)};
            if (name == "COLOR" && n <= 1) return {"oD" + std::to_string(n), mask_of(count)};
            if (name == "FOG") return {"oFog", 0xF};
            if (name == "PSIZE") return {"oPts", 0xF};
            throw CompileError("vertex output semantic '" + semantic + "' has no vs_2_0 register (POSITION, TEXCOORD0-7, "
                               "COLOR0-1, FOG, PSIZE)");
        }
        if ((name == "COLOR" || name == "TARGET") && n <= 3) {
            if (count != 4) throw CompileError("pixel output " + semantic + " must be a float4 (oC# is written whole)");
            return {"oC" + std::to_string(n), 0xF};
        }
        if (name == "DEPTH" && n == 0) return {"oDepth", 0xF};
        throw CompileError("pixel output semantic '" + semantic + "' has no ps_2_0 register (COLOR0-3, DEPTH)");
    }

    void translate(const SpirvInstruction& ins) {
        const auto& w = ins.words;
        auto result_count = [&] { return type_of_value_components(w.at(0)); };
        switch (ins.opcode) {
        case op::Label: enter_block(w.at(0)); return;
        case op::Return:
        case op::FunctionEnd:
        case op::Variable: return;
        case op::Load: {
            define(w.at(1), pointer_load(pointer_of(w.at(2))));
            return;
        }
        case op::AccessChain:
        case op::InBoundsAccessChain: {
            Value p = pointer_of(w.at(2));
            for (size_t k = 3; k < w.size(); ++k) {
                auto c = constants_.find(w[k]);
                p = c == constants_.end() ? dynamic_step(p, w[k]) : step_pointer(p, constant_int(w[k]));
            }
            define(w.at(1), p);
            return;
        }
        case op::Store: {
            const Value& p = pointer_of(w.at(0));
            if (p.storage != kStorageOutput) throw CompileError("writing a variable other than an output (local arrays indexed at run time) is not supported");
            Value v = as_register(w.at(1));
            const auto [reg, mask] = output_register(p.variable, v.count);
            if (reg == "oDepth" || reg == "oFog" || reg == "oPts") {
                emit("mov", reg, 0xF, {component_view(v, 0)});
            } else {
                emit("mov", reg, mask, {v}, reg[1] == 'C');
            }
            return;
        }
        case op::CopyObject: define(w.at(1), value(w.at(2))); return;
        case op::CompositeExtract: {
            const Value v = value(w.at(2));
            if (v.kind == Value::Kind::Register) {
                define(w.at(1), component_view(v, w.at(3)));
                return;
            }
            if (v.kind == Value::Kind::Matrix && w.size() == 4) {
                define(w.at(1), matrix_column(v, w.at(3)));
                return;
            }
            throw CompileError("extracting from this value (a struct or array expression) is not supported");
        }
        case op::VectorShuffle: {
            const Value a = as_register(w.at(2)), b = as_register(w.at(3));
            std::vector<Value> parts;
            for (size_t k = 4; k < w.size(); ++k) {
                const uint32_t c = w[k];
                parts.push_back(c < a.count ? component_view(a, c) : component_view(b, c - a.count));
            }
            define(w.at(1), construct(parts));
            return;
        }
        case op::CompositeInsert: {  // `v.w = x`: the vector with one component replaced
            const Value object = as_register(w.at(2)), composite = value(w.at(3));
            if (composite.kind != Value::Kind::Register || w.size() != 5)
                throw CompileError("inserting into this value (a struct, array or matrix) is not supported");
            std::vector<Value> parts;
            for (uint32_t c = 0; c < composite.count; ++c)
                parts.push_back(c == w.at(4) ? component_view(object, 0) : component_view(composite, c));
            define(w.at(1), construct(parts));
            return;
        }
        case op::CompositeConstruct: {
            // A scalar comparison splat to a bool vector (`flag > 0 ? v3 : 0`): the comparison
            // itself, which the select applies to every component.
            if (value(w.at(2)).kind == Value::Kind::Condition) {
                for (size_t k = 3; k < w.size(); ++k)
                    if (w[k] != w[2]) throw CompileError("a vector of different comparisons is not supported in a select");
                const Value c = value(w.at(2));
                extend_last_use(c.lhs, last_use_[w.at(1)]);
                extend_last_use(c.rhs, last_use_[w.at(1)]);
                define(w.at(1), c);
                return;
            }
            std::vector<Value> parts;
            for (size_t k = 2; k < w.size(); ++k) {
                const Value p = as_register(w[k]);
                for (uint32_t c = 0; c < p.count; ++c) parts.push_back(component_view(p, c));
            }
            define(w.at(1), construct(parts));
            return;
        }
        case op::FNegate: {
            Value v = as_register(w.at(2));
            v.negate = !v.negate;
            define(w.at(1), v);
            return;
        }
        case op::FAdd:
        case op::FSub: {
            const bool a_fused = fused_.count(w.at(2)) > 0, b_fused = fused_.count(w.at(3)) > 0;
            if (a_fused || b_fused) {
                Value a = a_fused ? Value{} : as_register(w.at(2)), b = b_fused ? Value{} : as_register(w.at(3));
                if (ins.opcode == op::FSub && !b_fused) b.negate = !b.negate;
                const uint32_t mul_id = a_fused ? w.at(2) : w.at(3);
                Value addend = a_fused ? b : a;
                const bool negate_product = !a_fused && ins.opcode == op::FSub;
                auto [x, y] = fused_operands_.at(mul_id);
                if (negate_product) x.negate = !x.negate;
                Value d = new_temp(result_count());
                emit("mad", temp_name(d), mask_of(d.count), {x, y, addend});
                define(w.at(1), d);
                return;
            }
            Value a = as_register(w.at(2)), b = as_register(w.at(3));
            if (ins.opcode == op::FSub) b.negate = !b.negate;
            binary("add", w.at(1), result_count(), a, b);
            return;
        }
        case op::FMul:
        case op::VectorTimesScalar: {
            if (fused_.count(w.at(1))) {
                fused_operands_[w.at(1)] = {as_register(w.at(2)), as_register(w.at(3))};
                return;
            }
            binary("mul", w.at(1), result_count(), as_register(w.at(2)), as_register(w.at(3)));
            return;
        }
        case op::FDiv: {
            const Value a = as_register(w.at(2)), b = as_register(w.at(3));
            Value r = new_temp(b.count);
            for (uint32_t c = 0; c < b.count; ++c)
                emit("rcp", temp_name(r), static_cast<uint8_t>(1 << c), {component_view(b, c)});
            if (is_literal(w.at(2), 1.0f) && b.count == result_count()) {  // 1 / x: the rcp alone (1 * y is y)
                define(w.at(1), r);
                return;
            }
            binary("mul", w.at(1), result_count(), a, r);
            return;
        }
        case op::Dot: define(w.at(1), dot(as_register(w.at(2)), as_register(w.at(3)))); return;
        case op::MatrixTimesVector:
        case op::VectorTimesMatrix: {
            const bool matrix_first = ins.opcode == op::MatrixTimesVector;
            Value m = value(w.at(matrix_first ? 2 : 3));
            const Value v = as_register(w.at(matrix_first ? 3 : 2));
            if (m.kind != Value::Kind::Matrix) throw CompileError("only uniform matrices can be multiplied (mul) here");
            // M * v dots v with M's rows; v * M with M's columns.
            if (matrix_first) {
                std::swap(m.columns, m.rows);
                m.registers_are_columns = !m.registers_are_columns;
            }
            define(w.at(1), vector_times_matrix(v, m));
            return;
        }
        case op::Transpose: {
            Value m = value(w.at(2));
            if (m.kind != Value::Kind::Matrix) throw CompileError("transpose of a non-uniform matrix is not supported");
            std::swap(m.columns, m.rows);
            m.registers_are_columns = !m.registers_are_columns;
            define(w.at(1), m);
            return;
        }
        case op::LogicalNot: {
            Value c = value(w.at(2));
            if (c.kind != Value::Kind::Condition) throw CompileError("boolean logic beyond one comparison is not supported");
            if (c.any) throw CompileError("!any() is not supported: texkill kills when any component is negative");
            c.negate = !c.negate;
            for (uint32_t operand : {c.lhs, c.rhs})  // the comparison's operands live as long as the negation
                if (operand != 0) extend_last_use(operand, last_use_[w.at(1)]);
            define(w.at(1), c);
            return;
        }
        case op::Select: {
            auto flow = bool_conditions_.find(position_);
            if (flow != bool_conditions_.end()) {
                select_on_bool(w.at(1), flow->second, as_register(w.at(3)), as_register(w.at(4)), result_count());
                return;
            }
            const Value c = value(w.at(2));
            if (c.kind != Value::Kind::Condition) throw CompileError("a condition SM2 cannot evaluate without branches");
            define(w.at(1), select(c, as_register(w.at(3)), as_register(w.at(4)), result_count()));
            return;
        }
        case op::ImageSampleExplicitLod:
            throw CompileError(pixel_ ? "texture sampling with an explicit level (tex2Dlod) needs ps_3_0"
                                      : "texture sampling in a vertex shader needs vs_3_0 (vs_2_0 has no texld)");
        case op::ConvertSToF:
        case op::ConvertUToF: define(w.at(1), value(w.at(2))); return;  // SM2 holds integers as floats
        case op::ImageSampleImplicitLod:
        case op::ImageSampleProjImplicitLod: {
            if (!pixel_) throw CompileError("texture sampling in a vertex shader needs vs_3_0 (vs_2_0 has no texld)");
            // tex2Dbias/texCUBEbias/tex3Dbias (t.w the bias): the Bias image operand (mask 0x1).
            const bool bias = ins.opcode == op::ImageSampleImplicitLod && w.size() == 6 && w.at(4) == 0x1;
            if (w.size() > 4 && !bias) throw CompileError("texture sampling with offsets or gradients is not supported");
            const Value s = value(w.at(2));
            if (s.kind != Value::Kind::Sampler) throw CompileError("internal error: sampling without a sampler");
            Value coord = as_register(w.at(3));
            if (bias) {  // texldb reads the bias from the coordinate's .w
                std::vector<Value> parts;
                for (uint32_t c = 0; c < 3; ++c) parts.push_back(component_view(coord, std::min(c, coord.count - 1)));
                parts.push_back(component_view(as_register(w.at(5)), 0));
                coord = construct(parts);
            }
            // The register as it is when the coordinate is its first components (t0.xy of a float4
            // input: texld reads the components the texture needs), else moved to a temp.
            bool leading = coord.count >= 2;
            for (uint32_t c = 0; c < coord.count && leading; ++c) leading = coord.swizzle[c] == c;
            if (!(coord.file == 'r' || coord.file == 't') || coord.negate || !leading)
                coord = materialize(coord, mask_of(std::max<uint32_t>(coord.count, 2)));
            Value d = new_temp(4);
            line(std::string(ins.opcode == op::ImageSampleProjImplicitLod ? "texldp " : bias ? "texldb " : "texld ") + temp_name(d) +
                 ", " + register_name(coord) + ", s" + std::to_string(s.sampler));
            define(w.at(1), d);
            return;
        }
        case op::ExtInst: extended(ins); return;
        case op::Phi: {
            auto r = phi_registers_.find(w.at(1));
            if (r == phi_registers_.end()) throw CompileError("internal error: a phi no branch assigned");
            define(w.at(1), r->second);
            return;
        }
        case op::SelectionMerge: return;  // the branch that follows opens the if
        case op::LoopMerge: open_loop(); return;
        case op::Branch: branch_to(w.at(0)); return;
        case op::BranchConditional: {
            auto kill = kill_branches_.find(position_);
            if (kill != kill_branches_.end()) {
                kill_if(value(w.at(0)), kill->second);
                return;
            }
            open_if();
            return;
        }
        case op::Any: {
            Value c = value(w.at(2));
            if (c.kind != Value::Kind::Condition || c.lhs == 0) throw CompileError("any() of something other than one comparison is not supported");
            c.any = true;
            for (uint32_t operand : {c.lhs, c.rhs}) extend_last_use(operand, last_use_[w.at(1)]);
            define(w.at(1), c);
            return;
        }
        case op::INotEqual:
        case op::IEqual:
            throw CompileError(pixel_ ? "a uniform bool or int read as a value (an integer comparison) is not supported in ps_2_0"
                                      : "a condition on uniform bools other than one bool alone (`b`, `!b`; not `a && b`), or a "
                                        "uniform bool or int read as a value, is not supported: vs_2_0's `if b#` tests one bool");
        case op::Kill:
            if (pixel_) {  // a discard the optimizer left unconditional: every pixel dies
                kill_always();
                // The outputs' stores followed the discard and are gone; ps_2_0 must still write oC0.
                if (std::none_of(code_.begin(), code_.end(), [](const std::string& l) { return l.rfind("mov oC0", 0) == 0; }))
                    emit("mov", "oC0", 0xF, {literal_vector({0, 0, 0, 0}, 4)});
                return;
            }
            throw CompileError("flow control that depends on run-time values (an if, loop or discard the optimizer "
                               "could not flatten) is not supported by this compiler for " + profile());
        default: break;
        }
        if (ins.opcode >= op::FOrdEqual && ins.opcode <= op::FUnordGreaterThanEqual) {
            Value c;
            c.kind = Value::Kind::Condition;
            c.compare = ins.opcode;
            c.lhs = w.at(2);
            c.rhs = w.at(3);
            extend_last_use(c.lhs, last_use_[w.at(1)]);
            extend_last_use(c.rhs, last_use_[w.at(1)]);
            define(w.at(1), c);
            return;
        }
        throw CompileError("this operation (SPIR-V opcode " + std::to_string(ins.opcode) +
                           ") has no SM2 translation in this compiler (integer or bit arithmetic, derivatives, "
                           "dynamic indexing, ...)");
    }

    Value pointer_of(uint32_t id) {
        auto it = values_.find(id);
        if (it != values_.end() && it->second.kind == Value::Kind::Pointer) return it->second;
        auto var = variables_.find(id);
        if (var == variables_.end()) throw CompileError("internal error: not a pointer");
        Value p;
        p.kind = Value::Kind::Pointer;
        p.variable = id;
        p.storage = var->second.second;
        p.pointee = types_.at(var->second.first).element;
        p.index = 0;
        return p;
    }

    // lights[i] with i a run-time value (vs_2_0: a loop counter): the element's registers are read
    // at c[a0.x + n], a0.x = i * the element's register count (mova), when the pointer is loaded.
    Value dynamic_step(Value p, uint32_t index) {
        const Type& t = types_.at(p.pointee);
        if (pixel_) throw CompileError("indexing a uniform array with a run-time value needs relative addressing, which ps_2_0 lacks");
        if (p.storage != kStorageUniform || t.opcode != op::TypeArray)
            throw CompileError("only uniform arrays can be indexed with a run-time value (vs_2_0: c[a0.x + n])");
        if (p.dynamic_index) throw CompileError("a second run-time index into one uniform is not supported");
        p.dynamic_index = index;
        p.dynamic_stride = static_cast<int>(register_size(t.element, p.row_major));
        p.pointee = t.element;
        return p;
    }

    Value step_pointer(Value p, uint32_t index) {
        const Type& t = types_.at(p.pointee);
        if (p.storage != kStorageUniform)
            throw CompileError("indexing an input, output or local array is not supported");
        if (t.opcode == op::TypeStruct) {
            if (index >= t.members.size()) throw CompileError("internal error: member out of range");
            auto flow = flow_registers_.find({p.pointee, index});
            if (flow != flow_registers_.end())
                throw CompileError("the uniform '" + member_name(p.pointee, index) + "' lives in " + flow->second +
                                   " (it decides an if or counts a loop) and cannot also be read as a value");
            const auto placed = member_register_.find({p.pointee, index});
            if (placed != member_register_.end()) {  // a member of the $Global block: its register
                p.index = static_cast<int>(placed->second);
            } else {  // a member of a struct inside it (an array of structs): after the ones before it
                for (uint32_t m = 0; m < index; ++m)
                    p.index += static_cast<int>(register_size(t.members[m], member_decorations_[p.pointee][m].count(decoration::RowMajor) > 0));
            }
            const auto& md = member_decorations_[p.pointee][index];
            p.row_major = md.count(decoration::RowMajor) > 0;
            p.pointee = t.members[index];
        } else if (t.opcode == op::TypeArray) {
            if (index >= t.component_count) throw CompileError("array index " + std::to_string(index) + " is out of range");
            p.index += static_cast<int>(index * register_size(t.element, p.row_major));
            p.pointee = t.element;
        } else if (t.opcode == op::TypeMatrix) {
            if (p.row_major) throw CompileError("a column of a row_major matrix is not supported here; use the whole matrix");
            p.index += static_cast<int>(index);
            p.pointee = t.element;
        } else if (t.opcode == op::TypeVector && index < t.component_count) {
            p.component = static_cast<int>(index);
            p.pointee = t.element;
        } else {
            throw CompileError("indexing this uniform is not supported");
        }
        if (p.index > (pixel_ ? 31 : 255)) throw CompileError("uniforms need more constant registers than " + profile() + " has");
        return p;
    }

    Value matrix_column(const Value& m, uint32_t j) {
        Value reg;
        reg.kind = Value::Kind::Register;
        reg.file = 'c';
        if (m.registers_are_columns) {
            reg.index = m.index + static_cast<int>(j);
            reg.count = m.rows;
            return reg;
        }
        std::vector<Value> parts;
        for (uint32_t i = 0; i < m.rows; ++i) {
            reg.index = m.index + static_cast<int>(i);
            reg.count = 4;
            parts.push_back(component_view(reg, j));
        }
        return construct(parts);
    }

    // Components gathered into one value: a view when they all come from one register, else a
    // temp filled by masked movs (one per run of components from the same register).
    Value construct(const std::vector<Value>& parts) {
        if (parts.size() > 4 || parts.empty()) throw CompileError("internal error: vector of more than 4 components");
        bool same = true;
        for (const auto& p : parts)
            same = same && p.file == parts[0].file && p.index == parts[0].index && p.negate == parts[0].negate;
        if (same) {
            Value v = parts[0];
            v.count = static_cast<uint32_t>(parts.size());
            for (size_t k = 0; k < parts.size(); ++k) v.swizzle[k] = parts[k].swizzle[0];
            for (size_t k = parts.size(); k < 4; ++k) v.swizzle[k] = v.swizzle[parts.size() - 1];
            return v;
        }
        Value d = new_temp(static_cast<uint32_t>(parts.size()));
        std::vector<bool> done(parts.size(), false);
        for (size_t k = 0; k < parts.size(); ++k) {
            if (done[k]) continue;
            Value source = parts[k];
            source.count = 4;
            uint8_t mask = 0;
            for (size_t j = k; j < parts.size(); ++j)
                if (!done[j] && parts[j].file == parts[k].file && parts[j].index == parts[k].index &&
                    parts[j].negate == parts[k].negate) {
                    source.swizzle[j] = parts[j].swizzle[0];
                    mask = static_cast<uint8_t>(mask | (1 << j));
                    done[j] = true;
                }
            emit("mov", temp_name(d), mask, {source});
        }
        return d;
    }

    void binary(const std::string& mnemonic, uint32_t result, uint32_t count, const Value& a, const Value& b) {
        Value d = new_temp(count);
        emit(mnemonic, temp_name(d), mask_of(count), {a, b});
        define(result, d);
    }

    Value dot(const Value& a, const Value& b) {
        Value d = new_temp(1);
        if (a.count == 4 || a.count == 3) {
            emit(a.count == 4 ? "dp4" : "dp3", temp_name(d), 1, {a, b});
        } else {
            emit("mul", temp_name(d), 1, {component_view(a, 0), component_view(b, 0)});
            for (uint32_t c = 1; c < a.count; ++c)
                emit("mad", temp_name(d), 1, {component_view(a, c), component_view(b, c), d});
        }
        d.swizzle = {0, 0, 0, 0};
        return d;
    }

    // v * M, M with `rows` = v's size and `columns` = the result's.
    Value vector_times_matrix(const Value& v, const Value& m) {
        Value d = new_temp(m.columns);
        Value reg;
        reg.kind = Value::Kind::Register;
        reg.file = 'c';
        if (m.registers_are_columns) {  // result.j = dot(v, column j): one dp per component
            for (uint32_t j = 0; j < m.columns; ++j) {
                reg.index = m.index + static_cast<int>(j);
                reg.count = m.rows;
                const uint8_t bit = static_cast<uint8_t>(1 << j);
                if (m.rows >= 3) {
                    emit(m.rows == 4 ? "dp4" : "dp3", temp_name(d), bit, {v, reg});
                } else {
                    Value t = dot(v, reg);
                    emit("mov", temp_name(d), bit, {t});
                }
            }
        } else {  // result = sum_i v.i * row i
            for (uint32_t i = 0; i < m.rows; ++i) {
                reg.index = m.index + static_cast<int>(i);
                reg.count = m.columns;
                if (i == 0)
                    emit("mul", temp_name(d), mask_of(m.columns), {reg, component_view(v, 0)});
                else
                    emit("mad", temp_name(d), mask_of(m.columns), {reg, component_view(v, i), d});
            }
        }
        return d;
    }

    // ps_2_0 saturate(x) where x is used by it alone and was just written by one instruction that
    // takes _sat (`dp3 r0.x, ...` then saturate): that instruction gets `_sat` (dp3_sat, the
    // same value as dp3 then mov_sat) and the result is x's register.
    bool fold_saturate(uint32_t result, uint32_t x) {
        auto after = code_after_.find(x);
        auto u = uses_.find(x);
        if (after == code_after_.end() || after->second != code_.size() || code_.empty() || u == uses_.end() ||
            u->second.size() != 1)
            return false;
        const Value& v = value(x);
        if (v.kind != Value::Kind::Register || v.file != 'r' || v.negate || temp_holders_[v.index] != 1) return false;
        std::string& last = code_.back();
        const size_t space = last.find(' ');
        if (space == std::string::npos) return false;
        const std::string mnemonic = last.substr(0, space);
        static const std::set<std::string> kSat = {"mov", "add", "mul", "mad", "dp3", "dp4", "min", "max", "cmp", "lrp",
                                                   "rcp", "rsq", "exp", "log", "pow", "nrm", "abs", "crs", "dp2add"};
        if (!kSat.count(mnemonic)) return false;
        // The destination: this register, a mask holding every component x reads.
        const std::string reg = temp_name(v);
        const size_t comma = last.find(',', space);
        if (comma == std::string::npos) return false;
        const std::string dest = last.substr(space + 1, comma - space - 1);
        if (dest.rfind(reg, 0) != 0) return false;
        const std::string mask = dest.substr(reg.size());
        if (!mask.empty() && mask[0] != '.') return false;
        for (uint32_t c = 0; c < v.count; ++c)
            if (!mask.empty() && mask.find(kComponents[v.swizzle[c]]) == std::string::npos) return false;
        last.insert(space, "_sat");
        define(result, v);
        return true;
    }

    void kill_always() {
        Value t = new_temp(4);
        emit("mov", temp_name(t), 0xF, {literal(-1.0f)});
        line("texkill " + temp_name(t));
    }

    // texkill where the comparison `c` (negated once more by `negate`) holds: a temp whose four
    // components (texkill tests all four) hold a - b, or cmp's -1/1 of it, so that one is negative
    // exactly then; components past the comparison's size hold 0 or 1, which never kill.
    void kill_if(Value c, bool negate) {
        if (c.kind != Value::Kind::Condition) throw CompileError("a discard condition SM2 cannot evaluate without branches");
        c.negate = c.negate != negate;
        if (c.lhs == 0) {  // a constant condition the optimizer left
            if ((c.compare != 0) != c.negate) kill_always();
            return;
        }
        if (c.any && c.negate)
            throw CompileError("discard when all components of a comparison hold (!any, all) is not supported: "
                               "texkill kills when any component is negative (clip(x), `if (any(x < y)) discard;`)");
        const Value a = as_register(c.lhs), b = as_register(c.rhs);
        // As in select(): kill when first - second >= 0, or (when_negative) when it is < 0.
        const uint32_t base = c.compare - (c.compare - op::FOrdEqual) % 2;
        bool swap_operands = false, when_negative = c.negate, equality = false;
        switch (base) {
        case op::FOrdEqual: equality = true; break;
        case op::FOrdEqual + 2: equality = true; when_negative = !when_negative; break;  // !=
        case op::FOrdEqual + 4: when_negative = !when_negative; break;  // a < b: a - b < 0
        case op::FOrdEqual + 6: swap_operands = true; when_negative = !when_negative; break;  // a > b: b - a < 0
        case op::FOrdEqual + 8: swap_operands = true; break;  // a <= b: b - a >= 0
        default: break;  // a >= b
        }
        const Value& first = swap_operands ? b : a;
        Value second = swap_operands ? a : b;
        second.negate = !second.negate;
        const uint32_t n = std::max(a.count, b.count);
        const uint8_t mask = n == 1 ? 0xF : mask_of(n);  // a scalar is replicated to all four
        Value t = new_temp(4);
        if (is_literal(c.rhs, 0.0f) || is_literal(c.lhs, 0.0f)) {  // x against 0: x itself, or -x
            const bool zero_second = is_literal(swap_operands ? c.lhs : c.rhs, 0.0f);
            emit("mov", temp_name(t), mask, {zero_second ? first : second});
        } else {
            emit("add", temp_name(t), mask, {first, second});
        }
        Value diff = t;
        diff.count = n == 1 ? 4 : n;
        if (equality) {  // -(a-b)^2 >= 0 only when a == b
            Value neg = diff;
            neg.negate = true;
            emit("mul", temp_name(t), mask, {neg, diff});
        }
        if (!when_negative) emit("cmp", temp_name(t), mask, {diff, literal(-1.0f), literal(1.0f)});
        if (mask != 0xF) emit("mov", temp_name(t), static_cast<uint8_t>(0xF & ~mask), {literal(when_negative ? 0.0f : 1.0f)});
        line("texkill " + temp_name(t));
    }

    // select(condition, x, y) with cmp (ps: src0 >= 0 ? src1 : src2) or sge/slt and lrp (vs).
    Value select(const Value& c, const Value& x, const Value& y, uint32_t count) {
        if (c.any) throw CompileError("any() is supported only as a discard's condition (clip)");
        Value d = new_temp(count);
        const uint8_t mask = mask_of(count);
        if (c.lhs == 0) {  // a constant condition the optimizer left
            emit("mov", temp_name(d), mask, {c.compare ^ (c.negate ? 1u : 0u) ? x : y});
            return d;
        }
        const Value a = as_register(c.lhs), b = as_register(c.rhs);
        // Normalize to "a >= b" (taken = x) or "a > b" forms.
        const uint32_t base = c.compare - (c.compare - op::FOrdEqual) % 2;  // ordered and unordered alike
        bool swap_operands = false, swap_results = c.negate, equality = false;
        switch (base) {
        case op::FOrdEqual: equality = true; break;
        case op::FOrdEqual + 2: equality = true; swap_results = !swap_results; break;  // !=
        case op::FOrdEqual + 4: swap_results = !swap_results; break;  // a < b: !(a >= b)
        case op::FOrdEqual + 6: swap_operands = true; swap_results = !swap_results; break;  // a > b: !(b >= a)
        case op::FOrdEqual + 8: swap_operands = true; break;  // a <= b: b >= a
        default: break;  // a >= b
        }
        const Value& first = swap_operands ? b : a;
        Value second = swap_operands ? a : b;
        const Value& taken = swap_results ? y : x;
        const Value& other = swap_results ? x : y;
        const uint32_t n = std::max(a.count, b.count);
        Value diff = new_temp(n);
        second.negate = !second.negate;
        emit("add", temp_name(diff), mask_of(n), {first, second});  // first - second
        if (n == 1) diff.swizzle = {0, 0, 0, 0};
        if (pixel_) {
            if (equality) {  // -(a-b)^2 >= 0 only when a == b
                Value neg = diff;
                neg.negate = true;
                emit("mul", temp_name(diff), mask_of(n), {neg, diff});
            }
            emit("cmp", temp_name(d), mask, {diff, taken, other});
            return d;
        }
        if (equality) throw CompileError("== and != comparisons are not supported in vs_2_0 by this compiler");
        Value zero = literal(0.0f);
        Value t = new_temp(n);
        emit("sge", temp_name(t), mask_of(n), {diff, zero});  // 1 where first >= second
        if (n == 1) t.swizzle = {0, 0, 0, 0};
        emit("lrp", temp_name(d), mask, {t, taken, other});
        return d;
    }

    // A scalar instruction (rcp, rsq, exp, log, pow) once per component.
    Value per_component(const std::string& mnemonic, const Value& a, const Value* b, uint32_t count) {
        Value d = new_temp(count);
        for (uint32_t c = 0; c < count; ++c) {
            std::vector<Value> sources = {component_view(a, a.count == 1 ? 0 : c)};
            if (b) sources.push_back(component_view(*b, b->count == 1 ? 0 : c));
            emit(mnemonic, temp_name(d), static_cast<uint8_t>(1 << c), sources);
        }
        return d;
    }

    void extended(const SpirvInstruction& ins) {
        const auto& w = ins.words;
        const uint32_t result = w.at(1), count = type_of_value_components(w.at(0));
        const uint32_t which = w.at(3);
        auto arg = [&](size_t k) { return as_register(w.at(4 + k)); };
        const uint8_t mask = mask_of(count);
        switch (which) {
        case glsl::FAbs: {
            Value d = new_temp(count);
            emit("abs", temp_name(d), mask, {arg(0)});
            define(result, d);
            return;
        }
        case glsl::Fract: {
            Value d = new_temp(count);
            emit("frc", temp_name(d), mask, {arg(0)});
            define(result, d);
            return;
        }
        case glsl::Floor: {
            Value f = new_temp(count);
            emit("frc", temp_name(f), mask, {arg(0)});
            f.negate = true;
            binary("add", result, count, arg(0), f);
            return;
        }
        case glsl::FMin: binary("min", result, count, arg(0), arg(1)); return;
        case glsl::FMax: binary("max", result, count, arg(0), arg(1)); return;
        case glsl::FClamp: {
            Value d = new_temp(count);
            const Value lo = arg(1), hi = arg(2);
            if (pixel_ && is_literal(w.at(5), 0.0f) && is_literal(w.at(6), 1.0f)) {
                if (fold_saturate(result, w.at(4))) return;
                emit("mov_sat", temp_name(d), mask, {arg(0)});  // saturate()
            } else {
                emit("max", temp_name(d), mask, {arg(0), lo});
                emit("min", temp_name(d), mask, {d, hi});
            }
            define(result, d);
            return;
        }
        case glsl::FMix: {  // mix(x, y, t) = t * (y - x) + x = lrp t, y, x
            Value d = new_temp(count);
            emit("lrp", temp_name(d), mask, {arg(2), arg(1), arg(0)});
            define(result, d);
            return;
        }
        case glsl::Fma: {
            Value d = new_temp(count);
            emit("mad", temp_name(d), mask, {arg(0), arg(1), arg(2)});
            define(result, d);
            return;
        }
        case glsl::InverseSqrt: define(result, per_component("rsq", arg(0), nullptr, count)); return;
        case glsl::Sqrt: {
            const Value r = per_component("rsq", arg(0), nullptr, count);
            define(result, per_component("rcp", r, nullptr, count));
            return;
        }
        case glsl::Exp2: define(result, per_component("exp", arg(0), nullptr, count)); return;
        case glsl::Log2: define(result, per_component("log", arg(0), nullptr, count)); return;
        case glsl::Exp: {  // e^x = 2^(x * log2(e))
            Value t = new_temp(count);
            emit("mul", temp_name(t), mask, {arg(0), literal(1.44269504f)});
            define(result, per_component("exp", t, nullptr, count));
            return;
        }
        case glsl::Log: {  // ln x = log2(x) * ln(2)
            const Value l = per_component("log", arg(0), nullptr, count);
            binary("mul", result, count, l, literal(0.693147182f));
            return;
        }
        case glsl::Pow: {
            const Value y = arg(1);
            define(result, per_component("pow", arg(0), &y, count));
            return;
        }
        case glsl::Length:
        case glsl::Distance: {
            Value v = arg(0);
            if (which == glsl::Distance) {
                Value b = arg(1);
                b.negate = !b.negate;
                Value diff = new_temp(v.count);
                emit("add", temp_name(diff), mask_of(v.count), {v, b});
                v = diff;
            }
            const Value squared = dot(v, v);
            const Value r = per_component("rsq", squared, nullptr, 1);
            define(result, per_component("rcp", r, nullptr, 1));
            return;
        }
        case glsl::Normalize: {
            const Value v = arg(0);
            Value d = new_temp(count);
            if (count == 3) {
                emit("nrm", temp_name(d), 0x7, {v}, true);
            } else {
                Value r = dot(v, v);
                emit("rsq", temp_name(r), 1, {r});
                emit("mul", temp_name(d), mask, {v, r});
            }
            define(result, d);
            return;
        }
        case glsl::Cross: {
            Value d = new_temp(3);
            emit("crs", temp_name(d), 0x7, {arg(0), arg(1)}, true);
            define(result, d);
            return;
        }
        case glsl::Reflect: {  // reflect(i, n) = i - 2 dot(n, i) n: dp, add, mad (fxc's sequence)
            const Value i = arg(0), n = arg(1);
            Value k = dot(n, i);
            emit("add", temp_name(k), 1, {k, k});
            k.negate = true;
            Value d = new_temp(count);
            emit("mad", temp_name(d), mask, {n, k, i});
            define(result, d);
            return;
        }
        case glsl::Step: {  // step(edge, x) = x >= edge ? 1 : 0
            Value c;
            c.kind = Value::Kind::Condition;
            c.compare = op::FUnordGreaterThanEqual - 1;
            c.lhs = w.at(5);
            c.rhs = w.at(4);
            define(result, select(c, literal(1.0f), literal(0.0f), count));
            return;
        }
        case glsl::Sin:
        case glsl::Cos: {
            // sincos wants -pi..pi: x / 2pi + 0.5, frc, * 2pi - pi.
            Value t = new_temp(count);
            emit("mad", temp_name(t), mask, {arg(0), literal(0.159154937f), literal(0.5f)});
            emit("frc", temp_name(t), mask, {t});
            emit("mad", temp_name(t), mask, {t, literal(6.28318548f), literal(-3.14159274f)});
            const Value k1 = literal_vector({-1.5500992e-006f, -2.1701389e-005f, 0.0026041667f, 0.00026041668f}, 4);
            const Value k2 = literal_vector({-0.020833334f, -0.125f, 1.0f, 0.5f}, 4);
            Value d = new_temp(count);
            const uint8_t bit = which == glsl::Cos ? 1 : 2;  // sincos writes cos in .x, sin in .y
            for (uint32_t c = 0; c < count; ++c) {
                Value s = new_temp(2);
                line("sincos " + temp_name(s) + mask_text(bit) + ", " + source_text(t, {static_cast<uint8_t>(c), static_cast<uint8_t>(c), static_cast<uint8_t>(c), static_cast<uint8_t>(c)}) +
                     ", " + register_name(k1) + ", " + register_name(k2));
                emit("mov", temp_name(d), static_cast<uint8_t>(1 << c), {component_view(s, bit == 1 ? 0 : 1)});
            }
            define(result, d);
            return;
        }
        default: break;
        }
        throw CompileError("intrinsic (GLSL.std.450 #" + std::to_string(which) + ") has no SM2 translation in this compiler");
    }

    bool is_literal(uint32_t id, float expected) const {
        auto c = constants_.find(id);
        if (c == constants_.end()) return false;
        const SpirvInstruction* s = &c->second;
        if (s->opcode == op::ConstantNull) return expected == 0.0f;
        if (s->opcode == op::ConstantComposite && s->words.size() > 2) {
            for (size_t k = 2; k < s->words.size(); ++k)
                if (!is_literal(s->words[k], expected)) return false;
            return true;
        }
        if (s->opcode != op::Constant) return false;
        float f;
        std::memcpy(&f, &s->words.at(2), 4);
        return f == expected;
    }

    void finish(AssemblyOutput& out) {
        std::vector<std::string> head;
        head.push_back(profile());
        for (auto& line : constant_table_comment()) head.push_back(std::move(line));
        for (const auto& [reg, text] : declarations_) head.push_back(text);
        static const char* kTypes[] = {"dcl_2d", "dcl_2d", "dcl_volume", "dcl_cube"};
        for (const auto& [s, dim] : samplers_used_)
            head.push_back(std::string(kTypes[std::min<uint32_t>(dim, 3)]) + " s" + std::to_string(s));
        for (size_t r = 0; r < defs_.size(); ++r) {
            const int reg = static_cast<int>(first_def_register_ + r);
            if (reg > (pixel_ ? 31 : 255)) {
                location_ = entry_location_;
                throw CompileError("uniforms and literals need more constant registers than " + profile() + " has");
            }
            head.push_back("def c" + std::to_string(reg) + ", " + format_float(defs_[r][0]) + ", " + format_float(defs_[r][1]) +
                           ", " + format_float(defs_[r][2]) + ", " + format_float(defs_[r][3]));
        }
        for (const auto& [count, reg] : integer_defs_)
            head.push_back("defi i" + std::to_string(reg) + ", " + std::to_string(count) + ", 0, 0, 0");
        for (const auto& h : head) {
            out.text += h + "\n";
            out.origin.push_back(entry_location_);
            out.line_origin.push_back({});
            out.line_file.push_back(std::string());
        }
        for (size_t k = 0; k < code_.size(); ++k) {
            out.text += code_[k] + "\n";
            out.origin.push_back(code_origin_[k]);
            const auto& [where, file] = code_line_[k];
            auto name = strings_.find(file);
            out.line_origin.push_back(where);
            out.line_file.push_back(name == strings_.end() || name->second.empty() ? options_.file_name : name->second);
        }
    }

    // The CTAB comment block as an assembler `comment` directive, eight DWORDs to a line.
    std::vector<std::string> constant_table_comment() const {
        isa::ConstantTable table;
        table.creator = kCreator;
        table.version = (pixel_ ? 0xFFFF0000u : 0xFFFE0000u) | 0x0200u;
        table.target = profile();
        table.constants = constants_table_;
        const std::vector<uint32_t> payload = isa::serialize_constant_table(table);
        std::vector<std::string> lines;
        for (size_t k = 0; k < payload.size(); k += 8) {
            std::string line = k == 0 ? "comment " : "        ";
            for (size_t j = k; j < std::min(k + 8, payload.size()); ++j) {
                char word[16];
                std::snprintf(word, sizeof word, "0x%08x", payload[j]);
                line += std::string(j > k ? ", " : "") + word;
            }
            if (k + 8 < payload.size()) line += ",";
            lines.push_back(std::move(line));
        }
        return lines;
    }

    const std::vector<uint32_t>& spirv_;
    std::string_view source_;
    const CompileOptions& options_;
    const bool pixel_;

    isa::SourceLocation location_{1, 1}, entry_location_{1, 1};
    uint32_t entry_function_ = 0;
    std::vector<uint32_t> interface_;
    std::unordered_map<uint32_t, std::map<uint32_t, uint32_t>> decorations_;
    std::unordered_map<uint32_t, std::map<uint32_t, std::set<uint32_t>>> member_decorations_;
    std::unordered_map<uint32_t, std::string> semantics_;
    std::unordered_map<uint32_t, Type> types_;
    std::unordered_map<uint32_t, SpirvInstruction> constants_;
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> variables_;  // id -> (pointer type, storage); ordered by id = declaration order
    std::vector<SpirvInstruction> body_;

    std::unordered_map<uint32_t, std::string> names_;
    std::map<std::pair<uint32_t, uint32_t>, std::string> member_names_;
    std::vector<isa::ConstantInfo> constants_table_;  // registers in declaration order, samplers
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> member_register_;
    std::map<uint32_t, int> sampler_of_;
    std::map<int, uint32_t> samplers_used_;
    uint32_t first_def_register_ = 0;
    std::vector<std::array<float, 4>> defs_;
    std::vector<uint32_t> def_used_;
    std::vector<bool> def_scalar_;

    // Flow control: blocks, uses, and what analyze_flow found.
    std::vector<uint32_t> block_of_;                          // per body_ position: its block's label
    std::unordered_map<uint32_t, size_t> label_position_, terminator_of_, defined_at_;
    std::unordered_map<uint32_t, std::vector<size_t>> uses_;  // id -> positions that read it
    std::unordered_map<size_t, std::vector<uint32_t>> incoming_uses_;  // branch position -> phi values it moves
    std::unordered_map<uint32_t, std::vector<std::pair<uint32_t, uint32_t>>> phi_incoming_;  // phi -> (value, block)
    std::unordered_map<uint32_t, std::vector<size_t>> phis_of_;  // block -> its phis' positions
    std::unordered_map<uint32_t, Value> phi_registers_;
    std::set<size_t> skip_;  // positions not translated (conditions and counters b#/i# replace)
    std::map<size_t, FlowBool> bool_conditions_;  // branch or select position -> its uniform bool
    std::unordered_map<uint32_t, size_t> code_after_;  // value id -> code_.size() after its instruction
    std::map<size_t, bool> kill_branches_;
    std::set<uint32_t> read_counters_;  // vs_2_0: loop counters read in their loop's body          // ps: branch to a lone OpKill -> kill on its false arm
    std::map<uint32_t, Loop> loops_;              // header label -> loop
    std::set<std::pair<uint32_t, uint32_t>> flow_bool_members_, flow_int_members_;
    std::map<std::pair<uint32_t, uint32_t>, std::string> flow_registers_;  // member -> "b0", "i0"
    std::map<int, int> integer_defs_;  // rolled loop count -> i# of its defi
    std::vector<Construct> open_;
    int static_flow_count_ = 0;
    size_t position_ = 0;

    std::unordered_map<uint32_t, Value> values_;
    std::unordered_map<uint32_t, size_t> last_use_;
    std::unordered_map<size_t, std::vector<uint32_t>> released_also_at_;  // extend_last_use
    std::set<uint32_t> fused_;
    std::unordered_map<uint32_t, std::pair<Value, Value>> fused_operands_;
    std::array<bool, kTempCount> temp_busy_{};
    std::map<int, int> temp_holders_;
    std::vector<int> scratch_;
    int max_temp_ = 0;
    std::array<int, 16> texture_level_{};      // ps: track_texture_level
    std::array<bool, 16> temp_written_{};

    std::map<std::string, std::string> declarations_;
    std::vector<std::string> code_;
    std::vector<isa::SourceLocation> code_origin_;
    // Per code_ line, for the line table: the OpLine in effect, or the last one before it when the
    // SPIR-V instruction has none (line 0: none yet), and its OpString id.
    std::vector<std::pair<isa::SourceLocation, uint32_t>> code_line_;
    std::unordered_map<uint32_t, std::string> strings_;  // OpString: file names
    isa::SourceLocation line_location_;
    uint32_t location_file_ = 0;
};

}  // namespace

AssemblyOutput spirv_to_assembly(const std::vector<uint32_t>& spirv, std::string_view source,
                                 const CompileOptions& options) {
    return Backend(spirv, source, options).run();
}

}  // namespace sm2::hlsl
