// Designing the measurement (workflows/measurement_design.hpp): the designed plans against the
// bundled tilting-table plan and the inclined-head docs example, the predicted uncertainties
// against the spread of identifications from simulated readings, the refusal of a parameter set
// no instrument can separate, the plan file read back, and the machine-time model in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "mtacc/identification/identification.hpp"
#include "mtacc/io/plan_yaml.hpp"
#include "mtacc/measurement/design_candidates.hpp"
#include "mtacc/measurement/machine_time.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/workflows/measurement_design.hpp"
#include "test_helpers.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

const std::string kInclinedHead = test::testDataDir() + "/../../docs/examples/inclined-head.yaml";
const std::string kInclinedHeadPlan = test::testDataDir() + "/../../docs/examples/inclined-head-rtest.yaml";

MachineSetup setupOf(const std::string& machine) { return loadMachineSetup({machine, "", "", std::nullopt, ""}); }

void recordFigures(const MeasurementDesign& d) {
  testing::Test::RecordProperty("design_minutes", std::to_string(d.outlook.minutes));
  testing::Test::RecordProperty("plan_minutes", std::to_string(d.own->minutes));
  for (size_t k = 0; k < d.parameters.size(); ++k)
    testing::Test::RecordProperty("ratio_" + d.parameters[k].name,
                   std::to_string(d.outlook.prediction.uncertainty[static_cast<Eigen::Index>(k)] / d.own->prediction.uncertainty[static_cast<Eigen::Index>(k)]));
}

// The bundled plan's parameters, each determined at least as well, in at most half its time.
TEST(MeasurementDesign, TiltingTableReachesTheBundledPlanInHalfItsTime) {
  MeasurementDesignRequest request;
  request.plan = "tilting-table-rtest";
  request.reach = true;
  const auto d = designMeasurement(setupOf("tilting-table"), request);
  ASSERT_TRUE(d.own);
  EXPECT_TRUE(d.reached);
  EXPECT_LE(d.outlook.minutes, 0.5 * d.own->minutes) << d.outlook.minutes << " min against " << d.own->minutes;
  for (size_t k = 0; k < d.parameters.size(); ++k)
    EXPECT_LE(d.outlook.prediction.uncertainty[static_cast<Eigen::Index>(k)], d.own->prediction.uncertainty[static_cast<Eigen::Index>(k)])
        << d.parameters[k].name;
  recordFigures(d);
}

// In the docs plan's own time, every uncertainty at most half the plan's.
TEST(MeasurementDesign, InclinedHeadHalvesTheDocsPlansUncertaintiesInItsTime) {
  const auto setup = setupOf(kInclinedHead);
  MeasurementDesignRequest request;
  request.plan = kInclinedHeadPlan;
  request.againstPlan = true;
  request.minutes = planMinutes(*setup.machine, loadTestPlan(setup.nominal(), kInclinedHeadPlan).runs, request.time);
  const auto d = designMeasurement(setup, request);
  ASSERT_TRUE(d.own);
  EXPECT_LE(d.outlook.minutes, d.own->minutes * (1 + 1e-9));
  for (size_t k = 0; k < d.parameters.size(); ++k)
    EXPECT_LE(d.outlook.prediction.uncertainty[static_cast<Eigen::Index>(k)], 0.5 * d.own->prediction.uncertainty[static_cast<Eigen::Index>(k)])
        << d.parameters[k].name;
  recordFigures(d);
}

// The first-order prediction against what identification does with simulated readings: a
// machine with location errors of realistic size, the spheres' set-up errors random per draw,
// the readings' noise the design assumed; 200 draws, the standard deviation of each estimate
// within ±15 % of its predicted standard uncertainty (the sampling spread of a standard deviation
// of 200 draws is 5 %: the bound is three of it).
TEST(MeasurementDesign, PredictedUncertaintiesMatchTheSpreadOfIdentifications) {
  const auto setup = setupOf("tilting-table");
  MeasurementDesignRequest request;
  request.plan = "tilting-table-rtest";
  request.minutes = 20;
  const auto d = designMeasurement(setup, request);
  IdentificationProblem problem{setup.machine, ErrorModel::zero(*setup.machine), d.parameters, {}};
  for (const auto& c : d.chosen) problem.runs.push_back(c.run);
  const auto nominal = setup.nominal();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ErrorModel truth = problem.start;
  for (const auto& p : problem.parameters) setParameterValue(truth, p, u(rng) * (p.dimension == Dimension::Length ? 20e-3 : 40e-6));
  const auto model = compile(setup.machine, truth);
  const auto p = static_cast<Eigen::Index>(problem.parameters.size());
  const int draws = 200;
  Eigen::MatrixXd estimates(draws, p);
  const auto designed = problem.runs;
  for (int draw = 0; draw < draws; ++draw) {
    problem.runs = designed;
    for (auto& r : problem.runs) {
      for (int k = 0; k < 3; ++k) r.setup.errors[static_cast<size_t>(SetupParameter::TargetX) + static_cast<size_t>(k)] = 0.05 * u(rng);
      simulateRun(model, nominal, r, {}, request.noise.at(r.instrument), &rng);
      r.setup.errors = {};
    }
    IdentificationOptions options;
    options.threads = 1;
    const auto result = identify(problem, options);
    ASSERT_TRUE(result.converged) << result.solverReport;
    estimates.row(draw) = result.values.head(p).transpose();
  }
  for (Eigen::Index k = 0; k < p; ++k) {
    const Eigen::VectorXd x = estimates.col(k);
    const double spread = std::sqrt((x.array() - x.mean()).square().sum() / (draws - 1));
    const double predicted = d.outlook.prediction.uncertainty[k];
    EXPECT_NEAR(spread / predicted, 1.0, 0.15) << problem.parameters[static_cast<size_t>(k)].name << ": spread " << spread << ", predicted " << predicted;
    RecordProperty("spread_over_predicted_" + problem.parameters[static_cast<size_t>(k)].name, std::to_string(spread / predicted));
  }
}

// X0B and X0C act alike on the inclined head (both shift the tool against the table along X),
// and the table's zero offset C.zero is taken up by where the sphere sits: no R-test run can
// separate them, so no plan is returned and the message says which and why.
TEST(MeasurementDesign, RefusesWhatNoInstrumentCanSeparate) {
  MeasurementDesignRequest request;
  request.parameters = {"X0B", "X0C", "C.zero", "A0B"};
  request.candidates.instruments = {Instrument::RTest};
  request.minutes = 60;
  request.planOut = testing::TempDir() + "/refused-plan.yaml";
  std::filesystem::remove(*request.planOut);
  try {
    designMeasurement(setupOf(kInclinedHead), request);
    FAIL() << "a design was returned";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("X0B and X0C act alike"), std::string::npos) << what;
    EXPECT_NE(what.find("C.zero has no effect"), std::string::npos) << what;
    EXPECT_EQ(what.find("A0B"), std::string::npos) << "A0B can be determined: " << what;
  }
  EXPECT_FALSE(std::filesystem::exists(*request.planOut));
}

// The plan written is read as any plan, and its runs predict what the design printed.
TEST(MeasurementDesign, WrittenPlanIsReadBackWithTheSamePrediction) {
  const auto setup = setupOf("tilting-table");
  MeasurementDesignRequest request;
  request.parameters = {"X0C", "Y0C", "A0C", "B0C", "X0B", "A0B"};
  request.criterion = DesignCriterion::I;
  request.minutes = 30;
  request.planOut = testing::TempDir() + "/designed-plan.yaml";
  const auto d = designMeasurement(setup, request);
  const auto plan = loadTestPlan(setup.nominal(), *request.planOut);
  ASSERT_EQ(plan.runs.size(), d.chosen.size());
  EXPECT_EQ(plan.parameters, (std::vector<std::string>{"X0C", "Y0C", "A0C", "B0C", "X0B", "A0B"}));
  std::vector<double> noise;
  for (size_t r = 0; r < plan.runs.size(); ++r) {
    EXPECT_EQ(plan.runs[r].name, d.chosen[r].name);
    EXPECT_LT((plan.runs[r].q - d.chosen[r].run.q).cwiseAbs().maxCoeff(), 1e-9) << plan.runs[r].name;
    ASSERT_TRUE(plan.runs[r].noise);
    noise.push_back(*plan.runs[r].noise);
  }
  const auto again = predictUncertainty({setup.machine, setup.errors, d.parameters, plan.runs}, noise, 1);
  EXPECT_LT((again.uncertainty - d.outlook.prediction.uncertainty).cwiseAbs().maxCoeff(), 1e-6 * d.outlook.prediction.uncertainty.maxCoeff());
  EXPECT_NEAR(planMinutes(*setup.machine, plan.runs, request.time), d.outlook.minutes, 1e-9);
  EXPECT_LE(d.outlook.minutes, 30.0 * (1 + 1e-9));
  // The I criterion's TCP figure is the one the design minimised: its RMS over the volume.
  EXPECT_NEAR(d.pareto[3].tcpRms, d.outlook.tcpRms, 1e-6 * d.outlook.tcpRms);
}

// Each candidate run's plan entry, read as a plan, is that run: on every bundled 5-axis machine,
// and on a tilting table whose B axis cannot reach zero, where the runs start at B's mid-travel
// and the ballbar circles' entries say so (at B = 0 no circle would be within the travel).
TEST(DesignCandidates, PlanEntriesRegenerateTheRuns) {
  auto offZero = std::make_shared<Machine>(*test::bundled("tilting-table"));
  offZero->name = "tilting table, B from 10 deg";
  offZero->axes[static_cast<size_t>(offZero->commandedAxisIndex("B"))].travel->min = 10 * kDeg;
  std::vector<std::shared_ptr<const Machine>> machines{offZero};
  for (const char* name : {"tilting-table", "double-pivot-head", "swivel-head-table", "inclined-a-table", "maho", "multitasking-b-c"})
    machines.push_back(test::bundled(name));
  for (const auto& machine : machines) {
    SCOPED_TRACE(machine->name);
    const auto nominal = compileNominal(machine);
    const auto set = designCandidates(nominal, {});
    std::string plan = "name: candidates\nruns:\n";
    size_t circles = 0;
    for (const auto& c : set.candidates) {
      plan += c.planEntry;
      circles += c.name.starts_with("circle-");
      EXPECT_EQ(travelViolation(*machine, c.run), "") << c.name;
    }
    if (machine == offZero) {
      EXPECT_EQ(circles, 3 * CandidateOptions{}.ballbarLengths.size());  // XY, YZ, ZX at each bar length
    }
    const auto read = parseTestPlan(nominal, plan, "plan.yaml");
    ASSERT_EQ(read.runs.size(), set.candidates.size());
    for (size_t k = 0; k < read.runs.size(); ++k) {
      const auto& run = set.candidates[k].run;
      EXPECT_EQ(read.runs[k].name, run.name);
      ASSERT_EQ(read.runs[k].q.rows(), run.q.rows()) << run.name;
      EXPECT_LT((read.runs[k].q - run.q).cwiseAbs().maxCoeff(), 1e-9) << run.name;
    }
  }
}

// Closed forms: a rest-to-rest move with a trapezoidal profile (t = d/v + v/a when the axis
// reaches its rapid, 2 sqrt(d/a) when it does not), the dwell per R-test position, a contouring
// run at its feed; and the set-ups a plan shares.
TEST(MachineTime, RunsAndPlansInClosedForm) {
  const auto machine = test::bundled("tilting-table");
  const int x = machine->axisIndex("X");
  MachineTimeModel t;
  MeasurementRun run;
  run.instrument = Instrument::RTest;
  run.q = JointMatrix::Zero(3, machine->commandedCount());
  run.q(1, x) = 100.0;  // 100 mm: v^2/a = 27.8 mm, the rapid is reached
  run.q(2, x) = 110.0;  // 10 mm: it is not
  const double v = t.linearRapid / 60.0, a = t.linearAcceleration;
  const double seconds = (100.0 / v + v / a) + 2 * std::sqrt(10.0 / a) + 3 * t.rtestDwell;
  EXPECT_NEAR(runMinutes(*machine, run, t), seconds / 60.0, 1e-12);
  run.instrument = Instrument::Ballbar;
  run.feed = 500.0;
  EXPECT_NEAR(runMinutes(*machine, run, t), 110.0 / 500.0, 1e-12);
  // Two R-test runs on one sphere share its set-up; a ballbar run has its own.
  MeasurementRun other = run;
  other.instrument = Instrument::RTest;
  MeasurementRun same = other;
  same.name = "another sweep";
  const double each = runMinutes(*machine, other, t);
  EXPECT_NEAR(planMinutes(*machine, {other, same}, t), 2 * each + t.setupMinutes + t.instrumentMinutes, 1e-12);
  EXPECT_NEAR(planMinutes(*machine, {other, same, run}, t), 2 * each + runMinutes(*machine, run, t) + 2 * t.setupMinutes + 2 * t.instrumentMinutes, 1e-12);
}

}  // namespace
}  // namespace mtacc
