#pragma once
// Workflow `cone`: the 5-axis cone-frustum test piece of seed 000 on a machine — tool path,
// axis motions, the closed-form ranges of Table 3.1, the form error of the machine's errors,
// each error alone, and a Monte Carlo over tolerance limits.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/procedures/measured_cone.hpp"
#include "mtacc/procedures/monte_carlo.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct ConeStudyRequest {
  ConeSpec spec;                 // conePreset(...) or as given
  int points = 720;              // 8 .. 1,000,000
  double chordTolerance = 0;     // mm; > 0: choose the points for this chord error instead
  TiltBranch branch = TiltBranch::Negative;
  double feed = 500;             // mm/min, for the axis speeds
  bool singleErrors = false;     // form error of each non-zero error alone
  int monteCarlo = 0;            // samples; 0: none
  std::string limitsFile;        // empty (and no limitsYaml): seed 000 Table 3.9 (bundled)
  std::string limitsYaml;        // a 'limits:' mapping given as text (Python's dict) instead of a file
  std::uint64_t seed = 1;
  std::function<void(int, int)> progress;  // Monte Carlo samples done, total
  std::string measuredFile;      // CMM points of the machined cone; empty: none
};

// The options of `cone`, declared once (angles in deg, lengths in mm; the files to write are read
// by test_piece_files.hpp's coneFiles), and the request they describe for `machine`: a preset's set-up (preset "family": this machine's, Bossoni 2009
// §3.6) or the cone as given. The study checks the values' ranges; throws InputError naming the key.
const OptionSchema& coneSchema();
ConeStudyRequest coneStudyRequest(const Machine& machine, const OptionValues& values);

struct ConeSingleError {
  std::string name;
  ConeFormResult form;
  FormErrorType type;
};

// The measured cone section whose radius is nearest the path's beside the simulated form: the
// simulated normal deviation at each measured point's angle (linear between the path's points),
// both ranges and the RMS of their difference, mm.
struct ConeFormComparison {
  size_t section = 0;
  std::vector<double> simulated;
  double measuredRange = 0, simulatedRange = 0, rmsDifference = 0;
};
ConeFormComparison compareForms(const MeasuredCone& measured, const std::vector<double>& simulated, double radius);

struct ConeStudy {
  std::shared_ptr<const Machine> machine;
  ConeStudyRequest options;  // with the number of points used
  ConePath path;
  ConeMotion motion;
  RotaryRanges closedForm;
  PointMatrix machineNormals;  // the surface normal in the bed frame at each point
  std::optional<ConeFormResult> form;  // of the machine's errors (when it has any)
  double firstOrderFormError = 0;      // mm
  std::vector<ConeSingleError> singleErrors;  // largest first
  std::optional<ConeMonteCarlo> monteCarlo;
  ErrorLimits limits;  // as drawn (with their file): their keys label monteCarlo->drawn's columns
  std::optional<MeasuredCone> measured;
  std::optional<ConeFormComparison> comparison;
};

ConeStudy coneStudy(const MachineSetup& setup, const ConeStudyRequest& options);
nlohmann::json toJson(const ConeStudy& study);

}  // namespace mtacc
