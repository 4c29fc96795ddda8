// mtacc simulate component | plate | artefact: direct measurements of one component error (the 1991 BCR report's levels,
// laser and straightedge runs) and a hole-plate measurement, as the machine with its errors
// gives them, in the formats `fit` and `plate` read.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/artefacts.hpp"
#include "mtacc/workflows/plates.hpp"

namespace mtacc::cli {
namespace {

struct ArtefactCliOptions : MachineOptions {
  OptionValues values;
};

CommandLine addArtefactCommand(const CommandLine& simulate, const char* name, const char* help, const OptionSchema& schema, ArtefactCliOptions& o) {
  auto cmd = simulate.subcommand(name, help);
  cmd.argument("machine", o.source.machine, "machine file, or the name of a bundled machine");
  cmd.option("--errors", o.source.errorsFile, "errors file; default: the machine file's");
  cmd.schemaOptions(schema, o.values, {{"output", "-o"}});
  return cmd;
}

}  // namespace

void addSimulateArtefactCommands(const CommandLine& simulate) {
  auto component = std::make_shared<ArtefactCliOptions>();
  auto comp = addArtefactCommand(simulate, "component",
                                  "Direct-measurement runs of one component error (the 1991 BCR report), forward and backward",
                                  componentSimulationSchema(), *component);
  comp.flag("--json", component->json, "the file written, its positions and runs as JSON");
  comp.callback([component] {
    const ComponentSimulationRequest request = componentSimulationRequest(component->values);
    const auto f = simulateComponentFile(loadMachineSetup(component->source), request);
    if (component->json)
      std::cout << nlohmann::json{{"output", request.output}, {"component", request.component}, {"positions", f.runs.positions.size()},
                                  {"runs_each_way", f.runs.forward.cols()}}.dump(2) << "\n";
    else
      std::cout << fmt::format("{}: {} positions x {} runs each way -> {}\n", request.component, f.runs.positions.size(),
                               f.runs.forward.cols(), request.output);
  });

  auto plate = std::make_shared<ArtefactCliOptions>();
  auto cmd = addArtefactCommand(simulate, "plate",
                                 "A hole-plate measurement (the 1991 BCR report): each feature as the machine with its errors measures it",
                                 plateSimulationSchema(), *plate);
  cmd.flag("--json", plate->json, "the file written and its number of features as JSON");
  cmd.callback([plate] {
    const PlateSimulationRequest request = plateSimulationRequest(plate->values);
    const auto m = simulatePlateFile(loadMachineSetup(plate->source), request);
    if (plate->json) std::cout << nlohmann::json{{"output", request.output}, {"features", m.features.size()}}.dump(2) << "\n";
    else std::cout << fmt::format("{} features -> {}\n", m.features.size(), request.output);
  });

  auto artefact = std::make_shared<ArtefactCliOptions>();
  auto art = addArtefactCommand(simulate, "artefact",
                                "A calibrated artefact's measurement: each feature of a layout file probed on the machine with its errors",
                                artefactSimulationSchema(), *artefact);
  art.flag("--json", artefact->json, "the file written and its number of features as JSON");
  art.callback([artefact] {
    const ArtefactSimulationRequest request = artefactSimulationRequest(artefact->values);
    const auto m = simulateArtefactFile(loadMachineSetup(artefact->source), request);
    if (artefact->json) std::cout << nlohmann::json{{"output", request.output}, {"features", m.artefact.features.size()}}.dump(2) << "\n";
    else std::cout << fmt::format("{} features -> {}\n", m.artefact.features.size(), request.output);
  });
}

}  // namespace mtacc::cli
