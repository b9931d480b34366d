// Shared helpers of the assembler tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/isa/bytecode.h"

namespace sm2::assembler::test {

using Tokens = std::vector<uint32_t>;

inline std::string hex(const Tokens& tokens) {
    std::string s;
    char buf[16];
    for (uint32_t t : tokens) {
        std::snprintf(buf, sizeof buf, "%08X ", t);
        s += buf;
    }
    if (!s.empty()) s.pop_back();
    return s;
}

inline std::string diagnostics_text(const AssembleResult& r) {
    std::string s;
    for (const auto& d : r.diagnostics) s += d.to_string() + "\n";
    return s;
}

// Assembles without the validator (the Wine-parity mode); fails the test on errors.
inline Tokens assemble_tokens(std::string_view text, bool wine_order = false) {
    AssembleOptions options;
    options.validate = false;
    options.wine_order = wine_order;
    const AssembleResult r = assemble(text, options);
    EXPECT_TRUE(r.ok()) << text << "\n" << diagnostics_text(r);
    return r.tokens;
}

// The tokens of a one-statement program after the version token, without END.
inline Tokens statement_tokens(std::string_view profile, std::string_view statement) {
    const std::string text = std::string(profile) + "\n" + std::string(statement) + "\n";
    Tokens t = assemble_tokens(text);
    if (t.size() < 2) return {};
    return Tokens(t.begin() + 1, t.end() - 1);
}

inline AssembleResult assemble_unvalidated(std::string_view text) {
    AssembleOptions options;
    options.validate = false;
    return assemble(text, options);
}

}  // namespace sm2::assembler::test
