#pragma once
// The errors at a thermal state (issue 19, seed 003 §2.6-2.7): each measuring scale's expansion
// from the temperatures along it, added to its linear axis's positioning error, and the
// spindle's drift from its temperatures, added to the spindle's location errors, so that the
// kinematics, the tests' simulation and the compensation tables can be evaluated warm.
#include <optional>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/thermal/scale_expansion.hpp"
#include "mtacc/thermal/spindle_drift.hpp"

namespace mtacc {

struct ScaleState {
  int axis = 0;                      // index of a linear axis in Machine::axes
  ScaleSensors sensors;              // positions in the axis's own coordinate, mm
  std::vector<double> temperatures;  // degC, one per sensor
};

struct SpindleState {
  SpindleDriftModel model;
  Eigen::VectorXd temperatures;  // degC, one per model sensor
  double probeAboveTcp = 0.0;    // mm: probe set 1 of the drift test, from the TCP along the tool towards the spindle
};

struct ThermalState {
  std::vector<ScaleState> scales;
  std::optional<SpindleState> spindle;
};

// Delta(p) of scaleExpansion as a piecewise quadratic in the axis position over [from, to]:
// breaks at the travel's ends and every sensor between them, each interval's polynomial taken
// from three values of Delta (exact: Delta is quadratic between adjacent breaks).
PiecewiseTerm scaleExpansionTerm(const ScaleSensors& sensors, const std::vector<double>& temperatures, double from, double to);

// `errors` with each scale's expansion added to its axis's positioning error E<own><axis>: a
// warm scale reads short, so the axis goes Delta(p) beyond its command and the tool ends
// Delta(p) d further relative to the workpiece (on the workpiece side the error motion, the
// table's, is -Delta); and with the spindle's drift: the rigid motion of the spindle that moves
// probe set 1 by the predicted (X, Y, Z) and turns by (A, B) (rotationXYZ), added to the
// spindle's location errors at its location point, in the frame the spindle is mounted in (the
// machine's at the rotary axes' zero). Throws InvalidInput for a scale's axis that is not
// linear or has no travel, a scale given twice, or a spindle's drift on a machine without one.
ErrorModel atThermalState(const Machine& machine, ErrorModel errors, const ThermalState& state);
// The TCP's displacement by the spindle's drift (mm, in the spindle's frame): probe set 1's,
// and the turn (A, B) of the tool between it and the TCP. Throws as spindleDrift does.
Vec3 spindleDriftAtTcp(const Machine& machine, const SpindleState& spindle);

}  // namespace mtacc
