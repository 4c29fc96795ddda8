#pragma once
// A test's results against the tolerances of a tolerance file, with the decision rule it states:
// the verdict of every quantity that has a tolerance.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "mtacc/io/tolerances_yaml.hpp"
#include "mtacc/procedures/measurement_uncertainty.hpp"

namespace mtacc {

struct QuantityVerdict {
  std::string quantity;
  double value = 0, expanded = 0, tolerance = 0;  // mm or rad
  std::string toleranceText;
  Verdict verdict = Verdict::Undecided;
};

struct Conformance {
  std::string toleranceFile;
  DecisionRule rule = DecisionRule::Iso14253_1;
  std::vector<QuantityVerdict> verdicts;

  Verdict overall() const;  // fail if any fails, else undecided if any is, else pass
};

// `test` names the tolerance file's section (toleranceTests()); throws InputError naming the file
// when it has none for the test, or when a tolerance does not cover the measured length.
Conformance judge(const UncertaintyBudget& budget, const ToleranceSet& tolerances, const std::string& test);

// Values in the display unit: `scale` per mm or rad.
nlohmann::json toJson(const Conformance& conformance, double scale);
nlohmann::json toJson(const UncertaintyBudget& budget, double scale);

}  // namespace mtacc
