#include "mtacc/kinematics/inverse_with_errors.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

// 1 urad of direction weighs as 1 um of position, and a rotary command is solved for in mrad, so
// that at a regular pose every singular value of the scaled Jacobian is about 1 and near a
// singularity the smallest is about the sine of the angle to it.
constexpr double kDirectionWeight = 1000.0;  // mm per rad

// The residual of the pose at q: position (mm), then, when controlled, the direction's
// difference times the weight.
Eigen::VectorXd residual(const KinematicModel& m, const std::vector<double>& q, const Vec3& position, const Vec3& direction,
                         bool withDirection) {
  const ToolPoint t = toolPoint(m, q.data());
  Eigen::VectorXd r(withDirection ? 6 : 3);
  r.head<3>() = t.position - position;
  if (withDirection) r.tail<3>() = kDirectionWeight * (t.direction - direction);
  return r;
}

int rotaryCount(const Machine& machine) {
  int n = 0;
  for (int i = 0; i < machine.commandedCount(); ++i) n += machine.axes[static_cast<size_t>(i)].isRotary() ? 1 : 0;
  return n;
}

}  // namespace

ErrorIkSolution solveIkWithErrors(const KinematicModel& actual, const KinematicModel& nominal, const Vec3& position,
                                  const Vec3& toolDirection, const ErrorIkOptions& o) {
  const Vec3 direction = toolDirection.normalized();
  const IkSolution start = solveIk(nominal, position, direction, o.ik);
  ErrorIkSolution s;
  s.q = start.q;
  s.nominalQ = start.q;
  s.directionControlled = rotaryCount(*actual.machine) >= 2;
  const auto n = static_cast<Eigen::Index>(s.q.size());
  // At a singular pose the direction is given up and the position alone is reached.
  bool withDirection = s.directionControlled && !start.singular;
  Eigen::VectorXd r = residual(actual, s.q, position, direction, withDirection);
  auto within = [&](const Eigen::VectorXd& res) {
    return res.head<3>().norm() <= o.positionTolerance && (!withDirection || res.tail<3>().norm() / kDirectionWeight <= o.directionTolerance);
  };
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd scale(n);
  for (Eigen::Index k = 0; k < n; ++k) scale[k] = actual.machine->axes[static_cast<size_t>(k)].isRotary() ? 1.0 / kDirectionWeight : 1.0;
  s.singular = start.singular;
  while (!within(r) && s.iterations < o.maxIterations) {
    // Newton: the Jacobian at the current commands, by central differences (h in mm or rad: the
    // model is smooth over it, and rounding stays far below the step's effect).
    jacobian.resize(r.size(), n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const double h = 1e-4;
      std::vector<double> plus = s.q, minus = s.q;
      plus[static_cast<size_t>(k)] += h;
      minus[static_cast<size_t>(k)] -= h;
      jacobian.col(k) = scale[k] * (residual(actual, plus, position, direction, withDirection) -
                                    residual(actual, minus, position, direction, withDirection)) / (2.0 * h);
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinU | Eigen::ComputeThinV);
    svd.setThreshold(o.singularRatio);
    if (svd.rank() < std::min<Eigen::Index>(n, withDirection ? 5 : 3)) {
      s.singular = true;
      if (withDirection) {
        withDirection = false;
        r = residual(actual, s.q, position, direction, false);
        continue;
      }
    }
    const Eigen::VectorXd step = scale.cwiseProduct(svd.solve(-r));
    for (Eigen::Index k = 0; k < n; ++k) s.q[static_cast<size_t>(k)] += step[k];
    const Eigen::VectorXd next = residual(actual, s.q, position, direction, withDirection);
    ++s.iterations;
    // At a singular pose the part of the residual no command reaches stays: stop when the
    // reachable part no longer shrinks.
    const auto reachable = svd.matrixU().leftCols(svd.rank());
    const bool stalled = (reachable.transpose() * next).norm() >= 0.5 * (reachable.transpose() * r).norm();
    r = next;
    if (stalled) break;
  }
  const ToolPoint t = toolPoint(actual, s.q.data());
  s.positionResidual = (t.position - position).norm();
  s.directionResidual = std::atan2(t.direction.cross(direction).norm(), t.direction.dot(direction));
  s.converged = s.positionResidual <= o.positionTolerance && (!withDirection || s.directionResidual <= o.directionTolerance);
  s.travelViolation = actual.machine->travelViolation(s.q);
  return s;
}

}  // namespace mtacc
