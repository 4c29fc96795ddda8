#include "mtacc/procedures/cone.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/procedures/circle_fit.hpp"

namespace mtacc {
namespace {

Mat3 coneRotation(const ConeSpec& s) { return rotationAbout(Vec3::UnitZ(), s.gamma) * rotationAbout(Vec3::UnitY(), s.beta); }

}  // namespace

std::optional<ConeSpec> conePreset(const std::string& name) {
  ConeSpec s;  // alpha 45, beta 30, r 40 (§3.6.1)
  if (name == "tilting-table") {
    s.centre = Vec3(-65.0, 0.0, 150.0);  // §3.6.4: x0 = -r_table + r cos(beta), z0 = 150 (Table 3.6)
  } else if (name == "swivel-head") {
    s.centre = Vec3(100.0 - 40.0 * std::cos(s.beta), 0.0, 0.0);  // §3.6.3, eq. 3.60 with r_table = 100
  } else if (name == "double-pivot") {
    s.alpha = -45 * kDeg;  // §3.6.2: upside-down, gamma 45 deg
    s.gamma = 45 * kDeg;
    s.centre = Vec3(0.0, 0.0, 0.0);
  } else if (name == "seed000-comparison") {
    s.radius = 44.8;  // Table 3.6 (L4202-4222), alpha and beta swapped in print (erratum, reference §6.3)
    s.centre = Vec3(48.9, 0.0, 66.1);
  } else if (name == "nas979") {
    s.alpha = 15 * kDeg;  // 30 deg apex angle, 10 inch diameter, Z rises 1 inch over 180 deg (§2.1)
    s.beta = std::asin(0.1);
    s.radius = 127.0;
    s.centre = Vec3(0.0, 0.0, 0.0);
  } else {
    return std::nullopt;
  }
  return s;
}

std::string conePresetNames() { return "tilting-table, swivel-head, double-pivot, seed000-comparison, nas979"; }

std::optional<std::string> conePresetName(const Machine& machine) {
  int tool = 0, workpiece = 0;
  for (const auto& a : machine.axes)
    if (a.type == AxisType::Rotary) ++(a.side == Side::Tool ? tool : workpiece);
  if (tool + workpiece != 2) return std::nullopt;
  return workpiece == 2 ? "tilting-table" : tool == 2 ? "double-pivot" : "swivel-head";
}

ConePath conePath(const ConeSpec& s, int n) {
  ConePath p;
  const Mat3 r = coneRotation(s);
  const double sa = std::sin(s.alpha), ca = std::cos(s.alpha);
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * kPi * i / n, c = std::cos(phi), sn = std::sin(phi);
    const Vec3 normal = r * Vec3(ca * c, ca * sn, sa);
    p.phi.push_back(phi);
    p.points.push_back(s.centre + r * Vec3(s.radius * c, s.radius * sn, 0.0));
    p.normals.push_back(normal);
    p.tools.push_back(s.faceMilling ? normal : r * Vec3(-sa * c, -sa * sn, ca));
  }
  return p;
}

int pointsForChordTolerance(const ConeSpec& s, double tolerance) {
  const double half = std::acos(std::clamp(1.0 - tolerance / std::abs(s.radius), -1.0, 1.0));
  return static_cast<int>(std::clamp(std::ceil(kPi / std::max(half, 1e-9)), 8.0, 1e9));
}

RotaryRanges rotaryRangesClosedForm(double alphaSigned, double betaSigned, bool startAtPole) {
  // An upside-down cone (alpha < 0) runs through the same tilts half a turn later.
  const double alpha = std::abs(alphaSigned), beta = std::abs(betaSigned);
  if (std::abs(alpha - beta) < 1e-12) {
    if (startAtPole) return {0.0, 2 * alpha, 2 * alpha, kPi, "alpha = beta, start at the pole (phi = 0)"};
    return {-2 * beta, 2 * beta, 4 * alpha, kPi, "alpha = beta, start at phi = 180 deg"};
  }
  if (alpha > beta) return {alpha - beta, alpha + beta, 2 * beta, 2 * kPi, "alpha > beta"};
  const double t = std::tan(alpha) / std::tan(beta);
  const double cMax = std::atan(std::tan(alpha) / (std::sin(beta) * std::sqrt(1.0 - t * t)));  // eq. 3.38
  return {beta - alpha, alpha + beta, 2 * alpha, 2 * cMax, "alpha < beta"};
}

double rotarySpeedFactorAtStart(double alpha, double beta) {
  const double d = std::sin(alpha - beta);
  return d == 0.0 ? std::numeric_limits<double>::infinity() : std::sin(alpha) / d;
}

ConeMotion coneMotion(const KinematicModel& nominal, const ConeSpec& spec, const ConePath& path, const ConeDrive& drive) {
  const TiltBranch branch = drive.branch;
  const double feed = drive.feed;
  const Machine& m = *nominal.machine;
  ConeMotion out;
  const double gap = std::abs(spec.alpha - spec.beta);
  if (gap < 1e-9) {
    out.warnings.push_back(
        "singular set-up alpha = beta: at phi = 0 the tool is parallel to the rotary axis nearest the workpiece "
        "(tilt 0, rotary angle undefined, seed 000 §3.4.3). The path passes the pole with the tilt axis changing "
        "sign (option 2: continuous, the table turns once for two turns around the cone); option 1, stopping at "
        "the pole while the rotary axis turns 180 deg, is not continuous.");
  } else if (gap < 1.0 * kDeg) {
    const double k = rotarySpeedFactorAtStart(spec.alpha, spec.beta);
    out.warnings.push_back(fmt::format(
        "near-singular set-up |alpha - beta| = {:.3g} deg < 1 deg: dC/dphi at phi = 0 is sin(alpha)/sin(alpha - beta) "
        "= {:.4g}, so at {:g} mm/min the rotary axis needs {:.4g} deg/s (seed 000 §3.4.4)",
        gap / kDeg, k, feed, std::abs(k) * feed / spec.radius / kDeg / 60.0));
  }
  // Solve one extra point at phi = 2 pi to know how the path closes (a full turn of C).
  std::vector<Vec3> points = path.points, tools = path.tools;
  points.push_back(path.points.front());
  tools.push_back(path.tools.front());
  IkOptions o;
  o.branch = branch;
  const auto sol = solveIkPath(nominal, points, tools, o);
  const size_t n = path.points.size();
  const int axes = nominal.jointCount;
  out.q.resize(static_cast<Eigen::Index>(n), axes);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < axes; ++k) out.q(static_cast<Eigen::Index>(i), k) = sol[i].q[static_cast<size_t>(k)];
  std::vector<double> shift(static_cast<size_t>(axes));
  for (int k = 0; k < axes; ++k) shift[static_cast<size_t>(k)] = sol[n].q[static_cast<size_t>(k)] - sol[0].q[static_cast<size_t>(k)];
  auto at = [&](long i, int k) {  // periodic access, with the closing shift of each axis
    const long w = ((i % static_cast<long>(n)) + static_cast<long>(n)) % static_cast<long>(n);
    const double turns = std::floor(static_cast<double>(i) / static_cast<double>(n));
    return out.q(w, k) + turns * shift[static_cast<size_t>(k)];
  };
  const double dphi = 2.0 * kPi / static_cast<double>(n);
  const double phiDot = feed / std::abs(spec.radius);  // rad/min
  out.direction = DirectionMatrix::Zero(static_cast<Eigen::Index>(n), axes);
  for (int k = 0; k < axes; ++k) {
    AxisMotion a;
    a.axis = m.axes[static_cast<size_t>(k)].name;
    a.min = a.max = at(0, k);
    std::vector<double> slope(n);
    for (size_t i = 0; i <= n; ++i) {  // the closing point belongs to the path: a full turn spans 360 deg
      const double v = at(static_cast<long>(i), k);
      a.min = std::min(a.min, v);
      a.max = std::max(a.max, v);
    }
    for (size_t i = 0; i < n; ++i) {
      const long li = static_cast<long>(i);
      const double v = at(li, k);
      slope[i] = (at(li + 1, k) - at(li - 1, k)) / (2 * dphi);
      const double curvature = (at(li + 1, k) - 2 * v + at(li - 1, k)) / (dphi * dphi);
      a.maxSpeed = std::max(a.maxSpeed, std::abs(slope[i]) * phiDot);
      a.maxAcceleration = std::max(a.maxAcceleration, std::abs(curvature) * phiDot * phiDot);
    }
    a.range = a.max - a.min;
    a.moves = a.range > 1e-9 * std::max({1.0, std::abs(a.min), std::abs(a.max)});
    // A reversal is a change of the sign of motion, standing still in between allowed.
    const double still = 1e-9 * std::max(1.0, a.range);
    auto sign = [&](size_t i) { return slope[i] > still ? 1 : (slope[i] < -still ? -1 : 0); };
    int previous = 0;
    for (size_t i = n; i-- > 0 && previous == 0;) previous = sign(i);
    for (size_t i = 0; i < n; ++i) {
      const int s = sign(i);
      out.direction(static_cast<Eigen::Index>(i), k) = s;
      if (s != 0 && previous != 0 && s != previous) a.reversalsPhi.push_back(path.phi[i]);
      if (s != 0) previous = s;
    }
    out.axes.push_back(std::move(a));
  }
  return out;
}

FormErrorType formErrorType(const std::vector<double>& e) {
  const size_t n = e.size();
  double symmetric = 0.0, antisymmetric = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double mirror = e[(n - i) % n];  // value at -phi
    symmetric += 0.25 * (e[i] + mirror) * (e[i] + mirror);
    antisymmetric += 0.25 * (e[i] - mirror) * (e[i] - mirror);
  }
  return symmetric >= antisymmetric ? FormErrorType::TopBottom : FormErrorType::Asymmetric;
}

const char* toString(FormErrorType t) { return t == FormErrorType::TopBottom ? "top-bottom" : "asymmetric"; }

void removeFirstHarmonic(const std::vector<double>& phi, std::vector<double>& values) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < phi.size(); ++i) {
    const Eigen::Vector3d row(1.0, std::cos(phi[i]), std::sin(phi[i]));
    ata += row * row.transpose();
    atb += row * values[i];
  }
  const Eigen::Vector3d c = ata.ldlt().solve(atb);
  for (size_t i = 0; i < phi.size(); ++i) values[i] -= c[0] + c[1] * std::cos(phi[i]) + c[2] * std::sin(phi[i]);
}

namespace {

ConeFormResult finish(const ConePath& path, std::vector<double> e) {
  ConeFormResult r;
  r.rawDeviation = e;
  removeFirstHarmonic(path.phi, e);
  const auto [lo, hi] = std::minmax_element(e.begin(), e.end());
  r.formError = *hi - *lo;
  r.deviation = std::move(e);
  return r;
}

std::vector<Vec3> actualPoints(const KinematicModel& actual, const ConeMotion& motion) {
  std::vector<Vec3> pts;
  pts.reserve(static_cast<size_t>(motion.q.rows()));
  for (Eigen::Index i = 0; i < motion.q.rows(); ++i)
    pts.push_back(toolPosition(actual, motion.q.row(i).data(), motion.direction.row(i).data()));
  return pts;
}

}  // namespace

ConeFormResult coneFormErrorExact(const KinematicModel& actual, const ConeSpec& spec, const ConePath& path,
                                  const ConeMotion& motion) {
  const auto pts = actualPoints(actual, motion);
  const size_t n = pts.size();
  const CircleFit circle = fitCircle(pts, coneRotation(spec) * Vec3::UnitZ());
  const Vec3& axis = circle.normal;
  const Vec3& centre = circle.centre;
  const double radius = circle.radius;
  // Normal distance of each point from the cone through the fitted circle (general alpha form
  // of the distance from C*, seed 000 §3.9 / reference §4.1 step 6).
  const double sa = std::sin(spec.alpha), ca = std::cos(spec.alpha);
  std::vector<double> e(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 w = pts[i] - centre;
    const double z = w.dot(axis);
    const double rho = (w - z * axis).norm();
    e[i] = (rho - radius) * ca + z * sa;
  }
  return finish(path, std::move(e));
}

ConeFormResult coneFormErrorFirstOrder(const KinematicModel& actual, const KinematicModel& nominal, const ConePath& path,
                                       const ConeMotion& motion) {
  const auto pts = actualPoints(actual, motion);
  std::vector<double> e(pts.size());
  for (size_t i = 0; i < pts.size(); ++i)
    e[i] = path.normals[i].dot(pts[i] - toolPosition(nominal, motion.q.row(static_cast<Eigen::Index>(i)).data()));
  return finish(path, std::move(e));
}

}  // namespace mtacc
