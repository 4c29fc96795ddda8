#pragma once
// ISO 230-2:2014 evaluation of the positioning accuracy and repeatability of one numerically
// controlled axis, linear or rotary, from the standard test: m target positions P_i, each
// reached n times from the positive direction (forward, ↑) and n times from the negative one
// (backward, ↓). Every quantity is computed from the positional deviations
// x_ij = P_ij - P_i (measured actual position minus target), as the standard defines it
// (docs/conventions.md "ISO 230-2" lists each formula).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mtacc {

enum class PositioningAxis { Linear, Rotary };

struct PositioningTest {
  std::string name;
  PositioningAxis axis = PositioningAxis::Linear;
  std::vector<double> targets;      // P_i, strictly increasing; mm or rad
  Eigen::MatrixXd forward, backward;  // x_ij, one row per target, one column per cycle; mm or rad
};

// Per target position i (the standard's §2 terms at a position).
struct PositionStatistics {
  double target = 0;
  double meanForward = 0, meanBackward = 0;  // x̄_i↑, x̄_i↓: mean unidirectional positional deviation
  double mean = 0;                           // x̄_i = (x̄_i↑ + x̄_i↓) / 2: mean bidirectional positional deviation
  double reversal = 0;                       // B_i = x̄_i↑ - x̄_i↓
  double sForward = 0, sBackward = 0;        // s_i↑, s_i↓: estimator of the unidirectional standard uncertainty (n - 1)
  double repeatabilityForward = 0, repeatabilityBackward = 0;  // R_i↑ = 4 s_i↑, R_i↓ = 4 s_i↓
  double repeatability = 0;                  // R_i = max(2 s_i↑ + 2 s_i↓ + |B_i|, R_i↑, R_i↓)
};

// The axis values (the standard's §2 terms of an axis), in mm or rad.
struct PositioningResult {
  int cycles = 0;
  std::vector<PositionStatistics> positions;
  double accuracyForward = 0, accuracyBackward = 0, accuracy = 0;                    // A↑, A↓, A
  double reversal = 0, meanReversal = 0;                                             // B = max |B_i|, B̄ = mean B_i
  double systematicForward = 0, systematicBackward = 0, systematic = 0;              // E↑, E↓, E
  double meanDeviationRange = 0;                                                     // M
  double repeatabilityForward = 0, repeatabilityBackward = 0, repeatability = 0;    // R↑, R↓, R
  std::vector<std::string> notes;  // where the test departs from the standard's test conditions
};

// Requires at least 2 targets and 2 cycles (the standard asks for 5 cycles and, for axes up to
// 2 m, at least 5 targets per metre; fewer are reported in `notes`).
PositioningResult evaluatePositioning(const PositioningTest& test);

}  // namespace mtacc
