#include "mtacc/measurement/rtest_evaluation.hpp"

#include <utility>

#include <Eigen/Geometry>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

Vec3 columnRanges(const Eigen::MatrixXd& m) { return m.colwise().maxCoeff() - m.colwise().minCoeff(); }

// The ball on the side of the moving axis, in the bed frame: the sphere on the table for a
// workpiece-side axis, the tool ball for a head axis.
Pose carrier(const KinematicModel& nominal, const Machine& m, int axis, const double* q) {
  return m.axes[static_cast<size_t>(axis)].side == Side::Tool ? toolChainPose(nominal, q, nullptr) : workpiecePose(nominal, q, nullptr);
}

}  // namespace

RTestEvaluation evaluateRTest(const KinematicModel& nominal, const MeasurementRun& run) {
  if (run.instrument != Instrument::RTest) throw InvalidInput(run.name + ": not an R-test run");
  const Eigen::Index n = run.poses();
  if (n < 2) throw InvalidInput(run.name + ": an R-test run needs at least two poses");
  const Machine& m = *nominal.machine;
  // The rotary axis that turns most (the test is about it); a linear axis only when none turns.
  RTestEvaluation e;
  const Eigen::VectorXd spread = run.q.colwise().maxCoeff() - run.q.colwise().minCoeff();
  // Ranked by (rotary, spread): any rotary axis that moves before every linear one.
  auto rank = [&](int k) { return std::pair{m.axes[static_cast<size_t>(k)].isRotary(), spread[k]}; };
  for (int k = 0; k < static_cast<int>(spread.size()); ++k)
    if (spread[k] > 0.0 && (e.movingAxis < 0 || rank(k) > rank(e.movingAxis))) e.movingAxis = k;
  if (e.movingAxis < 0) throw InvalidInput(run.name + ": no axis moves over the run");
  e.position = run.q.col(e.movingAxis);
  e.displacement = run.readings;
  e.range = columnRanges(e.displacement);
  if (!m.axes[static_cast<size_t>(e.movingAxis)].isRotary()) return e;

  // About the axis's line at each pose: turning the axis by dq turns the ball's carrier by
  // omega dq (omega along the line, oriented by the axis's positive motion) and moves the ball
  // by omega x r dq, r the ball's offset from the line.
  const bool toolSide = m.axes[static_cast<size_t>(e.movingAxis)].side == Side::Tool;
  const Vec3 ball = toolSide ? run.setup.toolBall : run.setup.target;
  constexpr double kStep = 1e-6;  // rad
  RTestEvaluation::AboutTheAxis about;
  about.components.resize(n, 3);
  Eigen::RowVectorXd q(run.q.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    q = run.q.row(i);
    q[e.movingAxis] += kStep;
    const Pose ahead = carrier(nominal, m, e.movingAxis, q.data());
    q[e.movingAxis] -= 2.0 * kStep;
    const Pose behind = carrier(nominal, m, e.movingAxis, q.data());
    const Eigen::AngleAxisd turn(ahead.linear() * behind.linear().transpose());
    const Vec3 axial = turn.axis() * (turn.angle() >= 0 ? 1.0 : -1.0);
    const Vec3 velocity = (ahead * ball - behind * ball) / (2.0 * kStep);
    const double omega = turn.angle() / (2.0 * kStep);
    const Vec3 tangential = velocity.normalized(), radial = tangential.cross(axial);
    const Vec3 d = e.displacement.row(i).transpose();
    about.components.row(i) << d.dot(radial), d.dot(axial), d.dot(tangential);
    if (i == 0) {
      about.direction = axial;
      about.radius = velocity.norm() / omega;
      about.point = carrier(nominal, m, e.movingAxis, run.q.row(0).data()) * ball - about.radius * radial;
    }
  }
  about.range = columnRanges(about.components);
  // A ball on the line (radius below 1 um) has no radial or tangential direction.
  if (about.radius > 1e-3) e.aboutTheAxis = std::move(about);
  return e;
}

}  // namespace mtacc
