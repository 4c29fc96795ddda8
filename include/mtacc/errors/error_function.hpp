#pragma once
// A component error motion as a function of its axis position (ISO 230-1 E<D><axis>):
// a sum of terms, each linear in its parameters, so that sensitivities are exact.
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

namespace mtacc {

// f(q) = sum_k c_k * ((q - zero) / scale)^k. Constant and linear errors are polynomials.
struct PolynomialTerm {
  double zero = 0.0;
  double scale = 1.0;
  std::vector<double> coefficients;
};

// f(q) = amplitude * cos(2 pi * order * (q - zero) / period + phase). Harmonics over the
// travel and cyclic (pitch) errors are both this.
struct HarmonicTerm {
  double period = 1.0;
  double zero = 0.0;
  int order = 1;
  double amplitude = 0.0;
  double phase = 0.0;
  bool cyclic = false;  // a pitch error (parameter named "cyc") rather than a harmonic of the travel ("h<order>")
};

enum class Interpolation { Linear, CubicSpline };

// Values at positions, interpolated linearly or with a natural cubic spline; held constant
// beyond the first and last position.
struct TableTerm {
  TableTerm(std::vector<double> positions, std::vector<double> values, Interpolation interpolation);
  std::vector<double> positions;
  std::vector<double> values;
  Interpolation interpolation;
  // Natural spline: second derivatives = splineOperator * values (precomputed, n x n).
  Eigen::MatrixXd splineOperator;
  std::vector<double> secondDerivatives;
  bool uniform = false;

  void refresh();  // recompute secondDerivatives after values changed
};

// Reversal (hysteresis): +width/2 when the axis moves in its positive direction, -width/2
// when it moves in the negative direction, 0 when the direction is not known.
struct ReversalTerm {
  double width = 0.0;
};

using ErrorTerm = std::variant<PolynomialTerm, HarmonicTerm, TableTerm, ReversalTerm>;

class ErrorFunction {
 public:
  bool empty() const { return terms_.empty(); }
  void add(ErrorTerm term);
  const std::vector<ErrorTerm>& terms() const { return terms_; }

  // direction: +1, -1, or 0 (unknown / standing still).
  double value(double q, int direction) const;

  // The linear parameters of all terms, in order. Names are suffixes such as "c1", "h2",
  // "t3", "rev" (made unique within the function).
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
