// mtacc simulate component | plate: direct measurements of one component error (the 1991 BCR report's levels,
// laser and straightedge runs) and a hole-plate measurement, as the machine with its errors
// gives them, in the formats `fit` and `plate` read.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/plates.hpp"

namespace mtacc::cli {
namespace {

struct PlateSimulateOptions {
  MachineSource machine;
  PlateSimulationRequest request;
  bool json = false;
};

}  // namespace

void addSimulateArtefactCommands(CLI::App& simulate) {
  auto component = std::make_shared<ComponentSimulationRequest>();
  auto componentMachine = std::make_shared<MachineSource>();
  auto abbe = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto* comp = simulate.add_subcommand("component", "Direct-measurement runs of one component error (the 1991 BCR report), forward and backward");
  comp->add_option("machine", componentMachine->machine, "machine file, or the name of a bundled machine")->required();
  comp->add_option("--errors", componentMachine->errorsFile, "errors file; default: the machine file's");
  comp->add_option("--component", component->component, "component error: the 1991 BCR report name (xrx, ztz, ...) or ISO (EAX, EZZ)")->required();
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
  comp->add_flag("--json", *json, "the file written, its positions and runs as JSON");
  comp->callback([component, componentMachine, abbe, json] {
    if (!abbe->empty()) component->abbeOffset = parseLengths(*abbe, "--abbe-offset");
    const auto f = simulateComponentFile(loadMachineSetup(*componentMachine), *component);
    if (*json)
      std::cout << nlohmann::json{{"output", component->output}, {"component", component->component}, {"positions", f.runs.positions.size()},
                                  {"runs_each_way", f.runs.forward.cols()}}.dump(2) << "\n";
    else
      std::cout << fmt::format("{}: {} positions x {} runs each way -> {}\n", component->component, f.runs.positions.size(),
                               f.runs.forward.cols(), component->output);
  });

  auto plateOptions = std::make_shared<PlateSimulateOptions>();
  auto* plate = simulate.add_subcommand("plate", "A hole-plate measurement (the 1991 BCR report): each feature as the machine with its errors measures it");
  plate->add_option("machine", plateOptions->machine.machine, "machine file, or the name of a bundled machine")->required();
  plate->add_option("--errors", plateOptions->machine.errorsFile, "errors file; default: the machine file's");
  plate->add_option("--origin", plateOptions->request.layout.origin, "reference feature in the workpiece frame, e.g. -350,-455,-160mm")->required();
  plate->add_option("--axes", plateOptions->request.layout.axes, "plate u and v axes in the workpiece frame (default '1,0,0 / 0,1,0')");
  plate->add_option("--stylus", plateOptions->request.layout.stylus, "probe tip relative to the TCP, tool frame (default 0,0,0 mm)");
  plate->add_option("--plate", plateOptions->request.layout.plate, "plate layout (default '9 x 9, pitch 50 mm')");
  plate->add_option("--features", plateOptions->request.layout.features, "all (default) or outer");
  plate->add_option("--pose", plateOptions->request.layout.pose, "positions of the axes that stay, e.g. B=0,C=0");
  plate->add_option("--probe", plateOptions->request.layout.probe, "2S of the probe along u and v to state in the file, e.g. '1.1, 0.8 um'");
  plate->add_option("--simulation", plateOptions->request.layout.simulation, "2S of the model's prediction to state in the file, e.g. '6.3 um'");
  plate->add_option("--noise", plateOptions->request.noise, "standard deviation of each measured coordinate (default 0 um)");
  plate->add_option("--seed", plateOptions->request.seed, "random seed (default 1)");
  plate->add_option("-o,--output", plateOptions->request.output, "CSV to write (atomically)")->required();
  plate->add_flag("--json", plateOptions->json, "the file written and its number of features as JSON");
  plate->callback([plateOptions] {
    const auto& o = *plateOptions;
    const auto m = simulatePlateFile(loadMachineSetup(o.machine), o.request);
    if (o.json) std::cout << nlohmann::json{{"output", o.request.output}, {"features", m.features.size()}}.dump(2) << "\n";
    else std::cout << fmt::format("{} features -> {}\n", m.features.size(), o.request.output);
  });
}

}  // namespace mtacc::cli
