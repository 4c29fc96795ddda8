#include "mtacc/errors/error_model.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/errors/aliases.hpp"

namespace mtacc {
namespace {

constexpr char kComponentLetters[] = {'X', 'Y', 'Z', 'A', 'B', 'C'};

// X, Y, Z for linear letters (U, V, W are secondary X, Y, Z).
struct LocationSlot {
  std::string name;
  int component;
};

std::vector<LocationSlot> locationSlots(const Machine& machine, int axis) {
  const Axis& a = machine.axes[static_cast<size_t>(axis)];
  std::vector<LocationSlot> slots;
  if (a.type != AxisType::Linear) {
    for (int c = 0; c < 6; ++c) slots.push_back({std::string(1, kComponentLetters[c]) + "0" + a.name, c});
    return slots;
  }
  const int own = a.ownComponent();
  slots.push_back({std::string(1, kComponentLetters[own]) + "0" + a.name, own});
  for (int c = 0; c < 3; ++c) {
    if (std::abs(a.direction[c]) > 1.0 - 1e-9) continue;  // rotation about the axis itself
    slots.push_back({std::string(1, kComponentLetters[3 + c]) + "0" + a.name, 3 + c});
  }
  return slots;
}

Dimension componentDimension(int component) { return component < 3 ? Dimension::Length : Dimension::Angle; }

}  // namespace

ErrorModel ErrorModel::zero(const Machine& machine) {
  ErrorModel e;
  e.axes.resize(machine.axes.size());
  return e;
}

std::vector<std::string> locationErrorNames(const Machine& machine, int axis) {
  std::vector<std::string> names;
  for (const auto& s : locationSlots(machine, axis)) names.push_back(s.name);
  return names;
}

std::string motionErrorName(const Machine& machine, int axis, int component) {
  return std::string("E") + kComponentLetters[component] + machine.axes[static_cast<size_t>(axis)].name;
}

std::optional<MotionComponent> findMotionComponent(const Machine& machine, const std::string& name) {
  std::string iso = name;
  if (const auto alias = findAlias(name)) {
    if (alias->composite() || alias->terms[0].sign < 0) return std::nullopt;
    iso = alias->terms[0].isoName;
  }
  if (iso.size() < 3 || iso[0] != 'E') return std::nullopt;
  const std::string_view letters(kComponentLetters, 6);
  const auto c = letters.find(iso[1]);
  if (c == std::string_view::npos) return std::nullopt;
  const int axis = machine.axisIndex(iso.substr(2));
  if (axis < 0) return std::nullopt;
  return MotionComponent{axis, static_cast<int>(c)};
}

AxisSpan harmonicSpan(const Axis& a) {
  if (a.travel) return {a.travel->min, a.travel->max - a.travel->min};
  return {0.0, 2.0 * kPi};
}

std::vector<std::string> defineNamedTerms(const Machine& machine, ErrorModel& errors, const std::vector<std::string>& names) {
  static const std::regex term(R"((c)([0-9])|(h)([1-9][0-9]{0,2})([cs]?))");
  std::vector<std::string> out;
  for (const auto& name : names) {
    const auto dot = name.rfind('.');
    const auto component = dot == std::string::npos ? std::nullopt : findMotionComponent(machine, name.substr(0, dot));
    std::smatch m;
    const std::string suffix = dot == std::string::npos ? "" : name.substr(dot + 1);
    if (!component || !std::regex_match(suffix, m, term)) {
      out.push_back(name);
      continue;
    }
    const std::string iso = motionErrorName(machine, component->axis, component->component) + ".";
    auto defined = [&](const std::string& n) {
      const auto all = parameterCatalogue(machine, errors);
      return std::any_of(all.begin(), all.end(), [&](const Parameter& p) { return p.name == iso + n; });
    };
    if (defined(suffix)) {
      out.push_back(name);
      continue;
    }
    const Axis& axis = machine.axes[static_cast<size_t>(component->axis)];
    ErrorFunction& f = errors.axes[static_cast<size_t>(component->axis)].motion[static_cast<size_t>(component->component)];
    if (m[1].matched) {
      const int power = std::stoi(m[2]);
      const AxisSpan span = axis.travel ? harmonicSpan(axis) : AxisSpan{-kPi, 2.0 * kPi};
      f.add(PolynomialTerm{span.min + 0.5 * span.range, 0.5 * span.range, std::vector<double>(static_cast<size_t>(power) + 1, 0.0)});
      out.push_back(iso + suffix);
      continue;
    }
    const int order = std::stoi(m[4]);
    const AxisSpan span = harmonicSpan(axis);
    for (const auto part : {HarmonicPart::Cosine, HarmonicPart::Sine}) {
      const std::string partName = fmt::format("h{}{}", order, part == HarmonicPart::Cosine ? "c" : "s");
      if (m[5].length() > 0 && m[5] != partName.substr(partName.size() - 1)) continue;
      if (!defined(partName))
        f.add(HarmonicTerm{span.range, span.min, order, 0.0, part == HarmonicPart::Sine ? -0.5 * kPi : 0.0, false, part});
      out.push_back(iso + partName);
    }
  }
  return out;
}

std::vector<Parameter> parameterCatalogue(const Machine& machine, const ErrorModel& errors) {
  std::vector<Parameter> params;
  for (int a = 0; a < static_cast<int>(machine.axes.size()); ++a)
    for (const auto& s : locationSlots(machine, a))
      params.push_back({s.name, componentDimension(s.component), ParameterKind::Location, a, s.component, 0});
  for (int a = 0; a < static_cast<int>(machine.axes.size()); ++a) {
    for (int c = 0; c < 6; ++c) {
      const auto& f = errors.axes[static_cast<size_t>(a)].motion[static_cast<size_t>(c)];
      const auto suffixes = f.parameterSuffixes();
      for (int k = 0; k < static_cast<int>(suffixes.size()); ++k)
        params.push_back({motionErrorName(machine, a, c) + "." + suffixes[static_cast<size_t>(k)],
                          componentDimension(c), ParameterKind::Motion, a, c, k});
    }
  }
  return params;
}

std::vector<Parameter> nonZeroParameters(const Machine& machine, const ErrorModel& errors) {
  std::vector<Parameter> out;
  for (auto& p : parameterCatalogue(machine, errors))
    if (parameterValue(errors, p) != 0.0) out.push_back(std::move(p));
  return out;
}

Parameter zeroOffsetParameter(const Machine& machine, int axis) {
  const Axis& a = machine.axes[static_cast<size_t>(axis)];
  return {a.name + ".zero", Dimension::Angle, ParameterKind::ZeroOffset, axis, 3, 0,
          (a.side == Side::Tool ? 1.0 : -1.0) * a.direction};
}

double parameterValue(const ErrorModel& errors, const Parameter& p) {
  const auto& ax = errors.axes[static_cast<size_t>(p.axis)];
  switch (p.kind) {
    case ParameterKind::Location: return ax.location[p.component];
    case ParameterKind::ZeroOffset: return p.turn.dot(ax.location.tail<3>());
    case ParameterKind::Motion: break;
  }
  return ax.motion[static_cast<size_t>(p.component)].parameter(p.index);
}

void setParameterValue(ErrorModel& errors, const Parameter& p, double value) {
  auto& ax = errors.axes[static_cast<size_t>(p.axis)];
  switch (p.kind) {
    case ParameterKind::Location: ax.location[p.component] = value; return;
    case ParameterKind::ZeroOffset: ax.location.tail<3>() += (value - p.turn.dot(ax.location.tail<3>())) * p.turn; return;
    case ParameterKind::Motion: ax.motion[static_cast<size_t>(p.component)].setParameter(p.index, value); return;
  }
}

Parameter findParameter(const Machine& machine, const ErrorModel& errors, const std::string& name) {
  if (name.size() > 5 && name.ends_with(".zero")) {
    const int axis = machine.axisIndex(name.substr(0, name.size() - 5));
    if (axis >= 0 && machine.axes[static_cast<size_t>(axis)].commanded()) {
      const Axis& a = machine.axes[static_cast<size_t>(axis)];
      if (a.isRotary()) return zeroOffsetParameter(machine, axis);
      return findParameter(machine, errors, std::string(1, kComponentLetters[a.ownComponent()]) + "0" + a.name);
    }
  }
  std::string iso = name;
  if (const auto alias = findAlias(name)) {
    if (alias->composite())
      throw InputError(InputLocation{"", 0, name}, "'" + name + "' (" + alias->source + ") acts as " +
                                                       alias->isoExpression() + " in the ISO model; name those parameters");
    iso = alias->terms[0].isoName;
  }
  const auto all = parameterCatalogue(machine, errors);
  for (const auto& p : all)
    if (p.name == iso) return p;
  std::string known;
  for (const auto& p : all) known += (known.empty() ? "" : " ") + p.name;
  for (const auto& a : machine.axes)
    if (a.isRotary() && a.commanded()) known += " " + a.name + ".zero";
  throw InputError(InputLocation{"", 0, name}, "unknown error parameter '" + name + "'" +
                                                   (iso != name ? " (alias of " + iso + ")" : "") +
                                                   " for this machine; its parameters are: " + known);
}

Parameter defineParameter(const Machine& machine, ErrorModel& errors, const std::string& name) {
  const auto names = defineNamedTerms(machine, errors, {name});
  if (names.size() != 1)
    throw InputError(InputLocation{"", 0, name}, "'" + name + "' names the two parts of a harmonic: give " + names[0] + " and " +
                                                     names[1] + " (or the function's 'harmonics:')");
  return findParameter(machine, errors, names[0]);
}

ErrorModel withParametersZero(const Machine& machine, const ErrorModel& shape) {
  ErrorModel e = shape;
  e.stiffness.clear();
  for (const auto& q : parameterCatalogue(machine, e)) setParameterValue(e, q, 0.0);
  return e;
}

ErrorModel singleError(const Machine& machine, const ErrorModel& shape, const Parameter& p, double value) {
  ErrorModel e = withParametersZero(machine, shape);
  setParameterValue(e, p, value);
  return e;
}

}  // namespace mtacc
