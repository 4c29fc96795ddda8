#include "mtacc/compensation/program_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>

#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "tool_models.hpp"

namespace mtacc {
namespace {

// How far along a move (in s) its direction of motion is taken just before or after a point.
constexpr double kSide = 1e-9;

void lerp(const AxisPositions& a, const AxisPositions& b, double t, std::vector<double>& q) {
  q.resize(a.size());
  for (size_t k = 0; k < q.size(); ++k) q[k] = a[k] + t * (b[k] - a[k]);
}

class Compensator {
 public:
  Compensator(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
              const ProgramCompensationOptions& options)
      : models_(machine, errors), program_(program), o_(options) {
    for (int k = 0; k < machine->commandedCount(); ++k) rotary_.push_back(machine->axes[static_cast<size_t>(k)].isRotary());
    out_.largestCorrection.assign(static_cast<size_t>(machine->commandedCount()), 0.0);
    correction_.assign(out_.largestCorrection.size(), 0.0);
    previousCorrection_ = correction_;
  }

  CompensatedProgram run() {
    if (program_.moves.empty()) return out_;
    // A point per move and a few more where axes reverse (arcs add their chords as they come):
    // the vector grows once instead of doubling through a million points.
    out_.points.reserve(program_.moves.size() + program_.moves.size() / 16 + 1);
    const GcodeMove& first = program_.moves.front();
    first.heldMotion(0.5, lastMotion_);
    out_.points.push_back(solve(0, first, 0.0, lastMotion_, false));
    for (size_t m = 0; m < program_.moves.size(); ++m) compensate(static_cast<int>(m));
    return std::move(out_);
  }

 private:
  // `counted`: the point is written (the start, before the first move, is not: where the
  // machine stands then is the controller's business).
  CompensatedPoint solve(int index, const GcodeMove& move, double s, const std::vector<int>& motion, bool counted = true) {
    const Models& models = models_(move.toolLength);
    std::vector<double>& q = programmed_;
    move.at(s, q);
    const ToolPoint wanted = toolPoint(models.nominal, q.data());
    // The correction changes smoothly along a program: extrapolated from the linearised solutions
    // of the last two points (ErrorIkSolution::qLinearised), it leaves the Newton iteration
    // little or nothing to do.
    start_.resize(q.size());
    for (size_t k = 0; k < q.size(); ++k) start_[k] = q[k] + 2.0 * correction_[k] - previousCorrection_[k];
    if (&models != lastModels_) jacobian_.valid = false;
    lastModels_ = &models;
    ErrorIkSolution& solution = solution_;
    refineWithErrors(models.actual, wanted.position, wanted.direction, start_, o_.ik, jacobian_, solution, false, motion.data());
    previousCorrection_.swap(correction_);
    for (size_t k = 0; k < q.size(); ++k) correction_[k] = solution.qLinearised[k] - q[k];
    const CompensatedPoint point{index, s, {solution.q.begin(), solution.q.end()}, solution.positionResidual, solution.directionResidual};
    if (!counted) return point;
    for (size_t k = 0; k < q.size(); ++k) out_.largestCorrection[k] = std::max(out_.largestCorrection[k], std::abs(point.q[k] - q[k]));
    out_.largestResidual = std::max(out_.largestResidual, solution.positionResidual);
    const bool problem = !solution.converged || solution.singular || !solution.travelViolation.empty();
    out_.notConverged += solution.converged ? 0 : 1;
    out_.singular += solution.singular ? 1 : 0;
    if (problem && out_.firstProblemLine == 0) out_.firstProblemLine = move.line;
    if (!solution.travelViolation.empty() && out_.travelViolation.empty()) {
      out_.travelViolation = solution.travelViolation;
      out_.travelViolationLine = move.line;
    }
    return point;
  }

  // Where the written segment a-b, interpolated by the controller, leaves the nominal path at
  // its midpoint by more than the tolerances, it is halved.
  // `from`: where a lies on this move (0 for the previous move's end); `motion`: the axes'
  // directions along the move from a to b. `a` is an element of out_.points, which a push may
  // move: no frame reads its `a` after the first push below it (the second half starts from
  // the point pushed last).
  void refine(int index, const GcodeMove& move, const CompensatedPoint& a, double from, CompensatedPoint b, const std::vector<int>& motion,
              int depth) {
    const Models& models = models_(move.toolLength);
    const double s = 0.5 * (from + b.s);
    lerp(a.q, b.q, 0.5, written_);
    move.at(s, programmed_);
    const ToolPoint reached = toolPoint(models.actual, written_.data(), motion.data()), wanted = toolPoint(models.nominal, programmed_.data());
    // What the ends themselves cannot correct (the direction at a singular pose, on a machine
    // without two rotary axes) is not the interpolation's fault.
    const double position = o_.tolerance + std::max(a.positionResidual, b.positionResidual);
    const double direction = o_.directionTolerance + std::max(a.directionResidual, b.directionResidual);
    if (depth >= o_.maxSplits || ((reached.position - wanted.position).norm() <= position &&
                                  angleBetween(reached.direction, wanted.direction) <= direction)) {
      out_.points.push_back(std::move(b));
      return;
    }
    CompensatedPoint middle = solve(index, move, s, motion);
    refine(index, move, a, from, middle, motion, depth + 1);
    refine(index, move, out_.points.back(), s, std::move(b), motion, depth + 1);
  }

  void compensate(int index) {
    const GcodeMove& move = program_.moves[static_cast<size_t>(index)];
    if (move.mode == MotionMode::Rapid) {
      move.heldMotion(0.5, lastMotion_);
      out_.points.push_back(solve(index, move, 1.0, lastMotion_));
      return;
    }
    // Where an axis reverses, the reversal errors step: the program steps with them, a point
    // solved with the direction before and one with the direction after, at the same place (the
    // move's start when it sets off the other way, and an arc's quadrant points).
    ends_.clear();
    if (move.isArc()) ends_ = move.reversals();
    ends_.push_back(1.0);
    double from = 0.0;
    after_ = lastMotion_;
    move.heldMotion(std::min(kSide, 0.5), after_);
    if (after_ != lastMotion_) pushStep(solve(index, move, 0.0, after_));
    for (const double to : ends_) {
      // Arcs start as chords within the tolerance (sagitta r (1 - cos(angle / 2))), then halve.
      int pieces = 1;
      if (move.isArc()) {
        const double r = move.radius(), angle = std::abs(move.sweep) * (to - from);
        const double chordAngle = r > o_.tolerance ? 2.0 * std::acos(1.0 - o_.tolerance / r) : angle;
        pieces = std::max(2, static_cast<int>(std::ceil(angle / chordAngle)));
      }
      // A straight move goes one way throughout.
      before_ = after_;
      if (move.isArc()) move.heldMotion(to - std::min(kSide, 0.5 * (to - from)), before_);
      for (int i = 1; i <= pieces; ++i) {
        CompensatedPoint end = solve(index, move, from + (to - from) * i / pieces, before_);
        const CompensatedPoint& start = out_.points.back();  // the previous move's end is this one's start
        refine(index, move, start, start.move == index ? start.s : 0.0, std::move(end), before_, 0);
      }
      lastMotion_ = before_;
      if (to < 1.0) {
        after_ = before_;
        move.heldMotion(to + std::min(kSide, 0.5 * (1.0 - to)), after_);
        pushStep(solve(index, move, to, after_));
        lastMotion_ = after_;
      }
      from = to;
    }
  }

  // A step at a reversal is written only where the reversal errors move the commands by what
  // the program's five decimals (mm, deg) show: without them it would be a block of no length.
  void pushStep(CompensatedPoint step) {
    const auto& last = out_.points.back().q;
    for (size_t k = 0; k < step.q.size(); ++k)
      if (std::abs(step.q[k] - last[k]) >= 0.5e-5 * (rotary_[k] ? kDeg : 1.0)) {
        out_.points.push_back(std::move(step));
        return;
      }
  }

  ToolModels models_;
  std::vector<bool> rotary_;  // per commanded axis
  const GcodeProgram& program_;
  const ProgramCompensationOptions& o_;
  CompensatedProgram out_;
  std::vector<double> correction_, previousCorrection_, start_;
  std::vector<double> programmed_, written_;  // scratch of solve and refine
  std::vector<int> lastMotion_;  // the direction of motion the last point was solved for
  std::vector<int> after_, before_;  // a move's directions after its start or a reversal, and before its end or the next
  std::vector<double> ends_;  // where a move's pieces end: its reversals and 1
  const Models* lastModels_ = nullptr;
  ErrorIkJacobian jacobian_;
  ErrorIkSolution solution_;  // of the last point solved, its storage reused
};

// " X-123.45678": the word of axis `name` at v with five decimals, as "{:.5f}" writes it up to
// the rounding of v * 1e5, appended at once: the writer's inner loop writes five words on each
// of a million lines, where fmt's general float path and appending piece by piece were the
// larger part of the time.
void appendWord(std::string& out, const std::string& name, double v) {
  const double scaled = std::round(std::abs(v) * 1e5);
  if (!(scaled < 9e15) || name.size() > 8) {
    fmt::format_to(std::back_inserter(out), " {}{:.5f}", name, v);
    return;
  }
  char text[32];  // the space, 8 letters of name, the sign, 11 whole digits (below 9e10), the point, 5 decimals
  char* p = text;
  *p++ = ' ';
  p = std::copy(name.begin(), name.end(), p);
  const auto n = static_cast<uint64_t>(scaled);
  if (v < 0 && n != 0) *p++ = '-';
  const fmt::format_int whole(n / 100000);
  p = std::copy_n(whole.data(), whole.size(), p);
  *p++ = '.';
  for (int i = 5, f = static_cast<int>(n % 100000); i > 0; --i, f /= 10) p[i - 1] = static_cast<char>('0' + f % 10);
  out.append(text, p + 5);
}

// RS-274/NGC stops a program after the motion of its line; everything else kept acts before it.
bool actsAfterMotion(const std::string& word) {
  return word == "M0" || word == "M00" || word == "M1" || word == "M01" || word == "M2" || word == "M02" || word == "M30" ||
         word == "M60";
}

}  // namespace

// Every feed segment sampled at quarters: the controller's linear interpolation of the written
// commands against the program's nominal path at the same place on the move, and the program
// as written (no correction) at the same places for `before`.
ProgramDeviation programDeviation(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                  const std::vector<CompensatedPoint>& points) {
  ToolModels models(machine, errors);
  ProgramDeviation d;
  double before = 0.0, after = 0.0;
  std::vector<int> motion;
  std::vector<double> programmed, written;
  for (size_t i = 1; i < points.size(); ++i) {
    const CompensatedPoint &a = points[i - 1], &b = points[i];
    const GcodeMove& move = program.moves[static_cast<size_t>(b.move)];
    const double from = a.move == b.move ? a.s : 0.0;
    if (b.s == from) continue;  // a step at a reversal: the machine takes up its reversal there, standing
    // A written segment lies between reversals: its direction of motion is that of its middle
    // (at its ends an axis may be at its reversal point, standing for an instant).
    move.heldMotion(0.5 * (from + b.s), motion);
    if (move.mode == MotionMode::Rapid) continue;
    const Models& m = models(move.toolLength);
    for (int k = 1; k <= 4; ++k) {
      const double t = k / 4.0, s = from + t * (b.s - from);
      move.at(s, programmed);
      lerp(a.q, b.q, t, written);
      const ToolPoint wanted = toolPoint(m.nominal, programmed.data());
      const ToolPoint uncompensated = toolPoint(m.actual, programmed.data(), motion.data()),
                      compensated = toolPoint(m.actual, written.data(), motion.data());
      const double eBefore = (uncompensated.position - wanted.position).norm(), eAfter = (compensated.position - wanted.position).norm();
      d.before.maxPosition = std::max(d.before.maxPosition, eBefore);
      d.after.maxPosition = std::max(d.after.maxPosition, eAfter);
      d.before.maxDirection = std::max(d.before.maxDirection, angleBetween(uncompensated.direction, wanted.direction));
      d.after.maxDirection = std::max(d.after.maxDirection, angleBetween(compensated.direction, wanted.direction));
      before += eBefore * eBefore;
      after += eAfter * eAfter;
      ++d.after.samples;
    }
  }
  d.before.samples = d.after.samples;
  if (d.after.samples > 0) {
    d.before.rmsPosition = std::sqrt(before / d.before.samples);
    d.after.rmsPosition = std::sqrt(after / d.after.samples);
  }
  return d;
}

CompensatedProgram compensateProgram(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                     const ProgramCompensationOptions& options) {
  return Compensator(machine, errors, program, options).run();
}

std::string compensatedGcode(const Machine& m, const GcodeProgram& program, const CompensatedProgram& compensated,
                             const std::string& header) {
  const auto axes = static_cast<size_t>(m.commandedCount());
  std::string g;
  // About a dozen characters per axis on every point written (" X-123.45678"): grown once.
  g.reserve(compensated.points.size() * (axes * 12 + 8) + program.lines.size() * 8);
  auto out = std::back_inserter(g);
  size_t line = 0;
  if (!program.lines.empty() && program.lines.front().kept.size() == 1 && program.lines.front().kept.front().starts_with('%'))
    g += program.lines[line++].kept.front() + "\n";
  for (auto h : splitList(header, '\n')) {
    std::replace(h.begin(), h.end(), '(', '[');  // a comment ends at the first ')': the machine's name may hold parentheses
    std::replace(h.begin(), h.end(), ')', ']');
    fmt::format_to(out, "({})\n", h);
  }
  g += "G21 G90\n";
  size_t point = 1;  // points[0] is the start, not written
  double feed = -1.0;
  for (; line < program.lines.size(); ++line) {
    const GcodeLine& l = program.lines[line];
    std::string before = l.sequence, after;
    for (const auto& word : l.kept) {
      // A ';' comment runs to the end of the line: it goes last.
      std::string& to = l.move >= 0 && (actsAfterMotion(word) || word.starts_with(';')) ? after : before;
      to += (to.empty() ? "" : " ") + word;
    }
    if (l.move < 0) {
      g += before + "\n";
      continue;
    }
    const GcodeMove& move = program.moves[static_cast<size_t>(l.move)];
    bool firstSegment = true;
    while (point < compensated.points.size() && compensated.points[point].move == l.move) {
      const CompensatedPoint& p = compensated.points[point++];
      if (firstSegment && !before.empty()) fmt::format_to(out, "{} ", before);
      g.append(move.mode == MotionMode::Rapid ? "G0" : "G1", 2);
      for (size_t k = 0; k < axes; ++k) {
        const Axis& a = m.axes[k];
        appendWord(g, a.name, a.isRotary() ? p.q[k] / kDeg : p.q[k]);
      }
      if (move.mode != MotionMode::Rapid && move.feed != feed) {
        fmt::format_to(out, " F{:g}", move.feed);
        feed = move.feed;
      }
      const bool last = point == compensated.points.size() || compensated.points[point].move != l.move;
      if (last && !after.empty()) fmt::format_to(out, " {}", after);
      g += '\n';
      firstSegment = false;
    }
  }
  return g;
}

}  // namespace mtacc
