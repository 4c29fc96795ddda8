#pragma once
// The spindle's thermal drift test of ISO 230-3 as seed 003 ran it (§2.6, extraction §10.3): a
// test mandrel in the spindle, five displacement probes (X and Y at two heights, Z at the end),
// the spindle running and then at rest. The mandrel's displacement and tilts from the probes,
// the drift's extremes per direction, and the warm-up / cool-down hysteresis against a
// temperature (seed 003: 40 or 52 um of Y drift for the same 25 K rise).
#include <Eigen/Dense>

#include <optional>
#include <string>
#include <vector>

namespace mtacc {

// Readings of the mandrel's displacement along +X, +Y, +Z at each sample, mm; a probe absent is
// empty. Sets 1 and 2 sit at machine z = z1 and z2 (z1 != z2 when both X or both Y are given).
struct MandrelProbes {
  Eigen::VectorXd x1, y1, x2, y2, z;
  double z1 = 0.0, z2 = 0.0;  // mm
};

// Drift from the first sample: X, Y at probe set 1 and Z (mm); A, B tilts (rad) about X and Y
// from the two heights: B = dx / dz, A = -dy / dz. Absent where their probes are.
enum class DriftDirection { X, Y, Z, A, B };
constexpr DriftDirection kDriftDirections[] = {DriftDirection::X, DriftDirection::Y, DriftDirection::Z, DriftDirection::A, DriftDirection::B};
const char* nameOf(DriftDirection direction);
// A drift is shown in um (X, Y, Z) or urad (A, B): that unit, and its size per internal unit
// (mm, rad).
inline bool isTilt(DriftDirection d) { return d == DriftDirection::A || d == DriftDirection::B; }
inline const char* displayUnitOf(DriftDirection d) { return isTilt(d) ? "urad" : "um"; }
inline double displayScaleOf(DriftDirection d) { return isTilt(d) ? 1e6 : 1e3; }

struct MandrelDrift {
  std::optional<Eigen::VectorXd> series[5];  // by DriftDirection

  const std::optional<Eigen::VectorXd>& operator[](DriftDirection d) const { return series[static_cast<int>(d)]; }
};

// Throws InvalidInput for probes of unequal lengths, no probe at all, or two heights
// that coincide while a tilt needs them.
MandrelDrift mandrelDrift(const MandrelProbes& probes);

struct DriftExtremes {
  double largest = 0.0;  // the signed drift of largest magnitude from the start (mm or rad)
  double time = 0.0;     // s, when it occurred
  double range = 0.0;    // max - min over the test
};
DriftExtremes driftExtremes(const Eigen::VectorXd& drift, const Eigen::VectorXd& time);

// Warm-up (up to the temperature's highest sample) against cool-down (after it): the drift
// averaged in `bins` equal temperature bins over the range both branches cover, and the
// largest difference cool-down minus warm-up. Empty when a branch has no samples in common.
struct DriftHysteresis {
  double difference = 0.0;   // mm or rad, cool-down minus warm-up at `temperature`
  double temperature = 0.0;  // degC, the bin's centre
  double commonLow = 0.0, commonHigh = 0.0;  // degC: the range both branches cover
  int bins = 0;
};
std::optional<DriftHysteresis> driftHysteresis(const Eigen::VectorXd& drift, const Eigen::VectorXd& temperature, int bins = 20);

}  // namespace mtacc
