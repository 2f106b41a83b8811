#pragma once
// `fluidbed check`: derived quantities of a case, so a user sees what the numbers imply before running.
#include <string>

#include "io/case_config.hpp"

namespace fluidbed {

std::string describe_case(const CaseConfig& c);

}  // namespace fluidbed
