#include "mtacc/measurement/identification.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include <Eigen/Dense>

namespace mtacc {
namespace {

constexpr double kTypicalLength = 1e-3;  // 1 um
constexpr double kTypicalAngle = 1e-5;   // 10 urad: 1 um over 100 mm

std::vector<SetupParameter> setupOf(const MeasurementRun& run) {
  std::vector<SetupParameter> out;
  for (auto s : run.estimate)
    if (appliesTo(s, run.instrument)) out.push_back(s);
  return out;
}

// The state every residual block reads: the model compiled at the current estimate, and
// the runs with their current set-up errors.
struct State {
  const IdentificationProblem* problem = nullptr;
  ErrorModel errors;
  KinematicModel model, nominal;
  std::vector<MeasurementRun> runs;
  std::vector<std::vector<SetupParameter>> setup;    // per run
  std::vector<std::optional<PointJacobian>> setAt;  // per run, ballbar set at the tool ball

  explicit State(const IdentificationProblem& p) : problem(&p), errors(p.start), runs(p.runs) {
    nominal = compileNominal(p.machine);
    for (const auto& r : runs) setup.push_back(setupOf(r));
    setAt.resize(runs.size());
    recompile(true);
  }
  void setMachine(const double* values) {
    for (size_t k = 0; k < problem->parameters.size(); ++k) setParameterValue(errors, problem->parameters[k], values[k]);
  }
  void setSetup(size_t run, const double* values) {
    for (size_t k = 0; k < setup[run].size(); ++k) runs[run].setup.errors[static_cast<size_t>(setup[run][k])] = values[k];
  }
  void recompile(bool jacobians) {
    model = compile(problem->machine, errors, true);
    for (size_t r = 0; r < runs.size(); ++r)
      setAt[r] = jacobians && runs[r].setup.setAt
                     ? std::optional(pointJacobian(model, problem->parameters, runs[r].setup.setAt->data(), nullptr,
                                                   runs[r].setup.toolBall))
                     : std::nullopt;
  }
  ReadingJacobian evaluate(size_t run, Eigen::Index i) const {
    return readingJacobian(model, nominal, runs[run], i, problem->parameters, setup[run],
                           setAt[run] ? &*setAt[run] : nullptr);
  }
};

class Callback : public ceres::EvaluationCallback {
 public:
  Callback(State& state, const std::vector<double>& machine, const std::vector<std::vector<double>>& setup)
      : state_(state), machine_(machine), setup_(setup) {}
  void PrepareForEvaluation(bool jacobians, bool newPoint) override {
    if (!newPoint && !(jacobians && !withJacobians_)) return;
    if (!machine_.empty()) state_.setMachine(machine_.data());
    for (size_t r = 0; r < setup_.size(); ++r)
      if (!setup_[r].empty()) state_.setSetup(r, setup_[r].data());
    state_.recompile(jacobians);
    withJacobians_ = jacobians;
  }

 private:
  State& state_;
  const std::vector<double>& machine_;
  const std::vector<std::vector<double>>& setup_;
  bool withJacobians_ = false;
};

// One pose of one run: residual = predicted - measured.
class PoseResidual : public ceres::CostFunction {
 public:
  PoseResidual(const State& state, size_t run, Eigen::Index pose, int machineCount, int setupCount)
      : state_(state), run_(run), pose_(pose), hasMachine_(machineCount > 0) {
    set_num_residuals(readingSize(state.runs[run].instrument));
    if (machineCount > 0) mutable_parameter_block_sizes()->push_back(machineCount);
    if (setupCount > 0) mutable_parameter_block_sizes()->push_back(setupCount);
  }
  bool Evaluate(double const* const*, double* residuals, double** jacobians) const override {
    const MeasurementRun& run = state_.runs[run_];
    const int m = num_residuals();
    if (!jacobians) {
      const Eigen::VectorXd r = predictReading(state_.model, state_.nominal, run, pose_);
      for (int k = 0; k < m; ++k) residuals[k] = r[k] - run.readings(pose_, k);
      return true;
    }
    const auto j = state_.evaluate(run_, pose_);
    for (int k = 0; k < m; ++k) residuals[k] = j.reading[k] - run.readings(pose_, k);
    int block = 0;
    auto copy = [&](const Eigen::MatrixXd& src) {
      if (jacobians[block])
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[block], src.rows(),
                                                                                          src.cols()) = src;
      ++block;
    };
    if (hasMachine_) copy(j.machine);
    if (j.setup.cols() > 0) copy(j.setup);
    return true;
  }

 private:
  const State& state_;
  size_t run_;
  Eigen::Index pose_;
  bool hasMachine_;
};

Eigen::MatrixXd stack(const State& s, const IdentificationProblem& p, int threads, Eigen::VectorXd* residual) {
  const auto cols = problemColumns(p);
  std::vector<Eigen::Index> rowStart(s.runs.size() + 1, 0), colStart(s.runs.size(), 0);
  Eigen::Index col = static_cast<Eigen::Index>(p.parameters.size());
  for (size_t r = 0; r < s.runs.size(); ++r) {
    rowStart[r + 1] = rowStart[r] + s.runs[r].poses() * readingSize(s.runs[r].instrument);
    colStart[r] = col;
    col += static_cast<Eigen::Index>(s.setup[r].size());
  }
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(rowStart.back(), static_cast<Eigen::Index>(cols.names.size()));
  if (residual) residual->resize(rowStart.back());
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const int m = readingSize(s.runs[r].instrument);
    parallelFor(s.runs[r].poses(), threads, [&](long b, long e) {
      for (long i = b; i < e; ++i) {
        const auto rj = s.evaluate(r, i);
        const Eigen::Index row = rowStart[r] + i * m;
        j.block(row, 0, m, rj.machine.cols()) = rj.machine;
        if (rj.setup.cols()) j.block(row, colStart[r], m, rj.setup.cols()) = rj.setup;
        if (residual && s.runs[r].readings.rows() == s.runs[r].poses())
          residual->segment(row, m) = rj.reading - s.runs[r].readings.row(i).transpose();
      }
    });
  }
  return j;
}

void checkReadings(const IdentificationProblem& p, Eigen::Index columns) {
  Eigen::Index total = 0;
  for (const auto& r : p.runs) {
    if (r.readings.rows() != r.poses() || r.readings.cols() != readingSize(r.instrument))
      throw std::invalid_argument("run '" + r.name + "' has no readings");
    if (!r.readings.allFinite()) throw std::invalid_argument("run '" + r.name + "' has a reading that is not a number");
    total += r.readings.size();
  }
  if (total <= columns)
    throw std::invalid_argument("too few readings: " + std::to_string(total) + " for " + std::to_string(columns) +
                                " unknowns");
}

}  // namespace

ProblemColumns problemColumns(const IdentificationProblem& p) {
  ProblemColumns c;
  std::vector<double> typical;
  for (const auto& par : p.parameters) {
    c.names.push_back(par.name);
    c.dimensions.push_back(par.dimension);
  }
  for (const auto& run : p.runs)
    for (auto s : setupOf(run)) {
      c.names.push_back(run.name + "." + setupParameterName(s));
      c.dimensions.push_back(setupParameterDimension(s));
    }
  c.typical.resize(static_cast<Eigen::Index>(c.dimensions.size()));
  for (size_t k = 0; k < c.dimensions.size(); ++k)
    c.typical[static_cast<Eigen::Index>(k)] = c.dimensions[k] == Dimension::Length ? kTypicalLength : kTypicalAngle;
  return c;
}

Eigen::MatrixXd stackedJacobian(const IdentificationProblem& problem, int threads) {
  const State state(problem);
  return stack(state, problem, threads, nullptr);
}

ObservabilityReport planObservability(const IdentificationProblem& problem, int threads) {
  const auto cols = problemColumns(problem);
  return analyseObservability(stackedJacobian(problem, threads), cols.names, cols.typical);
}

IdentificationResult identify(const IdentificationProblem& problem, const IdentificationOptions& options) {
  IdentificationResult out;
  out.columns = problemColumns(problem);
  const auto n = static_cast<Eigen::Index>(out.columns.names.size());
  if (n == 0) throw std::invalid_argument("no parameter to identify");
  checkReadings(problem, n);

  State state(problem);
  out.observability = analyseObservability(stack(state, problem, options.threads, nullptr), out.columns.names,
                                           out.columns.typical);
  if (!out.observability.identifiable()) {
    std::string why;
    for (const auto& f : out.observability.findings()) why += (why.empty() ? "" : "; ") + f;
    throw NotIdentifiable(out.observability, "the plan cannot determine this parameter set: " + why);
  }

  std::vector<double> machine(problem.parameters.size());
  for (size_t k = 0; k < machine.size(); ++k) machine[k] = parameterValue(problem.start, problem.parameters[k]);
  std::vector<std::vector<double>> setup(state.runs.size());
  for (size_t r = 0; r < state.runs.size(); ++r)
    for (auto s : state.setup[r]) setup[r].push_back(state.runs[r].setup.errors[static_cast<size_t>(s)]);

  Callback callback(state, machine, setup);
  ceres::Problem::Options po;
  po.evaluation_callback = &callback;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem cp(po);
  ceres::HuberLoss huber(options.robustScale);
  for (size_t r = 0; r < state.runs.size(); ++r) {
    std::vector<double*> blocks;
    if (!machine.empty()) blocks.push_back(machine.data());
    if (!setup[r].empty()) blocks.push_back(setup[r].data());
    for (Eigen::Index i = 0; i < state.runs[r].poses(); ++i)
      cp.AddResidualBlock(new PoseResidual(state, r, i, static_cast<int>(machine.size()), static_cast<int>(setup[r].size())),
                          options.robust ? &huber : nullptr, blocks);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.num_threads = options.threads;
  so.max_num_iterations = options.maxIterations;
  so.logging_type = ceres::SILENT;
  so.function_tolerance = 1e-10;
  so.parameter_tolerance = 1e-10;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &cp, &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.solverReport = summary.BriefReport();

  // Final state, then the covariance from the Jacobian there.
  if (!machine.empty()) state.setMachine(machine.data());
  for (size_t r = 0; r < setup.size(); ++r)
    if (!setup[r].empty()) state.setSetup(r, setup[r].data());
  state.recompile(true);
  Eigen::VectorXd residual;
  const Eigen::MatrixXd j = stack(state, problem, options.threads, &residual);
  out.readings = static_cast<int>(residual.size());
  out.degreesOfFreedom = out.readings - static_cast<int>(n);
  out.sigma = std::sqrt(residual.squaredNorm() / out.degreesOfFreedom);
  out.residualRms = std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
  out.residualMax = residual.cwiseAbs().maxCoeff();
  const Eigen::VectorXd scale = j.colwise().norm().transpose();
  const Eigen::MatrixXd js = j * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd inv = (js.transpose() * js).ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  out.covariance = out.sigma * out.sigma * scale.cwiseInverse().asDiagonal() * inv * scale.cwiseInverse().asDiagonal();
  out.uncertainty = out.covariance.diagonal().cwiseSqrt();

  out.values.resize(n);
  Eigen::Index k = 0;
  for (double v : machine) out.values[k++] = v;
  for (const auto& s : setup)
    for (double v : s) out.values[k++] = v;
  out.errors = state.errors;
  out.runs = state.runs;
  return out;
}

}  // namespace mtacc
