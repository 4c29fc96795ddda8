// Measurement files: what `simulate` writes reads back as the same run (poses to the 1e-9 mm /
// deg of the printed digits, readings to the 1e-6 um printed), and a ballbar export without
// axis columns gives the poses of the circle it names.
#include <gtest/gtest.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/measurement_csv.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/procedures/cone.hpp"
#include "mtacc/io/plan_yaml.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(MeasurementCsv, WrittenRunsReadBackUnchanged) {
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const auto model = compile(machine, loadMachineErrors(*machine));
  for (auto run : loadTestPlan(nominal, "tilting-table-rtest").runs) {
    simulateRun(model, nominal, run);
    const auto back = parseMeasurementCsv(nominal, measurementCsv(*machine, run), run.name + ".csv");
    SCOPED_TRACE(run.name);
    EXPECT_EQ(back.name, run.name);
    EXPECT_EQ(back.instrument, run.instrument);
    EXPECT_EQ(back.estimate, run.estimate);
    ASSERT_EQ(back.poses(), run.poses());
    EXPECT_LT((back.q - run.q).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_EQ(back.direction, run.direction);
    EXPECT_LT((back.readings - run.readings).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((back.setup.target - run.setup.target).norm(), 1e-9);
    if (run.setup.setAt) {
      ASSERT_TRUE(back.setup.setAt.has_value());
      for (size_t j = 0; j < run.setup.setAt->size(); ++j) EXPECT_NEAR((*back.setup.setAt)[j], (*run.setup.setAt)[j], 1e-9);
    }
  }
}

TEST(MeasurementCsv, BallbarExportWithoutAxisColumns) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto nominal = compileNominal(machine);
  BallbarCircleSpec spec;
  spec.centre = Vec3(300, 200, 250);
  spec.points = 36;
  spec.bothDirections = false;
  auto run = ballbarCircle(nominal, spec);
  std::string text = "# instrument: ballbar\n# length: 100 mm\n# target: 300, 200, 250 mm\n# plane: XY\nangle_deg,dL_um\n";
  for (size_t i = 0; i < run.angle.size(); ++i) text += std::to_string(run.angle[i] / kDeg) + ",0.5\n";
  const auto back = parseMeasurementCsv(nominal, text, "export.csv");
  EXPECT_LT((back.q - run.q).cwiseAbs().maxCoeff(), 1e-5);  // angles printed to 1e-6 deg
  EXPECT_NEAR(back.readings(3, 0), 0.5e-3, 1e-15);
}

// A directional sensor's direction is a direction: written at any length, read as the unit vector.
TEST(MeasurementCsv, ASensingDirectionIsReadAsAUnitVector) {
  const auto nominal = compileNominal(test::bundled("three-axis-vertical"));
  const auto run = parseMeasurementCsv(nominal, "# instrument: directional\n# direction: 0, 3, 4\nX,Y,Z,d_um\n300,200,250,0.4\n", "d.csv");
  EXPECT_LT((run.setup.direction - Vec3(0, 0.6, 0.8)).norm(), 1e-15);
}

TEST(MeasurementCsv, BadPlansNameTheKey) {
  const auto nominal = compileNominal(test::bundled("tilting-table"));
  const auto unitless = test::thrown<InputError>([&] { parseTestPlan(nominal, "runs:\n  - circle: {plane: XY, radius: 100}\n", "plan.yaml"); });
  ASSERT_TRUE(unitless);
  EXPECT_EQ(unitless->where().line, 2);
  EXPECT_EQ(unitless->where().key, "runs[0].circle.radius");
  const auto linear = test::thrown<InputError>([&] {
    parseTestPlan(nominal, "runs:\n  - sphere: {axis: A, from: 0 deg, to: 90 deg, spheres: [[0 mm, 0 mm, 0 mm]]}\n", "plan.yaml");
  });
  ASSERT_TRUE(linear);
  EXPECT_NE(std::string(linear->what()).find("not a rotary axis"), std::string::npos) << linear->what();
  EXPECT_THROW(parseTestPlan(nominal, "runs:\n  - helix: {}\n", "plan.yaml"), InputError);
}

// Seed 000 ch. 4: the ballbar square to the cone surface. On the nominal machine the bar
// keeps its length along the whole 5-axis path, and every bar direction is the surface normal;
// with an error, dL follows the normal deviation n . (P_actual - P_nominal) to first order.
TEST(MeasurementCsv, ConeFrustumEquivalentPath) {
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const auto plan = parseTestPlan(nominal, "runs:\n  - cone: {preset: tilting-table, points: 180}\n", "plan.yaml");
  auto run = plan.runs.at(0);
  simulateRun(nominal, nominal, run);
  EXPECT_LT(run.readings.cwiseAbs().maxCoeff(), 1e-9);
  const auto spec = *conePreset("tilting-table");
  const auto path = conePath(spec, 180);
  for (size_t i = 0; i < path.points.size(); ++i)
    EXPECT_NEAR((path.points[i] - run.setup.target).normalized().dot(path.normals[i]), 1.0, 1e-9);
  auto withError = run;
  const auto errors = parseErrors(*machine, "errors:\n  X0C: 10 um\n", "test");
  const auto model = compile(machine, errors);
  simulateRun(model, nominal, withError);
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    const Vec3 d = toolPoint(model, run.q.row(i).data()).position - toolPoint(nominal, run.q.row(i).data()).position;
    // Second order: a tangential deviation t adds t^2 / 2L <= (10 um)^2 / 113 mm = 0.9e-6 mm.
    EXPECT_NEAR(withError.readings(i, 0), path.normals[static_cast<size_t>(i)].dot(d), 2e-6);
  }
}

}  // namespace
}  // namespace mtacc
