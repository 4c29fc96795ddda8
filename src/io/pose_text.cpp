#include "mtacc/io/pose_text.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

// Index of a commanded axis named in an assignment; InputError otherwise.
size_t commandedAxis(const Machine& m, const std::string& name, const std::string& key) {
  const int i = m.axisIndex(name);
  if (i < 0 || !m.axes[static_cast<size_t>(i)].commanded()) {
    std::string known;
    for (const auto& a : m.axes)
      if (a.commanded()) known += (known.empty() ? "" : " ") + a.name;
    throw InputError(InputLocation{"", 0, key}, "unknown axis '" + name + "' (commanded axes: " + known + ")");
  }
  return static_cast<size_t>(i);
}

}  // namespace

std::vector<double> parsePose(const Machine& m, const std::string& text, const std::string& key, bool partial) {
  std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
  std::vector<bool> seen(q.size(), false);
  for (const auto& a : parseAssignments(text, key)) {
    const size_t i = commandedAxis(m, a.name, key);
    if (seen[i]) throw InputError(InputLocation{"", 0, key + " " + a.name}, "axis given twice");
    const double v = parseNumber(a.value, key + " " + a.name);
    q[i] = m.axes[i].isRotary() ? v * kDeg : v;
    seen[i] = true;
  }
  for (size_t i = 0; i < q.size() && !partial; ++i)
    if (!seen[i]) throw InputError(InputLocation{"", 0, key}, "axis " + m.axes[i].name + " missing (mm for linear, deg for rotary axes)");
  return q;
}

std::vector<double> parseAxisQuantities(const Machine& m, const std::string& text, const std::string& key) {
  if (text.empty()) return {};
  std::vector<double> out(static_cast<size_t>(m.commandedCount()), 0.0);
  for (const auto& a : parseAssignments(text, key)) {
    const size_t i = commandedAxis(m, a.name, key);
    out[i] = parseQuantityAs(a.value, m.axes[i].isRotary() ? Dimension::Angle : Dimension::Length, key + " " + a.name);
  }
  return out;
}

std::vector<double> parseAxisTimes(const Machine& m, const std::string& text, const std::string& key) {
  if (text.empty()) return {};
  std::vector<double> out(static_cast<size_t>(m.commandedCount()), 0.0);
  for (const auto& a : parseAssignments(text, key)) {
    const size_t i = commandedAxis(m, a.name, key);
    const std::string& v = a.value;
    const bool ms = v.size() > 2 && v.compare(v.size() - 2, 2, "ms") == 0;
    const bool s = !ms && v.size() > 1 && v.back() == 's';
    if (!ms && !s) throw InputError(InputLocation{"", 0, key}, "expected a time in s or ms, got '" + v + "'");
    out[i] = parseNumber(v.substr(0, v.size() - (ms ? 2 : 1)), key + " " + a.name) * (ms ? 1e-3 : 1.0);
  }
  return out;
}

}  // namespace mtacc
