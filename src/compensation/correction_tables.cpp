#include "mtacc/compensation/correction_tables.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"

namespace mtacc {
namespace {

constexpr int kLinuxcncLines = 256;  // EMCMOT_COMP_SIZE in LinuxCNC's motion.h

// Where x lies between the nodes start + k step: the lower node and the fraction, clamped.
std::pair<int, double> bracket(double x, double start, double step, int count) {
  if (count < 2) return {0, 0.0};
  const double u = std::clamp((x - start) / step, 0.0, static_cast<double>(count - 1));
  const int k = std::min(static_cast<int>(u), count - 2);
  return {k, u - k};
}

// The TCP of the machine with its errors at the commands q, as written and corrected by `c`,
// against the nominal TCP at q; largest and RMS over the points added.
class ResidualSum {
 public:
  ResidualSum(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& g)
      : actual_(compile(machine, errors)), nominal_(compileNominal(machine)), axes_(g.axes) {}

  // `direction`: per commanded axis, empty standing.
  void add(const std::vector<double>& q, const std::vector<int>& direction, const DirectedCorrection& correction,
           const std::vector<RotaryPositioning>& rotary) {
    const auto x = static_cast<size_t>(axes_[0]), y = static_cast<size_t>(axes_[1]), z = static_cast<size_t>(axes_[2]);
    corrected_ = q;
    const Vec3 c = correction(q, direction);
    corrected_[x] += c.x();
    corrected_[y] += c.y();
    corrected_[z] += c.z();
    for (const RotaryPositioning& r : rotary) corrected_[static_cast<size_t>(r.axis)] += r.correction(q[static_cast<size_t>(r.axis)]);
    const int* dir = direction.empty() ? nullptr : direction.data();
    const Vec3 wanted = toolPosition(nominal_, q.data());
    const double before = (toolPosition(actual_, q.data(), dir) - wanted).norm();
    const double after = (toolPosition(actual_, corrected_.data(), dir) - wanted).norm();
    r_.beforeMax = std::max(r_.beforeMax, before);
    r_.afterMax = std::max(r_.afterMax, after);
    before_ += before * before;
    after_ += after * after;
    ++r_.samples;
  }

  TableResidual result() const {
    TableResidual r = r_;
    if (r.samples > 0) {
      r.beforeRms = std::sqrt(before_ / r.samples);
      r.afterRms = std::sqrt(after_ / r.samples);
    }
    return r;
  }

 private:
  KinematicModel actual_, nominal_;
  std::array<int, 3> axes_;
  std::vector<double> corrected_;
  TableResidual r_;
  double before_ = 0.0, after_ = 0.0;
};

}  // namespace

Vec3 CorrectionGrid::interpolate(const Vec3& xyz) const {
  const std::pair<int, double> bx = bracket(xyz.x(), start[0], step[0], counts[0]), by = bracket(xyz.y(), start[1], step[1], counts[1]),
                              bz = bracket(xyz.z(), start[2], step[2], counts[2]);
  const int i = bx.first, j = by.first, k = bz.first;
  const double u = bx.second, v = by.second, w = bz.second;
  const int i1 = std::min(i + 1, counts[0] - 1), j1 = std::min(j + 1, counts[1] - 1), k1 = std::min(k + 1, counts[2] - 1);
  auto along = [&](int jj, int kk) { return Vec3((1 - u) * at(i, jj, kk) + u * at(i1, jj, kk)); };
  return (1 - w) * ((1 - v) * along(j, k) + v * along(j1, k)) + w * ((1 - v) * along(j, k1) + v * along(j1, k1));
}

ErrorIkOptions positionCorrectionOptions() {
  ErrorIkOptions options;
  options.positionOnly = true;
  options.positionTolerance = 1e-7;
  options.checkTravel = false;
  return options;
}

CorrectionGrid correctionGrid(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGridSpec& spec) {
  CorrectionGrid g;
  const auto n = static_cast<size_t>(machine->commandedCount());
  g.pose = spec.pose.empty() ? std::vector<double>(n, 0.0) : spec.pose;
  if (g.pose.size() != n) throw InputError({"", 0, "pose"}, fmt::format("the pose needs {} axis positions", n));
  for (int a = 0; a < 3; ++a) {
    const int index = machine->commandedAxisIndex(kLinearAxisNames[a]);
    const auto ua = static_cast<size_t>(a);
    if (index < 0 || machine->axes[static_cast<size_t>(index)].isRotary())
      throw InputError({machine->sourceFile, 0, "axes"}, fmt::format("a correction grid needs a linear axis {}", kLinearAxisNames[a]));
    const auto& travel = machine->axes[static_cast<size_t>(index)].travel;
    if (!travel) throw InputError({machine->sourceFile, 0, kLinearAxisNames[a]}, "a correction grid needs the axis's travel");
    if (spec.counts[ua] < 2 || spec.counts[ua] > 1000)
      throw InputError({"", 0, "nodes"}, fmt::format("{} nodes along {}: give 2 to 1000", spec.counts[ua], kLinearAxisNames[a]));
    g.axes[ua] = index;
    g.counts[ua] = spec.counts[ua];
    g.start[ua] = travel->min;
    g.step[ua] = (travel->max - travel->min) / (spec.counts[ua] - 1);
  }
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  const ErrorIkOptions options = positionCorrectionOptions();
  g.corrections.resize(static_cast<size_t>(g.counts[0]) * static_cast<size_t>(g.counts[1]) * static_cast<size_t>(g.counts[2]));
  const auto x = static_cast<size_t>(g.axes[0]), y = static_cast<size_t>(g.axes[1]), z = static_cast<size_t>(g.axes[2]);
  // With the other axes standing, the nominal tool is affine in X, Y, Z (no rotation of the
  // chain moves): the wanted TCP at the first node and its change per node along each axis,
  // exact to the rounding of a difference (1e-13 mm a node, far below the solve's 1e-7 mm).
  std::vector<double> firstNode = g.pose;
  for (size_t a = 0; a < 3; ++a) firstNode[static_cast<size_t>(g.axes[a])] = g.start[a];
  const ToolPoint first = toolPoint(nominal, firstNode.data());
  std::array<Vec3, 3> perNode;
  for (size_t a = 0; a < 3; ++a) {
    std::vector<double> last = firstNode;
    last[static_cast<size_t>(g.axes[a])] = g.node(static_cast<int>(a), g.counts[a] - 1);
    perNode[a] = (toolPosition(nominal, last.data()) - first.position) / (g.counts[a] - 1);
  }
  // Each Z layer on its own, from scratch: the result does not depend on the threads.
  parallelFor(g.counts[2], spec.threads, [&](long firstLayer, long endLayer) {
    ErrorIkJacobian jacobian;
    ErrorIkSolution s;
    std::vector<double> q = g.pose, start(n);
    for (auto k = static_cast<int>(firstLayer); k < endLayer; ++k) {
      jacobian.valid = false;
      for (int j = 0; j < g.counts[1]; ++j)
        for (int i = 0; i < g.counts[0]; ++i) {
          q[x] = g.node(0, i);
          q[y] = g.node(1, j);
          q[z] = g.node(2, k);
          const Vec3 wanted = first.position + i * perNode[0] + j * perNode[1] + k * perNode[2];
          // The errors are mostly sums of each axis's own functions: from the previous row the
          // correction takes its change along X (periodic errors of the X axis included), from the
          // node before its change along Y. The first row extrapolates along X from the two nodes
          // before; a row starts from the previous row's start.
          const Vec3 guess = j >= 1 && i >= 1 ? Vec3(g.at(i, j - 1, k) + g.at(i - 1, j, k) - g.at(i - 1, j - 1, k))
                             : i >= 2         ? Vec3(2 * g.at(i - 1, j, k) - g.at(i - 2, j, k))
                             : i == 1         ? g.at(0, j, k)
                             : j >= 1         ? g.at(0, j - 1, k)
                                              : Vec3::Zero();
          start = q;
          start[x] += guess.x();
          start[y] += guess.y();
          start[z] += guess.z();
          refineWithErrors(actual, wanted, first.direction, start, options, jacobian, s);
          g.corrections[static_cast<size_t>(i + g.counts[0] * (j + g.counts[1] * k))] = Vec3(s.q[x] - q[x], s.q[y] - q[y], s.q[z] - q[z]);
        }
    }
  }, 1);
  return g;
}

double AxisFunction::at(double position) const {
  const double step = positions.size() > 1 ? positions[1] - positions[0] : 1.0;
  const auto [k, u] = bracket(position, positions.front(), step, static_cast<int>(positions.size()));
  const auto kk = static_cast<size_t>(k);
  return positions.size() > 1 ? (1 - u) * values[kk] + u * values[kk + 1] : values[0];
}

Vec3 OneAxisReduction::correction(const Vec3& xyz) const {
  Vec3 c = Vec3::Zero();
  for (const auto& f : functions) c[f.output] += f.at(xyz[f.input]);
  return c;
}

OneAxisReduction reduceToOneAxisFunctions(const CorrectionGrid& g, int maxFunctions) {
  const double nodes = static_cast<double>(g.corrections.size());
  Vec3 grand = Vec3::Zero();
  for (const auto& c : g.corrections) grand += c;
  grand /= nodes;
  std::vector<AxisFunction> all;
  for (int input = 0; input < 3; ++input) {
    const int count = g.counts[static_cast<size_t>(input)];
    std::vector<Vec3> mean(static_cast<size_t>(count), Vec3::Zero());
    for (int k = 0; k < g.counts[2]; ++k)
      for (int j = 0; j < g.counts[1]; ++j)
        for (int i = 0; i < g.counts[0]; ++i) mean[static_cast<size_t>(input == 0 ? i : input == 1 ? j : k)] += g.at(i, j, k);
    for (auto& m : mean) m *= count / nodes;
    for (int output = 0; output < 3; ++output) {
      AxisFunction f;
      f.input = input;
      f.output = output;
      for (int n = 0; n < count; ++n) {
        f.positions.push_back(g.node(input, n));
        // The main effect; the grand mean rides on the output axis's own function.
        f.values.push_back(mean[static_cast<size_t>(n)][output] - (input == output ? 0.0 : grand[output]));
      }
      double squares = 0.0;
      for (double v : f.values) squares += v * v;
      f.rms = std::sqrt(squares / count);
      all.push_back(std::move(f));
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const AxisFunction& a, const AxisFunction& b) { return a.rms > b.rms; });
  OneAxisReduction r;
  r.functions.assign(all.begin(), all.begin() + std::clamp(maxFunctions, 0, static_cast<int>(all.size())));
  double squares = 0.0;
  for (int k = 0; k < g.counts[2]; ++k)
    for (int j = 0; j < g.counts[1]; ++j)
      for (int i = 0; i < g.counts[0]; ++i) {
        const double left = (g.at(i, j, k) - r.correction({g.node(0, i), g.node(1, j), g.node(2, k)})).norm();
        r.residualMax = std::max(r.residualMax, left);
        squares += left * left;
      }
  r.residualRms = std::sqrt(squares / nodes);
  return r;
}

namespace {

// The X, Y, Z commands of q, for a table that looks its correction up from them.
CommandCorrection ofLinearCommands(const CorrectionGrid& g, const std::function<Vec3(const Vec3&)>& correction) {
  const auto x = static_cast<size_t>(g.axes[0]), y = static_cast<size_t>(g.axes[1]), z = static_cast<size_t>(g.axes[2]);
  return [=](const std::vector<double>& q) { return correction({q[x], q[y], q[z]}); };
}

}  // namespace

TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& g,
                            const std::function<Vec3(const Vec3&)>& correction, int perAxis, const std::vector<RotaryPositioning>& rotary) {
  return tableResidual(machine, errors, g, ofLinearCommands(g, correction), perAxis, rotary);
}

TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& g, const std::function<Vec3(const Vec3&)>& correction,
                                 const std::vector<RotaryPositioning>& rotary) {
  return tableResidualAlong(machine, errors, program, g, ofLinearCommands(g, correction), rotary);
}

namespace {

DirectedCorrection standing(const CommandCorrection& correction) {
  return [correction](const std::vector<double>& q, const std::vector<int>&) { return correction(q); };
}

// The lattice's points, `perAxis` at most along each axis, the other axes at the grid's pose.
void forEachLatticePoint(const CorrectionGrid& g, int perAxis, const std::function<void(const std::vector<double>&)>& visit) {
  std::array<std::vector<double>, 3> lattice;
  for (size_t a = 0; a < 3; ++a) {
    // The nodes and the midpoints between them, thinned to perAxis.
    const int points = std::min(2 * g.counts[a] - 1, perAxis);
    const double span = g.step[a] * (g.counts[a] - 1);
    for (int p = 0; p < points; ++p) lattice[a].push_back(g.start[a] + span * p / (points - 1));
  }
  std::vector<double> q = g.pose;
  const auto x = static_cast<size_t>(g.axes[0]), y = static_cast<size_t>(g.axes[1]), z = static_cast<size_t>(g.axes[2]);
  for (double zz : lattice[2])
    for (double yy : lattice[1])
      for (double xx : lattice[0]) {
        q[x] = xx;
        q[y] = yy;
        q[z] = zz;
        visit(q);
      }
}

constexpr int kMovingPerAxis = 11;

}  // namespace

TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& g,
                            const CommandCorrection& correction, int perAxis, const std::vector<RotaryPositioning>& rotary) {
  return tableResidual(machine, errors, g, standing(correction), perAxis, rotary);
}

TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& g,
                            const DirectedCorrection& correction, int perAxis, const std::vector<RotaryPositioning>& rotary) {
  ResidualSum sum(machine, errors, g);
  forEachLatticePoint(g, perAxis, [&](const std::vector<double>& q) { sum.add(q, {}, correction, rotary); });
  TableResidual r = sum.result();
  for (int way : {1, -1}) {
    ResidualSum moving(machine, errors, g);
    std::vector<int> direction(g.pose.size(), 0);
    for (int axis : g.axes) direction[static_cast<size_t>(axis)] = way;
    forEachLatticePoint(g, std::min(perAxis, kMovingPerAxis), [&](const std::vector<double>& q) { moving.add(q, direction, correction, rotary); });
    (way > 0 ? r.forwardMax : r.backwardMax) = moving.result().afterMax;
  }
  return r;
}

TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& g, const CommandCorrection& correction, const std::vector<RotaryPositioning>& rotary) {
  return tableResidualAlong(machine, errors, program, g, standing(correction), rotary);
}

TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& g, const DirectedCorrection& correction, const std::vector<RotaryPositioning>& rotary) {
  ResidualSum sum(machine, errors, g), moving(machine, errors, g);
  std::vector<int> held;
  for (const GcodeMove& move : program.moves) {
    if (move.mode == MotionMode::Rapid) {
      move.heldMotion(1.0, held);
      continue;
    }
    for (int k = 0; k <= 16; ++k) {
      const std::vector<double> q = move.at(k / 16.0);
      move.heldMotion(k / 16.0, held);
      sum.add(q, {}, correction, rotary);
      moving.add(q, held, correction, rotary);
    }
  }
  TableResidual r = sum.result();
  r.programmedMax = moving.result().afterMax;
  return r;
}

DirectedCorrection directedCorrection(const CorrectionGrid& g, const CommandCorrection& standing, const std::array<ReversalTrims, 3>& trims) {
  return [g, standing, trims](const std::vector<double>& q, const std::vector<int>& direction) {
    Vec3 c = standing(q);
    if (direction.empty()) return c;
    for (size_t a = 0; a < 3; ++a) {
      const auto axis = static_cast<size_t>(g.axes[a]);
      const int way = direction[axis];
      if (way == 0) continue;
      const std::vector<double>& column = way > 0 ? trims[a].forward : trims[a].reverse;
      const auto [node, t] = bracket(q[axis], g.start[a], g.step[a], g.counts[a]);
      const auto n = static_cast<size_t>(node);
      c[static_cast<Eigen::Index>(a)] += (1.0 - t) * column[n] + t * column[std::min(n + 1, column.size() - 1)];
    }
    return c;
  };
}

DirectedCorrection directedCorrection(const CorrectionGrid& g, const OneAxisReduction& functions, const std::array<ReversalTrims, 3>& trims) {
  return directedCorrection(g, ofLinearCommands(g, [functions](const Vec3& p) { return functions.correction(p); }), trims);
}

std::array<ReversalTrims, 3> roundedTrims(std::array<ReversalTrims, 3> trims, double unit) {
  for (ReversalTrims& t : trims)
    for (auto* column : {&t.forward, &t.reverse})
      for (double& v : *column) v = std::round(v / unit) * unit;
  return trims;
}

bool anyNonZero(const std::vector<double>& values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return v != 0.0; });
}

std::vector<AxisReversalTable> axisReversalTables(const Machine& machine, const CorrectionGrid& g, const std::array<ReversalTrims, 3>& trims,
                                                  const std::vector<RotaryPositioning>& rotary) {
  std::vector<AxisReversalTable> out;
  for (size_t a = 0; a < 3; ++a) {
    if (!anyNonZero(trims[a].forward) && !anyNonZero(trims[a].reverse)) continue;
    AxisReversalTable t{machine.axes[static_cast<size_t>(g.axes[a])].name, g.axes[a], false, false, {}, trims[a].forward, trims[a].reverse};
    for (int n = 0; n < g.counts[a]; ++n) t.positions.push_back(g.node(static_cast<int>(a), n));
    out.push_back(std::move(t));
  }
  for (const RotaryPositioning& r : rotary) {
    AxisReversalTable t{machine.axes[static_cast<size_t>(r.axis)].name, r.axis, true, r.modulo, {}, {}, {}};
    for (size_t n = 0; n < r.positions.size(); ++n) {
      t.positions.push_back(r.positions[n] / kDeg);
      t.forward.push_back((r.forward[n] - r.standing[n]) / kDeg);
      t.reverse.push_back((r.reverse[n] - r.standing[n]) / kDeg);
    }
    if (anyNonZero(t.forward) || anyNonZero(t.reverse)) out.push_back(std::move(t));
  }
  return out;
}

std::vector<std::string> reversalFunctions(const Machine& machine, const ErrorModel& errors,
                                           const std::function<bool(int axis, int component)>& among) {
  const auto reverses = [](const auto& term) { return std::holds_alternative<ReversalTerm>(term) && std::get<ReversalTerm>(term).width != 0.0; };
  std::vector<std::string> names;
  for (size_t a = 0; a < machine.axes.size(); ++a)
    for (int c = 0; c < 6; ++c) {
      if (among && !among(static_cast<int>(a), c)) continue;
      const auto& terms = errors.axes[a].motion[static_cast<size_t>(c)].terms();
      if (std::any_of(terms.begin(), terms.end(), reverses)) names.push_back(motionErrorName(machine, static_cast<int>(a), c));
    }
  return names;
}

std::string correctionGridCsv(const Machine& machine, const CorrectionGrid& g) {
  std::string out = fmt::format(
      "# mtacc correction grid for {}: add (dx, dy, dz) to the X, Y, Z commands; trilinear between the nodes, the end value beyond\n"
      "# nodes: {} x {} x {} from ({:g}, {:g}, {:g}) mm, step ({:g}, {:g}, {:g}) mm; x fastest\n"
      "# pose of the other axes: {}\n"
      "# carries the position only: the tool direction's error is not corrected\n"
      "x_mm,y_mm,z_mm,dx_mm,dy_mm,dz_mm\n",
      machine.name, g.counts[0], g.counts[1], g.counts[2], g.start[0], g.start[1], g.start[2], g.step[0], g.step[1], g.step[2],
      machine.describePose(g.pose));
  auto it = std::back_inserter(out);
  for (int k = 0; k < g.counts[2]; ++k)
    for (int j = 0; j < g.counts[1]; ++j)
      for (int i = 0; i < g.counts[0]; ++i) {
        const Vec3& c = g.at(i, j, k);
        fmt::format_to(it, "{:.6f},{:.6f},{:.6f},{:.7f},{:.7f},{:.7f}\n", g.node(0, i), g.node(1, j), g.node(2, k), c.x(), c.y(), c.z());
      }
  return out;
}

ReversalTrims reversalTrims(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& g, int axis) {
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  const auto options = positionCorrectionOptions();
  const auto own = static_cast<size_t>(g.axes[static_cast<size_t>(axis)]);
  std::vector<double> q = g.pose;
  for (int a = 0; a < 3; ++a) q[static_cast<size_t>(g.axes[static_cast<size_t>(a)])] = g.node(a, g.counts[static_cast<size_t>(a)] / 2);
  std::vector<int> motion(q.size(), 0);
  ErrorIkJacobian jacobian;
  ReversalTrims out;
  for (int n = 0; n < g.counts[static_cast<size_t>(axis)]; ++n) {
    q[own] = g.node(axis, n);
    const ToolPoint wanted = toolPoint(nominal, q.data());
    auto corrected = [&](int direction) {
      motion[own] = direction;
      return refineWithErrors(actual, wanted.position, wanted.direction, q, options, jacobian, false, motion.data()).q[own];
    };
    const double standing = corrected(0);
    out.forward.push_back(corrected(1) - standing);
    out.reverse.push_back(corrected(-1) - standing);
  }
  return out;
}

namespace {

void checkCompFile(size_t lines, int type) {
  if (static_cast<int>(lines) > kLinuxcncLines)
    throw InputError({"", 0, "nodes"}, fmt::format("LinuxCNC takes at most {} lines per joint, not {}", kLinuxcncLines, lines));
  if (type != 0 && type != 1) throw InputError({"", 0, "type"}, "COMP_FILE_TYPE is 0 or 1");
}

// LinuxCNC reads no comments: the file holds the triplets only (type 1 the trims, 0 the positions),
// the trims to `decimals` places.
std::string compFileLines(const std::vector<double>& positions, const std::vector<double>& forward, const std::vector<double>& reverse,
                          int type, int decimals) {
  checkCompFile(positions.size(), type);
  std::string out;
  auto it = std::back_inserter(out);
  for (size_t n = 0; n < positions.size(); ++n) {
    const double p = positions[n], shift = type == 1 ? 0.0 : p;
    fmt::format_to(it, "{:.6f} {:.{}f} {:.{}f}\n", p, shift + forward[n], decimals, shift + reverse[n], decimals);
  }
  return out;
}

std::vector<double> inDegrees(std::vector<double> radians) {
  for (double& v : radians) v /= kDeg;
  return radians;
}

}  // namespace

std::string linuxcncCompFile(const AxisFunction& f, const ReversalTrims& reversal, int type) {
  if (f.input != f.output) throw InputError({"", 0, "table"}, "a LinuxCNC COMP_FILE holds an axis's correction as a function of its own command");
  checkCompFile(f.positions.size(), type);
  if (reversal.forward.size() != f.values.size() || reversal.reverse.size() != f.values.size())
    throw InvalidInput("linuxcncCompFile: the reversal trims are not at the function's positions");
  std::vector<double> forward = f.values, reverse = f.values;
  for (size_t n = 0; n < forward.size(); ++n) {
    forward[n] += reversal.forward[n];
    reverse[n] += reversal.reverse[n];
  }
  return compFileLines(f.positions, forward, reverse, type, 7);
}

std::string linuxcncCompFile(const RotaryPositioning& r, int type) {
  return compFileLines(inDegrees(r.positions), inDegrees(r.forward), inDegrees(r.reverse), type, 9);
}

std::string siemensCecTables(const std::vector<AxisFunction>& functions, const std::vector<AxisReversalTable>& reversal, const std::string& pose) {
  std::string out = "%_N_NC_CEC_INI\n; mtacc CEC tables: values in mm (degrees on a rotary axis), added to the output axis\n"
                    "; taken with the other axes at " + pose + "\n";
  auto it = std::back_inserter(out);
  int t = 0;
  const auto table = [&](const std::string& input, const std::string& output, const std::vector<double>& positions, int direction, bool modulo,
                         const std::vector<double>& values) {
    const double step = positions.size() > 1 ? positions[1] - positions[0] : 0.0;
    fmt::format_to(it, "$AN_CEC_INPUT_AXIS[{0}]=({1})\n$AN_CEC_OUTPUT_AXIS[{0}]=({2})\n$AN_CEC_STEP[{0}]={3:.6f}\n$AN_CEC_MIN[{0}]={4:.6f}\n"
                       "$AN_CEC_MAX[{0}]={5:.6f}\n$AN_CEC_DIRECTION[{0}]={6}\n$AN_CEC_MULT_BY_TABLE[{0}]=0\n$AN_CEC_IS_MODULO[{0}]={7}\n",
                   t, input, output, step, positions.front(), positions.back(), direction, modulo ? 1 : 0);
    for (size_t n = 0; n < values.size(); ++n) fmt::format_to(it, "$AN_CEC[{},{}]={:.7f}\n", t, n, values[n]);
    ++t;
  };
  if (!functions.empty()) fmt::format_to(it, "; tables 0 to {}: the one-axis correction functions\n", functions.size() - 1);
  for (const AxisFunction& f : functions) table(kLinearAxisNames[f.input], kLinearAxisNames[f.output], f.positions, 0, false, f.values);
  for (const AxisReversalTable& r : reversal) {
    fmt::format_to(it, "; tables {} and {}: the reversal of {}, added moving positive (DIRECTION 1) and moving negative (-1)\n", t, t + 1, r.axis);
    table(r.axis, r.axis, r.positions, 1, r.modulo, r.forward);
    table(r.axis, r.axis, r.positions, -1, r.modulo, r.reverse);
  }
  return out + "M17\n";
}

std::string siemensLecTables(const std::vector<AxisFunction>& ownAxes, const Machine& machine, const std::vector<RotaryPositioning>& rotary,
                             const std::string& pose) {
  std::string out = "%_N_AX_EEC_INI\n; mtacc: each axis's correction of its own command as LEC tables on measuring system 1; values in mm "
                    "(degrees for a rotary axis), the error (the correction negated: a positive value moves the axis negative)\n"
                    "; taken with the other axes at " + pose + "\nCHANDATA(1)\n";
  auto it = std::back_inserter(out);
  // One axis's table: its points, the error at each (the correction negated), equidistant from the first to the last.
  const auto table = [&](const std::string& axis, const std::vector<double>& positions, const std::vector<double>& corrections, bool modulo) {
    fmt::format_to(it, "; {}: {} points: needs MD38000 $MA_MM_ENC_COMP_MAX_POINTS >= {} and MD32700 ENC_COMP_ENABLE[0] = 1\n", axis,
                   corrections.size(), corrections.size());
    for (size_t n = 0; n < corrections.size(); ++n) fmt::format_to(it, "$AA_ENC_COMP[0,{},{}]={:.7f}\n", n, axis, -corrections[n]);
    const double step = positions.size() > 1 ? positions[1] - positions[0] : 0.0;
    fmt::format_to(it, "$AA_ENC_COMP_STEP[0,{0}]={1:.6f}\n$AA_ENC_COMP_MIN[0,{0}]={2:.6f}\n$AA_ENC_COMP_MAX[0,{0}]={3:.6f}\n$AA_ENC_COMP_IS_MODULO[0,{0}]={4}\n",
                   axis, step, positions.front(), positions.back(), modulo ? 1 : 0);
  };
  for (const AxisFunction& f : ownAxes) {
    if (f.input != f.output) throw InputError({"", 0, "table"}, "an LEC table holds an axis's correction as a function of its own command");
    table(kLinearAxisNames[f.input], f.positions, f.values, false);
  }
  for (const RotaryPositioning& r : rotary) table(machine.axes[static_cast<size_t>(r.axis)].name, inDegrees(r.positions), inDegrees(r.standing), r.modulo);
  return out + "M17\n";
}

}  // namespace mtacc
