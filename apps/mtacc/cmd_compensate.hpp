#pragma once
// The options of `mtacc compensate`, shared by its two outputs: a compensated program
// (cmd_compensate.cpp) and controller tables (cmd_compensate_tables.cpp).
#include <string>

#include "cli_common.hpp"
#include "mtacc/workflows/compensate_options.hpp"

namespace mtacc::cli {

struct CompensateOptions : MachineOptions {
  OptionValues values;  // compensateSchema()'s
};

// --tables DIR: written once, or with --every rewritten for the thermal state each period.
void runCompensationTables(const CompensateOptions& o);

}  // namespace mtacc::cli
