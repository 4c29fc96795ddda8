#include "mtacc/machine/machine.hpp"

#include <fmt/format.h>

#include "mtacc/core/units.hpp"

namespace mtacc {

int Axis::ownComponent() const {
  switch (name[0]) {
    case 'X': case 'U': return 0;
    case 'Y': case 'V': return 1;
    default: return 2;
  }
}

int Machine::commandedCount() const {
  int n = 0;
  for (const auto& a : axes) n += a.commanded() ? 1 : 0;
  return n;
}

std::vector<std::string> Machine::commandedAxisNames() const {
  std::vector<std::string> names;
  for (const auto& a : axes)
    if (a.commanded()) names.push_back(a.name);
  return names;
}

int Machine::rotaryCount() const {
  int n = 0;
  for (const auto& a : axes) n += a.type == AxisType::Rotary ? 1 : 0;
  return n;
}

int Machine::spindleIndex() const {
  const auto found = std::find_if(axes.begin(), axes.end(), [](const Axis& a) { return a.type == AxisType::Spindle; });
  return found == axes.end() ? -1 : static_cast<int>(found - axes.begin());
}

int Machine::axisIndex(const std::string& axisName) const {
  for (size_t i = 0; i < axes.size(); ++i)
    if (axes[i].name == axisName) return static_cast<int>(i);
  return -1;
}

int Machine::commandedAxisIndex(const std::string& axisName) const {
  const int i = axisIndex(axisName);
  return i >= 0 && axes[static_cast<size_t>(i)].commanded() ? i : -1;
}

std::string Machine::travelViolation(std::span<const double> q) const {
  for (size_t i = 0; i < q.size() && i < axes.size(); ++i) {
    const Axis& a = axes[i];
    if (!a.travel) continue;
    constexpr double tol = 1e-9;
    if (q[i] < a.travel->min - tol || q[i] > a.travel->max + tol) {
      const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
      const char* unit = a.isRotary() ? "deg" : "mm";
      return fmt::format("{}={:.6g} {} beyond travel [{:.6g}, {:.6g}] {}", a.name, q[i] * f, unit, a.travel->min * f,
                         a.travel->max * f, unit);
    }
  }
  return {};
}

std::string Machine::describePose(const std::vector<double>& q) const {
  std::string s;
  for (size_t i = 0; i < q.size() && i < axes.size(); ++i) {
    if (!s.empty()) s += ", ";
    if (axes[i].isRotary())
      s += fmt::format("{}={:.6g} deg", axes[i].name, q[i] / kDeg);
    else
      s += fmt::format("{}={:.6g} mm", axes[i].name, q[i]);
  }
  return s;
}

}  // namespace mtacc
