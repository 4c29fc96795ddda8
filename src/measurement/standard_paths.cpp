#include "mtacc/measurement/standard_paths.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {
namespace {

std::vector<double> basePose(const Machine& m, const std::vector<double>& pose) {
  if (pose.empty()) return std::vector<double>(static_cast<size_t>(m.commandedCount()), 0.0);
  if (static_cast<int>(pose.size()) != m.commandedCount())
    throw InvalidInput("a pose needs " + std::to_string(m.commandedCount()) + " axis values");
  return pose;
}

int commandedAxis(const Machine& m, const std::string& name) {
  const int j = m.axisIndex(name);
  if (j >= 0 && j == m.spindleIndex())
    throw InvalidInput("'" + name + "' is the spindle of " + m.name + ", not a commanded rotary axis");
  if (j < 0 || !m.axes[static_cast<size_t>(j)].isRotary())
    throw InvalidInput("'" + name + "' is not a rotary axis of " + m.name);
  return j;
}

Vec3 toolPointInWorkpiece(const KinematicModel& nominal, const std::vector<double>& q, const Vec3& toolPoint) {
  return toolInWorkpiece(nominal, q.data()) * toolPoint;
}

// Sign of each axis's motion towards the next pose; where the axis does not move (and at
// the last pose) it keeps the previous direction, as a drive does until it reverses.
DirectionMatrix motionDirections(const JointMatrix& q) {
  DirectionMatrix d = DirectionMatrix::Zero(q.rows(), q.cols());
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    for (Eigen::Index j = 0; j < q.cols(); ++j) {
      const double dq = i + 1 < q.rows() ? q(i + 1, j) - q(i, j) : 0.0;
      d(i, j) = dq > 1e-12 ? 1 : (dq < -1e-12 ? -1 : (i > 0 ? d(i - 1, j) : 0));
    }
  return d;
}

JointMatrix toMatrix(const std::vector<std::vector<double>>& rows) {
  JointMatrix q(static_cast<Eigen::Index>(rows.size()), rows.empty() ? 0 : static_cast<Eigen::Index>(rows[0].size()));
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < rows[i].size(); ++j) q(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
  return q;
}

// A right-handed pair spanning the plane normal to `axis`, the machine axes where possible
// (seed 002: B tests in Z-X, C tests in X-Y).
std::array<Vec3, 2> planeNormalTo(const Vec3& axis) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(axis[k]) - 1.0) < 1e-9) {
      const double s = axis[k] > 0 ? 1.0 : -1.0;
      return {Vec3::Unit((k + 1) % 3), s * Vec3::Unit((k + 2) % 3)};
    }
  }
  Vec3 e1 = axis.unitOrthogonal();
  return {e1, axis.cross(e1)};
}

double plotAngle(const std::array<Vec3, 2>& plane, const Vec3& d) { return std::atan2(d.dot(plane[1]), d.dot(plane[0])); }

Vec3 perpendicularFrom(const AxisLine& line, const Vec3& p) {
  Vec3 r = p - line.point;
  return r - line.direction * line.direction.dot(r);
}

}  // namespace

AxisLine axisLine(const KinematicModel& nominal, const std::vector<double>& q, int axis) {
  const auto frames = errorFrames(nominal, q.data());
  const Pose& f = frames[static_cast<size_t>(axis)];
  const auto& a = nominal.machine->axes[static_cast<size_t>(axis)];
  return {f.translation(), (f.linear() * a.direction).normalized()};
}

void placeToolPoint(const KinematicModel& nominal, std::vector<double>& q, const Vec3& toolPoint, const Vec3& target) {
  const Machine& m = *nominal.machine;
  std::vector<int> linear;
  for (int j = 0; j < m.commandedCount(); ++j)
    if (!m.axes[static_cast<size_t>(j)].isRotary()) linear.push_back(j);
  if (linear.empty()) throw UnreachablePose("the machine has no linear axis to place the tool");
  // Nominal positions are affine in the linear axes for fixed rotary ones, so two Newton
  // steps with a difference Jacobian (step 1 mm) are exact to rounding.
  for (int iteration = 0; iteration < 3; ++iteration) {
    const Vec3 p0 = toolPointInWorkpiece(nominal, q, toolPoint);
    const Vec3 residual = target - p0;
    if (residual.norm() < 1e-10) return;
    Eigen::Matrix<double, 3, Eigen::Dynamic> jac(3, static_cast<Eigen::Index>(linear.size()));
    for (size_t k = 0; k < linear.size(); ++k) {
      auto qk = q;
      qk[static_cast<size_t>(linear[k])] += 1.0;
      jac.col(static_cast<Eigen::Index>(k)) = toolPointInWorkpiece(nominal, qk, toolPoint) - p0;
    }
    const Eigen::VectorXd step = jac.completeOrthogonalDecomposition().solve(residual);
    for (size_t k = 0; k < linear.size(); ++k) q[static_cast<size_t>(linear[k])] += step[static_cast<Eigen::Index>(k)];
  }
  const Vec3 miss = target - toolPointInWorkpiece(nominal, q, toolPoint);
  if (miss.norm() > 1e-7)
    throw UnreachablePose("the linear axes cannot reach the point at " + m.describePose(q));
}

std::array<Vec3, 2> planeAxes(const std::string& plane) {
  if (plane == "XY") return {Vec3::UnitX(), Vec3::UnitY()};
  if (plane == "YZ") return {Vec3::UnitY(), Vec3::UnitZ()};
  if (plane == "ZX") return {Vec3::UnitZ(), Vec3::UnitX()};
  throw InvalidInput("unknown plane '" + plane + "' (XY, YZ or ZX)");
}

MeasurementRun ballbarCircle(const KinematicModel& nominal, const BallbarCircleSpec& spec) {
  const Machine& m = *nominal.machine;
  if (spec.points < 8) throw InvalidInput("a circle needs at least 8 points per direction");
  MeasurementRun run;
  run.name = "circle-" + spec.plane;
  run.instrument = Instrument::Ballbar;
  run.setup.toolBall = spec.toolBall;
  run.setup.target = spec.centre;
  run.setup.length = spec.radius;
  run.plotAxes = planeAxes(spec.plane);
  run.feed = spec.feed;
  const auto base = basePose(m, spec.pose);
  const Mat3 wpToMachine = workpiecePose(nominal, base.data(), nullptr).linear();
  // The centre ball is set where the tool-side cup is with the centre commanded (ISO 230-4
  // set-up with a setting fixture), so only the path's own deviations remain.
  auto setAt = base;
  placeToolPoint(nominal, setAt, spec.toolBall, spec.centre);
  run.setup.setAt = setAt;
  std::vector<std::vector<double>> rows;
  for (int sense : {1, -1}) {
    if (sense < 0 && !spec.bothDirections) break;
    for (int k = 0; k <= spec.points; ++k) {
      const double theta = sense > 0 ? 2 * kPi * k / spec.points : 2 * kPi * (spec.points - k) / spec.points;
      const Vec3 u = std::cos(theta) * run.plotAxes[0] + std::sin(theta) * run.plotAxes[1];
      auto q = base;
      placeToolPoint(nominal, q, spec.toolBall, spec.centre + wpToMachine.transpose() * (spec.radius * u));
      rows.push_back(q);
      run.angle.push_back(theta);
      run.sense.push_back(sense);
    }
  }
  run.q = toMatrix(rows);
  run.direction = motionDirections(run.q);
  return run;
}

RotaryTestMode parseRotaryTestMode(const std::string& name) {
  if (name == "radial") return RotaryTestMode::Radial;
  if (name == "tangential") return RotaryTestMode::Tangential;
  if (name == "axial") return RotaryTestMode::Axial;
  if (name == "x") return RotaryTestMode::X;
  if (name == "y") return RotaryTestMode::Y;
  if (name == "z") return RotaryTestMode::Z;
  throw InvalidInput("unknown rotary test '" + name + "' (radial, tangential, axial, x, y or z)");
}

MeasurementRun ballbarRotaryTest(const KinematicModel& nominal, const BallbarRotarySpec& spec) {
  const Machine& m = *nominal.machine;
  const int axis = commandedAxis(m, spec.axis);
  if (spec.points < 8) throw InvalidInput("a rotary test needs at least 8 points");
  const bool toolSide = m.axes[static_cast<size_t>(axis)].side == Side::Tool;
  MeasurementRun run;
  run.name = spec.axis + "-" + std::string(spec.mode == RotaryTestMode::Radial       ? "radial"
                                           : spec.mode == RotaryTestMode::Tangential ? "tangential"
                                           : spec.mode == RotaryTestMode::Axial      ? "axial"
                                           : spec.mode == RotaryTestMode::X          ? "x"
                                           : spec.mode == RotaryTestMode::Y          ? "y"
                                                                                     : "z");
  run.instrument = Instrument::Ballbar;
  run.setup.toolBall = spec.toolBall;
  run.setup.length = spec.length;
  run.feed = spec.feed;
  const auto base = basePose(m, spec.pose);

  // Set-up: rotary axes at zero, tool ball on the work ball.
  auto setAt = base;
  for (int j = 0; j < m.commandedCount(); ++j)
    if (m.axes[static_cast<size_t>(j)].isRotary()) setAt[static_cast<size_t>(j)] = 0.0;
  placeToolPoint(nominal, setAt, spec.toolBall, spec.workBall);
  run.setup.setAt = setAt;
  run.setup.target = spec.workBall;

  run.plotAxes = planeNormalTo(axisLine(nominal, setAt, axis).direction);
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < spec.points; ++k) {
    auto q = setAt;
    q[static_cast<size_t>(axis)] = spec.from + (spec.to - spec.from) * k / spec.points;
    Vec3 d = Vec3::Zero();
    for (int pass = 0; pass < 2; ++pass) {  // the radial direction may move with the linear axes
      const AxisLine line = axisLine(nominal, q, axis);
      const Pose wp = workpiecePose(nominal, q.data(), nullptr);
      const Vec3 w = wp * spec.workBall;
      const Vec3 t = toolChainPose(nominal, q.data(), nullptr) * spec.toolBall;
      d = toolSide ? Vec3(-perpendicularFrom(line, t)) : perpendicularFrom(line, w);
      if (d.norm() < 1e-9) throw InvalidInput("the ball lies on the " + spec.axis + " axis: no radial direction");
      d.normalize();
      const Vec3 radial = toolSide ? d : Vec3(-d);
      Vec3 u = Vec3::Zero();
      switch (spec.mode) {
        case RotaryTestMode::Radial: u = radial; break;
        case RotaryTestMode::Tangential: u = line.direction.cross(d); break;
        case RotaryTestMode::Axial: u = line.direction; break;
        case RotaryTestMode::X: u = Vec3::UnitX(); break;
        case RotaryTestMode::Y: u = Vec3::UnitY(); break;
        case RotaryTestMode::Z: u = Vec3::UnitZ(); break;
      }
      placeToolPoint(nominal, q, spec.toolBall, spec.workBall + wp.linear().transpose() * (spec.length * u));
    }
    rows.push_back(q);
    run.angle.push_back(plotAngle(run.plotAxes, d));
    run.sense.push_back(spec.to >= spec.from ? 1 : -1);
  }
  run.q = toMatrix(rows);
  run.direction = motionDirections(run.q);
  return run;
}

std::vector<MeasurementRun> sphereTest(const KinematicModel& nominal, const SphereTestSpec& spec) {
  const Machine& m = *nominal.machine;
  const int axis = commandedAxis(m, spec.axis);
  if (spec.angles.empty() || spec.spheres.empty())
    throw InvalidInput("a sphere test needs at least one angle and one sphere position");
  const auto base = basePose(m, spec.pose);
  std::vector<MeasurementRun> runs;
  for (size_t s = 0; s < spec.spheres.size(); ++s) {
    MeasurementRun run;
    run.name = instrumentName(spec.instrument) + "-" + spec.axis + "-" + std::to_string(s + 1);
    run.instrument = spec.instrument;
    run.setup.toolBall = spec.toolBall;
    run.setup.target = spec.spheres[s];
    std::vector<std::vector<double>> rows;
    for (double angle : spec.angles) {
      auto q = base;
      q[static_cast<size_t>(axis)] = angle;
      placeToolPoint(nominal, q, spec.toolBall, spec.spheres[s]);
      rows.push_back(q);
      run.angle.push_back(angle);
    }
    run.q = toMatrix(rows);
    run.direction = motionDirections(run.q);
    runs.push_back(std::move(run));
  }
  return runs;
}

std::vector<double> evenAngles(double from, double to, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(n == 1 ? from : from + (to - from) * i / (n - 1));
  return out;
}

}  // namespace mtacc
