// mtacc simulate ballbar | rtest | plan: measurement data of a machine with errors, written in
// the same CSV format as measured data (docs/file-formats.md), so both take the same path.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <random>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/atomic_file.hpp"
#include "mtacc/measurement/measurement_csv.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/test_paths.hpp"
#include "mtacc/measurement/test_plan.hpp"

namespace mtacc::cli {
namespace {

struct SimulateOptions : MachineOptions {
  std::string noise = "0 um";
  unsigned seed = 1;
  std::string setupErrors;  // "xW=10um,zT=-5um"
  std::string pose;
  std::string toolBall = "0,0,0";
  // ballbar
  std::string plane = "XY", centre = "0,0,0", radius = "100 mm";
  int points = 360;
  double feed = 1000;
  bool oneDirection = false;
  std::string lag, backlash, spike;
  double spikeTime = 0.02;
  // rtest
  std::string axis = "C", from = "0 deg", to = "330 deg", sphere;
  int angles = 12;
  bool probe = false;
  // plan
  std::string plan;
};

// "X=1ms,Y=0.5ms" -> per commanded axis, scaled by `unit` after the number's own unit.
std::vector<double> perAxis(const Machine& m, const std::string& text, const std::string& what, bool time) {
  std::vector<double> out;
  if (text.empty()) return out;
  out.assign(static_cast<size_t>(m.commandedCount()), 0.0);
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    const int j = eq == std::string::npos ? -1 : m.axisIndex(item.substr(0, eq));
    if (j < 0) throw InputError(InputLocation{"", 0, what}, "expected AXIS=value, got '" + item + "'");
    const std::string value = item.substr(eq + 1);
    if (time) {
      const bool ms = value.size() > 2 && value.compare(value.size() - 2, 2, "ms") == 0;
      const bool s = !ms && value.size() > 1 && value.back() == 's';
      if (!ms && !s) throw InputError(InputLocation{"", 0, what}, "expected a time in s or ms, got '" + value + "'");
      try {
        out[static_cast<size_t>(j)] = std::stod(value.substr(0, value.size() - (ms ? 2 : 1))) * (ms ? 1e-3 : 1.0);
      } catch (const std::logic_error&) {
        throw InputError(InputLocation{"", 0, what}, "not a number: '" + value + "'");
      }
    } else {
      const bool rotary = m.axes[static_cast<size_t>(j)].isRotary();
      out[static_cast<size_t>(j)] = parseQuantityArg(value, rotary ? Dimension::Angle : Dimension::Length, what);
    }
  }
  return out;
}

void applySetupErrors(MeasurementRun& run, const std::string& text) {
  if (text.empty()) return;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    const auto p = eq == std::string::npos ? std::nullopt : parseSetupParameter(item.substr(0, eq));
    if (!p) throw InputError(InputLocation{"", 0, "--setup"}, "expected NAME=value with NAME one of xT yT zT xW yW zW aN bN cN dL, got '" + item + "'");
    if (appliesTo(*p, run.instrument))
      run.setup.errors[static_cast<size_t>(*p)] = parseQuantityArg(item.substr(eq + 1), setupParameterDimension(*p), "--setup");
  }
}

void writeRuns(const SimulateOptions& o, const Loaded& loaded, std::vector<MeasurementRun> runs, const Disturbance& d,
               bool directory) {
  const Machine& m = *loaded.machine;
  const auto nominal = compileNominal(loaded.machine);
  const auto model = compile(loaded.machine, loaded.errors);
  const double noise = parseQuantityArg(o.noise, Dimension::Length, "--noise");
  if (noise < 0) throw InputError(InputLocation{"", 0, "--noise"}, "must not be negative");
  std::mt19937_64 rng(o.seed);
  nlohmann::json j;
  j["machine"] = m.name;
  j["noise_um"] = noise * 1e3;
  std::vector<std::pair<std::string, std::string>> files;
  std::string human;
  for (auto& run : runs) {
    applySetupErrors(run, o.setupErrors);
    simulateRun(model, nominal, run, d, noise, &rng);
    const std::string path = directory ? (std::filesystem::path(o.output) / (run.name + ".csv")).string() : o.output;
    files.emplace_back(path, measurementCsv(m, run));
    human += fmt::format("{:<24} {:<12} {:>6} poses  -> {}\n", run.name, instrumentName(run.instrument), run.poses(), path);
    j["runs"].push_back({{"name", run.name}, {"instrument", instrumentName(run.instrument)}, {"poses", run.poses()}, {"file", path}});
  }
  // Everything is computed before anything is written.
  if (directory) std::filesystem::create_directories(o.output);
  for (const auto& [path, text] : files) writeFileAtomically(path, text);
  if (o.json) std::cout << j.dump(2) << "\n";
  else std::cout << human;
}

void addCommon(CLI::App* cmd, SimulateOptions& o) {
  cmd->add_option("machine", o.machine, "Machine file or bundled name")->required();
  cmd->add_option("--errors", o.errorsFile, "Error description (YAML); default: the machine file's errors");
  cmd->add_flag("--json", o.json, "Summary as JSON on stdout");
  cmd->add_option("--noise", o.noise, "Standard deviation of Gaussian reading noise, e.g. 0.5um")->capture_default_str();
  cmd->add_option("--seed", o.seed, "Random seed of the noise")->capture_default_str();
  cmd->add_option("--setup", o.setupErrors, "Set-up errors, e.g. xW=10um,zT=-5um (xT yT zT xW yW zW aN bN cN dL)");
  cmd->add_option("--tool-ball", o.toolBall, "Ball centre relative to the TCP in the tool frame, mm, e.g. 0,0,-50")
      ->capture_default_str();
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto* sim = app.add_subcommand("simulate", "Simulated measurement data (ballbar, R-test, a whole test plan)");
  sim->require_subcommand(1);
  auto o = std::make_shared<SimulateOptions>();

  auto* ballbar = sim->add_subcommand("ballbar", "ISO 230-4 ballbar circle, both directions, with optional servo, "
                                                 "backlash and reversal-spike disturbances");
  addCommon(ballbar, *o);
  ballbar->add_option("--plane", o->plane, "XY, YZ or ZX")->capture_default_str();
  ballbar->add_option("--centre", o->centre, "Centre ball in the workpiece frame, mm")->capture_default_str();
  ballbar->add_option("--radius", o->radius, "Bar length")->capture_default_str();
  ballbar->add_option("--points", o->points, "Points per direction")->capture_default_str();
  ballbar->add_option("--feed", o->feed, "Feed, mm/min")->capture_default_str();
  ballbar->add_option("--pose", o->pose, "The other axes, e.g. B=-30 (deg, mm; others 0)");
  ballbar->add_flag("--one-direction", o->oneDirection, "Counter-clockwise only");
  ballbar->add_option("--lag", o->lag, "Following error per axis (1/kv), e.g. X=1ms");
  ballbar->add_option("--backlash", o->backlash, "Lost motion per axis, e.g. X=5um");
  ballbar->add_option("--spike", o->spike, "Reversal spike height per axis, e.g. Y=4um");
  ballbar->add_option("--spike-time", o->spikeTime, "Decay time of the reversal spikes, s")->capture_default_str();
  ballbar->add_option("-o,--output", o->output, "CSV file to write")->required();
  ballbar->callback([o] {
    const auto loaded = load(*o);
    const auto nominal = compileNominal(loaded.machine);
    BallbarCircleSpec spec;
    spec.plane = o->plane;
    spec.centre = parseVector(o->centre, "--centre");
    spec.radius = parseQuantityArg(o->radius, Dimension::Length, "--radius");
    if (!(spec.radius > 0)) throw InputError(InputLocation{"", 0, "--radius"}, "must be positive");
    spec.points = o->points;
    spec.feed = o->feed;
    if (!(spec.feed > 0)) throw InputError(InputLocation{"", 0, "--feed"}, "must be positive");
    spec.bothDirections = !o->oneDirection;
    spec.toolBall = parseVector(o->toolBall, "--tool-ball");
    if (!o->pose.empty()) spec.pose = parsePose(*loaded.machine, o->pose, true);
    Disturbance d;
    d.lag = perAxis(*loaded.machine, o->lag, "--lag", true);
    d.backlash = perAxis(*loaded.machine, o->backlash, "--backlash", false);
    d.spikeHeight = perAxis(*loaded.machine, o->spike, "--spike", false);
    d.spikeTime = o->spikeTime;
    MeasurementRun run;
    try {
      run = ballbarCircle(nominal, spec);
    } catch (const std::invalid_argument& e) {
      throw InputError(InputLocation{"", 0, "ballbar"}, e.what());
    }
    writeRuns(*o, loaded, {run}, d, false);
  });

  auto* rtest = sim->add_subcommand("rtest", "R-test (or touch probe) on a sphere while one rotary axis steps");
  addCommon(rtest, *o);
  rtest->add_option("--axis", o->axis, "Rotary axis that steps")->capture_default_str();
  rtest->add_option("--from", o->from, "First angle")->capture_default_str();
  rtest->add_option("--to", o->to, "Last angle")->capture_default_str();
  rtest->add_option("--points", o->angles, "Number of angles")->capture_default_str();
  rtest->add_option("--sphere", o->sphere, "Sphere centre in the workpiece frame, mm")->required();
  rtest->add_option("--pose", o->pose, "The other axes, e.g. B=-30 (deg, mm; others 0)");
  rtest->add_flag("--probe", o->probe, "Touch-probe readings instead of the R-test's");
  rtest->add_option("-o,--output", o->output, "CSV file to write")->required();
  rtest->callback([o] {
    const auto loaded = load(*o);
    const auto nominal = compileNominal(loaded.machine);
    SphereTestSpec spec;
    spec.instrument = o->probe ? Instrument::TouchProbe : Instrument::RTest;
    spec.axis = o->axis;
    const double from = parseQuantityArg(o->from, Dimension::Angle, "--from");
    const double to = parseQuantityArg(o->to, Dimension::Angle, "--to");
    const int n = o->angles;
    if (n < 1) throw InputError(InputLocation{"", 0, "--points"}, "must be at least 1");
    for (int i = 0; i < n; ++i) spec.angles.push_back(n == 1 ? from : from + (to - from) * i / (n - 1));
    spec.spheres = {parseVector(o->sphere, "--sphere")};
    spec.toolBall = parseVector(o->toolBall, "--tool-ball");
    if (!o->pose.empty()) spec.pose = parsePose(*loaded.machine, o->pose, true);
    std::vector<MeasurementRun> runs;
    try {
      runs = sphereTest(nominal, spec);
    } catch (const std::invalid_argument& e) {
      throw InputError(InputLocation{"", 0, "rtest"}, e.what());
    }
    writeRuns(*o, loaded, runs, {}, false);
  });

  auto* plan = sim->add_subcommand("plan", "Every run of a test plan, one CSV per run in a directory");
  addCommon(plan, *o);
  plan->add_option("--plan", o->plan, "Test plan (YAML) or bundled plan name")->required();
  plan->add_option("-o,--output", o->output, "Directory to write the CSV files into")->required();
  plan->callback([o] {
    const auto loaded = load(*o);
    const auto nominal = compileNominal(loaded.machine);
    writeRuns(*o, loaded, loadTestPlan(nominal, o->plan).runs, {}, true);
  });
}

}  // namespace mtacc::cli
