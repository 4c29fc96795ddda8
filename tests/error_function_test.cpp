// Component error functions: values of each term type, natural-spline conditions, and the
// basis functions as exact derivatives with respect to the parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_function.hpp"

namespace mtacc {
namespace {

TEST(ErrorFunction, PolynomialHarmonicReversal) {
  ErrorFunction f;
  f.add(PolynomialTerm{100.0, 50.0, {1.0, 2.0, 3.0}});  // u = (q - 100) / 50
  f.add(HarmonicTerm{400.0, -200.0, 2, 0.5, 0.3});
  f.add(ReversalTerm{0.004});
  const double q = 180.0, u = 1.6;
  const double harmonic = 0.5 * std::cos(2 * kPi * 2 * (q + 200.0) / 400.0 + 0.3);
  EXPECT_NEAR(f.value(q, 1), 1 + 2 * u + 3 * u * u + harmonic + 0.002, 1e-14);
  EXPECT_NEAR(f.value(q, -1), 1 + 2 * u + 3 * u * u + harmonic - 0.002, 1e-14);
  EXPECT_NEAR(f.value(q, 0), 1 + 2 * u + 3 * u * u + harmonic, 1e-14);
  EXPECT_EQ(f.parameterSuffixes(), (std::vector<std::string>{"c0", "c1", "c2", "h2", "rev"}));
}

TEST(ErrorFunction, LinearTableInterpolatesAndHoldsEnds) {
  ErrorFunction f;
  f.add(TableTerm({0.0, 10.0, 30.0}, {1.0, 3.0, -1.0}, Interpolation::Linear));
  EXPECT_DOUBLE_EQ(f.value(5.0, 0), 2.0);
  EXPECT_DOUBLE_EQ(f.value(20.0, 0), 1.0);
  EXPECT_DOUBLE_EQ(f.value(-5.0, 0), 1.0);
  EXPECT_DOUBLE_EQ(f.value(40.0, 0), -1.0);
}

TEST(ErrorFunction, NaturalSplineConditions) {
  const std::vector<double> x{0.0, 1.0, 2.5, 3.0, 5.0}, y{0.0, 2.0, -1.0, 0.5, 1.0};
  const TableTerm t(x, y, Interpolation::CubicSpline);
  ErrorFunction f;
  f.add(t);
  for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(f.value(x[i], 0), y[i], 1e-13);  // interpolates
  for (size_t i = 1; i + 1 < x.size(); ++i) {  // first and second derivatives continuous at the knots
    const auto& cl = t.cubic[i - 1];
    const auto& cr = t.cubic[i];
    const double hl = x[i] - x[i - 1];
    EXPECT_NEAR(cl[1] + 2 * cl[2] * hl + 3 * cl[3] * hl * hl, cr[1], 1e-12);
    EXPECT_NEAR(2 * cl[2] + 6 * cl[3] * hl, 2 * cr[2], 1e-12);
  }
  EXPECT_NEAR(t.cubic.front()[2], 0.0, 1e-15);  // natural ends
  const auto& last = t.cubic.back();
  EXPECT_NEAR(2 * last[2] + 6 * last[3] * (x[4] - x[3]), 0.0, 1e-12);
}

TEST(ErrorFunction, BasisIsTheExactDerivative) {
  ErrorFunction f;
  f.add(PolynomialTerm{0.0, 100.0, {0.001, 0.002, -0.0005}});
  f.add(HarmonicTerm{30.0, 0.0, 1, 0.0005, 0.4, true});
  f.add(TableTerm({-100.0, -20.0, 40.0, 100.0}, {0.001, -0.002, 0.0015, 0.0}, Interpolation::CubicSpline));
  f.add(ReversalTerm{0.003});
  f.add(piecewiseFromIntervals({-100.0, 0.0, 100.0}, {{{1e-3, 2e-5, 1e-7}, {1e-3, 2e-5, -3e-7}}}));
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-120.0, 120.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double q = u(rng);
    for (int k = 0; k < f.parameterCount(); ++k) {
      ErrorFunction g = f;
      const double v = f.parameter(k);
      g.setParameter(k, v + 1.0);
      // Every term is linear in its parameters: a unit step changes the value by the basis.
      EXPECT_NEAR(g.value(q, 1) - f.value(q, 1), f.basis(k, q, 1), 1e-12 * std::max(1.0, std::abs(f.basis(k, q, 1)))) << k;
    }
  }
  EXPECT_EQ(f.parameterSuffixes(),
            (std::vector<std::string>{"c0", "c1", "c2", "cyc", "t0", "t1", "t2", "t3", "rev", "k0c0", "k0c1", "k0c2",
                                      "k1c0", "k1c1", "k1c2"}));
}

TEST(ErrorFunction, PiecewiseIntervalsRoundTripAndClamp) {
  // Per-interval polynomials in the absolute position (seed 003 App. D form), not continuous
  // here on purpose: each interval evaluates to its own polynomial, the value at a break
  // belongs to the interval on its left, and beyond the breaks the end values are held.
  const std::vector<std::array<double, 3>> pieces{{1.0, 0.5, -0.01}, {-3.0, 0.2, 0.002}, {4.0, -0.1, 0.0}};
  const auto p = piecewiseFromIntervals({0.0, 20.0, 50.0, 80.0}, pieces);
  auto poly = [&](size_t i, double u) { return pieces[i][0] + pieces[i][1] * u + pieces[i][2] * u * u; };
  for (const double u : {0.0, 7.5, 20.0}) EXPECT_NEAR(p.value(u), poly(0, u), 1e-12) << u;
  for (const double u : {20.0 + 1e-9, 33.0, 50.0}) EXPECT_NEAR(p.value(u), poly(1, u), 1e-9) << u;
  for (const double u : {61.0, 80.0}) EXPECT_NEAR(p.value(u), poly(2, u), 1e-9) << u;
  EXPECT_NEAR(p.value(-10.0), poly(0, 0.0), 1e-12);
  EXPECT_NEAR(p.value(95.0), poly(2, 80.0), 1e-9);
  const auto back = p.intervals();
  for (size_t i = 0; i < pieces.size(); ++i)
    for (size_t j = 0; j < 3; ++j) EXPECT_NEAR(back[i][j], pieces[i][j], 1e-12) << i << " " << j;
}

TEST(ErrorFunction, PiecewisePeriodicWrapsAroundItsZero) {
  const auto p = piecewiseFromIntervals({0.0, 5.0, 10.0}, {{{0.0, 0.4, -0.04}, {0.0, 0.4, -0.04}}}, 10.0, 3.0);
  for (const double q : {-17.0, 2.0, 3.0, 8.5, 31.0}) {
    const double u = std::fmod(std::fmod(q - 3.0, 10.0) + 10.0, 10.0);
    EXPECT_NEAR(p.value(q), 0.4 * u - 0.04 * u * u, 1e-12) << q;
  }
}

// The compiled form a kinematic model evaluates equals the truncated-power sum to rounding, on
// both sides of every break, on the breaks (the interval on the left), beyond the ends and for a
// periodic term; a C1 spline fit's form and the discontinuous per-interval form alike.
TEST(ErrorFunction, CompiledPiecewiseEqualsTheTruncatedPowerSum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coefficient(-1e-3, 1e-3);
  PiecewiseTerm spline = continuousPiecewise({0.0, 50.0, 120.0, 300.0, 450.0, 700.0});
  for (auto& c : spline.coefficients) c.value = coefficient(rng) * std::pow(1e-2, c.power);
  const auto intervals = piecewiseFromIntervals({-100.0, 20.0, 50.0, 80.0}, {{{1.0, 0.5, -0.01}, {-3.0, 0.2, 0.002}, {4.0, -0.1, 0.0}}});
  const auto periodic = piecewiseFromIntervals({0.0, 5.0, 10.0}, {{{0.0, 0.4, -0.04}, {0.0, 0.4, -0.04}}}, 10.0, 3.0);
  for (const PiecewiseTerm* term : std::initializer_list<const PiecewiseTerm*>{&spline, &intervals, &periodic}) {
    const CompiledPiecewise compiled(*term);
    std::vector<double> at = {term->breaks.front() - 50.0, term->breaks.back() + 50.0};
    for (double b : term->breaks)
      for (double d : {-1e-9, 0.0, 1e-9, 3.7}) at.push_back(b + d);
    std::uniform_real_distribution<double> u(term->breaks.front() - 20.0, term->breaks.back() + 20.0);
    for (int k = 0; k < 200; ++k) at.push_back(u(rng));
    double scale = 0.0;
    for (double q : at) scale = std::max(scale, std::abs(term->value(q)));
    for (double q : at) EXPECT_NEAR(compiled.value(q), term->value(q), 1e-13 * std::max(scale, 1.0)) << q;
  }
}

}  // namespace
}  // namespace mtacc
