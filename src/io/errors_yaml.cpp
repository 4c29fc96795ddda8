#include "mtacc/io/errors_yaml.hpp"

#include <map>

#include "mtacc/core/text_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "yaml_input.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/errors/axis_shift.hpp"

namespace mtacc {
namespace {

using yamlin::Context;

Dimension axisDimension(const Axis& a) { return a.isRotary() ? Dimension::Angle : Dimension::Length; }

// One `piecewise:` block (seed 003 App. D): breaks and coefficients in `per` units of position,
// values in `unit`; coefficient j of an interval in unit per per^j.
PiecewiseTerm readPiecewise(const Context& ctx, const Axis& axis, const YAML::Node& v, const std::string& k,
                            Dimension valueDim, Dimension posDim) {
  yamlin::rejectUnknownKeys(ctx, v, k, {"unit", "per", "breaks", "intervals", "period", "zero"});
  auto unitOf = [&](const char* name, Dimension dim) {
    const std::string key = k + "." + name;
    if (!v[name]) ctx.fail(v, key, std::string("missing '") + name + "': the unit of the " + (dim == Dimension::Length ? "lengths" : "angles"));
    const auto text = yamlin::scalar(ctx, v[name], key);
    const auto q = parseQuantity("1 " + text);
    if (!q || q->dimension != dim) ctx.fail(v[name], key, "'" + text + "' is not a unit of " + withArticle(dim));
    return q->value;
  };
  const double unit = unitOf("unit", valueDim);
  const double per = unitOf("per", posDim);
  const auto breaks = v["breaks"];
  const auto rows = v["intervals"];
  if (!yamlin::isSequence(breaks) || breaks.size() < 2) ctx.fail(v, k + ".breaks", "expected a list of at least two positions");
  if (!yamlin::isSequence(rows)) ctx.fail(v, k + ".intervals", "expected a list of [c0, c1, c2] per interval");
  if (rows.size() + 1 != breaks.size())
    ctx.fail(rows, k + ".intervals", fmt::format("{} interval(s) for {} breaks: expected {}", rows.size(), breaks.size(), breaks.size() - 1));
  std::vector<double> t;
  for (const auto& b : breaks) {
    t.push_back(per * yamlin::number(ctx, b, k + ".breaks"));
    if (std::abs(t.back()) > largestMagnitude(posDim)) ctx.fail(b, k + ".breaks", "position beyond the largest allowed");
    if (t.size() > 1 && !(t.back() > t[t.size() - 2])) ctx.fail(b, k + ".breaks", "breaks must increase strictly");
  }
  double period = 0.0, zero = 0.0;
  if (v["period"]) {
    period = per * yamlin::number(ctx, v["period"], k + ".period");
    if (!(period > 0.0 && period <= largestMagnitude(posDim))) ctx.fail(v["period"], k + ".period", "the period must be positive");
    if (v["zero"]) zero = per * yamlin::number(ctx, v["zero"], k + ".zero");
    if (std::abs(zero) > largestMagnitude(posDim)) ctx.fail(v["zero"], k + ".zero", "position beyond the largest allowed");
    if (t.front() != 0.0 || std::abs(t.back() - period) > 1e-9 * period)
      ctx.fail(breaks, k + ".breaks", "the breaks of a periodic term run from 0 to the period");
  } else if (v["zero"]) {
    ctx.fail(v["zero"], k + ".zero", "'zero' needs a 'period'");
  } else if (axis.travel) {
    const double slack = 1e-9 * std::max(1.0, axis.travel->max - axis.travel->min);
    if (t.front() < axis.travel->min - slack || t.back() > axis.travel->max + slack)
      ctx.fail(breaks, k + ".breaks",
               fmt::format("the breaks {:g} to {:g} reach beyond the axis travel {:g} to {:g}", t.front() / per,
                           t.back() / per, axis.travel->min / per, axis.travel->max / per));
  }
  std::vector<std::array<double, 3>> intervals;
  for (const auto& row : rows) {
    if (!yamlin::isSequence(row) || row.size() < 1 || row.size() > 3)
      ctx.fail(row, k + ".intervals", "expected [c0], [c0, c1] or [c0, c1, c2] (degree at most 2)");
    std::array<double, 3> c{0.0, 0.0, 0.0};
    for (size_t j = 0; j < row.size(); ++j) c[j] = unit * yamlin::number(ctx, row[j], k + ".intervals") / std::pow(per, static_cast<double>(j));
    const size_t i = intervals.size();
    const double vertex = c[2] != 0.0 ? std::clamp(-c[1] / (2.0 * c[2]), t[i], t[i + 1]) : t[i];
    for (const double u : {t[i], t[i + 1], vertex})
      if (!(std::abs(c[0] + u * (c[1] + u * c[2])) <= largestMagnitude(valueDim)))
        ctx.fail(row, k + ".intervals", "the polynomial exceeds the largest allowed value on its interval");
    intervals.push_back(c);
  }
  return piecewiseFromIntervals(std::move(t), intervals, period, zero);
}

// A mass "<number> kg" within [0, 1e6] kg (above 0 when `positive`).
double readLoad(const Context& ctx, const YAML::Node& node, const std::string& key, bool positive) {
  const std::string text = yamlin::scalar(ctx, node, key);
  const char* begin = text.c_str();
  char* end = nullptr;
  const double load = std::strtod(begin, &end);
  std::string_view unit(end, static_cast<size_t>(begin + text.size() - end));
  while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  if (end == begin || unit != "kg") ctx.fail(node, key, "'" + text + "' is not a mass: expected e.g. '260 kg'");
  if (!(load >= 0.0 && load <= 1e6) || (positive && load == 0.0))
    ctx.fail(node, key, fmt::format("'{}' is not a load: expected {} to 1e6 kg", text, positive ? "above 0" : "0"));
  return load;
}

// One `stiffness:` block (seed 003 §4.2): the change of component t over its axis's positions
// and, with `with`, another axis's positions, measured under `load` (none: independent of the load).
StiffnessError readStiffness(const Context& ctx, const Machine& m, const MotionComponent& t, const YAML::Node& v,
                             const std::string& k, Dimension valueDim) {
  yamlin::rejectUnknownKeys(ctx, v, k, {"load", "with", "unit", "positions", "with_positions", "values"});
  StiffnessError s;
  s.axis = t.axis;
  s.component = t.component;
  if (v["load"]) s.referenceLoad = readLoad(ctx, v["load"], k + ".load", true);
  auto grid = [&](const YAML::Node& node, const std::string& key, const Axis& axis) {
    if (!yamlin::isSequence(node) || node.size() < 2) ctx.fail(node ? node : v, key, "expected a list of at least two positions");
    std::vector<double> p;
    for (const auto& x : node) {
      p.push_back(yamlin::quantity(ctx, x, key, axisDimension(axis)));
      if (p.size() > 1 && !(p.back() > p[p.size() - 2])) ctx.fail(x, key, "positions must increase strictly");
    }
    return p;
  };
  s.positions = grid(v["positions"], k + ".positions", m.axes[static_cast<size_t>(t.axis)]);
  if (v["with"]) {
    const std::string other = yamlin::scalar(ctx, v["with"], k + ".with");
    s.otherAxis = m.axisIndex(other);
    if (s.otherAxis < 0 || !m.axes[static_cast<size_t>(s.otherAxis)].commanded())
      ctx.fail(v["with"], k + ".with", "'" + other + "' is not a commanded axis of this machine");
    if (s.otherAxis == t.axis)
      ctx.fail(v["with"], k + ".with", "a change with the axis's own position belongs in its geometric error");
    s.otherPositions = grid(v["with_positions"], k + ".with_positions", m.axes[static_cast<size_t>(s.otherAxis)]);
  } else if (v["with_positions"]) {
    ctx.fail(v["with_positions"], k + ".with_positions", "'with_positions' needs 'with' (the other axis)");
  } else {
    s.otherPositions = {0.0};
  }
  if (s.referenceLoad == 0.0 && s.otherAxis < 0)
    ctx.fail(v, k, "a stiffness change needs 'load' (the workpiece load it was measured with), 'with' (another axis), or both");
  const std::string unitText = v["unit"] ? yamlin::scalar(ctx, v["unit"], k + ".unit") : "";
  const auto unit = parseQuantity("1 " + unitText);
  if (!v["unit"] || !unit || unit->dimension != valueDim)
    ctx.fail(v["unit"] ? v["unit"] : v, k + ".unit", std::string("expected the unit of the values, ") + withArticle(valueDim) + " such as " +
                                                         (valueDim == Dimension::Angle ? "'arcsec'" : "'um'"));
  const auto rows = v["values"];
  const size_t columns = s.otherPositions.size();
  if (!yamlin::isSequence(rows) || rows.size() != s.positions.size())
    ctx.fail(rows ? rows : v, k + ".values", fmt::format("expected one {} per position ({})", columns > 1 ? "row" : "value", s.positions.size()));
  s.values.resize(static_cast<Eigen::Index>(s.positions.size()), static_cast<Eigen::Index>(columns));
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    if (columns > 1 && (!yamlin::isSequence(row) || row.size() != columns))
      ctx.fail(row, k + ".values", fmt::format("expected a row of {} values, one per position of {}", columns, m.axes[static_cast<size_t>(s.otherAxis)].name));
    for (size_t j = 0; j < columns; ++j) {
      const double x = unit->value * yamlin::number(ctx, columns > 1 ? row[j] : row, k + ".values");
      if (!(std::abs(x) <= largestMagnitude(valueDim))) ctx.fail(row, k + ".values", "value beyond the largest allowed");
      s.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = x;
    }
  }
  return s;
}

void readTerms(const Context& ctx, const Machine& m, const MotionComponent& t, const YAML::Node& node,
               const std::string& key, ErrorFunction& f, std::vector<StiffnessError>& stiffness) {
  const Axis& axis = m.axes[static_cast<size_t>(t.axis)];
  const Dimension valueDim = t.component < 3 ? Dimension::Length : Dimension::Angle;
  const Dimension posDim = axisDimension(axis);
  if (node.IsScalar()) {
    f.add(PolynomialTerm{0.0, 1.0, {yamlin::quantity(ctx, node, key, valueDim)}});
    return;
  }
  if (node.IsSequence()) {  // blocks added in order (two of a kind: two polynomials, two tables)
    if (node.size() == 0) ctx.fail(node, key, "expected a value with a unit, a mapping of terms or a list of them");
    for (const auto& block : node) {
      if (block.IsMap() && block["convention"]) ctx.fail(block["convention"], key + ".convention", "give the convention on the component's own mapping, not in a list");
      readTerms(ctx, m, t, block, key, f, stiffness);
    }
    return;
  }
  yamlin::rejectUnknownKeys(ctx, node, key,
                            {"constant", "linear", "polynomial", "harmonics", "cyclic", "table", "reversal", "piecewise", "stiffness", "convention"});
  for (const auto& kv : node) {
    const auto type = kv.first.as<std::string>();
    const auto& v = kv.second;
    const std::string k = key + "." + type;
    if (type == "convention") {
      continue;  // read by shiftsTheAxisLine
    } else if (type == "constant") {
      f.add(PolynomialTerm{0.0, 1.0, {yamlin::quantity(ctx, v, k, valueDim)}});
    } else if (type == "linear") {
      yamlin::rejectUnknownKeys(ctx, v, k, {"value", "over", "zero"});
      const double over = yamlin::size(ctx, v["over"], k + ".over", posDim);
      const double zero = v["zero"] ? yamlin::quantity(ctx, v["zero"], k + ".zero", posDim) : 0.0;
      f.add(PolynomialTerm{zero, over, {0.0, yamlin::quantity(ctx, v["value"], k + ".value", valueDim)}});
    } else if (type == "polynomial") {
      yamlin::rejectUnknownKeys(ctx, v, k, {"coefficients", "scale", "zero"});
      PolynomialTerm p;
      p.scale = yamlin::size(ctx, v["scale"], k + ".scale", posDim);
      p.zero = v["zero"] ? yamlin::quantity(ctx, v["zero"], k + ".zero", posDim) : 0.0;
      const auto coeffs = v["coefficients"];
      if (!yamlin::isSequence(coeffs) || coeffs.size() == 0) ctx.fail(coeffs, k + ".coefficients", "expected a list of values");
      for (const auto& c : coeffs) p.coefficients.push_back(yamlin::quantity(ctx, c, k + ".coefficients", valueDim));
      f.add(std::move(p));
    } else if (type == "harmonics" || type == "cyclic") {
      const bool cyclic = type == "cyclic";
      yamlin::rejectUnknownKeys(ctx, v, k, cyclic ? std::initializer_list<const char*>{"pitch", "amplitude", "phase", "zero"}
                                                  : std::initializer_list<const char*>{"period", "zero", "terms"});
      auto [zero, period] = harmonicSpan(axis);
      if (v["zero"]) zero = yamlin::quantity(ctx, v["zero"], k + ".zero", posDim);
      const char* periodKey = cyclic ? "pitch" : "period";
      if (v[periodKey]) period = yamlin::size(ctx, v[periodKey], k + "." + periodKey, posDim);
      else if (cyclic) ctx.fail(v, k + ".pitch", "missing pitch");
      if (cyclic) {
        const double phase = v["phase"] ? yamlin::quantity(ctx, v["phase"], k + ".phase", Dimension::Angle) : 0.0;
        f.add(HarmonicTerm{period, zero, 1, yamlin::quantity(ctx, v["amplitude"], k + ".amplitude", valueDim), phase, true});
        continue;
      }
      const auto terms = v["terms"];
      if (!yamlin::isSequence(terms) || terms.size() == 0) ctx.fail(terms, k + ".terms", "expected a list of {order, amplitude, phase}");
      for (const auto& h : terms) {
        yamlin::rejectUnknownKeys(ctx, h, k + ".terms", {"order", "amplitude", "phase", "part"});
        const int order = yamlin::wholeNumber(ctx, h["order"], k + ".terms.order", 1, 1000);
        const double amplitude = yamlin::quantity(ctx, h["amplitude"], k + ".terms.amplitude", valueDim);
        if (h["part"]) {  // the cosine or sine part of a pair (parameters .h<k>c, .h<k>s): its phase is fixed
          const auto part = yamlin::scalar(ctx, h["part"], k + ".terms.part");
          if (part != "cosine" && part != "sine") ctx.fail(h["part"], k + ".terms.part", "expected 'cosine' or 'sine'");
          if (h["phase"]) ctx.fail(h["phase"], k + ".terms.phase", "a cosine or sine part has no phase of its own");
          const bool sine = part == "sine";
          f.add(HarmonicTerm{period, zero, order, amplitude, sine ? -0.5 * kPi : 0.0, false,
                             sine ? HarmonicPart::Sine : HarmonicPart::Cosine});
          continue;
        }
        const double phase = h["phase"] ? yamlin::quantity(ctx, h["phase"], k + ".terms.phase", Dimension::Angle) : 0.0;
        f.add(HarmonicTerm{period, zero, order, amplitude, phase});
      }
    } else if (type == "table") {
      yamlin::rejectUnknownKeys(ctx, v, k, {"positions", "values", "interpolation"});
      const auto pos = v["positions"];
      const auto val = v["values"];
      if (!pos.IsSequence() || !val.IsSequence()) ctx.fail(v, k, "table needs 'positions' and 'values' lists");
      if (pos.size() != val.size()) ctx.fail(val, k + ".values", fmt::format("{} values for {} positions", val.size(), pos.size()));
      if (pos.size() < 2) ctx.fail(pos, k + ".positions", "a table needs at least two positions");
      std::vector<double> p, y;
      for (const auto& x : pos) p.push_back(yamlin::quantity(ctx, x, k + ".positions", posDim));
      for (const auto& x : val) y.push_back(yamlin::quantity(ctx, x, k + ".values", valueDim));
      for (size_t i = 1; i < p.size(); ++i)
        if (!(p[i] > p[i - 1])) ctx.fail(pos[i], k + ".positions", "positions must increase strictly");
      Interpolation interp = Interpolation::CubicSpline;
      if (v["interpolation"]) {
        const auto s = yamlin::scalar(ctx, v["interpolation"], k + ".interpolation");
        if (s == "linear") interp = Interpolation::Linear;
        else if (s != "spline") ctx.fail(v["interpolation"], k + ".interpolation", "expected 'linear' or 'spline'");
      }
      f.add(TableTerm(std::move(p), std::move(y), interp));
    } else if (type == "piecewise") {
      if (yamlin::isSequence(v)) {
        for (const auto& block : v) f.add(readPiecewise(ctx, axis, block, k, valueDim, posDim));
      } else {
        f.add(readPiecewise(ctx, axis, v, k, valueDim, posDim));
      }
    } else if (type == "stiffness") {
      if (yamlin::isSequence(v)) {
        for (const auto& block : v) stiffness.push_back(readStiffness(ctx, m, t, block, k, valueDim));
      } else {
        stiffness.push_back(readStiffness(ctx, m, t, v, k, valueDim));
      }
    } else if (type == "reversal") {
      f.add(ReversalTerm{yamlin::quantity(ctx, v, k, valueDim)});
    }
  }
}

// A rotary axis's radial error motion given with "convention: axis-shift" (seed 000's): the
// motion shifts the axis line (errors/axis_shift.hpp). "translation", the default, is ISO 230-1's.
bool shiftsTheAxisLine(const Context& ctx, const Machine& m, const MotionComponent& t, const YAML::Node& node, const std::string& key) {
  if (!node.IsMap() || !node["convention"]) return false;
  const auto convention = yamlin::scalar(ctx, node["convention"], key + ".convention");
  if (convention == "translation") return false;
  if (convention != "axis-shift") ctx.fail(node["convention"], key + ".convention", "expected 'translation' or 'axis-shift'");
  if (!m.axes[static_cast<size_t>(t.axis)].isRotary() || t.component > 2)
    ctx.fail(node["convention"], key + ".convention", "axis-shift applies to the translations EX, EY, EZ of a rotary axis");
  if (node["stiffness"]) ctx.fail(node["stiffness"], key + ".stiffness", "a stiffness change of an axis-shift motion is not supported");
  return true;
}

}  // namespace

ErrorModel parseErrors(const Machine& machine, const std::string& yamlText, const std::string& sourceName,
                       ErrorsKey errorsKey) {
  const Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  ErrorModel model = ErrorModel::zero(machine);
  if (!root.IsMap()) ctx.fail(root, "", "expected a YAML mapping with an 'errors' key");
  if (errorsKey == ErrorsKey::Required && root["base"]) {
    if (yamlin::scalar(ctx, root["base"], "base") != "machine")
      ctx.fail(root["base"], "base", "expected 'machine' (this file's errors add to the machine file's own)");
    model = loadMachineErrors(machine);
  }
  auto loadDependent = [&] { return std::any_of(model.stiffness.begin(), model.stiffness.end(), [](const auto& s) { return s.referenceLoad > 0.0; }); };
  const bool loadStated = loadDependent() || root["workpiece_load"];  // a base with load changes stated its load
  const auto errors = root["errors"];
  if (!errors && errorsKey == ErrorsKey::Required) ctx.fail(root, "errors", "an errors file needs an 'errors:' mapping");
  if (errorsKey == ErrorsKey::Required) {
    yamlin::rejectUnknownKeys(ctx, root, "", {"errors", "base", "workpiece_load", "identification", "description", "source"});
    if (root["identification"] && !root["identification"].IsMap())
      ctx.fail(root["identification"], "identification", "expected a mapping (what identified these errors)");
  }
  if (root["workpiece_load"]) model.workpieceLoad = readLoad(ctx, root["workpiece_load"], "workpiece_load", false);
  if (!errors) return model;
  if (!errors.IsMap()) ctx.fail(errors, "errors", "expected a mapping of error names to values");
  std::map<std::string, std::string> namedBy;  // parameter or component -> the key that gave it alone
  std::map<std::string, std::string> termNamedBy;  // component -> the first key that named one of its terms (EXX.c1)
  for (const auto& kv : errors) {
    const auto name = kv.first.as<std::string>();
    const std::string key = "errors." + name;
    std::vector<AliasTerm> terms{{name, 1.0}};
    if (const auto alias = findAlias(name)) terms = alias->terms;
    const std::string& iso = terms[0].isoName;
    if (const auto target = findMotionComponent(machine, iso); target && terms.size() == 1) {
      auto& f = model.axes[static_cast<size_t>(target->axis)].motion[static_cast<size_t>(target->component)];
      if (!namedBy.emplace(iso, name).second) ctx.fail(kv.first, key, "error given twice (" + iso + ")");
      if (const auto it = termNamedBy.find(iso); it != termNamedBy.end())
        ctx.fail(kv.first, key, "its term " + it->second + " is named on its own too: give " + iso + "'s terms in one of the two forms");
      if (terms[0].sign < 0) ctx.fail(kv.first, key, "a negated alias of a component error is not supported");
      if (shiftsTheAxisLine(ctx, machine, *target, kv.second, key)) {
        std::array<ErrorFunction, 3> shift;
        readTerms(ctx, machine, *target, kv.second, key, shift[static_cast<size_t>(target->component)], model.stiffness);
        try {
          addAxisShift(machine, target->axis, shift, model.axes[static_cast<size_t>(target->axis)]);
        } catch (const InvalidInput& e) {
          ctx.fail(kv.second, key, e.reason());
        }
      } else {
        readTerms(ctx, machine, *target, kv.second, key, f, model.stiffness);
      }
      continue;
    }
    for (const auto& term : terms) {
      Parameter p;
      try {
        p = defineParameter(machine, model, term.isoName);
      } catch (const InputError& e) {
        ctx.fail(kv.first, key, e.reason());
      }
      if (p.kind == ParameterKind::Motion) {
        const std::string component = motionErrorName(machine, p.axis, p.component);
        if (namedBy.count(component))
          ctx.fail(kv.first, key, "'" + component + "' is given as a function too: give its terms in one of the two forms");
        termNamedBy.emplace(component, name);
      }
      if (terms.size() == 1) {
        const auto [it, added] = namedBy.emplace(p.name, name);
        if (!added) ctx.fail(kv.first, key, "the same parameter " + p.name + " as '" + it->second + "'");
      }
      // Location errors add up: a composite alias and an ISO name may share a term, and a zero
      // offset (B.zero) turns the axis line on top of its A0B, B0B, C0B.
      setParameterValue(model, p, parameterValue(model, p) + term.sign * yamlin::quantity(ctx, kv.second, key, p.dimension));
    }
  }
  if (loadDependent() && !loadStated)
    ctx.fail(root, "workpiece_load", "stiffness changes measured under a load need the load of this state, e.g. 'workpiece_load: 260 kg'");
  return model;
}

std::string piecewiseErrorYaml(const std::string& name, const std::vector<PiecewiseTerm>& terms, Dimension valueDimension,
                               Dimension positionDimension) {
  std::string out = fmt::format("  {}:\n    piecewise:\n", name);
  for (const auto& t : terms) out += "      - " + piecewiseBlockYaml(t, valueDimension, positionDimension) + "\n";
  return out;
}

ErrorModel loadErrors(const Machine& machine, const std::string& path) {
  return parseErrors(machine, readTextFile(path), path, ErrorsKey::Required);
}

ErrorModel loadMachineErrors(const Machine& machine) {
  if (machine.sourceFile.empty()) return ErrorModel::zero(machine);
  return parseErrors(machine, readTextFile(machine.sourceFile), machine.sourceFile);
}

}  // namespace mtacc
