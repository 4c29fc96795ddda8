#pragma once
// `mtacc simulate motion`: the virtual machine of seed 004 runs an NC program at each feed of a
// ladder and writes what the NC and the instrument would record (docs/file-formats.md
// "Recorded signals"), the truth of every contribution, and the decomposition set that
// `mtacc decompose` reads.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/recorded_signal.hpp"
#include "mtacc/virtual_controller/motion_interpolator.hpp"
#include "mtacc/virtual_controller/virtual_recording.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct MotionSimulationRequest {
  std::string program;                // G-code: every move, at each feed in turn (its own F words are not used)
  std::vector<double> feeds{1000, 1800, 3240, 5832, 10498, 18896};  // mm/min, FGROUP (seed 004 L325)
  std::string structure;              // structure model (file or bundled name) for the dynamic error; empty: none
  InterpolatorLimits limits{.jerkTime = 0.02};
  // Servo loops: one value for every axis, or one per commanded axis in the machine's order.
  std::vector<double> positionGains{40.0};  // Kv, 1/s
  std::vector<double> feedForwards{0.99};   // 0 .. 1
  double clockOffset = 0.018;         // s
  double ncPeriod = 0.003, instrumentPeriod = 1e-4;  // s
  std::optional<Vec3> ball;           // mm, workpiece frame; default: the nominal TCP at the program's start
  Vec3 driftStep = Vec3(0.4e-3, 0.25e-3, 0.35e-3);  // mm: the k-th feed's drift is k times this
  double noise = 2e-4;                // mm
  std::uint64_t seed = 1;
  std::string folder;                 // where the files go (created)
  SignalFormat format = SignalFormat::Csv;
};

struct SimulatedFeed {
  double feed = 0.0;
  double duration = 0.0;  // s, dwells included
  size_t instrumentSamples = 0;
  Vec3 contouringMax, geometricMax, dynamicMax;  // largest |component| of the truth, mm
  std::vector<std::string> files;                // command, encoder, instrument, truth
};

struct MotionSimulationResult {
  Vec3 ball;
  std::vector<SimulatedFeed> feeds;
  std::string setFile;
};

// The options of `simulate motion`: program, output, feeds (mm/min), structure, noise, seed,
// acceleration, jerk_time_ms, kv, feed_forward, format, clock_offset_ms.
const OptionSchema& motionSimulationSchema();
MotionSimulationRequest motionSimulationRequest(const OptionValues& values);

// Throws InputError naming the program's file and line, the structure file, or the option
// (kv, feed_forward for lists of the wrong length).
MotionSimulationResult simulateMotion(const MachineSetup& setup, const MotionSimulationRequest& request);
// Lengths in um, durations in s.
nlohmann::json toJson(const MotionSimulationResult& simulation);

}  // namespace mtacc
