#include "sm2/assembler/diagnostics.h"

#include <algorithm>

namespace sm2::assembler {

std::string Diagnostic::to_string() const {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (column > 0) s += ':' + std::to_string(column);
    }
    switch (severity) {
    case Severity::Error: s += ": error: "; break;
    case Severity::Warning: s += ": warning: "; break;
    case Severity::Note: s += ": note: "; break;
    }
    return s + message;
}

bool has_errors(const std::vector<Diagnostic>& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

}  // namespace sm2::assembler
