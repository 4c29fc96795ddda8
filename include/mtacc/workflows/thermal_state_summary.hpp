#pragma once
// The thermal state a machine is evaluated at (--thermal FILE), as the report shows it: per
// scale its sensors, their temperatures, and the expansion along the axis's travel; the
// spindle's drift its temperatures predict.
#include <nlohmann/json.hpp>

#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// {"file", "scales": [{"axis", "sensors_mm", "temperatures_C", "reference_mm", "expansion_per_K",
// "reference_temperature_C", "position_mm", "expansion_um", "largest_um"}], and with a spindle
// "spindle": {"sensors": [{"name", "temperature_C"}], "directions": [{"direction", "unit" (um or
// urad), "drift", "sigma" (one standard deviation of a new reading)}], "probe_above_tcp_mm",
// "at_tcp_um": [x, y, z]}}, the scales' curves at
// `points` positions (2 .. 10001) over the travel. Throws InputError as loadMachineSetup does,
// or for a source without a thermal state.
nlohmann::json thermalStateSummary(const MachineSource& source, int points = 101);

}  // namespace mtacc
