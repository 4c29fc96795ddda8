#pragma once
// The workflows whose options are declared in a schema (core/option_schema.hpp), by the CLI
// command's name: what the front ends and the parity test enumerate.
#include <map>
#include <string>

#include "mtacc/core/option_schema.hpp"

namespace mtacc {

const std::map<std::string, const OptionSchema*>& workflowOptionSchemas();

}  // namespace mtacc
