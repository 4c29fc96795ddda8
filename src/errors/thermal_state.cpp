#include "mtacc/errors/thermal_state.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

PiecewiseTerm scaleExpansionTerm(const ScaleSensors& sensors, const std::vector<double>& temperatures, double from, double to) {
  if (!(to > from)) throw InvalidInput(fmt::format("an empty span for a scale's expansion ({} .. {} mm)", from, to));
  std::vector<double> breaks{from, to};
  for (const double s : sensors.positions)
    if (s > from && s < to) breaks.push_back(s);
  std::sort(breaks.begin(), breaks.end());
  std::vector<std::array<double, 3>> intervals;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    // Delta in v = u - start over [0, h]: a0 + a1 v + a2 v^2 from v = 0, h/2, h; then in u.
    const double start = breaks[k], h = breaks[k + 1] - start;
    const double d0 = scaleExpansion(sensors, temperatures, start), dm = scaleExpansion(sensors, temperatures, start + h / 2),
                 d1 = scaleExpansion(sensors, temperatures, start + h);
    const double a2 = 2 * (d1 - 2 * dm + d0) / (h * h), a1 = (d1 - d0) / h - a2 * h, a0 = d0;
    intervals.push_back({a0 - a1 * start + a2 * start * start, a1 - 2 * a2 * start, a2});
  }
  return piecewiseFromIntervals(breaks, intervals);
}

namespace {

void addScales(const Machine& machine, ErrorModel& errors, const std::vector<ScaleState>& scales) {
  std::vector<int> seen;
  for (const auto& scale : scales) {
    if (scale.axis < 0 || scale.axis >= static_cast<int>(machine.axes.size()))
      throw InvalidInput(fmt::format("a scale on axis {} of {}", scale.axis, machine.axes.size()));
    const auto& axis = machine.axes[static_cast<size_t>(scale.axis)];
    if (axis.type != AxisType::Linear || !axis.travel)
      throw InvalidInput(fmt::format("axis {}: a scale expands only on a linear axis with a travel", axis.name));
    if (std::count(seen.begin(), seen.end(), scale.axis)) throw InvalidInput(fmt::format("axis {}: two scales", axis.name));
    seen.push_back(scale.axis);
    // The error motion is the moving part's: a table (workpiece side) goes -Delta d further.
    auto term = scaleExpansionTerm(scale.sensors, scale.temperatures, axis.travel->min, axis.travel->max);
    if (axis.side == Side::Workpiece)
      for (auto& c : term.coefficients) c.value = -c.value;
    errors.axes[static_cast<size_t>(scale.axis)].motion[static_cast<size_t>(axis.ownComponent())].add(std::move(term));
  }
}

// The drift measured at the probe (drift: X, Y, Z in mm, A, B in rad) carried to the TCP.
Vec3 driftAtTcp(const Machine& machine, const SpindleState& spindle, const Vec6& drift) {
  const Mat3 turn = rotationXYZ(drift[kA], drift[kB], 0.0);
  return drift.head<3>() - (turn - Mat3::Identity()) * (spindle.probeAboveTcp * machine.toolDirection);
}

// The spindle's location error is a rotation R about its location point L and a translation t;
// it moves a point P of the spindle's frame by t + (R - I)(P - L).
void addSpindleDrift(const Machine& machine, ErrorModel& errors, const SpindleState& spindle) {
  const int index = machine.spindleIndex();
  if (index < 0)
    throw InvalidInput("the machine has no spindle for the spindle's drift to move: name it in the structure code, e.g. t-(C)-Z-b-Y-X-w");
  const Axis& axis = machine.axes[static_cast<size_t>(index)];
  const Vec6 drift = spindleDrift(spindle.model, spindle.temperatures);
  Vec6 location = Vec6::Zero();
  location.head<3>() = driftAtTcp(machine, spindle, drift) - (rotationXYZ(drift[kA], drift[kB], 0.0) - Mat3::Identity()) * (machine.toolOffset - axis.location);
  location[kA] = drift[kA];
  location[kB] = drift[kB];
  errors.axes[static_cast<size_t>(index)].location += location;
}

}  // namespace

Vec3 spindleDriftAtTcp(const Machine& machine, const SpindleState& spindle) {
  return driftAtTcp(machine, spindle, spindleDrift(spindle.model, spindle.temperatures));
}

ErrorModel atThermalState(const Machine& machine, ErrorModel errors, const ThermalState& state) {
  addScales(machine, errors, state.scales);
  if (state.spindle) addSpindleDrift(machine, errors, *state.spindle);
  return errors;
}

}  // namespace mtacc
