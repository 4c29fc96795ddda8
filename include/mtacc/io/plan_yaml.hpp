#pragma once
// A test plan (YAML, docs/file-formats.md "Test plans"): the measurement runs to simulate,
// to check for observability, or to pair with measured data, and optionally the parameters
// they are meant to determine. Bundled plans live in data/plans/.
#include <string>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

struct TestPlan {
  std::string name;
  std::vector<MeasurementRun> runs;     // poses and set-up; no readings
  std::vector<std::string> parameters;  // names (ISO or alias); may be empty
  InputLocation parametersAt;           // where the plan names them, for messages
};

// By path, or by the name of a bundled plan. Throws InputError naming file, line and key.
TestPlan loadTestPlan(const KinematicModel& nominal, const std::string& pathOrName);
TestPlan parseTestPlan(const KinematicModel& nominal, const std::string& text, const std::string& sourceName);

}  // namespace mtacc
