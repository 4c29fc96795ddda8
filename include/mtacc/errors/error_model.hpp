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

// ZeroOffset: a rotary axis's zero offset about its own line ("B.zero"), the position the
// axis takes when commanded 0. It is not a slot of its own: on an inclined axis it is a
// combination of the location rotations A0k B0k C0k, which are about the machine's X, Y, Z.
enum class ParameterKind { Location, Motion, ZeroOffset };

struct Parameter {
  std::string name;  // "X0C", "A0B", "EXX.c1", "EZC.t4", "B.zero"
  Dimension dimension;
  ParameterKind kind;
  int axis;       // index into Machine::axes
  int component;  // 0..5 (X Y Z A B C); ZeroOffset: 3
  int index;      // parameter index within the motion function (Motion only)
  // ZeroOffset: the turn of the axis line (rotation vector of A0k B0k C0k) per unit of the
  // parameter: the axis direction, negated on the workpiece side (the table turns the other way).
  Vec3 turn = Vec3::Zero();
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

// Where an axis's position-dependent errors run: the minimum and range of its motion.
struct AxisSpan {
  double min = 0, range = 1;
};
// The span an axis's harmonics default to: its travel, or one turn from 0.
AxisSpan harmonicSpan(const Axis& axis);

// A test plan may name a component-error term the errors do not define; this adds it at zero
// to `errors` and returns the names as parameters: "EXX.c<k>" a polynomial's power k in
// (q - the travel's middle) / half the travel (one turn: q / 180 deg), "ECC.h<k>" the harmonic
// of order k over the span above as its cosine and sine parts "ECC.h<k>c", "ECC.h<k>s" (which
// give amplitude and phase), "ECC.h<k>c" or ".h<k>s" one part. Other names pass unchanged.
std::vector<std::string> defineNamedTerms(const Machine& machine, ErrorModel& errors, const std::vector<std::string>& names);

// The parameter `name` names, for setting its value (an errors file's key, Python's
// errors[name] = v): as findParameter, with a component-error term the errors do not define
// (EXX.c1, ECC.h1c) added at zero first, as defineNamedTerms does for a test plan, so that a
// name means the same term in a plan, an identification's result and an errors file. A harmonic
// named without its part (ECC.h1, two parameters) is refused; `errors` then holds its two terms
// (a caller that goes on after the refusal passes a copy).
Parameter defineParameter(const Machine& machine, ErrorModel& errors, const std::string& name);

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
// The zero offset of a rotary axis about its own line, "<axis>.zero" (see ParameterKind).
// Not in the catalogue, whose A0k B0k C0k already span it.
Parameter zeroOffsetParameter(const Machine& machine, int axis);

// Looks a parameter up by ISO name, alias (see aliases.hpp) or "<axis>.zero" (a linear axis:
// its X0X slot); throws InputError (key: the name) listing the machine's parameters.
Parameter findParameter(const Machine& machine, const ErrorModel& errors, const std::string& name);

}  // namespace mtacc
