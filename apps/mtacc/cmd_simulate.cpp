// mtacc simulate ballbar | rtest | plan (component, plate and motion in cmd_simulate_*.cpp):
// measurement data of a machine with errors, written in the same CSV format as measured data
// (docs/file-formats.md), so both take the same path.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/measurement_runs.hpp"

namespace mtacc::cli {
namespace {

struct SimulateCliOptions : MachineOptions {
  std::string noise = "0 um", setupErrors, pose, toolBall = "0,0,0";
  std::uint64_t seed = 1;
  // ballbar
  std::string plane = "XY", centre = "0,0,0", radius = "100 mm", lag, backlash, spike;
  int points = 360;
  double feed = 1000, spikeTime = 0.02;
  bool oneDirection = false;
  // rtest
  std::string axis = "C", from = "0 deg", to = "330 deg", sphere;
  int angles = 12;
  bool probe = false;
  // plan
  std::string plan;
};

SimulationOptions simulationOptions(const SimulateCliOptions& o, const Machine& m, bool folder) {
  SimulationOptions s;
  s.noise = parseQuantityAs(o.noise, Dimension::Length, "--noise");
  s.seed = o.seed;
  s.setupErrors = parseSetupErrors(o.setupErrors, "--setup");
  s.disturbance = disturbanceFromText(m, o.lag, o.backlash, o.spike, o.spikeTime);
  s.output = o.output;
  s.outputIsFolder = folder;
  return s;
}

void report(const SimulateCliOptions& o, const SimulationResult& r) {
  if (o.json) {
    std::cout << toJson(r).dump(2) << "\n";
    return;
  }
  for (size_t i = 0; i < r.runs.size(); ++i)
    std::cout << fmt::format("{:<24} {:<12} {:>6} poses  -> {}\n", r.runs[i].name, instrumentName(r.runs[i].instrument),
                             r.runs[i].poses(), r.files[i]);
}

void addCommon(CLI::App* cmd, SimulateCliOptions& o) {
  cmd->add_option("machine", o.source.machine, "Machine file or bundled name")->required();
  cmd->add_option("--errors", o.source.errorsFile, "Error description (YAML); default: the machine file's errors");
  cmd->add_flag("--json", o.json, "Summary as JSON on stdout");
  cmd->add_option("--noise", o.noise, "Standard deviation of Gaussian reading noise, e.g. 0.5um")->capture_default_str();
  cmd->add_option("--seed", o.seed, "Random seed of the noise")->capture_default_str();
  cmd->add_option("--setup", o.setupErrors, "Set-up errors, e.g. xW=10um,zT=-5um (xT yT zT xW yW zW aN bN cN dL)");
}

// Single runs only: a plan states each run's ball as its `tool_ball`.
void addToolBall(CLI::App* cmd, SimulateCliOptions& o) {
  cmd->add_option("--tool-ball", o.toolBall, "Ball centre relative to the TCP in the tool frame, mm, e.g. 0,0,-50")
      ->capture_default_str();
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto* sim = app.add_subcommand("simulate", "Simulated measurement data (ballbar, R-test, a whole test plan)");
  sim->require_subcommand(1);
  auto o = std::make_shared<SimulateCliOptions>();

  auto* ballbar = sim->add_subcommand("ballbar", "ISO 230-4 ballbar circle, both directions, with optional servo, "
                                                 "backlash and reversal-spike disturbances");
  addCommon(ballbar, *o);
  addToolBall(ballbar, *o);
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
    const auto setup = loadMachineSetup(o->source);
    BallbarCircleSpec spec;
    spec.plane = o->plane;
    spec.centre = parseVector(o->centre, "--centre");
    spec.radius = parseQuantityAs(o->radius, Dimension::Length, "--radius");
    spec.points = o->points;
    spec.feed = o->feed;
    spec.bothDirections = !o->oneDirection;
    spec.toolBall = parseVector(o->toolBall, "--tool-ball");
    if (!o->pose.empty()) spec.pose = poseFromText(setup, o->pose, "--pose", true);
    report(*o, simulateBallbarCircle(setup, spec, simulationOptions(*o, *setup.machine, false)));
  });

  auto* rtest = sim->add_subcommand("rtest", "R-test (or touch probe) on a sphere while one rotary axis steps");
  addCommon(rtest, *o);
  addToolBall(rtest, *o);
  rtest->add_option("--axis", o->axis, "Rotary axis that steps")->capture_default_str();
  rtest->add_option("--from", o->from, "First angle")->capture_default_str();
  rtest->add_option("--to", o->to, "Last angle")->capture_default_str();
  rtest->add_option("--points", o->angles, "Number of angles")->capture_default_str();
  rtest->add_option("--sphere", o->sphere, "Sphere centre in the workpiece frame, mm")->required();
  rtest->add_option("--pose", o->pose, "The other axes, e.g. B=-30 (deg, mm; others 0)");
  rtest->add_flag("--probe", o->probe, "Touch-probe readings instead of the R-test's");
  rtest->add_option("-o,--output", o->output, "CSV file to write")->required();
  rtest->callback([o] {
    const auto setup = loadMachineSetup(o->source);
    SphereTestSpec spec;
    spec.instrument = o->probe ? Instrument::TouchProbe : Instrument::RTest;
    spec.axis = o->axis;
    if (o->angles < 1 || o->angles > kMaxPointsPerRun)
      throw InputError(InputLocation{"", 0, "--points"}, fmt::format("must be from 1 to {}", kMaxPointsPerRun));
    spec.angles = evenAngles(parseQuantityAs(o->from, Dimension::Angle, "--from"), parseQuantityAs(o->to, Dimension::Angle, "--to"),
                             o->angles);
    spec.spheres = {parseVector(o->sphere, "--sphere")};
    spec.toolBall = parseVector(o->toolBall, "--tool-ball");
    if (!o->pose.empty()) spec.pose = poseFromText(setup, o->pose, "--pose", true);
    report(*o, simulateSphereTest(setup, spec, simulationOptions(*o, *setup.machine, false)));
  });

  addSimulateArtefactCommands(*sim);
  addSimulateMotionCommand(*sim);

  auto* plan = sim->add_subcommand("plan", "Every run of a test plan, one CSV per run in a directory");
  addCommon(plan, *o);
  plan->add_option("--plan", o->plan, "Test plan (YAML) or bundled plan name")->required();
  plan->add_option("-o,--output", o->output, "Directory to write the CSV files into")->required();
  plan->callback([o] {
    const auto setup = loadMachineSetup(o->source);
    report(*o, simulatePlan(setup, o->plan, simulationOptions(*o, *setup.machine, true)));
  });
}

}  // namespace mtacc::cli
