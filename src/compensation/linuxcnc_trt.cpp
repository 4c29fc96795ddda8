#include "mtacc/compensation/linuxcnc_trt.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

constexpr double kNominalFit = 1e-6;  // mm: the nominal machine must be LinuxCNC's to rounding

struct TablePose {  // a pose of the table in LinuxCNC's terms
  Vec3 world;
  double tilt, c;  // rad, LinuxCNC's angles
};

// The machine's commanded axes in LinuxCNC's roles, and how its commands follow from the joints.
struct Roles {
  size_t x, y, z, tilt, c;
  std::array<int, 2> sign{1, 1};
};

// What the fit moves: the parameters (x-rot-point, y-rot-point, the tilting line's offset across
// its own direction: x for B, y for A; z-offset), and where LinuxCNC's world origin lies in the
// machine's workpiece coordinates (the work offset a probed workpiece sets).
struct Solution {
  LinuxcncTrt p;
  Vec3 origin = Vec3::Zero();
};
using Unknowns = Eigen::Matrix<double, 7, 1>;

Unknowns unknowns(const Solution& s) {
  Unknowns v;
  v << s.p.xRotPoint, s.p.yRotPoint, s.p.tilt == 'A' ? s.p.yOffset : s.p.xOffset, s.p.zOffset, s.origin;
  return v;
}

Solution withUnknowns(Solution s, const Unknowns& v) {
  s.p.xRotPoint = v[0];
  s.p.yRotPoint = v[1];
  (s.p.tilt == 'A' ? s.p.yOffset : s.p.xOffset) = v[2];
  s.p.zOffset = v[3];
  s.origin = v.tail<3>();
  return s;
}

std::vector<double> commands(const Roles& roles, size_t count, const Vec3& joints, const TablePose& pose) {
  std::vector<double> q(count, 0.0);
  q[roles.x] = joints.x();
  q[roles.y] = joints.y();
  q[roles.z] = joints.z();
  q[roles.tilt] = roles.sign[0] * pose.tilt;
  q[roles.c] = roles.sign[1] * pose.c;
  return q;
}

// Where the tool point is, relative to where LinuxCNC puts it, over the poses (mm, x y z per pose).
Eigen::VectorXd residual(const KinematicModel& model, const Roles& roles, const Solution& s, const std::vector<TablePose>& poses) {
  Eigen::VectorXd r(3 * static_cast<Eigen::Index>(poses.size()));
  const auto count = static_cast<size_t>(model.machine->commandedCount());
  for (size_t k = 0; k < poses.size(); ++k) {
    const std::vector<double> q = commands(roles, count, s.p.joints(poses[k].world, poses[k].tilt, poses[k].c), poses[k]);
    r.segment<3>(3 * static_cast<Eigen::Index>(k)) = toolPoint(model, q.data()).position - s.origin - poses[k].world;
  }
  return r;
}

// Gauss-Newton: the joints are affine in the unknowns and the machine nearly so over their
// micrometres, so a few steps converge. `withParameters` false: the work offset alone.
Solution fit(const KinematicModel& model, const Roles& roles, Solution s, const std::vector<TablePose>& poses, bool withParameters) {
  constexpr double h = 1e-3;  // mm
  const int first = withParameters ? 0 : 4;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Unknowns v = unknowns(s);
    const Eigen::VectorXd r = residual(model, roles, s, poses);
    Eigen::MatrixXd j(r.size(), 7 - first);
    for (int k = first; k < 7; ++k) {
      Unknowns plus = v, minus = v;
      plus[k] += h;
      minus[k] -= h;
      j.col(k - first) = (residual(model, roles, withUnknowns(s, plus), poses) - residual(model, roles, withUnknowns(s, minus), poses)) / (2.0 * h);
    }
    const Eigen::VectorXd step = j.colPivHouseholderQr().solve(-r);
    Unknowns next = v;
    next.tail(7 - first) += step;
    s = withUnknowns(s, next);
    if (step.norm() < 1e-12) break;
  }
  return s;
}

std::vector<double> spread(double low, double high, int count, bool closed) {
  std::vector<double> v(static_cast<size_t>(count));
  const double step = (high - low) / (closed ? count - 1 : count);
  for (int k = 0; k < count; ++k) v[static_cast<size_t>(k)] = low + k * step;
  return v;
}

Roles roles(const Machine& m) {
  const int x = m.commandedAxisIndex("X"), y = m.commandedAxisIndex("Y"), z = m.commandedAxisIndex("Z"), a = m.commandedAxisIndex("A"),
            b = m.commandedAxisIndex("B"), c = m.commandedAxisIndex("C");
  const InputLocation at{m.sourceFile, 0, "axes"};
  if (m.commandedCount() != 5 || x < 0 || y < 0 || z < 0 || c < 0 || (a < 0) == (b < 0))
    throw InputError(at, "LinuxCNC's trt kinematics need the commanded axes X, Y, Z, A or B, and C");
  const int tilt = a >= 0 ? a : b;
  for (int linear : {x, y, z})
    if (m.axes[static_cast<size_t>(linear)].isRotary()) throw InputError(at, "LinuxCNC's trt kinematics need linear X, Y, Z");
  const auto& chain = m.workpieceChain;
  const auto tiltAt = std::find(chain.begin(), chain.end(), tilt), cAt = std::find(chain.begin(), chain.end(), c);
  if (tiltAt == chain.end() || cAt == chain.end() || cAt < tiltAt)
    throw InputError(at, fmt::format("LinuxCNC's trt kinematics need a table tilting about {} that carries the C table",
                                     m.axes[static_cast<size_t>(tilt)].name));
  return {static_cast<size_t>(x), static_cast<size_t>(y), static_cast<size_t>(z), static_cast<size_t>(tilt), static_cast<size_t>(c)};
}

bool withinTravel(const Machine& m, const std::vector<double>& q) {
  for (size_t k = 0; k < q.size(); ++k) {
    const auto& travel = m.axes[k].travel;
    if (travel && (q[k] < travel->min - 1e-9 || q[k] > travel->max + 1e-9)) return false;
  }
  return true;
}

}  // namespace

Vec3 LinuxcncTrt::joints(const Vec3& world, double tiltAngle, double cAngle) const {
  const Vec3 r(xRotPoint, yRotPoint, 0.0);
  const Vec3 d = tilt == 'A' ? Vec3(0.0, yOffset, zOffset) : Vec3(xOffset, 0.0, zOffset);
  const Eigen::AngleAxisd tiltRotation(tiltAngle, tilt == 'A' ? Vec3::UnitX() : Vec3::UnitY());
  return tiltRotation * (Eigen::AngleAxisd(cAngle, Vec3::UnitZ()) * (world - r) - d) + r + d;
}

LinuxcncTrtFit fitLinuxcncTrt(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors) {
  const Machine& m = *machine;
  Roles r = roles(m);
  const KinematicModel nominal = compileNominal(machine), actual = compile(machine, errors);
  const auto count = static_cast<size_t>(m.commandedCount());
  const std::vector<double> home(count, 0.0);

  std::vector<TablePose> poses;
  const auto& tiltTravel = m.axes[r.tilt].travel;
  const auto& cTravel = m.axes[r.c].travel;
  const double halfTurn = std::numbers::pi;
  const std::vector<double> tilts = tiltTravel ? spread(tiltTravel->min, tiltTravel->max, 9, true) : spread(-halfTurn / 2, halfTurn / 2, 9, true);
  const std::vector<double> cs = cTravel ? spread(cTravel->min, cTravel->max, 12, true) : spread(0.0, 2.0 * halfTurn, 12, false);
  std::array<std::vector<double>, 3> lattice;
  for (int k = 0; k < 3; ++k) {
    const size_t axis = k == 0 ? r.x : k == 1 ? r.y : r.z;
    const auto& travel = m.axes[axis].travel;
    if (!travel) throw InputError({m.sourceFile, 0, m.axes[axis].name}, "the fit of LinuxCNC's trt parameters needs the axis's travel");
    const double middle = 0.5 * (travel->min + travel->max), quarter = 0.25 * (travel->max - travel->min);
    lattice[static_cast<size_t>(k)] = {middle - quarter, middle, middle + quarter};
  }
  // The machine's commands are LinuxCNC's angles times a sign each: the signs the nominal machine fits with.
  LinuxcncTrtFit f;
  f.nominal.tilt = f.actual.tilt = m.axes[r.tilt].name == "A" ? 'A' : 'B';
  for (double t : tilts)
    for (double c : cs)
      for (double x : lattice[0])
        for (double y : lattice[1])
          for (double z : lattice[2]) poses.push_back({{x, y, z}, t, c});
  const Solution start{f.nominal, toolPoint(nominal, home.data()).position};
  Solution exact;
  double best = std::numeric_limits<double>::infinity();
  for (int tiltSign : {1, -1})
    for (int cSign : {1, -1}) {
      Roles trial = r;
      trial.sign = {tiltSign, cSign};
      const Solution s = fit(nominal, trial, start, poses, true);
      const double largest = residual(nominal, trial, s, poses).cwiseAbs().maxCoeff();
      if (largest < best) {
        best = largest;
        r.sign = trial.sign;
        exact = s;
      }
    }
  if (best > kNominalFit)
    throw InputError({m.sourceFile, 0, "axes"}, fmt::format("the nominal machine is not LinuxCNC's {} (its best fit leaves {:.3g} mm)",
                                                            f.nominal.kinsName(), best));
  std::erase_if(poses, [&](const TablePose& pose) {
    return !withinTravel(m, commands(r, count, exact.p.joints(pose.world, pose.tilt, pose.c), pose));
  });
  if (poses.size() < 10) throw InputError({m.sourceFile, 0, "axes"}, "fewer than 10 poses of the fit lie within travel");
  // Before: the nominal parameters, the workpiece probed (its work offset fitted); after: both fitted.
  const Solution withNominal = fit(actual, r, exact, poses, false), fitted = fit(actual, r, exact, poses, true);
  f.nominal = exact.p;
  f.actual = fitted.p;
  f.sign = r.sign;
  f.worldOrigin = exact.origin;
  f.workOffset = fitted.origin - exact.origin;

  const Eigen::VectorXd before = residual(actual, r, withNominal, poses), after = residual(actual, r, fitted, poses);
  auto& res = f.residual;
  res.samples = static_cast<int>(poses.size());
  for (size_t k = 0; k < poses.size(); ++k) {
    const auto at = 3 * static_cast<Eigen::Index>(k);
    res.beforeMax = std::max(res.beforeMax, before.segment<3>(at).norm());
    res.afterMax = std::max(res.afterMax, after.segment<3>(at).norm());
  }
  res.beforeRms = std::sqrt(before.squaredNorm() / res.samples);
  res.afterRms = std::sqrt(after.squaredNorm() / res.samples);
  return f;
}

std::string linuxcncTrtHal(const Machine& machine, const LinuxcncTrtFit& f) {
  const LinuxcncTrt& p = f.actual;
  const std::string kins = p.kinsName(), tilt(1, p.tilt);
  const auto& res = f.residual;
  // No "-0.000000" from rounding noise: below half the printed resolution is zero.
  const auto shown = [](double mm, double resolution = 1e-6) { return std::abs(mm) < 0.5 * resolution ? 0.0 : mm; };
  std::string out = fmt::format(
      "# mtacc: LinuxCNC {} parameters (mm) for {}, fitted to its error model over {} poses within travel\n"
      "# TCP position error left: largest {:.3f} um, RMS {:.3f} um (with the nominal parameters: {:.3f} um, {:.3f} um)\n"
      "# carries the positions of the {} and C axis lines; not their orientations or zero offsets, the linear axes' errors, component errors\n"
      "# joints: {} = {:+d} x the machine's {}, C = {:+d} x its C (the default, unconventional directions); world = the machine's\n"
      "# workpiece coordinates less ({:.6f}, {:.6f}, {:.6f}) mm; the machine with its errors needs the work offset\n"
      "# ({:.6f}, {:.6f}, {:.6f}) mm besides (G54, as probing the workpiece at A, B, C = 0 finds it)\n"
      "# for the machine file's tool: tool-offset adds to z-offset\n",
      kins, machine.name, res.samples, res.afterMax * 1e3, res.afterRms * 1e3, res.beforeMax * 1e3, res.beforeRms * 1e3, tilt, tilt, f.sign[0],
      tilt, f.sign[1], shown(f.worldOrigin.x()), shown(f.worldOrigin.y()), shown(f.worldOrigin.z()), shown(f.workOffset.x()),
      shown(f.workOffset.y()), shown(f.workOffset.z()));
  const std::pair<const char*, double> pins[] = {{"x-rot-point", p.xRotPoint}, {"y-rot-point", p.yRotPoint}, {"z-rot-point", 0.0},
                                                 {"x-offset", p.xOffset},      {"y-offset", p.yOffset},      {"z-offset", p.zOffset}};
  auto it = std::back_inserter(out);
  for (const auto& [pin, value] : pins) fmt::format_to(it, "setp {}.{} {:.7f}\n", kins, pin, shown(value, 1e-7));
  return out;
}

}  // namespace mtacc
