#pragma once
// The options of `mtacc compensate`, shared by its two outputs: a compensated program
// (cmd_compensate.cpp) and controller tables (cmd_compensate_tables.cpp).
#include <string>

#include "cli_common.hpp"
#include "mtacc/workflows/compensation.hpp"

namespace mtacc::cli {

struct CompensateOptions : MachineOptions {
  std::string program, gcode, toolLengths, checkErrors;
  std::string tables, nodes = "21,21,21", pose, checkProgram;
  int functions = 9, linuxcncType = 1;
  double everySeconds = 0.0;  // tables: 0 once; else rewritten each period
  int updates = 0;            // with everySeconds: 0 until a stop signal
  double toleranceUm = ProgramCompensationOptions{}.tolerance * 1e3;
  double directionToleranceUrad = ProgramCompensationOptions{}.directionTolerance * 1e6;
};

// --tables DIR: written once, or with --every rewritten for the thermal state each period.
void runCompensationTables(const CompensateOptions& o);

}  // namespace mtacc::cli
