// Parameter-token codec (bytecode.md §5, §6, §6.1, §7).
#include "sm2/isa/tokens.h"

namespace sm2::isa::tokens {

namespace {

constexpr uint32_t kRegisterNumberMask = 0x7FFu;
constexpr uint32_t kRelativeBit = 0x2000u;
constexpr uint32_t kReservedParameterBits = 0xC000u;  // bits 14..15

bool fail(std::string* error, std::string message) {
    if (error) *error = std::move(message);
    return false;
}

bool check_parameter_common(uint32_t token, std::string* error) {
    if ((token & kParameterBit) == 0)
        return fail(error, "parameter token has bit 31 clear");
    if (token & kReservedParameterBits)
        return fail(error, "reserved bits 14..15 of a parameter token are set");
    if (decode_register_type(token) > kMaxRegisterType)
        return fail(error, "unknown register type " + std::to_string(decode_register_type(token)));
    return true;
}

}  // namespace

uint32_t encode_destination(const DestinationParameter& d) {
    uint32_t modifiers = (d.saturate ? 1u : 0u) | (d.partial_precision ? 2u : 0u) |
                         (d.centroid ? 4u : 0u);
    return kParameterBit | encode_register_type(d.type) | (d.index & kRegisterNumberMask) |
           (static_cast<uint32_t>(d.write_mask & 0xF) << 16) | (modifiers << 20) |
           (static_cast<uint32_t>(d.shift & 0xF) << 24);
}

uint32_t encode_source(const SourceParameter& s) {
    return kParameterBit | encode_register_type(s.type) | (s.index & kRegisterNumberMask) |
           (s.relative ? kRelativeBit : 0u) | (static_cast<uint32_t>(s.swizzle) << 16) |
           (static_cast<uint32_t>(s.modifier) << 24);
}

uint32_t encode_relative(const RelativeAddress& r) {
    return kParameterBit | encode_register_type(r.type) | (static_cast<uint32_t>(r.swizzle) << 16);
}

std::optional<DestinationParameter> decode_destination(uint32_t token, std::string* error) {
    if (!check_parameter_common(token, error)) return std::nullopt;
    if (token & kRelativeBit) {
        fail(error, "relative addressing on a destination exists only in vs_3_0");
        return std::nullopt;
    }
    const uint32_t modifiers = (token >> 20) & 0xF;
    if (modifiers & 0x8) {
        fail(error, "unknown result modifier bit 23 set in destination token");
        return std::nullopt;
    }
    DestinationParameter d;
    d.type = static_cast<RegisterType>(decode_register_type(token));
    d.index = static_cast<uint16_t>(token & kRegisterNumberMask);
    d.write_mask = static_cast<uint8_t>((token >> 16) & 0xF);
    d.saturate = modifiers & 1;
    d.partial_precision = modifiers & 2;
    d.centroid = modifiers & 4;
    d.shift = static_cast<uint8_t>((token >> 24) & 0xF);
    return d;
}

std::optional<SourceParameter> decode_source(uint32_t token, bool* relative, std::string* error) {
    if (!check_parameter_common(token, error)) return std::nullopt;
    const uint32_t modifier = (token >> 24) & 0xF;
    if (modifier > static_cast<uint32_t>(SourceModifier::Not)) {
        fail(error, "reserved source modifier " + std::to_string(modifier));
        return std::nullopt;
    }
    SourceParameter s;
    s.type = static_cast<RegisterType>(decode_register_type(token));
    s.index = static_cast<uint16_t>(token & kRegisterNumberMask);
    s.swizzle = static_cast<uint8_t>((token >> 16) & 0xFF);
    s.modifier = static_cast<SourceModifier>(modifier);
    if (relative) *relative = (token & kRelativeBit) != 0;
    return s;
}

std::optional<RelativeAddress> decode_relative(uint32_t token, std::string* error) {
    if (!check_parameter_common(token, error)) return std::nullopt;
    const auto type = static_cast<RegisterType>(decode_register_type(token));
    if (type != RegisterType::Address && type != RegisterType::Loop) {
        fail(error, "relative-address token must name a0 or aL");
        return std::nullopt;
    }
    // register number, relative flag and modifier must all be zero
    if ((token & kRegisterNumberMask) != 0 || (token & 0x0F00E000u) != 0) {
        fail(error, "relative-address token has register-number, relative or modifier bits set");
        return std::nullopt;
    }
    return RelativeAddress{type, static_cast<uint8_t>((token >> 16) & 0xFF)};
}

uint32_t encode_declaration(const Declaration& d) {
    return kParameterBit | (static_cast<uint32_t>(d.usage) & 0x1F) |
           (static_cast<uint32_t>(d.usage_index & 0xF) << 16) |
           (static_cast<uint32_t>(d.texture_type) << 27);
}

std::optional<Declaration> decode_declaration(uint32_t token, std::string* error) {
    if ((token & kParameterBit) == 0) {
        fail(error, "dcl usage token has bit 31 clear");
        return std::nullopt;
    }
    if (token & 0x07F0FFE0u) {
        fail(error, "dcl usage token has reserved bits set");
        return std::nullopt;
    }
    const uint32_t usage = token & 0x1F;
    const uint32_t texture = (token >> 27) & 0xF;
    if (usage > kMaxDeclUsage) {
        fail(error, "unknown dcl usage " + std::to_string(usage));
        return std::nullopt;
    }
    if (texture > static_cast<uint32_t>(TextureType::Volume)) {
        fail(error, "unknown sampler texture type " + std::to_string(texture));
        return std::nullopt;
    }
    return Declaration{static_cast<DeclUsage>(usage), static_cast<uint8_t>((token >> 16) & 0xF),
                       static_cast<TextureType>(texture)};
}

}  // namespace sm2::isa::tokens
