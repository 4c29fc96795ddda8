// Linear and not-a-knot cubic interpolation of uniformly sampled signals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/uniform_spline.hpp"

namespace mtacc {
namespace {

std::vector<double> sampled(double start, double period, int n, double (*f)(double)) {
  std::vector<double> v(n);
  for (int k = 0; k < n; ++k) v[k] = f(start + period * k);
  return v;
}

double cubicPolynomial(double t) { return 0.3 - 1.7 * t + 2.2 * t * t - 0.9 * t * t * t; }

// Samples drawn uniformly from [-amplitude, amplitude]: a signal with no smoothness to hide behind.
std::vector<double> randomSamples(size_t n, double amplitude, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> value(-amplitude, amplitude);
  std::vector<double> y(n);
  for (double& v : y) v = value(random);
  return y;
}

TEST(UniformSpline, NotAKnotReproducesACubicEverywhereIncludingTheEnds) {
  for (int n : {4, 5, 6, 40}) {
    const UniformSpline spline(-0.4, 0.07, sampled(-0.4, 0.07, n, cubicPolynomial));
    for (double u = 0; u <= 1.0; u += 1.0 / 997) {
      const double t = spline.first() + u * (spline.last() - spline.first());
      EXPECT_NEAR(spline(t), cubicPolynomial(t), 1e-12) << n << " " << t;
    }
  }
}

TEST(UniformSpline, PassesThroughTheSamplesWithContinuousSlopeAndCurvature) {
  const auto y = randomSamples(30, 1.0, 3);
  const double h = 0.5;
  const UniformSpline spline(1.0, h, y);
  for (size_t k = 0; k < y.size(); ++k) EXPECT_NEAR(spline(1.0 + h * static_cast<double>(k)), y[k], 1e-14);
  const double e = 1e-4;
  for (size_t k = 1; k + 1 < y.size(); ++k) {
    const double t = 1.0 + h * static_cast<double>(k);
    const double slopeLeft = (spline(t) - spline(t - e)) / e, slopeRight = (spline(t + e) - spline(t)) / e;
    EXPECT_NEAR(slopeLeft, slopeRight, 5e-3) << k;  // one-sided differences differ by the curvature * e
    const double curvatureLeft = (spline(t) - 2 * spline(t - e) + spline(t - 2 * e)) / (e * e);
    const double curvatureRight = (spline(t + 2 * e) - 2 * spline(t + e) + spline(t)) / (e * e);
    EXPECT_NEAR(curvatureLeft, curvatureRight, 2e-2 * (1.0 + std::fabs(curvatureLeft))) << k;
  }
}

// Seed 004 R9 (L290, extraction §4): linear interpolation of a trace sampled every T = 3 ms errs
// by a*T^2/8 at mid-interval, 1.125 um for a = 1000 mm/s^2 (printed rounded as 1.13 um); the
// cubic spline is exact on the parabola.
TEST(UniformSpline, Seed004R9LinearInterpolationOfA3msTraceErrsByAT2Over8) {
  const double period = 0.003, acceleration = 1000.0;  // s, mm/s^2
  std::vector<double> trace(200);
  for (size_t k = 0; k < trace.size(); ++k) {
    const double t = period * static_cast<double>(k);
    trace[k] = acceleration * t * t / 2;
  }
  const UniformSpline linear(0.0, period, trace, Interpolation::Linear), cubic(0.0, period, trace);
  double largestLinear = 0.0, largestCubic = 0.0;
  for (int j = 0; j <= 199 * 30; ++j) {  // a 10 kHz clock
    const double t = j * 1e-4;
    largestLinear = std::fmax(largestLinear, std::fabs(linear(t) - acceleration * t * t / 2));
    largestCubic = std::fmax(largestCubic, std::fabs(cubic(t) - acceleration * t * t / 2));
  }
  EXPECT_NEAR(largestLinear, acceleration * period * period / 8, 1e-12);
  EXPECT_NEAR(largestLinear * 1e3, 1.13, 0.005);  // um, as the extraction rounds it
  EXPECT_LT(largestCubic, 1e-11);
}

TEST(UniformSpline, RejectsTooFewSamplesNonFiniteValuesAndTimesOutsideTheSpan) {
  const std::vector<double> three{1, 2, 3}, four{1, 2, 3, 4}, withNan{1, 2, NAN, 4};
  EXPECT_THROW(UniformSpline(0, 1, three), InvalidInput);
  EXPECT_THROW(UniformSpline(0, 1, withNan), InvalidInput);
  EXPECT_THROW(UniformSpline(0, 0, four), InvalidInput);
  EXPECT_THROW(UniformSpline(0, INFINITY, four), InvalidInput);
  const UniformSpline spline(0, 1, four, Interpolation::Linear);
  EXPECT_DOUBLE_EQ(spline(3.0), 4.0);
  EXPECT_THROW(spline(3.01), InvalidInput);
  EXPECT_THROW(spline(-0.01), InvalidInput);
  EXPECT_THROW(spline(NAN), InvalidInput);
}

// atEvenly and slopeAtEvenly evaluate at(locate(t)) and slopeAt(locate(t)) at evenly spaced
// times: at the period, finer (as a 10 kHz instrument on a 3 ms trace), coarser, and backwards.
// The times and the period are binary fractions, so both find each time's interval and fraction
// without rounding and agree to the rounding of the polynomial alone.
TEST(UniformSpline, EvenlySpacedEvaluationEqualsThePointwiseOne) {
  const auto y = randomSamples(400, 5.0, 11);
  const double period = 0.25;
  for (const auto kind : {Interpolation::Linear, Interpolation::CubicSpline}) {
    const UniformSpline spline(0.0, period, y, kind);
    struct Run {
      double first, step;
      size_t count;
    };
    for (const Run run : {Run{0.0, period, 400}, Run{0.125, 1.0 / 64, 6000}, Run{1.0, 0.625, 150}, Run{99.5, -1.0 / 32, 3000}}) {
      std::vector<double> values(run.count), slopes(run.count);
      spline.atEvenly(run.first, run.step, values);
      spline.slopeAtEvenly(run.first, run.step, slopes);
      for (size_t k = 0; k < run.count; ++k) {
        const auto where = spline.locate(run.first + run.step * static_cast<double>(k));
        const double slope = spline.slopeAt(where);
        EXPECT_NEAR(values[k], spline.at(where), 1e-13) << k;
        EXPECT_NEAR(slopes[k], slope, 1e-13 * (1.0 + std::fabs(slope))) << k;
      }
    }
    std::vector<double> out(10);
    EXPECT_THROW(spline.atEvenly(-0.01, period, out), InvalidInput);     // the first before the span
    EXPECT_THROW(spline.atEvenly(98.0, period, out), InvalidInput);      // the last beyond it (99.75)
    EXPECT_THROW(spline.slopeAtEvenly(2.5, NAN, out), InvalidInput);
    EXPECT_NO_THROW(spline.atEvenly(NAN, period, std::span<double>()));  // nothing asked, nothing checked
  }
}

}  // namespace
}  // namespace mtacc
