#include "mtacc/workflows/thermal_state_summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/io/thermal_state_yaml.hpp"
#include "mtacc/thermal/scale_expansion.hpp"

namespace mtacc {
namespace {

nlohmann::json spindleSummary(const Machine& machine, const SpindleState& spindle) {
  const Vec6 drift = spindleDrift(spindle.model, spindle.temperatures), sigma = spindleDriftUncertainty(spindle.model, spindle.temperatures);
  nlohmann::json j{{"sensors", nlohmann::json::array()}, {"directions", nlohmann::json::array()}, {"probe_above_tcp_mm", spindle.probeAboveTcp}};
  for (size_t i = 0; i < spindle.model.sensors.size(); ++i)
    j["sensors"].push_back({{"name", spindle.model.sensors[i]}, {"temperature_C", spindle.temperatures[static_cast<long>(i)]}});
  for (const auto d : kDriftDirections) {
    const int k = static_cast<int>(d);
    if (!spindle.model.directions[k]) continue;
    const double scale = displayScaleOf(d);
    j["directions"].push_back({{"direction", nameOf(d)}, {"unit", displayUnitOf(d)}, {"drift", drift[k] * scale}, {"sigma", sigma[k] * scale}});
  }
  const Vec3 atTcp = spindleDriftAtTcp(machine, spindle) * 1e3;
  j["at_tcp_um"] = {atTcp.x(), atTcp.y(), atTcp.z()};
  return j;
}

}  // namespace

nlohmann::json thermalStateSummary(const MachineSource& source, int points) {
  if (source.thermalFile.empty()) throw InputError({"", 0, "thermal"}, "no thermal state given");
  if (points < 2 || points > 10001) throw InputError({"", 0, "points"}, fmt::format("{} points: give 2 to 10001", points));
  const MachineSetup setup = loadMachineSetup(source);
  nlohmann::json j{{"file", source.thermalFile}, {"scales", nlohmann::json::array()}};
  const auto state = loadThermalState(*setup.machine, source.thermalFile);
  for (const auto& scale : state.scales) {
    const auto& axis = setup.machine->axes[static_cast<size_t>(scale.axis)];
    nlohmann::json entry{{"axis", axis.name},
                         {"sensors_mm", scale.sensors.positions},
                         {"temperatures_C", scale.temperatures},
                         {"reference_mm", scale.sensors.referencePosition},
                         {"expansion_per_K", scale.sensors.expansion},
                         {"reference_temperature_C", scale.sensors.referenceTemperature},
                         {"position_mm", nlohmann::json::array()},
                         {"expansion_um", nlohmann::json::array()}};
    double largest = 0.0;
    for (int k = 0; k < points; ++k) {
      const double p = axis.travel->min + (axis.travel->max - axis.travel->min) * k / (points - 1);
      const double delta = scaleExpansion(scale.sensors, scale.temperatures, p) * 1e3;
      entry["position_mm"].push_back(p);
      entry["expansion_um"].push_back(delta);
      if (std::fabs(delta) > std::fabs(largest)) largest = delta;
    }
    entry["largest_um"] = largest;
    j["scales"].push_back(entry);
  }
  if (state.spindle) j["spindle"] = spindleSummary(*setup.machine, *state.spindle);
  return j;
}

}  // namespace mtacc
