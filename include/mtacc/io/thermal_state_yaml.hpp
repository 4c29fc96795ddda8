#pragma once
// A machine's thermal state (YAML, docs/file-formats.md "Thermal states"): the temperatures
// along each measuring scale and the spindle's, for `--thermal FILE` on every machine command, so that the model,
// the simulated tests and the compensation tables are those of the warm machine. A logger that
// rewrites the file lets `mtacc compensate --tables` rewrite the controller's tables for the
// current temperatures (seed 003 §2.7: every 60 s).
//   scales:
//     X: {sensors: [0 mm, 337 mm, 600 mm], temperatures: [21.5, 26.0, 22.0], reference: 100 mm}
//   spindle: {model: spindle-drift.yaml, temperatures: {head: 31.5, column: 23.0}, probe_above_tcp: 100 mm}
#include <string>
#include <vector>

#include "mtacc/errors/thermal_state.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// Throws InputError naming file, line and key: an axis that is not a linear axis with a travel,
// sensors not increasing or fewer than two, a temperature per sensor missing or outside
// -50 .. 150 degC, an expansion coefficient outside +-1e-3 /K, an unknown key; a spindle on a
// machine without one, its model unreadable (the model file's own error, or the state's line when
// it cannot be read), a temperature of a model sensor missing, or probe_above_tcp missing where the
// model tilts. The model's path is relative to the state's folder.
ThermalState parseThermalState(const Machine& machine, const std::string& text, const std::string& sourceName);
ThermalState loadThermalState(const Machine& machine, const std::string& path);

}  // namespace mtacc
