#pragma once
// Reading an acceptance tests file: the tests performed, each with its data file, its instrument
// and environment, and the tolerances they are judged by (docs/file-formats.md "Acceptance tests").
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/units.hpp"
#include "mtacc/procedures/conformance.hpp"

namespace mtacc {

enum class AcceptanceTestType { Positioning, Rotary, Geometric, Circular, Drift };

struct AcceptanceTestSpec {
  std::string name;
  AcceptanceTestType type = AcceptanceTestType::Positioning;
  std::string data;                      // paths resolved against the tests file's folder
  std::optional<std::string> conditions;  // positioning: the measurement conditions file
  std::optional<std::string> tolerances;  // this test's tolerance file, in place of the file's
  std::optional<Quantity> calibration;    // rotary, geometric, circular: U (k = 2) of the instrument's reading
  std::optional<Quantity> drift;          // rotary, geometric, circular: E_VE (not for a drift test, which measures it)
  int line = 0;
  std::string key;  // "tests[i]", for messages
};

struct AcceptancePlan {
  std::string file;
  std::string title;
  std::optional<std::string> tolerances;    // every test's tolerance file unless it names its own
  std::optional<DecisionRule> decisionRule;  // in place of the tolerance files' rules
  std::vector<AcceptanceTestSpec> tests;
};

// Throws InputError naming file, line and key: an unknown key or test type, a test without data,
// keys that do not apply to its type, a value without its unit, two tests of one name.
AcceptancePlan loadAcceptancePlan(const std::string& path);
AcceptancePlan parseAcceptancePlan(const std::string& yamlText, const std::string& sourceName);

}  // namespace mtacc
