#include "mtacc/virtual_controller/motion_interpolator.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {

namespace {

using Point = Eigen::VectorXd;

void requirePositive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) throw InvalidInput(std::string("motion: ") + what + " must be positive and finite");
}

// The path in FGROUP units (rotary axes in deg), repeated points dropped.
std::vector<Point> pathPoints(const std::vector<std::vector<double>>& path, const std::vector<bool>& rotary) {
  std::vector<Point> points;
  for (const auto& row : path) {
    if (row.size() != rotary.size()) throw InvalidInput("motion: a path point has another number of axes");
    Point p(static_cast<long>(row.size()));
    for (size_t a = 0; a < row.size(); ++a) {
      if (!std::isfinite(row[a])) throw InvalidInput("motion: a path point is not finite");
      p[static_cast<long>(a)] = rotary[a] ? row[a] / kDeg : row[a];
    }
    if (points.empty() || (p - points.back()).norm() > 1e-12) points.push_back(p);
  }
  if (points.size() < 2) throw InvalidInput("motion: the path needs two distinct points");
  return points;
}

// Points every `step` along the polyline, the last one at its end.
std::vector<Point> evenlySpaced(const std::vector<Point>& points, double step) {
  std::vector<Point> out{points.front()};
  double carried = 0.0;  // path length since the last point put out
  for (size_t i = 1; i < points.size(); ++i) {
    const Point d = points[i] - points[i - 1];
    const double length = d.norm();
    double at = step - carried;
    for (; at < length; at += step) out.push_back(points[i - 1] + d * (at / length));
    carried = length - (at - step);
  }
  if ((out.back() - points.back()).norm() > 1e-9 * step) out.push_back(points.back());
  return out;
}

// Gaussian smoothing along evenly spaced points; beyond the ends the path is mirrored through
// its end points, so that the ends stay where they are and a straight end stays straight.
std::vector<Point> rounded(const std::vector<Point>& p, double sigmaInSteps) {
  const auto n = static_cast<long>(p.size());
  const long half = static_cast<long>(std::ceil(4 * sigmaInSteps));
  if (half == 0) return p;
  std::vector<double> weights(static_cast<size_t>(2 * half + 1));
  double total = 0.0;
  for (long k = -half; k <= half; ++k) total += weights[static_cast<size_t>(k + half)] = std::exp(-0.5 * k * k / (sigmaInSteps * sigmaInSteps));
  const auto at = [&](long i) -> Point {
    if (i < 0) return 2 * p.front() - p[static_cast<size_t>(std::min(-i, n - 1))];
    if (i >= n) return 2 * p.back() - p[static_cast<size_t>(std::max(2 * (n - 1) - i, 0L))];
    return p[static_cast<size_t>(i)];
  };
  std::vector<Point> out(p.size());
  for (long i = 0; i < n; ++i) {
    Point sum = Point::Zero(p.front().size());
    for (long k = -half; k <= half; ++k) sum += weights[static_cast<size_t>(k + half)] * at(i + k);
    out[static_cast<size_t>(i)] = sum / total;
  }
  return out;
}

}  // namespace

SampledTrace interpolateMotion(const std::vector<std::vector<double>>& path, const std::vector<bool>& rotary, double feed,
                               const InterpolatorLimits& limits, double period) {
  requirePositive(feed, "the feed");
  requirePositive(limits.acceleration, "the acceleration");
  requirePositive(period, "the period");
  if (!(limits.cornerRounding >= 0.0 && limits.jerkTime >= 0.0 && limits.dwell >= 0.0) ||
      !std::isfinite(limits.cornerRounding + limits.jerkTime + limits.dwell))
    throw InvalidInput("motion: corner rounding, jerk time and dwell must be finite and not negative");
  const auto corners = pathPoints(path, rotary);
  double length = 0.0;
  for (size_t i = 1; i < corners.size(); ++i) length += (corners[i] - corners[i - 1]).norm();
  const double step = limits.cornerRounding > 0 ? std::min(limits.cornerRounding / 4, length / 200) : length / 2000;
  if (length / step > 1e7) throw InvalidInput("motion: the path is too long for its corner rounding (over 10^7 points)");
  const auto points = rounded(evenlySpaced(corners, step), limits.cornerRounding / step);

  // Speed limits: the feed, and sqrt(a / curvature) from the turn at each point.
  const size_t n = points.size();
  const double top = feed / 60.0;
  std::vector<double> gap(n, 0.0), speed(n, top);
  for (size_t i = 1; i < n; ++i) gap[i] = (points[i] - points[i - 1]).norm();
  for (size_t i = 1; i + 1 < n; ++i) {
    const Point in = points[i] - points[i - 1], out = points[i + 1] - points[i];
    if (gap[i] == 0.0 || gap[i + 1] == 0.0) continue;
    const double turn = std::acos(std::clamp(in.dot(out) / (gap[i] * gap[i + 1]), -1.0, 1.0));
    const double curvature = turn / ((gap[i] + gap[i + 1]) / 2);
    if (curvature > 0) speed[i] = std::min(top, std::sqrt(limits.acceleration / curvature));
  }
  speed.front() = speed.back() = 0.0;
  for (size_t i = 1; i < n; ++i) speed[i] = std::min(speed[i], std::sqrt(speed[i - 1] * speed[i - 1] + 2 * limits.acceleration * gap[i]));
  for (size_t i = n - 1; i-- > 0;) speed[i] = std::min(speed[i], std::sqrt(speed[i + 1] * speed[i + 1] + 2 * limits.acceleration * gap[i + 1]));

  // Time at each point, constant acceleration between points.
  std::vector<double> time(n, 0.0);
  for (size_t i = 1; i < n; ++i) time[i] = time[i - 1] + (gap[i] > 0 ? 2 * gap[i] / (speed[i - 1] + speed[i]) : 0.0);
  const auto dwellSamples = static_cast<long>(std::llround(limits.dwell / period));
  const auto filterSamples = std::max(1L, static_cast<long>(std::llround(limits.jerkTime / period)));
  const double motionSamples = std::ceil(time.back() / period);
  if (motionSamples + 2.0 * static_cast<double>(dwellSamples + filterSamples) > 1e8)
    throw InvalidInput("motion: more than 10^8 samples at this period");

  std::vector<Point> raw;
  for (long k = 0; k < dwellSamples; ++k) raw.push_back(points.front());
  for (size_t i = 1, k = 0; k <= static_cast<size_t>(motionSamples); ++k) {
    const double t = std::min(static_cast<double>(k) * period, time.back());
    while (i < n - 1 && time[i] < t) ++i;
    const double dt = t - time[i - 1], span = time[i] - time[i - 1];
    const double acceleration = span > 0 ? (speed[i] - speed[i - 1]) / span : 0.0;
    const double travelled = speed[i - 1] * dt + 0.5 * acceleration * dt * dt;
    raw.push_back(gap[i] > 0 ? points[i - 1] + (points[i] - points[i - 1]) * std::clamp(travelled / gap[i], 0.0, 1.0) : points[i]);
  }
  for (long k = 0; k < dwellSamples + filterSamples; ++k) raw.push_back(points.back());

  // Causal moving average of `filterSamples` samples, the command at rest on the first point before time 0.
  SampledTrace trace{0.0, period, std::vector<std::vector<double>>(rotary.size(), std::vector<double>(raw.size()))};
  const auto m = static_cast<size_t>(filterSamples);
  Point window = static_cast<double>(m) * raw.front();
  for (size_t k = 0; k < raw.size(); ++k) {
    window += raw[k] - (k >= m ? raw[k - m] : raw.front());
    for (size_t a = 0; a < rotary.size(); ++a) {
      const double averaged = window[static_cast<long>(a)] / static_cast<double>(m);
      trace.channels[a][k] = rotary[a] ? averaged * kDeg : averaged;
    }
  }
  return trace;
}

}  // namespace mtacc
