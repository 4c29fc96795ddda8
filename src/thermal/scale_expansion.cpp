#include "mtacc/thermal/scale_expansion.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

void check(const ScaleSensors& scale, std::span<const double> temperatures, double position) {
  const auto& s = scale.positions;
  if (s.size() < 2) throw InvalidInput(fmt::format("a scale needs at least two temperature sensors, not {}", s.size()));
  if (temperatures.size() != s.size())
    throw InvalidInput(fmt::format("{} temperatures for {} sensors on the scale", temperatures.size(), s.size()));
  for (size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i]) || !std::isfinite(temperatures[i])) throw InvalidInput(fmt::format("scale sensor {}: not a finite number", i));
    if (i > 0 && !(s[i] > s[i - 1]))
      throw InvalidInput(fmt::format("scale sensors must be in increasing position ({} mm after {} mm)", s[i], s[i - 1]));
  }
  if (!std::isfinite(position) || !std::isfinite(scale.expansion) || !std::isfinite(scale.referencePosition) ||
      !std::isfinite(scale.referenceTemperature))
    throw InvalidInput("scale expansion: a position, coefficient or reference that is not finite");
}

// The integral of T(u) - T_ref from the first sensor to x (negative below it), K mm.
double excessIntegral(const std::vector<double>& s, std::span<const double> t, double reference, double x) {
  if (x <= s.front()) return (t.front() - reference) * (x - s.front());
  double sum = 0.0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const double length = s[i + 1] - s[i], slope = (t[i + 1] - t[i]) / length;
    const double d = std::min(x, s[i + 1]) - s[i];
    sum += (t[i] - reference) * d + 0.5 * slope * d * d;
    if (x <= s[i + 1]) return sum;
  }
  return sum + (t.back() - reference) * (x - s.back());
}

}  // namespace

double scaleExpansion(const ScaleSensors& scale, std::span<const double> temperatures, double position) {
  check(scale, temperatures, position);
  const auto& s = scale.positions;
  const double T = scale.referenceTemperature;
  return scale.expansion * (excessIntegral(s, temperatures, T, position) - excessIntegral(s, temperatures, T, scale.referencePosition));
}

}  // namespace mtacc
