#pragma once
// Workflows `observability` and `identify`: which error parameters a test plan (or measured
// files) determines, and their least-squares estimates with standard uncertainties.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/measurement/identification.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct IdentificationRequest {
  std::string plan;                 // test plan (path or bundled name): runs and parameter list
  std::vector<std::string> data{};  // measurement files (identify: the runs; observability: added to the plan's)
  std::vector<std::string> parameters;  // default: the plan's list
  std::optional<std::vector<std::string>> setup{};  // set-up errors to estimate in every run (overrides the files)
  bool robust = false;
  double robustScale = 2e-3;        // mm
  int threads = kAllCores;
};

struct ObservabilityResult {
  std::shared_ptr<const Machine> machine;
  size_t runs = 0;
  Eigen::Index readings = 0;
  ObservabilityReport report;
};

// The plan's runs (and any files): rank, singular values and what it cannot separate.
ObservabilityResult planObservability(const MachineSetup& setup, const IdentificationRequest& request);
nlohmann::json toJson(const ObservabilityResult& result);
nlohmann::json toJson(const ObservabilityReport& report);

struct IdentificationOutcome {
  std::shared_ptr<const Machine> machine;
  size_t runs = 0;
  std::vector<std::string> given;  // the parameter names as the request wrote them
  bool robust = false;
  IdentificationResult result;
};

// Identifies from the request's files; refuses (InputError) a set the data cannot determine.
IdentificationOutcome identifyParameters(const MachineSetup& setup, const IdentificationRequest& request);
nlohmann::json toJson(const IdentificationOutcome& outcome);

}  // namespace mtacc
