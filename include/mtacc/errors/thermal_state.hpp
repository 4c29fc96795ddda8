#pragma once
// The errors at a thermal state (issue 19, seed 003 §2.7): each measuring scale's expansion
// from the temperatures along it, added to its linear axis's positioning error, so that the
// kinematics, the tests' simulation and the compensation tables can be evaluated warm.
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/thermal/scale_expansion.hpp"

namespace mtacc {

struct ScaleState {
  int axis = 0;                      // index of a linear axis in Machine::axes
  ScaleSensors sensors;              // positions in the axis's own coordinate, mm
  std::vector<double> temperatures;  // degC, one per sensor
};

// Delta(p) of scaleExpansion as a piecewise quadratic in the axis position over [from, to]:
// breaks at the travel's ends and every sensor between them, each interval's polynomial taken
// from three values of Delta (exact: Delta is quadratic between adjacent breaks).
PiecewiseTerm scaleExpansionTerm(const ScaleSensors& sensors, const std::vector<double>& temperatures, double from, double to);

// `errors` with each scale's expansion added to its axis's positioning error E<own><axis>: a
// warm scale reads short, so the axis goes Delta(p) beyond its command and the tool ends
// Delta(p) d further relative to the workpiece (on the workpiece side the error motion, the
// table's, is -Delta). Throws
// std::invalid_argument for an axis that is not linear or has no travel, or a scale given twice.
ErrorModel atThermalState(const Machine& machine, ErrorModel errors, const std::vector<ScaleState>& scales);

}  // namespace mtacc
