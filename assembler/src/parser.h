// Tokens -> statements of a Program, in source order, each tagged with the group Wine's
// writer puts it in (input dcl, sampler dcl, def, defb, defi, or an instruction).
#pragma once

#include <optional>
#include <vector>

#include "lexer.h"
#include "sm2/isa/program.h"

namespace sm2::assembler::detail {

enum class Group : uint8_t { InputDcl, SamplerDcl, Def, DefB, DefI, Code };

struct Statement {
    isa::Instruction instruction;
    Group group = Group::Code;
    uint32_t file = 0;  // Reporter::files index, for diagnostics about this statement
};

struct ParseOutput {
    std::optional<isa::ShaderVersion> version;
    std::vector<Statement> statements;
};

[[nodiscard]] ParseOutput parse(const std::vector<Token>& tokens, Reporter& reporter);

}  // namespace sm2::assembler::detail
