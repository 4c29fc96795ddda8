#include "mtacc/kinematics/inverse_with_errors.hpp"

#include <algorithm>
#include <cmath>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

// 1 urad of direction weighs as 1 um of position, and a rotary command is solved for in mrad, so
// that at a regular pose every singular value of the scaled Jacobian is about 1 and near a
// singularity the smallest is about the sine of the angle to it.
constexpr double kDirectionWeight = 1000.0;  // mm per rad

// Position, then the weighted direction when controlled: at most six rows, on the stack.
using Residual = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// The wanted pose on the model, and the axes' directions of motion there (or null).
struct Target {
  const KinematicModel& model;
  Vec3 position, direction;
  const int* motion;
};

// The residual of the pose at q: position (mm), then, when controlled, the direction's
// difference times the weight; `reached` the tool there.
Residual residual(const Target& t, const std::vector<double>& q, bool withDirection, ToolPoint& reached) {
  reached = toolPoint(t.model, q.data(), t.motion);
  Residual r(withDirection ? 6 : 3);
  r.head<3>() = reached.position - t.position;
  if (withDirection) r.tail<3>() = kDirectionWeight * (reached.direction - t.direction);
  return r;
}

// The Jacobian of the residual at q by central differences (h in mm or rad: the model is smooth
// over it, and rounding stays far below the step's effect), columns scaled, factorised. For the
// position alone, a machine with three linear axes moves only those: the rotary axes keep their
// commands rather than turn the tool to reach a few micrometres.
void factorise(ErrorIkJacobian& jacobian, const Target& t, const std::vector<double>& q, bool withDirection, double singularRatio) {
  const auto n = static_cast<Eigen::Index>(q.size());
  const Machine& machine = *t.model.machine;
  auto& scale = jacobian.scale;
  scale.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) scale[k] = machine.axes[static_cast<size_t>(k)].isRotary() ? 1.0 / kDirectionWeight : 1.0;
  const bool positionByLinearAxes = n - machine.rotaryCount() >= 3;
  Eigen::MatrixXd j(withDirection ? 6 : 3, n);
  std::vector<double> plus = q, minus = q;
  ToolPoint reached;
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto kk = static_cast<size_t>(k);
    if (!withDirection && positionByLinearAxes && machine.axes[kk].isRotary()) {
      j.col(k).setZero();
      continue;
    }
    const double h = 1e-4;
    plus[kk] += h;
    minus[kk] -= h;
    j.col(k) = scale[k] * (residual(t, plus, withDirection, reached) - residual(t, minus, withDirection, reached)) / (2.0 * h);
    plus[kk] = minus[kk] = q[kk];
  }
  auto& svd = jacobian.svd;
  svd.compute(j, Eigen::ComputeThinU | Eigen::ComputeThinV);
  svd.setThreshold(singularRatio);
  jacobian.rank = svd.rank();
  const Eigen::Index r = jacobian.rank;
  jacobian.reachable = svd.matrixU().leftCols(r).transpose();
  jacobian.pseudoInverse = svd.matrixV().leftCols(r) * svd.singularValues().head(r).cwiseInverse().asDiagonal() * jacobian.reachable;
  jacobian.valid = true;
  jacobian.withDirection = withDirection;
}

}  // namespace

ErrorIkSolution refineWithErrors(const KinematicModel& actual, const Vec3& position, const Vec3& toolDirection,
                                 const std::vector<double>& start, const ErrorIkOptions& o, ErrorIkJacobian& jacobian,
                                 bool singularStart, const int* motion) {
  ErrorIkSolution s;
  refineWithErrors(actual, position, toolDirection, start, o, jacobian, s, singularStart, motion);
  return s;
}

void refineWithErrors(const KinematicModel& actual, const Vec3& position, const Vec3& toolDirection, const std::vector<double>& start,
                      const ErrorIkOptions& o, ErrorIkJacobian& jacobian, ErrorIkSolution& s, bool singularStart, const int* motion) {
  const Vec3 direction = toolDirection.normalized();
  const Target target{actual, position, direction, motion};
  s.q = start;
  s.nominalQ.clear();
  s.iterations = 0;
  s.directionControlled = !o.positionOnly && actual.machine->rotaryCount() >= 2;
  s.singular = singularStart;
  const auto n = static_cast<Eigen::Index>(s.q.size());
  const auto& scale = jacobian.scale;  // set with the factorisation
  // At a singular pose the direction is given up and the position alone is reached.
  bool withDirection = s.directionControlled && !singularStart;
  ToolPoint reached;
  Residual r = residual(target, s.q, withDirection, reached);
  auto within = [&](const Residual& res) {
    return res.head<3>().norm() <= o.positionTolerance && (!withDirection || res.tail<3>().norm() / kDirectionWeight <= o.directionTolerance);
  };
  while (!within(r) && s.iterations < o.maxIterations) {
    const bool fresh = !jacobian.valid || jacobian.withDirection != withDirection;
    if (fresh) factorise(jacobian, target, s.q, withDirection, o.singularRatio);
    if (jacobian.rank < std::min<Eigen::Index>(n, withDirection ? 5 : 3)) {
      if (!fresh) {  // a kept Jacobian from a pose that was singular: take it here
        jacobian.valid = false;
        continue;
      }
      s.singular = true;
      if (withDirection) {
        withDirection = false;
        r = residual(target, s.q, false, reached);
        continue;
      }
    }
    jacobian.step.noalias() = jacobian.pseudoInverse * r;
    for (Eigen::Index k = 0; k < n; ++k) s.q[static_cast<size_t>(k)] -= scale[k] * jacobian.step[k];
    const Residual next = residual(target, s.q, withDirection, reached);
    ++s.iterations;
    Residual reachedNext, reachedBefore;  // at most six rows: the rank of a Jacobian of six
    reachedNext.noalias() = jacobian.reachable * next;
    reachedBefore.noalias() = jacobian.reachable * r;
    const double contraction = reachedNext.norm() / std::max(reachedBefore.norm(), 1e-300);
    r = next;
    // At a singular pose the part of the residual no command reaches stays: stop when the
    // reachable part no longer shrinks under a Jacobian taken here.
    if (fresh && contraction >= 0.5) break;
    if (contraction > 0.1) jacobian.valid = false;
  }
  s.qLinearised = s.q;
  if (jacobian.valid && jacobian.withDirection == withDirection) {
    jacobian.step.noalias() = jacobian.pseudoInverse * r;
    for (Eigen::Index k = 0; k < n; ++k) s.qLinearised[static_cast<size_t>(k)] -= scale[k] * jacobian.step[k];
  }
  s.positionResidual = (reached.position - position).norm();
  s.directionResidual = angleBetween(reached.direction, direction);
  s.converged = within(r);
  s.travelViolation = o.checkTravel ? actual.machine->travelViolation(s.q) : std::string();
}

ErrorIkSolution solveIkWithErrors(const KinematicModel& actual, const KinematicModel& nominal, const Vec3& position,
                                  const Vec3& toolDirection, const ErrorIkOptions& o) {
  Vec3 startDirection = toolDirection.normalized();
  if (nominal.machine->rotaryCount() == 0) {
    // The errors tilt the one direction a machine without rotary axes has (fk reports it tilted),
    // and its direction is not corrected: start from the nominal direction when the target's is
    // within what errors can tilt.
    const std::vector<double> home(static_cast<size_t>(nominal.machine->commandedCount()), 0.0);
    const Vec3 fixed = toolPoint(nominal, home.data()).direction;
    constexpr double kLargestTilt = 1e-3;  // rad
    if (std::acos(std::clamp(fixed.dot(startDirection), -1.0, 1.0)) <= kLargestTilt) startDirection = fixed;
  }
  const IkSolution start = solveIk(nominal, position, startDirection, o.ik);
  ErrorIkJacobian jacobian;
  ErrorIkSolution s = refineWithErrors(actual, position, toolDirection, start.q, o, jacobian, start.singular);
  s.nominalQ = start.q;
  return s;
}

}  // namespace mtacc
