#include "mtacc/procedures/measured_cone.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

struct Line {
  Vec3 point, direction;
};

// The least-squares line through the points (a single point: along `fallback`).
Line fitLine(const std::vector<Vec3>& pts, const Vec3& fallback) {
  const PointSpread spread = pointSpread(pts);
  if (pts.size() < 2) return {spread.centroid, fallback};
  Vec3 d = spread.axes.col(2);
  if (d.dot(fallback) < 0) d = -d;
  return {spread.centroid, d};
}

double distanceFromLine(const Vec3& p, const Line& line) {
  const Vec3 w = p - line.point;
  return (w - w.dot(line.direction) * line.direction).norm();
}

// The signed normal distance of p from the cone with axis (point, direction), radius r0 at the
// point and radius slope t (dr/dz).
double coneDistance(const Vec3& p, const Line& axis, double r0, double t) {
  const Vec3 w = p - axis.point;
  const double z = w.dot(axis.direction);
  return ((w - z * axis.direction).norm() - r0 - z * t) / std::sqrt(1.0 + t * t);
}

struct ConeFit {
  Line axis;
  double r0, t;
};

// Gauss-Newton over the axis (two turns and two shifts across it), r0 and t, with central
// differences; from the sections' estimate, which is already close.
ConeFit bestFitCone(const std::vector<Vec3>& pts, ConeFit start) {
  const Vec3 e1 = start.axis.direction.unitOrthogonal(), e2 = start.axis.direction.cross(e1);
  const auto model = [&](const Eigen::Matrix<double, 6, 1>& x) {
    ConeFit f;
    f.axis.direction = (start.axis.direction + x[0] * e1 + x[1] * e2).normalized();
    f.axis.point = start.axis.point + x[2] * e1 + x[3] * e2;
    f.r0 = start.r0 + x[4];
    f.t = start.t + x[5];
    return f;
  };
  const auto residuals = [&](const Eigen::Matrix<double, 6, 1>& x) {
    const ConeFit f = model(x);
    Eigen::VectorXd r(static_cast<Eigen::Index>(pts.size()));
    for (size_t i = 0; i < pts.size(); ++i) r[static_cast<Eigen::Index>(i)] = coneDistance(pts[i], f.axis, f.r0, f.t);
    return r;
  };
  Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::VectorXd r = residuals(x);
    Eigen::MatrixXd j(r.size(), 6);
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
      h[k] = k < 2 || k == 5 ? 1e-7 : 1e-5;
      j.col(k) = (residuals(x + h) - residuals(x - h)) / (2 * h[k]);
    }
    const Eigen::Matrix<double, 6, 1> step = j.colPivHouseholderQr().solve(-r);
    x += step;
    if (step.head<2>().norm() < 1e-14 && step.segment<4>(2).norm() < 1e-11) break;
  }
  return model(x);
}

MeasuredSection section(const ConeSection& s, const Vec3& towards) {
  if (s.points.size() < 4) throw InvalidInput("section '" + s.name + "': at least four points");
  MeasuredSection m;
  m.name = s.name;
  try {
    m.circle = fitCircle(s.points, towards);
  } catch (const InvalidInput& e) {
    throw InvalidInput("section '" + s.name + "': " + e.what());
  }
  m.radial = radialDeviations(s.points, m.circle);
  const auto [low, high] = std::minmax_element(m.radial.begin(), m.radial.end());
  m.leastSquaresCircularity = *high - *low;
  const auto zone = minimumZoneCircle(s.points, m.circle);
  m.minimumZoneCircularity = zone.width;
  m.minimumZoneCentre = zone.centre;
  return m;
}

}  // namespace

MeasuredCone evaluateMeasuredCone(const ConePoints& in, double nominalHalfAngle) {
  if (in.cone.empty()) throw InvalidInput("no cone section");
  MeasuredCone out;
  Vec3 up = Vec3::UnitZ();
  if (!in.plane.empty()) {
    if (in.plane.size() < 3) throw InvalidInput("plane A: at least three points");
    const PointSpread spread = pointSpread(in.plane);
    if (spread.onOneLine()) throw InvalidInput("plane A: the points lie on one line");
    const Vec3& centroid = spread.centroid;
    Vec3 normal = spread.axes.col(0);
    // Towards the cone: the side of the plane where the cone's points are.
    if (normal.dot(in.cone.front().points.front() - centroid) < 0) normal = -normal;
    out.planeNormal = normal;
    double low = INFINITY, high = -INFINITY;
    for (const auto& p : in.plane) {
      low = std::min(low, normal.dot(p - centroid));
      high = std::max(high, normal.dot(p - centroid));
    }
    out.flatness = high - low;
    up = normal;
  }
  for (const auto& s : in.cone) out.cone.push_back(section(s, up));
  for (const auto& s : in.cylinder) out.cylinder.push_back(section(s, up));
  std::vector<Vec3> centres;
  for (const auto& s : out.cone) centres.push_back(s.circle.centre);
  const Line axis = fitLine(centres, out.cone.size() == 1 ? out.cone.front().circle.normal : up);
  out.axisDirection = axis.direction;
  out.axisPoint = axis.point + (out.cone.front().circle.centre - axis.point).dot(axis.direction) * axis.direction;
  double halfAngle = nominalHalfAngle;
  if (out.cone.size() >= 2) {
    // Radius against height, then the best fit through every point.
    Eigen::MatrixXd a(static_cast<Eigen::Index>(out.cone.size()), 2);
    Eigen::VectorXd b(a.rows());
    for (size_t k = 0; k < out.cone.size(); ++k) {
      a.row(static_cast<Eigen::Index>(k)) << 1.0, (out.cone[k].circle.centre - out.axisPoint).dot(out.axisDirection);
      b[static_cast<Eigen::Index>(k)] = out.cone[k].circle.radius;
    }
    const Eigen::Vector2d line = a.colPivHouseholderQr().solve(b);
    std::vector<Vec3> all;
    for (const auto& s : in.cone) all.insert(all.end(), s.points.begin(), s.points.end());
    const ConeFit fit = bestFitCone(all, {{out.axisPoint, out.axisDirection}, line[0], line[1]});
    out.axisPoint = fit.axis.point;
    out.axisDirection = fit.axis.direction;
    halfAngle = std::atan(-fit.t);
    out.halfAngle = halfAngle;
    double low = INFINITY, high = -INFINITY;
    for (const auto& p : all) {
      const double d = coneDistance(p, fit.axis, fit.r0, fit.t);
      low = std::min(low, d);
      high = std::max(high, d);
    }
    out.formError = high - low;
  }
  const Line coneAxis{out.axisPoint, out.axisDirection};
  std::optional<Line> datum;
  if (!out.cylinder.empty()) {
    std::vector<Vec3> cylinderCentres;
    for (const auto& s : out.cylinder) cylinderCentres.push_back(s.circle.centre);
    datum = fitLine(cylinderCentres, out.cylinder.front().circle.normal);
    double worst = 0;
    for (const auto& s : out.cone) worst = std::max(worst, distanceFromLine(s.circle.centre, *datum));
    out.coaxiality = 2.0 * worst;
  }
  if (out.planeNormal) out.squareness = std::acos(std::clamp(std::abs(out.planeNormal->dot(out.axisDirection)), 0.0, 1.0));
  // Angles from the frame's x about the axis.
  Vec3 x = Vec3::UnitX() - Vec3::UnitX().dot(out.axisDirection) * out.axisDirection;
  x = x.norm() > 1e-6 ? Vec3(x.normalized()) : Vec3(out.axisDirection.unitOrthogonal());
  const Vec3 y = out.axisDirection.cross(x);
  const auto angles = [&](MeasuredSection& m, const std::vector<Vec3>& pts, const Line& reference, double slant) {
    m.height = (m.circle.centre - out.axisPoint).dot(out.axisDirection);
    m.axisOffset = distanceFromLine(m.circle.centre, reference);
    for (size_t i = 0; i < pts.size(); ++i) {
      const Vec3 w = pts[i] - m.circle.centre;
      const double phi = std::atan2(w.dot(y), w.dot(x));
      m.phi.push_back(phi < 0 ? phi + 2 * std::numbers::pi : phi);
      m.normal.push_back(m.radial[i] * std::cos(slant));
    }
  };
  for (size_t k = 0; k < out.cone.size(); ++k) angles(out.cone[k], in.cone[k].points, datum ? *datum : coneAxis, halfAngle);
  for (size_t k = 0; k < out.cylinder.size(); ++k) angles(out.cylinder[k], in.cylinder[k].points, datum ? *datum : coneAxis, 0.0);
  return out;
}

}  // namespace mtacc
