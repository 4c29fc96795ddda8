#pragma once
// Workflow `check`: a machine description validated and summarised (chains, axes, tool,
// workpiece, the error parameters and the non-zero ones with their values), and the location
// errors that no measurement on this machine can tell apart.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/machine/machine_class.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct MachineCheck {
  MachineSetup setup;
  std::vector<Parameter> parameters;  // the catalogue: location errors, then component-error coefficients
  std::vector<Parameter> nonZero;
  int locationCount = 0;
  // Per rotary axis, its zero offset about its own line and what it is in the location
  // errors: "B.zero = 0.707107 B0B + 0.707107 C0B" on a B axis along (0, 1, 1)/sqrt(2).
  std::vector<std::string> zeroOffsets;
  // Location errors that act alike at every pose within travel (TCP and tool direction):
  // "X0B and X0C act alike: only X0B - X0C is observable ...", and those without effect.
  std::vector<std::string> actingAlike;
  // What the description leaves out that a measurement would need: a rotary axis carrying the
  // tool across its line with no spindle element in the structure code, so that the spindle's
  // location errors (the pivot length among them) are not parameters.
  std::vector<std::string> warnings;
  MachineClass machineClass;  // seed 003 Tables 2.2 and 2.3
};

MachineCheck checkMachine(const MachineSetup& setup);
// parameters: list every error parameter in the printed table (the JSON always holds them).
const OptionSchema& checkSchema();
nlohmann::json toJson(const MachineCheck& check);

const char* axisTypeName(AxisType type);  // "linear", "rotary", "spindle"

}  // namespace mtacc
