// Assembly text -> Program -> bytecode, byte for byte as Microsoft's assemblers write it
// (every statement in source order), or as Wine's D3DAssemble writes it with wine_order
// (declarations and definitions moved to the top: input dcl, sampler dcl, def, defb, defi,
// then the instructions in source order).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sm2/assembler/diagnostics.h"
#include "sm2/isa/program.h"
#include "sm2/isa/validator.h"

namespace sm2::assembler {

struct AssembleOptions {
    std::string file_name = "<input>";  // used in diagnostics
    bool validate = true;               // run the isa validator; its violations become errors
    isa::ValidationOptions validation;
    size_t max_errors = 20;             // stop reporting after this many
    bool wine_order = false;            // Wine's statement order instead of the source order
};

struct AssembleResult {
    std::optional<isa::Program> program;  // set when there were no errors
    std::vector<uint32_t> tokens;         // the bytecode, version .. END
    std::vector<Diagnostic> diagnostics;  // errors and warnings, in source order
    [[nodiscard]] bool ok() const { return program.has_value(); }
};

// Never throws and never crashes on any input; every problem becomes a diagnostic.
[[nodiscard]] AssembleResult assemble(std::string_view text, const AssembleOptions& options = {});

}  // namespace sm2::assembler
