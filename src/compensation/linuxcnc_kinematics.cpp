#include "mtacc/compensation/linuxcnc_kinematics.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

using Module = LinuxcncKinematics::Module;

constexpr double kNominalFit = 1e-6;  // mm: the nominal machine must be LinuxCNC's to rounding
// An error alone is carried when the fit leaves less of it than this (mm), or than this share of its
// effect: the pins carry errors exactly up to second-order terms of micrometres over hundreds of mm.
constexpr double kCarriedLeft = 1e-6, kCarriedShare = 1e-3;

struct TablePose {  // a pose in LinuxCNC's terms
  Vec3 world;
  double tilt, c;  // rad, LinuxCNC's angles
};

// The machine's commanded axes in LinuxCNC's roles, and how its commands follow from the joints.
struct Roles {
  size_t x, y, z, tilt, c;
  Module module;
  std::array<int, 2> sign{1, 1};
};

// What a fit moves: the pins, where LinuxCNC's world origin lies in the machine's workpiece
// coordinates (the work offset a probed workpiece sets), and the machine's commands at the joints' zero.
struct Solution {
  LinuxcncKinematics p;
  Vec3 origin = Vec3::Zero();
  Vec3 jointOrigin = Vec3::Zero();
};

// The values a fit moves: the work offset alone, or with the module's pins. The trt pins fix the
// lines in the joints' frame, so the joints' zero stays; 5axiskins moves everything with the
// joints, so its joints' zero is the work offset; maxkins turns the world about its origin, so the
// joints' zero places the C line and the world origin's height is the joints' zero's.
std::vector<double*> freeValues(Solution& s, bool withPins) {
  Vec3& o = s.origin;
  if (!withPins) return {&o.x(), &o.y(), &o.z()};
  LinuxcncKinematics& p = s.p;
  switch (p.module) {
    case Module::XyzacTrt: return {&p.xRotPoint, &p.yRotPoint, &p.yOffset, &p.zOffset, &o.x(), &o.y(), &o.z()};
    case Module::XyzbcTrt: return {&p.xRotPoint, &p.yRotPoint, &p.xOffset, &p.zOffset, &o.x(), &o.y(), &o.z()};
    case Module::FiveAxis: return {&p.pivotLength, &o.x(), &o.y(), &o.z()};
    case Module::Max: return {&p.pivotLength, &s.jointOrigin.x(), &s.jointOrigin.y(), &s.jointOrigin.z(), &o.x(), &o.y()};
  }
  return {};
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
    const Vec3 joints = s.p.joints(poses[k].world, poses[k].tilt, poses[k].c) + s.jointOrigin;
    const std::vector<double> q = commands(roles, count, joints, poses[k]);
    r.segment<3>(3 * static_cast<Eigen::Index>(k)) = toolPoint(model, q.data()).position - s.origin - poses[k].world;
  }
  return r;
}

// The residual's derivatives by the free values (central differences: the joints are affine in them).
Eigen::MatrixXd residualJacobian(const KinematicModel& model, const Roles& roles, const Solution& s, const std::vector<TablePose>& poses,
                                 bool withPins) {
  constexpr double h = 1e-3;  // mm
  Solution probe = s;
  const std::vector<double*> values = freeValues(probe, withPins);
  Eigen::MatrixXd j(3 * static_cast<Eigen::Index>(poses.size()), static_cast<Eigen::Index>(values.size()));
  for (size_t k = 0; k < values.size(); ++k) {
    const double v = *values[k];
    *values[k] = v + h;
    const Eigen::VectorXd plus = residual(model, roles, probe, poses);
    *values[k] = v - h;
    j.col(static_cast<Eigen::Index>(k)) = (plus - residual(model, roles, probe, poses)) / (2.0 * h);
    *values[k] = v;
  }
  return j;
}

// Gauss-Newton: the joints are affine in the free values and the machine nearly so over their
// micrometres, so a few steps converge.
Solution fit(const KinematicModel& model, const Roles& roles, Solution s, const std::vector<TablePose>& poses, bool withPins) {
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::VectorXd step =
        residualJacobian(model, roles, s, poses, withPins).colPivHouseholderQr().solve(-residual(model, roles, s, poses));
    const std::vector<double*> values = freeValues(s, withPins);
    for (size_t k = 0; k < values.size(); ++k) *values[k] += step[static_cast<Eigen::Index>(k)];
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
    throw InputError(at, "LinuxCNC's 5-axis kinematics need the commanded axes X, Y, Z, A or B, and C");
  const int tilt = a >= 0 ? a : b;
  for (int linear : {x, y, z})
    if (m.axes[static_cast<size_t>(linear)].isRotary()) throw InputError(at, "LinuxCNC's 5-axis kinematics need linear X, Y, Z");
  const auto place = [](const std::vector<int>& chain, int axis) { return std::find(chain.begin(), chain.end(), axis) - chain.begin(); };
  const auto& table = m.workpieceChain;
  const auto& head = m.toolChain;
  const bool tiltOnTable = place(table, tilt) < std::ssize(table), cOnTable = place(table, c) < std::ssize(table);
  const std::string tiltName = m.axes[static_cast<size_t>(tilt)].name;
  Module module;
  if (tiltOnTable && cOnTable && place(table, c) > place(table, tilt))
    module = tiltName == "A" ? Module::XyzacTrt : Module::XyzbcTrt;
  else if (!tiltOnTable && !cOnTable && tiltName == "B" && place(head, c) < place(head, tilt))
    module = Module::FiveAxis;
  else if (!tiltOnTable && cOnTable && tiltName == "B")
    module = Module::Max;
  else
    throw InputError(at, fmt::format("LinuxCNC's 5-axis kinematics need a table tilting about {0} that carries the C table (trt), "
                                     "a head tilting about B on a head turning about C (5axiskins), or a head tilting about B over a "
                                     "C table (maxkins); this machine has {0} on the {1} and C on the {2}",
                                     tiltName, tiltOnTable ? "table" : "head", cOnTable ? "table" : "head"));
  return {static_cast<size_t>(x), static_cast<size_t>(y), static_cast<size_t>(z), static_cast<size_t>(tilt), static_cast<size_t>(c), module};
}

bool withinTravel(const Machine& m, const std::vector<double>& q) {
  for (size_t k = 0; k < q.size(); ++k) {
    const auto& travel = m.axes[k].travel;
    if (travel && (q[k] < travel->min - 1e-9 || q[k] > travel->max + 1e-9)) return false;
  }
  return true;
}

double largestPerPose(const Eigen::VectorXd& r) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < r.size(); k += 3) largest = std::max(largest, r.segment<3>(k).norm());
  return largest;
}

// Each error of the model alone, at the nominal pins: what of its effect over the poses the pins
// and the work offset leave (to first order, exact for the errors they carry). Named when it is not
// nothing; the reversals and stiffness changes, which standing kinematics never see, by kind.
std::vector<std::string> notCarried(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const Roles& roles,
                                    const Solution& exact, const std::vector<TablePose>& poses) {
  const Machine& m = *machine;
  const KinematicModel nominal = compileNominal(machine);
  const Eigen::VectorXd base = residual(nominal, roles, exact, poses);
  const Eigen::MatrixXd pins = residualJacobian(nominal, roles, exact, poses, true);
  const auto carried = pins.colPivHouseholderQr();
  std::vector<std::string> left;
  for (const Parameter& p : nonZeroParameters(m, errors)) {
    const ErrorModel alone = singleError(m, errors, p, parameterValue(errors, p));
    const Eigen::VectorXd effect = residual(compile(machine, alone), roles, exact, poses) - base;
    const double largest = largestPerPose(effect), rest = largestPerPose(effect - pins * carried.solve(effect));
    if (rest > std::max(kCarriedLeft, kCarriedShare * largest))
      left.push_back(fmt::format("{} (leaves {:.3f} um; {:.3f} um uncorrected)", p.name, rest * 1e3, largest * 1e3));
  }
  if (const auto reversal = reversalFunctions(m, errors); !reversal.empty())
    left.push_back(fmt::format("the reversal terms of {} (the kinematics have no direction of motion)", fmt::join(reversal, ", ")));
  if (!errors.stiffness.empty())
    left.push_back(fmt::format("{} changes of component errors with another axis or the load (the kinematics are rigid)", errors.stiffness.size()));
  return left;
}

}  // namespace

std::string LinuxcncKinematics::name() const {
  switch (module) {
    case Module::XyzacTrt: return "xyzac-trt-kins";
    case Module::XyzbcTrt: return "xyzbc-trt-kins";
    case Module::FiveAxis: return "5axiskins";
    case Module::Max: return "maxkins";
  }
  return {};
}

std::string LinuxcncKinematics::carries() const {
  switch (module) {
    case Module::FiveAxis: return "the pivot length";
    case Module::Max: return "the pivot length and, with the joints' zero, the C line's position";
    case Module::XyzacTrt:
    case Module::XyzbcTrt: return fmt::format("the positions of the {} and C axis lines", tilt());
  }
  return {};
}

Vec3 LinuxcncKinematics::joints(const Vec3& world, double tiltAngle, double cAngle) const {
  const double st = std::sin(tiltAngle), ct = std::cos(tiltAngle), sc = std::sin(cAngle), cc = std::cos(cAngle);
  switch (module) {
    case Module::FiveAxis: return world - pivotLength * Vec3(st * cc, st * sc, 1.0 - ct);
    case Module::Max:
      return Vec3(cc * world.x() + sc * world.y() + (conventionalDirections ? 1.0 : -1.0) * pivotLength * st,
                  -sc * world.x() + cc * world.y(), world.z() - pivotLength * (1.0 - ct));
    case Module::XyzacTrt:
    case Module::XyzbcTrt: {
      const Vec3 r(xRotPoint, yRotPoint, 0.0);
      const Vec3 d = tilt() == 'A' ? Vec3(0.0, yOffset, zOffset) : Vec3(xOffset, 0.0, zOffset);
      const Eigen::AngleAxisd tiltRotation(tiltAngle, tilt() == 'A' ? Vec3::UnitX() : Vec3::UnitY());
      return tiltRotation * (Eigen::AngleAxisd(cAngle, Vec3::UnitZ()) * (world - r) - d) + r + d;
    }
  }
  return world;
}

std::vector<std::pair<std::string, double>> LinuxcncKinematics::pins() const {
  switch (module) {
    case Module::FiveAxis: return {{"pivot-length", pivotLength}};
    case Module::Max: return {{"pivot-length", pivotLength}, {"conventional-directions", conventionalDirections ? 1.0 : 0.0}};
    case Module::XyzacTrt:
    case Module::XyzbcTrt:
      return {{"x-rot-point", xRotPoint}, {"y-rot-point", yRotPoint}, {"z-rot-point", 0.0},
              {"x-offset", xOffset},      {"y-offset", yOffset},      {"z-offset", zOffset}};
  }
  return {};
}

LinuxcncKinematicsFit fitLinuxcncKinematics(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors) {
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
    if (!travel) throw InputError({m.sourceFile, 0, m.axes[axis].name}, "the fit of LinuxCNC's kinematics parameters needs the axis's travel");
    const double middle = 0.5 * (travel->min + travel->max), quarter = 0.25 * (travel->max - travel->min);
    lattice[static_cast<size_t>(k)] = {middle - quarter, middle, middle + quarter};
  }
  for (double t : tilts)
    for (double c : cs)
      for (double x : lattice[0])
        for (double y : lattice[1])
          for (double z : lattice[2]) poses.push_back({{x, y, z}, t, c});
  // The machine's commands are LinuxCNC's angles times a sign each: the signs the nominal machine fits with.
  Solution start;
  start.p.module = r.module;
  start.origin = toolPoint(nominal, home.data()).position;
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
    throw InputError({m.sourceFile, 0, "axes"},
                     fmt::format("the nominal machine is not LinuxCNC's {} (its best fit leaves {:.3g} mm)", start.p.name(), best));
  // maxkins' conventional-directions turns B the other way: the pin in place of a sign.
  if (r.module == Module::Max && r.sign[0] < 0) {
    r.sign[0] = 1;
    exact.p.conventionalDirections = true;
    for (TablePose& pose : poses) pose.tilt = -pose.tilt;
  }
  std::erase_if(poses, [&](const TablePose& pose) {
    return !withinTravel(m, commands(r, count, exact.p.joints(pose.world, pose.tilt, pose.c) + exact.jointOrigin, pose));
  });
  if (poses.size() < 10) throw InputError({m.sourceFile, 0, "axes"}, "fewer than 10 poses of the fit lie within travel");
  // Before: the nominal pins, the workpiece probed (its work offset fitted); after: both fitted.
  const Solution withNominal = fit(actual, r, exact, poses, false), fitted = fit(actual, r, exact, poses, true);
  LinuxcncKinematicsFit f;
  f.nominal = exact.p;
  f.actual = fitted.p;
  f.sign = r.sign;
  f.worldOrigin = exact.origin;
  f.workOffset = fitted.origin - exact.origin;
  f.jointOrigin = exact.jointOrigin;
  f.jointOriginShift = fitted.jointOrigin - exact.jointOrigin;
  f.notCarried = notCarried(machine, errors, r, exact, poses);

  const Eigen::VectorXd before = residual(actual, r, withNominal, poses), after = residual(actual, r, fitted, poses);
  auto& res = f.residual;
  res.samples = static_cast<int>(poses.size());
  res.beforeMax = largestPerPose(before);
  res.afterMax = largestPerPose(after);
  res.beforeRms = std::sqrt(before.squaredNorm() / res.samples);
  res.afterRms = std::sqrt(after.squaredNorm() / res.samples);
  return f;
}

CommandCorrection linuxcncCorrection(const std::shared_ptr<const Machine>& machine, const LinuxcncKinematicsFit& f) {
  Roles r = roles(*machine);
  r.sign = f.sign;
  const auto nominal = std::make_shared<const KinematicModel>(compileNominal(machine));
  return [r, nominal, f](const std::vector<double>& q) -> Vec3 {
    const Vec3 world = toolPoint(*nominal, q.data()).position - f.worldOrigin - f.workOffset;
    const Vec3 joints = f.actual.joints(world, r.sign[0] * q[r.tilt], r.sign[1] * q[r.c]) + f.jointOrigin + f.jointOriginShift;
    return joints - Vec3(q[r.x], q[r.y], q[r.z]);
  };
}

std::string linuxcncKinematicsHal(const Machine& machine, const LinuxcncKinematicsFit& f) {
  const LinuxcncKinematics& p = f.actual;
  const std::string kins = p.name(), tilt(1, p.tilt());
  const auto& res = f.residual;
  const bool trt = p.module == Module::XyzacTrt || p.module == Module::XyzbcTrt;
  // No "-0.000000" from rounding noise: below half the printed resolution is zero.
  const auto shown = [](double mm, double resolution = 1e-6) { return std::abs(mm) < 0.5 * resolution ? 0.0 : mm; };
  const auto vec = [&](const Vec3& v) { return fmt::format("({:.6f}, {:.6f}, {:.6f})", shown(v.x()), shown(v.y()), shown(v.z())); };
  std::string out = fmt::format(
      "# mtacc: LinuxCNC {} parameters (mm) for {}, fitted to its error model over {} poses within travel\n"
      "# TCP position error left: largest {:.3f} um, RMS {:.3f} um (with the nominal parameters: {:.3f} um, {:.3f} um)\n"
      "# carries {}\n",
      kins, machine.name, res.samples, res.afterMax * 1e3, res.afterRms * 1e3, res.beforeMax * 1e3, res.beforeRms * 1e3, p.carries());
  for (const auto& left : f.notCarried) out += "# not carried: " + left + "\n";
  out += fmt::format("# joints: {} = {:+d} x the machine's {}, C = {:+d} x its C{}; world = the machine's workpiece coordinates less {} mm;\n"
                     "# the machine with its errors needs the work offset {} mm besides (G54, as probing the workpiece at the rotary axes' 0 finds it)\n",
                     tilt, f.sign[0], tilt, f.sign[1], p.module == Module::Max ? "" : " (the module's default directions)", vec(f.worldOrigin),
                     vec(f.workOffset));
  if (p.module == Module::Max)
    out += fmt::format("# joints X, Y, Z = the machine's X, Y, Z less {} mm (nominal; the tool tip on the C line at B = 0), less {} mm more on the\n"
                       "# machine with its errors: set through the joints' HOME_OFFSET\n",
                       vec(f.jointOrigin), vec(f.jointOriginShift));
  out += trt ? "# for the machine file's tool: tool-offset adds to z-offset\n"
             : "# pivot-length is to the machine file's tool tip: add another tool's length offset to it\n";
  auto it = std::back_inserter(out);
  for (const auto& [pin, value] : p.pins())
    if (pin == "conventional-directions")
      fmt::format_to(it, "setp {}.{} {}\n", kins, pin, static_cast<int>(value));
    else
      fmt::format_to(it, "setp {}.{} {:.7f}\n", kins, pin, shown(value, 1e-7));
  return out;
}

}  // namespace mtacc
