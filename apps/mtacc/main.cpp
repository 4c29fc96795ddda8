// mtacc: the command-line front end. One subcommand per workflow; errors end in one line on
// stderr and a non-zero exit, and no output file is left behind.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mtacc: geometric accuracy of multi-axis machine tools"};
  app.require_subcommand(1);
  mtacc::cli::addCheckCommand(app);
  mtacc::cli::addForwardCommands(app);
  mtacc::cli::addInverseCommand(app);
  mtacc::cli::addSensitivityCommand(app);
  mtacc::cli::addBudgetCommand(app);
  mtacc::cli::addConeCommand(app);
  mtacc::cli::addSimulateCommand(app);
  mtacc::cli::addEvaluateCommand(app);
  mtacc::cli::addIdentifyCommands(app);
  mtacc::cli::addDynamicsCommand(app);
  mtacc::cli::addReportCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const mtacc::InputError& e) {
    std::cerr << "mtacc: error: " << e.what() << "\n";
    return 2;
  } catch (const mtacc::UnreachablePose& e) {
    std::cerr << "mtacc: error: unreachable pose: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "mtacc: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
