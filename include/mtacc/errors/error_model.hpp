#pragma once
// The ISO 230-1 errors of one machine: location errors of every axis and the six component
// error motions of every axis, each a function of that axis's position. Every scalar that
// can be identified or varied is a named Parameter.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_function.hpp"
#include "mtacc/errors/stiffness_error.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct AxisErrors {
  // Rotary axis and spindle: X0k Y0k Z0k A0k B0k C0k, the pose error of the axis line at its
  // location point (the own-letter rotation, e.g. B0B, is the zero offset).
  // Linear axis: A0k B0k C0k tilt the direction of motion; the own-letter slot (X0X, Y0Y,
  // Z0Z) is the zero offset along the axis; the other translation slots are unused.
  Vec6 location = Vec6::Zero();
  // EXk EYk EZk EAk EBk ECk.
  std::array<ErrorFunction, 6> motion;
};

struct ErrorModel {
  std::vector<AxisErrors> axes;  // indexed like Machine::axes
  // Changes of component errors with another axis's position or the workpiece load (not
  // parameters: measured, then held fixed), and the load on the table in this state (kg).
  std::vector<StiffnessError> stiffness;
  double workpieceLoad = 0.0;
  static ErrorModel zero(const Machine& machine);
};

enum class ParameterKind { Location, Motion };

struct Parameter {
  std::string name;  // "X0C", "A0B", "EXX.c1", "EZC.t4"
  Dimension dimension;
  ParameterKind kind;
  int axis;       // index into Machine::axes
  int component;  // 0..5 (X Y Z A B C)
  int index;      // parameter index within the motion function (Motion only)
};

// The location-error names that exist on this axis, e.g. {"X0C","Y0C",...}; linear axes
// offer only their zero offset and the tilts that change their direction.
std::vector<std::string> locationErrorNames(const Machine& machine, int axis);
// "E" + component letter + axis name, e.g. "EXC".
std::string motionErrorName(const Machine& machine, int axis, int component);

// The component error motion named by an ISO name ("EAX") or a one-term alias ("xrx").
struct MotionComponent {
  int axis;
  int component;  // 0..5 (X Y Z A B C): translations, then rotations
};
std::optional<MotionComponent> findMotionComponent(const Machine& machine, const std::string& name);

// Every location parameter of the machine, then every parameter of the motion functions
// defined in `errors`.
std::vector<Parameter> parameterCatalogue(const Machine& machine, const ErrorModel& errors);
// Only the parameters whose value is not zero.
std::vector<Parameter> nonZeroParameters(const Machine& machine, const ErrorModel& errors);

double parameterValue(const ErrorModel& errors, const Parameter& p);
// `shape` with every parameter zero and no stiffness changes: the nominal machine, with the
// functions `shape` defines still there to be identified.
ErrorModel withParametersZero(const Machine& machine, const ErrorModel& shape);
// `shape` with every parameter zero except p, which is set to value, and no stiffness
// changes (one error alone).
ErrorModel singleError(const Machine& machine, const ErrorModel& shape, const Parameter& p, double value);
void setParameterValue(ErrorModel& errors, const Parameter& p, double value);
// Looks a parameter up by ISO name or alias (see aliases.hpp); throws InputError (key: the
// name) listing the machine's parameters.
Parameter findParameter(const Machine& machine, const ErrorModel& errors, const std::string& name);

}  // namespace mtacc
