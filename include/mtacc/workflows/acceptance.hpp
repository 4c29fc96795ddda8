#pragma once
// Workflow `acceptance`: every test of an acceptance tests file (docs/file-formats.md "Acceptance
// tests") evaluated as its standard defines the result — ISO 230-2 positioning, ISO 10791-6
// rotary-axis tests, ISO 230-1 straightness and angular deviations, ISO 230-4 circular tests, ISO 230-3 drift — with its ISO/TR 230-9
// uncertainty, its tolerance and its ISO 14253-1 verdict; the summary first.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/acceptance_yaml.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "mtacc/workflows/verdicts.hpp"

namespace mtacc {

struct AcceptanceTestResult {
  AcceptanceTestSpec spec;
  std::string standard;     // "ISO 230-2", ...
  std::string section;      // the tolerance file's test: positioning, rotary_rtest, straightness, ...
  std::string instrument;
  std::vector<std::string> defaulted;  // what the uncertainty took from the defaults
  UncertaintyBudget uncertainty;
  Conformance conformance;
  const char* unit = "um";  // of the values shown
  double scale = 1e3;       // per mm or rad
  nlohmann::json detail;    // the test's own evaluation, as its command gives it
};

struct AcceptanceResult {
  std::string machine, title, file;
  std::vector<AcceptanceTestResult> tests;
  Verdict overall() const;  // fail if any fails, else undecided if any is, else pass
};

// tests (required), html (the report, written by the Python package).
const OptionSchema& acceptanceSchema();

// Throws InputError naming the tests file's line and key, or the data or tolerance file's.
AcceptanceResult runAcceptance(const MachineSetup& setup, const std::string& testsFile);
nlohmann::json toJson(const AcceptanceResult& result);

}  // namespace mtacc
