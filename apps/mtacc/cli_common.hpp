#pragma once
// Shared plumbing of the mtacc subcommands: loading, argument parsing, output.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc::cli {

struct MachineOptions {
  std::string machine;
  std::string errorsFile;
  bool json = false;
  std::string output;
  std::string alignment;  // overrides the machine file's workpiece alignment
};

// Adds MACHINE, --errors, --json, -o to a subcommand.
void addMachineOptions(CLI::App& cmd, MachineOptions& o);

struct Loaded {
  std::shared_ptr<const Machine> machine;
  ErrorModel errors;
};
// Errors come from --errors when given, else from the machine file's `errors:`.
Loaded load(const MachineOptions& o);

// "X=10,Y=0,Z=5,B=-15,C=30" (mm and deg); every commanded axis must be given unless
// `partial` (the others are then zero).
std::vector<double> parsePose(const Machine& m, const std::string& text, bool partial = false);
// "1,0,0"
Vec3 parseVector(const std::string& text, const std::string& what);
// "10um", "30 urad"
double parseQuantityArg(const std::string& text, Dimension expected, const std::string& what);

// JSON to stdout (or -o); otherwise the human text to stdout and, with -o, the CSV.
void emit(const MachineOptions& o, const nlohmann::json& json, const std::string& human, const std::string& csv);

nlohmann::json poseJson(const Machine& m, const double* q);
std::string formatPose(const Machine& m, const double* q);
std::string unitOf(Dimension d);        // "um" or "urad"
double toDisplay(double v, Dimension d);  // mm -> um, rad -> urad

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
void addIdentifyCommands(CLI::App& app);      // identify, observability
void addDynamicsCommand(CLI::App& app);       // dynamics modes | frf | accel | map

}  // namespace mtacc::cli
