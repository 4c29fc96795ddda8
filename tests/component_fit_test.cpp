// Fitting a component error as seed 003 §5.2 does: C1 piecewise quadratics with fixed breaks,
// stepwise removal, a periodic term. The acceptance check of the issue: the procedure run on
// data sampled from the App. D tables (10 mm step, 20 runs forward and backward, noise at the
// instruments' stated uncertainty, extraction §6.1) recovers them within the fit's own
// uncertainty.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <Eigen/LU>

#include <cmath>
#include <random>

#include "mtacc/measurement/component_fit.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct Sampled {
  std::vector<double> x, y;  // position, mean of the 40 readings there
};

// 20 runs forward and 20 backward at a 10 mm step, each reading with Gaussian noise `sigma`;
// the mean of the 40 readings per position, as the seed fits.
Sampled sampleRuns(const ErrorFunction& truth, double from, double to, double sigma, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  Sampled s;
  for (double x = from; x <= to + 1e-9; x += 10.0) {
    double sum = 0;
    for (int reading = 0; reading < 40; ++reading) sum += truth.value(x, 0) + noise(rng);
    s.x.push_back(x);
    s.y.push_back(sum / 40);
  }
  return s;
}

// The C1 coefficients of an App. D table in the fit's order: 1, x, x^2, then (x - t_i)_+^2. The
// table's value and slope jumps at its breaks are printed rounding (Seed003AppendixD.*C1*).
Eigen::VectorXd c1Coefficients(const PiecewiseTerm& p) {
  std::vector<double> out;
  for (const auto& c : p.coefficients)
    if (c.knot == 0 || c.power == 2) out.push_back(c.value);
  return Eigen::Map<Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

struct Component {
  const char* name;
  double sigma;  // standard deviation of one reading, internal units
};

// Extraction §6.1: angular laser 0.2", levels 0.5" (xrx, zrz; yry from straightness runs, for
// which no figure is given, taken as the levels'), linear laser 0.05 + 0.5 L um: 0.4 um over 0.7 m.
const Component kComponents[] = {{"xrx", 0.5 * kArcsec}, {"xry", 0.2 * kArcsec}, {"xrz", 0.2 * kArcsec}, {"yrx", 0.2 * kArcsec},
                                 {"yry", 0.5 * kArcsec}, {"yrz", 0.2 * kArcsec}, {"zrx", 0.2 * kArcsec}, {"zry", 0.2 * kArcsec},
                                 {"zrz", 0.5 * kArcsec}, {"yty", 0.4 * kMicro}, {"ztz", 0.4 * kMicro}};

// A straight line through five points whose residuals (1, -2, 0, 2, -1) um are orthogonal to
// the constant and the slope: the fit returns them exactly, with n - p = 3 degrees of freedom,
// s = sqrt(10 um^2 / 3) and the slope's variance s^2 / sum (x - mean)^2 = s^2 / 6250 mm^2.
TEST(ComponentFit, DegreesOfFreedomAndResidualStdOnAHandCase) {
  const std::vector<double> x = {0, 25, 50, 75, 100}, r = {1e-3, -2e-3, 0, 2e-3, -1e-3};
  std::vector<double> y;
  for (size_t i = 0; i < x.size(); ++i) y.push_back(0.004 + 2e-5 * x[i] + r[i]);
  const ComponentFit fit = fitComponent(x, y, {{0.0, 100.0}, 1, 0.0});
  EXPECT_EQ(fit.degreesOfFreedom, 3);
  EXPECT_NEAR(fit.residualStd, std::sqrt(10e-6 / 3.0), 1e-15);
  for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(fit.residuals[static_cast<Eigen::Index>(i)], r[i], 1e-15) << i;
  // The fitted values' uncertainty at the ends: s^2 (1/n + (x - mean)^2 / 6250), x - mean = -+50.
  const double s2 = 10e-6 / 3.0, end = s2 * (1.0 / 5.0 + 2500.0 / 6250.0);
  EXPECT_NEAR(fit.valueUncertainty(0.0), std::sqrt(end), 1e-12);
  EXPECT_NEAR(fit.valueUncertainty(100.0), std::sqrt(end), 1e-12);
  EXPECT_NEAR(fit.valueUncertainty(50.0), std::sqrt(s2 / 5.0), 1e-12);
}

TEST(ComponentFit, AppendixDTablesRecoveredWithinTheirUncertainty) {
  // Without stepwise removal the fitted model holds the truth exactly, so the coefficient error
  // e with the fit's covariance C gives e^T C^-1 e ~ chi-square with p degrees of freedom: each
  // table must stay below its 99.9 % quantile.
  const auto machine = test::bundled("maho");
  const auto errors = loadMachineErrors(*machine);
  std::mt19937 rng(2024);
  for (const auto& c : kComponents) {
    const auto& truth = test::seed003Component(*machine, errors, c.name);
    const auto& table = std::get<PiecewiseTerm>(truth.terms()[0]);
    const auto data = sampleRuns(truth, table.breaks.front(), table.breaks.back(), c.sigma, rng);
    const auto fit = fitComponent(data.x, data.y, {.breaks = table.breaks, .significance = 0});
    const Eigen::VectorXd expected = c1Coefficients(table);
    ASSERT_EQ(static_cast<size_t>(expected.size()), fit.trend.coefficients.size()) << c.name;
    Eigen::VectorXd error(expected.size());
    for (Eigen::Index k = 0; k < expected.size(); ++k) error[k] = fit.trend.coefficients[static_cast<size_t>(k)].value - expected[k];
    const double chi2 = error.dot(fit.covariance.fullPivLu().solve(error));
    const boost::math::chi_squared distribution(static_cast<double>(expected.size()));
    EXPECT_LT(chi2, boost::math::quantile(distribution, 0.999)) << c.name;
    // The residual scatter is the mean of 40 readings': sigma / sqrt(40), within sampling error.
    EXPECT_NEAR(fit.residualStd / (c.sigma / std::sqrt(40.0)), 1.0, 0.35) << c.name;
  }
}

TEST(ComponentFit, XtxTrendAndPeriodicTermRecovered) {
  // xtx: the trend and the lambda = 39.6 mm term fitted together; the joint function at every
  // sampled position within 4 standard uncertainties of the fit, and the periodic term zero at
  // both ends of its period with equal slopes there.
  const auto machine = test::bundled("maho");
  const auto errors = loadMachineErrors(*machine);
  const auto& truth = test::seed003Component(*machine, errors, "xtx");
  const auto& trend = std::get<PiecewiseTerm>(truth.terms()[0]);
  std::mt19937 rng(7);
  const auto data = sampleRuns(truth, 0, 700, 0.4 * kMicro, rng);
  const auto fit = fitComponent(data.x, data.y, {.breaks = trend.breaks, .significance = 0, .period = 39.6});
  ASSERT_TRUE(fit.periodic);
  double worst = 0;
  for (double x = 0; x <= 700; x += 1.0) worst = std::max(worst, std::abs(fit.value(x) - truth.value(x, 0)) / fit.valueUncertainty(x));
  EXPECT_LT(worst, 4.0);
  const auto& p = *fit.periodic;
  EXPECT_EQ(p.value(0.0), 0.0);
  EXPECT_NEAR(p.value(39.6 - 1e-9), 0.0, 1e-12);
  const double h = 1e-6;
  EXPECT_NEAR((p.value(h) - p.value(0.0)) / h, (p.value(39.6 - 1e-9) - p.value(39.6 - 1e-9 - h)) / h, 1e-6);
  // Its amplitude: the table's term ranges from -1.82 to +0.84 um (extraction §8.3).
  double low = 0, high = 0;
  for (double u = 0; u < 39.6; u += 0.05) {
    low = std::min(low, p.value(u));
    high = std::max(high, p.value(u));
  }
  EXPECT_NEAR(low / kMicro, -1.82, 0.15);
  EXPECT_NEAR(high / kMicro, 0.84, 0.15);
}

TEST(ComponentFit, StepwiseRemovesWhatTheDataDoNotNeed) {
  // A plain parabola sampled with noise, fitted with six breaks: the knot terms are not needed,
  // the stepwise test drops them and keeps the curvature; the fit stays within 4 uncertainties.
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> x, y;
  auto parabola = [](double v) { return 1.0 + 0.02 * v - 4e-5 * v * v; };
  for (double v = 0; v <= 600; v += 5) {
    x.push_back(v);
    y.push_back(parabola(v) + noise(rng));
  }
  const auto fit = fitComponent(x, y, {.breaks = {0, 100, 200, 300, 400, 500, 600}});
  EXPECT_EQ(fit.removed.size(), 5u);
  ASSERT_EQ(fit.trend.coefficients.size(), 3u);
  for (const auto& c : fit.trend.coefficients) EXPECT_EQ(c.knot, 0);
  for (double v = 0; v <= 600; v += 10) EXPECT_LT(std::abs(fit.value(v) - parabola(v)), 4 * fit.valueUncertainty(v)) << v;
}

TEST(ComponentFit, ExactDataGiveTheTableBack) {
  // Noise-free samples of a C1 table at 5 mm: the fit reproduces the table's intervals.
  const auto table = piecewiseFromIntervals({0, 100, 250}, {{{0.5, 0.01, -1e-4}, {0.5 + 1e-4 * 100 * 100 * 0.5, 0.01 - 1e-4 * 100, -0.5e-4}}});
  std::vector<double> x, y;
  for (double v = 0; v <= 250; v += 5) {
    x.push_back(v);
    y.push_back(table.value(v));
  }
  const auto fit = fitComponent(x, y, {.breaks = {0, 100, 250}, .significance = 0});
  const auto pieces = fit.trend.intervals();
  const auto expected = table.intervals();
  for (size_t i = 0; i < 2; ++i)
    for (size_t j = 0; j < 3; ++j) EXPECT_NEAR(pieces[i][j], expected[i][j], 1e-9 * std::max(1.0, std::abs(expected[i][j]))) << i << j;
  EXPECT_LT(fit.residualStd, 1e-12);
}

}  // namespace
}  // namespace mtacc
