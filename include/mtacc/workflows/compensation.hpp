#pragma once
// Workflow `compensate program`: an axis program (G-code) read for a machine, compensated for
// the machine's errors, as G-code text and a summary (corrections, what the tool's path would
// deviate from the program on the machine with its errors, before and after).
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "mtacc/compensation/program_compensation.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct ProgramCompensationRequest {
  std::string programFile;
  std::map<int, double> toolLengths;  // G43 H<n>: mm beyond the machine file's tool
  ProgramCompensationOptions options;
};

struct ProgramCompensationResult {
  MachineSetup setup;
  GcodeProgram program;
  CompensatedProgram compensated;
  ProgramDeviation deviation;  // the program as written and compensated, on the machine with its errors
  std::string gcode;  // the compensated program
};

// Throws InputError naming the program's file and line for bad G-code, and for a compensated
// point beyond travel (nothing is written then).
ProgramCompensationResult compensateProgramFile(const MachineSetup& setup, const ProgramCompensationRequest& request);
nlohmann::json toJson(const ProgramCompensationResult& result);

}  // namespace mtacc
