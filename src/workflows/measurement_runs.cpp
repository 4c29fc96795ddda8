#include "mtacc/workflows/measurement_runs.hpp"

#include <filesystem>
#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/io/measurement_csv.hpp"
#include "mtacc/io/plan_yaml.hpp"
#include "mtacc/io/pose_text.hpp"

namespace mtacc {

namespace {

// The runs' folder: created when missing; an existing one must not hold other CSV files,
// which a later `identify --data FOLDER/*.csv` would take for measurements of this plan.
void requireFolderFor(const std::string& folder, const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    throw InputError(InputLocation{"", 0, "output"}, "'" + folder + "' is a file; name a folder for the runs");
  if (!fs::exists(folder, ec)) {
    fs::create_directories(folder, ec);
    if (ec) throw InputError(InputLocation{"", 0, "output"}, "cannot create the folder '" + folder + "': " + ec.message());
    return;
  }
  std::vector<std::string> stale;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const auto path = entry.path();
    if (path.extension() != ".csv") continue;
    bool written = false;
    for (const auto& f : files) written = written || fs::path(f).filename() == path.filename();
    if (!written) stale.push_back(path.filename().string());
  }
  if (!stale.empty())
    throw InputError(InputLocation{"", 0, "output"}, "'" + folder + "' already holds " + std::to_string(stale.size()) +
                                                       " CSV file(s) this plan does not write (" + stale.front() +
                                                       (stale.size() > 1 ? ", ..." : "") + "); name an empty or new folder");
}

}  // namespace

Disturbance disturbanceFromText(const Machine& machine, const std::string& lag, const std::string& backlash, const std::string& spike,
                                double spikeTime) {
  Disturbance d;
  d.lag = parseAxisTimes(machine, lag, "lag");
  d.backlash = parseAxisQuantities(machine, backlash, "backlash");
  d.spikeHeight = parseAxisQuantities(machine, spike, "spike");
  d.spikeTime = spikeTime;
  return d;
}

std::array<std::optional<double>, kSetupParameterCount> parseSetupErrors(const std::string& text, const std::string& key) {
  std::array<std::optional<double>, kSetupParameterCount> errors{};
  for (const auto& a : parseAssignments(text, key)) {
    const auto p = parseSetupParameter(a.name);
    if (!p) throw InputError(InputLocation{"", 0, key}, "expected NAME=value with NAME one of xT yT zT xW yW zW aN bN cN dL, got '" + a.name + "'");
    errors[static_cast<size_t>(*p)] = parseQuantityAs(a.value, setupParameterDimension(*p), key + " " + a.name);
  }
  return errors;
}

SimulationResult simulateRuns(const MachineSetup& setup, std::vector<MeasurementRun> runs, const SimulationOptions& o) {
  if (!(o.noise >= 0)) throw InputError(InputLocation{"", 0, "noise"}, "must not be negative");
  if (!(o.disturbance.spikeTime > 0 && o.disturbance.spikeTime <= 1e3))
    throw InputError(InputLocation{"", 0, "spike_time"}, "must be positive and at most 1000 s");
  for (double lag : o.disturbance.lag)
    if (!(lag >= 0 && lag <= 1e3)) throw InputError(InputLocation{"", 0, "lag"}, "must be from 0 to 1000 s");
  for (double lostMotion : o.disturbance.backlash)
    if (!(lostMotion >= 0)) throw InputError(InputLocation{"", 0, "backlash"}, "must not be negative");
  const auto nominal = setup.nominal();
  const auto model = setup.actual();
  std::mt19937_64 rng(o.seed);
  SimulationResult r{setup.machine, o.noise, {}, {}};
  std::vector<std::string> texts;
  for (auto& run : runs) {
    for (int k = 0; k < kSetupParameterCount; ++k)
      if (o.setupErrors[static_cast<size_t>(k)] && appliesTo(static_cast<SetupParameter>(k), run.instrument))
        run.setup.errors[static_cast<size_t>(k)] = *o.setupErrors[static_cast<size_t>(k)];
    simulateRun(model, nominal, run, o.disturbance, o.noise, &rng);
    if (o.noise > 0) run.noise = o.noise;
    if (!o.output.empty()) {
      r.files.push_back(o.outputIsFolder ? (std::filesystem::path(o.output) / (run.name + ".csv")).string() : o.output);
      texts.push_back(measurementCsv(*setup.machine, run));
    }
  }
  if (!o.output.empty() && !o.outputIsFolder && runs.size() != 1)
    throw InputError(InputLocation{"", 0, "output"}, "several runs need an output folder");
  if (o.outputIsFolder && !o.output.empty()) requireFolderFor(o.output, r.files);
  for (size_t i = 0; i < r.files.size(); ++i) writeFileAtomically(r.files[i], texts[i]);
  r.runs = std::move(runs);
  return r;
}

SimulationResult simulateBallbarCircle(const MachineSetup& setup, const BallbarCircleSpec& spec, const SimulationOptions& options) {
  if (!(spec.radius > 0)) throw InputError(InputLocation{"", 0, "radius"}, "must be positive");
  if (!(spec.feed > 0 && spec.feed <= 1e6)) throw InputError(InputLocation{"", 0, "feed"}, "must be positive (at most 1e6 mm/min)");
  if (spec.points < 8 || spec.points > kMaxPointsPerRun)
    throw InputError(InputLocation{"", 0, "points"}, "must be from 8 to " + std::to_string(kMaxPointsPerRun));
  std::vector<MeasurementRun> runs;
  try {
    runs = {ballbarCircle(setup.nominal(), spec)};
  } catch (const InvalidInput& e) {
    throw InputError(InputLocation{"", 0, "plane"}, e.what());
  }
  if (const auto violation = travelViolation(*setup.machine, runs[0]); !violation.empty())
    throw InputError(InputLocation{"", 0, "centre"}, "the circle leaves the machine's travel at " + violation);
  return simulateRuns(setup, std::move(runs), options);
}

SimulationResult simulateSphereTest(const MachineSetup& setup, const SphereTestSpec& spec, const SimulationOptions& options) {
  if (spec.angles.empty() || spec.angles.size() > static_cast<size_t>(kMaxPointsPerRun))
    throw InputError(InputLocation{"", 0, "points"}, "must be from 1 to " + std::to_string(kMaxPointsPerRun));
  std::vector<MeasurementRun> runs;
  try {
    runs = sphereTest(setup.nominal(), spec);
  } catch (const InvalidInput& e) {
    throw InputError(InputLocation{"", 0, "axis"}, e.what());
  }
  for (const auto& run : runs)
    if (const auto violation = travelViolation(*setup.machine, run); !violation.empty())
      throw InputError(InputLocation{"", 0, "sphere"}, "the test leaves the machine's travel at " + violation);
  return simulateRuns(setup, std::move(runs), options);
}

SimulationResult simulatePlan(const MachineSetup& setup, const std::string& planFile, const SimulationOptions& options) {
  auto plan = loadTestPlan(setup.nominal(), planFile);
  ErrorModel shape = setup.errors;  // the plan's parameters checked as identify will find them
  findPlanParameters(setup.machine, shape, plan.parameters, plan.parametersAt);
  return simulateRuns(setup, std::move(plan.runs), options);
}

nlohmann::json runJson(const Machine& m, const MeasurementRun& run) {
  nlohmann::json poses = nlohmann::json::array(), readings = nlohmann::json::array(), angle = nlohmann::json::array();
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int k = 0; k < m.commandedCount(); ++k)
      row.push_back(m.axes[static_cast<size_t>(k)].isRotary() ? run.q(i, k) / kDeg : run.q(i, k));
    poses.push_back(row);
  }
  for (Eigen::Index i = 0; i < run.readings.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index k = 0; k < run.readings.cols(); ++k) row.push_back(run.readings(i, k) * 1e3);
    readings.push_back(row);
  }
  for (double a : run.angle) angle.push_back(a / kDeg);
  return {{"name", run.name}, {"instrument", instrumentName(run.instrument)}, {"poses", poses.size()},
          {"q", poses}, {"readings_um", readings}, {"angle_deg", angle}, {"sense", run.sense},
          {"length_mm", run.setup.length},
          // Where the balls are: the sphere (R-test, probe) or work ball (ballbar, unless set at
          // the tool ball: "set_at"), workpiece frame, and the tool ball, tool frame.
          {"target_mm", run.setup.setAt ? nlohmann::json(nullptr) : vectorJson(run.setup.target)},
          {"tool_ball_mm", vectorJson(run.setup.toolBall)}};
}

nlohmann::json toJson(const SimulationResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine->name;
  j["noise_um"] = r.noise * 1e3;
  j["runs"] = nlohmann::json::array();
  for (size_t i = 0; i < r.runs.size(); ++i) {
    auto run = runJson(*r.machine, r.runs[i]);
    run["file"] = i < r.files.size() ? nlohmann::json(r.files[i]) : nlohmann::json(nullptr);
    j["runs"].push_back(run);
  }
  return j;
}

namespace {

template <class Result, class Evaluate>
RunEvaluation<Result> evaluateRun(const MachineSetup& setup, const std::string& file, MeasurementRun run, Evaluate&& evaluate) {
  RunEvaluation<Result> e{setup.machine, file, std::move(run), {}};
  try {
    e.result = evaluate(e.run);
  } catch (const InvalidInput& reason) {
    throw InputError(InputLocation{file, 0, ""}, reason.what());
  }
  return e;
}

CircularEvaluation evaluateBallbarRun(const MachineSetup& setup, const std::string& file, MeasurementRun run) {
  return evaluateRun<CircularTestResult>(setup, file, std::move(run), [](const MeasurementRun& r) { return evaluateCircularTest(r); });
}

RTestRunEvaluation evaluateRTestRun(const MachineSetup& setup, const std::string& file, MeasurementRun run) {
  const auto nominal = setup.nominal();
  return evaluateRun<RTestEvaluation>(setup, file, std::move(run), [&](const MeasurementRun& r) { return evaluateRTest(nominal, r); });
}

}  // namespace

MeasurementRun readMeasurementFile(const MachineSetup& setup, const std::string& file) { return readMeasurementCsv(setup.nominal(), file); }

CircularEvaluation evaluateBallbarFile(const MachineSetup& setup, const std::string& file) {
  return evaluateBallbarRun(setup, file, readMeasurementCsv(setup.nominal(), file));
}

RTestRunEvaluation evaluateRTestFile(const MachineSetup& setup, const std::string& file) {
  return evaluateRTestRun(setup, file, readMeasurementCsv(setup.nominal(), file));
}

const OptionSchema& evaluationSchema() {
  static const OptionSchema schema{
      "evaluate", {{.key = "data", .kind = OptionKind::Text, .help = "Ballbar or R-test CSV (docs/file-formats.md)", .positional = true}}};
  return schema;
}

std::variant<CircularEvaluation, RTestRunEvaluation> evaluateMeasurementFile(const MachineSetup& setup, const std::string& file) {
  auto run = readMeasurementCsv(setup.nominal(), file);
  if (run.instrument == Instrument::Ballbar) return evaluateBallbarRun(setup, file, std::move(run));
  if (run.instrument == Instrument::RTest) return evaluateRTestRun(setup, file, std::move(run));
  throw InputError(InputLocation{file, 0, "instrument"},
                   "evaluate takes a ballbar or an R-test run, not a " + instrumentName(run.instrument) + " run");
}

nlohmann::json toJson(const RTestRunEvaluation& e) {
  const Machine& m = *e.machine;
  const auto& r = e.result;
  const Axis& axis = m.axes[static_cast<size_t>(r.movingAxis)];
  const double unit = axis.isRotary() ? 1.0 / kDeg : 1.0;
  nlohmann::json j = runJson(m, e.run);
  j["file"] = e.file;
  j["moving_axis"] = axis.name;
  j["position"] = std::vector<double>(r.position.data(), r.position.data() + r.position.size());
  for (auto& v : j["position"]) v = v.get<double>() * unit;
  j["position_unit"] = axis.isRotary() ? "deg" : "mm";
  j["range_um"] = vectorJson(r.range * 1e3);
  j["about_the_axis"] = nullptr;
  if (r.aboutTheAxis) {
    const auto& a = *r.aboutTheAxis;
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index i = 0; i < a.components.rows(); ++i)
      rows.push_back({a.components(i, 0) * 1e3, a.components(i, 1) * 1e3, a.components(i, 2) * 1e3});
    j["about_the_axis"] = {{"point_mm", vectorJson(a.point)},
                           {"direction", vectorJson(a.direction)},
                           {"radius_mm", a.radius},
                           {"radial_axial_tangential_um", rows},
                           {"range_um", {{"radial", a.range.x() * 1e3}, {"axial", a.range.y() * 1e3}, {"tangential", a.range.z() * 1e3}}}};
  }
  return j;
}

nlohmann::json toJson(const CircularEvaluation& e) {
  const auto& r = e.result;
  const auto& g = r.diagnostics;
  nlohmann::json j = runJson(*e.machine, e.run);
  j["file"] = e.file;
  j["eccentricity_um"] = vectorJson(r.eccentricity.eccentricity * 1e3);
  j["eccentricity_plot_um"] = {r.eccentricity.e1 * 1e3, r.eccentricity.e2 * 1e3};
  j["offset_um"] = r.eccentricity.offset * 1e3;
  j["directions"] = nlohmann::json::array();
  for (const auto& d : r.directions)
    j["directions"].push_back({{"sense", d.sense > 0 ? "ccw" : "cw"},
                               {"circular_deviation_um", d.circularDeviation * 1e3},
                               {"radial_deviation_min_um", d.radialMin * 1e3},
                               {"radial_deviation_max_um", d.radialMax * 1e3}});
  j["hysteresis_um"] = r.bothDirections ? nlohmann::json(r.hysteresis * 1e3) : nlohmann::json(nullptr);
  j["diagnostics"] = {{"squareness_urad", g.squareness * 1e6},
                      {"scale_mismatch_um_per_m", g.scaleMismatch * 1e6},
                      {"servo_mismatch_ms", r.bothDirections ? nlohmann::json(g.servoMismatch * 1e3) : nlohmann::json(nullptr)},
                      {"backlash_a_um", g.backlashA * 1e3},
                      {"backlash_b_um", g.backlashB * 1e3},
                      {"reversal_spike_a_um", g.reversalSpikeA * 1e3},
                      {"reversal_spike_b_um", g.reversalSpikeB * 1e3},
                      {"residual_rms_um", g.residualRms * 1e3}};
  return j;
}

}  // namespace mtacc
