// Seed 000 §3.11: Monte Carlo over the uniform limits of Table 3.9 (L4353-4556), bundled as
// data/limits/seed000-table3.9.yaml.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "mtacc/io/limits_yaml.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/procedures/monte_carlo.hpp"
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
  std::vector<AxisSpan> spans;
  for (const auto& a : motion.axes) spans.push_back({a.min, a.range});
  std::mt19937_64 rng(3);
  for (int s = 0; s < 30; ++s) {
    const auto model = compile(machine, sampleErrors(*machine, limits, spans, rng));
    const double exact = coneFormErrorExact(model, spec, path, motion).formError;
    const double first = coneFormErrorFirstOrder(model, nominal, path, motion).formError;
    EXPECT_NEAR(exact, first, 0.02 * exact) << "sample " << s;
  }
}

// Table 3.5 (L4133-4145): the distribution of 1000 random combinations of the thesis' model.
// Its conventions and random phases are not fully given (reference section 6.6) and 12 of the
// 31 single-error values of Table 3.4 differ, so no statistic is reproduced: each is pinned
// (1000 samples, seed 11) and must keep the thesis' order of magnitude (within a factor of
// two). The circular form of the cylinder (first column) is a test piece mtacc does not have.
TEST(Seed000MonteCarlo, Table3_5MonteCarloDistribution) {
  const auto machine = test::bundled("tilting-table");
  const auto limits = loadErrorLimits(*machine, limitsFile());
  const ConeSpec spec;
  const auto path = conePath(spec, 720);
  const auto motion = coneMotion(compileNominal(machine), spec, path);
  const auto st = coneMonteCarlo(machine, limits, spec, path, motion, 1000, 11).statistics;
  const char* reason = "the thesis' random phases and conventions are not given, and 12 entries of Table 3.4 differ";
  struct Row {
    const char* name;
    double cone, mtacc, today, cylinder;  // um; today: the pinned value
  };
  const Row rows[] = {{"maximum", 23.9, st.max * 1e3, 21.479, 13.6},
                      {"upper quartile", 11.0, st.upperQuartile * 1e3, 12.003, 6.7},
                      {"median", 8.8, st.median * 1e3, 9.868, 5.2},
                      {"lower quartile", 6.9, st.lowerQuartile * 1e3, 7.909, 4.1},
                      {"minimum", 2.6, st.min * 1e3, 3.371, 1.3}};
  for (const auto& r : rows) {
    test::expectKnownDifference({"000", "Table 3.5, L4133-4145", fmt::format("cone form error, {}", r.name), r.cone, 1, "um"},
                                r.mtacc, r.today, 0.01, reason);
    EXPECT_GT(r.mtacc, r.cone / 2) << r.name;
    EXPECT_LT(r.mtacc, r.cone * 2) << r.name;
    test::recordNotComputed({"000", "Table 3.5, L4133-4145", fmt::format("circular form of the cylinder, {}", r.name), r.cylinder,
                             1, "um"},
                            "the cylinder test piece is not modelled");
  }
}

TEST(Seed000MonteCarlo, BoxStatistics) {
  const auto b = boxStatistics({5, 1, 4, 2, 3});
  EXPECT_EQ(b.min, 1);
  EXPECT_EQ(b.lowerQuartile, 2);
  EXPECT_EQ(b.median, 3);
  EXPECT_EQ(b.upperQuartile, 4);
  EXPECT_EQ(b.max, 5);
}

}  // namespace
}  // namespace mtacc
