#pragma once
// The subcommands of `mtacc simulate`, by what they simulate.
#include <CLI/CLI.hpp>

namespace mtacc::cli {

void addSimulateArtefactCommands(CLI::App& simulate);  // simulate component | plate
void addSimulateMotionCommand(CLI::App& simulate);     // simulate motion

}  // namespace mtacc::cli
