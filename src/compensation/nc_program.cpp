#include "mtacc/compensation/nc_program.hpp"

#include <cmath>

namespace mtacc {

std::vector<double> GcodeMove::at(double s) const {
  std::vector<double> q(from.size());
  for (size_t k = 0; k < q.size(); ++k) q[k] = from[k] + s * (to[k] - from[k]);
  if (!isArc()) return q;
  const auto a = static_cast<size_t>(planeAxes[0]), b = static_cast<size_t>(planeAxes[1]);
  const double r0 = radius(), r1 = std::hypot(to[a] - centre[0], to[b] - centre[1]);
  const double angle = std::atan2(from[b] - centre[1], from[a] - centre[0]) + s * sweep, r = r0 + s * (r1 - r0);
  q[a] = centre[0] + r * std::cos(angle);
  q[b] = centre[1] + r * std::sin(angle);
  return q;
}

double GcodeMove::radius() const {
  return std::hypot(from[static_cast<size_t>(planeAxes[0])] - centre[0], from[static_cast<size_t>(planeAxes[1])] - centre[1]);
}

}  // namespace mtacc
