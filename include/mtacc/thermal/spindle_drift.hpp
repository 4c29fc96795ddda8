#pragma once
// The spindle's thermal drift as its temperatures predict it: per direction the regression of
// a spindle drift test (drift_regression.hpp) on named temperature channels, as `mtacc drift
// --save-model` writes it, so that a thermal state can carry the spindle's drift into the errors.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/thermal/drift_regression.hpp"
#include "mtacc/thermal/drift_test.hpp"

namespace mtacc {

struct SpindleDriftModel {
  std::vector<std::string> sensors;  // temperature channels; each direction's DriftModel::sensors index them
  // By DriftDirection: X, Y (at probe set 1) and Z in mm, the tilts A and B in rad; an absent
  // direction does not drift. None is position-dependent.
  std::optional<DriftModel> directions[5];
};

// (X, Y, Z, A, B, 0) at `temperatures` (degC, one per sensor). Throws InvalidInput for
// a temperature count that is not the sensors'.
Vec6 spindleDrift(const SpindleDriftModel& model, const Eigen::VectorXd& temperatures);
// One standard deviation of each direction's prediction there (of a new reading: the
// residual's and the fit's), 0 where absent.
Vec6 spindleDriftUncertainty(const SpindleDriftModel& model, const Eigen::VectorXd& temperatures);

}  // namespace mtacc
