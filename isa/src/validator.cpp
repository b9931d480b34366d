// The validator: registers-and-limits.md §10, rules 2..19 (rule 1, the stream's shape, is the
// decoder's; rule 20, loop constants, is checked at draw time).
//
// Every check reads the ISA tables (OpcodeInfo, RegisterFile, Profile) rather than naming
// versions, so a new profile is new table rows. The few facts the tables do not carry are
// shader-type facts that hold for every SM2 profile and are named where they are used:
// which output a shader must write, that vertex inputs carry a usage while pixel inputs carry a
// component mask, and that vertex shaders take no result modifiers (_sat is vs_3_0).
//
// Order of work: rules 2/3 first decide, per instruction, whether its shape (opcode row,
// operand count and register kinds) can be trusted; every later rule looks only at
// instructions that passed, so a hand-built Program with a missing destination or too few
// sources produces one "operands" violation and never a crash or a cascade.
//
// Temp initialization (rule 7) and a0/aL use (rule 8) are one walk over the static flow:
//   * if/else/endif: a component is written after the block only if it is written on both
//     arms (an `if` without `else` has an empty arm): intersection.
//   * loop/rep bodies: the body is checked once with the state on entry (its first
//     iteration, the strictest); after the block the state is the entry state, because the
//     iteration count i#.x may be 0 (writes inside a loop do not count after it).
//   * call/callnz: the subroutine is analysed at each call site with the caller's state and
//     loop depth; after `call` the state is the routine's exit state, after `callnz` the
//     intersection of the exit state and the state before the call. A subroutine nobody calls
//     is dead code and is not walked. A violation inside a routine is reported once, at the
//     instruction inside the routine, naming the first call site that shows it.
//   * sgn's scratch temps (src1, src2) are neither read nor counted as written.
//   * Components read: component-wise ops read the swizzled channels of the write mask;
//     dp3/dp4/dp2add, matrix macros (every row), crs, nrm, lit, dst and the scalar ops read
//     what their formula uses; texld reads .xy (2D) or .xyz (cube, volume) of its coordinate,
//     plus .w for texldp/texldb; texkill reads all four components (instructions.md §10).
#include "sm2/isa/validator.h"

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace sm2::isa {

std::string_view rule_name(Rule rule) {
    switch (rule) {
    case Rule::Structure: return "structure";
    case Rule::OpcodeVersion: return "opcode-version";
    case Rule::Operands: return "operands";
    case Rule::SetupFirst: return "setup-first";
    case Rule::InputDeclared: return "input-declared";
    case Rule::SamplerDeclared: return "sampler-declared";
    case Rule::TempInitialized: return "temp-initialized";
    case Rule::AddressRegister: return "address-register";
    case Rule::RelativeAddressing: return "relative-addressing";
    case Rule::SourceModifiers: return "source-modifiers";
    case Rule::DestModifiers: return "dest-modifiers";
    case Rule::Swizzle: return "swizzle";
    case Rule::WriteMask: return "write-mask";
    case Rule::ReadPorts: return "read-ports";
    case Rule::InstructionOperands: return "instruction-operands";
    case Rule::SlotBudget: return "slot-budget";
    case Rule::DependentReads: return "dependent-reads";
    case Rule::FlowControl: return "flow-control";
    case Rule::Outputs: return "outputs";
    }
    return "unknown";
}

namespace {

constexpr uint8_t kX = 1, kY = 2, kZ = 4, kW = 8;

// D3DSINCOSCONST1 / D3DSINCOSCONST2 as float bits (bytecode.md §8).
constexpr std::array<uint32_t, 4> kSinCosConst1 = {0xB5D00D01u, 0xB7B60B61u, 0x3B2AAAABu,
                                                   0x39888889u};
constexpr std::array<uint32_t, 4> kSinCosConst2 = {0xBCAAAAABu, 0xBE000000u, 0x3F800000u,
                                                   0x3F000000u};

// ps_2_0 source swizzles when the profile has no arbitrary swizzle (registers-and-limits.md §5).
constexpr std::array<uint8_t, 8> kRestrictedSwizzles = {0xE4, 0x00, 0x55, 0xAA,
                                                        0xFF, 0xC9, 0xD2, 0x1B};

std::string mask_text(uint8_t mask) {
    std::string s = ".";
    for (int c = 0; c < 4; ++c)
        if (mask & (1u << c)) s += "xyzw"[c];
    return s == "." ? std::string(".<none>") : s;
}

std::string swizzle_text(uint8_t swizzle) {
    std::string s = ".";
    for (int c = 0; c < 4; ++c) s += "xyzw"[swizzle_component(swizzle, c)];
    return s;
}

// Register components read when the channels `channels` of a source are used.
uint8_t swizzled(uint8_t channels, uint8_t swizzle) {
    uint8_t out = 0;
    for (int c = 0; c < 4; ++c)
        if (channels & (1u << c)) out |= static_cast<uint8_t>(1u << swizzle_component(swizzle, c));
    return out;
}

uint8_t first_channels(unsigned n) { return static_cast<uint8_t>((1u << n) - 1u); }

std::string_view modifier_text(SourceModifier m) {
    switch (m) {
    case SourceModifier::None: return "none";
    case SourceModifier::Negate: return "negate";
    case SourceModifier::Bias: return "_bias";
    case SourceModifier::BiasNegate: return "-_bias";
    case SourceModifier::Sign: return "_bx2";
    case SourceModifier::SignNegate: return "-_bx2";
    case SourceModifier::Complement: return "1-";
    case SourceModifier::X2: return "_x2";
    case SourceModifier::X2Negate: return "-_x2";
    case SourceModifier::DivideZ: return "_dz";
    case SourceModifier::DivideW: return "_dw";
    case SourceModifier::Abs: return "_abs";
    case SourceModifier::AbsNegate: return "-_abs";
    case SourceModifier::Not: return "! (not)";
    }
    return "unknown";
}

std::string_view kind_text(SourceKind k) {
    switch (k) {
    case SourceKind::None: return "nothing";
    case SourceKind::Value: return "a value register (r#, v#, c#, t#)";
    case SourceKind::Sampler: return "a sampler s#";
    case SourceKind::Label: return "a label l#";
    case SourceKind::Bool: return "a boolean constant b#";
    case SourceKind::Int: return "an integer constant i#";
    case SourceKind::LoopCounter: return "the loop counter aL";
    case SourceKind::Predicate: return "the predicate p0";
    }
    return "?";
}

struct RegKey {
    RegisterType type;
    uint16_t index;
    friend auto operator<=>(const RegKey&, const RegKey&) = default;
};

// One register read by an instruction, with the components it reads.
struct Read {
    RegisterType type;
    uint16_t index;
    uint8_t components;
};

// Static-flow state for rules 7 and 8: written components of each temp and of a0.
struct InitState {
    std::vector<uint8_t> temps;
    uint8_t a0 = 0;
    void meet(const InitState& o) {  // intersection: written on both paths
        for (size_t k = 0; k < temps.size(); ++k) temps[k] &= o.temps[k];
        a0 &= o.a0;
    }
};

class Validator {
public:
    Validator(const Program& program, const Profile& profile, const ValidationOptions& options)
        : program_(program), profile_(profile), version_(program.version), options_(options),
          ok_(program.instructions.size(), false) {}

    std::vector<Violation> run() {
        for (size_t i = 0; i < size(); ++i) ok_[i] = check_shape(i);
        check_setup_order();
        collect_declarations();
        for (size_t i = 0; i < size(); ++i) {
            if (!ok_[i]) continue;
            check_declared_reads(i);
            check_relative_addressing(i);
            check_source_modifiers(i);
            check_dest_modifiers(i);
            check_swizzles(i);
            check_write_mask(i);
            check_read_ports(i);
            check_instruction_operands(i);
        }
        check_slot_budget();
        check_dependent_reads();
        check_flow_control();
        check_initialization();
        check_outputs();
        return finish();
    }

private:
    // ---- plumbing ------------------------------------------------------------------------
    size_t size() const { return program_.instructions.size(); }
    const Instruction& at(size_t i) const { return program_.instructions[i]; }
    const OpcodeInfo& info(size_t i) const { return *at(i).info(); }  // only when ok_[i]
    bool is_comment(size_t i) const { return at(i).opcode == Opcode::Comment; }

    std::string mnemonic(size_t i) const {
        if (const OpcodeInfo* row = at(i).info()) return std::string(row->mnemonic);
        return "opcode " + std::to_string(static_cast<unsigned>(at(i).opcode));
    }

    void report(Rule rule, size_t i, const std::string& message) {
        Violation v{rule, message, i, {}};
        if (i < size()) {
            v.message = mnemonic(i) + ": " + message;
            v.location = at(i).location;
        }
        out_.push_back(std::move(v));
    }

    std::vector<Violation> finish() {
        // Drop exact repeats, then order by instruction (whole-program findings last); within
        // one instruction the order is the order of the checks.
        std::set<std::tuple<Rule, size_t, std::string>> seen;
        std::vector<Violation> unique;
        for (auto& v : out_)
            if (seen.insert({v.rule, v.instruction, v.message}).second) unique.push_back(std::move(v));
        std::stable_sort(unique.begin(), unique.end(), [](const Violation& a, const Violation& b) {
            return a.instruction < b.instruction;
        });
        return unique;
    }

    // The register file holding `type` (and, for fixed registers, number `index`), ignoring
    // whether a numbered index is in range.
    const RegisterFile* file_of(RegisterType type, uint32_t index) const {
        for (const RegisterFile& f : register_files()) {
            if (f.shader != version_.type || f.type != type ||
                !f.versions.contains(version_.number()))
                continue;
            if (f.numbered || f.first == index) return &f;
        }
        return nullptr;
    }
    std::string name(RegisterType type, uint32_t index) const {
        if (const RegisterFile* f = file_of(type, index))
            return std::string(f->name) + (f->numbered ? std::to_string(index) : "");
        return "register type " + std::to_string(static_cast<unsigned>(type)) + " #" +
               std::to_string(index);
    }
    std::string name(const SourceParameter& s) const { return name(s.type, s.index); }
    std::string name(const DestinationParameter& d) const { return name(d.type, d.index); }

    // Type 3 is a0 in a vertex shader and t# in a pixel shader.
    bool is_address(RegisterType t) const { return t == RegisterType::Address && version_.is_vertex(); }
    bool is_texcoord(RegisterType t) const { return t == RegisterType::Texture && version_.is_pixel(); }

    static bool same_register(const DestinationParameter& d, const SourceParameter& s) {
        return !s.relative && d.type == s.type && d.index == s.index;
    }

    uint16_t temp_count() const {
        const RegisterFile* f = file_of(RegisterType::Temp, 0);
        return f ? f->count : 0;
    }

    // ---- rules 2 and 3: opcode and operand shape -----------------------------------------

    // True when the register exists in this profile and `index` is within its documented
    // count (RegisterFile::count: r12 in ps_2_0 or i0 in ps_2_0 are out of range).
    bool check_register(size_t i, const std::string& role, RegisterType type, uint32_t index) {
        const RegisterFile* f = file_of(type, index);
        if (!f) {
            report(Rule::Operands, i, role + ": " + name(type, index) + " does not exist in " +
                                          version_.name());
            return false;
        }
        if (f->count == 0) {
            report(Rule::Operands, i, role + ": " + std::string(f->name) + "# registers do not exist in " +
                                          version_.name());
            return false;
        }
        if (f->numbered && (index < f->first || index >= f->first + f->count)) {
            report(Rule::Operands, i,
                   role + ": " + name(type, index) + " is out of range (" + std::string(f->name) +
                       std::to_string(f->first) + ".." + std::string(f->name) +
                       std::to_string(f->first + f->count - 1) + " in " + version_.name() + ")");
            return false;
        }
        return true;
    }

    bool check_dest_kind(size_t i, DestKind kind, const DestinationParameter& d) {
        const RegisterFile* f = file_of(d.type, d.index);
        bool good = false;
        std::string want;
        switch (kind) {
        case DestKind::None: return true;
        case DestKind::Value:
            good = f && f->writable && !is_address(d.type);
            want = "a writable register (r# or an output)";
            if (is_address(d.type)) want += "; a0 is written only by mova";
            break;
        case DestKind::Temp:
            good = d.type == RegisterType::Temp;
            want = "a temporary register r#";
            break;
        case DestKind::Address:
            good = is_address(d.type);
            want = "the address register a0";
            break;
        case DestKind::Tested:
            good = d.type == RegisterType::Temp || is_texcoord(d.type);
            want = "a texture coordinate t# or a temporary r#";
            break;
        }
        if (!good) report(Rule::Operands, i, "destination must be " + want + ", got " + name(d));
        return good;
    }

    bool check_source_kind(size_t i, size_t k, SourceKind kind, const SourceParameter& s) {
        const RegisterFile* f = file_of(s.type, s.index);
        bool good = false;
        switch (kind) {
        case SourceKind::None: good = false; break;
        case SourceKind::Value:
            good = f && f->readable &&
                   (s.type == RegisterType::Temp || s.type == RegisterType::Input ||
                    s.type == RegisterType::Const || is_texcoord(s.type));
            break;
        case SourceKind::Sampler: good = s.type == RegisterType::Sampler; break;
        case SourceKind::Label: good = s.type == RegisterType::Label; break;
        case SourceKind::Bool: good = s.type == RegisterType::ConstBool; break;
        case SourceKind::Int: good = s.type == RegisterType::ConstInt; break;
        case SourceKind::LoopCounter: good = s.type == RegisterType::Loop; break;
        case SourceKind::Predicate: good = s.type == RegisterType::Predicate; break;
        }
        if (!good)
            report(Rule::Operands, i, "source " + std::to_string(k) + " must be " +
                                          std::string(kind_text(kind)) + ", got " + name(s));
        return good;
    }

    bool check_shape(size_t i) {
        const Instruction& ins = at(i);
        if (ins.opcode == Opcode::Comment) return false;
        const OpcodeInfo* row = ins.info();
        if (!row) {
            report(Rule::OpcodeVersion, i, "unknown opcode (control " +
                                               std::to_string(ins.control) + ")");
            return false;
        }
        if (!row->allowed_in(version_)) {
            report(Rule::OpcodeVersion, i, "not available in " + version_.name());
            return false;
        }
        bool good = true;
        // The predicate token is read by no other rule, so a misplaced one leaves the rest of
        // the instruction checkable.
        if (ins.predicate && !file_of(RegisterType::Predicate, 0))
            report(Rule::Operands, i, "predication is not available in " + version_.name());
        if (row->layout != OperandLayout::Standard) return check_setup_shape(i, *row) && good;

        if (row->has_dest() != ins.dest.has_value()) {
            report(Rule::Operands, i, row->has_dest() ? "missing destination" : "takes no destination");
            return false;
        }
        if (ins.dest) {
            good = check_register(i, "destination", ins.dest->type, ins.dest->index) &&
                   check_dest_kind(i, row->dest, *ins.dest) && good;
        }
        const size_t n = ins.sources.size();
        if (n >= row->min_sources && n < row->num_sources) {
            // A short form some assembler writes (Wine's one-source ps sincos): not the
            // documented form of this profile.
            report(Rule::InstructionOperands, i,
                   "the " + std::to_string(n) + "-source form is not valid in " + version_.name() +
                       "; the documented form has " + std::to_string(row->num_sources) + " sources");
            return false;
        }
        if (n != row->num_sources) {
            report(Rule::Operands, i, "has " + std::to_string(n) + " source(s), needs " +
                                          std::to_string(row->num_sources));
            return false;
        }
        for (size_t k = 0; k < n; ++k) {
            const SourceParameter& s = ins.sources[k];
            const std::string role = "source " + std::to_string(k);
            if (!check_register(i, role, s.type, s.index)) { good = false; continue; }
            if (!check_source_kind(i, k, row->sources[k], s)) { good = false; continue; }
            if (k == 1 && row->matrix_rows > 0) {
                const RegisterFile* f = file_of(s.type, s.index);
                const unsigned last = s.index + row->matrix_rows - 1u;
                if (f && f->numbered && last >= f->first + f->count) {
                    report(Rule::Operands, i, "matrix rows " + name(s) + ".." + name(s.type, last) +
                                                  " run past the end of the register file");
                    good = false;
                }
            }
        }
        return good;
    }

    bool check_setup_shape(size_t i, const OpcodeInfo& row) {
        const Instruction& ins = at(i);
        if (!ins.dest) {
            report(Rule::Operands, i, "missing the register it declares or defines");
            return false;
        }
        if (!ins.sources.empty()) {
            report(Rule::Operands, i, "takes no source operands");
            return false;
        }
        const DestinationParameter& d = *ins.dest;
        if (!check_register(i, "register", d.type, d.index)) return false;
        bool good = true;
        switch (row.layout) {
        case OperandLayout::Declaration: {
            const RegisterFile* f = file_of(d.type, d.index);
            good = f && f->needs_declaration;
            if (!good)
                report(Rule::Operands, i, name(d) + " cannot be declared in " + version_.name());
            break;
        }
        case OperandLayout::FloatDef: good = d.type == RegisterType::Const; break;
        case OperandLayout::IntDef: good = d.type == RegisterType::ConstInt; break;
        case OperandLayout::BoolDef: good = d.type == RegisterType::ConstBool; break;
        case OperandLayout::Standard: break;
        }
        if (!good && row.layout != OperandLayout::Declaration)
            report(Rule::Operands, i, "cannot define " + name(d));
        return good;
    }

    // ---- rule 4: dcl/def before the first executable instruction -------------------------
    void check_setup_order() {
        std::optional<size_t> first;
        for (size_t i = 0; i < size(); ++i) {
            if (is_comment(i) || !at(i).info()) continue;
            if (!at(i).is_setup()) {
                if (!first) first = i;
            } else if (first) {
                report(Rule::SetupFirst, i,
                       "declarations and definitions must come before the first instruction (" +
                           mnemonic(*first) + " at " + std::to_string(*first) + ")");
            }
        }
    }

    // ---- rules 5 and 6: declarations -----------------------------------------------------
    void collect_declarations() {
        std::map<std::pair<DeclUsage, uint8_t>, size_t> usages;
        for (size_t i = 0; i < size(); ++i) {
            if (!ok_[i]) continue;
            const Instruction& ins = at(i);
            const DestinationParameter& d = *ins.dest;
            if (ins.opcode == Opcode::Def) {
                float_defs_[d.index] = ins.constant_bits;  // the last definition wins
                continue;
            }
            if (ins.opcode != Opcode::Dcl) continue;
            const Declaration& decl = ins.declaration;
            if (d.type == RegisterType::Sampler) {
                const TextureType t = decl.texture_type;
                if (t != TextureType::Texture2D && t != TextureType::Cube && t != TextureType::Volume)
                    report(Rule::SamplerDeclared, i,
                           name(d) + " needs a known texture type (dcl_2d, dcl_cube or dcl_volume)");
                if (!samplers_.emplace(d.index, t).second)
                    report(Rule::SamplerDeclared, i, name(d) + " is declared twice");
                continue;
            }
            if (!inputs_.emplace(RegKey{d.type, d.index}, d.write_mask).second)
                report(Rule::InputDeclared, i, name(d) + " is declared twice");
            if (version_.is_vertex()) {  // vertex inputs carry a usage (bytecode.md §7.1)
                if (static_cast<uint8_t>(decl.usage) > kMaxDeclUsage || decl.usage_index > 15)
                    report(Rule::InputDeclared, i, "unknown usage " +
                                                       std::to_string(static_cast<unsigned>(decl.usage)) +
                                                       " index " + std::to_string(decl.usage_index));
                else if (auto [it, fresh] = usages.emplace(std::pair{decl.usage, decl.usage_index}, i);
                         !fresh)
                    report(Rule::InputDeclared, i, "usage " +
                                                       std::to_string(static_cast<unsigned>(decl.usage)) +
                                                       " index " + std::to_string(decl.usage_index) +
                                                       " is already declared at instruction " +
                                                       std::to_string(it->second));
            } else if (decl.usage != DeclUsage::Position || decl.usage_index != 0 ||
                       decl.texture_type != TextureType::Unknown) {
                // pixel inputs of SM2 carry only a mask (bytecode.md §7.2)
                report(Rule::InputDeclared, i, name(d) + ": " + version_.name() +
                                                   " input declarations take no usage");
            }
        }
    }

    std::optional<TextureType> sampler_type(uint16_t index) const {
        auto it = samplers_.find(index);
        if (it == samplers_.end()) return std::nullopt;
        return it->second;
    }

    // Channels (before swizzling) of source `k` that instruction i uses.
    uint8_t channels_used(size_t i, size_t k) const {
        const Instruction& ins = at(i);
        const OpcodeInfo& row = info(i);
        const uint8_t mask = ins.dest ? ins.dest->write_mask : kMaskAll;
        if ((row.replicate_sources >> k) & 1u) return kX;
        if (row.matrix_rows > 0) return first_channels(row.matrix_columns);
        switch (ins.opcode) {
        case Opcode::Tex: {
            if (k != 0) return 0;
            // 2D: .xy; cube and volume: .xyz; texldp/texldb also read .w (instructions.md §10)
            const auto type = sampler_type(ins.sources[1].index).value_or(TextureType::Texture2D);
            uint8_t c = (type == TextureType::Cube || type == TextureType::Volume) ? kX | kY | kZ
                                                                                   : kX | kY;
            if (ins.control != kTexLdPlain) c |= kW;
            return c;
        }
        case Opcode::Dp3: return kX | kY | kZ;
        case Opcode::Dp4: return kMaskAll;
        case Opcode::Dp2Add: return kX | kY;
        case Opcode::Crs: return kX | kY | kZ;
        case Opcode::Nrm: return static_cast<uint8_t>(kX | kY | kZ | mask);
        case Opcode::SinCos: return k == 0 ? kX : kMaskAll;
        case Opcode::Sgn: return k == 0 ? mask : 0;  // src1/src2 are scratch, not read
        case Opcode::Lit:  // r.y needs s.x; r.z needs s.x, s.y, s.w
            return static_cast<uint8_t>(((mask & (kY | kZ)) ? kX : 0) | ((mask & kZ) ? kY | kW : 0));
        case Opcode::Dst:  // r = (1, a.y*b.y, a.z, b.w)
            return static_cast<uint8_t>(((mask & kY) ? kY : 0) |
                                        (k == 0 ? ((mask & kZ) ? kZ : 0) : ((mask & kW) ? kW : 0)));
        default: return mask;  // component-wise: channel c feeds result channel c
        }
    }

    // Value registers instruction i reads, with components (after swizzle); matrix rows and
    // texkill's tested register included. Samplers, labels, b#, i#, aL are not listed.
    std::vector<Read> reads_of(size_t i) const {
        const Instruction& ins = at(i);
        const OpcodeInfo& row = info(i);
        std::vector<Read> reads;
        if (ins.opcode == Opcode::TexKill) {
            reads.push_back({ins.dest->type, ins.dest->index, ins.dest->write_mask});
            return reads;
        }
        for (size_t k = 0; k < ins.sources.size(); ++k) {
            if (row.sources[k] != SourceKind::Value) continue;
            const SourceParameter& s = ins.sources[k];
            const uint8_t comps = swizzled(channels_used(i, k), s.swizzle);
            if (comps == 0) continue;
            const unsigned rows = (k == 1 && row.matrix_rows > 0) ? row.matrix_rows : 1u;
            for (unsigned r = 0; r < rows; ++r)
                reads.push_back({s.type, static_cast<uint16_t>(s.index + r), comps});
        }
        return reads;
    }

    void check_declared_reads(size_t i) {
        const Instruction& ins = at(i);
        for (const Read& r : reads_of(i)) {
            const RegisterFile* f = file_of(r.type, r.index);
            if (!f || !f->needs_declaration) continue;
            auto it = inputs_.find(RegKey{r.type, r.index});
            if (it == inputs_.end()) {
                report(Rule::InputDeclared, i, name(r.type, r.index) + " is read but not declared");
            } else if (r.components & ~it->second) {
                report(Rule::InputDeclared, i,
                       "reads " + name(r.type, r.index) + mask_text(r.components & ~it->second) +
                           " but the dcl declares only " + mask_text(it->second));
            }
        }
        for (const SourceParameter& s : ins.sources)
            if (s.type == RegisterType::Sampler && !sampler_type(s.index))
                report(Rule::SamplerDeclared, i, "sampler " + name(s) + " is not declared");
    }

    // ---- rule 9: relative addressing -----------------------------------------------------
    void check_relative_addressing(size_t i) {
        for (const SourceParameter& s : at(i).sources) {
            if (!s.relative) continue;
            const std::string what = name(s) + "[...]";
            if (!profile_.relative_addressing) {
                report(Rule::RelativeAddressing, i,
                       "relative addressing is not available in " + version_.name());
                continue;
            }
            const RegisterFile* f = file_of(s.type, s.index);
            if (!f || !f->relative_addressing) {
                report(Rule::RelativeAddressing, i,
                       "relative addressing is only allowed on constant registers c#, got " + what);
                continue;
            }
            const RelativeAddress& rel = *s.relative;
            if (is_address(rel.type)) {
                if (!is_replicate_swizzle(rel.swizzle))
                    report(Rule::RelativeAddressing, i,
                           "the index a0 must name one component (a0.x, a0.y, a0.z or a0.w), got a0" +
                               swizzle_text(rel.swizzle));
            } else if (rel.type == RegisterType::Loop && file_of(RegisterType::Loop, 0)) {
                if (rel.swizzle != kSwizzleIdentity)
                    report(Rule::RelativeAddressing, i, "the index aL takes no component");
            } else {
                report(Rule::RelativeAddressing, i, "the index of " + what + " must be a0.c or aL, got " +
                                                        name(rel.type, 0));
            }
        }
    }

    // ---- rule 10: source modifiers -------------------------------------------------------
    void check_source_modifiers(size_t i) {
        const Instruction& ins = at(i);
        const OpcodeInfo& row = info(i);
        const bool plain_write = ins.dest && (ins.dest->type == RegisterType::ColorOut ||
                                              ins.dest->type == RegisterType::DepthOut);
        for (size_t k = 0; k < ins.sources.size(); ++k) {
            const SourceParameter& s = ins.sources[k];
            const SourceModifier m = s.modifier;
            if (m == SourceModifier::None) continue;
            const SourceKind kind = row.sources[k];
            const std::string which = "source " + std::to_string(k) + " (" + name(s) + ")";
            if (m == SourceModifier::Not) {
                if (kind != SourceKind::Bool)
                    report(Rule::SourceModifiers, i, "! (not) is only allowed on a b# condition, not on " + which);
                continue;
            }
            if (m != SourceModifier::Negate) {
                report(Rule::SourceModifiers, i, "source modifier " + std::string(modifier_text(m)) +
                                                     " on " + which + " is not available in " +
                                                     version_.name() + " (only negate)");
                continue;
            }
            if (kind != SourceKind::Value)
                report(Rule::SourceModifiers, i, which + " cannot be negated");
            else if (k == 1 && row.matrix_rows > 0)
                report(Rule::SourceModifiers, i, "the matrix source (source 1) cannot be negated");
            else if (row.category == Category::Texture)
                report(Rule::SourceModifiers, i, "texture instruction operands take no modifier");
            else if (plain_write)
                report(Rule::SourceModifiers, i, "the source of a write to " + name(*ins.dest) +
                                                     " takes no modifier");
        }
    }

    // ---- rule 11: destination modifiers --------------------------------------------------
    void check_dest_modifiers(size_t i) {
        const Instruction& ins = at(i);
        if (!ins.dest) return;
        const DestinationParameter& d = *ins.dest;
        if (d.shift != 0) report(Rule::DestModifiers, i, "result shifts are not available in " + version_.name());
        const bool pixel = version_.is_pixel();  // vs_2_0/vs_2_x take no result modifier
        auto forbid = [&](bool set, const char* mod, const std::string& why) {
            if (set) report(Rule::DestModifiers, i, std::string(mod) + " " + why);
        };
        if (ins.opcode == Opcode::Dcl) {
            // ps inputs take _pp, t# also _centroid (v# is always centroid-sampled); vertex
            // inputs and samplers take nothing.
            const bool pixel_input = pixel && d.type != RegisterType::Sampler;
            const std::string where = "is not allowed on dcl of " + name(d);
            forbid(d.saturate, "_sat", where);
            forbid(d.partial_precision && !pixel_input, "_pp", where);
            forbid(d.centroid && !(pixel_input && is_texcoord(d.type)), "_centroid", where);
            return;
        }
        if (ins.is_setup()) {
            forbid(d.saturate || d.partial_precision || d.centroid, "a result modifier",
                   "is not allowed on a constant definition");
            return;
        }
        if (!pixel) {
            const std::string where = "is not available in " + version_.name();
            forbid(d.saturate, "_sat", where);
            forbid(d.partial_precision, "_pp", where);
            forbid(d.centroid, "_centroid", where);
            return;
        }
        forbid(d.centroid, "_centroid", "is only allowed on dcl");
        const bool output = d.type == RegisterType::ColorOut || d.type == RegisterType::DepthOut;
        if (output) forbid(d.saturate, "_sat", "is not allowed on a write to " + name(d));
        else if (ins.opcode == Opcode::Frc || ins.opcode == Opcode::SinCos ||
                 info(i).category == Category::Texture)
            forbid(d.saturate, "_sat", "is not allowed on " + mnemonic(i));
        if (d.type == RegisterType::ColorOut)
            forbid(d.partial_precision, "_pp", "is not allowed on a write to " + name(d));
    }

    // ---- rule 12: swizzles ---------------------------------------------------------------
    void check_swizzles(size_t i) {
        const Instruction& ins = at(i);
        const OpcodeInfo& row = info(i);
        if (row.layout != OperandLayout::Standard) return;
        const bool to_color = ins.dest && ins.dest->type == RegisterType::ColorOut;
        const bool to_depth = ins.dest && ins.dest->type == RegisterType::DepthOut;
        for (size_t k = 0; k < ins.sources.size(); ++k) {
            const SourceParameter& s = ins.sources[k];
            const SourceKind kind = row.sources[k];
            const std::string which = "source " + std::to_string(k) + " (" + name(s) +
                                      swizzle_text(s.swizzle) + ")";
            auto need = [&](bool good, const std::string& what) {
                if (!good) report(Rule::Swizzle, i, which + " " + what);
            };
            const bool identity = s.swizzle == kSwizzleIdentity;
            if (kind == SourceKind::Sampler || kind == SourceKind::LoopCounter) {
                need(identity, "takes no swizzle");
            } else if (kind != SourceKind::Value) {
                continue;  // l#, b#, i#: only type and number carry meaning
            } else if ((row.replicate_sources >> k) & 1u) {
                need(is_replicate_swizzle(s.swizzle), "needs a replicate swizzle (.x, .y, .z or .w)");
            } else if (row.category == Category::Texture) {
                need(identity, "of a texture instruction takes no swizzle");
            } else if (ins.opcode == Opcode::Crs) {
                need(identity, "of crs takes no swizzle");
            } else if (k == 1 && row.matrix_rows > 0) {
                need(identity, "is the matrix and takes no swizzle");
            } else if (ins.opcode == Opcode::SinCos && k > 0) {
                continue;  // the constants: rule 15
            } else if (to_color) {
                need(identity, "of a write to oC# takes no swizzle");
            } else if (to_depth) {
                need(is_replicate_swizzle(s.swizzle), "of a write to oDepth needs a replicate swizzle");
            } else if (!profile_.arbitrary_swizzle) {
                need(std::find(kRestrictedSwizzles.begin(), kRestrictedSwizzles.end(), s.swizzle) !=
                         kRestrictedSwizzles.end(),
                     "is not one of the swizzles " + version_.name() +
                         " allows (.xyzw .x .y .z .w .yzxw .zxyw .wzyx)");
            }
        }
    }

    // ---- rule 13: write masks ------------------------------------------------------------
    void check_write_mask(size_t i) {
        const Instruction& ins = at(i);
        if (!ins.dest) return;
        const OpcodeInfo& row = info(i);
        const DestinationParameter& d = *ins.dest;
        const uint8_t m = d.write_mask & kMaskAll;
        auto need = [&](bool good, const std::string& what) {
            if (!good) report(Rule::WriteMask, i, what + ", got " + name(d) + mask_text(m));
        };
        if (m == 0) {
            report(Rule::WriteMask, i, "empty write mask on " + name(d));
            return;
        }
        if (ins.opcode == Opcode::Dcl) {
            if (d.type == RegisterType::Sampler) need(m == kMaskAll, "a sampler dcl takes the full mask");
            return;
        }
        if (ins.is_setup()) {
            need(m == kMaskAll, "a constant definition takes the full mask");
            return;
        }
        const RegisterFile* f = file_of(d.type, d.index);
        if (ins.opcode == Opcode::TexKill) need(m == kMaskAll, "texkill takes the full mask");
        else if (row.category == Category::Texture) need(m == kMaskAll, "the destination needs the full mask .xyzw");
        else if (ins.opcode == Opcode::SinCos)
            need(m == kX || m == kY || m == (kX | kY), "the mask must be .x, .y or .xy");
        else if (ins.opcode == Opcode::Crs)
            need((m & kW) == 0, "the mask must be one of .x .y .z .xy .xz .yz .xyz");
        else if (row.matrix_rows > 0)
            need(m == first_channels(row.matrix_rows),
                 "the mask must be " + mask_text(first_channels(row.matrix_rows)));
        if (d.type == RegisterType::ColorOut) need(m == kMaskAll, "oC# takes the full mask");
        else if (d.type == RegisterType::DepthOut || (f && f->scalar))
            need(m == kMaskAll, name(d) + " takes no write mask");
    }

    // ---- rule 14: read ports -------------------------------------------------------------
    void check_read_ports(size_t i) {
        const Instruction& ins = at(i);
        std::map<RegisterType, std::set<std::tuple<uint16_t, int, uint8_t>>> distinct;
        std::map<RegisterType, unsigned> index_reads;
        for (const SourceParameter& s : ins.sources) {
            // A relative c# is its own register: c[a0.x + 5] may or may not be c5.
            const int rel = s.relative ? 1 + static_cast<int>(s.relative->type) : 0;
            distinct[s.type].insert({s.index, rel, s.relative ? s.relative->swizzle : 0});
            if (s.relative) ++index_reads[s.relative->type];
        }
        for (const auto& [type, regs] : distinct) {
            const RegisterFile* f = file_of(type, std::get<0>(*regs.begin()));
            if (!f || f->read_ports == 0 || regs.size() <= f->read_ports) continue;
            std::string list;
            for (const auto& r : regs) list += (list.empty() ? "" : ", ") + name(type, std::get<0>(r));
            report(Rule::ReadPorts, i, "reads " + std::to_string(regs.size()) + " different " +
                                           std::string(f->name) + "# registers (" + list +
                                           "); at most " + std::to_string(f->read_ports) +
                                           " per instruction");
        }
        for (const auto& [type, count] : index_reads) {
            const RegisterFile* f = file_of(type, 0);
            if (f && f->read_ports > 0 && count > f->read_ports)
                report(Rule::ReadPorts, i, "uses " + std::string(f->name) + " as an index " +
                                               std::to_string(count) + " times; at most " +
                                               std::to_string(f->read_ports));
        }
    }

    // ---- rule 15: instruction-specific operand rules -------------------------------------
    void check_instruction_operands(size_t i) {
        const Instruction& ins = at(i);
        const OpcodeInfo& row = info(i);
        if (row.layout != OperandLayout::Standard) return;
        auto dest_not = [&](size_t k, const char* what) {
            if (same_register(*ins.dest, ins.sources[k]))
                report(Rule::InstructionOperands, i, "the destination " + name(*ins.dest) +
                                                         " must not be " + what);
        };
        switch (ins.opcode) {
        case Opcode::SinCos: check_sincos_constants(i); break;
        case Opcode::Crs:
            dest_not(0, "source 0");
            dest_not(1, "source 1");
            break;
        case Opcode::Nrm: dest_not(0, "the source"); break;
        case Opcode::Pow:  // instructions.md §5: dest a temp, not the same register as src1
            if (ins.dest->type != RegisterType::Temp)
                report(Rule::InstructionOperands, i,
                       "the destination must be a temporary register r#, got " + name(*ins.dest));
            dest_not(1, "source 1 (the exponent)");
            break;
        case Opcode::Sgn: {
            const SourceParameter& t1 = ins.sources[1];
            const SourceParameter& t2 = ins.sources[2];
            if (t1.type != RegisterType::Temp || t2.type != RegisterType::Temp || t1.relative || t2.relative)
                report(Rule::InstructionOperands, i, "sources 1 and 2 must be scratch temporaries r#, got " +
                                                         name(t1) + " and " + name(t2));
            else if (t1.index == t2.index)
                report(Rule::InstructionOperands, i,
                       "the scratch temporaries (sources 1 and 2) must be different, got " +
                           name(t1) + " twice");
            break;
        }
        case Opcode::Tex: {
            const SourceParameter& c = ins.sources[0];
            if (c.type != RegisterType::Temp && !is_texcoord(c.type))
                report(Rule::InstructionOperands, i,
                       "the coordinate (source 0) must be t# or r#, got " + name(c));
            break;
        }
        default: break;
        }
        if (row.matrix_rows > 0) {
            dest_not(0, "source 0");
            const SourceParameter& m = ins.sources[1];
            const DestinationParameter& d = *ins.dest;
            if (d.type == m.type && d.index >= m.index && d.index < m.index + row.matrix_rows)
                report(Rule::InstructionOperands, i, "the destination " + name(d) +
                                                         " must not be one of the matrix rows " +
                                                         name(m) + ".." +
                                                         name(m.type, m.index + row.matrix_rows - 1u));
        }
    }

    void check_sincos_constants(size_t i) {
        const Instruction& ins = at(i);
        const SourceParameter& s1 = ins.sources[1];
        const SourceParameter& s2 = ins.sources[2];
        bool plain = true;
        for (const SourceParameter* s : {&s1, &s2}) {
            if (s->type != RegisterType::Const || s->relative || s->modifier != SourceModifier::None ||
                s->swizzle != kSwizzleIdentity) {
                report(Rule::InstructionOperands, i,
                       "sources 1 and 2 must be plain constant registers c# (no index, modifier "
                       "or swizzle), got " + name(*s));
                plain = false;
            }
        }
        if (!plain) return;
        if (s1.index == s2.index) {
            report(Rule::InstructionOperands, i,
                   "sources 1 and 2 must be two different constant registers, got " + name(s1) + " twice");
            return;
        }
        const std::pair<const SourceParameter*, const std::array<uint32_t, 4>*> expect[] = {
            {&s1, &kSinCosConst1}, {&s2, &kSinCosConst2}};
        for (const auto& [s, bits] : expect) {
            auto it = float_defs_.find(s->index);
            if (it != float_defs_.end() && it->second != *bits)
                report(Rule::InstructionOperands, i,
                       name(*s) + " is defined in the shader but does not hold " +
                           (bits == &kSinCosConst1 ? "D3DSINCOSCONST1" : "D3DSINCOSCONST2"));
        }
    }

    // ---- rule 16: instruction slots ------------------------------------------------------
    void check_slot_budget() {
        unsigned total = 0, arithmetic = 0, texture = 0;
        bool total_over = false, arithmetic_over = false, texture_over = false;
        const bool override_total = options_.max_instruction_slots != 0;
        const unsigned total_limit =
            override_total ? options_.max_instruction_slots : profile_.max_instruction_slots;
        for (size_t i = 0; i < size(); ++i) {
            const SlotCount slots = instruction_slots(version_, at(i));
            if (slots.total == 0) continue;
            total += slots.total;
            arithmetic += slots.arithmetic;
            texture += slots.texture;
            auto over = [&](bool& flag, unsigned used, unsigned limit, const char* kind) {
                if (flag || used <= limit) return;
                flag = true;
                report(Rule::SlotBudget, i, "uses " + std::string(kind) + " instruction slot " +
                                                std::to_string(used) + "; the limit is " +
                                                std::to_string(limit));
            };
            over(total_over, total, total_limit, "total");
            // An explicit total replaces the per-class budgets. A profile whose arithmetic
            // budget is the whole budget (vs) has one budget; ps_2_0 splits it 64 + 32.
            if (!override_total && profile_.max_arithmetic_slots < profile_.max_instruction_slots) {
                over(arithmetic_over, arithmetic, profile_.max_arithmetic_slots, "arithmetic");
                over(texture_over, texture, profile_.max_texture_slots, "texture");
            }
        }
    }

    // ---- rule 17: dependent texture reads (instructions.md §10 tracking rule) ------------
    void check_dependent_reads() {
        const unsigned limit = profile_.max_dependent_read_order;
        if (limit == kUnlimited8) return;
        std::vector<int> level(temp_count(), -1);
        std::vector<bool> written(temp_count(), false);
        for (size_t i = 0; i < size(); ++i) {
            if (!ok_[i] || at(i).is_setup()) continue;
            const Instruction& ins = at(i);
            if (!ins.dest || ins.dest->type != RegisterType::Temp || ins.opcode == Opcode::TexKill)
                continue;
            const uint16_t d = ins.dest->index;
            if (ins.opcode == Opcode::Tex) {
                int order = 0;
                const SourceParameter& c = ins.sources[0];
                if (c.type == RegisterType::Temp) order = std::max(order, std::max(1, level[c.index] + 1));
                if (written[d]) order = std::max(order, std::max(1, level[d] + 1));
                if (order > static_cast<int>(limit))
                    report(Rule::DependentReads, i,
                           "is a dependent read of order " + std::to_string(order) + "; " +
                               version_.name() + " allows order " + std::to_string(limit) + " (" +
                               std::to_string(limit + 1) + " levels of texture reads)");
                level[d] = order;
            } else {
                int from = -1;
                for (const Read& r : reads_of(i))
                    if (r.type == RegisterType::Temp) from = std::max(from, level[r.index]);
                level[d] = (ins.dest->write_mask & kMaskAll) == kMaskAll ? from : std::max(level[d], from);
            }
            written[d] = true;
        }
    }

    // ---- rule 18: flow control -----------------------------------------------------------
    struct Routine {
        size_t label = 0;         // index of the label instruction
        size_t end = SIZE_MAX;    // index of its ret (SIZE_MAX: none)
        unsigned loop_depth = 0;  // deepest loop/rep nesting inside
    };

    void check_flow_control() {
        main_end_ = size();
        struct Block { Opcode opcode; size_t index; bool has_else; };
        std::vector<Block> stack;
        std::vector<std::pair<size_t, unsigned>> calls;  // call index, loops open at the call
        unsigned flow_count = 0;
        bool flow_count_reported = false;
        bool in_main = true, after_ret = false;
        size_t ret_at = 0;
        Routine* routine = nullptr;      // the routine being read (nullptr: main or dead code)
        unsigned main_loop_depth = 0;
        auto loops_open = [&] {
            return static_cast<unsigned>(std::count_if(stack.begin(), stack.end(), [](const Block& b) {
                return b.opcode == Opcode::Loop || b.opcode == Opcode::Rep;
            }));
        };
        auto close = [&](size_t i, Opcode opener, const char* opener_name) {
            auto match = std::find_if(stack.rbegin(), stack.rend(),
                                      [&](const Block& b) { return b.opcode == opener; });
            if (match == stack.rend()) {
                report(Rule::FlowControl, i, std::string("has no matching ") + opener_name);
                return;
            }
            if (match != stack.rbegin())
                report(Rule::FlowControl, i, "closes the " + std::string(opener_name) + " at " +
                                                 std::to_string(match->index) + " while the " +
                                                 mnemonic(stack.back().index) + " at " +
                                                 std::to_string(stack.back().index) +
                                                 " is still open (blocks must nest)");
            stack.erase(std::prev(match.base()), stack.end());
        };
        auto report_open = [&] {
            for (const Block& b : stack)
                report(Rule::FlowControl, b.index, "block is not closed before the end of its routine");
            stack.clear();
        };

        for (size_t i = 0; i < size(); ++i) {
            if (!ok_[i] || at(i).is_setup()) continue;
            const Opcode op = at(i).opcode;
            if (info(i).category == Category::FlowControl && !profile_.flow_control) {
                report(Rule::FlowControl, i, version_.name() + " has no flow control");
                continue;
            }
            if (after_ret && op != Opcode::Label) {
                report(Rule::FlowControl, i,
                       op == Opcode::Ret
                           ? "a routine has one ret; the ret at " + std::to_string(ret_at) + " already ended it"
                           : std::string("code after a ret must start with a label l#"));
                if (op != Opcode::Ret) after_ret = false, routine = nullptr;
                continue;
            }
            switch (op) {
            case Opcode::If:
            case Opcode::Loop:
            case Opcode::Rep:
                if (op != Opcode::If && loops_open() + 1 > profile_.max_loop_nesting)
                    report(Rule::FlowControl, i, "loop/rep nesting deeper than " +
                                                     std::to_string(profile_.max_loop_nesting));
                stack.push_back({op, i, false});
                if (op != Opcode::If) {
                    unsigned& deepest = routine ? routine->loop_depth : main_loop_depth;
                    deepest = std::max(deepest, loops_open());
                }
                break;
            case Opcode::Else:
                if (stack.empty() || stack.back().opcode != Opcode::If || stack.back().has_else)
                    report(Rule::FlowControl, i, "has no matching if");
                else
                    stack.back().has_else = true;
                break;
            case Opcode::EndIf: close(i, Opcode::If, "if"); break;
            case Opcode::EndLoop: close(i, Opcode::Loop, "loop"); break;
            case Opcode::EndRep: close(i, Opcode::Rep, "rep"); break;
            case Opcode::Call:
            case Opcode::CallNz:
                // A call from main nests 1 deep, a call from a subroutine 2.
                if ((in_main ? 1u : 2u) > profile_.max_call_nesting)
                    report(Rule::FlowControl, i, "call nesting deeper than " +
                                                     std::to_string(profile_.max_call_nesting) +
                                                     (in_main ? "" : " (a subroutine cannot call)"));
                calls.push_back({i, loops_open()});
                break;
            case Opcode::Ret:
                if (!stack.empty()) {
                    report(Rule::FlowControl, i, "ret inside an open " + mnemonic(stack.back().index) +
                                                     " block (at " + std::to_string(stack.back().index) + ")");
                    stack.clear();
                }
                if (in_main) main_end_ = i;
                else if (routine) routine->end = i;
                in_main = false;
                after_ret = true;
                ret_at = i;
                break;
            case Opcode::Label: {
                const uint16_t label = at(i).sources[0].index;
                if (!after_ret) {
                    report(Rule::FlowControl, i, "a label must directly follow a ret");
                    report_open();
                    if (in_main) main_end_ = i;
                    in_main = false;
                }
                after_ret = false;
                auto [it, fresh] = routines_.emplace(label, Routine{i, SIZE_MAX, 0});
                if (!fresh) {
                    report(Rule::FlowControl, i, name(RegisterType::Label, label) +
                                                     " is already defined at " +
                                                     std::to_string(it->second.label));
                    routine = nullptr;
                } else {
                    routine = &it->second;
                }
                break;
            }
            default: break;
            }
            const bool counted = op == Opcode::If || op == Opcode::Else || op == Opcode::Loop ||
                                 op == Opcode::Rep || op == Opcode::Call || op == Opcode::CallNz;
            if (counted && ++flow_count > profile_.max_static_flow_count && !flow_count_reported) {
                flow_count_reported = true;
                report(Rule::FlowControl, i, "static flow count exceeds " +
                                                 std::to_string(profile_.max_static_flow_count) +
                                                 " (if, else, loop, rep, call, callnz count one each)");
            }
        }
        report_open();
        for (const auto& [label, r] : routines_)
            if (r.end == SIZE_MAX)
                report(Rule::FlowControl, r.label, "routine " + name(RegisterType::Label, label) + " has no ret");
        check_calls(calls);
    }

    // Called labels exist, calls go forward, and loop/rep nesting holds across the call.
    void check_calls(const std::vector<std::pair<size_t, unsigned>>& calls) {
        for (const auto& [i, loops_at_call] : calls) {
            const uint16_t label = at(i).sources[0].index;
            auto it = routines_.find(label);
            if (it == routines_.end()) {
                report(Rule::FlowControl, i, name(RegisterType::Label, label) + " is not defined");
                continue;
            }
            if (it->second.label < i)
                report(Rule::FlowControl, i, "calls must go forward; " +
                                                 name(RegisterType::Label, label) + " is defined at " +
                                                 std::to_string(it->second.label));
            else if (loops_at_call + it->second.loop_depth > profile_.max_loop_nesting)
                report(Rule::FlowControl, i, "calls " + name(RegisterType::Label, label) +
                                                 ", which has a loop/rep, from inside a loop/rep "
                                                 "(loop/rep nesting deeper than " +
                                                 std::to_string(profile_.max_loop_nesting) + ")");
        }
    }

    // ---- rules 7 and 8: temps and a0 written before read; aL inside loops ----------------
    // See the comment at the top of the file for how flow control is treated.
    void check_initialization() {
        InitState state;
        state.temps.assign(temp_count(), 0);
        walk(0, main_end_, state, 0, std::nullopt);
    }

    // Walks [begin, end) in static order. `loops`: enclosing `loop` blocks (aL is valid when
    // > 0), the caller's included. `call_site`: the call being analysed, if any.
    void walk(size_t begin, size_t end, InitState& state, unsigned loops,
              std::optional<size_t> call_site) {
        struct Frame { Opcode opcode; InitState entry; std::optional<InitState> then_arm; };
        std::vector<Frame> frames;
        for (size_t i = begin; i < end && i < size(); ++i) {
            const Instruction& ins = at(i);
            if (is_comment(i) || !ins.info() || ins.is_setup()) continue;
            if (!ok_[i]) {  // not trusted: only keep a plainly written temp, to avoid cascades
                if (ins.dest && ins.dest->type == RegisterType::Temp && ins.dest->index < state.temps.size())
                    state.temps[ins.dest->index] |= ins.dest->write_mask & kMaskAll;
                continue;
            }
            switch (ins.opcode) {
            case Opcode::If:
            case Opcode::Loop:
            case Opcode::Rep:
                frames.push_back({ins.opcode, state, std::nullopt});
                if (ins.opcode == Opcode::Loop) ++loops;
                continue;
            case Opcode::Else:
                if (!frames.empty() && frames.back().opcode == Opcode::If) {
                    frames.back().then_arm = state;
                    state = frames.back().entry;
                }
                continue;
            case Opcode::EndIf:
            case Opcode::EndLoop:
            case Opcode::EndRep: {
                if (frames.empty()) continue;
                Frame& f = frames.back();
                if (f.opcode == Opcode::Loop) --loops;
                // if without else: meet with the entry state; with else: meet both arms.
                // loop/rep: the body may run zero times, so the entry state survives.
                if (f.opcode == Opcode::If) state.meet(f.then_arm ? *f.then_arm : f.entry);
                else state = f.entry;
                frames.pop_back();
                continue;
            }
            case Opcode::Call:
            case Opcode::CallNz: {
                auto it = routines_.find(ins.sources[0].index);
                if (call_site || it == routines_.end() || it->second.label < i) continue;
                InitState after = state;
                walk(it->second.label + 1, it->second.end, after, loops, i);
                if (ins.opcode == Opcode::Call) state = std::move(after);
                else state.meet(after);
                continue;
            }
            case Opcode::Ret:
            case Opcode::Label:
                return;
            default: break;
            }
            check_reads_initialized(i, state, loops, call_site);
            if (ins.dest && ins.opcode != Opcode::TexKill) {
                const uint8_t m = ins.dest->write_mask & kMaskAll;
                if (ins.dest->type == RegisterType::Temp) state.temps[ins.dest->index] |= m;
                else if (is_address(ins.dest->type)) state.a0 |= m;
            }
        }
    }

    void check_reads_initialized(size_t i, const InitState& state, unsigned loops,
                                 std::optional<size_t> call_site) {
        // A routine walked from several call sites reports each finding once, naming the
        // first call site that shows it.
        auto once = [&](Rule rule, const std::string& what) {
            if (!walk_reported_.insert({i, what}).second) return;
            report(rule, i, what + (call_site ? " (in a subroutine called at " +
                                                    std::to_string(*call_site) + ")"
                                              : std::string()));
        };
        for (const Read& r : reads_of(i)) {
            if (r.type != RegisterType::Temp) continue;
            const uint8_t missing = r.components & ~state.temps[r.index];
            if (missing)
                once(Rule::TempInitialized, "reads " + name(r.type, r.index) + mask_text(missing) +
                                                " before it is written on every path");
        }
        for (const SourceParameter& s : at(i).sources) {
            if (!s.relative) continue;
            if (is_address(s.relative->type)) {
                const uint8_t c = swizzle_component(s.relative->swizzle, 0);
                if (!(state.a0 & (1u << c)))
                    once(Rule::AddressRegister, "a0" + mask_text(static_cast<uint8_t>(1u << c)) +
                                                    " is used as an index before mova writes it");
            } else if (s.relative->type == RegisterType::Loop && loops == 0) {
                once(Rule::AddressRegister, "aL is used outside a loop");
            }
        }
    }

    // ---- rule 19: outputs (and the combined oT# masks of rule 13) ------------------------
    void check_outputs() {
        std::map<RegKey, size_t> single_writes;  // oC#/oDepth -> first writer
        std::map<uint16_t, size_t> colors;       // oC# -> first writer
        bool position = false;
        std::map<uint16_t, std::pair<uint8_t, size_t>> texcoords;  // oT#: combined mask, last writer
        for (size_t i = 0; i < size(); ++i) {
            if (!ok_[i] || at(i).is_setup() || !at(i).dest || at(i).opcode == Opcode::TexKill) continue;
            const DestinationParameter& d = *at(i).dest;
            if (d.type == RegisterType::ColorOut || d.type == RegisterType::DepthOut) {
                if (at(i).opcode != Opcode::Mov)
                    report(Rule::Outputs, i, name(d) + " can only be written by mov");
                auto [it, fresh] = single_writes.emplace(RegKey{d.type, d.index}, i);
                if (!fresh)
                    report(Rule::Outputs, i, name(d) + " is written more than once (first at " +
                                                 std::to_string(it->second) + ")");
                if (d.type == RegisterType::ColorOut) colors.emplace(d.index, i);
            }
            if (d.type == RegisterType::RastOut && d.index == kRastOutPosition) position = true;
            if (d.type == RegisterType::TexCrdOut) {
                auto& [mask, last] = texcoords[d.index];
                mask |= d.write_mask & kMaskAll;
                last = i;
            }
        }
        // Required outputs (registers-and-limits.md §9): the same for every SM2 profile.
        if (version_.is_vertex() && !position)
            report(Rule::Outputs, SIZE_MAX, version_.name() + " shader never writes oPos");
        if (version_.is_pixel() && !colors.count(0))
            report(Rule::Outputs, SIZE_MAX, version_.name() + " shader never writes oC0");
        for (const auto& [index, first] : colors)
            if (index > 0 && !colors.count(static_cast<uint16_t>(index - 1)))
                report(Rule::Outputs, first, name(RegisterType::ColorOut, index) + " is written but " +
                                                 name(RegisterType::ColorOut, index - 1u) +
                                                 " is not (oC# must be contiguous from oC0)");
        for (const auto& [index, written] : texcoords) {
            const auto [mask, last] = written;
            if (mask != kX && mask != (kX | kY) && mask != (kX | kY | kZ) && mask != kMaskAll)
                report(Rule::WriteMask, last, "the combined write mask of " +
                                                  name(RegisterType::TexCrdOut, index) + " is " +
                                                  mask_text(mask) + "; it must be .x, .xy, .xyz or .xyzw");
            if (index > 0 && !texcoords.count(static_cast<uint16_t>(index - 1)))
                report(Rule::WriteMask, last, name(RegisterType::TexCrdOut, index) + " is written but " +
                                                  name(RegisterType::TexCrdOut, index - 1u) +
                                                  " is not (oTn needs oT0..oTn-1)");
        }
    }

    const Program& program_;
    const Profile& profile_;
    ShaderVersion version_;
    ValidationOptions options_;
    std::vector<Violation> out_;
    std::vector<bool> ok_;  // rules 2/3 passed: the shape can be trusted by the other rules
    std::map<RegKey, uint8_t> inputs_;           // declared v#/t# -> declared mask
    std::map<uint16_t, TextureType> samplers_;   // declared s# -> texture type
    std::map<uint16_t, std::array<uint32_t, 4>> float_defs_;  // def c# -> bits (last wins)
    std::map<uint16_t, Routine> routines_;       // label number -> routine
    size_t main_end_ = 0;                        // index of main's ret (or the end)
    std::set<std::pair<size_t, std::string>> walk_reported_;  // rules 7/8 findings so far
};

}  // namespace

std::vector<Violation> validate(const Program& program, const ValidationOptions& options) {
    const Profile* profile = find_profile(program.version);
    if (!profile)
        return {Violation{Rule::Structure,
                          "no profile for shader version " + program.version.name() +
                              " (supported: vs_2_0, ps_2_0)",
                          SIZE_MAX,
                          {}}};
    return Validator(program, *profile, options).run();
}

SlotCount instruction_slots(ShaderVersion version, const Instruction& instruction) {
    const OpcodeInfo* row = instruction.opcode == Opcode::Comment ? nullptr : instruction.info();
    if (!row || row->slot_class == SlotClass::Setup) return {};
    const unsigned slots = row->slots_in(version);
    const bool texture = row->slot_class == SlotClass::Texture;
    return SlotCount{slots, texture ? 0 : slots, texture ? slots : 0};
}

SlotCount count_slots(const Program& program) {
    SlotCount sum;
    for (const Instruction& ins : program.instructions) {
        const SlotCount one = instruction_slots(program.version, ins);
        sum.total += one.total;
        sum.arithmetic += one.arithmetic;
        sum.texture += one.texture;
    }
    return sum;
}

std::string slot_summary(const SlotCount& slots) {
    std::string s = "approximately " + std::to_string(slots.total) + " instruction slot" +
                    (slots.total == 1 ? "" : "s") + " used";
    if (slots.texture > 0)
        s += " (" + std::to_string(slots.texture) + " texture, " + std::to_string(slots.arithmetic) + " arithmetic)";
    return s;
}

}  // namespace sm2::isa
