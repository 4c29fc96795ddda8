#pragma once
// Shared plumbing of the mtacc subcommands: their command line (command_line.hpp) and their
// output (JSON, human tables, CSV). Each command parses its options, calls one workflow of the
// library and formats its result.
#include <nlohmann/json.hpp>

#include <map>
#include <string>

#include "command_line.hpp"
#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc::cli {

// Thrown after a complete result when --strict asks for a failing exit status on warnings
// (already printed): mtacc exits with status 4.
struct StrictFailure {
  size_t warnings;
};

struct MachineOptions {
  MachineSource source;
  bool json = false;
  std::string output;
};

// Replaces this process by /usr/bin/python3 -m MODULE ARGUMENTS with the build's Python package
// first on PYTHONPATH (the report and the acceptance report, which the package builds).
[[noreturn]] void runPythonModule(const std::string& module, const std::vector<std::string>& arguments);

// JSON to stdout (or -o); otherwise the human text to stdout and, with -o, the CSV.
void emit(const MachineOptions& o, const nlohmann::json& json, const std::string& human, const std::string& csv);

// "   10.0000    -15.0000" (mm, deg) and the matching header of axis names.
std::string formatPose(const Machine& m, const double* q);
std::string poseHeader(const Machine& m);
// "10,-15," (mm, deg), and the header "X,B,".
std::string poseCsv(const Machine& m, const double* q);
std::string poseCsvHeader(const Machine& m);

// The estimates, residuals and quality of an identification (human, JSON or CSV), and with
// `errorsOut` the identified errors file written there; warnings on stderr, and StrictFailure
// after them when `strict`.
void emitIdentification(const MachineOptions& o, const IdentificationStudy& out, bool strict, const std::string& errorsOut);
// --errors-out of identify and cubic-identify.
void addErrorsOutOption(const CommandLine& cmd, std::string& errorsOut);

// Registration of each subcommand.
void addCheckCommand(const CommandLine& app);
void addForwardCommands(const CommandLine& app);  // fk, errors
void addInverseCommand(const CommandLine& app);   // ik
void addSensitivityCommand(const CommandLine& app);
void addBudgetCommand(const CommandLine& app);
void addReportCommand(const CommandLine& app);
void addConeCommand(const CommandLine& app);
void addSimulateCommand(const CommandLine& app);       // simulate ballbar | rtest | plan
void addEvaluateCommand(const CommandLine& app);
void addPositioningCommand(const CommandLine& app);    // positioning (ISO 230-2)
void addRotaryTestsCommand(const CommandLine& app);    // rotary-tests (ISO 10791-6)
void addAcceptanceCommand(const CommandLine& app);     // acceptance (tests, uncertainty, tolerances, verdicts)
void addDesignCommand(const CommandLine& app);         // design (the measurement plan)
void addFitCommand(const CommandLine& app);            // fit (seed 003 component fits)
void addPlateCommand(const CommandLine& app);          // plate (seed 003 hole plates)
void addStiffnessCommand(const CommandLine& app);      // stiffness (seed 003 finite stiffness)
void addCompensateCommand(const CommandLine& app);     // compensate (compensated programs)
void addDeviationCommand(const CommandLine& app);      // deviation (a program on a model, against its intended path)
void addIdentifyCommands(const CommandLine& app);      // identify, observability
void addCubicCommands(const CommandLine& app);         // cubic, cubic-identify
void addDynamicsCommand(const CommandLine& app);       // dynamics modes | frf | accel | map
void addDecomposeCommand(const CommandLine& app);      // decompose (seed 004 error decomposition)
void addDriftCommand(const CommandLine& app);          // drift (ISO 230-3 spindle drift test, seed 003 thermal)
void addMultitaskingCommand(const CommandLine& app);   // multitasking (seed 002 closed-form identification)
void addDirectProcedureCommands(const CommandLine& app);  // squareness, yry (seed 003 App. B)

}  // namespace mtacc::cli
