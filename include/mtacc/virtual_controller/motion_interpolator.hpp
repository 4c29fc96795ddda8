#pragma once
// The interpolator of the virtual machine (seed 004 §14.1 of the extraction): a path of axis
// positions travelled at one feed in FGROUP units (linear axes in mm and rotary axes in deg on
// one path length, O8), corners rounded by a Gaussian smoothing along the path, the speed held
// to sqrt(a / curvature) and to a tangential acceleration by forward and backward passes, a
// moving-average filter on the positions that bounds the jerk, and a dwell at each end.
#include <vector>

#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

struct InterpolatorLimits {
  double acceleration = 3000.0;  // path units/s^2 (mm/s^2 and deg/s^2 on one length)
  double jerkTime = 0.006;       // s: length of the moving average (jerk <= acceleration / jerkTime)
  double cornerRounding = 0.25;  // path units: standard deviation of the smoothing along the path
  double dwell = 0.15;           // s at rest before and after the motion
};

// `path`: the commanded axes at successive points (mm, rad), the controller's straight moves
// between them (arcs given as dense points). `rotary` marks the axes measured in deg on the path.
// Returns the commanded positions (mm, rad) every `period` s from time 0. Throws
// InvalidInput for fewer than two distinct points, rows of another length, a feed,
// limit or period that is not positive and finite, or more than 10^8 samples.
SampledTrace interpolateMotion(const std::vector<std::vector<double>>& path, const std::vector<bool>& rotary, double feed,
                               const InterpolatorLimits& limits, double period);

}  // namespace mtacc
