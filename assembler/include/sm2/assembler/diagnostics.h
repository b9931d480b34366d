// Diagnostics with file:line:column, shared by the assembler and the sm2 tool.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sm2::assembler {

enum class Severity : uint8_t { Error, Warning, Note };

struct Diagnostic {
    Severity severity = Severity::Error;
    std::string file;      // as given by the caller ("<stdin>", "shader.asm")
    uint32_t line = 0;     // 1-based; 0 = no position (whole program)
    uint32_t column = 0;   // 1-based
    std::string message;
    // "file:line:column: error: message" (or "file: error: message" without a position)
    [[nodiscard]] std::string to_string() const;
};

[[nodiscard]] bool has_errors(const std::vector<Diagnostic>& diagnostics);

}  // namespace sm2::assembler
