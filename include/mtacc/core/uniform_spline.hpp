#pragma once
// Interpolation of a signal sampled at a constant rate: piecewise linear, or the not-a-knot
// cubic spline (SciPy's CubicSpline default, so that a NumPy/SciPy pipeline gives the same
// numbers). The spline is exact for cubic polynomials; linear interpolation of a trace sampled
// every T errs by up to a*T^2/8 where the signal accelerates by a (seed 004 L290, O7).
#include <span>
#include <vector>

#include "mtacc/core/interpolation.hpp"

namespace mtacc {

class UniformSpline {
 public:
  // Samples at start + k * period, k = 0 .. n - 1. Throws InvalidInput for fewer than
  // four samples, a period that is not positive and finite, or a value that is not finite.
  UniformSpline(double start, double period, std::span<const double> values, Interpolation kind = Interpolation::CubicSpline);

  // Where t falls: the interval and the fraction of it. Throws InvalidInput for t
  // outside [first(), last()] beyond a millionth of a period.
  struct Location {
    size_t interval;
    double fraction;
  };
  Location locate(double t) const;
  // The value and the slope (per s) at a location; splines of one start, period and length
  // share their locations.
  double at(const Location& where) const;
  double slopeAt(const Location& where) const;
  double operator()(double t) const { return at(locate(t)); }
  // The values, or the slopes (per s), at first + k * step for k = 0 .. out.size() - 1: at and
  // slopeAt at each time, in one pass the compiler vectorises. Throws InvalidInput like locate
  // when the first or the last time falls outside the span.
  void atEvenly(double first, double step, std::span<double> out) const;
  void slopeAtEvenly(double first, double step, std::span<double> out) const;

  double first() const { return start_; }
  double last() const { return start_ + period_ * static_cast<double>(values_.size() - 1); }

 private:
  double start_, period_;
  Interpolation kind_;
  std::vector<double> values_;
  std::vector<double> curvature_;  // second derivative at each sample, times period^2 / 6
};

}  // namespace mtacc
