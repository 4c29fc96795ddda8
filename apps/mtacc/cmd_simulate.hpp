#pragma once
// The subcommands of `mtacc simulate`, by what they simulate.
#include "command_line.hpp"

namespace mtacc::cli {

void addSimulateArtefactCommands(const CommandLine& simulate);  // simulate component | plate
void addSimulateMotionCommand(const CommandLine& simulate);     // simulate motion

}  // namespace mtacc::cli
