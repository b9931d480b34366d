// What the HLSL command-line tests share: compile HLSL with `sm2 compile`, run the bytecode with
// `sm2 run` and read an output register's values.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"

namespace hlsl_support {

// Compiles `hlsl` with `profile` into a bytecode file; fails the test (and returns "") on errors.
inline std::string compile(const std::string& name, const std::string& hlsl, const std::string& profile,
                           const std::string& extra = "") {
    const std::string source = cli_support::tmp(name + ".hlsl"), output = cli_support::tmp(name + ".bin");
    cli_support::write_file(source, hlsl);
    const cli_support::Run r = cli_support::sm2("compile " + source + " -T " + profile + " -o " + output + " " + extra);
    EXPECT_EQ(r.status, 0) << r.err;
    return r.status == 0 ? output : std::string();
}

// The values `sm2 run` prints for one output register ("oC0 = 1 0.5 0.25 1"); none if absent.
inline std::vector<float> output_of(const std::string& run_text, const std::string& reg) {
    std::istringstream lines(run_text);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind(reg + " = ", 0) != 0) continue;
        std::istringstream values(line.substr(reg.size() + 3));
        std::vector<float> out;
        for (float f; values >> f;) out.push_back(f);
        return out;
    }
    return {};
}

inline void expect_near(const std::vector<float>& actual, const std::vector<float>& expected, float tolerance = 1e-5f) {
    ASSERT_EQ(actual.size(), expected.size());
    for (size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(actual[k], expected[k], tolerance) << "component " << k;
}

// `sm2 run SHADER ARGS`' values of `reg`; fails the test if the run fails or prints no `reg`.
inline std::vector<float> run_output(const std::string& shader, const std::string& args, const std::string& reg) {
    const cli_support::Run r = cli_support::sm2("run " + shader + " " + args);
    EXPECT_EQ(r.status, 0) << r.err;
    std::vector<float> out = output_of(r.out, reg);
    if (out.empty()) ADD_FAILURE() << "no " << reg << " in: " << r.out;
    return out;
}

}  // namespace hlsl_support
