// Issue 19's stepwise sensor selection at the size: 64 candidate temperature sensors
// over 24 h at 1 Hz (86,400 samples) from the virtual thermal machine (16 first-order nodes of
// time constants from 5 min to 8 h, heated by the spindle or by the axes on their own schedules,
// the drift driven by three nodes, four sensors per node or three and one in the room), forward selection by five-fold
// cross-validated RMS in contiguous blocks with backward removal, then the final fit. Side by side in the same run,
// NumPy doing the same steps (bench/sensor_selection_numpy.py: the blocks' Gram matrices by
// BLAS, every candidate's folds solved at once by batched np.linalg.solve, the final fit by
// lstsq) on the same record; writing the record is in neither. One thread against one
// (OpenBLAS limited to one); the selection is not threaded. mtacc runs once before and once
// after the baseline and the mean is compared. Target: under 1 s. Exits non-zero when the
// chosen sensors, a step's cross-validated RMS or a coefficient disagrees.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include "bench_support.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "mtacc/thermal/thermal_machine.hpp"

using namespace mtacc;

// The benchmark's size is also its agreement check's: both sides take well under a second.
int main(int argc, char** argv) {
  bench::agreementCheckOnly(argc, argv);
  VirtualThermalMachine machine;
  for (int j = 0; j < 16; ++j) {
    const double gain = 2.0 + static_cast<double>((7 * j) % 11);
    machine.nodes.push_back({300.0 * std::pow(96.0, j / 15.0), j % 2 == 0 ? std::vector<double>{gain, 0} : std::vector<double>{0, gain}});
    machine.driftPerKelvin.push_back(j == 1 ? 1.5e-3 : j == 6 ? 2.5e-3 : j == 11 ? -0.8e-3 : 0.0);
    for (int s = 0; s < 4; ++s) machine.sensedNode.push_back(s == 3 && j % 4 == 0 ? -1 : j);
  }
  machine.roomSwing = 0.5;
  Eigen::MatrixXd loads = Eigen::MatrixXd::Zero(24 * 3600, 2);
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{0, 6}, {14, 18}}) loads.col(0).segment(from * 3600, (to - from) * 3600).setOnes();
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{2, 5}, {9, 16}, {18, 20}}) loads.col(1).segment(from * 3600, (to - from) * 3600).setOnes();
  const auto record = recordDriftTest(machine, loads, 1.0).record;
  const SensorSelectionOptions options;

  const auto timed = [&](SensorSelection& result) {
    const auto t0 = std::chrono::steady_clock::now();
    result = selectSensors(record, options);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  SensorSelection result;
  const double before = timed(result);

  const auto dir = std::filesystem::temp_directory_path() / ("mtacc-bench-sensors-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "temperatures.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(record.temperatures.data()), static_cast<std::streamsize>(record.temperatures.size() * sizeof(double)));
  std::ofstream(dir / "drift.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(record.drift.data()), static_cast<std::streamsize>(record.drift.size() * sizeof(double)));
  std::ofstream(dir / "meta.json") << nlohmann::json{{"samples", record.temperatures.rows()},
                                                     {"sensors", record.temperatures.cols()},
                                                     {"folds", options.folds},
                                                     {"maximum_sensors", options.maximumSensors},
                                                     {"minimum_improvement", options.minimumImprovement}}
                                          .dump();
  const std::string cmd = bench::benchDir() + "/sensor_selection_numpy.py " + dir.string();
  const std::string pyOut = bench::runPythonBaseline(cmd);
  std::filesystem::remove_all(dir);
  const double after = timed(result), ours = (before + after) / 2;
  if (pyOut.empty()) {
    fmt::print(stderr, "bench_sensor_selection_vs_numpy: the NumPy baseline failed ({})\n", cmd);
    return 1;
  }
  const auto py = nlohmann::json::parse(pyOut);
  std::vector<int> theirSensors;
  double rmsGap = 0, coefficientGap = 0;
  const auto& steps = py["steps"];
  bool sameSteps = steps.size() == result.steps.size();
  for (size_t s = 0; sameSteps && s < steps.size(); ++s) {
    sameSteps = steps[s]["sensor"].get<int>() == result.steps[s].sensor && steps[s]["added"].get<bool>() == result.steps[s].added;
    rmsGap = std::max(rmsGap, std::abs(steps[s]["rms"].get<double>() / result.steps[s].crossValidatedRms - 1));
  }
  for (size_t j = 0; sameSteps && j < result.model.sensors.size(); ++j)
    coefficientGap = std::max(coefficientGap, std::abs(py["coefficients"][j].get<double>() - result.model.coefficients[static_cast<long>(j)]));

  fmt::print("sensor selection: {} sensors, {} samples (24 h at 1 Hz), {} folds; chosen {} (the drift's nodes 1, 6, 11 carry sensors "
             "4-7, 24-27, 44-47)\n",
             record.temperatures.cols(), record.temperatures.rows(), options.folds, result.model.sensors);
  fmt::print("cross-validated RMS {:.3f} um (best single sensor {} : {:.2f} um); NumPy agrees: steps {}, RMS to {:.1e} relative, "
             "coefficients to {:.1e} mm/K\n",
             result.crossValidatedRms * 1e3, result.bestSingleSensor, result.bestSingleSensorRms * 1e3, sameSteps ? "equal" : "DIFFER", rmsGap,
             coefficientGap);
  fmt::print("mtacc, 1 thread: {:.3f} s, mean of {:.3f} s before and {:.3f} s after the baseline (not threaded; target < 1 s)\n", ours, before,
             after);
  fmt::print("NumPy (Gram matrices by BLAS, batched solves), 1 thread: {:.3f} s\n", py["seconds"].get<double>());
  fmt::print("ratio at 1 thread against 1: mtacc is {:.1f}x faster\n", py["seconds"].get<double>() / ours);
  if (!sameSteps || rmsGap > 1e-8 || coefficientGap > 1e-10) {
    fmt::print(stderr, "bench_sensor_selection_vs_numpy: mtacc and NumPy disagree\n");
    return 1;
  }
  return 0;
}
