#include "mtacc/measurement/design_candidates.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/measurement/rotary_axis_tests.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "rotary_run_setup.hpp"

namespace mtacc {
namespace {

bool uses(const CandidateOptions& o, Instrument i) { return std::find(o.instruments.begin(), o.instruments.end(), i) != o.instruments.end(); }

std::string estimateEntry(const std::vector<SetupParameter>& estimate) {
  if (estimate.empty()) return "";
  std::string names;
  for (const auto s : estimate) names += (names.empty() ? "" : ", ") + setupParameterName(s);
  return "    estimate: [" + names + "]\n";
}

// Positions of a rotary axis while another one turns: zero and ±30, 60, 90 deg within its travel.
std::vector<double> otherAxisPositions(const Axis& axis) {
  std::vector<double> out;
  for (const double deg : {0.0, -30.0, 30.0, -60.0, 60.0, -90.0, 90.0}) {
    const double v = deg * kDeg;
    if (!axis.travel || (v >= axis.travel->min && v <= axis.travel->max)) out.push_back(v);
  }
  return out;
}

// Every combination of the other rotary axes' positions (commanded-axis vectors, the rest at start).
std::vector<std::vector<double>> otherAxesPoses(const Machine& m, int axis) {
  std::vector<std::vector<double>> poses{startPose(m)};
  for (int k = 0; k < m.commandedCount(); ++k) {
    const auto& other = m.axes[static_cast<size_t>(k)];
    if (k == axis || !other.isRotary()) continue;
    std::vector<std::vector<double>> next;
    for (const auto& p : poses)
      for (const double v : otherAxisPositions(other)) {
        auto q = p;
        q[static_cast<size_t>(k)] = v;
        next.push_back(q);
      }
    poses = std::move(next);
  }
  return poses;
}

// "-B-60" for B at -60 deg, "" with every other rotary axis at zero.
std::string poseLabel(const Machine& m, int axis, const std::vector<double>& q) {
  std::string out;
  for (int k = 0; k < m.commandedCount(); ++k)
    if (k != axis && m.axes[static_cast<size_t>(k)].isRotary()) out += fmt::format("-{}{:g}", m.axes[static_cast<size_t>(k)].name, std::round(q[static_cast<size_t>(k)] / kDeg));
  return out;
}

// A sweep of a rotary axis: ±90 deg about zero within its travel, or all of its travel (a turn
// at most); a continuous axis a full turn.
struct Sweep {
  double from, to;
  bool fullTurn;
  const char* label;
};
std::vector<Sweep> sweeps(const Axis& axis) {
  if (!axis.travel) return {{0.0, 2 * kPi, true, ""}};
  const auto& t = *axis.travel;
  std::vector<Sweep> out{{std::max(t.min, -kPi / 2), std::min(t.max, kPi / 2), false, ""}};
  const Sweep whole{t.min, std::min(t.max, t.min + 2 * kPi), t.max - t.min >= 2 * kPi - 1e-12, "-travel"};
  if (whole.to - whole.from > out.front().to - out.front().from + 1e-9) out.push_back(whole);
  return out;
}

// Where a sphere may sit (workpiece frame) so that runs over any axis at any pose share it: on the
// workpiece side, at each radius from the innermost table axis's line, level with its location
// point and `spread` along it; with no table axis, where the tool is at the start.
std::vector<Vec3> spherePlacements(const KinematicModel& nominal, const CandidateOptions& o) {
  const Machine& m = *nominal.machine;
  const auto q = startPose(m);
  const Pose workpiece = workpiecePose(nominal, q.data(), nullptr);
  int table = -1;
  for (int j = 0; j < m.commandedCount(); ++j)
    if (m.axes[static_cast<size_t>(j)].isRotary() && m.axes[static_cast<size_t>(j)].side == Side::Workpiece) table = j;
  if (table < 0) return {toolInWorkpiece(nominal, q.data()).translation()};
  const AxisLine line = axisLine(nominal, q, table);
  const Vec3 point = workpiece.inverse() * line.point;
  const Vec3 direction = workpiece.linear().transpose() * line.direction;
  const Vec3 out = across(direction);
  std::vector<Vec3> placements;
  for (const double radius : o.radii)
    for (const double along : {0.0, o.spread}) placements.push_back(point + radius * out + along * direction);
  return placements;
}

// The R-test and probe runs: every rotary axis, at every position of the others, over each sweep,
// on each sphere placement, with the tool ball at the tip (and `spread` beyond it on a machine with
// a head axis), at each number of positions; those within the travel.
void sphereCandidates(const KinematicModel& nominal, const CandidateOptions& o, CandidateSet& out) {
  const Machine& m = *nominal.machine;
  bool headAxis = false;
  for (int j = 0; j < m.commandedCount(); ++j) headAxis |= m.axes[static_cast<size_t>(j)].isRotary() && m.axes[static_cast<size_t>(j)].side == Side::Tool;
  std::vector<Vec3> toolBalls{Vec3::Zero()};
  if (headAxis) toolBalls.push_back(-o.spread * m.toolDirection);
  const auto placements = spherePlacements(nominal, o);
  const std::vector<SetupParameter> sphere{SetupParameter::TargetX, SetupParameter::TargetY, SetupParameter::TargetZ};
  size_t beyond = 0;
  for (int j = 0; j < m.commandedCount(); ++j) {
    const auto& axis = m.axes[static_cast<size_t>(j)];
    if (!axis.isRotary()) continue;
    for (const auto& pose : otherAxesPoses(m, j))
      for (const auto& sweep : sweeps(axis))
        for (size_t s = 0; s < placements.size(); ++s)
          for (size_t b = 0; b < toolBalls.size(); ++b)
            for (const int positions : o.positions)
              for (const auto instrument : {Instrument::RTest, Instrument::TouchProbe}) {
                if (!uses(o, instrument)) continue;
                SphereTestSpec spec;
                spec.instrument = instrument;
                spec.axis = axis.name;
                const double to = sweep.fullTurn ? sweep.to - (sweep.to - sweep.from) / positions : sweep.to;
                spec.angles = evenAngles(sweep.from, to, positions);
                spec.spheres = {placements[s]};
                spec.toolBall = toolBalls[b];
                spec.pose = pose;
                DesignCandidate c;
                try {
                  c.run = sphereTest(nominal, spec).front();
                } catch (const UnreachablePose&) {
                  ++beyond;
                  continue;
                }
                if (!travelViolation(m, c.run).empty()) {
                  ++beyond;
                  continue;
                }
                const char* kind = instrument == Instrument::RTest ? "rtest" : "probe";
                c.name = fmt::format("{}-{}-s{}{}{}{}-n{}", axis.name, kind, s + 1, b > 0 ? "-long" : "", poseLabel(m, j, pose), sweep.label,
                                     positions);
                c.run.name = c.name;
                c.run.estimate = sphere;
                c.description = fmt::format("{}: {} from {:g} to {:g} deg, {} positions, sphere {} at {}{}", instrument == Instrument::RTest ? "R-test" : "touch probe",
                                            axis.name, sweep.from / kDeg, to / kDeg, positions, s + 1, mm(placements[s]),
                                            b > 0 ? fmt::format(", the tool ball {:g} mm beyond the tip", o.spread) : "");
                for (int k = 0; k < m.commandedCount(); ++k)
                  if (k != j && m.axes[static_cast<size_t>(k)].isRotary())
                    c.description += fmt::format(", {} at {:g} deg", m.axes[static_cast<size_t>(k)].name, pose[static_cast<size_t>(k)] / kDeg);
                c.planEntry = fmt::format("  - name: {}\n    sphere: {{{}axis: {}, from: {:.10g} deg, to: {:.10g} deg, points: {}, spheres: [{}]{}}}\n{}{}",
                                          c.name, instrument == Instrument::TouchProbe ? "instrument: probe, " : "", axis.name, sweep.from / kDeg,
                                          to / kDeg, positions, mm(placements[s]), poseEntry(m, pose, j),
                                          b > 0 ? "    tool_ball: " + mm(toolBalls[b]) + "\n" : "", estimateEntry(sphere));
                out.candidates.push_back(std::move(c));
              }
  }
  if (beyond > 0) out.notes.push_back(fmt::format("{} sphere runs beyond the travel left out", beyond));
}

// The ballbar's radial, tangential and axial tests of each rotary axis (seed 002's set-up, the
// rotary axes at zero), at each radius and bar length.
void rotaryBallbarCandidates(const KinematicModel& nominal, const CandidateOptions& o, CandidateSet& out) {
  for (const double length : o.ballbarLengths)
    for (const double radius : o.radii) {
      RotaryAxisTestOptions t;
      t.radius = radius;
      t.spread = o.spread;
      t.ballbarLength = length;
      t.ballbarPoints = o.ballbarPoints;
      t.feed = o.feed;
      RotaryAxisTestSet set;
      try {
        set = rotaryAxisTests(nominal, t);
      } catch (const InputError& e) {
        out.notes.push_back(fmt::format("ballbar tests at {:g} mm with a {:g} mm bar: {}", radius, length, e.reason()));
        continue;
      }
      for (auto& test : set.tests) {
        if (test.kind == RotaryTestKind::RTest) continue;
        DesignCandidate c;
        c.name = fmt::format("{}-r{:g}-L{:g}", test.name, radius, length);
        c.run = std::move(test.run);
        c.run.name = c.name;
        c.description = test.description + fmt::format(", {:g} to {:g} deg", test.from / kDeg, test.to / kDeg);
        c.planEntry = "  - name: " + c.name + "\n" + test.planEntry.substr(test.planEntry.find('\n') + 1);
        out.candidates.push_back(std::move(c));
      }
    }
}

// ISO 230-4 circles in XY, YZ, ZX of each bar length, the centre pivot at the tool at mid-travel,
// the rotary axes at the start pose (given in the plan entry).
void circleCandidates(const KinematicModel& nominal, const CandidateOptions& o, CandidateSet& out) {
  const Machine& m = *nominal.machine;
  const auto q = startPose(m);
  const Vec3 centre = toolInWorkpiece(nominal, q.data()).translation();
  for (const double length : o.ballbarLengths)
    for (const std::string plane : {"XY", "YZ", "ZX"}) {
      const std::string name = fmt::format("circle-{}-L{:g}", plane, length);
      BallbarCircleSpec spec;
      spec.plane = plane;
      spec.centre = centre;
      spec.radius = length;
      spec.pose = q;
      spec.points = o.ballbarPoints;
      spec.feed = o.feed;
      DesignCandidate c;
      try {
        c.run = ballbarCircle(nominal, spec);
      } catch (const UnreachablePose& e) {
        out.notes.push_back(fmt::format("{}: not generated: {}", name, e.what()));
        continue;
      } catch (const InputError& e) {
        out.notes.push_back(fmt::format("{}: not generated: {}", name, e.reason()));
        continue;
      }
      if (const auto beyond = travelViolation(m, c.run); !beyond.empty()) {
        out.notes.push_back(fmt::format("{}: not generated: {}", name, beyond));
        continue;
      }
      const auto component = [](const Vec3& axis) {
        return axis.x() != 0 ? SetupParameter::TargetX : axis.y() != 0 ? SetupParameter::TargetY : SetupParameter::TargetZ;
      };
      c.run.estimate = {component(planeAxes(plane)[0]), component(planeAxes(plane)[1])};
      c.name = name;
      c.run.name = c.name;
      c.description = fmt::format("ballbar circle {:g} mm in {}, both directions, about the tool at mid-travel", length, plane);
      c.planEntry = fmt::format("  - name: {}\n    circle: {{plane: {}, centre: {}, radius: {:.10g} mm, points: {}, feed: {:.10g} mm/min{}}}\n{}",
                                c.name, plane, mm(centre), length, o.ballbarPoints, o.feed, poseEntry(m, q, -1), estimateEntry(c.run.estimate));
      out.candidates.push_back(std::move(c));
    }
}

}  // namespace

CandidateSet designCandidates(const KinematicModel& nominal, const CandidateOptions& o) {
  const Machine& m = *nominal.machine;
  if (o.instruments.empty()) throw InvalidInput("no instrument to design with");
  for (const auto i : o.instruments)
    if (i == Instrument::Directional) throw InvalidInput("a design chooses among rtest, ballbar and probe runs");
  if (o.radii.empty() || o.positions.empty() || o.ballbarLengths.empty())
    throw InvalidInput("a design needs at least one sphere radius, one number of positions and one ballbar length");
  CandidateSet out;
  sphereCandidates(nominal, o, out);
  const bool rotary = std::any_of(m.axes.begin(), m.axes.end(), [](const Axis& a) { return a.commanded() && a.isRotary(); });
  if (uses(o, Instrument::Ballbar)) {
    if (rotary) rotaryBallbarCandidates(nominal, o, out);
    circleCandidates(nominal, o, out);
  }
  if (out.candidates.empty()) throw InvalidInput("no candidate run can be generated for these instruments on " + m.name);
  return out;
}

}  // namespace mtacc
