#pragma once
// A controller's 5-axis kinematic model fitted to the machine with its errors (LinuxCNC's modules,
// SINUMERIK's orientable toolholder): the controller's parameters and its world origin are values
// the fit moves; the residual is where the machine puts the tool tip, at the commands the
// controller gives, against where the controller means it. Private to the compensation module.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc::controller_fit {

// mm: the largest residual of the controller's model fitted to the nominal machine; beyond it the
// nominal machine is not of the controller's kind.
constexpr double kNominalFit = 1e-6;

struct ControllerPose {
  Vec3 world;            // the tool tip in the controller's world coordinates (mm)
  double first, second;  // the controller's angles of its two rotary axes (rad)
};

// A 3 x 3 x 3 lattice over the middle half of each linear travel (the world points), 9 angles of
// the first rotary axis over its travel (+-90 deg without one) and 12 of the second (a turn).
// Throws InputError for a linear axis without travel.
std::vector<ControllerPose> poseLattice(const Machine& machine, const std::array<size_t, 3>& linear, size_t first, size_t second);
// Keeps the poses whose commands lie within travel; throws InputError when fewer than 10 are left.
void keepWithinTravel(const Machine& machine, std::vector<ControllerPose>& poses,
                      const std::function<std::vector<double>(const ControllerPose&)>& commands);

// The controller's model as the fit sees it: the machine's commands it gives for a pose, and its
// world frame in the machine's workpiece coordinates (origin, and the rotation vector of its axes
// when it turns: a work offset with a rotation; null when it does not), all read from the state
// that `values` point into (the values the fit moves).
struct Model {
  std::function<std::vector<double>(const ControllerPose&)> commands;
  const Vec3& origin;
  std::vector<double*> values;
  const Vec3* turn = nullptr;
};

// The world frame's rotation for a rotation vector (rad).
Mat3 turned(const Vec3& turn);

// x y z per pose (mm): the machine's tool tip at the commands, less where the world point lies.
Eigen::VectorXd residual(const KinematicModel& machine, const Model& model, const std::vector<ControllerPose>& poses);
// Gauss-Newton on the values, in place: the commands are affine or nearly so in them over the
// errors' micrometres, so a few steps converge (central differences, least-norm steps by SVD).
// Combinations of the values that move the tool tip by less than 0.1 mm RMS per mm or rad are
// left alone: those that change nothing (a point's position along its own axis line) and those
// that act only through lever arms of micrometres (a table's zero offset against the workpiece's
// rotation, when the lines pass through the workpiece origin).
void fit(const KinematicModel& machine, const Model& model, const std::vector<ControllerPose>& poses);
double largestPerPose(const Eigen::VectorXd& residual);
// Largest and RMS over the poses of the residuals before and after (mm).
TableResidual residualFigures(const Eigen::VectorXd& before, const Eigen::VectorXd& after);

// Each error of `errors` alone, at the nominal fit `model`: what of its effect over the poses the
// values leave (to first order, exact for the errors they carry), named with it when it is more
// than 0.001 um and 0.1 % of the effect; the reversals and stiffness changes, which standing rigid
// kinematics never see, by kind.
std::vector<std::string> notCarried(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const Model& model,
                                    const std::vector<ControllerPose>& poses);

}  // namespace mtacc::controller_fit
