#include "mtacc/workflows/measurement_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/plan_yaml.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/workflows/measurement_runs.hpp"

namespace mtacc {
namespace {

// "30min", "30 min", "1.5 h", "90 s"; a bare number is minutes.
double parseMinutes(const std::string& given) {
  std::string text;
  for (const char c : given)
    if (c != ' ') text += c;
  double factor = 1.0;
  for (const auto& [unit, f] : std::vector<std::pair<std::string, double>>{{"min", 1.0}, {"h", 60.0}, {"s", 1.0 / 60.0}})
    if (text.size() > unit.size() && text.ends_with(unit)) {
      text.resize(text.size() - unit.size());
      factor = f;
      break;
    }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) || !(value > 0) || value * factor > 7 * 24 * 60)
    throw InputError({"", 0, "time"}, "'" + given + "' is not a machine time (e.g. 30min, 1.5h; above 0, at most a week)");
  return value * factor;
}

std::string instrumentsText(const std::vector<Instrument>& instruments) {
  std::string out;
  for (const auto i : instruments) out += (out.empty() ? "" : ", ") + instrumentName(i);
  return out;
}

// A run's information on the machine parameters (columns scaled by `typical`) once its own set-up
// unknowns are estimated from it: the Schur complement of its normal matrix, as the rows F with
// F^T F equal to it (its eigenvectors, those of no information left out).
Eigen::MatrixXd informationFactor(const IdentificationProblem& problem, double noise, const Eigen::VectorXd& typical) {
  const Eigen::MatrixXd j = nominalJacobian(problem, 1) / noise;
  const Eigen::Index p = typical.size();
  Eigen::MatrixXd jp = j.leftCols(p) * typical.asDiagonal();
  if (j.cols() > p) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(j.rightCols(j.cols() - p));
    const Eigen::MatrixXd q = Eigen::MatrixXd(qr.householderQ()).leftCols(qr.rank());
    jp -= q * (q.transpose() * jp);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jp.transpose() * jp);
  const double largest = eig.eigenvalues().maxCoeff();
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < p; ++k)
    if (eig.eigenvalues()[k] > 1e-12 * largest) kept.push_back(k);
  Eigen::MatrixXd f(static_cast<Eigen::Index>(std::max<size_t>(kept.size(), 1)), p);
  f.setZero();
  for (size_t r = 0; r < kept.size(); ++r)
    f.row(static_cast<Eigen::Index>(r)) = std::sqrt(eig.eigenvalues()[kept[r]]) * eig.eigenvectors().col(kept[r]).transpose();
  return f;
}

// Poses over the working volume: the linear axes at a quarter, half and three quarters of their
// travels, each rotary axis at five positions over its travel (or a turn).
std::vector<std::vector<double>> volumePoses(const Machine& m) {
  std::vector<std::vector<double>> poses{{}};
  for (int j = 0; j < m.commandedCount(); ++j) {
    const auto& a = m.axes[static_cast<size_t>(j)];
    std::vector<double> levels;
    if (!a.isRotary()) {
      const double lo = a.travel ? a.travel->min : -100, hi = a.travel ? a.travel->max : 100;
      levels = {lo + 0.25 * (hi - lo), 0.5 * (lo + hi), lo + 0.75 * (hi - lo)};
    } else if (a.travel) {
      for (int k = 0; k < 5; ++k) levels.push_back(a.travel->min + (a.travel->max - a.travel->min) * k / 4.0);
    } else {
      for (int k = 0; k < 5; ++k) levels.push_back(2 * kPi * k / 5.0);
    }
    std::vector<std::vector<double>> next;
    for (const auto& q : poses)
      for (const double v : levels) {
        auto r = q;
        r.push_back(v);
        next.push_back(r);
      }
    poses = std::move(next);
  }
  return poses;
}

// The TCP's k = 2 uncertainty over the volume (root mean square and largest, mm) from the
// parameters' covariance: u^2 = trace(T Sigma T^T) at each pose, T the TCP's Jacobian.
std::pair<double, double> tcpSpread(const std::vector<Eigen::MatrixXd>& tcp, const Eigen::MatrixXd& covariance) {
  double sum = 0, largest = 0;
  for (const auto& t : tcp) {
    const double u2 = std::max(0.0, (t * covariance * t.transpose()).trace());
    sum += u2;
    largest = std::max(largest, u2);
  }
  return {2 * std::sqrt(sum / static_cast<double>(tcp.size())), 2 * std::sqrt(largest)};
}

class Designer {
 public:
  Designer(const MachineSetup& setup, const MeasurementDesignRequest& request) : setup_(setup), request_(request) {
    const auto nominal = setup.nominal();
    std::vector<std::string> names = request.parameters;
    std::optional<TestPlan> own;
    InputLocation namedAt{"", 0, "parameters"};
    if (request.plan) {
      own = loadTestPlan(nominal, *request.plan);
      if (names.empty()) {
        names = own->parameters;
        namedAt = own->parametersAt;
      }
    }
    if (names.empty()) throw InputError({"", 0, "parameters"}, "no parameter to determine (name them, or give a plan with 'parameters')");
    shape_ = setup.errors;
    out_.parameters = findPlanParameters(setup.machine, shape_, names, namedAt);
    out_.machine = setup.machine;
    out_.criterion = request.criterion;
    out_.time = request.time;
    out_.againstPlan = request.againstPlan || request.reach;
    out_.budget = request.minutes;
    typical_ = problemColumns(problemOf({})).typical;  // 1 um, 10 urad
    tcpJacobians();
    CandidateSet set;
    try {
      set = designCandidates(nominal, request.candidates);
    } catch (const InvalidInput& e) {
      throw InputError({"", 0, "instruments"}, e.reason());
    }
    candidates_ = std::move(set.candidates);
    out_.notes = std::move(set.notes);
    out_.candidates = candidates_.size();
    factorCandidates();
    refuseWhatNoRunDetermines();
    if (own) {
      try {
        out_.own = outlook(own->runs);
      } catch (const NotIdentifiable& e) {
        if (request.reach || request.againstPlan) throw InputError({"", 0, "plan"}, e.reason());
        out_.ownRefused = e.reason();
      }
    }
    if ((request.reach || request.againstPlan) && !own)
      throw InputError({"", 0, request.reach ? "reach" : "criterion"}, "the design against a plan needs the plan (--plan)");
    if (out_.own) target_ = out_.own->prediction.uncertainty.head(typical_.size()).cwiseQuotient(typical_);
  }

  MeasurementDesign run() {
    if (request_.reach) reachOwnPlan();
    out_.design = designAt(out_.budget);
    for (const int c : out_.design.chosen) out_.chosen.push_back(candidates_[static_cast<size_t>(c)]);
    // In the order an operator makes them: by instrument, then set-up (a sphere moved once).
    std::stable_sort(out_.chosen.begin(), out_.chosen.end(), [](const DesignCandidate& a, const DesignCandidate& b) {
      return std::pair{a.run.instrument, setupKey(a.run)} < std::pair{b.run.instrument, setupKey(b.run)};
    });
    std::vector<MeasurementRun> runs;
    for (const auto& c : out_.chosen) runs.push_back(c.run);
    out_.outlook = outlook(runs);
    for (const double factor : {0.25, 0.5, 0.75, 1.0, 1.5, 2.0}) out_.pareto.push_back(paretoPoint(factor * out_.budget));
    out_.planText = planText();
    return std::move(out_);
  }

 private:
  void tcpJacobians() {
    const KinematicModel model = compile(setup_.machine, withParametersZero(*setup_.machine, shape_), out_.parameters);
    KinematicData data;
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(typical_.size(), typical_.size());
    for (const auto& q : volumePoses(*setup_.machine)) {
      tcp_.push_back(pointJacobian(model, q.data(), nullptr, Vec3::Zero(), data).jacobian);
      const Eigen::MatrixXd scaled = tcp_.back() * typical_.asDiagonal();
      w.noalias() += scaled.transpose() * scaled;
    }
    tcpWeight_ = w / static_cast<double>(tcp_.size());
    out_.volumePoses = tcp_.size();
  }

  double noiseOf(const MeasurementRun& run) const {
    const auto it = request_.noise.find(run.instrument);
    if (it == request_.noise.end())
      throw InputError({"", 0, "noise"}, fmt::format("no noise given for the {} of run '{}'", instrumentName(run.instrument), run.name));
    return it->second;
  }

  IdentificationProblem problemOf(std::vector<MeasurementRun> runs) const { return {setup_.machine, shape_, out_.parameters, std::move(runs)}; }

  void factorCandidates() {
    std::vector<double> noise;
    for (const auto& c : candidates_) noise.push_back(noiseOf(c.run));
    factors_.resize(candidates_.size());
    parallelFor(static_cast<long>(candidates_.size()), request_.threads, [&](long begin, long end) {
      for (auto c = static_cast<size_t>(begin); c < static_cast<size_t>(end); ++c)
        factors_[c] = informationFactor(problemOf({candidates_[c].run}), noise[c], typical_);
    }, 1);
    // Groups: the instruments (mounted once), then the set-ups (a sphere placed once for its runs).
    std::map<std::string, int> group;
    for (const auto i : request_.candidates.instruments) group.emplace(instrumentName(i), static_cast<int>(group.size()));
    groupCost_.assign(group.size(), request_.time.instrumentMinutes);
    for (const auto& c : candidates_) {
      cost_.push_back(runMinutes(*setup_.machine, c.run, request_.time));
      const auto [it, added] = group.emplace(setupKey(c.run), static_cast<int>(group.size()));
      if (added) groupCost_.push_back(request_.time.setupMinutes);
      groups_.push_back({group.at(instrumentName(c.run.instrument)), it->second});
    }
  }

  // What no candidate run can determine, their set-ups estimated: refused with the reasons.
  void refuseWhatNoRunDetermines() const {
    Eigen::Index rows = 0;
    for (const auto& f : factors_) rows += f.rows();
    Eigen::MatrixXd all(rows, typical_.size());
    rows = 0;
    for (const auto& f : factors_) {
      all.middleRows(rows, f.rows()) = f;
      rows += f.rows();
    }
    std::vector<std::string> names;
    for (const auto& p : out_.parameters) names.push_back(p.name);
    const auto report = analyseObservability(all, names, Eigen::VectorXd::Ones(typical_.size()), kRankTolerance, request_.threads);
    if (report.identifiable()) return;
    const std::string scope = fmt::format("any run of {} ({} candidates, each with its set-up estimated)",
                                          instrumentsText(request_.candidates.instruments), candidates_.size());
    std::string why;
    for (const auto& f : report.findings(scope)) why += (why.empty() ? "" : "; ") + f;
    throw InputError({"", 0, "parameters"}, "no plan of these instruments can determine this parameter set: " + why +
                                                " (name fewer parameters, or add an instrument)");
  }

  // The parameters' standard uncertainties of a design relative to the user's plan's.
  Eigen::VectorXd ratioToPlan(const Design& d) const {
    const Eigen::Index p = typical_.size();
    return d.information.ldlt().solve(Eigen::MatrixXd::Identity(p, p)).diagonal().cwiseSqrt().cwiseQuotient(target_);
  }

  // The design whose largest uncertainty relative to the plan's is smallest: I-optimal designs for
  // W = diag(w / u_plan^2), the weights w of the parameters already well determined lowered by the
  // square of their ratio to the worst, a few times (a minimax approached by reweighting); the best.
  Design balancedAt(double budget) const {
    Eigen::VectorXd w = target_.cwiseInverse().cwiseAbs2();
    std::optional<Design> best;
    double bestRatio = 0;
    for (int round = 0; round < 6; ++round) {
      DesignOptions o = optionsAt(budget);
      o.criterion = DesignCriterion::I;
      o.weight = w.asDiagonal();
      const Design d = designExperiment(factors_, o);
      const Eigen::VectorXd r = ratioToPlan(d);
      if (!best || r.maxCoeff() < bestRatio) {
        best = d;
        bestRatio = r.maxCoeff();
      }
      w = w.cwiseProduct((r / r.maxCoeff()).cwiseAbs2());
      w /= w.maxCoeff();
    }
    return *best;
  }

  // The shortest budget, in whole minutes up to twice the plan's time, whose balanced design
  // determines every parameter at least as well as the user's plan: every fifth minute, then the
  // minutes below the first that reaches it.
  void reachOwnPlan() {
    const auto reaches = [&](double budget) {
      try {
        return (ratioToPlan(balancedAt(budget)).array() <= 1 + 1e-9).all();
      } catch (const InvalidInput&) {
        return false;  // too short to determine the parameters at all
      }
    };
    for (double coarse = 5; coarse <= 2 * out_.own->minutes + 5; coarse += 5) {
      if (!reaches(coarse)) continue;
      out_.budget = coarse;
      for (double fine = coarse - 4; fine < coarse; fine += 1)
        if (fine > 0 && reaches(fine)) {
          out_.budget = fine;
          break;
        }
      out_.reached = true;
      return;
    }
    throw InputError({"", 0, "reach"}, fmt::format("no design of {} reaches the plan's uncertainties in twice its {:.0f} min",
                                                   instrumentsText(request_.candidates.instruments), out_.own->minutes));
  }

  DesignOptions optionsAt(double budget) const {
    DesignOptions o;
    o.criterion = request_.criterion;
    o.cost = cost_;
    o.groups = groups_;
    o.groupCost = groupCost_;
    o.budget = budget;
    o.repeats = false;
    if (o.criterion == DesignCriterion::I) o.weight = tcpWeight_;
    return o;
  }

  Design designOf(double budget) const { return againstPlan() ? balancedAt(budget) : designExperiment(factors_, optionsAt(budget)); }
  bool againstPlan() const { return request_.againstPlan || request_.reach; }

  Design designAt(double budget) const {
    try {
      return designOf(budget);
    } catch (const InvalidInput&) {
      for (double more = 2 * budget; more <= 64 * budget; more *= 2) {
        try {
          const Design d = designOf(more);
          throw InputError({"", 0, "time"}, fmt::format("{:.0f} min is too short to determine these {} parameters with {}: a design of "
                                                        "{:.1f} min does (give --time {:.0f}min or more, or name fewer parameters)",
                                                        budget, out_.parameters.size(), instrumentsText(request_.candidates.instruments),
                                                        d.cost, std::ceil(d.cost)));
        } catch (const InvalidInput&) {
        }
      }
      throw InputError({"", 0, "time"}, fmt::format("{:.0f} min is far too short to determine these parameters", budget));
    }
  }

  ParetoPoint paretoPoint(double budget) const {
    ParetoPoint point;
    point.budget = budget;
    try {
      const Design d = designOf(budget);
      point.minutes = d.cost;
      point.runs = d.chosen.size();
      point.criterion = d.criterion;
      const Eigen::Index p = typical_.size();
      const Eigen::MatrixXd covariance =
          typical_.asDiagonal() * d.information.ldlt().solve(Eigen::MatrixXd::Identity(p, p)) * typical_.asDiagonal();
      std::tie(point.tcpRms, point.tcpMax) = tcpSpread(tcp_, covariance);
      for (Eigen::Index k = 0; k < p; ++k) {
        double& worst = out_.parameters[static_cast<size_t>(k)].dimension == Dimension::Length ? point.worstLength : point.worstAngle;
        worst = std::max(worst, 2 * std::sqrt(covariance(k, k)));
      }
    } catch (const InvalidInput&) {
      point.refused = fmt::format("too short to determine the {} parameters", out_.parameters.size());
    }
    return point;
  }

  PlanOutlook outlook(const std::vector<MeasurementRun>& runs) const {
    PlanOutlook o;
    std::vector<double> noise;
    for (const auto& r : runs) {
      o.runs.push_back(r.name);
      o.runMinutes.push_back(runMinutes(*setup_.machine, r, request_.time));
      noise.push_back(noiseOf(r));
    }
    o.minutes = planMinutes(*setup_.machine, runs, request_.time);
    o.prediction = predictUncertainty(problemOf(runs), noise, request_.threads);
    const auto p = static_cast<Eigen::Index>(out_.parameters.size());
    std::tie(o.tcpRms, o.tcpMax) = tcpSpread(tcp_, o.prediction.covariance.topLeftCorner(p, p));
    return o;
  }

  std::string planText() const {
    std::string names;
    for (const auto& p : out_.parameters) names += (names.empty() ? "" : ", ") + p.name;
    std::string text = fmt::format(
        "# Designed by mtacc design for {}: {}-optimal among {} candidate runs of {}, {:.1f} min of machine time\n"
        "# (budget {:g} min; {:g} min per set-up, {:g} min per instrument). Each run's noise is the one the design assumed.\n",
        setup_.machine->name, out_.againstPlan ? "plan" : toString(out_.criterion), candidates_.size(), instrumentsText(request_.candidates.instruments),
        out_.outlook.minutes, out_.budget, request_.time.setupMinutes, request_.time.instrumentMinutes);
    text += fmt::format("name: Designed plan, {}-optimal in {:g} min\nparameters: [{}]\nruns:\n", out_.againstPlan ? "plan" : toString(out_.criterion),
                        out_.budget, names);
    for (size_t k = 0; k < out_.chosen.size(); ++k) {
      const auto& c = out_.chosen[k];
      text += fmt::format("  # {:.1f} min: {}\n{}    noise: {:.6g} um\n", out_.outlook.runMinutes[k], c.description, c.planEntry,
                          noiseOf(c.run) * 1e3);
    }
    return text;
  }

  const MachineSetup& setup_;
  const MeasurementDesignRequest& request_;
  ErrorModel shape_;
  Eigen::VectorXd typical_;
  std::vector<Eigen::MatrixXd> tcp_;
  Eigen::MatrixXd tcpWeight_;  // I: the TCP's variance over the volume
  Eigen::VectorXd target_;     // against the plan: its standard uncertainties (in the typical sizes)
  std::vector<DesignCandidate> candidates_;
  std::vector<Eigen::MatrixXd> factors_;
  std::vector<double> cost_, groupCost_;
  std::vector<std::vector<int>> groups_;
  MeasurementDesign out_;
};

}  // namespace

const OptionSchema& measurementDesignSchema() {
  static const OptionSchema schema{
      "design",
      {{"parameters", OptionKind::List, "Parameters to determine, e.g. X0B,Z0B,A0C; default: the plan's list (--plan)"},
       {.key = "instruments", .kind = OptionKind::List, .help = "the instruments at hand: rtest, ballbar, probe", .defaultText = "rtest,ballbar"},
       {"time", OptionKind::Text, "the machine time available, e.g. 30min, 1.5h"},
       {"reach", OptionKind::Flag, "instead of --time: the shortest design that determines every parameter at least as well as --plan"},
       {.key = "criterion", .kind = OptionKind::Text,
        .help = "D (the parameters' joint uncertainty), A (the sum of their variances), I (the TCP's after compensation over the working "
                "volume), plan (the largest uncertainty relative to --plan's)",
        .defaultText = "D"},
       {.key = "noise", .kind = OptionKind::List, .help = "each instrument's reading noise (standard deviation)",
        .defaultText = "rtest=0.5um,ballbar=0.5um,probe=1um"},
       {"plan", OptionKind::Text, "your own plan: its time and predicted uncertainties beside the design's (and its parameters by default)"},
       {"plan_out", OptionKind::Text, "write the designed plan (YAML) that simulate, observability and identify read"},
       {"html", OptionKind::Text, "write the report for the operator (HTML: the plan in order, set-ups, uncertainties, time against uncertainty)"},
       {.key = "radii", .kind = OptionKind::List, .help = "the spheres' distances from a table axis's line to choose from",
        .defaultText = "50mm,100mm,200mm"},
       {.key = "spread", .kind = OptionKind::Quantity, .help = "the second sphere along a table axis's line, the tool ball beyond the tip on a head axis",
        .defaultText = "100 mm", .low = 1.0, .high = 2000.0, .outOfRange = "must be from 1 mm to 2 m"},
       {.key = "lengths", .kind = OptionKind::List, .help = "the ballbar lengths to choose from", .defaultText = "100mm,150mm"},
       {.key = "positions", .kind = OptionKind::Numbers, .help = "the numbers of R-test and probe positions per sweep to choose from",
        .defaultText = "8,16", .low = 3, .high = 360, .outOfRange = "must be from 3 to 360"},
       {.key = "points", .kind = OptionKind::Count, .help = "ballbar readings per sweep (a circle: per direction)", .defaultText = "72",
        .low = 8, .high = 3600, .outOfRange = "must be from 8 to 3600"},
       {.key = "feed", .kind = OptionKind::Number, .help = "the ballbar's contouring feed (mm/min)", .defaultText = "1000", .low = 1,
        .high = 1e5, .outOfRange = "must be from 1 to 100000 mm/min"},
       {.key = "rapid", .kind = OptionKind::Number, .help = "the linear axes' rapid feed (mm/min)", .defaultText = "10000", .low = 10,
        .high = 2e5, .outOfRange = "must be from 10 to 200000 mm/min"},
       {.key = "rotary_rapid", .kind = OptionKind::Number, .help = "the rotary axes' rapid feed (deg/min)", .defaultText = "3600", .low = 10,
        .high = 2e5, .outOfRange = "must be from 10 to 200000 deg/min"},
       {.key = "acceleration", .kind = OptionKind::Number, .help = "the linear axes' acceleration (mm/s^2)", .defaultText = "1000", .low = 1,
        .high = 1e5, .outOfRange = "must be from 1 to 100000 mm/s^2"},
       {.key = "rotary_acceleration", .kind = OptionKind::Number, .help = "the rotary axes' acceleration (deg/s^2)", .defaultText = "180",
        .low = 1, .high = 1e5, .outOfRange = "must be from 1 to 100000 deg/s^2"},
       {.key = "dwell", .kind = OptionKind::Number, .help = "seconds per R-test position (settling and reading)", .defaultText = "2", .low = 0,
        .high = 600, .outOfRange = "must be from 0 to 600 s"},
       {.key = "probe_time", .kind = OptionKind::Number, .help = "seconds per probed sphere", .defaultText = "20", .low = 0, .high = 600,
        .outOfRange = "must be from 0 to 600 s"},
       {.key = "setup_time", .kind = OptionKind::Number, .help = "minutes per run's set-up (a sphere placed, a ballbar mounted)",
        .defaultText = "3", .low = 0, .high = 600, .outOfRange = "must be from 0 to 600 min"},
       {.key = "change_time", .kind = OptionKind::Number, .help = "minutes to mount an instrument", .defaultText = "15", .low = 0,
        .high = 600, .outOfRange = "must be from 0 to 600 min"},
       threadsOption()}};
  return schema;
}

MeasurementDesignRequest measurementDesignRequest(const OptionValues& values) {
  const OptionReader r(measurementDesignSchema(), values);
  MeasurementDesignRequest q;
  q.parameters = r.list("parameters");
  q.candidates.instruments.clear();
  for (const auto& name : r.list("instruments")) {
    const auto i = parseInstrument(name);
    if (!i || *i == Instrument::Directional) throw InputError({"", 0, "instruments"}, "'" + name + "' is not rtest, ballbar or probe");
    if (std::find(q.candidates.instruments.begin(), q.candidates.instruments.end(), *i) == q.candidates.instruments.end())
      q.candidates.instruments.push_back(*i);
  }
  q.reach = r.flag("reach");
  if (const auto time = r.text("time")) {
    if (q.reach) throw InputError({"", 0, "reach"}, "give --time or --reach, not both");
    q.minutes = parseMinutes(*time);
  } else if (!q.reach) {
    throw InputError({"", 0, "time"}, "give the machine time available (--time 30min), or --reach with --plan");
  }
  const std::string criterion = *r.text("criterion");
  if (criterion == "D" || criterion == "d") q.criterion = DesignCriterion::D;
  else if (criterion == "A" || criterion == "a") q.criterion = DesignCriterion::A;
  else if (criterion == "I" || criterion == "i" || criterion == "tcp") q.criterion = DesignCriterion::I;
  else if (criterion == "plan") q.againstPlan = true;
  else throw InputError({"", 0, "criterion"}, "'" + criterion + "' is not D, A, I or plan");
  for (const auto& entry : r.list("noise")) {
    const auto eq = entry.find('=');
    const auto instrument = eq == std::string::npos ? std::nullopt : parseInstrument(trim(entry.substr(0, eq)));
    if (!instrument) throw InputError({"", 0, "noise"}, "'" + entry + "' is not instrument=noise, e.g. rtest=0.5um");
    const double noise = parseQuantityAs(trim(entry.substr(eq + 1)), Dimension::Length, "noise");
    if (!(noise >= 1e-6 && noise <= 1.0)) throw InputError({"", 0, "noise"}, "'" + entry + "': the noise must be from 1 nm to 1 mm");
    q.noise[*instrument] = noise;
  }
  q.plan = r.text("plan");
  q.planOut = r.text("plan_out");
  q.candidates.radii.clear();
  for (const auto& text : r.list("radii")) {
    const double radius = parseQuantityAs(text, Dimension::Length, "radii");
    if (!(radius >= 1.0 && radius <= 2000.0)) throw InputError({"", 0, "radii"}, "'" + text + "': a radius must be from 1 mm to 2 m");
    q.candidates.radii.push_back(radius);
  }
  q.candidates.spread = *r.quantity("spread");
  q.candidates.ballbarLengths.clear();
  for (const auto& text : r.list("lengths")) {
    const double length = parseQuantityAs(text, Dimension::Length, "lengths");
    if (!(length >= 10.0 && length <= 1500.0)) throw InputError({"", 0, "lengths"}, "'" + text + "': a ballbar length must be from 10 mm to 1.5 m");
    q.candidates.ballbarLengths.push_back(length);
  }
  q.candidates.positions.clear();
  for (const double n : r.numbers("positions")) {
    if (n != std::round(n)) throw InputError({"", 0, "positions"}, fmt::format("{:g} is not a whole number of positions", n));
    q.candidates.positions.push_back(static_cast<int>(n));
  }
  q.candidates.ballbarPoints = *r.count("points");
  q.candidates.feed = *r.number("feed");
  q.time.linearRapid = *r.number("rapid");
  q.time.rotaryRapid = *r.number("rotary_rapid") * kDeg;
  q.time.linearAcceleration = *r.number("acceleration");
  q.time.rotaryAcceleration = *r.number("rotary_acceleration") * kDeg;
  q.time.rtestDwell = *r.number("dwell");
  q.time.probeTime = *r.number("probe_time");
  q.time.setupMinutes = *r.number("setup_time");
  q.time.instrumentMinutes = *r.number("change_time");
  q.threads = *r.count("threads");
  return q;
}

MeasurementDesign designMeasurement(const MachineSetup& setup, const MeasurementDesignRequest& request) {
  if (!(request.minutes > 0) && !request.reach)
    throw InputError({"", 0, "time"}, "give the machine time available (--time 30min), or --reach with --plan");
  auto design = Designer(setup, request).run();
  if (request.planOut) {
    writeFileAtomically(*request.planOut, design.planText, "plan_out");
    design.written.push_back(*request.planOut);
  }
  return design;
}

namespace {

nlohmann::json toJson(const PlanOutlook& o, const std::vector<Parameter>& parameters) {
  nlohmann::json ps = nlohmann::json::array();
  for (size_t k = 0; k < parameters.size(); ++k) {
    const bool length = parameters[k].dimension == Dimension::Length;
    const double u = o.prediction.uncertainty[static_cast<Eigen::Index>(k)] * (length ? 1e3 : 1e6);
    ps.push_back({{"name", parameters[k].name}, {"unit", length ? "um" : "urad"}, {"u", u}, {"u_k2", 2 * u}});
  }
  return {{"runs", o.runs},   {"run_time_min", o.runMinutes},    {"time_min", o.minutes},
          {"parameters", ps}, {"tcp_rms_k2_um", o.tcpRms * 1e3}, {"tcp_max_k2_um", o.tcpMax * 1e3}};
}

}  // namespace

nlohmann::json toJson(const MeasurementDesign& d) {
  nlohmann::json runs = nlohmann::json::array();
  for (size_t k = 0; k < d.chosen.size(); ++k) {
    const auto& c = d.chosen[k];
    nlohmann::json run = runJson(*d.machine, c.run);
    run.erase("readings_um");
    run.update({{"description", c.description}, {"set_up", setupKey(c.run)}, {"time_min", d.outlook.runMinutes[k]}});
    runs.push_back(run);
  }
  nlohmann::json pareto = nlohmann::json::array();
  for (const auto& p : d.pareto) {
    nlohmann::json row{{"budget_min", p.budget}};
    if (!p.refused.empty()) {
      row["refused"] = p.refused;
    } else {
      row.update({{"time_min", p.minutes}, {"runs", p.runs}, {"criterion_value", p.criterion}, {"tcp_rms_k2_um", p.tcpRms * 1e3},
                  {"tcp_max_k2_um", p.tcpMax * 1e3}, {"worst_length_k2_um", p.worstLength * 1e3}, {"worst_angle_k2_urad", p.worstAngle * 1e6}});
    }
    pareto.push_back(row);
  }
  nlohmann::json out{{"machine", d.machine->name},
                     {"criterion", d.againstPlan ? "plan" : toString(d.criterion)},
                     {"reached", d.reached},
                     {"budget_min", d.budget},
                     {"candidates", d.candidates},
                     {"exchanges", d.design.exchanges},
                     {"volume_poses", d.volumePoses},
                     {"runs", runs},
                     {"design", toJson(d.outlook, d.parameters)},
                     {"pareto", pareto},
                     {"time_model", {{"rapid_mm_per_min", d.time.linearRapid}, {"dwell_s", d.time.rtestDwell},
                                     {"probe_time_s", d.time.probeTime}, {"set_up_min", d.time.setupMinutes},
                                     {"change_min", d.time.instrumentMinutes}}},
                     {"notes", d.notes},
                     {"plan", d.planText},
                     {"written", d.written}};
  if (d.own) out["own_plan"] = toJson(*d.own, d.parameters);
  if (!d.ownRefused.empty()) out["own_plan"] = {{"refused", d.ownRefused}};
  return out;
}

}  // namespace mtacc
