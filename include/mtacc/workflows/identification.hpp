#pragma once
// Workflows `observability` and `identify`: which error parameters a test plan (or measured
// files) determines, and their least-squares estimates with standard uncertainties.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/identification/fit_quality.hpp"
#include "mtacc/identification/identification.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct IdentificationRequest {
  std::string plan;                 // test plan (path or bundled name): runs and parameter list
  std::vector<std::string> data{};  // measurement files (identify: the runs; observability: added to the plan's)
  std::vector<MeasurementRun> runs{};  // runs already read (e.g. from zone results), added to the files' runs
  std::vector<std::string> parameters;  // default: the plan's list
  std::optional<std::vector<std::string>> setup{};  // set-up errors to estimate in every run (overrides the files)
  bool robust = false;
  // The errors not identified are held at zero (the nominal machine) instead of at the values of
  // the machine file or --errors: a machine that already carries its true errors hides aliasing.
  bool fromNominal = false;
  double robustScale = 2e-3;        // mm
  int threads = kAllCores;
  // The reading noise (standard deviation, mm) for the goodness-of-fit test; default: each
  // file's `# noise:` line (no test when a file has none).
  std::optional<double> noise{};
  // A parameter is poorly determined when its standard uncertainty exceeds this fraction of
  // its plausible magnitude (kPlausibleLength, kPlausibleAngle).
  double uncertaintyFraction = 0.1;
};

// The options of `identify` and of `observability` (a subset), declared once: the CLI's flags and
// Python's keyword arguments are these keys, read by identificationRequest.
const OptionSchema& identificationSchema();
const OptionSchema& observabilitySchema();
// The request the values describe, each checked against `schema`; throws InputError naming the key.
IdentificationRequest identificationRequest(const OptionSchema& schema, const OptionValues& values);

// The parameters a plan can determine together when it cannot determine all that were named:
// identify `kept`, hold `held` at zero, and the estimate of kept[k] stands for
// kept[k] + sum_d coefficients(k, d) held[d] (coefficients in the parameters' units, mm/rad).
struct IdentifiableSetProposal {
  std::vector<Parameter> kept, held;
  Eigen::MatrixXd coefficients;
  std::string standsFor(size_t k) const;  // "X0B - 1 X0C + 0.15 um/urad B0C"
};

struct ObservabilityResult {
  std::shared_ptr<const Machine> machine;
  size_t runs = 0;
  Eigen::Index readings = 0;
  ObservabilityReport report;
  std::optional<IdentifiableSetProposal> proposal;  // when the plan cannot determine every parameter
  // With the readings' noise known (request.noise, or every run's own: a plan's `noise:`, a
  // file's '# noise:'): the standard uncertainties the plan would give the parameters (the
  // proposal's when there is one) and the set-up unknowns.
  std::optional<PredictedUncertainty> prediction;
  std::string noiseSource;  // "--noise", "the runs' own noise", or empty
  size_t parameterCount = 0;  // of the prediction's columns, the machine parameters come first
};

// The plan's runs (and any files): rank, singular values, what it cannot separate and what it
// can instead, and with a noise the uncertainty each parameter would get.
ObservabilityResult planObservability(const MachineSetup& setup, const IdentificationRequest& request);
nlohmann::json toJson(const ObservabilityResult& result);
nlohmann::json toJson(const ObservabilityReport& report);

struct IdentificationStudy {
  std::shared_ptr<const Machine> machine;
  size_t runs = 0;
  std::vector<std::string> given;  // the parameter names as the request wrote them
  std::vector<std::string> held;   // the non-zero parameters not identified, held at their values
  bool robust = false;
  IdentificationResult result;
  IdentificationQuality quality;
  std::vector<HarmonicEstimate> harmonics;
  // Where it came from, for the record an identified errors file keeps (identified_errors.hpp).
  std::string command = "identify";  // or "cubic-identify"
  std::string plan;                  // the test plan (or cubic test piece), as given
  std::vector<std::string> dataFiles;
  bool heldAtZero = false;           // the errors not identified held at zero (--from-nominal)
};

// Identifies from the request's files; refuses (InputError) a set the data cannot determine,
// and flags (quality.warnings) residuals that the stated noise does not explain and
// parameters the data hardly determine.
IdentificationStudy identifyParameters(const MachineSetup& setup, const IdentificationRequest& request);
nlohmann::json toJson(const IdentificationStudy& outcome);

}  // namespace mtacc
