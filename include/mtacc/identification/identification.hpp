#pragma once
// Generic identification: any chosen subset of error parameters (and the runs' set-up
// errors) from any combination of measurement runs, by nonlinear least squares (Ceres
// Solver) on the exact model, with standard uncertainties from the covariance. The plan is
// checked for observability first; a parameter set it cannot determine is refused.
#include <memory>
#include <string>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/measurement/measurement.hpp"
#include "mtacc/identification/observability.hpp"

namespace mtacc {

struct IdentificationProblem {
  std::shared_ptr<const Machine> machine;
  ErrorModel start;                        // known errors; the estimated ones start from here
  std::vector<Parameter> parameters;       // machine parameters to estimate
  std::vector<MeasurementRun> runs;                   // with readings; MeasurementRun::estimate names their set-up unknowns
};

// Column names and typical sizes (1 um, 10 urad) of the stacked problem: the machine
// parameters, then "<run>.<setup>" for each run.
struct ProblemColumns {
  std::vector<std::string> names;
  std::vector<Dimension> dimensions;
  Eigen::VectorXd typical;
};
ProblemColumns problemColumns(const IdentificationProblem& problem);

// Readings x columns at the problem's current state (start errors, run set-up errors).
Eigen::MatrixXd stackedJacobian(const IdentificationProblem& problem, int threads = kAllCores);
// The same about the nominal machine (every error parameter and set-up error at zero): the
// first-order Jacobian planObservability and predictUncertainty analyse.
Eigen::MatrixXd nominalJacobian(const IdentificationProblem& problem, int threads = kAllCores);
// What the plan determines to first order: the Jacobian about the nominal machine (every
// error and set-up error at zero), so that the answer does not hinge on second-order
// effects of the errors (the sense of the sensitivities of seeds 001 and 002).
ObservabilityReport planObservability(const IdentificationProblem& problem, int threads = kAllCores);

struct IdentificationOptions {
  bool robust = false;          // Huber loss
  double robustScale = 2e-3;    // mm: residuals beyond count linearly
  int maxIterations = 50;
  int threads = kAllCores;
};

struct IdentificationResult {
  ProblemColumns columns;
  Eigen::VectorXd values;       // mm, rad
  Eigen::VectorXd uncertainty;  // standard uncertainty, from sigma^2 (J^T J)^-1
  Eigen::MatrixXd covariance;
  ErrorModel errors;            // start with the machine parameters replaced
  std::vector<MeasurementRun> runs;        // set-up errors replaced, readings as measured
  double sigma = 0;             // residual standard deviation (mm), dof-corrected
  double residualRms = 0, residualMax = 0;
  std::vector<double> runResidualSquares;  // sum of the squared residuals of each run, mm^2
  Eigen::VectorXd residual;     // reading minus model at the estimates (mm), runs in order, each pose's readings together
  int readings = 0, degreesOfFreedom = 0, iterations = 0;
  bool converged = false;
  std::string solverReport;
  ObservabilityReport observability;
};

// What the plan would give with readings of standard deviation runNoise[r] (mm) in run r: the
// first-order covariance (J^T W J)^-1 of the least-squares estimates about the nominal machine,
// W = diag(1 / noise^2). Throws NotIdentifiable when the plan cannot determine the unknowns.
struct PredictedUncertainty {
  ProblemColumns columns;
  Eigen::VectorXd uncertainty;  // standard uncertainty, mm or rad
  Eigen::MatrixXd covariance;
};
PredictedUncertainty predictUncertainty(const IdentificationProblem& problem, const std::vector<double>& runNoise,
                                        int threads = kAllCores);
// The problem's machine parameters that the plan can determine together (the set-up unknowns
// always estimated), and what each then stands for: proposeIdentifiableColumns about the
// nominal machine.
IdentifiableColumns proposeIdentifiableSet(const IdentificationProblem& problem, int threads = kAllCores);

// Refusal of a parameter set the plan cannot determine; what() lists the findings.
class NotIdentifiable : public InvalidInput {
 public:
  NotIdentifiable(ObservabilityReport report, const std::string& what) : InvalidInput(what), report_(std::move(report)) {}
  const ObservabilityReport& report() const { return report_; }

 private:
  ObservabilityReport report_;
};

// Throws NotIdentifiable, or InvalidInput for runs without readings or fewer
// readings than unknowns.
IdentificationResult identify(const IdentificationProblem& problem, const IdentificationOptions& options = {});

}  // namespace mtacc
