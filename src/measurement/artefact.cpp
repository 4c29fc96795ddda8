#include "mtacc/measurement/artefact.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"

namespace mtacc {
namespace {

Vec3 toolPointError(const KinematicModel& actual, const KinematicModel& nominal, const double* q, const Vec3& stylus) {
  return toolInWorkpiece(actual, q) * stylus - toolInWorkpiece(nominal, q) * stylus;
}

Eigen::Index farthestFrom(const Eigen::MatrixXd& points, const Eigen::VectorXd& from) {
  Eigen::Index best = 0;
  (points.colwise() - from).colwise().norm().maxCoeff(&best);
  return best;
}

Eigen::Index farthestFromLine(const Eigen::MatrixXd& points, const Eigen::VectorXd& a, const Eigen::VectorXd& direction) {
  const Eigen::MatrixXd relative = points.colwise() - a;
  const Eigen::MatrixXd across = relative - direction * (direction.transpose() * relative);
  Eigen::Index best = 0;
  across.colwise().norm().maxCoeff(&best);
  return best;
}

// The orthonormal frame (columns) of three points: along a->b, then in their plane.
Eigen::Matrix3d pointFrame(const Vec3& a, const Vec3& b, const Vec3& c) {
  Eigen::Matrix3d f;
  f.col(0) = (b - a).normalized();
  f.col(2) = f.col(0).cross(c - a).normalized();
  f.col(1) = f.col(2).cross(f.col(0));
  return f;
}

// The rigid motion (k x k rotation, translation) carrying the calibrated alignment features onto
// the measured ones; calibrated and measured are k x n.
void threePoint(const Eigen::MatrixXd& cal, const Eigen::MatrixXd& mea, int dimension, AlignedArtefact& out) {
  const Eigen::Index k = cal.rows();
  auto& f = out.features;
  if (f[0] < 0) f[0] = 0;
  const Eigen::VectorXd ca = cal.col(f[0]), ma = mea.col(f[0]);
  out.rotation = Eigen::MatrixXd::Identity(k, k);
  if (k > 1) {
    if (f[1] < 0) f[1] = static_cast<int>(farthestFrom(cal, ca));
    const Eigen::VectorXd ab = cal.col(f[1]) - ca;
    if (!(ab.norm() > 1e-3)) throw InvalidInput("three-point alignment: the first two features coincide");
    if (k == 2) {
      const Eigen::Vector2d measuredAb = mea.col(f[1]) - ma;
      const double turn = std::atan2(measuredAb.y(), measuredAb.x()) - std::atan2(ab.y(), ab.x());
      out.rotation = Eigen::Rotation2Dd(turn).toRotationMatrix();
    } else if (dimension == 1) {
      // Collinear features: the turn about their line is free; the least turn from line to line.
      out.rotation = Eigen::Quaterniond::FromTwoVectors(Vec3(ab), Vec3(mea.col(f[1]) - ma)).toRotationMatrix();
    } else {
      if (f[2] < 0) f[2] = static_cast<int>(farthestFromLine(cal, ca, ab.normalized()));
      const Vec3 a = ca, b = cal.col(f[1]), c = cal.col(f[2]);
      if (!((b - a).normalized().cross(c - a).norm() > 1e-3))
        throw InvalidInput("three-point alignment: the three features lie on one line");
      out.rotation = pointFrame(ma, mea.col(f[1]), mea.col(f[2])) * pointFrame(a, b, c).transpose();
    }
  }
  out.translation = ma - out.rotation * ca;
}

}  // namespace

int directionCount(ProbedDirections probed) {
  return probed == ProbedDirections::All ? 3 : probed == ProbedDirections::InPlane ? 2 : 1;
}

Eigen::Matrix3d ArtefactPlacement::frame() const {
  Eigen::Matrix3d f;
  f << u, v, u.cross(v);
  return f;
}

JointMatrix artefactPoses(const KinematicModel& nominal, const Artefact& artefact, const ArtefactPlacement& placement) {
  const Machine& m = *nominal.machine;
  std::vector<double> hint = placement.fixedAxes;
  if (hint.empty()) hint = m.referencePose;
  if (hint.size() != static_cast<size_t>(m.commandedCount())) throw InvalidInput("artefact placement: one fixed position per axis");
  const Pose tool = toolInWorkpiece(nominal, hint.data());
  const Vec3 direction = tool.linear() * m.toolDirection;
  JointMatrix q(static_cast<Eigen::Index>(artefact.features.size()), m.commandedCount());
  IkOptions options;
  options.hint = hint;
  for (size_t k = 0; k < artefact.features.size(); ++k) {
    const auto& feature = artefact.features[k];
    IkSolution s;
    try {
      s = solveIk(nominal, placement.place(feature.calibrated) - tool.linear() * placement.stylus, direction, options);
    } catch (const UnreachablePose& e) {
      throw UnreachablePose(fmt::format("artefact '{}', feature {}: {}", placement.name, feature.id, e.what()));
    }
    for (int a = 0; a < m.commandedCount(); ++a) {
      const auto axis = static_cast<size_t>(a);
      if (m.axes[axis].isRotary() && std::abs(s.q[axis] - hint[axis]) > 1e-9)
        throw UnreachablePose(fmt::format("artefact '{}', feature {}: needs {} to turn", placement.name, feature.id, m.axes[axis].name));
      q(static_cast<Eigen::Index>(k), a) = s.q[axis];
    }
  }
  return q;
}

Eigen::MatrixX3d artefactProbingErrors(const KinematicModel& actual, const KinematicModel& nominal, const ArtefactPlacement& placement,
                                       const JointMatrix& poses) {
  // The probe triggers where the actual stylus touches the feature, and the machine reports
  // where its nominal model puts the stylus then: measured - true = -(actual - nominal).
  Eigen::MatrixX3d d(poses.rows(), 3);
  for (Eigen::Index k = 0; k < poses.rows(); ++k) d.row(k) = -toolPointError(actual, nominal, poses.row(k).data(), placement.stylus).transpose();
  return d;
}

AlignedArtefact alignArtefact(const Eigen::MatrixX3d& calibrated, const Eigen::MatrixX3d& measured, ProbedDirections probed, int dimension,
                              const Alignment& alignment) {
  const int k = directionCount(probed);
  const Eigen::MatrixXd cal = calibrated.leftCols(k).transpose(), mea = measured.leftCols(k).transpose();
  AlignedArtefact out;
  out.features = alignment.features;
  if (alignment.method == AlignmentMethod::ThreePoint) {
    threePoint(cal, mea, dimension, out);
  } else {
    const Eigen::MatrixXd t = Eigen::umeyama(cal, mea, alignment.method == AlignmentMethod::LeastSquaresScaled);
    const Eigen::MatrixXd sr = t.topLeftCorner(k, k);
    out.scale = sr.col(0).norm();
    out.rotation = sr / out.scale;
    out.translation = t.topRightCorner(k, 1);
  }
  out.deviations = (mea - ((out.scale * out.rotation * cal).colwise() + out.translation)).transpose();
  return out;
}

Eigen::MatrixXd deviationUncertainty(const Eigen::MatrixX3d& calibrated, const Eigen::MatrixX3d& measured, ProbedDirections probed,
                                     int dimension, const Alignment& alignment, const Eigen::VectorXd& certificateSigma, const Vec3& probeSigma,
                                     int draws, std::uint64_t seed) {
  const int k = directionCount(probed);
  const Eigen::Index n = calibrated.rows();
  // The three-point features as the measurement chose them, so that every draw aligns on the same.
  Alignment fixed = alignment;
  fixed.features = alignArtefact(calibrated, measured, probed, dimension, alignment).features;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, k), squares = Eigen::MatrixXd::Zero(n, k);
  for (int draw = 0; draw < draws; ++draw) {
    Eigen::MatrixX3d cal = calibrated, mea = measured;
    for (Eigen::Index i = 0; i < n; ++i)
      for (int j = 0; j < k; ++j) {
        cal(i, j) += certificateSigma[i] * unit(rng);
        mea(i, j) += probeSigma[j] * unit(rng);
      }
    const Eigen::MatrixXd d = alignArtefact(cal, mea, probed, dimension, fixed).deviations;
    sum += d;
    squares += d.cwiseAbs2();
  }
  const Eigen::MatrixXd mean = sum / draws;
  return 2.0 * (squares / draws - mean.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt() * std::sqrt(draws / (draws - 1.0));
}

}  // namespace mtacc
