// Generic identification and observability: round trips on the tilting-table and the
// inclined-axis machines (random location errors, simulated R-test and ballbar data with
// 0.5 um noise), coverage of the reported 95 % intervals, and the seed-001 ambiguity of the
// cubic machining test.
#include <gtest/gtest.h>

#include <random>

#include "mtacc/identification/identification.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

std::vector<double> degrees(double from, double to, int n) {
  std::vector<double> a;
  for (int k = 0; k < n; ++k) a.push_back((from + (to - from) * k / (n - 1)) * kDeg);
  return a;
}

std::vector<double> pose(const Machine& m, std::initializer_list<std::pair<const char*, double>> values) {
  std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
  for (const auto& [name, v] : values) q[static_cast<size_t>(m.axisIndex(name))] = v;
  return q;
}

// R-test over each rotary axis with the sphere at two offset positions, plus the three
// ISO 230-4 ballbar circles at the home pose (for the squareness of the linear axes).
std::vector<MeasurementRun> testPlan(const KinematicModel& nominal, const std::string& tilt, double tiltAngle) {
  const Machine& m = *nominal.machine;
  std::vector<MeasurementRun> runs;
  auto add = [&](std::vector<MeasurementRun> more, std::vector<SetupParameter> estimate) {
    for (auto& r : more) {
      r.estimate = estimate;
      r.name += "-" + std::to_string(runs.size());
      runs.push_back(std::move(r));
    }
  };
  SphereTestSpec c;
  c.axis = "C";
  c.angles = degrees(0, 330, 12);
  c.spheres = {Vec3(120, 0, 60), Vec3(0, 80, 160)};
  // The sphere's position on the table is unknown up to its set-up.
  const std::vector<SetupParameter> sphere = {SetupParameter::TargetX, SetupParameter::TargetY,
                                              SetupParameter::TargetZ};
  add(sphereTest(nominal, c), sphere);
  c.pose = pose(m, {{tilt.c_str(), tiltAngle}});
  add(sphereTest(nominal, c), sphere);
  SphereTestSpec t;
  t.axis = tilt;
  t.angles = degrees(0, tiltAngle / kDeg, 10);
  t.spheres = {Vec3(100, 50, 50), Vec3(-60, 0, 150)};
  add(sphereTest(nominal, t), sphere);
  // The ballbar's centre is unknown within the plane of its circle.
  const std::pair<const char*, std::vector<SetupParameter>> circles[] = {
      {"XY", {SetupParameter::TargetX, SetupParameter::TargetY}},
      {"YZ", {SetupParameter::TargetY, SetupParameter::TargetZ}},
      {"ZX", {SetupParameter::TargetZ, SetupParameter::TargetX}}};
  for (const auto& [plane, centre] : circles) {
    BallbarCircleSpec b;
    b.plane = plane;
    b.radius = 150;
    b.points = 72;
    b.centre = Vec3(0, 0, 100);
    add({ballbarCircle(nominal, b)}, centre);
  }
  return runs;
}

IdentificationProblem problemFor(const std::shared_ptr<const Machine>& machine, const std::vector<std::string>& names,
                                 const std::vector<MeasurementRun>& runs) {
  IdentificationProblem p;
  p.machine = machine;
  p.start = ErrorModel::zero(*machine);
  for (const auto& n : names) p.parameters.push_back(findParameter(*machine, p.start, n));
  p.runs = runs;
  return p;
}

// Location errors of realistic size: positions within +-20 um, angles within +-40 urad.
ErrorModel randomErrors(const IdentificationProblem& p, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ErrorModel e = p.start;
  for (const auto& par : p.parameters)
    setParameterValue(e, par, u(rng) * (par.dimension == Dimension::Length ? 20e-3 : 40e-6));
  return e;
}

struct RoundTripCase {
  std::string machine, tilt;
  double tiltAngle;
  std::vector<std::string> parameters;
};

class Identification : public ::testing::TestWithParam<RoundTripCase> {};

// 100 noisy trials: every estimate must lie within its reported uncertainty's reach
// (|error| < 4.5 u, far beyond chance for 100 x 11 normal draws), and the uncertainties must
// be neither too small nor too large: the 95 % intervals (1.96 u) cover the true value in
// 90-99 % of the cases (1100 draws, 11 per trial correlated: +-4 binomial sigma and more),
// and the normalised errors error / u have an RMS within 1 +- 0.15 (about 6 sigma of its
// spread for 1100 draws; an uncertainty inflated or shrunk by 20 % fails).
TEST_P(Identification, IdentifiedWithinUncertaintyAndIntervalsCover) {
  const auto& c = GetParam();
  const auto machine = test::bundled(c.machine);
  const auto nominal = compileNominal(machine);
  auto problem = problemFor(machine, c.parameters, testPlan(nominal, c.tilt, c.tiltAngle));
  ASSERT_TRUE(planObservability(problem).identifiable());

  std::mt19937_64 rng(7);
  const auto truth = randomErrors(problem, rng);
  const auto model = compile(machine, truth);
  std::uniform_real_distribution<double> setup(-0.05, 0.05);
  for (auto& r : problem.runs)
    for (int k = 0; k < 3; ++k)
      r.setup.errors[static_cast<size_t>(SetupParameter::TargetX) + static_cast<size_t>(k)] = setup(rng);
  const auto truthRuns = problem.runs;

  int covered = 0, total = 0;
  double squaredNormalised = 0;
  const int trials = 100;
  for (int trial = 0; trial < trials; ++trial) {
    problem.runs = truthRuns;
    for (auto& r : problem.runs) simulateRun(model, nominal, r, {}, 0.5e-3, &rng);
    for (auto& r : problem.runs) r.setup.errors = {};  // the set-up is unknown too
    const auto result = identify(problem);
    ASSERT_TRUE(result.converged) << result.solverReport;
    for (size_t k = 0; k < problem.parameters.size(); ++k) {
      const double error = result.values[static_cast<Eigen::Index>(k)] - parameterValue(truth, problem.parameters[k]);
      const double u = result.uncertainty[static_cast<Eigen::Index>(k)];
      EXPECT_LT(std::abs(error), 4.5 * u) << problem.parameters[k].name << " trial " << trial;
      covered += std::abs(error) <= 1.96 * u;
      squaredNormalised += (error / u) * (error / u);
      ++total;
    }
    EXPECT_NEAR(result.sigma, 0.5e-3, 0.1e-3);
  }
  const double coverage = static_cast<double>(covered) / total;
  const double rms = std::sqrt(squaredNormalised / total);
  EXPECT_GE(coverage, 0.90) << "95 % intervals covered " << coverage;
  EXPECT_LE(coverage, 0.99) << "95 % intervals covered " << coverage << ": uncertainties too large";
  EXPECT_NEAR(rms, 1.0, 0.15) << "RMS of error / uncertainty";
  RecordProperty("coverage", std::to_string(coverage));
  RecordProperty("normalised_rms", std::to_string(rms));
}

INSTANTIATE_TEST_SUITE_P(
    Machines, Identification,
    ::testing::Values(RoundTripCase{"tilting-table", "B", -60 * kDeg,
                                    {"X0B", "Z0B", "A0B", "C0B", "X0C", "Y0C", "A0C", "B0C", "C0Y", "A0Z", "B0Z"}},
                      RoundTripCase{"inclined-a-table", "A", 90 * kDeg,
                                    {"Y0A", "X0A", "B0A", "C0A", "X0C", "Y0C", "A0C", "B0C", "C0Y", "A0Z", "B0Z"}}),
    [](const auto& info) {
      std::string n = info.param.machine;
      for (auto& ch : n) ch = ch == '-' ? '_' : ch;
      return n;
    });

}  // namespace
}  // namespace mtacc
