#pragma once
// Workflow `deviation`: a program (G-code) run on the machine with its errors, against the path
// it or another program was meant to cut: the largest and RMS TCP deviation, the tool
// direction's, and each block's.
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "mtacc/compensation/path_deviation.hpp"
#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct ProgramDeviationRequest {
  std::string programFile;
  std::string intendedFile;           // the program whose nominal path is meant; "": the program's own
  std::map<int, double> toolLengths;  // G43 H<n>: mm beyond the machine file's tool
  PathDeviationOptions options;
};

struct ProgramDeviationResult {
  MachineSetup setup;
  GcodeProgram program;
  std::optional<GcodeProgram> intended;
  ProgramPathDeviation deviation;
  // With an identified errors file: at each sampled block's end, the standard uncertainty (k = 1,
  // mm, x y z) of the TCP the model gives, which after compensating with it is what is not known
  // of the residual; empty otherwise.
  std::vector<Vec3> uncertainty;
};

// program (required), intended, tool_length ("1=0,2=35.5", mm), step (mm).
const OptionSchema& programDeviationSchema();
ProgramDeviationRequest programDeviationRequest(const OptionValues& values);

// Throws InputError naming the file and line of bad G-code, a program without feed moves, or
// the option ("step") out of range.
ProgramDeviationResult programDeviationFile(const MachineSetup& setup, const ProgramDeviationRequest& request);
// um and urad; blocks by line, the worst first among `worst_blocks`; the uncertainty with k = 2.
nlohmann::json toJson(const ProgramDeviationResult& result);

}  // namespace mtacc
