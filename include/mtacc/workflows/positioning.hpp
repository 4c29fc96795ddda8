#pragma once
// ISO 230-2 evaluation of a positioning-test file (linear or rotary axis).
#include <nlohmann/json.hpp>

#include <string>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/procedures/iso230_2.hpp"

namespace mtacc {

struct PositioningEvaluation {
  std::string file;
  PositioningTest test;
  PositioningResult result;
};

// Reads the file (docs/file-formats.md "Positioning tests") and evaluates it; throws InputError
// naming the file.
PositioningEvaluation evaluatePositioningFile(const std::string& path);
// data: the test's file.
const OptionSchema& positioningSchema();

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
