#include "mtacc/measurement/rotary_axis_tests.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/measurement/rtest_evaluation.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "rotary_run_setup.hpp"

namespace mtacc {
namespace {

double distanceFromLine(const AxisLine& line, const Vec3& p) {
  const Vec3 r = p - line.point;
  return (r - line.direction * line.direction.dot(r)).norm();
}

// A full turn for a continuous axis, else its travel within ±half of its start.
std::pair<double, double> sweep(const Axis& axis, double start, double half) {
  if (!axis.travel) return {0.0, 2 * kPi};
  return {std::max(axis.travel->min, start - half), std::min(axis.travel->max, start + half)};
}

void requireWithinTravel(const Machine& m, const RotaryAxisTest& t) {
  const std::string violation = travelViolation(m, t.run);
  if (!violation.empty())
    throw UnreachableInput({}, fmt::format("{}: {} (a smaller radius, spread or ballbar length may reach)", t.name, violation));
}

}  // namespace

namespace {

// One axis's tests for one sweep, built from where the test starts.
class AxisTestBuilder {
 public:
  AxisTestBuilder(const KinematicModel& nominal, const RotaryAxisTestOptions& o, int axis, std::vector<double> start)
      : nominal_(nominal), m_(*nominal.machine), o_(o), j_(axis), axis_(m_.axes[static_cast<size_t>(axis)]), q0_(std::move(start)) {
    head_ = axis_.side == Side::Tool;
    if (head_ && distanceFromLine(axisLine(nominal_, q0_, j_), toolBallInBed(Vec3::Zero())) < 1.0) {
      // The tool on the head axis's line: the other head axes tilted 30 deg (within travel) take it off.
      for (int k = 0; k < m_.commandedCount(); ++k) {
        const auto& other = m_.axes[static_cast<size_t>(k)];
        if (k == j_ || !other.isRotary() || other.side != Side::Tool) continue;
        q0_[static_cast<size_t>(k)] = other.travel ? std::clamp(30 * kDeg, other.travel->min, other.travel->max) : 30 * kDeg;
      }
      if (distanceFromLine(axisLine(nominal_, q0_, j_), toolBallInBed(Vec3::Zero())) < 1.0)
        throw InvalidInput("the tool lies on the " + axis_.name + " axis's line at every tilt of the head: no radial direction for its tests");
    }
    const AxisLine line = axisLine(nominal_, q0_, j_);
    const Vec3 tcp = toolBallInBed(Vec3::Zero());
    direction_ = line.direction;
    base_ = line.point;
    const Vec3 foot = line.point + line.direction * line.direction.dot(tcp - line.point);
    out_ = (tcp - foot).norm() > 1.0 ? Vec3((tcp - foot).normalized()) : across(line.direction);
    workpiece_ = workpiecePose(nominal_, q0_.data(), nullptr);
  }

  // A table axis's sphere starts at the axis's location point (where its tilts turn it, so that
  // the first R-test's radial deviations see its offsets alone), or, where the travel does not
  // reach there, level with the tool at the start pose.
  void startLevelWithTheTool() {
    const Vec3 tcp = toolBallInBed(Vec3::Zero());
    base_ = base_ + direction_ * direction_.dot(tcp - base_);
  }
  bool head() const { return head_; }

  // The R-tests at the two set-ups and the three ballbar tests over ±half (a full turn on a
  // continuous axis); notes for the tests not generated.
  std::vector<RotaryAxisTest> tests(double half, std::vector<std::string>& notes) const {
    const auto [from, to] = sweep(axis_, q0_[static_cast<size_t>(j_)], half);
    std::vector<RotaryAxisTest> out{rtest(1, 0.0, from, to)};
    // The second set-up `spread` along the line or beyond the tip: the other way, or half as far,
    // where the travel does not reach.
    std::optional<RotaryAxisTest> second;
    for (const double factor : {1.0, -1.0, 0.5, -0.5, 0.25, -0.25}) {
      if (head_ && factor < 0) continue;  // a tool ball is not inside the spindle
      auto t = rtest(2, factor * o_.spread, from, to);
      if (travelViolation(m_, t.run).empty()) {
        second = std::move(t);
        break;
      }
    }
    out.push_back(second ? std::move(*second) : rtest(2, o_.spread, from, to));
    for (const auto kind : {RotaryTestKind::BallbarRadial, RotaryTestKind::BallbarTangential, RotaryTestKind::BallbarAxial}) {
      try {
        out.push_back(ballbar(kind, from, to));
      } catch (const InvalidInput& e) {  // seed 002's set-up: the rotary axes at zero
        notes.push_back(fmt::format("{}-ballbar-{}: not generated: {} (the set-up puts every rotary axis at zero; the R-tests stand for it)",
                                    axis_.name, toString(kind), e.reason()));
      }
    }
    return out;
  }

 private:
  Vec3 toolBallInBed(const Vec3& ball) const { return toolChainPose(nominal_, q0_.data(), nullptr) * ball; }

  // The sphere (workpiece frame) and the tool ball (tool frame): on a head axis the tool ball
  // `offset` beyond the tool tip, on a table axis the sphere where the tool is at the start pose,
  // moved to the radius from the line and `offset` along it.
  std::pair<Vec3, Vec3> setUp(double offset) const {
    if (head_) {
      const Vec3 ball = -offset * m_.toolDirection;
      return {toolInWorkpiece(nominal_, q0_.data()) * ball, ball};
    }
    return {workpiece_.inverse() * (base_ + o_.radius * out_ + offset * direction_), Vec3::Zero()};
  }

  RotaryAxisTest rtest(int k, double offset, double from, double to) const {
    const auto [sphere, toolBall] = setUp(offset);
    RotaryAxisTest t;
    t.axis = axis_.name;
    t.kind = RotaryTestKind::RTest;
    t.name = fmt::format("{}-rtest-{}", axis_.name, k);
    t.from = from;
    t.to = axis_.travel ? to : to - (to - from) / o_.rtestPositions;  // a full turn: the last position is the first
    t.description = head_ ? fmt::format("R-test: {} with the linear axes, the tool ball {:g} mm beyond the tool tip", axis_.name, offset)
                          : fmt::format("R-test: {} with the linear axes, the sphere {:g} mm from its line, {:g} mm along it",
                                        axis_.name, o_.radius, offset);
    SphereTestSpec spec;
    spec.instrument = Instrument::RTest;
    spec.axis = axis_.name;
    spec.angles = evenAngles(t.from, t.to, o_.rtestPositions);
    spec.spheres = {sphere};
    spec.toolBall = toolBall;
    spec.pose = q0_;
    t.run = sphereTest(nominal_, spec).front();
    t.run.name = t.name;
    t.run.feed = o_.feed;
    t.planEntry = fmt::format("  - name: {}\n    sphere: {{axis: {}, from: {:.10g} deg, to: {:.10g} deg, points: {}, spheres: [{}]{}}}\n{}",
                              t.name, axis_.name, t.from / kDeg, t.to / kDeg, o_.rtestPositions, mm(sphere), poseEntry(m_, q0_, j_),
                              toolBall.isZero() ? "" : "    tool_ball: " + mm(toolBall) + "\n");
    return t;
  }

  RotaryAxisTest ballbar(RotaryTestKind kind, double from, double to) const {
    const auto [workBall, toolBall] = setUp(0.0);
    RotaryAxisTest t;
    t.axis = axis_.name;
    t.kind = kind;
    t.name = fmt::format("{}-ballbar-{}", axis_.name, toString(kind));
    t.from = from;
    t.to = to;
    t.description = fmt::format("ballbar {:g} mm in the {} direction of {}, {} with the linear axes", o_.ballbarLength, toString(kind),
                                axis_.name, axis_.name);
    BallbarRotarySpec spec;
    spec.axis = axis_.name;
    spec.mode = parseRotaryTestMode(toString(kind));
    spec.length = o_.ballbarLength;
    spec.workBall = workBall;
    spec.toolBall = toolBall;
    spec.from = from;
    spec.to = to;
    spec.points = o_.ballbarPoints;
    spec.pose = q0_;
    spec.feed = o_.feed;
    t.run = ballbarRotaryTest(nominal_, spec);
    t.run.name = t.name;
    t.planEntry = fmt::format("  - name: {}\n    rotary: {{axis: {}, mode: {}, length: {:.10g} mm, work_ball: {}, from: {:.10g} deg, to: {:.10g} deg, "
                              "points: {}, feed: {:.10g} mm/min{}}}\n{}",
                              t.name, axis_.name, toString(kind), o_.ballbarLength, mm(workBall), from / kDeg, to / kDeg, o_.ballbarPoints,
                              o_.feed, poseEntry(m_, q0_, j_), toolBall.isZero() ? "" : "    tool_ball: " + mm(toolBall) + "\n");
    return t;
  }

  const KinematicModel& nominal_;
  const Machine& m_;
  const RotaryAxisTestOptions& o_;
  int j_;
  const Axis& axis_;
  std::vector<double> q0_;
  bool head_ = false;
  Vec3 direction_, base_, out_;
  Pose workpiece_;
};

// The rotary axis whose position changes most over the run.
Eigen::Index turningAxis(const Machine& m, const MeasurementRun& run) {
  Eigen::Index best = -1;
  double widest = 0;
  for (int j = 0; j < m.commandedCount(); ++j) {
    if (!m.axes[static_cast<size_t>(j)].isRotary()) continue;
    const double range = run.q.col(j).maxCoeff() - run.q.col(j).minCoeff();
    if (range > widest) {
      widest = range;
      best = j;
    }
  }
  if (best < 0) throw InvalidInput(run.name + ": no rotary axis turns over the run");
  return best;
}

}  // namespace

const char* toString(RotaryTestKind kind) {
  switch (kind) {
    case RotaryTestKind::BallbarRadial:
      return "radial";
    case RotaryTestKind::BallbarTangential:
      return "tangential";
    case RotaryTestKind::BallbarAxial:
      return "axial";
    case RotaryTestKind::RTest:
      break;
  }
  return "rtest";
}

RotaryAxisTestSet rotaryAxisTests(const KinematicModel& nominal, const RotaryAxisTestOptions& o) {
  const Machine& m = *nominal.machine;
  if (!(o.radius > 0 && o.spread > 0 && o.ballbarLength > 0) || o.rtestPositions < 3 || o.ballbarPoints < 8)
    throw InvalidInput("rotary-axis tests: radius, spread and ballbar length must be positive, at least 3 R-test positions and 8 ballbar points");
  std::vector<std::string> axes = o.axes;
  if (axes.empty())
    for (int j = 0; j < m.commandedCount(); ++j)
      if (m.axes[static_cast<size_t>(j)].isRotary()) axes.push_back(m.axes[static_cast<size_t>(j)].name);
  if (axes.empty()) throw InvalidInput(m.name + " has no commanded rotary axis");
  RotaryAxisTestSet set;
  for (const auto& name : axes) {
    const int j = m.commandedAxisIndex(name);
    if (j < 0 || !m.axes[static_cast<size_t>(j)].isRotary()) throw InvalidInput("'" + name + "' is not a commanded rotary axis of " + m.name);
    AxisTestBuilder builder(nominal, o, j, startPose(m));
    const bool continuous = !m.axes[static_cast<size_t>(j)].travel;
    // The widest sweep (±90, 60, 45, 30, 15 deg) whose tests all stay within the travel, from the
    // axis's location point, else level with the tool.
    for (const double half : {90.0, 60.0, 45.0, 30.0, 15.0}) {
      std::vector<std::string> notes;
      auto tests = builder.tests(half * kDeg, notes);
      const auto within = [&](const std::vector<RotaryAxisTest>& ts) {
        return std::find_if(ts.begin(), ts.end(), [&](const RotaryAxisTest& t) { return !travelViolation(m, t.run).empty(); });
      };
      if (within(tests) != tests.end() && !builder.head()) {
        AxisTestBuilder level = builder;
        level.startLevelWithTheTool();
        std::vector<std::string> levelNotes;
        auto levelTests = level.tests(half * kDeg, levelNotes);
        if (within(levelTests) == levelTests.end()) {
          tests = std::move(levelTests);
          notes = std::move(levelNotes);
          notes.push_back(fmt::format("{}: the sphere level with the tool, not at the axis's location point (beyond the travel there)", name));
        }
      }
      const auto beyond = within(tests);
      if (beyond != tests.end()) {
        if (!continuous && half > 15) continue;
        requireWithinTravel(m, *beyond);
      }
      if (!continuous && half < 90)
        notes.push_back(fmt::format("{}: swept ±{:g} deg about its start, the widest of ±90, 60, 45, 30, 15 deg within the travel", name, half));
      for (auto& t : tests) set.tests.push_back(std::move(t));
      for (auto& n : notes) set.notes.push_back(std::move(n));
      break;
    }
  }
  return set;
}

RotaryTestResult evaluateRotaryTest(const KinematicModel& nominal, const MeasurementRun& run) {
  if (run.readings.rows() != run.poses() || run.poses() < 2) throw InvalidInput("a rotary-axis test needs its readings at every pose");
  if (run.instrument != Instrument::RTest && run.instrument != Instrument::Ballbar)
    throw InvalidInput("a rotary-axis test is read by an R-test or a ballbar");
  // The sphere is set at the tool ball at the first position: what the first reading shows is
  // the sphere's offset on the workpiece, which turns with it (as the ballbar's work ball is set).
  MeasurementRun fromStart = run;
  if (run.instrument == Instrument::RTest) {
    const Mat3 start = nominalFrame(nominal, run, 0).workpieceRotation;
    const Vec3 offset = start.transpose() * run.readings.row(0).transpose().head<3>();
    for (Eigen::Index i = 0; i < run.poses(); ++i)
      fromStart.readings.row(i).head<3>() -= (nominalFrame(nominal, run, i).workpieceRotation * offset).transpose();
  }
  RotaryTestResult r;
  if (run.instrument == Instrument::Ballbar) {
    r.quantities = {"length"};
    r.series = run.readings.leftCols(1);
    r.position = run.q.col(turningAxis(*nominal.machine, run));
  } else {
    const auto e = evaluateRTest(nominal, fromStart);
    r.position = e.position;
    if (!e.aboutTheAxis) throw InvalidInput("the R-test's sphere lies on the axis that turns: no radial and tangential directions");
    r.quantities = {"radial", "tangential", "axial"};
    const auto& c = e.aboutTheAxis->components;  // radial, axial, tangential
    r.series.resize(run.poses(), 3);
    r.series << c.col(0), c.col(2), c.col(1);
  }
  for (Eigen::Index q = 0; q < r.series.cols(); ++q) r.ranges.push_back(r.series.col(q).maxCoeff() - r.series.col(q).minCoeff());
  return r;
}

RotaryTestSensitivity rotaryTestSensitivities(const KinematicModel& nominal, const std::vector<RotaryAxisTest>& tests) {
  const Machine& m = *nominal.machine;
  const auto machine = nominal.machine;
  const ErrorModel zero = ErrorModel::zero(m);
  RotaryTestSensitivity s;
  for (const auto& p : parameterCatalogue(m, zero))
    if (p.kind == ParameterKind::Location) s.parameters.push_back(p);
  s.perTest.resize(tests.size());
  for (size_t t = 0; t < tests.size(); ++t) s.perTest[t].assign(tests[t].kind == RotaryTestKind::RTest ? 3 : 1, std::vector<double>(s.parameters.size()));
  for (size_t k = 0; k < s.parameters.size(); ++k) {
    const auto& p = s.parameters[k];
    const double unit = p.dimension == Dimension::Length ? kMicro : 1e-6;
    const KinematicModel model = compile(machine, singleError(m, zero, p, unit));
    for (size_t t = 0; t < tests.size(); ++t) {
      MeasurementRun run = tests[t].run;
      simulateRun(model, nominal, run);
      const auto result = evaluateRotaryTest(nominal, run);
      for (size_t q = 0; q < result.ranges.size(); ++q) s.perTest[t][q][k] = result.ranges[q] / kMicro;
    }
  }
  return s;
}

std::string rotaryTestProgram(const Machine& machine, const RotaryAxisTest& test, int decimals) {
  const auto& run = test.run;
  std::string out = fmt::format("(ISO 10791-6 {}: {})\n", test.name, test.description);
  if (run.instrument == Instrument::Ballbar)
    out += fmt::format("(work ball at {} in the workpiece frame, set at the tool ball at the first position; bar {:g} mm)\n",
                       mm(run.setup.target), run.setup.length);
  else
    out += fmt::format("(sphere at {} in the workpiece frame; read the R-test at each dwell)\n", mm(run.setup.target));
  if (!run.setup.toolBall.isZero()) out += fmt::format("(tool ball {} from the tool tip, tool frame)\n", mm(run.setup.toolBall));
  out += "G90 G21 G94\n";
  const auto names = machine.commandedAxisNames();
  const auto words = [&](Eigen::Index i) {
    std::string w;
    for (int j = 0; j < machine.commandedCount(); ++j)
      w += fmt::format(" {}{:.{}f}", names[static_cast<size_t>(j)], run.q(i, j) / machine.axes[static_cast<size_t>(j)].fileUnit(), decimals);
    return w;
  };
  out += "G0" + words(0) + "\n";
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    out += fmt::format("G1{} F{:g}\n", words(i), run.feed);
    if (run.instrument == Instrument::RTest) out += "G4 P1\n";
  }
  out += "M30\n";
  return out;
}

}  // namespace mtacc
