// Seed 000 §3.11: Monte Carlo over the uniform limits of Table 3.9 (L4353-4556), bundled as
// data/limits/seed000-table3.9.yaml.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/limits_yaml.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/core/statistics.hpp"
#include "mtacc/procedures/monte_carlo.hpp"
#include "mtacc/workflows/cone_study.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

std::string limitsFile() { return bundledDataDir() + "/limits/seed000-table3.9.yaml"; }

TEST(Seed000MonteCarlo, Table3_9LimitsLoad) {
  const auto machine = test::bundled("tilting-table");
  const auto limits = loadErrorLimits(*machine, limitsFile());
  EXPECT_EQ(limits.limits.size(), 99u);  // 21 X + 21 Y + 21 Z + 19 B + 17 C rows
}

TEST(Seed000MonteCarlo, ExactAndFirstOrderAgreeForTable3_9SizedErrors) {
  const auto machine = test::bundled("tilting-table");
  const auto limits = loadErrorLimits(*machine, limitsFile());
  const ConeSpec spec;  // proposed set-up
  const auto nominal = compileNominal(machine);
  const auto path = conePath(spec, 720);
  const auto motion = coneMotion(nominal, spec, path);
  std::vector<std::string> notes;
  const auto spans = monteCarloSpans(*machine, limits, motion, notes);
  std::mt19937_64 rng(3);
  for (int s = 0; s < 30; ++s) {
    const auto model = compile(machine, sampleErrors(*machine, limits, spans, rng));
    const double exact = coneFormErrorExact(model, spec, path, motion).formError;
    const double first = coneFormErrorFirstOrder(model, nominal, path, motion).formError;
    EXPECT_NEAR(exact, first, 0.02 * exact) << "sample " << s;
  }
}

ConeStudy monteCarloStudy(const std::string& machine, const std::string& preset, int samples) {
  ConeStudyRequest o;
  if (!preset.empty()) o.spec = *conePreset(preset);
  o.monteCarlo = samples;
  return coneStudy(loadMachineSetup({machine, "", "", std::nullopt, ""}), o);
}

// On the NAS 979 and double-pivot paths of the tilting-table machine Z does not move (range
// 1e-13 mm): the .lin limits divided by that range gave median form errors of 2.9e10 um. Such an
// axis's range-relative limits are taken over its travel, said in a note, and every form error
// stays of the order of the limits (all of Table 3.9 at once: tens of um).
TEST(Seed000MonteCarlo, AnAxisThatDoesNotMoveOnThePathIsScaledOverItsTravel) {
  for (const char* preset : {"nas979", "double-pivot"}) {
    const auto s = monteCarloStudy("tilting-table", preset, 40);
    ASSERT_TRUE(s.monteCarlo);
    EXPECT_FALSE(s.motion.axes[2].moves) << preset;
    ASSERT_EQ(s.monteCarlo->notes.size(), 1u) << preset;
    EXPECT_NE(s.monteCarlo->notes[0].find("Z does not move"), std::string::npos) << s.monteCarlo->notes[0];
    for (double e : s.monteCarlo->formErrors) {
      EXPECT_TRUE(std::isfinite(e)) << preset;
      EXPECT_LT(e, 0.1) << preset;  // mm
    }
    EXPECT_EQ(s.monteCarlo->drawn.rows(), 40);
    EXPECT_EQ(s.monteCarlo->drawn.cols(), static_cast<Eigen::Index>(s.limits.limits.size()));
  }
}

// The bundled limits are seed 000's tilting-table machine's: on a machine without its B axis
// the B entries are left out (and named), not a refusal of the whole Monte Carlo.
TEST(Seed000MonteCarlo, BundledLimitsOnAMachineWithoutTheirAxes) {
  const auto s = monteCarloStudy("inclined-a-table", "", 10);
  ASSERT_TRUE(s.monteCarlo);
  EXPECT_EQ(s.limits.leftOut.size(), 19u);
  ASSERT_FALSE(s.monteCarlo->notes.empty());
  EXPECT_NE(s.monteCarlo->notes[0].find("19 limits"), std::string::npos) << s.monteCarlo->notes[0];
  for (double e : s.monteCarlo->formErrors) EXPECT_LT(e, 0.1);
  // A user's own file naming an axis the machine lacks is a typo until shown otherwise.
  const auto machine = test::bundled("inclined-a-table");
  EXPECT_TRUE(test::thrown<InputError>([&] { loadErrorLimits(*machine, limitsFile()); }));
}

// The cone column of Tables 3.5 and 3.8: box statistics of 1000 random combinations of the
// thesis' model within Table 3.9. A statistic of 1000 samples is itself random, so mtacc's is
// judged against its own sampling spread: sigma of each statistic over 1000-sample subsamples
// of a 4000-sample run. The thesis' value is one such draw from its model; were the models the
// same, printed - mtacc would have a standard deviation of sqrt(2) sigma, so
// |printed - mtacc| <= 1.96 sqrt(2) sigma (95 %) counts as reproduced. A larger difference is a
// known difference of the models: the thesis' random phases and conventions are not given
// (reference §6.6) and 12 of the 31 single-error values of Table 3.4 differ. Pinned to 0.01 um
// (the run is deterministic for its seeds).
struct ConeDistribution {
  BoxStatisticsSpread spread;
  std::vector<double> formErrors;  // um, the 4000 samples
};

ConeDistribution coneDistribution(const std::string& preset) {
  const auto machine = test::bundled("tilting-table");
  const auto limits = loadErrorLimits(*machine, limitsFile());
  const ConeSpec spec = *conePreset(preset);
  const auto path = conePath(spec, 720);
  const auto motion = coneMotion(compileNominal(machine), spec, path);
  ConeDistribution d;
  for (double e : coneMonteCarlo(machine, limits, spec, path, motion, 4000, 11).formErrors) d.formErrors.push_back(e * 1e3);
  d.spread = boxStatisticsSpread(d.formErrors, 1000, 1000, 11);
  return d;
}

struct ConeRow {
  const char* name;
  double printed, today;  // um; today: mtacc's mean 1000-sample statistic, pinned
};

void expectConeColumn(const std::string& where, const ConeDistribution& d, const ConeRow (&rows)[5]) {
  const auto& m = d.spread.mean;
  const auto& s = d.spread.standardDeviation;
  const double mean[5] = {m.max, m.upperQuartile, m.median, m.lowerQuartile, m.min};
  const double sigma[5] = {s.max, s.upperQuartile, s.median, s.lowerQuartile, s.min};
  for (int k = 0; k < 5; ++k) {
    const test::Printed printed{"000", where, fmt::format("cone form error, {}", rows[k].name), rows[k].printed, 1, "um"};
    const double tolerance = 1.96 * std::sqrt(2.0) * sigma[k];
    if (std::abs(mean[k] - rows[k].printed) <= tolerance) {
      test::expectReproduced(printed, mean[k], tolerance, fmt::format("95 % of the difference of two 1000-sample runs, sigma {:.2f}", sigma[k]));
      EXPECT_NEAR(mean[k], rows[k].today, 0.01) << rows[k].name << ": today's value changed";
    } else {
      test::expectKnownDifference(printed, mean[k], rows[k].today, 0.01,
                                  fmt::format("beyond the 1000-sample spread ({:.2f} um at 95 %): the thesis' random phases and "
                                              "conventions are not given, and 12 entries of Table 3.4 differ",
                                              tolerance));
    }
  }
}

// Table 3.5 (L4133-4145): the proposed set-up. The circular form of the cylinder (first
// column) needs the cylinder element, whose size and place App. Fig. A.3 shows without numbers.
TEST(Seed000MonteCarlo, Table3_5ConeColumnAgainstItsSamplingSpread) {
  const ConeRow rows[5] = {{"maximum", 23.9, 22.351}, {"upper quartile", 11.0, 12.001}, {"median", 8.8, 9.737},
                           {"lower quartile", 6.9, 7.825}, {"minimum", 2.6, 3.635}};
  expectConeColumn("Table 3.5, L4133-4145", coneDistribution("tilting-table"), rows);
  const double cylinder[5] = {13.6, 6.7, 5.2, 4.1, 1.3};
  for (int k = 0; k < 5; ++k)
    test::recordNotComputed({"000", "Table 3.5, L4133-4145", fmt::format("circular form of the cylinder, {}", rows[k].name), cylinder[k], 1, "um"},
                            "the cylinder element's radius and place on the test piece are drawn in App. Fig. A.3 (L6617) without numbers");
}

// Table 3.8 (L4322-4334): the set-up cut at IWF for comparison (Table 3.6's first column), and
// the verification of L4340-4351 / Fig. 3.58: the measured normal circular form of the cone,
// 8.4 um, lies "nicely between the calculated median and the upper quartile".
TEST(Seed000MonteCarlo, Table3_8ComparisonSetupAndTheMeasuredConeOfFig3_58) {
  const ConeRow rows[5] = {{"maximum", 20.6, 22.880}, {"upper quartile", 10.0, 11.328}, {"median", 7.9, 9.196},
                           {"lower quartile", 6.3, 7.427}, {"minimum", 2.0, 2.878}};
  const auto d = coneDistribution("seed000-comparison");
  expectConeColumn("Table 3.8, L4322-4334", d, rows);
  const double cylinder[5] = {11.2, 6.4, 5.0, 4.0, 1.2};
  for (int k = 0; k < 5; ++k)
    test::recordNotComputed({"000", "Table 3.8, L4322-4334", fmt::format("circular form of the cylinder, {}", rows[k].name), cylinder[k], 1, "um"},
                            "the cylinder element's radius and place on the test piece are drawn in App. Fig. A.3 (L6617) without numbers");
  test::recordNotComputed({"000", "Fig. 3.58, L4291 and L4340-4351", "measured cylinder form error (between 5.0 and 6.4)", 5.8, 1, "um"},
                          "the cylinder element's radius and place on the test piece are drawn in App. Fig. A.3 (L6617) without numbers");
  const double measured = 8.4;
  const auto& m = d.spread.mean;
  const bool between = m.median <= measured && measured <= m.upperQuartile;
  const double below = static_cast<double>(std::count_if(d.formErrors.begin(), d.formErrors.end(), [&](double e) { return e < measured; })) /
                       static_cast<double>(d.formErrors.size());
  const test::Statement statement{"000", "Fig. 3.58, L4291 and L4340-4351", "measured cone form error between the median and the upper quartile",
                                  "7.9 <= 8.4 <= 10.0"};
  const std::string mtacc = fmt::format("{:.2f} <= 8.4 <= {:.2f}: {:.0f} % of the machines below 8.4", m.median, m.upperQuartile, 100 * below);
  if (between)
    test::expectStatementHolds(statement, between, mtacc, "mtacc's median and upper quartile of the comparison set-up");
  else
    test::expectStatementFails(statement, between, mtacc, "mtacc's distribution of the comparison set-up lies higher than the thesis'");
}

TEST(Seed000MonteCarlo, BoxStatistics) {
  const auto b = boxStatistics({5, 1, 4, 2, 3});
  EXPECT_EQ(b.min, 1);
  EXPECT_EQ(b.lowerQuartile, 2);
  EXPECT_EQ(b.median, 3);
  EXPECT_EQ(b.upperQuartile, 4);
  EXPECT_EQ(b.max, 5);
}

// The median of n uniform values on [0, 1] has a standard deviation of 1 / (2 sqrt(n)), times the
// finite-population factor sqrt(1 - n / N) when drawn without replacement from N; 2000 draws
// estimate it to about 2 %, so 10 % fails a wrong estimator (with replacement, or the spread of
// the values instead of the statistic) and passes this one.
TEST(Seed000MonteCarlo, BoxStatisticsSpreadOfTheMedianOfUniformValues) {
  std::vector<double> uniform;
  for (int k = 0; k < 40000; ++k) uniform.push_back((k + 0.5) / 40000);
  const auto s = boxStatisticsSpread(uniform, 1000, 2000, 3);
  EXPECT_NEAR(s.standardDeviation.median / (0.5 / std::sqrt(1000.0) * std::sqrt(1 - 1000.0 / 40000)), 1.0, 0.1);
  EXPECT_NEAR(s.mean.median, 0.5, 0.005);
  EXPECT_LT(s.mean.min, s.mean.lowerQuartile);
  EXPECT_THROW(boxStatisticsSpread(uniform, 30000, 10, 3), InvalidInput);
  EXPECT_THROW(boxStatisticsSpread(uniform, 1, 10, 3), InvalidInput);
  EXPECT_THROW(boxStatisticsSpread(uniform, 1000, 1, 3), InvalidInput);
}

}  // namespace
}  // namespace mtacc
