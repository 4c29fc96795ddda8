#pragma once
// Evaluation of circular ballbar runs: the eccentricity by least-squares first harmonics
// (seed 002 §8), the ISO 230-4 circular deviation G, radial deviation F and circular
// hysteresis H, and the usual ballbar diagnostics fitted to both directions at once.
#include <string>
#include <vector>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

// dL ~ c0 + e1 cos(angle) + e2 sin(angle) [+ a2 cos 2angle + b2 sin 2angle], least squares.
// eccentricity = e1 * plotAxes[0] + e2 * plotAxes[1] (machine frame, mm). The second
// harmonics keep shape terms out of a partial arc's centre.
struct EccentricityFit {
  double offset = 0;                 // c0, mm
  double e1 = 0, e2 = 0;             // along plotAxes[0], plotAxes[1], mm
  Vec3 eccentricity = Vec3::Zero();  // mm
  double cos2 = 0, sin2 = 0;         // mm
  double rms = 0;                    // residual, mm
};
// Throws InvalidInput for a run without angles, or with fewer than 8 samples.
EccentricityFit fitEccentricity(const MeasurementRun& run, bool secondHarmonics = true);

struct CircularDirection {
  int sense = 1;                  // +1 counter-clockwise, -1 clockwise
  double circularDeviation = 0;   // G: peak to valley about the least-squares circle, mm
  double radialMax = 0, radialMin = 0;  // F: extremes of dL about the set centre, mm
};

// Fitted to both directions at once: dL = c0 + e1 cos + e2 sin + A cos2 + B sin2
// + S sense sin2 + Ba sgn(v_a) cos + Bb sgn(v_b) sin (a, b the plot axes).
struct BallbarDiagnostics {
  double squareness = 0;    // angle between +a and +b minus 90 deg, rad
  double scaleMismatch = 0; // s_a - s_b (dimensionless)
  double servoMismatch = 0; // lag of a minus lag of b, s (needs both directions)
  double backlashA = 0, backlashB = 0;  // mm (full width)
  double reversalSpikeA = 0, reversalSpikeB = 0;  // largest residual just after a reversal, mm
  double residualRms = 0;   // mm
};

struct CircularTestResult {
  EccentricityFit eccentricity;
  std::vector<CircularDirection> directions;
  double hysteresis = 0;    // H: largest radial difference between the two directions, mm
  bool bothDirections = false;
  BallbarDiagnostics diagnostics;
};

CircularTestResult evaluateCircularTest(const MeasurementRun& run);

}  // namespace mtacc
