#include "rotary_run_setup.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/units.hpp"

namespace mtacc {

std::vector<double> startPose(const Machine& m) {
  std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
  for (int j = 0; j < m.commandedCount(); ++j) {
    const auto& a = m.axes[static_cast<size_t>(j)];
    if (a.travel && (!a.isRotary() || a.travel->min > 0 || a.travel->max < 0)) q[static_cast<size_t>(j)] = 0.5 * (a.travel->min + a.travel->max);
  }
  return q;
}

Vec3 across(const Vec3& direction) {
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(direction[k]) < std::abs(direction[best])) best = k;
  return (Vec3::Unit(best) - direction * direction[best]).normalized();
}

std::string mm(const Vec3& v) { return fmt::format("[{:.12g} mm, {:.12g} mm, {:.12g} mm]", v.x(), v.y(), v.z()); }

std::string poseEntry(const Machine& m, const std::vector<double>& q, int moving) {
  std::string out;
  for (int j = 0; j < m.commandedCount(); ++j) {
    const auto& a = m.axes[static_cast<size_t>(j)];
    if (j == moving || !a.isRotary()) continue;
    out += fmt::format("{}{}: {:.10g} deg", out.empty() ? "" : ", ", a.name, q[static_cast<size_t>(j)] / kDeg);
  }
  return out.empty() ? "" : ", pose: {" + out + "}";
}

}  // namespace mtacc
