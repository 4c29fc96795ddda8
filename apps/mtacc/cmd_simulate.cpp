// mtacc simulate ballbar | rtest | plan (component, plate and motion in cmd_simulate_*.cpp):
// measurement data of a machine with errors, written in the same CSV format as measured data
// (docs/file-formats.md), so both take the same path.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/workflows/simulation_options.hpp"

namespace mtacc::cli {
namespace {

struct SimulateCliOptions : MachineOptions {
  OptionValues values;  // the subcommand's schema's
};

void report(const SimulateCliOptions& o, const SimulationResult& r) {
  if (o.json) {
    std::cout << toJson(r).dump(2) << "\n";
    return;
  }
  for (size_t i = 0; i < r.runs.size(); ++i)
    std::cout << fmt::format("{:<24} {:<12} {:>6} poses  -> {}\n", r.runs[i].name, instrumentName(r.runs[i].instrument),
                             r.runs[i].poses(), r.files[i]);
}

// A simulation's command: the machine, its errors and --json, then the workflow's schema, whose
// output the command must be given (Python may leave it out and keep the result alone).
void addSimulation(const CommandLine& simulate, const char* name, const char* help, const OptionSchema& schema,
                   SimulationResult (*run)(const MachineSetup&, const OptionValues&)) {
  auto o = std::make_shared<SimulateCliOptions>();
  auto cmd = simulate.subcommand(name, help);
  cmd.argument("machine", o->source.machine, "Machine file or bundled name");
  cmd.option("--errors", o->source.errorsFile, "Error description (YAML); default: the machine file's errors");
  cmd.flag("--json", o->json, "Summary as JSON on stdout");
  cmd.schemaOptions(schema, o->values, {{"output", "-o"}});
  cmd.requireOption("--output");
  cmd.callback([o, run] { report(*o, run(loadMachineSetup(o->source), o->values)); });
}

}  // namespace

void addSimulateCommand(const CommandLine& app) {
  auto sim = app.subcommand("simulate", "Simulated measurement data (ballbar, R-test, a whole test plan)");
  sim.requireSubcommand();
  addSimulation(sim, "ballbar", "ISO 230-4 ballbar circle, both directions, with optional servo, backlash and reversal-spike disturbances",
                ballbarSimulationSchema(), simulateBallbar);
  addSimulation(sim, "rtest", "R-test (or touch probe) on a sphere while one rotary axis steps", rtestSimulationSchema(), simulateRTest);
  addSimulateArtefactCommands(sim);
  addSimulateMotionCommand(sim);
  addSimulation(sim, "plan", "Every run of a test plan, one CSV per run in a directory", planSimulationSchema(), simulatePlanRuns);
}

}  // namespace mtacc::cli
