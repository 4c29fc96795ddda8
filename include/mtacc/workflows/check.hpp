#pragma once
// Workflow `check`: a machine description validated and summarised (chains, axes, tool,
// workpiece, the error parameters and the non-zero ones with their values).
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct MachineCheck {
  MachineSetup setup;
  std::vector<Parameter> parameters;  // the catalogue: location errors, then component-error coefficients
  std::vector<Parameter> nonZero;
  int locationCount = 0;
};

MachineCheck checkMachine(const MachineSetup& setup);
nlohmann::json toJson(const MachineCheck& check);

const char* axisTypeName(AxisType type);  // "linear", "rotary", "spindle"

}  // namespace mtacc
