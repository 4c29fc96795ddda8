#include "mtacc/core/uniform_spline.hpp"

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

namespace {

// Second derivatives of the uniform not-a-knot spline, scaled by h^2 / 6 (s_i = M_i h^2 / 6):
// the rows s_{i-1} + 4 s_i + s_{i+1} = y_{i-1} - 2 y_i + y_{i+1} for i = 1 .. n-2, with
// s_0 = 2 s_1 - s_2 and s_{n-1} = 2 s_{n-2} - s_{n-3} (a continuous third derivative at the
// second and second-last samples) substituted, which turns the first and last rows into 6 s = d.
std::vector<double> notAKnotCurvature(std::span<const double> y) {
  const size_t n = y.size(), last = n - 2;
  std::vector<double> s(n, 0.0), upper(n, 0.0);
  for (size_t i = 1; i <= last; ++i) {
    const bool boundaryRow = i == 1 || i == last;
    const double below = boundaryRow ? 0.0 : 1.0, diagonal = boundaryRow ? 6.0 : 4.0, above = boundaryRow ? 0.0 : 1.0;
    const double pivot = diagonal - below * upper[i - 1];
    upper[i] = above / pivot;
    s[i] = (y[i - 1] - 2 * y[i] + y[i + 1] - below * s[i - 1]) / pivot;
  }
  for (size_t i = last; i-- > 1;) s[i] -= upper[i] * s[i + 1];
  s[0] = 2 * s[1] - s[2];
  s[n - 1] = 2 * s[n - 2] - s[n - 3];
  return s;
}

}  // namespace

UniformSpline::UniformSpline(double start, double period, std::span<const double> values, Interpolation kind)
    : start_(start), period_(period), kind_(kind), values_(values.begin(), values.end()) {
  if (!(period > 0.0) || !std::isfinite(period) || !std::isfinite(start))
    throw InvalidInput("a sampled signal needs a finite start and a positive, finite period");
  if (values_.size() < 4) throw InvalidInput("a sampled signal needs at least four samples to be interpolated");
  for (double v : values_)
    if (!std::isfinite(v)) throw InvalidInput("a sampled signal holds a value that is not finite");
  if (kind == Interpolation::CubicSpline) curvature_ = notAKnotCurvature(values_);
}

UniformSpline::Location UniformSpline::locate(double t) const {
  const double position = (t - start_) / period_;
  const auto intervals = static_cast<double>(values_.size() - 1);
  if (!(position >= -1e-6 && position <= intervals + 1e-6))
    throw InvalidInput("interpolation outside the sampled span");
  const double clamped = std::fmin(std::fmax(position, 0.0), intervals);
  const auto i = std::min(static_cast<size_t>(clamped), values_.size() - 2);
  return {i, clamped - static_cast<double>(i)};
}

double UniformSpline::at(const Location& where) const {
  const size_t i = where.interval;
  const double u = where.fraction, w = 1.0 - u;
  const double straight = w * values_[i] + u * values_[i + 1];
  if (kind_ == Interpolation::Linear) return straight;
  return straight + (w * w * w - w) * curvature_[i] + (u * u * u - u) * curvature_[i + 1];
}

double UniformSpline::slopeAt(const Location& where) const {
  const size_t i = where.interval;
  const double u = where.fraction, w = 1.0 - u;
  double slope = values_[i + 1] - values_[i];
  if (kind_ == Interpolation::CubicSpline) slope += (1.0 - 3 * w * w) * curvature_[i] + (3 * u * u - 1.0) * curvature_[i + 1];
  return slope / period_;
}

}  // namespace mtacc
