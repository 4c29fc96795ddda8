#include "mtacc/errors/thermal_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace mtacc {

PiecewiseTerm scaleExpansionTerm(const ScaleSensors& sensors, const std::vector<double>& temperatures, double from, double to) {
  if (!(to > from)) throw std::invalid_argument(fmt::format("an empty span for a scale's expansion ({} .. {} mm)", from, to));
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

ErrorModel atThermalState(const Machine& machine, ErrorModel errors, const std::vector<ScaleState>& scales) {
  std::vector<int> seen;
  for (const auto& scale : scales) {
    if (scale.axis < 0 || scale.axis >= static_cast<int>(machine.axes.size()))
      throw std::invalid_argument(fmt::format("a scale on axis {} of {}", scale.axis, machine.axes.size()));
    const auto& axis = machine.axes[static_cast<size_t>(scale.axis)];
    if (axis.type != AxisType::Linear || !axis.travel)
      throw std::invalid_argument(fmt::format("axis {}: a scale expands only on a linear axis with a travel", axis.name));
    if (std::count(seen.begin(), seen.end(), scale.axis)) throw std::invalid_argument(fmt::format("axis {}: two scales", axis.name));
    seen.push_back(scale.axis);
    // The error motion is the moving part's: a table (workpiece side) goes -Delta d further.
    auto term = scaleExpansionTerm(scale.sensors, scale.temperatures, axis.travel->min, axis.travel->max);
    if (axis.side == Side::Workpiece)
      for (auto& c : term.coefficients) c.value = -c.value;
    errors.axes[static_cast<size_t>(scale.axis)].motion[static_cast<size_t>(axis.ownComponent())].add(std::move(term));
  }
  return errors;
}

}  // namespace mtacc
