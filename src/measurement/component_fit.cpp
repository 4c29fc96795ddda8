#include "mtacc/measurement/component_fit.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

// A C1 quadratic over quarters of the period, zero at 0 and at the period, with equal slopes
// at both ends; `map` (6 x 3) takes its free parameters to its coefficients.
PiecewiseTerm periodicShape(double period, double zero, Eigen::MatrixXd& map) {
  PiecewiseTerm p;
  p.period = period;
  p.zero = zero;
  p.breaks = {0.0, 0.25 * period, 0.5 * period, 0.75 * period, period};
  for (int j = 0; j <= 2; ++j) p.coefficients.push_back({0, j, 0.0});
  for (int i = 1; i <= 3; ++i) p.coefficients.push_back({i, 2, 0.0});
  Eigen::MatrixXd constraints = Eigen::MatrixXd::Zero(3, 6);
  constraints(0, 0) = 1.0;  // f(0) = 0
  for (int k = 0; k < 6; ++k) {
    const auto& c = p.coefficients[static_cast<size_t>(k)];
    const double v = period - (c.knot == 0 ? 0.0 : p.breaks[static_cast<size_t>(c.knot)]);
    constraints(1, k) = std::pow(v, c.power);                                   // f(period) = 0
    constraints(2, k) = c.power == 0 ? 0.0 : c.power * std::pow(v, c.power - 1);  // f'(period) - f'(0) = 0
  }
  constraints(2, 1) -= 1.0;
  map = Eigen::HouseholderQR<Eigen::MatrixXd>(constraints.fullPivLu().kernel()).householderQ() * Eigen::MatrixXd::Identity(6, 3);
  map.row(0).setZero();
  return p;
}

struct Solution {
  Eigen::VectorXd parameters;
  Eigen::MatrixXd inverseNormal;  // (A^T A)^-1
  Eigen::VectorXd residuals;
};

Solution solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  // Columns scaled to unit norm so that 1, x and x^2 over hundreds of mm mix safely.
  const Eigen::VectorXd norms = a.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::MatrixXd scaled = a * norms.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  if (qr.rank() < a.cols()) throw InvalidInput("component fit: the points do not determine every term (too few in some interval)");
  Solution s;
  s.parameters = qr.solve(y).cwiseQuotient(norms);
  s.residuals = y - a * s.parameters;
  const Eigen::MatrixXd gram = scaled.transpose() * scaled;
  s.inverseNormal = norms.cwiseInverse().asDiagonal() * gram.ldlt().solve(Eigen::MatrixXd::Identity(a.cols(), a.cols())) *
                    norms.cwiseInverse().asDiagonal();
  return s;
}

}  // namespace

Eigen::RowVectorXd ComponentFit::basis(double x) const {
  const auto nt = static_cast<Eigen::Index>(trend.coefficients.size());
  Eigen::RowVectorXd row(nt + (periodic ? periodicMap.cols() : 0));
  const double u = trend.position(x);
  for (Eigen::Index k = 0; k < nt; ++k) row[k] = trend.basis(trend.coefficients[static_cast<size_t>(k)], u);
  if (periodic) {
    const double v = periodic->position(x);
    Eigen::RowVectorXd b(6);
    for (Eigen::Index k = 0; k < 6; ++k) b[k] = periodic->basis(periodic->coefficients[static_cast<size_t>(k)], v);
    row.tail(periodicMap.cols()) = b * periodicMap;
  }
  return row;
}

double ComponentFit::value(double x) const { return trend.value(x) + (periodic ? periodic->value(x) : 0.0); }

double ComponentFit::valueUncertainty(double x) const {
  const Eigen::RowVectorXd b = basis(x);
  return std::sqrt(std::max(0.0, (b * covariance * b.transpose())(0, 0)));
}

ComponentFit fitComponent(const std::vector<double>& x, const std::vector<double>& y, const ComponentFitOptions& o) {
  if (o.degree != 1 && o.degree != 2) throw InvalidInput("component fit: the degree must be 1 or 2");
  if (o.breaks.size() < 2) throw InvalidInput("component fit: needs at least two breaks");
  for (size_t i = 1; i < o.breaks.size(); ++i)
    if (!(o.breaks[i] > o.breaks[i - 1])) throw InvalidInput("component fit: the breaks must increase");
  if (x.size() != y.size()) throw InvalidInput("component fit: as many values as positions");
  for (const double v : x)
    if (!(v >= o.breaks.front() && v <= o.breaks.back())) throw InvalidInput("component fit: a position outside the breaks");
  ComponentFit fit;
  fit.trend = continuousPiecewise(o.breaks, o.degree);
  if (o.period) fit.periodic = periodicShape(*o.period, o.periodZero, fit.periodicMap);
  const auto n = static_cast<Eigen::Index>(x.size());
  const Eigen::Map<const Eigen::VectorXd> values(y.data(), n);
  for (;;) {
    const auto nt = static_cast<Eigen::Index>(fit.trend.coefficients.size());
    const Eigen::Index np = nt + (fit.periodic ? fit.periodicMap.cols() : 0);
    if (n <= np) throw InvalidInput("component fit: fewer points than terms");
    Eigen::MatrixXd a(n, np);
    for (Eigen::Index i = 0; i < n; ++i) a.row(i) = fit.basis(x[static_cast<size_t>(i)]);
    const Solution s = solve(a, values);
    fit.degreesOfFreedom = static_cast<int>(n - np);
    fit.residuals = s.residuals;
    fit.residualStd = std::sqrt(s.residuals.squaredNorm() / fit.degreesOfFreedom);
    fit.covariance = fit.residualStd * fit.residualStd * s.inverseNormal;
    for (Eigen::Index k = 0; k < nt; ++k) fit.trend.coefficients[static_cast<size_t>(k)].value = s.parameters[k];
    if (fit.periodic) {
      const Eigen::VectorXd coefficients = fit.periodicMap * s.parameters.tail(fit.periodicMap.cols());
      for (Eigen::Index k = 0; k < 6; ++k) fit.periodic->coefficients[static_cast<size_t>(k)].value = coefficients[k];
    }
    // Stepwise: the least significant trend term other than the constant goes while its
    // two-sided t-test cannot reject zero.
    if (o.significance <= 0.0 || fit.residualStd == 0.0) break;
    Eigen::Index weakest = -1;
    double smallest = INFINITY;
    for (Eigen::Index k = 1; k < nt; ++k) {
      const double t = std::abs(s.parameters[k]) / std::sqrt(fit.covariance(k, k));
      if (t < smallest) {
        smallest = t;
        weakest = k;
      }
    }
    if (weakest < 0) break;
    const boost::math::students_t student(fit.degreesOfFreedom);
    if (2.0 * boost::math::cdf(boost::math::complement(student, smallest)) <= o.significance) break;
    const auto& gone = fit.trend.coefficients[static_cast<size_t>(weakest)];
    fit.removed.push_back("k" + std::to_string(gone.knot) + "c" + std::to_string(gone.power));
    fit.trend.coefficients.erase(fit.trend.coefficients.begin() + weakest);
  }
  return fit;
}

std::vector<double> evenBreaks(double from, double to, bool rotary, size_t positions, int degree, int pieces) {
  if (pieces <= 0) {
    const double step = rotary ? 30.0 * kDeg : 100.0;
    const int most = std::max(1, static_cast<int>(positions) - degree - 1);
    pieces = std::min(most, std::max(1, static_cast<int>(std::round((to - from) / step))));
  }
  std::vector<double> b;
  for (int i = 0; i <= pieces; ++i) b.push_back(from + (to - from) * i / pieces);
  return b;
}

}  // namespace mtacc
