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

namespace {

void checkInside(double position, double intervals) {
  if (!(position >= -1e-6 && position <= intervals + 1e-6)) throw InvalidInput("interpolation outside the sampled span");
}

// The value and the slope (per sample) in interval i at fraction u, from the samples y and the
// scaled curvatures s: without the curvatures for linear interpolation.
template <bool Cubic>
double valueIn(const double* __restrict y, const double* __restrict s, long i, double u) {
  const double w = 1.0 - u;
  const double straight = w * y[i] + u * y[i + 1];
  if constexpr (!Cubic) return straight;
  return straight + (w * w * w - w) * s[i] + (u * u * u - u) * s[i + 1];
}
template <bool Cubic>
double riseIn(const double* __restrict y, const double* __restrict s, long i, double u) {
  const double w = 1.0 - u;
  const double rise = y[i + 1] - y[i];
  if constexpr (!Cubic) return rise;
  return rise + (1.0 - 3 * w * w) * s[i] + (3 * u * u - 1.0) * s[i + 1];
}

// out[k] = f(interval, fraction) at the positions (in samples) position + k * advance, the
// first and the last checked inside [0, intervals]. Forwards by less than a sample a step (an
// instrument's clock on a trace's), one interval at a time: its coefficients loaded once and the
// loop over its times vectorised.
template <class F>
void evenly(double position, double advance, double intervals, std::span<double> out, F&& f) {
  const size_t n = out.size();
  if (n == 0) return;
  checkInside(position, intervals);
  checkInside(position + advance * static_cast<double>(n - 1), intervals);
  const auto lastInterval = static_cast<long>(intervals) - 1;
  double* __restrict to = out.data();  // aliases none of the samples f reads: their loads may leave the loop
  const auto from = [&](size_t k) { return std::clamp(position + advance * static_cast<double>(k), 0.0, intervals); };
  const auto intervalOf = [&](double x) { return std::min(static_cast<long>(x), lastInterval); };
  if (!(advance > 0.0 && advance < 0.5)) {
    for (size_t k = 0; k < n; ++k) {
      const double x = from(k);
      const long i = intervalOf(x);
      to[k] = f(i, x - static_cast<double>(i));
    }
    return;
  }
  for (size_t k = 0; k < n;) {
    const long i = intervalOf(from(k));
    // The times before the interval's end (all the rest in the last interval); at least k itself
    // where rounding puts the end before it.
    size_t end = n;
    if (i < lastInterval) end = std::min(n, static_cast<size_t>(std::ceil((static_cast<double>(i + 1) - position) / advance)));
    end = std::max(end, k + 1);
    for (size_t j = k; j < end; ++j) {
      double x = position + advance * static_cast<double>(j);
      x = x < 0.0 ? 0.0 : x;  // as from(j), in a form the vectoriser takes
      x = x > intervals ? intervals : x;
      to[j] = f(i, x - static_cast<double>(i));
    }
    k = end;
  }
}

}  // namespace

UniformSpline::Location UniformSpline::locate(double t) const {
  const double position = (t - start_) / period_;
  const auto intervals = static_cast<double>(values_.size() - 1);
  checkInside(position, intervals);
  const double clamped = std::clamp(position, 0.0, intervals);
  const auto i = std::min(static_cast<size_t>(clamped), values_.size() - 2);
  return {i, clamped - static_cast<double>(i)};
}

double UniformSpline::at(const Location& where) const {
  const auto i = static_cast<long>(where.interval);
  const double u = where.fraction;
  return kind_ == Interpolation::CubicSpline ? valueIn<true>(values_.data(), curvature_.data(), i, u)
                                             : valueIn<false>(values_.data(), curvature_.data(), i, u);
}

double UniformSpline::slopeAt(const Location& where) const {
  const auto i = static_cast<long>(where.interval);
  const double u = where.fraction;
  return (kind_ == Interpolation::CubicSpline ? riseIn<true>(values_.data(), curvature_.data(), i, u)
                                              : riseIn<false>(values_.data(), curvature_.data(), i, u)) / period_;
}

void UniformSpline::atEvenly(double first, double step, std::span<double> out) const {
  const double* y = values_.data();
  const double* s = curvature_.data();
  const double position = (first - start_) / period_, advance = step / period_, intervals = static_cast<double>(values_.size() - 1);
  if (kind_ == Interpolation::CubicSpline)
    evenly(position, advance, intervals, out, [=](long i, double u) { return valueIn<true>(y, s, i, u); });
  else
    evenly(position, advance, intervals, out, [=](long i, double u) { return valueIn<false>(y, s, i, u); });
}

void UniformSpline::slopeAtEvenly(double first, double step, std::span<double> out) const {
  const double* y = values_.data();
  const double* s = curvature_.data();
  const double position = (first - start_) / period_, advance = step / period_, intervals = static_cast<double>(values_.size() - 1);
  const double perSecond = 1.0 / period_;
  if (kind_ == Interpolation::CubicSpline)
    evenly(position, advance, intervals, out, [=](long i, double u) { return riseIn<true>(y, s, i, u) * perSecond; });
  else
    evenly(position, advance, intervals, out, [=](long i, double u) { return riseIn<false>(y, s, i, u) * perSecond; });
}

}  // namespace mtacc
