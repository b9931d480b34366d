// The parts of `sm2 run` that read user text: numbers, input register names and the --lanes CSV
// (a library of their own so the fuzz target tests/fuzz/lanes_fuzz.cpp runs the same code).
#pragma once

#include <charconv>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "sm2/isa/program.h"

namespace sm2::tools {

// Invalid input (a file's content): "sm2 run: <message>", exit status 1.
struct InputError {
    std::string message;
};
// A malformed option value: "sm2 run: <message>", exit status 2 like every usage error.
struct UsageError {
    std::string message;
};

// A decimal number (floats also inf, -inf, nan; a leading '+' allowed); throws Error naming `what`.
template <typename T, typename Error = UsageError>
T parse_number(std::string_view text, const std::string& what) {
    T value{};
    std::string_view t = text;
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    if constexpr (std::is_floating_point_v<T>) {
        if (t == "inf") return std::numeric_limits<T>::infinity();
        if (t == "-inf") return -std::numeric_limits<T>::infinity();
        if (t == "nan") return std::numeric_limits<T>::quiet_NaN();
    }
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc{} || end != t.data() + t.size() || t.empty())
        throw Error{"bad number '" + std::string(text) + "' in " + what};
    return value;
}

std::vector<std::string_view> split(std::string_view s, char sep);

// Where an input register lives in a batch: v# (both shader types) or t# (pixel shaders).
// Throws Error naming `what` for a register the shader type does not have.
template <typename Error = UsageError>
unsigned input_slot(isa::ShaderVersion version, std::string_view name, const std::string& what);

struct LaneValue {
    unsigned slot;
    unsigned component;
    double value;
};
// A --lanes CSV: a header of REGISTER.COMPONENT columns (v0.x, t1.w), then one row of numbers
// per lane; blank lines are skipped, CR LF accepted. Throws InputError naming `name:line`.
std::vector<std::vector<LaneValue>> parse_lanes_csv(std::string_view text, const std::string& name,
                                                    isa::ShaderVersion version);

}  // namespace sm2::tools
