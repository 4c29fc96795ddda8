#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/overloaded.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"

namespace mtacc {
namespace {

// 15 significant digits: the value read back is the value written (to the last few ulp).
std::string value(double v, Dimension d) {
  return d == Dimension::Angle ? fmt::format("{:.15g} urad", v * 1e6) : fmt::format("{:.15g} um", v * 1e3);
}
std::string position(double q, Dimension d) {
  return d == Dimension::Angle ? fmt::format("{:.15g} deg", q / kDeg) : fmt::format("{:.15g} mm", q);
}
template <class Range, class F>
std::string list(const Range& items, F&& format) {
  std::string s = "[";
  for (const auto& x : items) {
    if (s.size() > 1) s += ", ";
    s += format(x);
  }
  return s + "]";
}

std::string termBlock(const ErrorTerm& term, Dimension valueDim, Dimension posDim) {
  return std::visit(
      Overloaded{[&](const PolynomialTerm& p) {
                   return fmt::format("polynomial: {{scale: {}, zero: {}, coefficients: {}}}", position(p.scale, posDim),
                                      position(p.zero, posDim), list(p.coefficients, [&](double c) { return value(c, valueDim); }));
                 },
                 [&](const HarmonicTerm& h) {
                   if (h.cyclic)
                     return fmt::format("cyclic: {{pitch: {}, zero: {}, amplitude: {}, phase: {:.15g} deg}}", position(h.period, posDim),
                                        position(h.zero, posDim), value(h.amplitude, valueDim), h.phase / kDeg);
                   const std::string shape = h.part == HarmonicPart::Amplitude ? fmt::format("phase: {:.15g} deg", h.phase / kDeg)
                                             : h.part == HarmonicPart::Cosine  ? std::string("part: cosine")
                                                                               : std::string("part: sine");
                   return fmt::format("harmonics: {{period: {}, zero: {}, terms: [{{order: {}, amplitude: {}, {}}}]}}",
                                      position(h.period, posDim), position(h.zero, posDim), h.order, value(h.amplitude, valueDim), shape);
                 },
                 [&](const TableTerm& t) {
                   return fmt::format("table: {{positions: {}, values: {}, interpolation: {}}}",
                                      list(t.positions, [&](double q) { return position(q, posDim); }),
                                      list(t.values, [&](double v) { return value(v, valueDim); }),
                                      t.interpolation == Interpolation::Linear ? "linear" : "spline");
                 },
                 [&](const ReversalTerm& r) { return "reversal: " + value(r.width, valueDim); },
                 [&](const PiecewiseTerm& p) { return "piecewise: " + piecewiseBlockYaml(p, valueDim, posDim); }},
      term);
}

std::string stiffnessBlock(const Machine& machine, const StiffnessError& s, Dimension valueDim) {
  const Dimension own = machine.axes[static_cast<size_t>(s.axis)].isRotary() ? Dimension::Angle : Dimension::Length;
  std::string out = "stiffness: {";
  if (s.referenceLoad > 0.0) out += fmt::format("load: {:.15g} kg, ", s.referenceLoad);
  const double unit = valueDim == Dimension::Angle ? 1e-6 : 1e-3;
  out += fmt::format("unit: {}, positions: {}", valueDim == Dimension::Angle ? "urad" : "um",
                     list(s.positions, [&](double q) { return position(q, own); }));
  if (s.otherAxis >= 0) {
    const Axis& other = machine.axes[static_cast<size_t>(s.otherAxis)];
    out += fmt::format(", with: {}, with_positions: {}", other.name,
                       list(s.otherPositions, [&](double q) { return position(q, other.isRotary() ? Dimension::Angle : Dimension::Length); }));
  }
  // One value per position, or with another axis one row per position.
  std::string rows;
  for (Eigen::Index i = 0; i < s.values.rows(); ++i) {
    std::string row;
    for (Eigen::Index j = 0; j < s.values.cols(); ++j) row += fmt::format("{}{:.15g}", j ? ", " : "", s.values(i, j) / unit);
    if (i) rows += ", ";
    rows += s.otherAxis >= 0 ? "[" + row + "]" : row;
  }
  return out + ", values: [" + rows + "]}";
}

}  // namespace

std::string piecewiseBlockYaml(const PiecewiseTerm& t, Dimension valueDimension, Dimension positionDimension) {
  const bool angle = valueDimension == Dimension::Angle, rotary = positionDimension == Dimension::Angle;
  const double unit = angle ? kArcsec : 1.0, per = rotary ? kDeg : 1.0;
  std::string out = fmt::format("{{unit: {}, per: {}, breaks: {}", angle ? "arcsec" : "mm", rotary ? "deg" : "mm",
                                list(t.breaks, [&](double b) { return fmt::format("{:.15g}", b / per); }));
  if (t.period > 0.0) out += fmt::format(", period: {:.15g}, zero: {:.15g}", t.period / per, t.zero / per);
  return out + ", intervals: " + list(t.intervals(), [&](const std::array<double, 3>& c) {
           return fmt::format("[{:.15e}, {:.15e}, {:.15e}]", c[0] / unit, c[1] * per / unit, c[2] * per * per / unit);
         }) + "}";
}

std::string errorsYaml(const Machine& machine, const ErrorModel& errors) {
  std::string out;
  bool loadDependent = false;
  for (const auto& s : errors.stiffness) loadDependent = loadDependent || s.referenceLoad > 0.0;
  if (loadDependent) out += fmt::format("workpiece_load: {:.15g} kg\n", errors.workpieceLoad);
  std::string entries;
  for (const auto& p : parameterCatalogue(machine, errors))
    if (p.kind == ParameterKind::Location && parameterValue(errors, p) != 0.0)
      entries += fmt::format("  {}: {}\n", p.name, value(parameterValue(errors, p), p.dimension));
  for (int a = 0; a < static_cast<int>(machine.axes.size()); ++a) {
    const Dimension posDim = machine.axes[static_cast<size_t>(a)].isRotary() ? Dimension::Angle : Dimension::Length;
    for (int c = 0; c < 6; ++c) {
      const Dimension valueDim = c < 3 ? Dimension::Length : Dimension::Angle;
      std::string blocks;
      for (const auto& term : errors.axes[static_cast<size_t>(a)].motion[static_cast<size_t>(c)].terms())
        blocks += "    - " + termBlock(term, valueDim, posDim) + "\n";
      for (const auto& s : errors.stiffness)
        if (s.axis == a && s.component == c) blocks += "    - " + stiffnessBlock(machine, s, valueDim) + "\n";
      if (!blocks.empty()) entries += "  " + motionErrorName(machine, a, c) + ":\n" + blocks;
    }
  }
  return out + (entries.empty() ? "errors: {}\n" : "errors:\n" + entries);
}

}  // namespace mtacc
