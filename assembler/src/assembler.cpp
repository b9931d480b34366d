// assemble(): text -> tokens -> statements -> Program (source order, or Wine's) -> validation -> bytecode.
#include "sm2/assembler/assembler.h"

#include <algorithm>
#include <exception>

#include "lexer.h"
#include "parser.h"
#include "sm2/isa/bytecode.h"

namespace sm2::assembler {

namespace {

using detail::Group;

// Wine's writer emits the version, then all input dcls, sampler dcls, defs, defbs and defis
// (each in source order), then the instructions and comment blocks (spec README item 1).
constexpr Group kEmitOrder[] = {Group::InputDcl, Group::SamplerDcl, Group::Def,
                                Group::DefB,     Group::DefI,       Group::Code};

void run(std::string_view text, const AssembleOptions& options, detail::Reporter& reporter,
         AssembleResult& result) {
    const std::vector<detail::Token> tokens = detail::tokenize(text, reporter);
    detail::ParseOutput parsed = detail::parse(tokens, reporter);
    if (reporter.error_count() > 0 || !parsed.version) return;

    isa::Program program;
    program.version = *parsed.version;
    std::vector<uint32_t> files;  // file of each program instruction
    program.instructions.reserve(parsed.statements.size());
    if (options.wine_order) {
        for (Group group : kEmitOrder) {
            for (detail::Statement& s : parsed.statements) {
                if (s.group != group) continue;
                program.instructions.push_back(std::move(s.instruction));
                files.push_back(s.file);
            }
        }
    } else {
        for (detail::Statement& s : parsed.statements) {
            program.instructions.push_back(std::move(s.instruction));
            files.push_back(s.file);
        }
    }

    if (options.validate) {
        for (const isa::Violation& v : isa::validate(program, options.validation)) {
            const std::string message = "[" + std::string(isa::rule_name(v.rule)) + "] " + v.message;
            const bool in_program = v.instruction < program.instructions.size();
            const uint32_t file = in_program ? files[v.instruction] : 0;
            isa::SourceLocation at = v.location;
            if (at.line == 0 && in_program) at = program.instructions[v.instruction].location;
            if (at.line == 0)
                reporter.error_whole(message);
            else
                reporter.error_at(file, at.line, at.column, at.line, message);
        }
        if (reporter.error_count() > 0) return;
    }
    result.tokens = isa::encode(program);
    result.program = std::move(program);
}

}  // namespace

AssembleResult assemble(std::string_view text, const AssembleOptions& options) {
    AssembleResult result;
    detail::Reporter reporter(options.file_name);
    try {
        run(text, options, reporter, result);
    } catch (const std::exception& e) {
        result.program.reset();
        result.tokens.clear();
        reporter.error_whole(std::string("internal error: ") + e.what());
    }
    result.diagnostics = reporter.take(options.max_errors);
    return result;
}

}  // namespace sm2::assembler
