// mtacc: the command-line front end. One subcommand per workflow; errors end in one line on
// stderr and a non-zero exit, and no output file is left behind.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <string>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/version.hpp"

namespace {

CLI::App* invokedCommand(CLI::App& app) {
  CLI::App* command = &app;
  while (!command->get_subcommands().empty()) command = command->get_subcommands().front();
  return command;
}

// A problem with a command-line value comes back from the library with the workflow's key
// ("radius", "monte_carlo"), or with the file as a whole ("no such file"); shown with the
// name of the option or argument that gave it.
std::string describe(const mtacc::InputError& e, CLI::App* command) {
  const auto& where = e.where();
  if (!where.file.empty() && where.line == 0 && where.key.empty()) {  // a file as a whole: named by its option
    for (const auto* option : command->get_options()) {
      const auto& given = option->results();
      if (std::find(given.begin(), given.end(), where.file) != given.end())
        return (option->get_lnames().empty() ? option->get_name() : "--" + option->get_lnames().front()) + ": " + e.what();
    }
  }
  if (!where.file.empty() || where.line > 0 || where.key.empty() || where.key.rfind("--", 0) == 0) return e.what();
  const std::string key = where.key.substr(0, where.key.find_first_of(" .["));
  std::string option = key == "parameters" ? "params" : key;
  for (auto& c : option)
    if (c == '_') c = '-';
  if (command->get_option_no_throw("--" + option) == nullptr) return e.what();
  return "--" + option + std::string(e.what()).substr(key.size());
}

// CLI11 reports on two lines; mtacc's promise is one.
int parseFailure(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help
  std::string message = e.what();
  if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
    message = fmt::format("'{}' is not a subcommand; the subcommands are:", argv[1]);
    for (const auto* sub : app.get_subcommands({})) message += " " + sub->get_name();
  }
  std::string help = "mtacc";
  for (CLI::App* c = &app; !c->get_subcommands().empty();) {
    c = c->get_subcommands().front();
    help += " " + c->get_name();
  }
  std::cerr << "mtacc: error: " << message << " (" << help << " --help)\n";
  return e.get_exit_code();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mtacc: geometric accuracy of multi-axis machine tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("mtacc ") + mtacc::version());
  mtacc::cli::CommandLine commands(app);
  mtacc::cli::addCheckCommand(commands);
  mtacc::cli::addForwardCommands(commands);
  mtacc::cli::addInverseCommand(commands);
  mtacc::cli::addSensitivityCommand(commands);
  mtacc::cli::addBudgetCommand(commands);
  mtacc::cli::addConeCommand(commands);
  mtacc::cli::addCubicCommands(commands);
  mtacc::cli::addSimulateCommand(commands);
  mtacc::cli::addEvaluateCommand(commands);
  mtacc::cli::addPositioningCommand(commands);
  mtacc::cli::addRotaryTestsCommand(commands);
  mtacc::cli::addAcceptanceCommand(commands);
  mtacc::cli::addDesignCommand(commands);
  mtacc::cli::addFitCommand(commands);
  mtacc::cli::addDirectProcedureCommands(commands);
  mtacc::cli::addMultitaskingCommand(commands);
  mtacc::cli::addPlateCommand(commands);
  mtacc::cli::addStiffnessCommand(commands);
  mtacc::cli::addCompensateCommand(commands);
  mtacc::cli::addDeviationCommand(commands);
  mtacc::cli::addIdentifyCommands(commands);
  mtacc::cli::addDynamicsCommand(commands);
  mtacc::cli::addDecomposeCommand(commands);
  mtacc::cli::addDriftCommand(commands);
  mtacc::cli::addReportCommand(commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parseFailure(app, e, argc, argv);
  } catch (const mtacc::cli::StrictFailure&) {
    return 4;
  } catch (const mtacc::InputError& e) {
    std::cerr << "mtacc: error: " << describe(e, invokedCommand(app)) << "\n";
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
