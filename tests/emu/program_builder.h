// A small builder for isa::Program, so engine tests can state shaders without the assembler:
//   ProgramBuilder p(ShaderType::Vertex);
//   p.op(Opcode::Add, r(0).mask("xy"), {v(0), c(1).swz("yzxw").neg()});
#pragma once

#include <bit>
#include <cstdint>
#include <initializer_list>
#include <string_view>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::test {

using isa::Opcode;
using isa::RegisterType;
using isa::ShaderType;

inline uint8_t component_index(char c) {
    switch (c) {
    case 'x': case 'r': return 0;
    case 'y': case 'g': return 1;
    case 'z': case 'b': return 2;
    default: return 3;
    }
}

struct Src {
    isa::SourceParameter p;
    // "yzxw", or one letter for a replicate swizzle ("x" = .xxxx); shorter forms repeat the
    // last letter as the assembler does.
    Src swz(std::string_view s) const {
        Src out = *this;
        uint8_t swizzle = 0;
        for (int k = 0; k < 4; ++k) {
            const char letter = s[static_cast<size_t>(k) < s.size() ? static_cast<size_t>(k) : s.size() - 1];
            swizzle = static_cast<uint8_t>(swizzle | (component_index(letter) << (2 * k)));
        }
        out.p.swizzle = swizzle;
        return out;
    }
    Src neg() const { Src out = *this; out.p.modifier = isa::SourceModifier::Negate; return out; }
    Src logical_not() const { Src out = *this; out.p.modifier = isa::SourceModifier::Not; return out; }
    // c[a0.<component> + index]
    Src rel_a0(char component) const {
        Src out = *this;
        out.p.relative = isa::RelativeAddress{RegisterType::Address,
                                              isa::replicate_swizzle(component_index(component))};
        return out;
    }
    // c[aL + index]
    Src rel_aL() const {
        Src out = *this;
        out.p.relative = isa::RelativeAddress{RegisterType::Loop, isa::kSwizzleIdentity};
        return out;
    }
};

struct Dst {
    isa::DestinationParameter p;
    Dst mask(std::string_view m) const {
        Dst out = *this;
        uint8_t bits = 0;
        for (char c : m) bits = static_cast<uint8_t>(bits | (1u << component_index(c)));
        out.p.write_mask = bits;
        return out;
    }
    Dst sat() const { Dst out = *this; out.p.saturate = true; return out; }
    Dst pp() const { Dst out = *this; out.p.partial_precision = true; return out; }
};

inline Src source(RegisterType type, unsigned index) {
    Src s;
    s.p.type = type;
    s.p.index = static_cast<uint16_t>(index);
    return s;
}
inline Dst dest(RegisterType type, unsigned index) {
    Dst d;
    d.p.type = type;
    d.p.index = static_cast<uint16_t>(index);
    return d;
}

// Sources.
inline Src r(unsigned n) { return source(RegisterType::Temp, n); }
inline Src v(unsigned n) { return source(RegisterType::Input, n); }
inline Src c(unsigned n) { return source(RegisterType::Const, n); }
inline Src t(unsigned n) { return source(RegisterType::Texture, n); }
inline Src b(unsigned n) { return source(RegisterType::ConstBool, n); }
inline Src i(unsigned n) { return source(RegisterType::ConstInt, n); }
inline Src l(unsigned n) { return source(RegisterType::Label, n); }
inline Src s(unsigned n) { return source(RegisterType::Sampler, n); }
inline Src aL() { return source(RegisterType::Loop, 0); }
// Destinations.
inline Dst rd(unsigned n) { return dest(RegisterType::Temp, n); }
inline Dst oPos() { return dest(RegisterType::RastOut, isa::kRastOutPosition); }
inline Dst oFog() { return dest(RegisterType::RastOut, isa::kRastOutFog); }
inline Dst oD(unsigned n) { return dest(RegisterType::AttrOut, n); }
inline Dst oT(unsigned n) { return dest(RegisterType::TexCrdOut, n); }
inline Dst oC(unsigned n) { return dest(RegisterType::ColorOut, n); }
inline Dst oDepth() { return dest(RegisterType::DepthOut, 0); }
inline Dst a0() { return dest(RegisterType::Address, 0); }
inline Dst td(unsigned n) { return dest(RegisterType::Texture, n); }

class ProgramBuilder {
public:
    explicit ProgramBuilder(ShaderType type) { program_.version = isa::ShaderVersion{type, 2, 0}; }

    ProgramBuilder& op(Opcode opcode, Dst d, std::initializer_list<Src> sources = {}) {
        isa::Instruction ins;
        ins.opcode = opcode;
        ins.dest = d.p;
        for (const Src& s : sources) ins.sources.push_back(s.p);
        program_.instructions.push_back(std::move(ins));
        return *this;
    }
    // Instructions without a destination (flow control).
    ProgramBuilder& flow(Opcode opcode, std::initializer_list<Src> sources = {}) {
        isa::Instruction ins;
        ins.opcode = opcode;
        for (const Src& s : sources) ins.sources.push_back(s.p);
        program_.instructions.push_back(std::move(ins));
        return *this;
    }
    ProgramBuilder& tex(Dst d, Src coordinates, unsigned sampler, uint8_t control = isa::kTexLdPlain) {
        op(Opcode::Tex, d, {coordinates, s(sampler)});
        program_.instructions.back().control = control;
        return *this;
    }
    ProgramBuilder& texkill(Dst tested) { return op(Opcode::TexKill, tested); }
    ProgramBuilder& def(unsigned reg, float x, float y, float z, float w) {
        isa::Instruction ins;
        ins.opcode = Opcode::Def;
        ins.dest = dest(RegisterType::Const, reg).p;
        ins.constant_bits = {std::bit_cast<uint32_t>(x), std::bit_cast<uint32_t>(y),
                             std::bit_cast<uint32_t>(z), std::bit_cast<uint32_t>(w)};
        program_.instructions.push_back(std::move(ins));
        return *this;
    }
    ProgramBuilder& defi(unsigned reg, int32_t x, int32_t y, int32_t z, int32_t w) {
        isa::Instruction ins;
        ins.opcode = Opcode::DefI;
        ins.dest = dest(RegisterType::ConstInt, reg).p;
        ins.constant_bits = {static_cast<uint32_t>(x), static_cast<uint32_t>(y),
                             static_cast<uint32_t>(z), static_cast<uint32_t>(w)};
        program_.instructions.push_back(std::move(ins));
        return *this;
    }
    ProgramBuilder& defb(unsigned reg, bool value) {
        isa::Instruction ins;
        ins.opcode = Opcode::DefB;
        ins.dest = dest(RegisterType::ConstBool, reg).p;
        ins.constant_bits[0] = value ? 1u : 0u;
        program_.instructions.push_back(std::move(ins));
        return *this;
    }
    [[nodiscard]] const isa::Program& program() const { return program_; }

private:
    isa::Program program_;
};

}  // namespace sm2::test
