// ISO 230-1 straightness and angular deviation from direct measurements: closed forms on runs
// built in the test, and the acceptance tests file's reader.
#include <gtest/gtest.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/acceptance_yaml.hpp"
#include "mtacc/procedures/geometric_tests.hpp"
#include "mtacc/procedures/measurement_uncertainty.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// Runs of EYX over X from -400 to 400 mm: a tilt of 5 um per 800 mm (the instrument's line) plus a
// bow of 3 um (a parabola 0 at the ends), the same in every run but one reading's noise.
ComponentRuns bowedRuns(double bow) {
  ComponentRuns r;
  for (int i = 0; i <= 16; ++i) r.positions.push_back(-400.0 + 50.0 * i);
  r.forward.resize(17, 3);
  r.backward.resize(17, 3);
  for (int i = 0; i <= 16; ++i) {
    const double u = r.positions[static_cast<size_t>(i)] / 400.0;
    const double y = 5e-3 * (u + 1) / 2 + bow * (1 - u * u);
    for (int j = 0; j < 3; ++j) {
      r.forward(i, j) = y + (j - 1) * 1e-4;  // readings 0.1 um apart: s = 0.1 um per direction
      r.backward(i, j) = y - (j - 1) * 1e-4;
    }
  }
  return r;
}

TEST(GeometricTests, StraightnessAgainstBothReferenceLines) {
  const auto machine = test::bundled("tilting-table");
  const auto g = evaluateGeometricTest(*machine, {0, 1}, bowedRuns(3e-3));  // EYX
  EXPECT_EQ(g.kind, GeometricTestKind::Straightness);
  EXPECT_EQ(g.component, "EYX");
  EXPECT_DOUBLE_EQ(g.measuredLength, 800.0);
  ASSERT_EQ(g.quantities.size(), 2u);
  // End-point line: through both ends, so the deviation is the bow, 3 um at the middle.
  EXPECT_NEAR(g.quantities[0].second, 3e-3, 1e-12);
  // Least squares: a parabola b (1 - u^2) on 17 even points has its best line at its mean,
  // b (1 - m), m the mean of u^2; the residuals run from b m (the middle) down to -b (1 - m) (the
  // ends), so the range is b. m over u = -1..1 in 1/8 steps = 2 sum_{k=1}^{8} (k/8)^2 / 17 = 0.375.
  EXPECT_NEAR(g.quantities[1].second, 3e-3, 1e-12);
  const double m = 2.0 * 204.0 / 64.0 / 17.0;
  EXPECT_NEAR(g.leastSquaresResidual[0], -3e-3 * (1 - m), 1e-12);
  EXPECT_NEAR(g.leastSquaresResidual[8], 3e-3 * m, 1e-12);
  EXPECT_NEAR(g.leastSquaresSlope, 5e-3 / 800.0, 1e-15);  // the bow is even: the line keeps the tilt
  EXPECT_NEAR(g.repeatability, 1e-4, 1e-15);
  EXPECT_EQ(g.readingsPerPosition, 6);
}

TEST(GeometricTests, AngularAndPositionalRanges) {
  const auto machine = test::bundled("tilting-table");
  auto runs = bowedRuns(0.0);
  runs.forward *= kArcsec / kMicro;  // the same shape in arcsec: 5 arcsec over the travel
  runs.backward *= kArcsec / kMicro;
  const auto pitch = evaluateGeometricTest(*machine, {0, 4}, runs);  // EBX
  EXPECT_EQ(pitch.kind, GeometricTestKind::Angular);
  ASSERT_EQ(pitch.quantities.size(), 1u);
  EXPECT_NEAR(pitch.quantities[0].second, 5 * kArcsec, 1e-12);
  EXPECT_EQ(evaluateGeometricTest(*machine, {0, 0}, bowedRuns(0.0)).kind, GeometricTestKind::Positional);  // EXX
  EXPECT_THROW(evaluateGeometricTest(*machine, {4, 2}, bowedRuns(0.0)), InvalidInput);                    // EZC: C turns
}

TEST(GeometricTests, RangeUncertaintyIsItsClosedForm) {
  RangeReadings r;
  r.instrument = "laser";
  r.instrumentStandard = 0.3e-3;
  r.drift = 1e-3;
  r.scatter = 0.4e-3;
  r.readingsPerMean = 10;
  const auto b = rangeUncertainty({{"end_point", 4e-3}}, 800, r);
  const double expected = std::sqrt(2 * 0.3e-3 * 0.3e-3 + 1e-6 / 3 + 2 * 0.16e-6 / 10);
  EXPECT_NEAR(b.at("end_point").combined, expected, 1e-15);
  EXPECT_NEAR(b.at("end_point").expanded, 2 * expected, 1e-15);
}

TEST(AcceptancePlan, ReadsTestsAndNamesTheirErrors) {
  const auto plan = parseAcceptancePlan(R"(title: T
tolerances: tol.yaml
tests:
  - {name: X, test: positioning, data: x.dat, conditions: c.yaml}
  - {test: rotary, data: runs/r.csv, calibration: 1 um, drift: 0.5 um}
  - {test: geometric, data: /abs/p.csv, calibration: 0.5 arcsec}
)",
                                        "/work/acc/tests.yaml");
  ASSERT_EQ(plan.tests.size(), 3u);
  EXPECT_EQ(*plan.tolerances, "/work/acc/tol.yaml");
  EXPECT_EQ(plan.tests[0].data, "/work/acc/x.dat");
  EXPECT_EQ(*plan.tests[0].conditions, "/work/acc/c.yaml");
  EXPECT_EQ(plan.tests[1].name, "r");
  EXPECT_NEAR(plan.tests[1].calibration->value, 1e-3, 1e-15);
  EXPECT_EQ(plan.tests[2].data, "/abs/p.csv");
  EXPECT_EQ(plan.tests[2].calibration->dimension, Dimension::Angle);
  const auto error = [](const std::string& yaml) {
    try {
      parseAcceptancePlan(yaml, "t.yaml");
    } catch (const InputError& e) {
      return e.where().key + "@" + std::to_string(e.where().line);
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("tests:\n  - {test: laser, data: a}\n"), "tests[0].test@2");
  EXPECT_EQ(error("tests:\n  - {test: rotary}\n"), "tests[0].data@2");
  EXPECT_EQ(error("tests:\n  - {test: positioning, data: a, drift: 1 um}\n"), "tests[0].drift@2");
  EXPECT_EQ(error("tests:\n  - {test: rotary, data: a, conditions: c}\n"), "tests[0].conditions@2");
  EXPECT_EQ(error("tests:\n  - {test: rotary, data: a, calibration: 1 arcsec}\n"), "tests[0].calibration@2");
  EXPECT_EQ(error("tests:\n  - {test: rotary, data: a}\n  - {test: rotary, data: b/a}\n"), "tests[1].name@3");
  EXPECT_EQ(error("tests: []\n"), "tests@1");
  EXPECT_EQ(error("title: x\n"), "tests@0");
}

}  // namespace
}  // namespace mtacc
