// PLACEHOLDER until the validator lands in this session.
#include "sm2/isa/validator.h"
namespace sm2::isa {
std::string_view rule_name(Rule) { return "?"; }
std::vector<Violation> validate(const Program&, const ValidationOptions&) { return {}; }
}
