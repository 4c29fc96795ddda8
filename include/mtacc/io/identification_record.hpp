#pragma once
// The record an identified errors file keeps under `identification:` (docs/file-formats.md,
// "Identified errors"): the units its estimates are written in, and their covariance read back
// for the parameters of the model the file describes.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/errors/error_model.hpp"

namespace mtacc {

// An estimate's written value is its value in mtacc's units (mm, rad, or a function's
// coefficient in mm or rad per mm^k or rad^k) times `scale`, in `unit` ("um", "urad/mm^2").
struct EstimateUnit {
  double scale = 1.0;
  std::string unit;
  static EstimateUnit of(Dimension d);
  // The coefficient of u^power of a function of a linear (mm) or rotary (deg) axis's position.
  static EstimateUnit coefficient(Dimension value, bool rotaryPosition, int power);
};

struct ParameterCovariance {
  std::vector<Parameter> parameters;
  Eigen::MatrixXd covariance;        // in mtacc's units, in the order of `parameters`
  std::vector<std::string> leftOut;  // estimates that are not the model's parameters (set-up unknowns) or were not determined
};

// The covariance of the record's estimates that name parameters of `errors` (the model the file
// describes, read with it). nullopt when the file has no record. Throws InputError naming file,
// line and key for a record that is there but malformed (an estimate without a value, a unit
// that does not fit its parameter, a covariance of another size, an entry not finite).
std::optional<ParameterCovariance> readParameterCovariance(const Machine& machine, const ErrorModel& errors, const std::string& path);
std::optional<ParameterCovariance> parseParameterCovariance(const Machine& machine, const ErrorModel& errors, const std::string& text,
                                                            const std::string& sourceName);

}  // namespace mtacc
