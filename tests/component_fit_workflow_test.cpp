// The direct-measurement workflow end to end: runs simulated from the Maho machine's App. D
// errors (read at an Abbe offset, with noise and the lubrication pump), read back, corrected,
// averaged, fitted, and the fitted function written as YAML that the machine loads again; the
// reader's and the workflow's errors.
#include <gtest/gtest.h>


#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "mtacc/core/units.hpp"
#include "mtacc/io/component_runs_csv.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

namespace fs = std::filesystem;

class ComponentFitWorkflow : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_.machine = test::bundled("maho");
    setup_.errors = loadMachineErrors(*setup_.machine);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  test::TestFolder folder_{"mtacc-fit"};
  const fs::path dir_ = folder_.dir();
  MachineSetup setup_;
};

TEST_F(ComponentFitWorkflow, XtxReadAtAnAbbeOffsetIsFittedBackAndLoadsAsYaml) {
  // xtx read 60 mm beside and 110 mm above the centroid: the pitch and yaw of App. D move the
  // reading by (rotation x offset)_x = xry * 110 mm - xrz * 60 mm, -0.86 um at X = 700; the Abbe
  // correction with the machine's own rotations takes it back to the centroid, and the fit with
  // the table's breaks and the 39.6 mm term recovers the truth within 4 standard uncertainties.
  ComponentSimulationRequest sim;
  sim.component = "xtx";
  sim.output = path("xtx.csv");
  sim.noise = "0.4 um";
  sim.abbeOffset = Vec3(0, 60, 110);
  simulateComponentFile(setup_, sim);
  const auto& truth = test::seed003Component(*setup_.machine, setup_.errors, "xtx");
  ComponentFitRequest request;
  request.file = sim.output;
  request.breaks = std::get<PiecewiseTerm>(truth.terms()[0]).breaks;
  request.period = 39.6;
  request.significance = 0;
  const auto s = fitComponentFile(setup_, request);
  ASSERT_EQ(s.corrections.size(), 1u);
  ASSERT_TRUE(s.fit.periodic);
  for (double x = 0; x <= 700; x += 5) EXPECT_LT(std::abs(s.fit.value(x) - truth.value(x, 0)), 4 * s.fit.valueUncertainty(x)) << x;
  // The uncorrected readings carry that term (mean of 40 readings: 0.06 um noise), far outside
  // the fit's band.
  const auto& motion = setup_.errors.axes[static_cast<size_t>(setup_.machine->axisIndex("X"))].motion;
  const double abbe = motion[4].value(700, 0) * 110 - motion[5].value(700, 0) * 60;
  EXPECT_NEAR(abbe / kMicro, -0.86, 0.01);
  const auto raw = readComponentRuns(*setup_.machine, sim.output);
  const double offsetAtEnd = (raw.runs.forward.row(70).mean() + raw.runs.backward.row(70).mean()) / 2 - truth.value(700, 0);
  EXPECT_NEAR(offsetAtEnd, abbe, 4 * 0.4 * kMicro / std::sqrt(40.0));
  EXPECT_GT(std::abs(abbe), 8 * s.fit.valueUncertainty(700));

  // The YAML entry loads into the machine and evaluates to the fit (nine significant digits).
  const auto loaded = parseErrors(*setup_.machine, "errors:\n" + s.yaml, "fit.yaml", ErrorsKey::Required);
  const auto& f = test::seed003Component(*setup_.machine, loaded, "xtx");
  for (double x = 0; x <= 700; x += 3.3) EXPECT_NEAR(f.value(x, 0), s.fit.value(x), 1e-9) << x;
}

TEST_F(ComponentFitWorkflow, TheAbbeCorrectionNeedsTheRotations) {
  ComponentSimulationRequest sim;
  sim.component = "ztz";
  sim.output = path("ztz.csv");
  sim.abbeOffset = Vec3(30, 0, 0);
  simulateComponentFile(setup_, sim);
  MachineSetup bare{setup_.machine, ErrorModel::zero(*setup_.machine), std::nullopt};
  ComponentFitRequest request;
  request.file = sim.output;
  const auto e = test::thrown<InputError>([&] { fitComponentFile(bare, request); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().key, "abbe_offset");
}

// A rotary axis's positions are written in degrees and held in radians, as every angle is; the
// travel is checked in the same unit (the Maho's C turns from -60 to 60 deg).
TEST_F(ComponentFitWorkflow, ARotaryAxisPositionsAreDegrees) {
  const std::string head = "# component: ECC\n# unit: urad\nposition,run,direction,value\n";
  std::string rows;
  for (int r = 1; r <= 2; ++r)
    for (const int d : {1, -1})
      for (const int position : {-45, 0, 45}) rows += fmt::format("{},{},{},{}\n", position, r, d, 0.1 * position);
  const auto file = parseComponentRuns(*setup_.machine, head + rows, "c.csv");
  ASSERT_EQ(file.runs.positions.size(), 3u);
  EXPECT_NEAR(file.runs.positions.front(), -45 * kDeg, 1e-15);
  EXPECT_NEAR(file.runs.positions.back(), 45 * kDeg, 1e-15);
  EXPECT_NEAR(file.runs.forward(2, 0), 4.5e-6, 1e-18);
  const auto beyond = test::thrown<InputError>([&] { parseComponentRuns(*setup_.machine, head + "61,1,1,0\n", "c.csv"); });
  EXPECT_EQ(beyond->where().key, "position");
}

TEST_F(ComponentFitWorkflow, BadRunsAndBreaksAreLocated) {
  const std::string head = "# component: xrx\n# unit: arcsec\nposition,run,direction,value\n";
  auto rows = [](int runs, bool backward, int positions) {
    std::string t;
    for (int r = 1; r <= runs; ++r)
      for (const int d : {1, -1}) {
        if (d < 0 && !backward) continue;
        for (int i = 0; i < positions; ++i) t += fmt::format("{},{},{},{}\n", 100 * i, r, d, 0.1 * i);
      }
    return t;
  };
  auto where = [&](const std::string& text) {
    const auto e = test::thrown<InputError>([&] { parseComponentRuns(*setup_.machine, text, "runs.csv"); });
    return e ? e->where().key : std::string("(none)");
  };
  EXPECT_NO_THROW(parseComponentRuns(*setup_.machine, head + rows(2, true, 4), "runs.csv"));
  EXPECT_EQ(where(head + rows(2, false, 4)), "direction");                  // a run without its backward pass
  EXPECT_EQ(where(head + rows(1, true, 4)), "run");                         // too few repeats
  EXPECT_EQ(where(head + rows(2, true, 4) + "0,3,1,0\n0,3,-1,0\n"), "position");  // a ragged third run
  EXPECT_EQ(where(head + rows(2, true, 4) + "0,1,1,0\n"), "row");           // a reading given twice
  EXPECT_EQ(where("# component: xqx\n"), "component");
  EXPECT_EQ(where("# component: xrx\n# unit: mm\n"), "unit");
  EXPECT_EQ(where(head + "800,1,1,0\n"), "position");                       // beyond the X travel
  // Breaks that do not span the measurements, or reach beyond the travel.
  const std::string file = path("runs.csv");
  writeFileAtomically(file, head + rows(2, true, 8));
  ComponentFitRequest request;
  request.file = file;
  request.breaks = {100, 400, 700};
  EXPECT_EQ(test::thrown<InputError>([&] { fitComponentFile(setup_, request); })->where().key, "breaks");
  request.breaks = {0, 400, 800};
  EXPECT_EQ(test::thrown<InputError>([&] { fitComponentFile(setup_, request); })->where().key, "breaks");
}

}  // namespace
}  // namespace mtacc
