#pragma once
// Workflow `design`: the measurement plan that determines the parameters wanted (or the TCP after
// compensation) best within the machine time available, chosen among the runs the instruments at
// hand can make on this machine (measurement/design_candidates.hpp), by a greedy start and
// Fedorov's exchange (identification/experiment_design.hpp). Each candidate run's set-up unknowns
// are estimated from its own readings, so its information on the machine parameters is the Schur
// complement of its Jacobian's normal matrix, and the runs' informations add. Output: the plan YAML
// that simulate, observability and identify read, its predicted uncertainties, its machine time,
// a Pareto table of time against uncertainty, and the user's own plan beside it.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/identification/experiment_design.hpp"
#include "mtacc/identification/identification.hpp"
#include "mtacc/measurement/design_candidates.hpp"
#include "mtacc/measurement/machine_time.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct MeasurementDesignRequest {
  std::vector<std::string> parameters;  // default: the plan's list
  CandidateOptions candidates{};
  std::map<Instrument, double> noise{{Instrument::RTest, 0.5e-3}, {Instrument::Ballbar, 0.5e-3}, {Instrument::TouchProbe, 1e-3}};  // mm
  double minutes = 0;                   // the machine time available
  // Instead of a time: the shortest design that determines every parameter at least as well as
  // `plan` (its predicted uncertainties with the same noise and set-ups).
  bool reach = false;
  DesignCriterion criterion = DesignCriterion::D;
  // Instead of the criterion: the largest of the parameters' uncertainties relative to `plan`'s.
  bool againstPlan = false;
  MachineTimeModel time{};
  std::optional<std::string> plan{};     // the user's own plan, predicted beside the design
  std::optional<std::string> planOut{};  // the designed plan written there
  int threads = kAllCores;
};

// parameters, instruments, time, reach, criterion, noise, plan, plan_out, html (the front ends write the report), radii, spread, lengths,
// positions, points, feed, rapid, rotary_rapid, acceleration, rotary_acceleration, dwell,
// probe_time, setup_time, change_time, threads.
const OptionSchema& measurementDesignSchema();
MeasurementDesignRequest measurementDesignRequest(const OptionValues& values);

// What a plan gives: its time and the parameters' predicted uncertainties, and the TCP's after
// compensating with the estimates over the working volume (k = 2, root mean square and largest).
struct PlanOutlook {
  std::vector<std::string> runs;
  std::vector<double> runMinutes;   // motion and readings, per run
  double minutes = 0;               // runs, their set-ups and the instruments' mounting
  PredictedUncertainty prediction;  // machine parameters first, then the set-up unknowns
  double tcpRms = 0, tcpMax = 0;    // mm, k = 2
};

struct ParetoPoint {
  double budget = 0, minutes = 0;
  size_t runs = 0;
  double criterion = 0;
  double tcpRms = 0, tcpMax = 0;     // mm, k = 2
  double worstLength = 0, worstAngle = 0;  // the largest k = 2 uncertainty of a length (mm) and an angle (rad)
  std::string refused;               // why no design fits this budget
};

struct MeasurementDesign {
  std::shared_ptr<const Machine> machine;
  std::vector<Parameter> parameters;
  DesignCriterion criterion = DesignCriterion::D;
  bool againstPlan = false;
  double budget = 0;
  bool reached = false;  // the budget is the shortest that reaches the user's plan
  size_t candidates = 0;
  std::vector<std::string> notes;
  std::vector<DesignCandidate> chosen;
  Design design;
  PlanOutlook outlook;
  std::optional<PlanOutlook> own;
  std::string ownRefused;  // why the user's plan cannot determine the parameters
  std::vector<ParetoPoint> pareto;
  size_t volumePoses = 0;
  MachineTimeModel time;
  std::string planText;
  std::vector<std::string> written;
};

// Throws NotIdentifiable naming the parameters no run of the instruments can determine (and why),
// InputError for a budget too short to determine them.
MeasurementDesign designMeasurement(const MachineSetup& setup, const MeasurementDesignRequest& request);
nlohmann::json toJson(const MeasurementDesign& design);

}  // namespace mtacc
