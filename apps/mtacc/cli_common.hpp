#pragma once
// Shared plumbing of the mtacc subcommands: the options every machine command takes, and the
// output (JSON, human tables, CSV). Each command parses its options, calls one workflow of the
// library and formats its result.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <string>

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

// Adds MACHINE, --errors, --alignment, --load, --json, -o to a subcommand.
void addMachineOptions(CLI::App& cmd, MachineOptions& o);
// A workpiece load in kg, 0 to 1e6 (--load).
CLI::Validator loadInKg();
// Adds a flag --key ('_' written '-') for each key of a workflow's schema, storing what is given
// in `values` for the workflow's reader; `aliases` gives a key further flag names ("--params").
void addSchemaOptions(CLI::App& cmd, const OptionSchema& schema, OptionValues& values,
                      const std::map<std::string, std::string>& aliases = {});
// Adds --json and -o only.
void addOutputOptions(CLI::App& cmd, MachineOptions& o);

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
void addErrorsOutOption(CLI::App& cmd, std::string& errorsOut);

// Registration of each subcommand.
void addCheckCommand(CLI::App& app);
void addForwardCommands(CLI::App& app);  // fk, errors
void addInverseCommand(CLI::App& app);   // ik
void addSensitivityCommand(CLI::App& app);
void addBudgetCommand(CLI::App& app);
void addReportCommand(CLI::App& app);
void addConeCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);       // simulate ballbar | rtest | plan
void addEvaluateCommand(CLI::App& app);
void addPositioningCommand(CLI::App& app);    // positioning (ISO 230-2)
void addFitCommand(CLI::App& app);            // fit (seed 003 component fits)
void addPlateCommand(CLI::App& app);          // plate (seed 003 hole plates)
void addStiffnessCommand(CLI::App& app);      // stiffness (seed 003 finite stiffness)
void addCompensateCommand(CLI::App& app);     // compensate (compensated programs)
void addDeviationCommand(CLI::App& app);      // deviation (a program on a model, against its intended path)
void addIdentifyCommands(CLI::App& app);      // identify, observability
void addCubicCommands(CLI::App& app);         // cubic, cubic-identify
void addDynamicsCommand(CLI::App& app);       // dynamics modes | frf | accel | map
void addDecomposeCommand(CLI::App& app);      // decompose (seed 004 error decomposition)
void addDriftCommand(CLI::App& app);          // drift (ISO 230-3 spindle drift test, seed 003 thermal)

}  // namespace mtacc::cli
