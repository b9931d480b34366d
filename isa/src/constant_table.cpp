// CTAB parsing with every offset checked against the comment block.
#include "sm2/isa/constant_table.h"

#include <algorithm>

namespace sm2::isa {

namespace {

constexpr uint32_t kHeaderBytes = 28;        // D3DXSHADER_CONSTANTTABLE
constexpr uint32_t kConstantInfoBytes = 20;  // D3DXSHADER_CONSTANTINFO
constexpr uint32_t kTypeInfoBytes = 16;      // D3DXSHADER_TYPEINFO
constexpr uint32_t kMemberInfoBytes = 8;     // D3DXSHADER_STRUCTMEMBERINFO
constexpr int kMaxStructDepth = 16;
constexpr size_t kMaxResolvedTypes = 4096;


struct Failure {
    std::string message;
};

std::string hex(uint32_t v) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string s = "0x";
    bool started = false;
    for (int shift = 28; shift >= 0; shift -= 4) {
        const uint32_t d = (v >> shift) & 15;
        if (d != 0 || started || shift == 0) {
            s += kDigits[d];
            started = true;
        }
    }
    return s;
}

class Reader {
public:
    explicit Reader(std::span<const uint32_t> payload) : words_(payload) {}

    [[nodiscard]] uint32_t size_bytes() const { return static_cast<uint32_t>(words_.size() * 4); }

    // `bytes` bytes at `offset` lie inside the block; `what` names the field for the message.
    void need(uint32_t offset, uint32_t bytes, const std::string& what) const {
        if (offset > size_bytes() || bytes > size_bytes() - offset)
            throw Failure{what + " at byte offset " + hex(offset) + " (" + std::to_string(bytes) +
                          " bytes) lies outside the " + std::to_string(size_bytes()) + " bytes after 'CTAB'"};
    }

    [[nodiscard]] uint8_t byte(uint32_t offset) const {
        return static_cast<uint8_t>(words_[offset / 4] >> (8 * (offset % 4)));
    }
    [[nodiscard]] uint16_t word16(uint32_t offset) const {
        return static_cast<uint16_t>(byte(offset) | byte(offset + 1) << 8);
    }
    [[nodiscard]] uint32_t dword(uint32_t offset) const {
        return static_cast<uint32_t>(word16(offset)) | static_cast<uint32_t>(word16(offset + 2)) << 16;
    }

    // A NUL-terminated string at `offset`; offset 0 means "none" (an empty string).
    [[nodiscard]] std::string string_at(uint32_t offset, const std::string& what) const {
        if (offset == 0) return {};
        need(offset, 1, what);
        std::string s;
        for (uint32_t at = offset; at < size_bytes(); ++at) {
            const auto c = static_cast<char>(byte(at));
            if (c == '\0') return s;
            s += c;
        }
        throw Failure{what + " at byte offset " + hex(offset) + " has no terminating NUL before the end of the block"};
    }

private:
    std::span<const uint32_t> words_;
};

class Parser {
public:
    // Offsets count from the header, the DWORD after the FOURCC.
    explicit Parser(std::span<const uint32_t> payload)
        : in_(payload.empty() ? payload : payload.subspan(1)),
          starts_with_fourcc_(!payload.empty() && payload[0] == kFourccCtab) {}

    ConstantTable run() {
        if (!starts_with_fourcc_) throw Failure{"the block does not start with 'CTAB'"};
        in_.need(0, kHeaderBytes, "the CTAB header");
        const uint32_t header = 0;
        const uint32_t size = in_.dword(header);
        if (size != kHeaderBytes)
            throw Failure{"the CTAB header gives its size as " + std::to_string(size) + " bytes, not " +
                          std::to_string(kHeaderBytes)};
        ConstantTable table;
        table.creator = in_.string_at(in_.dword(header + 4), "the creator string");
        table.version = in_.dword(header + 8);
        const uint32_t count = in_.dword(header + 12);
        const uint32_t info = in_.dword(header + 16);
        table.flags = in_.dword(header + 20);
        table.target = in_.string_at(in_.dword(header + 24), "the target string");
        // The count is checked against the space it needs before anything is allocated.
        if (count > in_.size_bytes() / kConstantInfoBytes)
            throw Failure{std::to_string(count) + " constants cannot fit in the " +
                          std::to_string(in_.size_bytes()) + " bytes after 'CTAB'"};
        in_.need(info, count * kConstantInfoBytes, "the constant list");
        for (uint32_t i = 0; i < count; ++i) table.constants.push_back(constant(info + i * kConstantInfoBytes, i));
        return table;
    }

private:
    ConstantInfo constant(uint32_t at, uint32_t i) {
        const std::string what = "constant " + std::to_string(i);
        ConstantInfo c;
        c.name = in_.string_at(in_.dword(at), what + "'s name");
        const uint16_t set = in_.word16(at + 4);
        if (set > static_cast<uint16_t>(ConstantRegisterSet::Sampler))
            throw Failure{what + " ('" + c.name + "') has register set " + std::to_string(set) + " (0..3 exist)"};
        c.register_set = static_cast<ConstantRegisterSet>(set);
        c.register_index = in_.word16(at + 6);
        c.register_count = in_.word16(at + 8);
        c.type = type(in_.dword(at + 12), what + " ('" + c.name + "')", 0);
        const uint32_t defaults = in_.dword(at + 16);
        if (defaults != 0) {
            in_.need(defaults, 4, what + "'s default value");
            const uint32_t per_register = c.register_set == ConstantRegisterSet::Bool ? 1 : 4;
            const uint32_t wanted = c.register_count * per_register;
            const uint32_t available = (in_.size_bytes() - defaults) / 4;
            for (uint32_t k = 0; k < std::min(wanted, available); ++k)
                c.default_value.push_back(in_.dword(defaults + 4 * k));
        }
        return c;
    }

    ConstantType type(uint32_t at, const std::string& owner, int depth) {
        if (depth > kMaxStructDepth)
            throw Failure{owner + ": struct members nest more than " + std::to_string(kMaxStructDepth) +
                          " deep (a cycle?)"};
        if (++resolved_ > kMaxResolvedTypes)
            throw Failure{owner + ": the table resolves more than " + std::to_string(kMaxResolvedTypes) + " types"};
        in_.need(at, kTypeInfoBytes, owner + "'s type");
        ConstantType t;
        t.parameter_class = in_.word16(at);
        t.parameter_type = in_.word16(at + 2);
        t.rows = in_.word16(at + 4);
        t.columns = in_.word16(at + 6);
        t.elements = in_.word16(at + 8);
        const uint16_t members = in_.word16(at + 10);
        const uint32_t member_info = in_.dword(at + 12);
        if (members == 0) return t;
        in_.need(member_info, members * kMemberInfoBytes, owner + "'s member list");
        for (uint16_t m = 0; m < members; ++m) {
            const uint32_t entry = member_info + m * kMemberInfoBytes;
            ConstantMember member;
            member.name = in_.string_at(in_.dword(entry), owner + "'s member " + std::to_string(m));
            member.type = type(in_.dword(entry + 4), owner + "." + member.name, depth + 1);
            t.members.push_back(std::move(member));
        }
        return t;
    }

    Reader in_;
    bool starts_with_fourcc_;
    size_t resolved_ = 0;
};

// Offsets in the layout count bytes from the header, which is where `bytes_` starts.
class Writer {
public:
    std::vector<uint32_t> run(const ConstantTable& table) {
        const uint32_t header = reserve(kHeaderBytes);
        const uint32_t info = reserve(static_cast<uint32_t>(table.constants.size()) * kConstantInfoBytes);
        for (size_t i = 0; i < table.constants.size(); ++i) {
            const ConstantInfo& c = table.constants[i];
            const uint32_t at = info + static_cast<uint32_t>(i) * kConstantInfoBytes;
            put32(at, string(c.name));
            put16(at + 4, static_cast<uint16_t>(c.register_set));
            put16(at + 6, c.register_index);
            put16(at + 8, c.register_count);
            put32(at + 12, type(c.type));
            if (!c.default_value.empty()) {
                const uint32_t defaults = reserve(static_cast<uint32_t>(c.default_value.size()) * 4);
                for (size_t k = 0; k < c.default_value.size(); ++k)
                    put32(defaults + static_cast<uint32_t>(k) * 4, c.default_value[k]);
                put32(at + 16, defaults);
            }
        }
        put32(header, kHeaderBytes);
        put32(header + 4, string(table.creator));
        put32(header + 8, table.version);
        put32(header + 12, static_cast<uint32_t>(table.constants.size()));
        put32(header + 16, table.constants.empty() ? 0 : info);
        put32(header + 20, table.flags);
        put32(header + 24, string(table.target));
        align();
        std::vector<uint32_t> payload{kFourccCtab};
        for (size_t k = 0; k < bytes_.size(); k += 4)
            payload.push_back(static_cast<uint32_t>(bytes_[k]) | static_cast<uint32_t>(bytes_[k + 1]) << 8 |
                              static_cast<uint32_t>(bytes_[k + 2]) << 16 | static_cast<uint32_t>(bytes_[k + 3]) << 24);
        return payload;
    }

private:
    uint32_t type(const ConstantType& t) {
        const uint32_t at = reserve(kTypeInfoBytes);
        put16(at, t.parameter_class);
        put16(at + 2, t.parameter_type);
        put16(at + 4, t.rows);
        put16(at + 6, t.columns);
        put16(at + 8, t.elements);
        put16(at + 10, static_cast<uint16_t>(t.members.size()));
        if (t.members.empty()) return at;
        const uint32_t list = reserve(static_cast<uint32_t>(t.members.size()) * kMemberInfoBytes);
        put32(at + 12, list);
        for (size_t m = 0; m < t.members.size(); ++m) {
            const uint32_t entry = list + static_cast<uint32_t>(m) * kMemberInfoBytes;
            put32(entry, string(t.members[m].name));
            put32(entry + 4, type(t.members[m].type));
        }
        return at;
    }

    uint32_t string(const std::string& text) {
        const uint32_t at = reserve(static_cast<uint32_t>(text.size()) + 1);
        std::copy(text.begin(), text.end(), bytes_.begin() + at);
        return at;
    }

    // `size` zero bytes at the next DWORD boundary; their offset.
    uint32_t reserve(uint32_t size) {
        align();
        const auto at = static_cast<uint32_t>(bytes_.size());
        bytes_.resize(bytes_.size() + size);
        return at;
    }
    void align() { bytes_.resize((bytes_.size() + 3) & ~size_t{3}); }
    void put16(uint32_t at, uint16_t value) {
        bytes_[at] = static_cast<uint8_t>(value);
        bytes_[at + 1] = static_cast<uint8_t>(value >> 8);
    }
    void put32(uint32_t at, uint32_t value) {
        put16(at, static_cast<uint16_t>(value));
        put16(at + 2, static_cast<uint16_t>(value >> 16));
    }

    std::vector<uint8_t> bytes_;
};

}  // namespace

std::vector<uint32_t> serialize_constant_table(const ConstantTable& table) { return Writer().run(table); }

ConstantTableResult parse_constant_table(std::span<const uint32_t> payload) {
    try {
        return ConstantTableResult{Parser(payload).run(), {}};
    } catch (const Failure& f) {
        return ConstantTableResult{std::nullopt, f.message};
    }
}

std::optional<ConstantTableResult> find_constant_table(const Program& program) {
    for (const Instruction& ins : program.instructions)
        if (ins.opcode == Opcode::Comment && !ins.comment.empty() && ins.comment[0] == kFourccCtab)
            return parse_constant_table(ins.comment);
    return std::nullopt;
}

std::string constant_type_name(const ConstantType& type) {
    static constexpr const char* kTypes[] = {
        "void",        "bool",      "int",       "float",     "string",      "texture",     "texture1D",
        "texture2D",   "texture3D", "textureCUBE", "sampler", "sampler1D",   "sampler2D",   "sampler3D",
        "samplerCUBE", "pixelshader", "vertexshader", "pixelfragment", "vertexfragment"};
    std::string s;
    if (type.parameter_class == parameter_class::Struct) {
        s = "struct";
    } else {
        s = type.parameter_type < std::size(kTypes) ? kTypes[type.parameter_type]
                                                    : "type" + std::to_string(type.parameter_type);
        switch (type.parameter_class) {
        case 0: break;  // scalar
        case 1: s += std::to_string(type.columns); break;
        case parameter_class::MatrixRows:
        case 3:
            s = (type.parameter_class == parameter_class::MatrixRows ? "row_major " : "") + s + std::to_string(type.rows) +
                "x" + std::to_string(type.columns);
            break;
        case 4: break;  // object
        default: s += " (class " + std::to_string(type.parameter_class) + ")"; break;
        }
    }
    if (type.elements > 1) s += "[" + std::to_string(type.elements) + "]";
    return s;
}

const char* register_set_prefix(ConstantRegisterSet set) {
    switch (set) {
    case ConstantRegisterSet::Bool: return "b";
    case ConstantRegisterSet::Int4: return "i";
    case ConstantRegisterSet::Float4: return "c";
    case ConstantRegisterSet::Sampler: return "s";
    }
    return "?";
}

const ConstantInfo* find_constant(const ConstantTable& table, std::string_view name) {
    for (const ConstantInfo& c : table.constants)
        if (c.name == name) return &c;
    return nullptr;
}

}  // namespace sm2::isa
