#pragma once
// The inverse error model: the axis commands that put the tool at a wanted pose on the machine
// with its errors (the step before compensation, issue 17). Newton's method on the exact
// model, started from the nominal inverse kinematics (or from the commands of a nearby pose),
// with the Jacobian of the model with its errors taken by central differences and kept while
// the iteration contracts fast (the errors change it by their own small relative size, so a
// Jacobian from a nearby pose still converges at about that rate per step). Machines with two
// rotary axes get position and tool direction; the others the position only, their direction
// error reported as what cannot be corrected.
#include <string>
#include <vector>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

struct ErrorIkOptions {
  IkOptions ik;                      // branch and hint of the nominal start
  double positionTolerance = 1e-9;   // mm
  double directionTolerance = 1e-12; // rad
  int maxIterations = 20;
  // A direction of the commands whose singular value lies below this share of the largest is not
  // used: the pose is singular. The Jacobian is scaled so that this is about the sine of the
  // angle between the tool and the rotary axis that cannot turn it there (1e-2: 0.6 deg, where
  // a direction error of 1e-4 rad would need 0.6 deg of the other rotary axis).
  double singularRatio = 1e-2;
  // The position alone, by the linear axes, the rotary axes kept (what a table of linear-axis
  // corrections can do), whatever the machine's rotary axes.
  bool positionOnly = false;
  // false: travelViolation is left empty (a correction table's nodes at the ends of travel lie
  // beyond them by their correction, by design).
  bool checkTravel = true;
};

struct ErrorIkSolution {
  std::vector<double> q;           // mm, rad
  std::vector<double> nominalQ;    // solveIkWithErrors: the nominal IK's commands it started from
  // q moved by the Newton step its remaining residual asks for (with the Jacobian at hand, not
  // evaluated): the closer estimate of the exact commands, to start a nearby pose from (q when
  // no Jacobian was at hand).
  std::vector<double> qLinearised;
  double positionResidual = 0.0;   // mm: |TCP(q) - wanted|
  double directionResidual = 0.0;  // rad: angle between the tool direction at q and the wanted one
  int iterations = 0;
  bool converged = false;          // within the tolerances of what it controls (the position alone when singular)
  bool directionControlled = true; // false with fewer than two rotary axes
  bool singular = false;           // near a singular orientation (singularRatio): the direction is given up,
                                   // the position reached, and directionResidual says how far off it is
  std::string travelViolation;     // empty when q is within travel
};

// The factorised, scaled Jacobian of the last Newton step, reused from one solve to the next
// along a path or program while consecutive poses are close; refreshed when a step contracts
// the residual by less than 10x.
struct ErrorIkJacobian {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
  Eigen::MatrixXd pseudoInverse;  // the scaled step per residual, V S^+ U^T over the rank kept
  Eigen::MatrixXd reachable;      // U^T over the rank kept: the part of a residual the commands reach
  Eigen::Index rank = 0;
  bool valid = false;
  bool withDirection = false;
  Eigen::VectorXd scale;  // per column: 1 for a linear axis (mm), 1e-3 for a rotary one (solved for in mrad)
  Eigen::VectorXd step;   // scratch of the solves, kept so that a solve allocates no more
};

// `actual` compiled with the errors, `nominal` without; position and direction in the workpiece
// frame. Throws UnreachablePose when the nominal IK cannot reach the pose.
ErrorIkSolution solveIkWithErrors(const KinematicModel& actual, const KinematicModel& nominal, const Vec3& position,
                                  const Vec3& toolDirection, const ErrorIkOptions& options = {});

// The same Newton iteration from `start` (the commands of a nearby pose, e.g. the nominal
// commands plus the previous line's correction in a program), reusing `jacobian` while it
// serves (nominalQ of the result is left empty). `singularStart`: the direction is known to be
// uncontrollable at this pose. `motion`: each commanded axis's direction of motion there (+1, -1,
// 0), for the reversal errors of a machine on its way along a path; null: standing still.
ErrorIkSolution refineWithErrors(const KinematicModel& actual, const Vec3& position, const Vec3& toolDirection,
                                 const std::vector<double>& start, const ErrorIkOptions& options, ErrorIkJacobian& jacobian,
                                 bool singularStart = false, const int* motion = nullptr);
// The same into `solution`, its vectors' storage reused: a program or a correction grid solves a
// million poses.
void refineWithErrors(const KinematicModel& actual, const Vec3& position, const Vec3& toolDirection, const std::vector<double>& start,
                      const ErrorIkOptions& options, ErrorIkJacobian& jacobian, ErrorIkSolution& solution, bool singularStart = false,
                      const int* motion = nullptr);

}  // namespace mtacc
