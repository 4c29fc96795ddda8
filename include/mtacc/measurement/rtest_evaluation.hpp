#pragma once
// One R-test run evaluated as ISO 10791-6 reports its tests around a rotary axis (the K and BK
// tests): the displacement of the sphere centre relative to the tool ball at each position of
// the axis that moves, its range along each machine axis, and its radial, axial and tangential
// components about that axis's line.
#include <optional>

#include <Eigen/Core>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

struct RTestEvaluation {
  int movingAxis = -1;            // the commanded axis whose position changes most over the run
  Eigen::VectorXd position;       // of that axis at each pose (mm or rad)
  Eigen::MatrixXd displacement;   // poses x 3: the readings, machine axes X Y Z (mm)
  Vec3 range = Vec3::Zero();      // max - min of each column (mm)
  // For a rotary axis whose ball (the sphere on a table axis, the tool ball on a head axis) is
  // off its line: the line at the first pose (bed frame; direction oriented so that the axis's
  // positive motion turns the ball counter-clockwise about it), the ball's radius about it, and
  // per pose the radial (outward), axial and tangential (direction of positive motion) components
  // of the displacement (mm) and their ranges.
  struct AboutTheAxis {
    Vec3 point = Vec3::Zero(), direction = Vec3::UnitZ();
    double radius = 0.0;  // of the sphere's circle (mm)
    Eigen::MatrixXd components;
    Vec3 range = Vec3::Zero();
  };
  std::optional<AboutTheAxis> aboutTheAxis;
};

// Throws InvalidInput for a run that is not an R-test or whose axes do not move.
RTestEvaluation evaluateRTest(const KinematicModel& nominal, const MeasurementRun& run);

}  // namespace mtacc
