#include "mtacc/compensation/siemens_toolholder.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"

#include "controller_kinematics_fit.hpp"

namespace mtacc {
namespace {

using controller_fit::ControllerPose;

// The machine's commanded axes in the data set's roles: X, Y, Z, and the rotary axes v1, v2.
struct ToolholderRoles {
  std::array<size_t, 3> linear;
  std::array<size_t, 2> rotary;
  char type;
};

// What a fit moves: the data set, each axis vector as tilts across its start, and the
// controller's workpiece frame in the machine's workpiece coordinates (origin and rotation vector).
struct ToolholderSolution {
  SiemensToolholder h;
  std::array<std::array<double, 2>, 2> tilt{};
  Vec3 origin = Vec3::Zero(), turn = Vec3::Zero();
};

// The data set a solution stands for: the axis vectors tilted, the chains closed as CYCLE800 closes
// them (the vector back to the reference point is the others' sum, negated).
SiemensToolholder dataSet(const ToolholderSolution& s) {
  SiemensToolholder h = s.h;
  for (size_t k = 0; k < 2; ++k) {
    const Vec3 v = h.v[k].normalized(), across = v.unitOrthogonal();
    h.v[k] = (v + s.tilt[k][0] * across + s.tilt[k][1] * v.cross(across)).normalized();
  }
  auto& l = h.l;
  if (h.type == 'T') l[0] = -(l[1] + l[2]);
  if (h.type == 'P') l[3] = -(l[1] + l[2]);
  if (h.type == 'M') l[0] = -l[1], l[3] = -l[2];
  return h;
}

// The values a fit moves: the work offset and rotation alone, or with l2, l3, the axis vectors'
// tilts and the angle offsets (the closing vectors follow from l2 and l3).
std::vector<double*> toolholderValues(ToolholderSolution& s, bool withDataSet) {
  std::vector<double*> values;
  for (Vec3* vector : {&s.origin, &s.turn})
    for (int k = 0; k < 3; ++k) values.push_back(&(*vector)[k]);
  if (!withDataSet) return values;
  for (Vec3* vector : {&s.h.l[1], &s.h.l[2]})
    for (int k = 0; k < 3; ++k) values.push_back(&(*vector)[k]);
  for (auto& tilt : s.tilt)
    for (double& t : tilt) values.push_back(&t);
  values.push_back(&s.h.offset[0]);
  values.push_back(&s.h.offset[1]);
  return values;
}

std::vector<double> commands(const ToolholderRoles& roles, size_t count, const SiemensToolholder& h, const ControllerPose& pose) {
  const Vec3 xyz = h.machinePosition(pose.world, {pose.first, pose.second}, Vec3::Zero());
  std::vector<double> q(count, 0.0);
  for (size_t k = 0; k < 3; ++k) q[roles.linear[k]] = xyz[static_cast<Eigen::Index>(k)];
  q[roles.rotary[0]] = pose.first;
  q[roles.rotary[1]] = pose.second;
  return q;
}

controller_fit::Model toolholderModel(const ToolholderRoles& roles, size_t count, ToolholderSolution& s, bool withDataSet) {
  return {[&roles, count, &s](const ControllerPose& pose) { return commands(roles, count, dataSet(s), pose); }, s.origin,
          toolholderValues(s, withDataSet), &s.turn};
}

// The tilts baked into the vectors after the fit.
ToolholderSolution fittedToolholder(const KinematicModel& machine, const ToolholderRoles& roles, ToolholderSolution s,
                                    const std::vector<ControllerPose>& poses, bool withDataSet) {
  controller_fit::fit(machine, toolholderModel(roles, static_cast<size_t>(machine.machine->commandedCount()), s, withDataSet), poses);
  s.h = dataSet(s);
  s.tilt = {};
  return s;
}

Eigen::VectorXd toolholderResidual(const KinematicModel& machine, const ToolholderRoles& roles, ToolholderSolution s,
                                   const std::vector<ControllerPose>& poses) {
  return controller_fit::residual(machine, toolholderModel(roles, static_cast<size_t>(machine.machine->commandedCount()), s, false), poses);
}

ToolholderRoles toolholderRoles(const Machine& m) {
  const int x = m.commandedAxisIndex("X"), y = m.commandedAxisIndex("Y"), z = m.commandedAxisIndex("Z");
  const InputLocation at{m.sourceFile, 0, "axes"};
  std::vector<int> rotary;
  for (int k = 0; k < m.commandedCount(); ++k)
    if (m.axes[static_cast<size_t>(k)].isRotary()) rotary.push_back(k);
  if (m.commandedCount() != 5 || x < 0 || y < 0 || z < 0 || rotary.size() != 2)
    throw InputError(at, "SINUMERIK's orientable toolholder needs the commanded axes X, Y, Z and two rotary axes");
  for (int linear : {x, y, z})
    if (m.axes[static_cast<size_t>(linear)].isRotary()) throw InputError(at, "SINUMERIK's orientable toolholder needs linear X, Y, Z");
  const auto place = [](const std::vector<int>& chain, int axis) { return std::find(chain.begin(), chain.end(), axis) - chain.begin(); };
  const auto onTable = [&](int axis) { return place(m.workpieceChain, axis) < std::ssize(m.workpieceChain); };
  ToolholderRoles r{{static_cast<size_t>(x), static_cast<size_t>(y), static_cast<size_t>(z)}, {}, 'M'};
  int first = rotary[0], second = rotary[1];
  if (onTable(first) == onTable(second)) {
    // Both in the head (T) or both in the table (P): v1 is the axis nearer the bed, which carries v2.
    const auto& chain = onTable(first) ? m.workpieceChain : m.toolChain;
    r.type = onTable(first) ? 'P' : 'T';
    if (place(chain, second) < place(chain, first)) std::swap(first, second);
  } else if (onTable(first)) {
    std::swap(first, second);  // M: v1 in the head, v2 in the table
  }
  r.rotary = {static_cast<size_t>(first), static_cast<size_t>(second)};
  return r;
}

}  // namespace

Vec3 SiemensToolholder::machinePosition(const Vec3& point, const std::array<double, 2>& angles, const Vec3& tool) const {
  const Eigen::AngleAxisd r1(angles[0] - offset[0], v[0].normalized()), r2(angles[1] - offset[1], v[1].normalized());
  switch (type) {
    case 'T': return point + l[0] + r1 * (l[1] + r2 * (l[2] + tool));
    case 'P': return l[1] + r1 * (l[2] + r2 * (point + l[3])) - (l[1] + l[2] + l[3]) + tool;
    default: return l[2] + r2 * (point + l[3]) - (l[2] + l[3]) + l[0] + r1 * (l[1] + tool);
  }
}

std::string SiemensToolholder::carries() const {
  return type == 'P' ? "the positions and directions of the two axis lines and their zero offsets"
                     : "the positions and directions of the two axis lines, their zero offsets and the spindle's offset from the head's pivot";
}

SiemensToolholderFit fitSiemensToolholder(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors) {
  const Machine& m = *machine;
  const ToolholderRoles r = toolholderRoles(m);
  const KinematicModel nominal = compileNominal(machine), actual = compile(machine, errors);
  const auto count = static_cast<size_t>(m.commandedCount());
  const std::vector<double> home(count, 0.0);
  std::vector<ControllerPose> poses = controller_fit::poseLattice(m, r.linear, r.rotary[0], r.rotary[1]);
  // Each axis turns what it carries right-handed about v: v along the machine file's direction or against it.
  ToolholderSolution start;
  start.h.type = r.type;
  for (size_t k = 0; k < 2; ++k) start.h.axes[k] = m.axes[r.rotary[k]].name;
  start.origin = toolPosition(nominal, home.data());
  ToolholderSolution exact;
  double best = std::numeric_limits<double>::infinity();
  for (double firstSign : {1.0, -1.0})
    for (double secondSign : {1.0, -1.0}) {
      ToolholderSolution trial = start;
      trial.h.v = {firstSign * m.axes[r.rotary[0]].direction, secondSign * m.axes[r.rotary[1]].direction};
      const ToolholderSolution s = fittedToolholder(nominal, r, trial, poses, true);
      const double largest = toolholderResidual(nominal, r, s, poses).cwiseAbs().maxCoeff();
      if (largest < best) {
        best = largest;
        exact = s;
      }
    }
  if (best > controller_fit::kNominalFit)
    throw InputError({m.sourceFile, 0, "axes"},
                     fmt::format("the nominal machine is not a SINUMERIK toolholder of type {} (its best fit leaves {:.3g} mm)", r.type, best));
  controller_fit::keepWithinTravel(m, poses, [&](const ControllerPose& pose) { return commands(r, count, dataSet(exact), pose); });
  // Before: the nominal data set, the workpiece probed (its work offset fitted); after: both fitted.
  const ToolholderSolution withNominal = fittedToolholder(actual, r, exact, poses, false);
  const ToolholderSolution withDataSet = fittedToolholder(actual, r, exact, poses, true);
  SiemensToolholderFit f;
  f.nominal = exact.h;
  f.actual = withDataSet.h;
  f.worldOrigin = exact.origin;
  f.workOffset = withDataSet.origin - exact.origin;
  f.workRotation = withDataSet.turn - exact.turn;
  f.notCarried = controller_fit::notCarried(machine, errors, toolholderModel(r, count, exact, true), poses);
  f.residual = controller_fit::residualFigures(toolholderResidual(actual, r, withNominal, poses), toolholderResidual(actual, r, withDataSet, poses));
  return f;
}

CommandCorrection siemensToolholderCorrection(const std::shared_ptr<const Machine>& machine, const SiemensToolholderFit& f) {
  const ToolholderRoles r = toolholderRoles(*machine);
  const auto nominal = std::make_shared<const KinematicModel>(compileNominal(machine));
  return [r, nominal, f](const std::vector<double>& q) -> Vec3 {
    const Vec3 world = controller_fit::turned(f.workRotation).transpose() * (toolPosition(*nominal, q.data()) - f.worldOrigin - f.workOffset);
    const Vec3 xyz = f.actual.machinePosition(world, {q[r.rotary[0]], q[r.rotary[1]]}, Vec3::Zero());
    return xyz - Vec3(q[r.linear[0]], q[r.linear[1]], q[r.linear[2]]);
  };
}

std::string siemensToolholderProgram(const Machine& machine, const SiemensToolholderFit& f, int number) {
  const SiemensToolholder& h = f.actual;
  const auto& res = f.residual;
  // No "-0.000000" from rounding noise: below half the printed resolution is zero.
  const auto shown = [](double value, double resolution) { return std::abs(value) < 0.5 * resolution ? 0.0 : value; };
  const auto vec = [&](const Vec3& v) { return fmt::format("({:.6f}, {:.6f}, {:.6f})", shown(v.x(), 1e-6), shown(v.y(), 1e-6), shown(v.z(), 1e-6)); };
  std::string out = fmt::format(
      "; mtacc: SINUMERIK orientable toolholder {} (function manual W1, $TC_CARR; CYCLE800) for {}, kinematic type {},\n"
      "; fitted to its error model over {} poses within travel\n"
      "; TCP position error left: largest {:.3f} um, RMS {:.3f} um (with the nominal data set: {:.3f} um, {:.3f} um)\n"
      "; carries {}\n",
      number, machine.name, h.type, res.samples, res.afterMax * 1e3, res.afterRms * 1e3, res.beforeMax * 1e3, res.beforeRms * 1e3, h.carries());
  for (const auto& left : f.notCarried) out += "; not carried: " + left + "\n";
  out += fmt::format(
      "; the machine file's tool tip is the tool adapter's reference point (tool length 0): for tools measured from the adapter,\n"
      "; move the start of l{} there; the workpiece zero = the machine's workpiece coordinates less {} mm; the machine with its\n"
      "; errors needs the work offset {} mm and the rotation {} urad (about X, Y, Z) besides, as probing the workpiece\n"
      "; at the rotary axes' initial state finds them\n",
      h.type == 'T' ? 3 : h.type == 'M' ? 2 : 1, vec(f.worldOrigin), vec(f.workOffset), vec(f.workRotation * 1e6));
  auto it = std::back_inserter(out);
  int block = 10;
  const auto assign = [&](int variable, const std::string& value) { fmt::format_to(it, "N{} $TC_CARR{}[{}]={}\n", block, variable, number, value), block += 10; };
  const int vectorVariables[4] = {1, 4, 15, 18};
  for (size_t k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) assign(vectorVariables[k] + c, fmt::format("{:.6f}", shown(h.l[k][c], 1e-6)));
  for (size_t k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) assign(7 + 3 * static_cast<int>(k) + c, fmt::format("{:.9f}", shown(h.v[k][c], 1e-9)));
  const auto& axes = machine.axes;
  const auto axisIndex = [&](const std::string& name) { return static_cast<size_t>(machine.commandedAxisIndex(name)); };
  for (size_t k = 0; k < 2; ++k) assign(21 + static_cast<int>(k), h.axes[k]);
  assign(23, fmt::format("\"{}\"", h.type));
  for (size_t k = 0; k < 2; ++k) assign(24 + static_cast<int>(k), fmt::format("{:.7f}", shown(h.offset[k] / kDeg, 1e-7)));
  // Software limits ($TC_CARR30-33, degrees): the axes' travel; 0 and 0 (not checked) without one.
  for (int bound = 0; bound < 2; ++bound)
    for (size_t k = 0; k < 2; ++k) {
      const auto& travel = axes[axisIndex(h.axes[k])].travel;
      assign(30 + 2 * bound + static_cast<int>(k), fmt::format("{:.6f}", travel ? (bound == 0 ? travel->min : travel->max) / kDeg : 0.0));
    }
  fmt::format_to(it, "N{} M17\n", block);
  return out;
}

}  // namespace mtacc

namespace mtacc {

std::vector<Trafo5Vector> trafo5Vectors(char type) {
  switch (type) {
    case 'T': return {{"TRAFO5_PART_OFFSET", 0}, {"TRAFO5_JOINT_OFFSET", 1}, {"TRAFO5_BASE_TOOL", 2}};
    case 'P': return {{"TRAFO5_BASE_TOOL", 1}, {"TRAFO5_JOINT_OFFSET", 2}, {"TRAFO5_PART_OFFSET", 3}};
    default: return {{"TRAFO5_JOINT_OFFSET", 0}, {"TRAFO5_BASE_TOOL", 1}, {"TRAFO5_JOINT_OFFSET_PART", 2}, {"TRAFO5_PART_OFFSET", 3}};
  }
}

std::string siemensTrafo5MachineData(const Machine& machine, const SiemensToolholderFit& f) {
  const SiemensToolholder& h = f.actual;
  const auto shown = [](double value, double resolution) { return std::abs(value) < 0.5 * resolution ? 0.0 : value; };
  std::string out = fmt::format(
      "%_N_TRAFO5_INI\n"
      "; mtacc: SINUMERIK generic 5-axis transformation (MD24100 TRAFO_TYPE_1) for {}: the orientable toolholder's data set of\n"
      "; siemens-toolholder.spf (kinematic type {}) as the transformation's machine data; it leaves what that leaves: largest {:.3f} um\n"
      "; the axes' assignment (MD24110, MD24120) stays as the machine has it; NEWCONF or a reset takes the data on\n"
      "CHANDATA(1)\n$MC_TRAFO_TYPE_1={}\n",
      machine.name, h.type, f.residual.afterMax * 1e3, h.type == 'T' ? 24 : h.type == 'P' ? 40 : 56);
  auto it = std::back_inserter(out);
  for (const auto& [name, l] : trafo5Vectors(h.type))
    for (int c = 0; c < 3; ++c) fmt::format_to(it, "$MC_{}_1[{}]={:.6f}\n", name, c, shown(h.l[static_cast<size_t>(l)][c], 1e-6));
  for (size_t k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) fmt::format_to(it, "$MC_TRAFO5_AXIS{}_1[{}]={:.9f}\n", k + 1, c, shown(h.v[k][c], 1e-9));
  for (size_t k = 0; k < 2; ++k) fmt::format_to(it, "$MC_TRAFO5_ROT_AX_OFFSET_1[{}]={:.7f}\n", k, shown(h.offset[k] / kDeg, 1e-7));
  return out + "M17\n";
}

}  // namespace mtacc
