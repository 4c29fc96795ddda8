#include "mtacc/procedures/circle_fit.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

double range(const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high - *low;
}

// The minimax solution of b - A x (Lawson 1961): weighted least squares, each weight then
// multiplied by its residual's magnitude; the weights gather on the extremal residuals.
Eigen::VectorXd chebyshevFit(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd w = Eigen::VectorXd::Constant(b.size(), 1.0 / static_cast<double>(b.size()));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(a.cols());
  double best = INFINITY;
  Eigen::VectorXd bestX = x;
  for (int iteration = 0; iteration < 2000; ++iteration) {
    const Eigen::VectorXd s = w.cwiseSqrt();
    x = (s.asDiagonal() * a).colPivHouseholderQr().solve(s.cwiseProduct(b));
    const Eigen::VectorXd r = (b - a * x).cwiseAbs();
    const double worst = r.maxCoeff();
    if (worst < best) {
      if (best - worst < 1e-13 * (1.0 + worst) && iteration > 50) return x;
      best = worst;
      bestX = x;
    }
    w = w.cwiseProduct(r);
    const double sum = w.sum();
    if (!(sum > 0)) break;
    w /= sum;
  }
  return bestX;
}

}  // namespace

PointSpread pointSpread(const std::vector<Vec3>& pts) {
  PointSpread s;
  for (const auto& p : pts) s.centroid += p;
  s.centroid /= static_cast<double>(std::max<size_t>(1, pts.size()));
  Mat3 scatter = Mat3::Zero();
  for (const auto& p : pts) scatter += (p - s.centroid) * (p - s.centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter);
  s.axes = eig.eigenvectors();
  s.spread = eig.eigenvalues();
  return s;
}

CircleFit fitCircle(const std::vector<Vec3>& pts, const Vec3& towards) {
  if (pts.size() < 3) throw InvalidInput("a circle needs at least three points");
  const auto n = static_cast<Eigen::Index>(pts.size());
  const PointSpread spread = pointSpread(pts);
  if (spread.onOneLine()) throw InvalidInput("the points of a circle lie on one line");
  const Vec3& centroid = spread.centroid;
  CircleFit c;
  c.normal = spread.axes.col(0);
  if (c.normal.dot(towards) < 0) c.normal = -c.normal;
  c.u = c.normal.unitOrthogonal();
  c.v = c.normal.cross(c.u);
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 w = pts[static_cast<size_t>(i)] - centroid;
    const double x = w.dot(c.u), y = w.dot(c.v);
    a.row(i) << x, y, 1.0;
    b[i] = -(x * x + y * y);
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  c.centre = centroid - 0.5 * def[0] * c.u - 0.5 * def[1] * c.v;
  for (const auto& p : pts) {
    const Vec3 w = p - c.centre;
    c.radius += (w - w.dot(c.normal) * c.normal).norm();
  }
  c.radius /= static_cast<double>(n);
  return c;
}

std::vector<double> radialDeviations(const std::vector<Vec3>& pts, const CircleFit& circle) {
  std::vector<double> out;
  out.reserve(pts.size());
  for (const auto& p : pts) {
    const Vec3 w = p - circle.centre;
    out.push_back((w - w.dot(circle.normal) * circle.normal).norm() - circle.radius);
  }
  return out;
}

MinimumZoneCircle minimumZoneCircle(const std::vector<Vec3>& pts, const CircleFit& circle) {
  const auto n = static_cast<Eigen::Index>(pts.size());
  CircleFit at = circle;
  const double leastSquares = range(radialDeviations(pts, circle));
  MinimumZoneCircle best{circle.centre, leastSquares};
  for (int outer = 0; outer < 20; ++outer) {
    // r_i(c + du u + dv v) - R - dR ~ r_i - R - (e_i . u) du - (e_i . v) dv - dR, e_i the unit
    // vector from the centre to the point in the plane.
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      Vec3 w = pts[static_cast<size_t>(i)] - at.centre;
      w -= w.dot(at.normal) * at.normal;
      const double r = w.norm();
      const Vec3 e = w / r;
      a.row(i) << e.dot(at.u), e.dot(at.v), 1.0;
      b[i] = r - at.radius;
    }
    const Eigen::Vector3d step = chebyshevFit(a, b);
    at.centre += step[0] * at.u + step[1] * at.v;
    at.radius += step[2];
    const double width = range(radialDeviations(pts, at));
    if (width < best.width) best = {at.centre, width};
    if (std::hypot(step[0], step[1]) < 1e-9) break;
  }
  return best;
}

}  // namespace mtacc
