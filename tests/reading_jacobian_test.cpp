// The derivative of every instrument's reading with respect to machine and set-up parameters
// against central differences of the exact readings, at a non-zero error state. Tolerance:
// 1e-6 of the column's largest entry plus the difference quotient's rounding error,
// kRounding / h: the readings are computed from coordinates up to about 1000 mm, whose
// rounding (2.2e-16 * 1000 mm, a few operations) is at most 1e-12 mm. The h^2 curvature term
// is below 1e-10 at these steps and covered by the same bound.
#include <gtest/gtest.h>

#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/procedures/cubic_test.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

constexpr double kRounding = 1e-12;  // mm

TEST(ReadingJacobian, AllInstrumentsAgainstCentralDifferences) {
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const ErrorModel errors = loadMachineErrors(*machine);  // location and component errors
  // Location errors and component-error coefficients (a polynomial and a harmonic of B).
  std::vector<Parameter> params;
  for (const char* n : {"X0B", "A0C", "C0Y", "EXX.c1", "EBB.h1"}) params.push_back(findParameter(*machine, errors, n));
  const auto model = compile(machine, errors, params);
  KinematicData data;

  BallbarRotarySpec b;
  b.axis = "C";
  b.length = 80;
  b.workBall = Vec3(60, 20, 40);
  b.points = 12;
  b.pose = {0, 0, 0, -20 * kDeg, 0};
  SphereTestSpec r;
  r.axis = "B";
  r.angles = {-10 * kDeg, -40 * kDeg};
  r.spheres = {Vec3(80, -30, 60)};
  std::vector<MeasurementRun> runs = {ballbarRotaryTest(nominal, b), sphereTest(nominal, r)[0]};
  r.instrument = Instrument::TouchProbe;
  runs.push_back(sphereTest(nominal, r)[0]);
  for (auto& r : cubicZoneRuns(nominal, seed001CubicTest(), true)) runs.push_back(std::move(r));
  std::vector<SetupParameter> all;
  for (int k = 0; k < kSetupParameterCount; ++k) all.push_back(static_cast<SetupParameter>(k));

  for (auto& run : runs) {
    SCOPED_TRACE(instrumentName(run.instrument));
    std::vector<SetupParameter> setup;
    for (auto p : all)
      if (appliesTo(p, run.instrument)) setup.push_back(p);
    for (auto p : setup) run.setup.errors[static_cast<size_t>(p)] = setupParameterDimension(p) == Dimension::Length ? 7e-3 : 30e-6;
    const std::optional<PointJacobian> setAt =
        run.setup.setAt ? std::optional(pointJacobian(model, run.setup.setAt->data(), nullptr, toolBallWithSetupError(run), data))
                        : std::nullopt;
    for (Eigen::Index i = 0; i < run.poses(); i += 3) {
      const RunGeometry geometry = runGeometry(model, run);
      const NominalFrame frame = nominalFrame(nominal, run, i);
      ReadingJacobian j;
      readingJacobian(model, {run, i, geometry, frame, setup, setAt ? &*setAt : nullptr}, data, j);
      EXPECT_LT((j.reading - predictReading(model, nominal, run, i)).cwiseAbs().maxCoeff(), 1e-12);
      for (size_t k = 0; k < params.size(); ++k) {
        const double h = params[k].dimension == Dimension::Length ? 1e-4 : 1e-6;
        auto plus = errors, minus = errors;
        setParameterValue(plus, params[k], parameterValue(errors, params[k]) + h);
        setParameterValue(minus, params[k], parameterValue(errors, params[k]) - h);
        const Eigen::VectorXd fd = (predictReading(compile(machine, plus), nominal, run, i) -
                                    predictReading(compile(machine, minus), nominal, run, i)) / (2 * h);
        const Eigen::VectorXd an = j.machine.col(static_cast<Eigen::Index>(k));
        EXPECT_LE((fd - an).cwiseAbs().maxCoeff(), 1e-6 * an.cwiseAbs().maxCoeff() + kRounding / h) << params[k].name;
      }
      for (size_t k = 0; k < setup.size(); ++k) {
        const double h = setupParameterDimension(setup[k]) == Dimension::Length ? 1e-4 : 1e-6;
        auto plus = run, minus = run;
        plus.setup.errors[static_cast<size_t>(setup[k])] += h;
        minus.setup.errors[static_cast<size_t>(setup[k])] -= h;
        const Eigen::VectorXd fd =
            (predictReading(model, nominal, plus, i) - predictReading(model, nominal, minus, i)) / (2 * h);
        const Eigen::VectorXd an = j.setup.col(static_cast<Eigen::Index>(k));
        EXPECT_LE((fd - an).cwiseAbs().maxCoeff(), 1e-6 * an.cwiseAbs().maxCoeff() + kRounding / h) << setupParameterName(setup[k]);
      }
    }
  }
}

}  // namespace
}  // namespace mtacc
