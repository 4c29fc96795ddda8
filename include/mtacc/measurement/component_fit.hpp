#pragma once
// Fitting one component error to its measured curve, as seed 003 §5.2 does (extraction §8.1):
// a piecewise polynomial of degree <= 2 with fixed breaks, continuous in value and (for degree
// 2) first derivative at every break, in truncated-power form (eq. [5.2]); stepwise removal of
// the terms that are not significant; optionally a periodic term of a given wavelength fitted
// with it (seed 003's xtx: lambda = 39.6 mm), itself C1 and periodic and zero at its start.
// Least squares on the given points (usually the mean of the forward and backward runs), with
// the parameter covariance from the residual.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/errors/error_function.hpp"

namespace mtacc {

struct ComponentFitOptions {
  std::vector<double> breaks;     // t_0 < ... < t_k: the range and the fixed interior breaks
  int degree = 2;                 // 1: continuous piecewise linear; 2: C1 piecewise quadratic
  double significance = 0.05;     // a term stays when its two-sided t-test rejects zero at this level; 0: keep all
  std::optional<double> period = std::nullopt;  // a periodic term of this wavelength, breaks at quarters of it
  double periodZero = 0.0;        // u = (x - periodZero) mod period
};

struct ComponentFit {
  PiecewiseTerm trend;
  std::optional<PiecewiseTerm> periodic;
  std::vector<std::string> removed;  // the trend terms dropped by the stepwise test ("k3c2")
  // The periodic term's coefficients = periodicMap * its free parameters (3 for the quarters:
  // six coefficients less zero at the start, zero at the end, equal slopes at both ends).
  Eigen::MatrixXd periodicMap;
  // Covariance of the fitted parameters: the trend's coefficients in order, then the periodic
  // term's free parameters.
  Eigen::MatrixXd covariance;
  double residualStd = 0;  // s, with `degreesOfFreedom`
  int degreesOfFreedom = 0;
  Eigen::VectorXd residuals;  // data minus fit, per point

  double value(double x) const;
  // The standard uncertainty of the fitted value at x (from `covariance`).
  double valueUncertainty(double x) const;
  // Basis row at x: d value / d parameter, in the order of `covariance`.
  Eigen::RowVectorXd basis(double x) const;
};

// Throws InvalidInput for fewer points than parameters, breaks that do not increase,
// points outside [t_0, t_k] or a degree other than 1 or 2 (the readers check first and say where).
ComponentFit fitComponent(const std::vector<double>& x, const std::vector<double>& y, const ComponentFitOptions& options);

// Breaks at equal intervals over [from, to]: `pieces` of them, or when 0 about one per 100 mm
// (30 deg for a rotary axis, `rotary`) and fewer than `positions` measured positions can carry
// with polynomials of `degree`.
std::vector<double> evenBreaks(double from, double to, bool rotary, size_t positions, int degree, int pieces = 0);

}  // namespace mtacc
