#include "mtacc/errors/error_model.hpp"

#include <string_view>

#include <cmath>
#include <stdexcept>

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

double parameterValue(const ErrorModel& errors, const Parameter& p) {
  const auto& ax = errors.axes[static_cast<size_t>(p.axis)];
  if (p.kind == ParameterKind::Location) return ax.location[p.component];
  return ax.motion[static_cast<size_t>(p.component)].parameter(p.index);
}

void setParameterValue(ErrorModel& errors, const Parameter& p, double value) {
  auto& ax = errors.axes[static_cast<size_t>(p.axis)];
  if (p.kind == ParameterKind::Location)
    ax.location[p.component] = value;
  else
    ax.motion[static_cast<size_t>(p.component)].setParameter(p.index, value);
}

Parameter findParameter(const Machine& machine, const ErrorModel& errors, const std::string& name) {
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
  throw InputError(InputLocation{"", 0, name}, "unknown error parameter '" + name + "'" +
                                                   (iso != name ? " (alias of " + iso + ")" : "") +
                                                   " for this machine; its parameters are: " + known);
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
