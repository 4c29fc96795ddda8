#pragma once
// ISO 230-2 evaluation of a positioning-test file (linear or rotary axis), with the uncertainty of
// every axis value after ISO/TR 230-9 and, given tolerances, its verdict (ISO 14253-1).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/procedures/iso230_2.hpp"
#include "mtacc/procedures/measurement_uncertainty.hpp"
#include "mtacc/workflows/verdicts.hpp"

namespace mtacc {

struct PositioningRequest {
  std::string data;
  std::optional<std::string> conditions;  // the measurement conditions file; none: the documented defaults
  std::optional<std::string> tolerances;  // the tolerance file; none: no verdict
};
// data: the test's file; conditions and tolerances: their files.
const OptionSchema& positioningSchema();
PositioningRequest positioningRequest(const OptionValues& values);

struct PositioningEvaluation {
  std::string file;
  PositioningTest test;
  PositioningResult result;
  std::string conditionsFile;  // empty: the defaults
  MeasurementConditions conditions;
  UncertaintyBudget uncertainty;
  std::optional<Conformance> conformance;
};

// The tolerance file's section for the test's axis: "positioning" or "positioning_rotary".
const char* positioningToleranceTest(PositioningAxis axis);

// Reads the files (docs/file-formats.md "Positioning tests", "Measurement conditions",
// "Tolerances") and evaluates the test; throws InputError naming the file.
PositioningEvaluation evaluatePositioningFile(const PositioningRequest& request);

// Deviations in um (linear) or arcsec (rotary), targets in mm or deg; "unit" and "target_unit"
// name them.
nlohmann::json toJson(const PositioningEvaluation& evaluation);

// The display units: um or arcsec per mm or rad, and the target unit per mm or rad.
struct PositioningUnits {
  double deviationScale;
  const char* deviation;
  double targetScale;
  const char* target;
};
PositioningUnits positioningUnits(PositioningAxis axis);

}  // namespace mtacc
