// ISO 10791-6 tests around the rotary axes: on every bundled 5-axis machine the runs, their plan
// entries and their programs read zero on the nominal machine (1e-6 um) and the first-order
// prediction with location errors; on the tilting table each rotary-axis location error alone
// shows in the tests whose set-up is designed to see it and in no other (docs/conventions.md
// "ISO 10791-6 tests": the table worked out from the set-ups' geometry).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/io/plan_yaml.hpp"
#include "mtacc/measurement/rotary_axis_tests.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

const char* const kFiveAxisMachines[] = {"tilting-table", "double-pivot-head", "swivel-head-table", "inclined-a-table", "maho",
                                         "multitasking-b-c"};

TEST(RotaryAxisTests, EveryBundledMachineReadsZeroWithoutErrors) {
  for (const char* name : kFiveAxisMachines) {
    SCOPED_TRACE(name);
    const auto machine = test::bundled(name);
    const auto nominal = compileNominal(machine);
    auto set = rotaryAxisTests(nominal, {});
    EXPECT_GE(set.tests.size(), 2u * static_cast<size_t>(machine->rotaryCount()));
    for (auto& t : set.tests) {
      simulateRun(nominal, nominal, t.run);
      EXPECT_LT(t.run.readings.cwiseAbs().maxCoeff(), 1e-9) << t.name;  // 1e-6 um
      EXPECT_EQ(travelViolation(*machine, t.run), "") << t.name;
      for (const double r : evaluateRotaryTest(nominal, t.run).ranges) EXPECT_LT(r, 1e-9) << t.name;
    }
  }
}

TEST(RotaryAxisTests, PlanEntriesRegenerateTheRuns) {
  for (const char* name : kFiveAxisMachines) {
    SCOPED_TRACE(name);
    const auto machine = test::bundled(name);
    const auto nominal = compileNominal(machine);
    const auto set = rotaryAxisTests(nominal, {});
    std::string plan = "name: ISO 10791-6\nruns:\n";
    for (const auto& t : set.tests) plan += t.planEntry;
    const auto read = parseTestPlan(nominal, plan, "plan.yaml");
    ASSERT_EQ(read.runs.size(), set.tests.size());
    for (size_t k = 0; k < read.runs.size(); ++k) {
      EXPECT_EQ(read.runs[k].name, set.tests[k].name);
      ASSERT_EQ(read.runs[k].q.rows(), set.tests[k].run.q.rows()) << set.tests[k].name;
      EXPECT_LT((read.runs[k].q - set.tests[k].run.q).cwiseAbs().maxCoeff(), 1e-9) << set.tests[k].name;
      EXPECT_LT((read.runs[k].setup.toolBall - set.tests[k].run.setup.toolBall).norm(), 1e-9) << set.tests[k].name;
    }
  }
}

// The tilting table's location errors as its machine file states them.
ErrorModel locationErrorsOnly(const Machine& machine) {
  const ErrorModel all = loadMachineErrors(machine);
  ErrorModel out = ErrorModel::zero(machine);
  for (const auto& p : parameterCatalogue(machine, out))
    if (p.kind == ParameterKind::Location) setParameterValue(out, p, parameterValue(all, p));
  return out;
}

// A bound of the second-order terms: (sum of the angles)^2 times the reach, plus twice the sum of
// the angles times the sum of the offsets.
double secondOrderBound(const Machine& machine, const ErrorModel& errors, double reach) {
  double angles = 0, offsets = 0;
  for (const auto& p : nonZeroParameters(machine, errors))
    (p.dimension == Dimension::Angle ? angles : offsets) += std::abs(parameterValue(errors, p));
  return angles * angles * reach + 2 * angles * offsets;
}

TEST(RotaryAxisTests, ProgramsRunToZeroWithoutErrorsAndToTheFirstOrderWithThem) {
  // Each program read back by mtacc's G-code reader; its positions run as the test's instrument
  // reads them: without errors the readings are the positions' rounding alone (below 1e-6 um with
  // 10 decimals; a controller's 6 decimals keep them below 3e-3 um), with the location errors the
  // change they make is the first-order prediction.
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const ErrorModel errors = locationErrorsOnly(*machine);
  const auto params = nonZeroParameters(*machine, errors);
  ASSERT_EQ(params.size(), 12u);
  const double bound = secondOrderBound(*machine, errors, 300.0);  // the tool within 300 mm of the pivot
  EXPECT_LT(bound, 2e-5);  // 0.02 um against deviations of 10 um
  const auto model = compile(machine, errors);
  for (const auto& t : rotaryAxisTests(nominal, {}).tests) {
    for (const auto& [decimals, rounding] : {std::pair{10, 1e-9}, std::pair{6, 3e-6}}) {
      SCOPED_TRACE(t.name + ", " + std::to_string(decimals) + " decimals");
      const auto program = parseGcodeProgram(rotaryTestProgram(*machine, t, decimals), t.name + ".nc", *machine);
      ASSERT_EQ(static_cast<Eigen::Index>(program.moves.size()), t.run.poses() + 1);  // the approach, then one move per pose
      MeasurementRun fromProgram = t.run;
      for (Eigen::Index i = 0; i < t.run.poses(); ++i)
        for (Eigen::Index j = 0; j < t.run.q.cols(); ++j) {
          fromProgram.q(i, j) = program.moves[static_cast<size_t>(i + 1)].to[static_cast<size_t>(j)];
          EXPECT_NEAR(fromProgram.q(i, j), t.run.q(i, j), 0.5 * std::pow(10.0, -decimals) * machine->axes[static_cast<size_t>(j)].fileUnit() + 1e-12);
        }
      MeasurementRun nominalReadings = fromProgram, withErrors = fromProgram;
      simulateRun(nominal, nominal, nominalReadings);
      EXPECT_LT(nominalReadings.readings.cwiseAbs().maxCoeff(), rounding);
      simulateRun(model, nominal, withErrors);
      Eigen::MatrixXd predicted = Eigen::MatrixXd::Zero(withErrors.readings.rows(), withErrors.readings.cols());
      for (const auto& param : params) {  // each error at a thousandth of its value, times 1000
        MeasurementRun one = fromProgram;
        simulateRun(compile(machine, singleError(*machine, errors, param, 1e-3 * parameterValue(errors, param))), nominal, one);
        predicted += 1e3 * (one.readings - nominalReadings.readings);
      }
      EXPECT_LT((withErrors.readings - nominalReadings.readings - predicted).cwiseAbs().maxCoeff(), bound);
      EXPECT_GT(withErrors.readings.cwiseAbs().maxCoeff(), 1e-3);  // the errors show: over 1 um
    }
  }
}

// Which results a location error alone moves (1e-3 um per um or urad and more): (test, quantity).
std::set<std::string> seenBy(const RotaryTestSensitivity& s, const std::vector<RotaryAxisTest>& tests, const std::string& parameter) {
  const auto k = std::find_if(s.parameters.begin(), s.parameters.end(), [&](const Parameter& p) { return p.name == parameter; });
  EXPECT_NE(k, s.parameters.end()) << parameter;
  std::set<std::string> out;
  static const char* const rtest[] = {"radial", "tangential", "axial"};
  for (size_t t = 0; t < tests.size(); ++t)
    for (size_t q = 0; q < s.perTest[t].size(); ++q)
      if (s.perTest[t][q][static_cast<size_t>(k - s.parameters.begin())] > 1e-3)
        out.insert(tests[t].name + (tests[t].kind == RotaryTestKind::RTest ? std::string(" ") + rtest[q] : ""));
  return out;
}

TEST(RotaryAxisTests, EachLocationErrorShowsInTheTestsDesignedToSeeIt) {
  // The tilting table (B tilts the table about Y, C turns on it): R-test 1 with the sphere at
  // 100 mm from the line, R-test 2 100 mm further along it; the ballbar's work ball where R-test 1's
  // sphere is (radial: the tool ball on the line; tangential, axial: 100 mm off).
  //  - An axis line's offset across it turns the sphere about another centre: the radial and
  //    tangential deviations of both R-tests, the ballbar radial and tangential; nothing axial.
  //  - An axis line's tilt moves the sphere along the axis by r times the tilt (axial, both R-tests,
  //    the ballbar axial) and across it by the height along the line times the tilt (R-test 2 only).
  //  - An offset along an axis's own line, and a zero offset of the axis that turns, move the sphere
  //    by a constant that the set-up takes up: nothing.
  //  - B's errors move what B carries, C's line and the table, as a whole: with B still (the C
  //    tests), B's tilts about X and its zero offset tilt C's line (as C's tilts do), its offsets
  //    along X and Y shift C's line (as C's offsets do), its offset along Z (C's own line) and its
  //    tilt about Z (C's own turn) are taken up by the set-up. C's errors do nothing while C is
  //    still (the B tests).
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const auto tests = rotaryAxisTests(nominal, {}).tests;
  const auto s = rotaryTestSensitivities(nominal, tests);
  const std::set<std::string> offsetC{"C-rtest-1 radial", "C-rtest-1 tangential", "C-rtest-2 radial", "C-rtest-2 tangential",
                                      "C-ballbar-radial", "C-ballbar-tangential"};
  const std::set<std::string> tiltC{"C-rtest-1 axial", "C-rtest-2 radial", "C-rtest-2 tangential", "C-rtest-2 axial", "C-ballbar-axial"};
  const std::set<std::string> offsetB{"B-rtest-1 radial", "B-rtest-1 tangential", "B-rtest-2 radial", "B-rtest-2 tangential",
                                      "B-ballbar-radial", "B-ballbar-tangential"};
  const std::set<std::string> tiltB{"B-rtest-1 axial", "B-rtest-2 radial", "B-rtest-2 tangential", "B-rtest-2 axial", "B-ballbar-axial"};
  const auto both = [](std::set<std::string> a, const std::set<std::string>& b) {
    a.insert(b.begin(), b.end());
    return a;
  };
  const std::map<std::string, std::set<std::string>> expected{
      {"X0C", offsetC}, {"Y0C", offsetC}, {"A0C", tiltC}, {"B0C", tiltC}, {"Z0C", {}}, {"C0C", {}},
      {"X0B", both(offsetB, offsetC)}, {"Z0B", offsetB}, {"C0B", tiltB}, {"A0B", both(tiltB, tiltC)}, {"B0B", tiltC}, {"Y0B", offsetC}};
  for (const auto& [parameter, tests_] : expected) EXPECT_EQ(seenBy(s, tests, parameter), tests_) << parameter;
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

TEST(PlanYaml, SphereRunsTakeTheirAnglesOneByOne) {
  // A designed plan's R-test: the positions listed, as the sphere generator steps through them.
  const auto nominal = compileNominal(test::bundled("tilting-table"));
  const auto plan = parseTestPlan(nominal, R"(runs:
  - sphere: {axis: C, angles: [0 deg, 35 deg, 90 deg, 271.5 deg], spheres: [[100 mm, 0 mm, 0 mm]], pose: {B: -30 deg}}
)",
                                  "plan.yaml");
  ASSERT_EQ(plan.runs.size(), 1u);
  const auto& q = plan.runs[0].q;
  ASSERT_EQ(q.rows(), 4);
  const int c = nominal.machine->commandedAxisIndex("C");
  EXPECT_NEAR(q(1, c), 35 * kDeg, 1e-15);
  EXPECT_NEAR(q(3, c), 271.5 * kDeg, 1e-15);
  EXPECT_THROW(parseTestPlan(nominal, "runs:\n  - sphere: {axis: C, angles: [0 deg], from: 0 deg, spheres: [[100 mm, 0 mm, 0 mm]]}\n", "p.yaml"),
               InputError);
  EXPECT_THROW(parseTestPlan(nominal, "runs:\n  - sphere: {axis: C, angles: [], spheres: [[100 mm, 0 mm, 0 mm]]}\n", "p.yaml"), InputError);
}

}  // namespace
}  // namespace mtacc
