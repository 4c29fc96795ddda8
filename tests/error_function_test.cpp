// Component error functions: values of each term type, natural-spline conditions, and the
// basis functions as exact derivatives with respect to the parameters.
#include <gtest/gtest.h>

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
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-120.0, 120.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double q = u(rng);
    for (int k = 0; k < f.parameterCount(); ++k) {
      ErrorFunction g = f;
      const double v = f.parameter(k);
      g.setParameter(k, v + 1.0);
      // Every term is linear in its parameters: a unit step changes the value by the basis.
      EXPECT_NEAR(g.value(q, 1) - f.value(q, 1), f.basis(k, q, 1), 1e-12) << k;
    }
  }
  EXPECT_EQ(f.parameterSuffixes(),
            (std::vector<std::string>{"c0", "c1", "c2", "cyc", "t0", "t1", "t2", "t3", "rev"}));
}

}  // namespace
}  // namespace mtacc
