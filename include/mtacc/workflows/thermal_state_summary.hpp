#pragma once
// The thermal state a machine is evaluated at (--thermal FILE), as the report shows it: per
// scale its sensors, their temperatures, and the expansion along the axis's travel.
#include <nlohmann/json.hpp>

#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// {"file", "scales": [{"axis", "sensors_mm", "temperatures_C", "reference_mm", "expansion_per_K",
// "reference_temperature_C", "position_mm", "expansion_um", "largest_um"}]}, the curve at
// `points` positions (2 .. 10001) over the travel. Throws InputError as loadMachineSetup does,
// or for a source without a thermal state.
nlohmann::json thermalStateSummary(const MachineSource& source, int points = 101);

}  // namespace mtacc
