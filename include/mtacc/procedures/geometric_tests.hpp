#pragma once
// ISO 230-1 geometric tests from direct measurements of one component error along a linear axis
// (docs/file-formats.md "Component runs"; seed 003's direct measurements): the straightness of the
// axis's motion against the end-point and the least-squares reference lines, an angular deviation's
// range, or the positional deviation's range, from the mean of every run at each position, with
// what its uncertainty takes (rangeUncertainty: the instrument's reading and the runs' scatter).
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/measurement/direct_measurement.hpp"

namespace mtacc {

enum class GeometricTestKind { Straightness, Angular, Positional };

struct GeometricTestResult {
  GeometricTestKind kind = GeometricTestKind::Straightness;
  std::string component;        // ISO name, e.g. EYX
  double measuredLength = 0;    // mm
  std::vector<double> positions;
  Eigen::VectorXd mean;         // per position: the mean of every run (mm or rad)
  Eigen::VectorXd endPointResidual, leastSquaresResidual;  // straightness: from each reference line
  double leastSquaresSlope = 0;  // straightness: of the least-squares line (mm/mm; the axis's angle to the instrument)
  double repeatability = 0;      // largest s of one reading about its direction's mean
  int readingsPerPosition = 0;
  std::vector<std::pair<std::string, double>> quantities;  // end_point, least_squares (straightness) or range: mm or rad
};

// Throws InvalidInput for a component of a rotary axis.
GeometricTestResult evaluateGeometricTest(const Machine& machine, const MotionComponent& component, const ComponentRuns& runs);

// The tolerance file's test name of a kind: "straightness", "angular_deviation", "positional_deviation".
const char* toleranceTestName(GeometricTestKind kind);

}  // namespace mtacc
