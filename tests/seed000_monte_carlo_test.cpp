// Seed 000 §3.11: Monte Carlo over the uniform limits of Table 3.9 (L4353-4556), bundled as
// data/limits/seed000-table3.9.yaml.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/limits_yaml.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/machine_yaml.hpp"
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
