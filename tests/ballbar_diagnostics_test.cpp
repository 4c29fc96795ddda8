// ISO 230-4 circular test evaluation and the ballbar diagnostics: each signature, simulated
// alone on the 3-axis machine (XY circle, R = 100 mm, both directions, 1000 mm/min), must come
// back as the value put in. The diagnostics are a linear fit of exactly these signatures, so
// the tolerances only allow for second-order terms (e^2 / R, a few nm).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/measurement/circular_evaluation.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct Bench {
  std::shared_ptr<const Machine> machine = test::bundled("three-axis-vertical");
  KinematicModel nominal = compileNominal(machine);

  MeasurementRun circle() const {
    BallbarCircleSpec spec;
    spec.centre = Vec3(300, 200, 250);
    spec.radius = 100;
    spec.points = 720;
    spec.feed = 1000;
    return ballbarCircle(nominal, spec);
  }
  // One counter-clockwise turn of 360 points, its first pose repeated at the end.
  MeasurementRun oneWayCircle() const {
    BallbarCircleSpec spec;
    spec.centre = Vec3(300, 200, 250);
    spec.points = 360;
    spec.bothDirections = false;
    return ballbarCircle(nominal, spec);
  }
  CircularTestResult measure(const std::string& errorsYaml, const Disturbance& d = {}, MeasurementRun run = {}) const {
    if (run.poses() == 0) run = circle();
    const auto errors = errorsYaml.empty() ? ErrorModel::zero(*machine)
                                           : parseErrors(*machine, "errors:\n" + errorsYaml, "test");
    const auto model = compile(machine, errors);
    simulateRun(model, nominal, run, d);
    return evaluateCircularTest(run);
  }
};

MeasurementRun firstPoses(MeasurementRun run, Eigen::Index n) {
  run.q.conservativeResize(n, Eigen::NoChange), run.readings.conservativeResize(n, Eigen::NoChange);
  run.angle.resize(static_cast<size_t>(n)), run.sense.resize(static_cast<size_t>(n));
  return run;
}

TEST(BallbarDiagnostics, SquarenessOfXY) {
  const auto r = Bench().measure("  C0Y: 20 urad\n");
  EXPECT_NEAR(r.diagnostics.squareness, 20e-6, 0.01e-6);
  EXPECT_NEAR(r.diagnostics.scaleMismatch, 0.0, 1e-9);
  EXPECT_NEAR(r.diagnostics.servoMismatch, 0.0, 1e-6);
  // (R gamma / 2) sin 2theta: circular deviation R gamma = 2 um in each direction.
  ASSERT_EQ(r.directions.size(), 2u);
  EXPECT_NEAR(r.directions[0].circularDeviation, 100 * 20e-6, 0.005e-3);
  EXPECT_NEAR(r.hysteresis, 0.0, 0.001e-3);
}

TEST(BallbarDiagnostics, ScaleMismatch) {
  // EXX of this machine's workpiece-side X is the table's positioning error: +10 um per
  // 1000 mm of table travel shortens the tool's travel relative to the workpiece,
  // s_x - s_y = -1e-5.
  const auto r = Bench().measure("  EXX: {linear: {value: 10 um, over: 1000 mm}}\n");
  EXPECT_NEAR(r.diagnostics.scaleMismatch, -1e-5, 0.01e-5);
  EXPECT_NEAR(r.diagnostics.squareness, 0.0, 0.01e-6);
}

TEST(BallbarDiagnostics, ServoMismatchNeedsBothDirections) {
  const Bench b;
  Disturbance d;
  d.lag = {1e-3, 0.0, 0.0};  // X follows 1 ms behind Y
  const auto r = b.measure("", d);
  EXPECT_NEAR(r.diagnostics.servoMismatch, 1e-3, 0.02e-3);
  EXPECT_NEAR(r.diagnostics.squareness, 0.0, 0.05e-6);  // the same sin 2theta, opposite in CW and CCW
  EXPECT_GT(r.hysteresis, 1e-3);  // 2 x (R omega dtau / 2) = 16.7 um / 2 between directions
}

TEST(BallbarDiagnostics, BacklashAndReversalSpike) {
  const Bench b;
  Disturbance d;
  d.backlash = {6e-3, 0.0, 0.0};
  const auto r = b.measure("", d);
  EXPECT_NEAR(r.diagnostics.backlashA, 6e-3, 0.05e-3);
  EXPECT_NEAR(r.diagnostics.backlashB, 0.0, 0.05e-3);
  EXPECT_NEAR(r.hysteresis, 6e-3, 0.1e-3);

  Disturbance spike;
  spike.spikeHeight = {0.0, 4e-3, 0.0};
  spike.spikeTime = 0.05;
  const auto s = b.measure("", spike);
  EXPECT_GT(s.diagnostics.reversalSpikeB, 2e-3);
  EXPECT_LT(s.diagnostics.reversalSpikeA, 0.5 * s.diagnostics.reversalSpikeB);
}

// Regression: the readings once took each pose's directions of motion from the wrong
// entries of the run's direction matrix. Every simulated reading must be the bar length
// at that pose with exactly that pose's directions.
TEST(BallbarDiagnostics, EachReadingUsesItsOwnPosesDirections) {
  const Bench b;
  auto run = b.circle();
  const auto model = compile(b.machine, parseErrors(*b.machine, "errors:\n  EXX: {reversal: 4 um}\n  EYY: {reversal: 3 um}\n", "test"));
  simulateRun(model, b.nominal, run);
  ASSERT_EQ(run.direction.rows(), run.poses());
  const Vec3 workBall = run.setup.target;
  int reversedX = 0;
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    std::vector<int> dir(static_cast<size_t>(run.direction.cols()));
    for (Eigen::Index k = 0; k < run.direction.cols(); ++k) dir[static_cast<size_t>(k)] = run.direction(i, k);
    reversedX += dir[0] < 0;
    const Vec3 tool = toolInWorkpiece(model, run.q.row(i).data(), dir.data()) * run.setup.toolBall;
    EXPECT_NEAR(run.readings(i, 0), (tool - workBall).norm() - run.setup.length, 1e-12) << "pose " << i;
  }
  EXPECT_GT(reversedX, 0);
  EXPECT_LT(reversedX, run.poses());
}

TEST(BallbarDiagnostics, CentreOffsetIsTheEccentricity) {
  const Bench b;
  auto run = b.circle();
  run.setup.errors[static_cast<size_t>(SetupParameter::TargetX)] = 10e-3;
  const auto r = b.measure("", {}, run);
  // The bar shortens towards +X: dL = -10 um cos(theta).
  EXPECT_NEAR(r.eccentricity.eccentricity.x(), -10e-3, 0.002e-3);
  EXPECT_NEAR(r.eccentricity.eccentricity.y(), 0.0, 0.002e-3);
  // The least-squares circle removes it: no circular deviation left.
  EXPECT_LT(r.directions[0].circularDeviation, 0.002e-3);
  EXPECT_NEAR(r.directions[0].radialMax, 10e-3, 0.01e-3);
}

TEST(BallbarDiagnostics, PartialArcKeepsShapeOutOfTheCentre) {
  const Bench b;
  auto run = b.oneWayCircle();
  const auto model = compile(b.machine, parseErrors(*b.machine, "errors:\n  C0Y: 50 urad\n", "test"));
  run.setup.errors[static_cast<size_t>(SetupParameter::TargetY)] = 5e-3;
  simulateRun(model, b.nominal, run);
  const Vec3 full = fitEccentricity(run, true).eccentricity;
  EXPECT_NEAR(full.y(), -5e-3, 0.002e-3);
  // Keep 200 of 360 degrees: the sin 2theta shape (R gamma / 2 = 2.5 um) leaks into a
  // first-harmonic-only fit, not into one with the second harmonics.
  const MeasurementRun arc = firstPoses(run, 200);
  EXPECT_LT((fitEccentricity(arc, true).eccentricity - full).norm(), 1e-6);
  EXPECT_GT((fitEccentricity(arc, false).eccentricity - full).norm(), 1e-3);
}

// A cos 3theta shape is none of the diagnostic signatures: on 360 evenly spaced angles
// (0 and 180 degrees among them) it is orthogonal to every column of the fit, the reversal
// columns included, so it is left whole in the residual and its RMS over the points is A / sqrt 2.
TEST(BallbarDiagnostics, ResidualRmsIsOverThePoints) {
  const Bench b;
  MeasurementRun run = b.oneWayCircle();
  simulateRun(b.nominal, b.nominal, run);
  const Eigen::Index n = 360;
  run = firstPoses(std::move(run), n);
  const double shape = 4e-3, squarenessTerm = 2e-3;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = run.angle[static_cast<size_t>(i)];
    run.readings(i, 0) = shape * std::cos(3 * t) + squarenessTerm * std::sin(2 * t);
  }
  const auto r = evaluateCircularTest(run);
  EXPECT_NEAR(r.diagnostics.residualRms, shape / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(r.diagnostics.squareness, -2 * squarenessTerm / run.setup.length, 1e-12);
}

TEST(BallbarDiagnostics, BadRunsAreRefused) {
  const Bench b;
  MeasurementRun run = b.circle();
  EXPECT_THROW(evaluateCircularTest(run), InvalidInput);  // no readings
  simulateRun(b.nominal, b.nominal, run);
  run.angle.resize(3), run.q.conservativeResize(3, Eigen::NoChange), run.readings.conservativeResize(3, Eigen::NoChange);
  EXPECT_THROW(evaluateCircularTest(run), InvalidInput);  // too few points
}

}  // namespace
}  // namespace mtacc
