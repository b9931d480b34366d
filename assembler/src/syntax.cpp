#include "syntax.h"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <system_error>

namespace sm2::assembler::syntax {

namespace {

constexpr std::array<std::string_view, isa::kMaxDeclUsage + 1> kUsageNames = {
    "position", "blendweight", "blendindices", "normal",  "psize", "texcoord", "tangent",
    "binormal", "tessfactor",  "positiont",    "color",   "fog",   "depth",    "sample",
};

constexpr std::array<std::string_view, 5> kTextureTypeNames = {"", "1d", "2d", "cube", "volume"};

constexpr char kComponentLetters[4] = {'x', 'y', 'z', 'w'};

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_hex_digit(char c) {
    return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// Double -> float with round to nearest even and IEEE overflow to infinity, without relying on
// the (formally undefined) out-of-range conversion.
float round_to_float(double d) {
    constexpr double kMax = static_cast<double>(std::numeric_limits<float>::max());
    // FLT_MAX + half an ulp: the first value that rounds to infinity.
    const double overflow = kMax + std::ldexp(1.0, 103);
    const double a = std::fabs(d);
    const float sign = std::signbit(d) ? -1.0f : 1.0f;
    if (a >= overflow) return sign * std::numeric_limits<float>::infinity();
    if (a > kMax) return sign * std::numeric_limits<float>::max();
    return static_cast<float>(d);
}

}  // namespace

std::string_view usage_name(isa::DeclUsage usage) {
    const auto i = static_cast<size_t>(usage);
    return i < kUsageNames.size() ? kUsageNames[i] : std::string_view("?");
}

std::optional<isa::DeclUsage> find_usage(std::string_view lower_name) {
    for (size_t i = 0; i < kUsageNames.size(); ++i)
        if (kUsageNames[i] == lower_name) return static_cast<isa::DeclUsage>(i);
    return std::nullopt;
}

std::string_view texture_type_name(isa::TextureType type) {
    const auto i = static_cast<size_t>(type);
    return i < kTextureTypeNames.size() ? kTextureTypeNames[i] : std::string_view("?");
}

std::optional<isa::TextureType> find_texture_type(std::string_view lower_name) {
    for (size_t i = 1; i < kTextureTypeNames.size(); ++i)
        if (kTextureTypeNames[i] == lower_name) return static_cast<isa::TextureType>(i);
    return std::nullopt;
}

int component_index(char c) {
    switch (c) {
    case 'x': case 'X': case 'r': case 'R': return 0;
    case 'y': case 'Y': case 'g': case 'G': return 1;
    case 'z': case 'Z': case 'b': case 'B': return 2;
    case 'w': case 'W': case 'a': case 'A': return 3;
    default: return -1;
    }
}

std::optional<uint8_t> parse_swizzle(std::string_view letters) {
    if (letters.empty() || letters.size() > 4) return std::nullopt;
    uint8_t swizzle = 0;
    int last = 0;
    for (size_t i = 0; i < 4; ++i) {
        if (i < letters.size()) {
            last = component_index(letters[i]);
            if (last < 0) return std::nullopt;
        }
        swizzle = static_cast<uint8_t>(swizzle | (last << (2 * i)));
    }
    return swizzle;
}

std::optional<uint8_t> parse_write_mask(std::string_view letters) {
    if (letters.empty() || letters.size() > 4) return std::nullopt;
    uint8_t mask = 0;
    int previous = -1;
    for (char c : letters) {
        const int k = component_index(c);
        if (k <= previous) return std::nullopt;  // unknown letter, repeat or out of order
        mask = static_cast<uint8_t>(mask | (1u << k));
        previous = k;
    }
    return mask;
}

std::string format_swizzle(uint8_t swizzle) {
    if (swizzle == isa::kSwizzleIdentity) return {};
    // The shortest prefix whose last letter, repeated, gives the remaining channels.
    size_t length = 4;
    while (length > 1 && isa::swizzle_component(swizzle, static_cast<int>(length - 1)) ==
                             isa::swizzle_component(swizzle, static_cast<int>(length - 2)))
        --length;
    std::string s;
    for (size_t i = 0; i < length; ++i)
        s += kComponentLetters[isa::swizzle_component(swizzle, static_cast<int>(i))];
    return s;
}

std::string format_write_mask(uint8_t mask) {
    if ((mask & 0xF) == 0xF) return {};
    std::string s;
    for (int k = 0; k < 4; ++k)
        if (mask & (1u << k)) s += kComponentLetters[k];
    return s;
}

bool is_hex_literal(std::string_view text) {
    return text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
}

std::optional<uint32_t> parse_hex_dword(std::string_view text, std::string* error) {
    auto fail = [&](std::string message) -> std::optional<uint32_t> {
        if (error) *error = std::move(message);
        return std::nullopt;
    };
    const std::string_view digits = is_hex_literal(text) ? text.substr(2) : std::string_view();
    if (digits.empty() || digits.size() > 8) return fail("'" + std::string(text) + "' is not 0x and 1 to 8 hex digits");
    uint32_t bits = 0;
    for (char c : digits) {
        if (!is_hex_digit(c)) return fail("invalid hex digit in '" + std::string(text) + "'");
        const uint32_t v = is_digit(c) ? static_cast<uint32_t>(c - '0') : static_cast<uint32_t>((c | 0x20) - 'a' + 10);
        bits = bits << 4 | v;
    }
    return bits;
}

std::optional<uint32_t> parse_float_literal(bool negative, std::string_view text,
                                            std::string* error) {
    auto fail = [&](std::string message) -> std::optional<uint32_t> {
        if (error) *error = std::move(message);
        return std::nullopt;
    };
    if (is_hex_literal(text)) {
        // Raw bit pattern (extension).
        if (negative) return fail("a raw bit pattern (0x...) cannot be negated");
        return parse_hex_dword(text, error);
    }
    std::string_view body = text;
    if (!body.empty() && (body.back() == 'f' || body.back() == 'F')) body.remove_suffix(1);
    // Validate the shape: digits [. digits] [e [+-] digits] with at least one digit before e.
    size_t i = 0;
    size_t mantissa_digits = 0;
    while (i < body.size() && is_digit(body[i])) ++i, ++mantissa_digits;
    if (i < body.size() && body[i] == '.') {
        ++i;
        while (i < body.size() && is_digit(body[i])) ++i, ++mantissa_digits;
    }
    if (mantissa_digits == 0) return fail("invalid number '" + std::string(text) + "'");
    if (i < body.size() && (body[i] == 'e' || body[i] == 'E')) {
        ++i;
        if (i < body.size() && (body[i] == '+' || body[i] == '-')) ++i;
        size_t exponent_digits = 0;
        while (i < body.size() && is_digit(body[i])) ++i, ++exponent_digits;
        if (exponent_digits == 0) return fail("invalid exponent in '" + std::string(text) + "'");
    }
    if (i != body.size()) return fail("invalid number '" + std::string(text) + "'");

    double value = 0.0;
    const auto result =
        std::from_chars(body.data(), body.data() + body.size(), value, std::chars_format::general);
    if (result.ec == std::errc::result_out_of_range) {
        // Too large or too small for a double: decide which by the decimal exponent.
        long exponent = 0;
        const size_t e = body.find_first_of("eE");
        const std::string_view mantissa = body.substr(0, e);
        if (e != std::string_view::npos) {
            std::string_view ex = body.substr(e + 1);
            bool neg = false;
            if (!ex.empty() && (ex[0] == '+' || ex[0] == '-')) neg = ex[0] == '-', ex.remove_prefix(1);
            long v = 0;
            for (char c : ex) v = std::min(v * 10 + (c - '0'), 100000L);
            exponent = neg ? -v : v;
        }
        const size_t point = mantissa.find('.');
        const std::string_view int_part = mantissa.substr(0, point);
        const size_t first_nonzero = int_part.find_first_not_of('0');
        exponent += first_nonzero == std::string_view::npos
                        ? -1
                        : static_cast<long>(int_part.size() - first_nonzero);
        value = exponent > 0 ? std::numeric_limits<double>::infinity() : 0.0;
    } else if (result.ec != std::errc() || result.ptr != body.data() + body.size()) {
        return fail("invalid number '" + std::string(text) + "'");
    }
    if (negative) value = -value;
    return std::bit_cast<uint32_t>(round_to_float(value));
}

std::string format_float_literal(uint32_t bits) {
    const float f = std::bit_cast<float>(bits);
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%08X", bits);
    if (!std::isfinite(f)) return hex;
    const float magnitude = std::fabs(f);
    const bool negative = std::signbit(f);
    auto reads_back = [&](std::string_view digits) {
        const auto parsed = parse_float_literal(negative, digits, nullptr);
        return parsed && *parsed == bits;
    };
    char buf[128];
    auto r = std::to_chars(buf, buf + sizeof buf, magnitude, std::chars_format::fixed);
    if (r.ec == std::errc() && reads_back(std::string_view(buf, static_cast<size_t>(r.ptr - buf))))
        return (negative ? "-" : "") + std::string(buf, r.ptr);
    for (int precision = 9; precision <= 60; precision += 3) {
        r = std::to_chars(buf, buf + sizeof buf, magnitude, std::chars_format::fixed, precision);
        if (r.ec == std::errc() &&
            reads_back(std::string_view(buf, static_cast<size_t>(r.ptr - buf))))
            return (negative ? "-" : "") + std::string(buf, r.ptr);
    }
    return hex;
}

std::string to_lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

}  // namespace sm2::assembler::syntax
