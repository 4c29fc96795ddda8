#pragma once
// A component error motion as a function of its axis position (ISO 230-1 E<D><axis>):
// a sum of terms, each linear in its parameters, so that sensitivities are exact.
#include <array>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/interpolation.hpp"

namespace mtacc {

// f(q) = sum_k c_k * ((q - zero) / scale)^k. Constant and linear errors are polynomials.
struct PolynomialTerm {
  double zero = 0.0;
  double scale = 1.0;
  std::vector<double> coefficients;

  double value(double q) const {
    const double u = (q - zero) / scale;
    double v = 0.0;
    for (auto it = coefficients.rbegin(); it != coefficients.rend(); ++it) v = v * u + *it;
    return v;
  }
};

// What a harmonic's one parameter is: its amplitude at a stated phase ("h<order>"), or the
// cosine or sine part of a pair whose two parameters give amplitude and phase ("h<order>c",
// "h<order>s": the sine part is the term at phase -90 deg).
enum class HarmonicPart { Amplitude, Cosine, Sine };

// f(q) = amplitude * cos(2 pi * order * (q - zero) / period + phase). Harmonics over the
// travel and cyclic (pitch) errors are both this.
struct HarmonicTerm {
  double period = 1.0;
  double zero = 0.0;
  int order = 1;
  double amplitude = 0.0;
  double phase = 0.0;
  bool cyclic = false;  // a pitch error (parameter named "cyc") rather than a harmonic of the travel ("h<order>")
  HarmonicPart part = HarmonicPart::Amplitude;
};

// Where q falls in a grid of increasing positions: the interval and the offset from its start,
// clamped to the grid.
struct GridLocation {
  size_t interval;
  double s;
};
GridLocation locateInGridSearch(const std::vector<double>& positions, double x);
inline GridLocation locateInGrid(const std::vector<double>& positions, bool uniform, double inverseStep, double q) {
  const double x0 = positions.front(), xn = positions.back();
  const double x = q < x0 ? x0 : (q > xn ? xn : q);
  if (!uniform) return locateInGridSearch(positions, x);
  const size_t last = positions.size() - 2;
  size_t i = static_cast<size_t>((x - x0) * inverseStep);
  if (i > last) i = last;
  return {i, x - positions[i]};
}

// Values at positions, interpolated linearly or with a natural cubic spline; held constant
// beyond the first and last position.
struct TableTerm {
  TableTerm(std::vector<double> positions, std::vector<double> values, Interpolation interpolation);
  std::vector<double> positions;
  std::vector<double> values;
  Interpolation interpolation;
  // Natural spline: second derivatives = splineOperator * values (precomputed, n x n).
  Eigen::MatrixXd splineOperator;
  // Per interval i, the exact cubic c0 + c1 s + c2 s^2 + c3 s^3 in s = x - positions[i].
  std::vector<std::array<double, 4>> cubic;
  bool uniform = false;
  double inverseStep = 0.0;  // 1 / spacing when uniform

  void refresh();  // recompute the cubic coefficients after values changed

  GridLocation locate(double q) const { return locateInGrid(positions, uniform, inverseStep, q); }
  double valueAt(const GridLocation& at) const {
    const auto& c = cubic[at.interval];
    return c[0] + at.s * (c[1] + at.s * (c[2] + at.s * c[3]));
  }
};

// Reversal (hysteresis): +width/2 when the axis moves in its positive direction, -width/2
// when it moves in the negative direction, 0 when the direction is not known.
struct ReversalTerm {
  double width = 0.0;
};

// A piecewise polynomial of degree <= 2 over breaks t_0 < t_1 < ... < t_n, in the truncated-power
// form of seed 003 eq. [5.2]:
//   f(u) = sum_j a_0j u^j + sum_{i=1..n-1} sum_j a_ij (u - t_i)_+^j,   v_+ = v if v > 0, else 0,
// in the absolute position u (as seed 003 App. D publishes its tables), clamped to [t_0, t_n].
// A C1 function has only the j = 2 terms at its interior breaks (a quadratic spline); a term
// that a stepwise fit removed is absent. With a period, u = (q - zero) mod period: a pitch
// error fitted over one period (breaks from 0 to the period).
struct PiecewiseTerm {
  struct Coefficient {
    int knot;   // 0: the plain powers of u; i >= 1: the powers of (u - t_i)_+
    int power;  // 0, 1, 2
    double value;
  };
  std::vector<double> breaks;
  std::vector<Coefficient> coefficients;
  double period = 0.0;  // 0: not periodic
  double zero = 0.0;

  double position(double q) const;  // u
  double basis(const Coefficient& c, double u) const;
  double value(double q) const;
  // The polynomial of each interval in the absolute position, (c0, c1, c2): c0 + c1 u + c2 u^2.
  std::vector<std::array<double, 3>> intervals() const;
};
// A piecewise term made fast to evaluate (for a compiled model, whose terms do not change): each
// interval's polynomial in (u - the interval's start), found by a search on the breaks, instead of
// one truncated power per coefficient. Equal to term.value to rounding; a u on a break belongs to
// the interval before it, as in the truncated-power form.
struct CompiledPiecewise {
  explicit CompiledPiecewise(PiecewiseTerm piecewise);
  double value(double q) const;

  PiecewiseTerm term;
  std::vector<std::array<double, 3>> local;  // per interval: a0 + a1 v + a2 v^2, v = u - breaks[k]
};

// The truncated-power form of per-interval polynomials (all three terms at every interior
// break, so that each interval evaluates to its own polynomial even where the table is not C1).
PiecewiseTerm piecewiseFromIntervals(std::vector<double> breaks, const std::vector<std::array<double, 3>>& intervals,
                                     double period = 0.0, double zero = 0.0);

// The C^(degree-1) spline of degree 1 or 2 over the breaks in this form, every coefficient zero:
// 1, u, ..., u^degree, then (u - t_i)_+^degree at each interior break (the terms a fit solves for).
PiecewiseTerm continuousPiecewise(std::vector<double> breaks, int degree = 2);

using ErrorTerm = std::variant<PolynomialTerm, HarmonicTerm, TableTerm, ReversalTerm, PiecewiseTerm>;

class ErrorFunction {
 public:
  bool empty() const { return terms_.empty(); }
  void add(ErrorTerm term);
  const std::vector<ErrorTerm>& terms() const { return terms_; }

  // direction: +1, -1, or 0 (unknown / standing still).
  double value(double q, int direction) const;

  // The linear parameters of all terms, in order. Names are suffixes such as "c1", "h2",
  // "t3", "rev", "k4c2" (piecewise: break 4, power 2), made unique within the function.
  int parameterCount() const;
  std::vector<std::string> parameterSuffixes() const;
  double parameter(int index) const;
  void setParameter(int index, double value);
  // d value / d parameter[index] at q (the basis function of that parameter).
  double basis(int index, double q, int direction) const;

 private:
  std::vector<ErrorTerm> terms_;
};

}  // namespace mtacc
