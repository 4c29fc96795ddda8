#pragma once
// A spindle's thermal drift model (YAML, docs/file-formats.md "Spindle drift models"), as
// `mtacc drift TEST --save-model FILE` writes it and a thermal state's `spindle: model:` reads it:
//   directions:
//     X:
//       offset: 0.0120 um
//       sensors: [{name: head, reference: 20.012, per_kelvin: 1.234 um}]
//       residual_sigma: 0.31 um
//       covariance: [[...], [...]]   # of (offset, per_kelvin...), um^2 (urad^2 for A, B)
#include <string>

#include "mtacc/thermal/spindle_drift.hpp"

namespace mtacc {

// `comment` leads the file, each line prefixed with "# ".
std::string spindleDriftModelYaml(const SpindleDriftModel& model, const std::string& comment);
// Throws InputError naming file, line and key: no direction, an unknown direction or key, a
// value that is not finite or out of range, a sensor named twice, a covariance that is not
// square of the parameters' size, symmetric with a non-negative diagonal.
SpindleDriftModel parseSpindleDriftModel(const std::string& text, const std::string& sourceName);
SpindleDriftModel loadSpindleDriftModel(const std::string& path);

}  // namespace mtacc
