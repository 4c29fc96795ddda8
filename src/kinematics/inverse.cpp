#include "mtacc/kinematics/inverse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"

#include "chain_program.hpp"

namespace mtacc {
namespace {

struct RotaryJointRef {
  int joint;
  Vec3 direction;  // in the workpiece-to-tool product, rotation is about this by +q
};

// Rotary joints in the order of the workpiece -> tool product W^-1 * T. Both chains rotate
// by +q about their direction in that product: the workpiece side moves by -q and is
// inverted.
std::vector<RotaryJointRef> rotaryOrder(const KinematicModel& m) {
  std::vector<RotaryJointRef> order;
  for (auto it = m.chains->workpieceChain.rbegin(); it != m.chains->workpieceChain.rend(); ++it)
    if (it->type == AxisType::Rotary) order.push_back({it->joint, it->direction});
  for (const auto& e : m.chains->toolChain)
    if (e.type == AxisType::Rotary) order.push_back({e.joint, e.direction});
  return order;
}

// Angle about unit axis w that turns u onto v (both already with equal components along w).
// Returns nullopt when u lies along w (any angle works).
std::optional<double> angleAbout(const Vec3& w, const Vec3& u, const Vec3& v, double tol) {
  const Vec3 up = u - w.dot(u) * w;
  const Vec3 vp = v - w.dot(v) * w;
  if (up.norm() < tol || vp.norm() < tol) return std::nullopt;
  return std::atan2(w.dot(up.cross(vp)), up.dot(vp));
}

struct AngleSet {
  std::vector<double> angles;  // one per rotary joint in rotaryOrder
  bool singular = false;
  int freeIndex = -1;
};

double hintOrZero(const IkOptions& o, int joint) { return o.hint ? (*o.hint)[static_cast<size_t>(joint)] : 0.0; }

std::vector<AngleSet> orientationSolutions(const std::vector<RotaryJointRef>& rot, const Vec3& u, const Vec3& v,
                                           const IkOptions& o) {
  const double tol = 1e-9;
  if (rot.empty()) {
    if ((u - v).norm() > 1e-9)
      throw UnreachablePose(fmt::format("tool direction ({:.6g}, {:.6g}, {:.6g}) cannot be reached: the machine has no rotary axis", v.x(), v.y(), v.z()));
    return {AngleSet{}};
  }
  if (rot.size() == 1) {
    const Vec3& w = rot[0].direction;
    if (std::abs(w.dot(u) - w.dot(v)) > 1e-9)
      throw UnreachablePose(fmt::format("tool direction ({:.6g}, {:.6g}, {:.6g}) is not reachable with one rotary axis", v.x(), v.y(), v.z()));
    const auto a = angleAbout(w, u, v, o.singularTolerance);
    if (!a) return {AngleSet{{hintOrZero(o, rot[0].joint)}, true, 0}};
    return {AngleSet{{*a}, false, -1}};
  }
  if (rot.size() > 2) throw UnreachablePose("inverse kinematics supports at most two rotary axes");
  // Rot(w1, t1) * Rot(w2, t2) * u = v (Paden-Kahan subproblem 2).
  const Vec3& w1 = rot[0].direction;
  const Vec3& w2 = rot[1].direction;
  const double c12 = w1.dot(w2);
  const double den = 1.0 - c12 * c12;
  if (den < tol) throw UnreachablePose("the two rotary axes are parallel; the tool direction is not controlled");
  const double a1 = w1.dot(v), a2 = w2.dot(u);
  const double alpha = (a1 - c12 * a2) / den;
  const double beta = (a2 - c12 * a1) / den;
  const Vec3 n = w1.cross(w2);
  double g2 = (1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12) / n.squaredNorm();
  if (g2 < -1e-9)
    throw UnreachablePose(fmt::format("tool direction ({:.6g}, {:.6g}, {:.6g}) lies outside the cone the rotary axes can reach", v.x(), v.y(), v.z()));
  g2 = std::max(g2, 0.0);
  std::vector<AngleSet> out;
  const double gs[2] = {std::sqrt(g2), -std::sqrt(g2)};
  for (int k = 0; k < (g2 > 0.0 ? 2 : 1); ++k) {
    const Vec3 z = alpha * w1 + beta * w2 + gs[k] * n;
    AngleSet s;
    s.angles.resize(2);
    const auto t2 = angleAbout(w2, u, z, o.singularTolerance);
    const auto t1 = angleAbout(w1, z, v, o.singularTolerance);
    if (!t2) {
      s.singular = true;
      s.freeIndex = 1;
    }
    if (!t1) {
      s.singular = true;
      s.freeIndex = 0;
    }
    if (t2 && t1) {
      s.angles = {*t1, *t2};
    } else if (!t1 && t2) {
      s.angles = {hintOrZero(o, rot[0].joint), *t2};
    } else {
      // The second axis is free: keep its hint and solve the first for the rest.
      const double free2 = hintOrZero(o, rot[1].joint);
      const Vec3 z2 = rotationAbout(w2, free2) * u;
      const auto t1b = angleAbout(w1, z2, v, o.singularTolerance);
      s.angles = {t1b.value_or(hintOrZero(o, rot[0].joint)), free2};
    }
    out.push_back(s);
  }
  return out;
}

double wrapToPi(double a) { return std::remainder(a, 2.0 * kPi); }

// Equivalent angles a + 2 pi k within travel (continuous: the one nearest the reference).
std::vector<double> equivalents(const Axis& axis, double a, double reference) {
  std::vector<double> out;
  if (!axis.travel) {
    out.push_back(reference + wrapToPi(a - reference));
    return out;
  }
  for (int k = -2; k <= 2; ++k) {
    const double c = a + 2.0 * kPi * k;
    if (c >= axis.travel->min - 1e-9 && c <= axis.travel->max + 1e-9) out.push_back(c);
  }
  if (out.empty()) out.push_back(reference + wrapToPi(a - reference));  // reported beyond travel
  return out;
}

// With the rotary angles fixed, the TCP is affine in the linear joints: solve for them.
bool solveLinear(const KinematicModel& m, std::vector<double>& q, const Vec3& target) {
  std::vector<int> linear;
  for (int i = 0; i < m.jointCount; ++i)
    if (m.machine->axes[static_cast<size_t>(i)].type == AxisType::Linear) linear.push_back(i);
  for (int i : linear) q[static_cast<size_t>(i)] = 0.0;
  const Vec3 f0 = toolInWorkpiece(m, q.data()).translation();
  Eigen::Matrix<double, 3, Eigen::Dynamic> a(3, static_cast<Eigen::Index>(linear.size()));
  for (size_t k = 0; k < linear.size(); ++k) {
    q[static_cast<size_t>(linear[k])] = 1.0;
    a.col(static_cast<Eigen::Index>(k)) = toolInWorkpiece(m, q.data()).translation() - f0;
    q[static_cast<size_t>(linear[k])] = 0.0;
  }
  if (linear.empty()) return (target - f0).norm() < 1e-9;
  const Eigen::VectorXd x = a.colPivHouseholderQr().solve(target - f0);
  for (size_t k = 0; k < linear.size(); ++k) q[static_cast<size_t>(linear[k])] = x[static_cast<Eigen::Index>(k)];
  return (a * x - (target - f0)).norm() < 1e-7 * std::max(1.0, target.norm());
}

}  // namespace

TiltBranch parseTiltBranch(const std::string& name) {
  if (name == "auto") return TiltBranch::Auto;
  if (name == "positive") return TiltBranch::Positive;
  if (name == "negative") return TiltBranch::Negative;
  throw InputError(InputLocation{"", 0, "branch"}, "expected auto, positive or negative, got '" + name + "'");
}

IkResult inverseKinematics(const KinematicModel& m, const Vec3& position, const Vec3& toolDirection,
                           const IkOptions& o) {
  const Machine& machine = *m.machine;
  if (!position.allFinite() || !toolDirection.allFinite() || toolDirection.norm() < 1e-12)
    throw UnreachablePose("pose is not finite or the tool direction is zero");
  const Vec3 v = m.alignment.linear().transpose() * toolDirection.normalized();
  const Vec3 target = position;
  const auto rot = rotaryOrder(m);
  const auto angleSets = orientationSolutions(rot, m.machine->toolDirection, v, o);

  IkResult result;
  for (const auto& set : angleSets) {
    // Cartesian product of the equivalent angles of each rotary axis.
    std::vector<std::vector<double>> combos{{}};
    for (size_t r = 0; r < rot.size(); ++r) {
      const Axis& axis = machine.axes[static_cast<size_t>(rot[r].joint)];
      std::vector<std::vector<double>> next;
      for (const auto& c : combos)
        for (double e : equivalents(axis, set.angles[r], hintOrZero(o, rot[r].joint))) {
          auto n = c;
          n.push_back(e);
          next.push_back(n);
        }
      combos = std::move(next);
    }
    for (const auto& c : combos) {
      IkSolution s;
      s.q.assign(static_cast<size_t>(m.jointCount), 0.0);
      for (size_t r = 0; r < rot.size(); ++r) s.q[static_cast<size_t>(rot[r].joint)] = c[r];
      if (!solveLinear(m, s.q, target))
        throw UnreachablePose(fmt::format("TCP ({:.6g}, {:.6g}, {:.6g}) mm cannot be reached by the linear axes", target.x(), target.y(), target.z()));
      s.singular = set.singular;
      if (set.singular) s.singularAxis = machine.axes[static_cast<size_t>(rot[static_cast<size_t>(set.freeIndex)].joint)].name;
      s.travelViolation = machine.travelViolation(s.q);
      s.withinTravel = s.travelViolation.empty();
      result.solutions.push_back(std::move(s));
    }
  }

  // Preference: within travel; requested tilt sign; closest rotary motion to the hint.
  const int tiltJoint = rot.size() == 2 ? rot[1].joint : -1;
  auto cost = [&](const IkSolution& s) {
    double c = s.withinTravel ? 0.0 : 1e6;
    if (tiltJoint >= 0 && o.branch != TiltBranch::Auto) {
      const double t = s.q[static_cast<size_t>(tiltJoint)];
      const bool ok = o.branch == TiltBranch::Positive ? t >= -1e-12 : t <= 1e-12;
      c += ok ? 0.0 : 1e3;
    }
    for (const auto& r : rot) c += std::abs(s.q[static_cast<size_t>(r.joint)] - hintOrZero(o, r.joint));
    return c;
  };
  std::stable_sort(result.solutions.begin(), result.solutions.end(),
                   [&](const IkSolution& a, const IkSolution& b) { return cost(a) < cost(b); });
  return result;
}

IkSolution solveIk(const KinematicModel& m, const Vec3& position, const Vec3& toolDirection, const IkOptions& o) {
  auto r = inverseKinematics(m, position, toolDirection, o);
  if (r.solutions.empty() || !r.solutions.front().withinTravel)
    throw UnreachablePose(fmt::format("pose TCP ({:.6g}, {:.6g}, {:.6g}) mm, tool ({:.6g}, {:.6g}, {:.6g}) is beyond travel: {}",
                                      position.x(), position.y(), position.z(), toolDirection.x(), toolDirection.y(),
                                      toolDirection.z(),
                                      r.solutions.empty() ? "no solution" : r.solutions.front().travelViolation));
  return r.solutions.front();
}

std::vector<IkSolution> solveIkPath(const KinematicModel& m, const std::vector<Vec3>& positions,
                                    const std::vector<Vec3>& directions, const IkOptions& options) {
  std::vector<IkSolution> out;
  IkOptions o = options;
  for (size_t i = 0; i < positions.size(); ++i) {
    try {
      out.push_back(solveIk(m, positions[i], directions[i], o));
    } catch (const UnreachablePose& e) {
      throw UnreachableTarget(i, e.what());
    }
    o.hint = out.back().q;
    o.branch = TiltBranch::Auto;
  }
  return out;
}

}  // namespace mtacc
