#include "mtacc/compensation/linuxcnc_kinematics.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"

#include "controller_kinematics_fit.hpp"

namespace mtacc {
namespace {

using Module = LinuxcncKinematics::Module;
using controller_fit::ControllerPose;

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

std::vector<double> commands(const Roles& roles, size_t count, const Solution& s, const ControllerPose& pose) {
  const Vec3 joints = s.p.joints(pose.world, pose.first, pose.second) + s.jointOrigin;
  std::vector<double> q(count, 0.0);
  q[roles.x] = joints.x();
  q[roles.y] = joints.y();
  q[roles.z] = joints.z();
  q[roles.tilt] = roles.sign[0] * pose.first;
  q[roles.c] = roles.sign[1] * pose.second;
  return q;
}

// The fit's view of `s` (which must outlive it).
controller_fit::Model model(const Roles& roles, size_t count, Solution& s, bool withPins) {
  return {[&roles, count, &s](const ControllerPose& pose) { return commands(roles, count, s, pose); }, s.origin, freeValues(s, withPins)};
}

Solution fitted(const KinematicModel& machine, const Roles& roles, Solution s, const std::vector<ControllerPose>& poses, bool withPins) {
  controller_fit::fit(machine, model(roles, static_cast<size_t>(machine.machine->commandedCount()), s, withPins), poses);
  return s;
}

Eigen::VectorXd residual(const KinematicModel& machine, const Roles& roles, Solution s, const std::vector<ControllerPose>& poses) {
  return controller_fit::residual(machine, model(roles, static_cast<size_t>(machine.machine->commandedCount()), s, false), poses);
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
  std::vector<ControllerPose> poses = controller_fit::poseLattice(m, {r.x, r.y, r.z}, r.tilt, r.c);
  // The machine's commands are LinuxCNC's angles times a sign each: the signs the nominal machine fits with.
  Solution start;
  start.p.module = r.module;
  start.origin = toolPosition(nominal, home.data());
  Solution exact;
  double best = std::numeric_limits<double>::infinity();
  for (int tiltSign : {1, -1})
    for (int cSign : {1, -1}) {
      Roles trial = r;
      trial.sign = {tiltSign, cSign};
      const Solution s = fitted(nominal, trial, start, poses, true);
      const double largest = residual(nominal, trial, s, poses).cwiseAbs().maxCoeff();
      if (largest < best) {
        best = largest;
        r.sign = trial.sign;
        exact = s;
      }
    }
  if (best > controller_fit::kNominalFit)
    throw InputError({m.sourceFile, 0, "axes"},
                     fmt::format("the nominal machine is not LinuxCNC's {} (its best fit leaves {:.3g} mm)", start.p.name(), best));
  // maxkins' conventional-directions turns B the other way: the pin in place of a sign.
  if (r.module == Module::Max && r.sign[0] < 0) {
    r.sign[0] = 1;
    exact.p.conventionalDirections = true;
    for (ControllerPose& pose : poses) pose.first = -pose.first;
  }
  controller_fit::keepWithinTravel(m, poses, [&](const ControllerPose& pose) { return commands(r, count, exact, pose); });
  // Before: the nominal pins, the workpiece probed (its work offset fitted); after: both fitted.
  const Solution withNominal = fitted(actual, r, exact, poses, false), withPins = fitted(actual, r, exact, poses, true);
  LinuxcncKinematicsFit f;
  f.nominal = exact.p;
  f.actual = withPins.p;
  f.sign = r.sign;
  f.worldOrigin = exact.origin;
  f.workOffset = withPins.origin - exact.origin;
  f.jointOrigin = exact.jointOrigin;
  f.jointOriginShift = withPins.jointOrigin - exact.jointOrigin;
  f.notCarried = controller_fit::notCarried(machine, errors, model(r, count, exact, true), poses);
  f.residual = controller_fit::residualFigures(residual(actual, r, withNominal, poses), residual(actual, r, withPins, poses));
  return f;
}

CommandCorrection linuxcncCorrection(const std::shared_ptr<const Machine>& machine, const LinuxcncKinematicsFit& f) {
  Roles r = roles(*machine);
  r.sign = f.sign;
  const auto nominal = std::make_shared<const KinematicModel>(compileNominal(machine));
  return [r, nominal, f](const std::vector<double>& q) -> Vec3 {
    const Vec3 world = toolPosition(*nominal, q.data()) - f.worldOrigin - f.workOffset;
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
