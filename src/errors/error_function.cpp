#include "mtacc/errors/error_function.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include <map>
#include <stdexcept>

#include <Eigen/LU>

#include "mtacc/core/overloaded.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

int termParameterCount(const ErrorTerm& term) {
  return std::visit(Overloaded{[](const PolynomialTerm& p) { return static_cast<int>(p.coefficients.size()); },
                               [](const HarmonicTerm&) { return 1; },
                               [](const TableTerm& t) { return static_cast<int>(t.values.size()); },
                               [](const ReversalTerm&) { return 1; },
                               [](const PiecewiseTerm& p) { return static_cast<int>(p.coefficients.size()); }},
                    term);
}

struct SplineWeights {
  size_t i;
  double a, b, c, d;  // f = a*y_i + b*y_{i+1} + c*M_i + d*M_{i+1}
};

SplineWeights weightsAt(const TableTerm& t, double q) {
  const auto [i, offset] = t.locate(q);
  const double h = t.positions[i + 1] - t.positions[i];
  const double b = offset / h;
  const double a = 1.0 - b;
  if (t.interpolation == Interpolation::Linear) return {i, a, b, 0.0, 0.0};
  return {i, a, b, (a * a * a - a) * h * h / 6.0, (b * b * b - b) * h * h / 6.0};
}

double polynomialBasis(const PolynomialTerm& p, int k, double q) { return std::pow((q - p.zero) / p.scale, k); }

double harmonicBasis(const HarmonicTerm& h, double q) {
  return std::cos(2.0 * kPi * h.order * (q - h.zero) / h.period + h.phase);
}

double reversalBasis(int direction) { return 0.5 * static_cast<double>((direction > 0) - (direction < 0)); }

}  // namespace

double PiecewiseTerm::position(double q) const {
  if (period > 0.0) {
    const double u = std::fmod(q - zero, period);
    return u < 0.0 ? u + period : u;
  }
  return std::clamp(q, breaks.front(), breaks.back());
}

double PiecewiseTerm::basis(const Coefficient& c, double u) const {
  const double v = c.knot == 0 ? u : u - breaks[static_cast<size_t>(c.knot)];
  if (c.knot > 0 && v <= 0.0) return 0.0;
  return c.power == 0 ? 1.0 : (c.power == 1 ? v : v * v);
}

double PiecewiseTerm::value(double q) const {
  const double u = position(q);
  double sum = 0.0;
  for (const auto& c : coefficients) sum += c.value * basis(c, u);
  return sum;
}

CompiledPiecewise::CompiledPiecewise(PiecewiseTerm piecewise) : term(std::move(piecewise)) {
  local.assign(term.breaks.size() - 1, {0.0, 0.0, 0.0});
  for (const auto& c : term.coefficients) {
    // (u - t)^p about each interval's start s >= t: with d = s - t, 1; v + d; v^2 + 2 d v + d^2.
    const double t = c.knot == 0 ? 0.0 : term.breaks[static_cast<size_t>(c.knot)];
    for (size_t k = static_cast<size_t>(c.knot); k < local.size(); ++k) {
      const double d = term.breaks[k] - t;
      auto& a = local[k];
      if (c.power == 0) {
        a[0] += c.value;
      } else if (c.power == 1) {
        a[0] += c.value * d;
        a[1] += c.value;
      } else {
        a[0] += c.value * d * d;
        a[1] += c.value * 2.0 * d;
        a[2] += c.value;
      }
    }
  }
}

double CompiledPiecewise::value(double q) const {
  const double u = term.position(q);
  // The intervals' interior breaks below u; on a break, the interval before it.
  const auto first = term.breaks.begin() + 1, last = term.breaks.end() - 1;
  const auto k = static_cast<size_t>(std::lower_bound(first, std::max(first, last), u) - first);
  const auto& a = local[k];
  const double v = u - term.breaks[k];
  return a[0] + v * (a[1] + v * a[2]);
}

std::vector<std::array<double, 3>> PiecewiseTerm::intervals() const {
  std::vector<std::array<double, 3>> out(breaks.size() - 1, {0.0, 0.0, 0.0});
  for (const auto& c : coefficients) {
    // (u - t)^j in powers of u, added to every interval from the one starting at t.
    const double t = c.knot == 0 ? 0.0 : breaks[static_cast<size_t>(c.knot)];
    const std::array<double, 3> powers = c.power == 0   ? std::array<double, 3>{1.0, 0.0, 0.0}
                                         : c.power == 1 ? std::array<double, 3>{-t, 1.0, 0.0}
                                                        : std::array<double, 3>{t * t, -2.0 * t, 1.0};
    for (size_t i = static_cast<size_t>(c.knot); i < out.size(); ++i)
      for (size_t j = 0; j < 3; ++j) out[i][j] += c.value * powers[j];
  }
  return out;
}

PiecewiseTerm piecewiseFromIntervals(std::vector<double> breaks, const std::vector<std::array<double, 3>>& intervals,
                                     double period, double zero) {
  PiecewiseTerm p;
  p.period = period;
  p.zero = zero;
  for (int j = 0; j < 3; ++j) p.coefficients.push_back({0, j, intervals[0][static_cast<size_t>(j)]});
  for (size_t i = 1; i < intervals.size(); ++i) {
    const double t = breaks[i];
    const double d0 = intervals[i][0] - intervals[i - 1][0];
    const double d1 = intervals[i][1] - intervals[i - 1][1];
    const double d2 = intervals[i][2] - intervals[i - 1][2];
    // d0 + d1 u + d2 u^2 = (d0 + d1 t + d2 t^2) + (d1 + 2 d2 t)(u - t) + d2 (u - t)^2
    const int knot = static_cast<int>(i);
    p.coefficients.push_back({knot, 0, d0 + d1 * t + d2 * t * t});
    p.coefficients.push_back({knot, 1, d1 + 2.0 * d2 * t});
    p.coefficients.push_back({knot, 2, d2});
  }
  p.breaks = std::move(breaks);
  return p;
}

PiecewiseTerm continuousPiecewise(std::vector<double> breaks, int degree) {
  PiecewiseTerm p;
  for (int j = 0; j <= degree; ++j) p.coefficients.push_back({0, j, 0.0});
  for (size_t i = 1; i + 1 < breaks.size(); ++i) p.coefficients.push_back({static_cast<int>(i), degree, 0.0});
  p.breaks = std::move(breaks);
  return p;
}

TableTerm::TableTerm(std::vector<double> p, std::vector<double> v, Interpolation interp)
    : positions(std::move(p)), values(std::move(v)), interpolation(interp) {
  const size_t n = positions.size();
  const double h0 = positions[1] - positions[0];
  uniform = true;
  for (size_t i = 1; i + 1 < n; ++i)
    uniform = uniform && std::abs((positions[i + 1] - positions[i]) - h0) <= 1e-12 * std::abs(h0);
  inverseStep = 1.0 / h0;
  splineOperator = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  if (interpolation == Interpolation::CubicSpline && n > 2) {
    // Natural spline: interior rows h_{i-1} M_{i-1} + 2(h_{i-1}+h_i) M_i + h_i M_{i+1}
    //   = 6[(y_{i+1}-y_i)/h_i - (y_i-y_{i-1})/h_{i-1}], M_0 = M_{n-1} = 0.
    const Eigen::Index m = static_cast<Eigen::Index>(n) - 2;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m, static_cast<Eigen::Index>(n));
    for (Eigen::Index r = 0; r < m; ++r) {
      const size_t i = static_cast<size_t>(r) + 1;
      const double hl = positions[i] - positions[i - 1];
      const double hr = positions[i + 1] - positions[i];
      if (r > 0) a(r, r - 1) = hl;
      a(r, r) = 2.0 * (hl + hr);
      if (r + 1 < m) a(r, r + 1) = hr;
      b(r, r) = 6.0 / hl;
      b(r, r + 1) = -6.0 / hl - 6.0 / hr;
      b(r, r + 2) = 6.0 / hr;
    }
    splineOperator.middleRows(1, m) = a.partialPivLu().solve(b);
  }
  refresh();
}

void TableTerm::refresh() {
  const Eigen::Map<const Eigen::VectorXd> y(values.data(), static_cast<Eigen::Index>(values.size()));
  const Eigen::VectorXd m = splineOperator * y;
  cubic.resize(positions.size() - 1);
  for (size_t i = 0; i + 1 < positions.size(); ++i) {
    const double h = positions[i + 1] - positions[i];
    const double slope = (values[i + 1] - values[i]) / h;
    const auto mi = static_cast<Eigen::Index>(i);
    cubic[i] = {values[i], slope - h * (2.0 * m[mi] + m[mi + 1]) / 6.0, m[mi] / 2.0, (m[mi + 1] - m[mi]) / (6.0 * h)};
  }
}

GridLocation locateInGridSearch(const std::vector<double>& positions, double x) {
  const size_t last = positions.size() - 2;
  const auto it = std::upper_bound(positions.begin(), positions.end(), x);
  const size_t i = std::min(last, static_cast<size_t>(std::max<std::ptrdiff_t>(it - positions.begin() - 1, 0)));
  return {i, x - positions[i]};
}

void ErrorFunction::add(ErrorTerm term) { terms_.push_back(std::move(term)); }

double ErrorFunction::value(double q, int direction) const {
  double sum = 0.0;
  for (const auto& term : terms_) {
    sum += std::visit(
        Overloaded{[&](const PolynomialTerm& p) { return p.value(q); },
                   [&](const HarmonicTerm& h) { return h.amplitude * harmonicBasis(h, q); },
                   [&](const TableTerm& t) { return t.valueAt(t.locate(q)); },
                   [&](const ReversalTerm& r) { return r.width * reversalBasis(direction); },
                   [&](const PiecewiseTerm& p) { return p.value(q); }},
        term);
  }
  return sum;
}

int ErrorFunction::parameterCount() const {
  int n = 0;
  for (const auto& t : terms_) n += termParameterCount(t);
  return n;
}

std::vector<std::string> ErrorFunction::parameterSuffixes() const {
  std::vector<std::string> names;
  std::map<std::string, int> used;
  auto push = [&](std::string s) {
    const int k = used[s]++;
    names.push_back(k == 0 ? s : fmt::format("{}#{}", s, k + 1));
  };
  for (const auto& term : terms_) {
    std::visit(Overloaded{[&](const PolynomialTerm& p) {
                            for (size_t k = 0; k < p.coefficients.size(); ++k) push(fmt::format("c{}", k));
                          },
                          [&](const HarmonicTerm& h) {
                            const char* part = h.part == HarmonicPart::Cosine ? "c" : h.part == HarmonicPart::Sine ? "s" : "";
                            push(h.cyclic ? std::string("cyc") : fmt::format("h{}{}", h.order, part));
                          },
                          [&](const TableTerm& t) {
                            for (size_t k = 0; k < t.values.size(); ++k) push(fmt::format("t{}", k));
                          },
                          [&](const ReversalTerm&) { push("rev"); },
                          [&](const PiecewiseTerm& p) {
                            for (const auto& c : p.coefficients) push(fmt::format("k{}c{}", c.knot, c.power));
                          }},
               term);
  }
  return names;
}

namespace {
// Calls f(term, localIndex) for the term that holds global parameter index.
template <class Terms, class F>
auto withParameter(Terms& terms, int index, F&& f) {
  for (auto& term : terms) {
    const int n = termParameterCount(term);
    if (index < n) return f(term, index);
    index -= n;
  }
  throw std::out_of_range("error-function parameter index out of range");
}
}  // namespace

double ErrorFunction::parameter(int index) const {
  return withParameter(terms_, index, [](const ErrorTerm& term, int k) -> double {
    return std::visit(Overloaded{[&](const PolynomialTerm& p) { return p.coefficients[static_cast<size_t>(k)]; },
                                 [&](const HarmonicTerm& h) { return h.amplitude; },
                                 [&](const TableTerm& t) { return t.values[static_cast<size_t>(k)]; },
                                 [&](const ReversalTerm& r) { return r.width; },
                                 [&](const PiecewiseTerm& p) { return p.coefficients[static_cast<size_t>(k)].value; }},
                      term);
  });
}

void ErrorFunction::setParameter(int index, double v) {
  withParameter(terms_, index, [v](ErrorTerm& term, int k) {
    std::visit(Overloaded{[&](PolynomialTerm& p) { p.coefficients[static_cast<size_t>(k)] = v; },
                          [&](HarmonicTerm& h) { h.amplitude = v; },
                          [&](TableTerm& t) {
                            t.values[static_cast<size_t>(k)] = v;
                            t.refresh();
                          },
                          [&](ReversalTerm& r) { r.width = v; },
                          [&](PiecewiseTerm& p) { p.coefficients[static_cast<size_t>(k)].value = v; }},
               term);
  });
}

double ErrorFunction::basis(int index, double q, int direction) const {
  return withParameter(terms_, index, [&](const ErrorTerm& term, int k) -> double {
    return std::visit(Overloaded{[&](const PolynomialTerm& p) { return polynomialBasis(p, k, q); },
                                 [&](const HarmonicTerm& h) { return harmonicBasis(h, q); },
                                 [&](const TableTerm& t) {
                                   const auto w = weightsAt(t, q);
                                   const auto ku = static_cast<size_t>(k);
                                   double v = (ku == w.i ? w.a : 0.0) + (ku == w.i + 1 ? w.b : 0.0);
                                   if (t.interpolation == Interpolation::CubicSpline)
                                     v += w.c * t.splineOperator(static_cast<Eigen::Index>(w.i), k) +
                                          w.d * t.splineOperator(static_cast<Eigen::Index>(w.i + 1), k);
                                   return v;
                                 },
                                 [&](const ReversalTerm&) { return reversalBasis(direction); },
                                 [&](const PiecewiseTerm& p) {
                                   return p.basis(p.coefficients[static_cast<size_t>(k)], p.position(q));
                                 }},
                      term);
  });
}

}  // namespace mtacc
