#pragma once
// Reading tolerance limits for the Monte Carlo (format in data/limits/seed000-table3.9.yaml).
#include <string>

#include "mtacc/procedures/monte_carlo.hpp"

namespace mtacc {

// What an entry for an axis the machine lacks does: refused (a user's file: a typo), or left
// out and listed in ErrorLimits::leftOut (limits written for another machine of the family,
// such as the bundled seed 000 table).
enum class AbsentAxes { Refuse, LeaveOut };

// Throws InputError naming file, line and key.
ErrorLimits loadErrorLimits(const Machine& machine, const std::string& path, AbsentAxes absent = AbsentAxes::Refuse);
ErrorLimits parseErrorLimits(const Machine& machine, const std::string& yamlText, const std::string& sourceName,
                             AbsentAxes absent = AbsentAxes::Refuse);

}  // namespace mtacc
