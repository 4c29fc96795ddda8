// mtacc simulate ballbar | rtest | component | plate | plan | motion: measurement data of a machine with errors, written in
// the same CSV format as measured data (docs/file-formats.md), so both take the same path.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/measurement_runs.hpp"
#include "mtacc/workflows/plates.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

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
  // motion
  MotionSimulationRequest motion;
  double clockOffsetMs = 18, jerkTimeMs = 20;
  std::string signalFormat = "csv";
};

SimulationOptions simulationOptions(const SimulateCliOptions& o, const Machine& m, bool folder) {
  SimulationOptions s;
  s.noise = parseQuantityAs(o.noise, Dimension::Length, "--noise");
  s.seed = o.seed;
  s.setupErrors = parseSetupErrors(o.setupErrors, "--setup");
  s.disturbance.lag = parseAxisTimes(m, o.lag, "--lag");
  s.disturbance.backlash = parseAxisQuantities(m, o.backlash, "--backlash");
  s.disturbance.spikeHeight = parseAxisQuantities(m, o.spike, "--spike");
  s.disturbance.spikeTime = o.spikeTime;
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
    if (!o->pose.empty()) spec.pose = parsePose(*setup.machine, o->pose, "--pose", true);
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
    if (!o->pose.empty()) spec.pose = parsePose(*setup.machine, o->pose, "--pose", true);
    report(*o, simulateSphereTest(setup, spec, simulationOptions(*o, *setup.machine, false)));
  });

  auto component = std::make_shared<ComponentSimulationRequest>();
  auto componentMachine = std::make_shared<MachineSource>();
  auto abbe = std::make_shared<std::string>();
  auto* comp = sim->add_subcommand("component", "Direct-measurement runs of one component error (seed 003), forward and backward");
  comp->add_option("machine", componentMachine->machine, "machine file, or the name of a bundled machine")->required();
  comp->add_option("--errors", componentMachine->errorsFile, "errors file; default: the machine file's");
  comp->add_option("--component", component->component, "component error: seed 003 name (xrx, ztz, ...) or ISO (EAX, EZZ)")->required();
  comp->add_option("-o,--output", component->output, "CSV to write (atomically)")->required();
  comp->add_option("--step", component->step, "step between positions over the travel (mm or deg, default 10)");
  comp->add_option("--runs", component->runs, "runs, each forward and backward (default 20)");
  comp->add_option("--noise", component->noise, "standard deviation of one reading, e.g. 0.5arcsec or 0.2um (default 0)");
  comp->add_option("--abbe-offset", *abbe, "measuring point relative to the carriage centroid, e.g. 0,60,110mm (translations)");
  comp->add_option("--instrument", component->instrument, "instrument named in the file (e.g. levels, laser)");
  comp->add_option("--reading-time", component->readingTime, "seconds per reading (default 6)");
  comp->add_option("--disturbance", component->disturbance, "a periodic disturbance of one reading, e.g. 1.5arcsec (the lubrication pump)");
  comp->add_option("--disturbance-interval", component->disturbanceInterval, "seconds between disturbances (default 1800)");
  comp->add_option("--settling", component->settling, "a drift at the start that dies away, e.g. 2arcsec (the machine settling)");
  comp->add_option("--settling-time", component->settlingTime, "seconds: the settling drift's time constant (default 600)");
  comp->add_option("--seed", component->seed, "random seed (default 1)");
  comp->callback([component, componentMachine, abbe] {
    if (!abbe->empty()) component->abbeOffset = parseLengths(*abbe, "--abbe-offset");
    const auto f = simulateComponentFile(loadMachineSetup(*componentMachine), *component);
    std::cout << fmt::format("{}: {} positions x {} runs each way -> {}\n", component->component, f.runs.positions.size(),
                             f.runs.forward.cols(), component->output);
  });

  struct PlateSimulateOptions {
    MachineSource machine;
    PlateSimulationRequest request;
    std::string origin, axes = "1,0,0 / 0,1,0", stylus = "0,0,0 mm", plate = "9 x 9, pitch 50 mm", features = "all", pose, probe, simulation;
  };
  auto plateOptions = std::make_shared<PlateSimulateOptions>();
  auto* plate = sim->add_subcommand("plate", "A hole-plate measurement (seed 003): each feature as the machine with its errors measures it");
  plate->add_option("machine", plateOptions->machine.machine, "machine file, or the name of a bundled machine")->required();
  plate->add_option("--errors", plateOptions->machine.errorsFile, "errors file; default: the machine file's");
  plate->add_option("--origin", plateOptions->origin, "reference feature in the workpiece frame, e.g. -350,-455,-160mm")->required();
  plate->add_option("--axes", plateOptions->axes, "plate u and v axes in the workpiece frame (default '1,0,0 / 0,1,0')");
  plate->add_option("--stylus", plateOptions->stylus, "probe tip relative to the TCP, tool frame (default 0,0,0 mm)");
  plate->add_option("--plate", plateOptions->plate, "plate layout (default '9 x 9, pitch 50 mm')");
  plate->add_option("--features", plateOptions->features, "all (default) or outer");
  plate->add_option("--pose", plateOptions->pose, "positions of the axes that stay, e.g. B=0,C=0");
  plate->add_option("--probe", plateOptions->probe, "2S of the probe along u and v to state in the file, e.g. '1.1, 0.8 um'");
  plate->add_option("--simulation", plateOptions->simulation, "2S of the model's prediction to state in the file, e.g. '6.3 um'");
  plate->add_option("--noise", plateOptions->request.noise, "standard deviation of each measured coordinate (default 0 um)");
  plate->add_option("--seed", plateOptions->request.seed, "random seed (default 1)");
  plate->add_option("-o,--output", plateOptions->request.output, "CSV to write (atomically)")->required();
  plate->callback([plateOptions] {
    auto& o = *plateOptions;
    const auto setup = loadMachineSetup(o.machine);
    // The options are written as the file's header and read back: one parser for both.
    std::string header = "# plate: " + o.plate + "\n# features: " + o.features + "\n# origin: " + o.origin + "\n# axes: " + o.axes +
                         "\n# stylus: " + o.stylus + "\n";
    if (!o.pose.empty()) header += "# pose: " + o.pose + "\n";
    if (!o.probe.empty()) header += "# probe: " + o.probe + "\n";
    if (!o.simulation.empty()) header += "# simulation: " + o.simulation + "\n";
    PlateMeasurement layout;
    try {
      layout = parsePlateLayout(*setup.machine, header, "options");
    } catch (const InputError& e) {
      throw InputError(InputLocation{"", 0, "--" + e.where().key}, e.reason());
    }
    o.request.layout = layout;
    const auto m = simulatePlateFile(setup, o.request);
    std::cout << fmt::format("{} features -> {}\n", m.features.size(), o.request.output);
  });

  auto* motion = sim->add_subcommand("motion", "Seed 004's virtual machine: an NC program run at each feed of a ladder, with servo loops, "
                                                "geometric errors, drift, structural deflection and instrument noise; the recorded signals, "
                                                "the truth and the decomposition set written to a directory");
  motion->add_option("machine", o->source.machine, "Machine file or bundled name")->required();
  motion->add_option("--errors", o->source.errorsFile, "Error description (YAML); default: the machine file's errors");
  motion->add_flag("--json", o->json, "Summary as JSON on stdout");
  motion->add_option("--noise", o->noise, "Standard deviation of the instrument's noise per component, e.g. 0.2um")->capture_default_str();
  motion->add_option("--seed", o->seed, "Random seed of the noise")->capture_default_str();
  motion->add_option("--program", o->motion.program, "NC program (G-code) in axis positions; its F words are replaced by each feed")->required();
  motion->add_option("--feeds", o->motion.feeds, "feeds in mm/min (FGROUP: mm and deg on one path length)")->delimiter(',')->capture_default_str()
      ->check(CLI::Range(1e-3, 1e6));
  motion->add_option("--structure", o->motion.structure, "structure model (YAML or bundled name, e.g. wcayfxzt-compact) for the dynamic error");
  motion->add_option("--acceleration", o->motion.limits.acceleration, "interpolator's acceleration limit, path units/s^2")->capture_default_str()
      ->check(CLI::Range(1e-3, 1e7));
  motion->add_option("--jerk-time-ms", o->jerkTimeMs, "moving-average filter of the interpolator, ms")->capture_default_str()->check(CLI::Range(0.0, 1e3));
  motion->add_option("--kv", o->motion.positionGains, "position loop gain, 1/s: one for every axis or one per axis, e.g. 40,45,50,35,30")
      ->delimiter(',')->capture_default_str()->check(CLI::Range(1e-3, 1e4));
  motion->add_option("--feed-forward", o->motion.feedForwards, "velocity feed-forward, 0..1: one for every axis or one per axis")->delimiter(',')
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  motion->add_option("--format", o->signalFormat, "signal files: csv or npy (NumPy structured arrays)")->capture_default_str();
  motion->add_option("--clock-offset-ms", o->clockOffsetMs, "offset of the command recording's clock, ms")->capture_default_str()
      ->check(CLI::Range(-1e4, 1e4));
  motion->add_option("-o,--output", o->motion.folder, "Directory to write the signal files and set.yaml into")->required();
  motion->callback([o] {
    auto request = o->motion;
    request.noise = parseQuantityAs(o->noise, Dimension::Length, "--noise");
    request.seed = o->seed;
    request.limits.jerkTime = o->jerkTimeMs * 1e-3;
    request.clockOffset = o->clockOffsetMs * 1e-3;
    request.format = signalFormatNamed(o->signalFormat, "--format");
    const auto s = simulateMotion(loadMachineSetup(o->source), request);
    if (o->json) {
      std::cout << toJson(s).dump(2) << "\n";
      return;
    }
    std::cout << fmt::format("ball at ({:.3f}, {:.3f}, {:.3f}) mm; largest |component| of each contribution, um\n", s.ball.x(), s.ball.y(), s.ball.z());
    std::cout << fmt::format("{:>9} {:>8} {:>9} | {:>22} | {:>22} | {:>22}\n", "feed", "time s", "samples", "contouring x y z", "geometric x y z",
                             "dynamic x y z");
    for (const auto& f : s.feeds)
      std::cout << fmt::format("{:>9.0f} {:>8.2f} {:>9} | {:>6.2f} {:>7.2f} {:>7.2f} | {:>6.2f} {:>7.2f} {:>7.2f} | {:>6.2f} {:>7.2f} {:>7.2f}\n", f.feed,
                               f.duration, f.instrumentSamples, f.contouringMax.x() * 1e3, f.contouringMax.y() * 1e3, f.contouringMax.z() * 1e3,
                               f.geometricMax.x() * 1e3, f.geometricMax.y() * 1e3, f.geometricMax.z() * 1e3, f.dynamicMax.x() * 1e3,
                               f.dynamicMax.y() * 1e3, f.dynamicMax.z() * 1e3);
    std::cout << "-> " << s.setFile << " (mtacc decompose MACHINE " << s.setFile << ")\n";
  });

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
