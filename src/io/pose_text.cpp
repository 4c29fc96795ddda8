#include "mtacc/io/pose_text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

// Index of a commanded axis named in an assignment; InputError otherwise.
size_t commandedAxis(const Machine& m, const std::string& name, const std::string& key) {
  const int i = m.commandedAxisIndex(name);
  if (i < 0) {
    const auto known = fmt::format("{}", fmt::join(m.commandedAxisNames(), " "));
    throw InputError(InputLocation{"", 0, key}, "unknown axis '" + name + "' (commanded axes: " + known + ")");
  }
  return static_cast<size_t>(i);
}

// Values per commanded axis from "AXIS=value, ..." (each axis at most once; the others 0).
struct AxisValues {
  std::vector<double> values;
  std::vector<bool> given;
};
template <class ParseValue>
AxisValues parsePerAxis(const Machine& m, const std::string& text, const std::string& key, ParseValue&& parseValue) {
  AxisValues out{std::vector<double>(static_cast<size_t>(m.commandedCount()), 0.0),
                 std::vector<bool>(static_cast<size_t>(m.commandedCount()), false)};
  for (const auto& a : parseAssignments(text, key)) {
    const size_t i = commandedAxis(m, a.name, key);
    if (out.given[i]) throw InputError(InputLocation{"", 0, key + " " + a.name}, "axis given twice");
    out.values[i] = parseValue(a.value, m.axes[i], key + " " + a.name);
    out.given[i] = true;
  }
  return out;
}

}  // namespace

std::vector<double> parsePose(const Machine& m, const std::string& text, const std::string& key, bool partial) {
  const auto pose = parsePerAxis(m, text, key, [](const std::string& value, const Axis& axis, const std::string& k) {
    const double v = parseNumber(value, k);
    return v * axis.fileUnit();
  });
  for (size_t i = 0; i < pose.given.size() && !partial; ++i)
    if (!pose.given[i])
      throw InputError(InputLocation{"", 0, key}, "axis " + m.axes[i].name + " missing (mm for linear, deg for rotary axes)");
  return pose.values;
}

std::vector<double> parseAxisQuantities(const Machine& m, const std::string& text, const std::string& key) {
  if (text.empty()) return {};
  return parsePerAxis(m, text, key, [](const std::string& value, const Axis& axis, const std::string& k) {
           return parseQuantityAs(value, axis.isRotary() ? Dimension::Angle : Dimension::Length, k);
         }).values;
}

std::vector<double> parseAxisTimes(const Machine& m, const std::string& text, const std::string& key) {
  if (text.empty()) return {};
  return parsePerAxis(m, text, key, [&](const std::string& v, const Axis&, const std::string& k) {
           const bool ms = v.size() > 2 && v.compare(v.size() - 2, 2, "ms") == 0;
           const bool s = !ms && v.size() > 1 && v.back() == 's';
           if (!ms && !s) throw InputError(InputLocation{"", 0, key}, "expected a time in s or ms, got '" + v + "'");
           return parseNumber(v.substr(0, v.size() - (ms ? 2 : 1)), k) * (ms ? 1e-3 : 1.0);
         }).values;
}

}  // namespace mtacc
