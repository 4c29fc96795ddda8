#pragma once
// Simulated measurements: the exact readings of a run on a machine with errors, with the
// non-geometric signatures a ballbar shows (servo gain mismatch, backlash, reversal spikes)
// as optional disturbances of the axis positions, and Gaussian reading noise.
#include <random>
#include <vector>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

// Per commanded axis (Machine::axes order); empty vectors mean none.
struct Disturbance {
  // Following error of the position loop: the axis lags by lag * velocity (s, 1/k_v). Equal
  // lags only shrink a circle; a difference between two axes makes the ballbar's
  // "servo mismatch" ellipse.
  std::vector<double> lag;
  // Lost motion: the axis lags by half the value against its direction of motion (mm or rad).
  std::vector<double> backlash;
  // After each reversal the axis sticks for a moment: a lag of `spikeHeight` decaying with
  // the time constant spikeTime (s).
  std::vector<double> spikeHeight;
  double spikeTime = 0.02;

  bool empty() const { return lag.empty() && backlash.empty() && spikeHeight.empty(); }
};

// Time of each pose along the run at its feed (mm/min on the tool point's path relative to
// the workpiece), in s.
std::vector<double> runTimes(const KinematicModel& nominal, const MeasurementRun& run);
// The axis positions the drives actually reach.
JointMatrix disturbedPoses(const KinematicModel& nominal, const MeasurementRun& run, const Disturbance& disturbance);

// Fills run.readings: exact readings on `model` (disturbed poses), plus N(0, noise) (mm).
void simulateRun(const KinematicModel& model, const KinematicModel& nominal, MeasurementRun& run,
                 const Disturbance& disturbance = {}, double noise = 0.0, std::mt19937_64* rng = nullptr);

}  // namespace mtacc
