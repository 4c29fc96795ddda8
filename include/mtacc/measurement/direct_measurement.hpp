#pragma once
// Direct measurement of one component error along its axis (seed 003 ch. 4.2, App. B): N runs
// forward and backward at the same positions, and the corrections the report applies before
// fitting — the mean of the runs, the Abbe offset (translations referred to the carriage
// centroid), the scale temperature, readings disturbed by a periodic source (the 30-min
// lubrication pump) — and the derived quantities of App. B: yry from two straightness runs
// (eq. B.2) and squareness from the two-sided block (B.5).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/transform.hpp"
#include "mtacc/errors/error_model.hpp"

namespace mtacc {

struct ComponentRuns {
  std::vector<double> positions;      // mm or rad, strictly increasing
  Eigen::MatrixXd forward, backward;  // readings: one row per position, one column per run (mm or rad)
  Eigen::MatrixXd forwardTime, backwardTime;  // s since the start, or empty
};

// The mean of every run in both directions, per position (the seed fits this), with the
// forward and backward means, their difference and the scatter of single readings.
struct ComponentCurve {
  std::vector<double> positions;
  Eigen::VectorXd mean, meanForward, meanBackward, reversal;  // reversal = forward - backward
  Eigen::VectorXd scatter;  // per position: standard deviation of one reading about its direction's mean
};
ComponentCurve averageRuns(const ComponentRuns& runs);
// The runs without the given ones (indices into the columns).
ComponentRuns withoutRuns(const ComponentRuns& runs, const std::vector<int>& left);

// Direct-measurement runs of one component simulated from an axis's error functions: `runs`
// passes forward (positions ascending) and backward, one reading every `readingTime` seconds,
// each the component at the carriage centroid, plus (for a translation) the rotations' Abbe
// term (rotation x abbeOffset), Gaussian noise, and a disturbance of `disturbanceAmplitude` for
// one reading every `disturbanceInterval` seconds (the lubrication pump), if any, and a settling
// drift `settlingOffset * exp(-t / settlingTime)` on every reading at time t, if any.
struct ComponentRunsSpec {
  std::vector<double> positions;
  int runs = 20;
  double noise = 0.0;
  Vec3 abbeOffset = Vec3::Zero();
  double readingTime = 6.0;
  double disturbanceAmplitude = 0.0, disturbanceInterval = 1800.0;
  double settlingOffset = 0.0, settlingTime = 600.0;
  std::uint64_t seed = 1;
};
ComponentRuns simulateComponentRuns(const AxisErrors& axis, int component, const ComponentRunsSpec& spec);

// A reading far from the others at its position and direction (beyond `threshold` robust
// standard deviations of all such departures), and whether such readings recur at a steady
// interval (seed 003's lubrication-pump peaks every 30 min, L2500-2510). Unsettled runs: the
// runs at the start of the measurement whose mean departure from the others (both directions)
// lies beyond `threshold` robust standard deviations of the run means (at least the reading
// scatter over the square root of the readings per run) from their median: the machine or the
// instrument still drifting. Seed 003's program waits for each reading to settle (L2347-2351);
// this finds whole runs that did not.
struct DisturbedReading {
  int run;
  bool forward;
  double position, departure, time;  // time NaN when the runs have no times
};
struct Disturbances {
  std::vector<DisturbedReading> readings;
  std::optional<double> interval;  // s: the median spacing when at least 3 recur within 10 % of it
  std::vector<int> unsettledRuns;  // leading runs, from 0
};
Disturbances findDisturbances(const ComponentRuns& runs, double threshold = 5.0);

// Abbe (centroid) correction, seed 003 Fig. 4.1: a translation read at point P, `offset` from
// the carriage centroid, with the carriage turned by `rotation` (small angles, rad):
// e_centroid = e_P - rotation x offset; `component` 0, 1, 2 picks x, y, z.
double abbeCorrected(double reading, const Vec3& rotation, const Vec3& offset, int component);

// Scale temperature (seed 003 L2587-2604): a reading taken with the scale at T, referred to
// T_ref, with expansion coefficient alpha (1/K), zeroed at position x0:
// e_ref = e - alpha (T - T_ref) (x - x0).
double scaleTemperatureCorrected(double reading, double position, double x0, double temperature, double reference, double alpha);

// Eq. B.2 (L4416-4470): yry at Y position y from two straightness readings ytz1, ytz2 of a
// straightedge taken with the X carriage at x1 and x2; y * xrx removes the straightedge's tilt
// by the X roll xrx between the two set-ups. Lengths in mm, angles in rad.
double yryFromStraightness(double ytz1, double ytz2, double y, double xrx, double x1, double x2);

// App. B.5: squareness from a calibrated square (block) probed along both sides: alpha and
// beta are the slopes (rad) of the least-squares lines through the probe readings along the
// side the block is aligned to and along the other side; the result is the machine's
// squareness (angle between the guides minus 90 deg) with the block's own squareness removed,
// result = reference * alpha + other * beta + block * squareness of the block, the signs
// following from how the block lies (seed L4656-4741).
struct SquarenessSetup {
  double reference, other, block;
};
// Block on the table aligned to X (Z w.r.t. X, L4656-4674; Y w.r.t. X, L4695-4711): -alpha - beta + block.
inline constexpr SquarenessSetup kBlockAlignedToX{-1.0, -1.0, 1.0};
// Block aligned to Z (Y w.r.t. Z, L4730-4741): alpha - beta - block.
inline constexpr SquarenessSetup kBlockAlignedToZ{1.0, -1.0, -1.0};
double squarenessFromBlock(double alpha, double beta, double blockSquareness, const SquarenessSetup& setup);
// Straightness from probe readings along a straightedge or a square's side (seed 003 App. B):
// the readings minus the artefact's own calibrated deviation at each position, minus their
// least-squares line (the line is the alignment, or, against a square, the squareness).
std::vector<double> straightness(const std::vector<double>& positions, const std::vector<double>& readings,
                                 const std::vector<double>& artefact);

// The slope of the least-squares line through (x, y): what the straightness of a side leaves.
double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace mtacc
