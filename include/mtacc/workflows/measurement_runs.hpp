#pragma once
// Workflows `simulate` and `evaluate`: measurement runs (a ballbar circle, an R-test, or every
// run of a test plan) simulated on a machine with its errors and written in the measured-data
// format; and the ISO 230-4 evaluation of a ballbar file.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/measurement/circular_evaluation.hpp"
#include "mtacc/measurement/rtest_evaluation.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct SimulationOptions {
  double noise = 0;  // standard deviation of the reading noise, mm
  std::uint64_t seed = 1;
  std::array<std::optional<double>, kSetupParameterCount> setupErrors{};  // applied where the instrument has them
  Disturbance disturbance;
  // Where to write: a file for one run, a folder (one <run>.csv each) for several; empty: nothing.
  std::string output;
  bool outputIsFolder = false;
};

// Set-up errors as "xW=10um,zT=-5um" (xT yT zT xW yW zW aN bN cN dL, each with its unit); throws
// InputError naming `key` for an unknown name or a bad value.
std::array<std::optional<double>, kSetupParameterCount> parseSetupErrors(const std::string& text, const std::string& key);

// A ballbar run's servo and reversal disturbances as the front ends take them, per axis: the
// following error "X=1ms" (key lag), lost motion "X=5um" (backlash), reversal spike heights
// "Y=4um" (spike); spikeTime in s.
Disturbance disturbanceFromText(const Machine& machine, const std::string& lag, const std::string& backlash, const std::string& spike,
                                double spikeTime);

struct SimulationResult {
  std::shared_ptr<const Machine> machine;
  double noise = 0;
  std::vector<MeasurementRun> runs;  // with readings
  std::vector<std::string> files;    // written, one per run (empty when nothing was written)
};

// Every file is computed before the first is written; each is written atomically.
SimulationResult simulateRuns(const MachineSetup& setup, std::vector<MeasurementRun> runs, const SimulationOptions& options);
nlohmann::json toJson(const SimulationResult& result);

// The runs of the standard paths, simulated (see standard_paths.hpp); InvalidInput of
// a path becomes an InputError.
SimulationResult simulateBallbarCircle(const MachineSetup& setup, const BallbarCircleSpec& spec, const SimulationOptions& options);
SimulationResult simulateSphereTest(const MachineSetup& setup, const SphereTestSpec& spec, const SimulationOptions& options);
// Every run of a test plan (path or bundled name).
SimulationResult simulatePlan(const MachineSetup& setup, const std::string& plan, const SimulationOptions& options);

// A measurement file's run (docs/file-formats.md "Measurement data"); throws InputError naming the file.
MeasurementRun readMeasurementFile(const MachineSetup& setup, const std::string& file);
// Poses (mm, deg), readings (um), plot angles (deg) and sense of one run.
nlohmann::json runJson(const Machine& machine, const MeasurementRun& run);

// A measurement file's run with its evaluation.
template <class Result>
struct RunEvaluation {
  std::shared_ptr<const Machine> machine;
  std::string file;
  MeasurementRun run;
  Result result;
};
using CircularEvaluation = RunEvaluation<CircularTestResult>;
using RTestRunEvaluation = RunEvaluation<RTestEvaluation>;

// Reads a ballbar measurement file and evaluates it; throws InputError naming the file.
CircularEvaluation evaluateBallbarFile(const MachineSetup& setup, const std::string& file);
nlohmann::json toJson(const CircularEvaluation& evaluation);

// Reads an R-test measurement file and evaluates it (rtest_evaluation.hpp); throws InputError
// naming the file.
RTestRunEvaluation evaluateRTestFile(const MachineSetup& setup, const std::string& file);
nlohmann::json toJson(const RTestRunEvaluation& evaluation);

// `mtacc evaluate`: a ballbar run's circular evaluation or an R-test run's, by the file's
// instrument; any other instrument is refused.
std::variant<CircularEvaluation, RTestRunEvaluation> evaluateMeasurementFile(const MachineSetup& setup, const std::string& file);
// data: the run's file.
const OptionSchema& evaluationSchema();

}  // namespace mtacc
