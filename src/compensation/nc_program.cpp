#include "mtacc/compensation/nc_program.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mtacc {

std::vector<double> GcodeMove::at(double s) const {
  std::vector<double> q;
  at(s, q);
  return q;
}

void GcodeMove::at(double s, std::vector<double>& q) const {
  q.resize(from.size());
  for (size_t k = 0; k < q.size(); ++k) q[k] = from[k] + s * (to[k] - from[k]);
  if (!isArc()) return;
  const auto a = static_cast<size_t>(planeAxes[0]), b = static_cast<size_t>(planeAxes[1]);
  const double r0 = radius(), r1 = std::hypot(to[a] - centre[0], to[b] - centre[1]);
  const double angle = std::atan2(from[b] - centre[1], from[a] - centre[0]) + s * sweep, r = r0 + s * (r1 - r0);
  q[a] = centre[0] + r * std::cos(angle);
  q[b] = centre[1] + r * std::sin(angle);
}

std::vector<int> GcodeMove::motion(double s) const {
  std::vector<int> d;
  heldMotion(s, d);
  return d;
}

void GcodeMove::heldMotion(double s, std::vector<int>& held) const {
  held.resize(from.size(), 0);
  // Along the circle for an arc's plane axes (an end radius differing by its tolerance does not
  // move the quadrants), along the line for the others.
  double alongArc[2] = {0.0, 0.0};
  if (isArc()) {
    const double angle = std::atan2(from[static_cast<size_t>(planeAxes[1])] - centre[1], from[static_cast<size_t>(planeAxes[0])] - centre[0]) + s * sweep;
    alongArc[0] = -sweep * std::sin(angle);
    alongArc[1] = sweep * std::cos(angle);
  }
  auto rate = [&](size_t k) {
    if (isArc() && static_cast<int>(k) == planeAxes[0]) return alongArc[0];
    if (isArc() && static_cast<int>(k) == planeAxes[1]) return alongArc[1];
    return to[k] - from[k];
  };
  double largest = 0.0;
  for (size_t k = 0; k < held.size(); ++k) largest = std::max(largest, std::abs(rate(k)));
  // Rounding leaves a standing axis (an arc's quadrant point) a rate of about 1e-16 of the others.
  for (size_t k = 0; k < held.size(); ++k)
    if (const double r = rate(k); std::abs(r) > 1e-12 * largest) held[k] = r > 0 ? 1 : -1;
}

std::vector<double> GcodeMove::reversals() const {
  std::vector<double> at;
  if (!isArc()) return at;
  const double start = std::atan2(from[static_cast<size_t>(planeAxes[1])] - centre[1], from[static_cast<size_t>(planeAxes[0])] - centre[0]);
  const double quarter = std::numbers::pi / 2.0, end = start + sweep;
  // Every multiple of a quarter turn strictly between the start and end angles.
  const double low = std::min(start, end), high = std::max(start, end);
  for (double m = std::floor(low / quarter) + 1.0; m * quarter < high; m += 1.0) {
    const double s = (m * quarter - start) / sweep;
    if (s > 1e-12 && s < 1.0 - 1e-12) at.push_back(s);
  }
  std::sort(at.begin(), at.end());
  return at;
}

double GcodeMove::radius() const {
  return std::hypot(from[static_cast<size_t>(planeAxes[0])] - centre[0], from[static_cast<size_t>(planeAxes[1])] - centre[1]);
}

}  // namespace mtacc
