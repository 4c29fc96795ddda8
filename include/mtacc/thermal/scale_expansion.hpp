#pragma once
// The expansion of a measuring scale from N temperature sensors along it (seed 003 §2.7,
// extraction §10.4): the temperature is linear between adjacent sensors, so the expansion is
// piecewise quadratic in the position.
#include <span>
#include <vector>

namespace mtacc {

struct ScaleSensors {
  std::vector<double> positions;       // mm along the axis, increasing; at least two
  double expansion = 11.5e-6;          // alpha, 1/K (steel)
  double referencePosition = 0.0;      // mm: p_ref, where the drift was measured; the expansion is zero there
  double referenceTemperature = 20.0;  // degC: T_ref, at which the scale reads true
};

// Delta(p) = alpha * integral from p_ref to p of (T(u) - T_ref) du, in mm, with T linear between
// adjacent sensors and held at the end sensors' temperatures beyond them. A warm scale reads
// short: the true position is the assigned one plus Delta, so a compensation subtracts it.
// Throws InvalidInput for fewer than two sensors, positions that do not increase, a
// temperature per sensor missing, or a value that is not finite.
double scaleExpansion(const ScaleSensors& scale, std::span<const double> temperatures, double position);

}  // namespace mtacc
