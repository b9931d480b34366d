// Printing validator violations of bytecode with where they are (sm2 validate, sm2 run).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "sm2/isa/program.h"
#include "sm2/isa/validator.h"

namespace sm2::tools {

// "NAME: token N (byte 0xB): error: [rule] message" and the instruction's text on the next line
// (without the location for whole-program violations).
void print_violations(std::ostream& out, const std::string& name, const isa::Program& program,
                      const std::vector<isa::Violation>& violations);

}  // namespace sm2::tools
