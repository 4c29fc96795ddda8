#pragma once
// Reading tolerance limits for the Monte Carlo (format in data/limits/seed000-table3.9.yaml).
#include <string>

#include "mtacc/procedures/monte_carlo.hpp"

namespace mtacc {

// Throws InputError naming file, line and key.
ErrorLimits loadErrorLimits(const Machine& machine, const std::string& path);
ErrorLimits parseErrorLimits(const Machine& machine, const std::string& yamlText, const std::string& sourceName);

}  // namespace mtacc
