#include "mtacc/compensation/path_deviation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "tool_models.hpp"

namespace mtacc {
namespace {

constexpr int kMostSamples = 10000;  // a move
constexpr size_t kWindow = 400;      // chords searched beyond the last closest one, either way

// A block whose nominal TCP path is shorter than this is not sampled: the controller passes it
// in a millisecond. A compensated program writes one at each reversal, a step of the reversal's
// size that the axis's play takes up while the TCP stands; the reversal model, switching the
// direction at once, cannot say where the TCP is during it.
constexpr double kInstantBlock = 0.01;  // mm

// How many samples a move takes: its nominal TCP path (a 4-chord estimate) over the step; 0 for
// a block passed in an instant.
int samplesOf(const GcodeMove& move, const KinematicModel& nominal, double step, std::vector<double>& q) {
  double length = 0.0;
  move.at(0.0, q);
  Vec3 last = toolPosition(nominal, q.data());
  for (int k = 1; k <= 4; ++k) {
    move.at(k / 4.0, q);
    const Vec3 p = toolPosition(nominal, q.data());
    length += (p - last).norm();
    last = p;
  }
  if (length < kInstantBlock) return 0;
  return std::clamp(static_cast<int>(std::ceil(length / step)), 4, kMostSamples);
}

// The intended program's nominal TCP path sampled along its feed moves: the chords between the
// samples find the stretch nearest a point, the move itself (each sample's move and s) the
// nearest point on it.
struct IntendedPath {
  std::vector<Vec3> points;
  std::vector<const GcodeMove*> moves;
  std::vector<double> s;
  double length = 0.0;
};

IntendedPath sampledPath(ToolModels& models, const GcodeProgram& program, double step) {
  IntendedPath path;
  std::vector<double> q;
  for (const auto& move : program.moves) {
    if (move.mode == MotionMode::Rapid) continue;
    const KinematicModel& nominal = models(move.toolLength).nominal;
    const int n = std::max(1, samplesOf(move, nominal, step, q));
    for (int k = path.points.empty() ? 0 : 1; k <= n; ++k) {
      const double s = static_cast<double>(k) / n;
      move.at(s, q);
      const Vec3 p = toolPosition(nominal, q.data());
      if (!path.points.empty()) path.length += (p - path.points.back()).norm();
      path.points.push_back(p);
      path.moves.push_back(&move);
      path.s.push_back(s);
    }
  }
  return path;
}

struct Closest {
  double distance = std::numeric_limits<double>::infinity();
  size_t chord = 0;
};

Closest closestOnChords(const IntendedPath& path, const Vec3& x, size_t from, size_t to) {
  Closest best;
  for (size_t j = from; j < to; ++j) {
    const Vec3 a = path.points[j], d = path.points[j + 1] - a;
    const double squared = d.squaredNorm();
    const double t = squared > 0.0 ? std::clamp((x - a).dot(d) / squared, 0.0, 1.0) : 0.0;
    const double distance = (a + t * d - x).norm();
    if (distance < best.distance) best = {distance, j};
  }
  return best;
}

// The nearest point to x on the intended move about chord j (a chord's sagitta, step^2 / 8R,
// would be counted as deviation): golden-section search on the distance over the move's s, from
// half a chord before its start to half a chord past its end.
ToolPoint nearestOnMove(ToolModels& models, const IntendedPath& path, size_t j, const Vec3& x, std::vector<double>& q) {
  const GcodeMove& move = *path.moves[j + 1];
  const KinematicModel& nominal = models(move.toolLength).nominal;
  double lo = path.moves[j] == path.moves[j + 1] ? path.s[j] : 0.0, hi = path.s[j + 1];
  const double width = hi - lo;
  lo = std::max(0.0, lo - 0.5 * width);  // the nearest point may lie just past a chord's end
  hi = std::min(1.0, hi + 0.5 * width);
  auto at = [&](double s) {
    move.at(s, q);
    return toolPoint(nominal, q.data());
  };
  constexpr double kGolden = 0.6180339887498949;
  double a = hi - kGolden * (hi - lo), b = lo + kGolden * (hi - lo);
  double fa = (at(a).position - x).squaredNorm(), fb = (at(b).position - x).squaredNorm();
  for (int i = 0; i < 40; ++i) {  // 0.618^40: 4e-9 of the interval
    if (fa < fb) {
      hi = b, b = a, fb = fa;
      a = hi - kGolden * (hi - lo);
      fa = (at(a).position - x).squaredNorm();
    } else {
      lo = a, a = b, fa = fb;
      b = lo + kGolden * (hi - lo);
      fb = (at(b).position - x).squaredNorm();
    }
  }
  return at(0.5 * (lo + hi));
}

}  // namespace

ProgramPathDeviation programPathDeviation(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors,
                                          const GcodeProgram& program, const GcodeProgram* intended, const PathDeviationOptions& o) {
  if (!(o.step >= 1e-3 && o.step <= 100.0)) throw InvalidInput("the sampling step must lie in 0.001 to 100 mm");
  ToolModels models(machine, errors);
  IntendedPath path;
  if (intended) {
    path = sampledPath(models, *intended, o.step);
    if (path.points.size() < 2) throw InvalidInput("the intended program has no feed moves");
  }
  ProgramPathDeviation out;
  out.intendedLength = path.length;
  double sum = 0.0;
  size_t cursor = 0;
  bool located = false;
  std::vector<double> q, nearQ;
  std::vector<int> motion;
  for (const auto& move : program.moves) {
    if (move.mode == MotionMode::Rapid) {
      move.heldMotion(1.0, motion);
      continue;
    }
    const Models& m = models(move.toolLength);
    const int n = samplesOf(move, m.nominal, o.step, q);
    if (n == 0) {
      move.heldMotion(1.0, motion);
      ++out.instantBlocks;
      continue;
    }
    BlockDeviation block{move.line, 0.0, 0.0, 0};
    for (int k = 1; k <= n; ++k) {
      const double s = (k - 0.5) / n;  // the middle of each stretch: no sample on a block's ends, where an axis may reverse
      move.heldMotion(s, motion);
      move.at(s, q);
      const ToolPoint reached = toolPoint(m.actual, q.data(), motion.data());
      double position = 0.0, direction = 0.0;
      if (!intended) {
        const ToolPoint wanted = toolPoint(m.nominal, q.data());
        position = (reached.position - wanted.position).norm();
        direction = angleBetween(reached.direction, wanted.direction);
      } else {
        const size_t chords = path.points.size() - 1;
        Closest c = located ? closestOnChords(path, reached.position, cursor > kWindow ? cursor - kWindow : 0, std::min(chords, cursor + kWindow))
                            : closestOnChords(path, reached.position, 0, chords);
        // Far off the window (more than a step beyond the chord length there): look along the whole path.
        if (located && c.distance > 10.0 * o.step) c = closestOnChords(path, reached.position, 0, chords);
        located = true;
        cursor = c.chord;
        const ToolPoint nearest = nearestOnMove(models, path, c.chord, reached.position, nearQ);
        position = std::min(c.distance, (nearest.position - reached.position).norm());
        direction = angleBetween(reached.direction, nearest.direction);
      }
      block.maxPosition = std::max(block.maxPosition, position);
      block.maxDirection = std::max(block.maxDirection, direction);
      ++block.samples;
      sum += position * position;
    }
    out.total.maxPosition = std::max(out.total.maxPosition, block.maxPosition);
    out.total.maxDirection = std::max(out.total.maxDirection, block.maxDirection);
    out.total.samples += block.samples;
    out.blocks.push_back(block);
  }
  if (out.total.samples > 0) out.total.rmsPosition = std::sqrt(sum / out.total.samples);
  return out;
}

}  // namespace mtacc
