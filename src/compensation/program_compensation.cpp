#include "mtacc/compensation/program_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <span>

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

}  // namespace

class ProgramCompensator::Impl {
 public:
  Impl(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const ProgramCompensationOptions& options)
      : models_(machine, errors), o_(options) {
    for (int k = 0; k < machine->commandedCount(); ++k) rotary_.push_back(machine->axes[static_cast<size_t>(k)].isRotary());
    out_.largestCorrection.assign(static_cast<size_t>(machine->commandedCount()), 0.0);
    correction_.assign(out_.largestCorrection.size(), 0.0);
    previousCorrection_ = correction_;
  }

  // The window: the point before the move (the start, solved first, not written), then its points.
  std::span<const CompensatedPoint> next(const GcodeMove& move, int index) {
    if (points_.empty()) {
      move.heldMotion(0.5, lastMotion_);
      points_.push_back(solve(0, move, 0.0, lastMotion_, false));
    } else {
      points_.erase(points_.begin(), points_.end() - 1);
    }
    compensate(index, move);
    out_.written += static_cast<long long>(points_.size() - 1);
    return points_;
  }

  const CompensationSummary& summary() const { return out_; }

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
  // directions along the move from a to b. `a` is an element of points_, which a push may
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
      points_.push_back(std::move(b));
      return;
    }
    CompensatedPoint middle = solve(index, move, s, motion);
    refine(index, move, a, from, middle, motion, depth + 1);
    refine(index, move, points_.back(), s, std::move(b), motion, depth + 1);
  }

  void compensate(int index, const GcodeMove& move) {
    if (move.mode == MotionMode::Rapid) {
      move.heldMotion(0.5, lastMotion_);
      points_.push_back(solve(index, move, 1.0, lastMotion_));
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
        const CompensatedPoint& start = points_.back();  // the previous move's end is this one's start
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
    const auto& last = points_.back().q;
    for (size_t k = 0; k < step.q.size(); ++k)
      if (std::abs(step.q[k] - last[k]) >= 0.5e-5 * (rotary_[k] ? kDeg : 1.0)) {
        points_.push_back(std::move(step));
        return;
      }
  }

  ToolModels models_;
  std::vector<bool> rotary_;  // per commanded axis
  const ProgramCompensationOptions o_;
  CompensationSummary out_;
  std::vector<CompensatedPoint> points_;
  std::vector<double> correction_, previousCorrection_, start_;
  std::vector<double> programmed_, written_;  // scratch of solve and refine
  std::vector<int> lastMotion_;  // the direction of motion the last point was solved for
  std::vector<int> after_, before_;  // a move's directions after its start or a reversal, and before its end or the next
  std::vector<double> ends_;  // where a move's pieces end: its reversals and 1
  const Models* lastModels_ = nullptr;
  ErrorIkJacobian jacobian_;
  ErrorIkSolution solution_;  // of the last point solved, its storage reused
};

ProgramCompensator::ProgramCompensator(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors,
                                       const ProgramCompensationOptions& options)
    : impl_(std::make_unique<Impl>(machine, errors, options)) {}
ProgramCompensator::~ProgramCompensator() = default;

std::span<const CompensatedPoint> ProgramCompensator::compensate(const GcodeMove& move, int index) { return impl_->next(move, index); }
const CompensationSummary& ProgramCompensator::summary() const { return impl_->summary(); }

namespace {

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
class DeviationSum::Impl {
 public:
  Impl(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors) : models_(machine, errors) {}

  void add(const CompensatedPoint& a, const CompensatedPoint& b, const GcodeMove& move) {
    const double from = a.move == b.move ? a.s : 0.0;
    if (b.s == from) return;  // a step at a reversal: the machine takes up its reversal there, standing
    // A written segment lies between reversals: its direction of motion is that of its middle
    // (at its ends an axis may be at its reversal point, standing for an instant).
    move.heldMotion(0.5 * (from + b.s), motion_);
    if (move.mode == MotionMode::Rapid) return;
    const Models& m = models_(move.toolLength);
    for (int k = 1; k <= 4; ++k) {
      const double t = k / 4.0, s = from + t * (b.s - from);
      move.at(s, programmed_);
      lerp(a.q, b.q, t, written_);
      const ToolPoint wanted = toolPoint(m.nominal, programmed_.data());
      const ToolPoint uncompensated = toolPoint(m.actual, programmed_.data(), motion_.data()),
                      compensated = toolPoint(m.actual, written_.data(), motion_.data());
      const double eBefore = (uncompensated.position - wanted.position).norm(), eAfter = (compensated.position - wanted.position).norm();
      d_.before.maxPosition = std::max(d_.before.maxPosition, eBefore);
      d_.after.maxPosition = std::max(d_.after.maxPosition, eAfter);
      d_.before.maxDirection = std::max(d_.before.maxDirection, angleBetween(uncompensated.direction, wanted.direction));
      d_.after.maxDirection = std::max(d_.after.maxDirection, angleBetween(compensated.direction, wanted.direction));
      before_ += eBefore * eBefore;
      after_ += eAfter * eAfter;
      ++d_.after.samples;
    }
  }

  ProgramDeviation result() const {
    ProgramDeviation d = d_;
    d.before.samples = d.after.samples;
    if (d.after.samples > 0) {
      d.before.rmsPosition = std::sqrt(before_ / d.before.samples);
      d.after.rmsPosition = std::sqrt(after_ / d.after.samples);
    }
    return d;
  }

 private:
  ToolModels models_;
  ProgramDeviation d_;
  double before_ = 0.0, after_ = 0.0;
  std::vector<int> motion_;
  std::vector<double> programmed_, written_;
};

DeviationSum::DeviationSum(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors)
    : impl_(std::make_unique<Impl>(machine, errors)) {}
DeviationSum::~DeviationSum() = default;
void DeviationSum::add(std::span<const CompensatedPoint> points, const GcodeMove& move) {
  for (size_t i = 1; i < points.size(); ++i) impl_->add(points[i - 1], points[i], move);
}
ProgramDeviation DeviationSum::result() const { return impl_->result(); }

ProgramDeviation programDeviation(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                  const std::vector<CompensatedPoint>& points) {
  DeviationSum sum(machine, errors);
  // Each move's points with the one before them.
  for (size_t first = 1; first < points.size();) {
    size_t end = first;
    while (end < points.size() && points[end].move == points[first].move) ++end;
    sum.add(std::span(points).subspan(first - 1, end - first + 1), program.moves[static_cast<size_t>(points[first].move)]);
    first = end;
  }
  return sum.result();
}

CompensatedProgram compensateProgram(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                     const ProgramCompensationOptions& options) {
  CompensatedProgram out;
  ProgramCompensator compensator(machine, errors, options);
  // A point per move and a few more where axes reverse (arcs add their chords as they come):
  // the vector grows once instead of doubling through a million points.
  out.points.reserve(program.moves.size() + program.moves.size() / 16 + 1);
  for (size_t m = 0; m < program.moves.size(); ++m) {
    const auto points = compensator.compensate(program.moves[m], static_cast<int>(m));
    out.points.insert(out.points.end(), points.begin() + (m == 0 ? 0 : 1), points.end());
  }
  static_cast<CompensationSummary&>(out) = compensator.summary();
  if (out.largestCorrection.empty()) out.largestCorrection.assign(static_cast<size_t>(machine->commandedCount()), 0.0);
  return out;
}

bool isPercentLine(const GcodeLine& line) { return line.kept.size() == 1 && line.kept.front().starts_with('%') && line.move < 0; }

std::string compensatedGcodePreamble(const GcodeLine* percent, const std::string& header) {
  std::string g = percent ? percent->kept.front() + "\n" : "";
  for (auto h : splitList(header, '\n')) {
    std::replace(h.begin(), h.end(), '(', '[');  // a comment ends at the first ')': the machine's name may hold parentheses
    std::replace(h.begin(), h.end(), ')', ']');
    fmt::format_to(std::back_inserter(g), "({})\n", h);
  }
  return g + "G21 G90\n";
}

void CompensatedGcodeWriter::line(std::string& g, const GcodeLine& l, const GcodeMove* move, std::span<const CompensatedPoint> points) {
  std::string before = l.sequence, after;
  for (const auto& word : l.kept) {
    // A ';' comment runs to the end of the line: it goes last.
    std::string& to = move && (actsAfterMotion(word) || word.starts_with(';')) ? after : before;
    to += (to.empty() ? "" : " ") + word;
  }
  if (!move) {
    g += before + "\n";
    return;
  }
  const size_t axes = static_cast<size_t>(machine_.commandedCount());
  for (size_t i = 0; i < points.size(); ++i) {
    const CompensatedPoint& p = points[i];
    if (i == 0 && !before.empty()) fmt::format_to(std::back_inserter(g), "{} ", before);
    g.append(move->mode == MotionMode::Rapid ? "G0" : "G1", 2);
    for (size_t k = 0; k < axes; ++k) {
      const Axis& a = machine_.axes[k];
      appendWord(g, a.name, a.isRotary() ? p.q[k] / kDeg : p.q[k]);
    }
    if (move->mode != MotionMode::Rapid && move->feed != feed_) {
      fmt::format_to(std::back_inserter(g), " F{:g}", move->feed);
      feed_ = move->feed;
    }
    if (i + 1 == points.size() && !after.empty()) fmt::format_to(std::back_inserter(g), " {}", after);
    g += '\n';
  }
}

std::string compensatedGcode(const Machine& m, const GcodeProgram& program, const CompensatedProgram& compensated,
                             const std::string& header) {
  const auto axes = static_cast<size_t>(m.commandedCount());
  const bool percent = !program.lines.empty() && isPercentLine(program.lines.front());
  std::string g = compensatedGcodePreamble(percent ? &program.lines.front() : nullptr, header);
  // About a dozen characters per axis on every point written (" X-123.45678"): grown once.
  g.reserve(compensated.points.size() * (axes * 12 + 8) + program.lines.size() * 8);
  CompensatedGcodeWriter writer(m);
  size_t point = 1;  // points[0] is the start, not written
  for (size_t line = percent ? 1 : 0; line < program.lines.size(); ++line) {
    const GcodeLine& l = program.lines[line];
    const size_t first = point;
    while (l.move >= 0 && point < compensated.points.size() && compensated.points[point].move == l.move) ++point;
    writer.line(g, l, l.move >= 0 ? &program.moves[static_cast<size_t>(l.move)] : nullptr,
                std::span(compensated.points).subspan(first, point - first));
  }
  return g;
}

}  // namespace mtacc
