#include "mtacc/identification/identification.hpp"

#include <ceres/ceres.h>
#include <ceres/tiny_solver.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>

#include <Eigen/Dense>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

constexpr double kTypicalLength = 1e-3;  // 1 um
constexpr double kTypicalAngle = 1e-5;   // 10 urad: 1 um over 100 mm

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::vector<SetupParameter> setupOf(const MeasurementRun& run) {
  std::vector<SetupParameter> out;
  for (auto s : run.estimate)
    if (appliesTo(s, run.instrument)) out.push_back(s);
  return out;
}

bool allZero(const IdentificationProblem& p) {
  for (const auto& par : parameterCatalogue(*p.machine, p.start))
    if (parameterValue(p.start, par) != 0.0) return false;
  for (const auto& r : p.runs)
    for (double e : r.setup.errors)
      if (e != 0.0) return false;
  return true;
}

// J^T J (lower triangle until completed), J^T r and r^T r of a stacked system, summed block
// by block.
struct NormalEquations {
  Eigen::MatrixXd gram;
  Eigen::VectorXd gradient;
  double squaredNorm = 0;

  explicit NormalEquations(Eigen::Index n = 0) : gram(Eigen::MatrixXd::Zero(n, n)), gradient(Eigen::VectorXd::Zero(n)) {}
  template <class Rows, class Residuals>
  void add(const Rows& j, const Residuals& r) {
    gram.selfadjointView<Eigen::Lower>().rankUpdate(j.transpose());
    gradient.noalias() += j.transpose() * r;
    squaredNorm += r.squaredNorm();
  }
  void add(const NormalEquations& other) {
    gram += other.gram, gradient += other.gradient, squaredNorm += other.squaredNorm;
  }
};

// The stacked problem at one estimate: the model compiled there, the runs with their set-up
// errors, and the layout of the stacked readings (rows) and unknowns (columns). `jacobian`
// and `residual` hold the evaluation with derivatives at `point` (when `valid`); `current` is
// the estimate the model is compiled at.
struct State {
  const IdentificationProblem* problem;
  ErrorModel errors;
  KinematicModel model, nominal;
  std::vector<MeasurementRun> runs;
  std::vector<std::vector<SetupParameter>> setup;   // per run
  std::vector<std::optional<PointJacobian>> setAt;  // per run, ballbar set at the tool ball
  std::vector<std::vector<NominalFrame>> frames;    // per run and pose
  std::vector<RunGeometry> geometry;                // per run, at `current`
  std::vector<Eigen::Index> poseStart, rowStart, colStart;  // per run (poseStart: and the total)
  Eigen::Index rows = 0, cols = 0;

  bool storeJacobian = true;  // keep the stacked Jacobian (else only its normal equations)
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residual;
  NormalEquations normal;  // of the Jacobian and residual, completed to the full matrix
  std::vector<double> point;    // machine values then set-up values at which they hold
  std::vector<double> current;  // the same for the compiled model
  bool valid = false;
  bool setAtReady = false;  // setAt holds the derivatives at `current`
  Eigen::VectorXd residualOnly;  // residuals at `residualPoint`, without derivatives
  std::vector<double> residualPoint;
  int threads = 1;

  // aboutNominal: every error parameter and set-up error at zero, the functions kept.
  State(const IdentificationProblem& p, bool aboutNominal, int threadsToUse)
      : problem(&p), errors(p.start), runs(p.runs), threads(threadsToUse) {
    if (aboutNominal) {
      for (const auto& par : parameterCatalogue(*p.machine, p.start)) setParameterValue(errors, par, 0.0);
      for (auto& r : runs) r.setup.errors = {};
    }
    nominal = compileNominal(p.machine);
    cols = static_cast<Eigen::Index>(p.parameters.size());
    poseStart.push_back(0);
    for (const auto& r : runs) {
      setup.push_back(setupOf(r));
      poseStart.push_back(poseStart.back() + r.poses());
      rowStart.push_back(rows);
      colStart.push_back(cols);
      rows += r.poses() * readingSize(r.instrument);
      cols += static_cast<Eigen::Index>(setup.back().size());
    }
    setAt.resize(runs.size());
    frames.resize(runs.size());
    for (size_t r = 0; r < runs.size(); ++r) frames[r].resize(static_cast<size_t>(runs[r].poses()));
    forEachPose([&](size_t r, Eigen::Index i) { frames[r][static_cast<size_t>(i)] = nominalFrame(nominal, runs[r], i); });
    recompile(true);
    current = values();
  }
  std::vector<double> values() const {
    std::vector<double> v;
    for (const auto& par : problem->parameters) v.push_back(parameterValue(errors, par));
    for (size_t r = 0; r < runs.size(); ++r)
      for (auto s : setup[r]) v.push_back(runs[r].setup.errors[static_cast<size_t>(s)]);
    return v;
  }
  void set(const std::vector<double>& v) {
    size_t k = 0;
    for (const auto& par : problem->parameters) setParameterValue(errors, par, v[k++]);
    for (size_t r = 0; r < runs.size(); ++r)
      for (auto s : setup[r]) runs[r].setup.errors[static_cast<size_t>(s)] = v[k++];
  }
  void recompile(bool jacobians) {
    model = compile(problem->machine, errors, jacobians ? problem->parameters : std::vector<Parameter>{});
    setAtReady = jacobians;
    KinematicData data;
    geometry.clear();
    for (size_t r = 0; r < runs.size(); ++r) {
      geometry.push_back(runGeometry(model, runs[r]));
      setAt[r].reset();
      if (jacobians && runs[r].setup.setAt)
        setAt[r] = pointJacobian(model, runs[r].setup.setAt->data(), nullptr, toolBallWithSetupError(runs[r]), data);
    }
  }
  // The rows of poses [begin, end) (counted over all runs) into `block` (their Jacobian) and
  // the residual.
  void evaluate(long begin, long end, RowMajorMatrix& block, KinematicData& data, ReadingJacobian& rj) {
    const auto machineCols = static_cast<Eigen::Index>(problem->parameters.size());
    const Eigen::Index row0 = rowOf(begin);
    block.rightCols(cols - machineCols).setZero();
    size_t run = runOf(begin);
    for (long p = begin; p < end; ++p) {
      while (p >= poseStart[run + 1]) ++run;
      const auto& r = runs[run];
      const Eigen::Index i = p - poseStart[run], m = readingSize(r.instrument), row = rowStart[run] + i * m;
      readingJacobian(model, {r, i, geometry[run], frames[run][static_cast<size_t>(i)], setup[run], setAt[run] ? &*setAt[run] : nullptr},
                      data, rj);
      for (Eigen::Index k = 0; k < m; ++k) {
        double* out = block.row(row - row0 + k).data();
        std::copy_n(rj.machine.row(k).data(), machineCols, out);
        std::copy_n(rj.setup.row(k).data(), rj.setup.cols(), out + colStart[run]);
        residual[row + k] = rj.reading[k] - (r.readings.rows() == r.poses() ? r.readings(i, k) : 0.0);
      }
    }
  }
  size_t runOf(long pose) const {
    return static_cast<size_t>(std::upper_bound(poseStart.begin(), poseStart.end(), pose) - poseStart.begin()) - 1;
  }
  Eigen::Index rowOf(long pose) const {
    if (pose == poseStart.back()) return rows;
    const size_t r = runOf(pose);
    return rowStart[r] + (pose - poseStart[r]) * readingSize(runs[r].instrument);
  }
  template <class F>
  void forEachPose(F&& f) const {
    parallelFor(poseStart.back(), threads, [&](long b, long e) {
      size_t r = runOf(b);
      for (long p = b; p < e; ++p) {
        while (p >= poseStart[r + 1]) ++r;
        f(r, p - poseStart[r]);
      }
    });
  }
  // The Jacobian (kept when storeJacobian), residuals and normal equations at `current`, on
  // all threads: each forms the normal equations of its poses a block at a time while the
  // block is in cache; the parts are summed in pose order, so that the result does not
  // depend on timing.
  void evaluateAll() {
    constexpr long kBlockPoses = 128;
    if (storeJacobian) jacobian.resize(rows, cols);
    residual.resize(rows);
    std::mutex mutex;
    std::vector<std::pair<long, NormalEquations>> parts;
    parallelFor(poseStart.back(), threads, [&](long begin, long end) {
      NormalEquations part(cols);
      RowMajorMatrix block(3 * kBlockPoses, cols);
      KinematicData data;
      ReadingJacobian rj;
      for (long b = begin; b < end; b += kBlockPoses) {
        const long e = std::min(end, b + kBlockPoses);
        evaluate(b, e, block, data, rj);
        const Eigen::Index row0 = rowOf(b), n = rowOf(e) - row0;
        part.add(block.topRows(n), residual.segment(row0, n));
        if (storeJacobian) jacobian.middleRows(row0, n) = block.topRows(n);
      }
      const std::lock_guard lock(mutex);
      parts.emplace_back(begin, std::move(part));
    });
    std::sort(parts.begin(), parts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    normal = NormalEquations(cols);
    for (const auto& part : parts) normal.add(part.second);
    normal.gram = normal.gram.selfadjointView<Eigen::Lower>();
    point = current;
    valid = true;
  }
  void evaluateResiduals() {
    residualOnly.resize(rows);
    forEachPose([&](size_t r, Eigen::Index i) {
      const auto& run = runs[r];
      const Eigen::Index m = readingSize(run.instrument);
      residualOnly.segment(rowStart[r] + i * m, m) =
          predictReading(model, {run, i, geometry[r], frames[r][static_cast<size_t>(i)]}) - run.readings.row(i).transpose();
    });
    residualPoint = current;
  }
  // Moves the estimate to v and evaluates there what the solver asks for (the derivatives
  // only when they are not there already).
  void prepare(const std::vector<double>& v, bool jacobians) {
    const bool derivativesThere = valid && point == v;
    if (v != current || (jacobians && !derivativesThere && !setAtReady)) {
      set(v);
      recompile(jacobians);
      current = v;
    }
    if (jacobians && !derivativesThere) evaluateAll();
    if (!jacobians && !derivativesThere && residualPoint != v) evaluateResiduals();
  }
  // The residuals at the current estimate (with or without derivatives).
  const Eigen::VectorXd& residualsAtCurrent() const { return valid && point == current ? residual : residualOnly; }
};

class Callback : public ceres::EvaluationCallback {
 public:
  Callback(State& state, const std::vector<double>& machine, const std::vector<std::vector<double>>& setup)
      : state_(state), machine_(machine), setup_(setup) {}
  // Everything the blocks of this evaluation need, computed here on all threads at once;
  // the blocks then only copy their rows.
  void PrepareForEvaluation(bool jacobians, bool) override {
    std::vector<double> v = machine_;
    for (const auto& s : setup_) v.insert(v.end(), s.begin(), s.end());
    state_.prepare(v, jacobians);
  }

 private:
  State& state_;
  const std::vector<double>& machine_;
  const std::vector<std::vector<double>>& setup_;
};

// One pose of one run: residual = predicted - measured.
class PoseBlock : public ceres::CostFunction {
 public:
  PoseBlock(State& state, size_t run, Eigen::Index pose) : state_(state), run_(run), pose_(pose) {
    m_ = readingSize(state.runs[run].instrument);
    set_num_residuals(m_);
    if (!state.problem->parameters.empty())
      mutable_parameter_block_sizes()->push_back(static_cast<int>(state.problem->parameters.size()));
    if (!state.setup[run].empty()) mutable_parameter_block_sizes()->push_back(static_cast<int>(state.setup[run].size()));
  }
  bool Evaluate(double const* const*, double* residuals, double** jacobians) const override {
    const Eigen::Index row0 = state_.rowStart[run_] + pose_ * m_, n = num_residuals();
    Eigen::Map<Eigen::VectorXd>(residuals, n) = state_.residualsAtCurrent().segment(row0, n);
    if (!jacobians) return true;
    int block = 0;
    const auto machineCols = static_cast<Eigen::Index>(state_.problem->parameters.size());
    if (machineCols > 0) {
      if (jacobians[block])
        Eigen::Map<RowMajorMatrix>(jacobians[block], n, machineCols) = state_.jacobian.block(row0, 0, n, machineCols);
      ++block;
    }
    const auto setupCols = static_cast<Eigen::Index>(state_.setup[run_].size());
    if (setupCols > 0 && jacobians[block])
      Eigen::Map<RowMajorMatrix>(jacobians[block], n, setupCols) =
          state_.jacobian.block(row0, state_.colStart[run_], n, setupCols);
    return true;
  }

 private:
  State& state_;
  size_t run_;
  Eigen::Index pose_;
  int m_ = 1;
};

void checkReadings(const IdentificationProblem& p, Eigen::Index columns) {
  Eigen::Index total = 0;
  for (const auto& r : p.runs) {
    if (r.readings.rows() != r.poses() || r.readings.cols() != readingSize(r.instrument))
      throw InvalidInput("run '" + r.name + "' has no readings");
    if (!r.readings.allFinite()) throw InvalidInput("run '" + r.name + "' has a reading that is not a number");
    total += r.readings.size();
  }
  if (total <= columns)
    throw InvalidInput("too few readings: " + std::to_string(total) + " for " + std::to_string(columns) +
                                " unknowns");
}

// Plain least squares with Ceres' TinySolver, its dense Levenberg-Marquardt for few unknowns,
// in typical units (1 um, 10 urad), so that its step tolerance reads "a millionth of the
// estimate". TinySolver uses the readings only through J^T J, J^T r and the cost |r|^2 / 2, so
// it is given an equivalent system of n + 1 rows instead of all of them: with C^T C = D J^T J D
// (Cholesky; D the typical sizes) the Jacobian [C; 0] and the residuals
// [C^-T D J^T r; sqrt(|r|^2 - |C^-T D J^T r|^2)] have the same three, so every step and every
// decision is the one it would take on the stacked readings; a call for the cost alone gets
// [|r|, 0, ..., 0]. The normal equations are formed on all threads with the evaluation.
// A call for the cost alone is a trial step, and TinySolver asks for the Jacobian at every
// step it accepts, which is nearly every step on these problems: such a call therefore
// evaluates the derivatives as well, ready for that next request.
struct StackedReadings {
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };
  State& state;
  const Eigen::VectorXd& typical;

  int NumResiduals() const { return static_cast<int>(state.cols) + 1; }
  int NumParameters() const { return static_cast<int>(state.cols); }
  std::vector<double> unscaled(const double* x) const {
    std::vector<double> v(static_cast<size_t>(state.cols));
    for (Eigen::Index k = 0; k < state.cols; ++k) v[static_cast<size_t>(k)] = x[k] * typical[k];
    return v;
  }
  bool operator()(const double* x, double* residuals, double* jacobian) const {
    const Eigen::Index n = state.cols;
    state.prepare(unscaled(x), true);
    Eigen::Map<Eigen::VectorXd> r(residuals, n + 1);
    r.setZero();
    if (!jacobian) {
      r[0] = std::sqrt(state.normal.squaredNorm);
      return true;
    }
    const NormalEquations& ne = state.normal;
    const Eigen::LLT<Eigen::MatrixXd> c(typical.asDiagonal() * ne.gram * typical.asDiagonal());
    if (c.info() != Eigen::Success) throw InvalidInput("identification: the normal matrix became singular: the data do not determine the parameters");
    r.head(n) = c.matrixL().solve(typical.cwiseProduct(ne.gradient));
    r[n] = std::sqrt(std::max(0.0, ne.squaredNorm - r.head(n).squaredNorm()));
    Eigen::Map<Eigen::MatrixXd> j(jacobian, n + 1, n);
    j.setZero();
    j.topRows(n) = c.matrixU();
    return true;
  }
};

std::vector<double> solveLeastSquares(State& state, const Eigen::VectorXd& typical, const IdentificationOptions& options,
                                      IdentificationResult& out) {
  StackedReadings readings{state, typical};
  const std::vector<double> start = state.values();
  Eigen::VectorXd x(state.cols);
  for (Eigen::Index k = 0; k < state.cols; ++k) x[k] = start[static_cast<size_t>(k)] / typical[k];
  ceres::TinySolver<StackedReadings> solver;
  solver.options.max_num_iterations = options.maxIterations;
  solver.options.parameter_tolerance = 1e-6;
  solver.options.function_tolerance = 0.0;  // stop on the step size (its cost test is absolute)
  solver.options.gradient_tolerance = 0.0;
  solver.options.initial_trust_region_radius = 1e10;  // a Gauss-Newton step first: these problems are nearly linear
  const auto& summary = solver.Solve(readings, &x);
  using Status = ceres::TinySolver<StackedReadings>::Status;
  out.converged = summary.status != Status::HIT_MAX_ITERATIONS;
  out.iterations = summary.iterations;
  out.solverReport = fmt::format("Ceres TinySolver: {} iterations, cost {:.6e} -> {:.6e}{}", summary.iterations,
                                 summary.initial_cost, summary.final_cost, out.converged ? "" : " (iteration limit)");
  return readings.unscaled(x.data());
}

// With a robust loss: a ceres::Problem with one residual block per pose, so that the Huber
// loss acts per reading.
std::vector<double> solveRobust(State& state, const IdentificationOptions& options, IdentificationResult& out) {
  const std::vector<double> start = state.values();
  const size_t machineCount = state.problem->parameters.size();
  std::vector<double> machine(start.begin(), start.begin() + static_cast<long>(machineCount));
  std::vector<std::vector<double>> setup(state.runs.size());
  for (size_t r = 0, k = machineCount; r < state.runs.size(); ++r)
    for (size_t i = 0; i < state.setup[r].size(); ++i) setup[r].push_back(start[k++]);

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
    for (Eigen::Index i = 0; i < state.runs[r].poses(); ++i) cp.AddResidualBlock(new PoseBlock(state, r, i), &huber, blocks);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.num_threads = 1;  // the callback evaluates on all threads
  so.max_num_iterations = options.maxIterations;
  so.logging_type = ceres::SILENT;
  so.function_tolerance = 1e-10;
  so.parameter_tolerance = 1e-10;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &cp, &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.solverReport = summary.BriefReport();
  std::vector<double> final = machine;
  for (const auto& s : setup) final.insert(final.end(), s.begin(), s.end());
  return final;
}

}  // namespace

ProblemColumns problemColumns(const IdentificationProblem& p) {
  ProblemColumns c;
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
  State state(problem, false, threadCount(threads));
  state.evaluateAll();
  return state.jacobian;
}

Eigen::MatrixXd nominalJacobian(const IdentificationProblem& problem, int threads) {
  State state(problem, true, threadCount(threads));
  state.evaluateAll();
  return std::move(state.jacobian);
}

ObservabilityReport planObservability(const IdentificationProblem& problem, int threads) {
  const auto cols = problemColumns(problem);
  return analyseObservability(nominalJacobian(problem, threads), cols.names, cols.typical, kRankTolerance, threads);
}

PredictedUncertainty predictUncertainty(const IdentificationProblem& problem, const std::vector<double>& runNoise, int threads) {
  if (runNoise.size() != problem.runs.size()) throw InvalidInput("predictUncertainty: one noise per run");
  State state(problem, true, threadCount(threads));
  state.evaluateAll();
  PredictedUncertainty out;
  out.columns = problemColumns(problem);
  const auto report = analyseObservability(state.jacobian, out.columns.names, out.columns.typical, kRankTolerance, threads);
  if (!report.identifiable()) {
    std::string why;
    for (const auto& f : report.findings()) why += (why.empty() ? "" : "; ") + f;
    throw NotIdentifiable(report, "the plan cannot determine this parameter set: " + why);
  }
  // Weighted and scaled to the typical sizes, so that the normal matrix is well conditioned.
  Eigen::MatrixXd& j = state.jacobian;
  for (size_t r = 0; r < problem.runs.size(); ++r)
    j.middleRows(state.rowStart[r], state.runs[r].poses() * readingSize(state.runs[r].instrument)) /= runNoise[r];
  j *= out.columns.typical.asDiagonal();
  const Eigen::MatrixXd normal = j.transpose() * j;
  const Eigen::Index n = normal.cols();
  out.covariance = out.columns.typical.asDiagonal() * normal.llt().solve(Eigen::MatrixXd::Identity(n, n)) *
                   out.columns.typical.asDiagonal();
  out.uncertainty = out.covariance.diagonal().cwiseSqrt();
  return out;
}

IdentifiableColumns proposeIdentifiableSet(const IdentificationProblem& problem, int threads) {
  State state(problem, true, threadCount(threads));
  state.evaluateAll();
  return proposeIdentifiableColumns(state.jacobian, problemColumns(problem).typical, static_cast<Eigen::Index>(problem.parameters.size()));
}

IdentificationResult identify(const IdentificationProblem& problem, const IdentificationOptions& options) {
  IdentificationResult out;
  out.columns = problemColumns(problem);
  const auto n = static_cast<Eigen::Index>(out.columns.names.size());
  if (n == 0) throw InvalidInput("no parameter to identify");
  checkReadings(problem, n);
  const int threads = threadCount(options.threads);

  // Observability about the nominal machine; when the start is the nominal machine, the same
  // evaluation is the solver's first.
  const bool startsAtNominal = allZero(problem);
  std::optional<State> holder(std::in_place, problem, true, threads);
  holder->evaluateAll();
  // Plain least squares use every evaluation only through its normal equations, so the
  // Jacobian can be factored in place; the robust solver reads its rows.
  const bool keepJacobian = options.robust;
  out.observability = analyseObservability(keepJacobian ? Eigen::MatrixXd(holder->jacobian) : std::move(holder->jacobian),
                                           out.columns.names, out.columns.typical, kRankTolerance, threads);
  if (!out.observability.identifiable()) {
    std::string why;
    for (const auto& f : out.observability.findings()) why += (why.empty() ? "" : "; ") + f;
    throw NotIdentifiable(out.observability, "the plan cannot determine this parameter set: " + why);
  }
  if (!startsAtNominal) holder.emplace(problem, false, threads);
  State& state = *holder;
  state.storeJacobian = keepJacobian;

  const std::vector<double> final = options.robust ? solveRobust(state, options, out)
                                                   : solveLeastSquares(state, out.columns.typical, options, out);

  // The covariance from the Jacobian at the solution (the solver's last one when it is there).
  if (!state.valid || state.point != final) {
    state.set(final);
    state.recompile(true);
    state.current = final;
    state.evaluateAll();
  }
  const Eigen::VectorXd& residual = state.residual;
  out.readings = static_cast<int>(residual.size());
  out.degreesOfFreedom = out.readings - static_cast<int>(n);
  out.sigma = std::sqrt(residual.squaredNorm() / out.degreesOfFreedom);
  out.residualRms = std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
  out.residualMax = residual.cwiseAbs().maxCoeff();
  out.residual = residual;
  for (size_t r = 0; r < state.runs.size(); ++r) {
    const Eigen::Index rows = state.runs[r].poses() * readingSize(state.runs[r].instrument);
    out.runResidualSquares.push_back(residual.segment(state.rowStart[r], rows).squaredNorm());
  }
  // The normal matrix with unit columns (Jacobi scaling), so that mm and rad mix safely.
  const Eigen::MatrixXd& gram = state.normal.gram;
  const Eigen::VectorXd scale = gram.diagonal().cwiseSqrt();
  const Eigen::MatrixXd normal = scale.cwiseInverse().asDiagonal() * gram * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd inv = normal.selfadjointView<Eigen::Lower>().ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  out.covariance = out.sigma * out.sigma * scale.cwiseInverse().asDiagonal() * inv * scale.cwiseInverse().asDiagonal();
  out.uncertainty = out.covariance.diagonal().cwiseSqrt();

  out.values = Eigen::Map<const Eigen::VectorXd>(final.data(), static_cast<Eigen::Index>(final.size()));
  out.errors = state.errors;
  out.runs = state.runs;
  return out;
}

}  // namespace mtacc
