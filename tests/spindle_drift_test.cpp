// The spindle's thermal drift in the errors (issue 19): the model `mtacc drift --save-model`
// writes and reads back, the rigid motion it gives the spindle in the kinematics, the
// compensation tables written at two spindle temperatures, and the thermal state's errors.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/errors/thermal_state.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/io/spindle_drift_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/io/thermal_state_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "mtacc/workflows/thermal_drift.hpp"
#include "test_helpers.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

const std::string kThermalData = test::testDataDir() + "/../../data/thermal/";

// Every direction on two sensors, "head" and "column", both 20 degC at the reference.
SpindleDriftModel handModel() {
  SpindleDriftModel m;
  m.sensors = {"head", "column"};
  const double offsets[5] = {1e-4, -2e-4, 3e-4, 2e-6, -1e-6};
  const double head[5] = {0.5e-3, 1.5e-3, -1.2e-3, -4e-6, 2e-6}, column[5] = {0.2e-3, 2.5e-3, -0.8e-3, 1e-6, -1e-6};
  for (int d = 0; d < 5; ++d) {
    DriftModel model;
    model.sensors = {0, 1};
    model.referenceTemperatures = Eigen::Vector2d(20.0, 20.0);
    model.offset = offsets[d];
    model.coefficients = Eigen::Vector2d(head[d], column[d]);
    model.covariance = Eigen::Matrix3d::Identity() * 1e-12;
    model.residualSigma = 3e-4;
    m.directions[d] = model;
  }
  return m;
}

SpindleState warmSpindle(double head, double column, double probeAboveTcp = 100.0) {
  return {handModel(), Eigen::Vector2d(head, column), probeAboveTcp};
}

// The drift the hand model predicts, written out: offset + coefficients x the rises.
Vec6 handDrift(double head, double column) {
  const auto m = handModel();
  Vec6 out = Vec6::Zero();
  for (int d = 0; d < 5; ++d)
    out[d] = m.directions[d]->offset + m.directions[d]->coefficients[0] * (head - 20) + m.directions[d]->coefficients[1] * (column - 20);
  return out;
}

TEST(SpindleDrift, ThePredictionIsTheModelsSumOverItsSensors) {
  const Vec6 drift = spindleDrift(handModel(), Eigen::Vector2d(31.5, 24.0));
  EXPECT_LT((drift - handDrift(31.5, 24.0)).cwiseAbs().maxCoeff(), 1e-17);  // to rounding
  EXPECT_TRUE(test::thrown<InvalidInput>([] { spindleDrift(handModel(), Eigen::VectorXd::Constant(3, 20.0)); }));
}

// The spindle's location error moves probe set 1 by the predicted (X, Y, Z) and turns the tool
// by (A, B): the TCP, h below it, ends at drift + (R - I)(-h d), exact, for a machine whose
// spindle's location point and TCP are both off the spindle frame's origin.
TEST(SpindleDrift, TheWarmSpindleMovesTheToolByTheModelsRigidMotion) {
  Machine shifted = loadMachine("three-axis-vertical");
  const int spindle = shifted.axisIndex("C");
  ASSERT_EQ(shifted.axes[static_cast<size_t>(spindle)].type, AxisType::Spindle);
  shifted.axes[static_cast<size_t>(spindle)].location = Vec3(1.0, 2.0, 40.0);
  shifted.toolOffset = Vec3(5.0, -3.0, -150.0);
  const auto machine = std::make_shared<const Machine>(shifted);
  const auto cold = loadMachineErrors(*machine);
  for (const double h : {0.0, 100.0, 250.0}) {
    const auto warm = atThermalState(*machine, cold, {{}, warmSpindle(31.5, 24.0, h)});
    const Vec6 drift = handDrift(31.5, 24.0);
    const Vec3 expected = drift.head<3>() + (rotationXYZ(drift[kA], drift[kB], 0.0) - Mat3::Identity()) * (-h * machine->toolDirection);
    const auto coldModel = compile(machine, cold), warmModel = compile(machine, warm);
    for (const auto& q : {std::vector<double>{0, 0, 0}, std::vector<double>{300, 200, 250}, std::vector<double>{600, 400, 500}}) {
      const Vec3 moved = toolPoint(warmModel, q.data()).position - toolPoint(coldModel, q.data()).position;
      // The table's angular errors (up to 15 urad here) turn the drift (under 35 um) by their product: below 0.6 nm.
      EXPECT_LT((moved - expected).norm(), 6e-7) << "h " << h << " moved " << moved.transpose() << " expected " << expected.transpose();
    }
    EXPECT_LT((spindleDriftAtTcp(*machine, warmSpindle(31.5, 24.0, h)) - expected).norm(), 1e-15);
  }
  const auto zero = ErrorModel::zero(*machine);
  const auto warm = compile(machine, atThermalState(*machine, zero, {{}, warmSpindle(31.5, 24.0, 100.0)}));
  const double q[3] = {300, 200, 250};
  const Vec3 moved = toolPoint(warm, q).position - toolPoint(compile(machine, zero), q).position;
  EXPECT_LT((moved - spindleDriftAtTcp(*machine, warmSpindle(31.5, 24.0, 100.0))).norm(), 1e-12) << "exact on a machine without other errors";
  const auto maho = test::bundled("maho");
  EXPECT_TRUE(test::thrown<InvalidInput>([&] { atThermalState(*maho, ErrorModel::zero(*maho), {{}, warmSpindle(30, 22)}); }));
}

// The tables written at two spindle temperatures differ by the change of the TCP's drift the
// model predicts (the same at every node of a 3-axis machine), to the product of the drift with
// the machine's own angular errors (below 1 nm, as above); each applied at its own state leaves what the
// cold table leaves cold, the cooler state's table on the warmer machine the drift's change.
TEST(SpindleDrift, TablesWrittenAtTwoSpindleTemperaturesDifferByThePrediction) {
  const auto setup = loadMachineSetup({"three-axis-vertical", "", "", std::nullopt, ""});
  const auto cooler = warmSpindle(25.0, 21.0), warmer = warmSpindle(33.0, 25.0);
  const auto coolErrors = atThermalState(*setup.machine, setup.errors, {{}, cooler});
  const auto warmErrors = atThermalState(*setup.machine, setup.errors, {{}, warmer});
  const CorrectionGridSpec spec{{7, 5, 5}, {}};
  const auto coolGrid = correctionGrid(setup.machine, coolErrors, spec), warmGrid = correctionGrid(setup.machine, warmErrors, spec);
  const Vec3 change = spindleDriftAtTcp(*setup.machine, warmer) - spindleDriftAtTcp(*setup.machine, cooler);
  ASSERT_GT(change.norm(), 10e-3) << "a change of tens of micrometres, as seed 003's spindle drifts";
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 7; ++i)
        EXPECT_LT((warmGrid.at(i, j, k) - coolGrid.at(i, j, k) + change).norm(), 1e-6) << i << " " << j << " " << k;
  const auto applied = [](const CorrectionGrid& g) { return [&g](const Vec3& p) { return g.interpolate(p); }; };
  const auto coldGrid = correctionGrid(setup.machine, setup.errors, spec);
  const auto coldOnCold = tableResidual(setup.machine, setup.errors, coldGrid, applied(coldGrid));
  const auto warmOnWarm = tableResidual(setup.machine, warmErrors, warmGrid, applied(warmGrid));
  const auto coolOnWarm = tableResidual(setup.machine, warmErrors, coolGrid, applied(coolGrid));
  EXPECT_LT(warmOnWarm.afterMax, coldOnCold.afterMax + 1e-4);
  EXPECT_GT(coolOnWarm.afterMax, 0.9 * change.norm());
  RecordProperty("residual_um_cold_warm_cool_on_warm", fmt::format("{:.3f} / {:.3f} / {:.3f} (drift change {:.3f})", coldOnCold.afterMax * 1e3,
                                                                   warmOnWarm.afterMax * 1e3, coolOnWarm.afterMax * 1e3, change.norm() * 1e3));
}

TEST(SpindleDriftModelFile, ReadsBackWhatWasWritten) {
  auto model = handModel();
  model.directions[static_cast<int>(DriftDirection::Z)].reset();
  model.directions[static_cast<int>(DriftDirection::A)]->sensors = {1};
  model.directions[static_cast<int>(DriftDirection::A)]->coefficients = Eigen::VectorXd::Constant(1, 3e-6);
  model.directions[static_cast<int>(DriftDirection::A)]->referenceTemperatures = Eigen::VectorXd::Constant(1, 19.5);
  model.directions[static_cast<int>(DriftDirection::A)]->covariance = Eigen::Matrix2d::Identity() * 4e-14;
  const auto read = parseSpindleDriftModel(spindleDriftModelYaml(model, "a hand model"), "m.yaml");
  EXPECT_EQ(read.sensors, model.sensors);
  EXPECT_FALSE(read.directions[static_cast<int>(DriftDirection::Z)]);
  for (const Eigen::Vector2d& t : {Eigen::Vector2d(20, 20), Eigen::Vector2d(35, 18)}) {
    // Written to nine significant digits.
    EXPECT_LT((spindleDrift(read, t) - spindleDrift(model, t)).cwiseAbs().maxCoeff(), 1e-11);
    EXPECT_LT((spindleDriftUncertainty(read, t) - spindleDriftUncertainty(model, t)).cwiseAbs().maxCoeff(), 1e-11);
  }
  EXPECT_EQ(read.directions[static_cast<int>(DriftDirection::A)]->sensors, std::vector<int>{1});
}

TEST(SpindleDriftModelFile, TheBundledModelIsWhatMtaccDriftWritesFromTheBundledTest) {
  const std::string bundled = kThermalData + "maho-spindle-drift-model.yaml";
  const std::string written = (std::filesystem::temp_directory_path() / "mtacc-spindle-drift-model.yaml").string();
  const auto evaluation = evaluateDriftTest({kThermalData + "maho-spindle-drift.csv", "", {}, "", written});
  if (std::getenv("MTACC_REGENERATE_DATA")) writeFileAtomically(bundled, readTextFile(written));
  EXPECT_EQ(readTextFile(bundled), readTextFile(written)) << "regenerate with MTACC_REGENERATE_DATA=1 ./build/tests/mtacc_tests --gtest_filter=SpindleDrift*";
  const auto model = loadSpindleDriftModel(bundled);
  EXPECT_EQ(model.sensors, (std::vector<std::string>{"head", "column", "bed"}));
  // At the test's own temperatures the model gives the prediction mtacc drift reports.
  const auto& test = evaluation.test;
  for (const auto& direction : evaluation.directions) {
    const auto& fitted = direction.model->model;
    const auto& read = *model.directions[static_cast<int>(direction.direction)];
    for (const long sample : {0L, 700L, 1679L}) {
      Eigen::VectorXd t(3);
      for (int s = 0; s < 3; ++s)
        t[s] = test.temperatures(sample, std::find(test.sensors.begin(), test.sensors.end(), model.sensors[static_cast<size_t>(s)]) - test.sensors.begin());
      const double expected = fitted.predict(test.temperatures.row(sample).transpose());
      EXPECT_NEAR(read.predict(t), expected, 1e-8 * std::max(1.0, std::fabs(expected) * 1e3)) << nameOf(direction.direction) << " " << sample;
    }
  }
  std::filesystem::remove(written);
  const auto axisTest = test::thrown<InputError>([&] { evaluateDriftTest({kThermalData + "z-axis-drift.csv", "", {}, "", written}); });
  ASSERT_TRUE(axisTest);
  EXPECT_EQ(axisTest->where().key, "save-model");
  EXPECT_FALSE(std::filesystem::exists(written)) << "no file from a refused model";
}

TEST(SpindleDriftModelFile, NamesTheLineAndKeyOfABadValue) {
  const auto message = [](const std::string& text) {
    const auto e = test::thrown<InputError>([&] { parseSpindleDriftModel(text, "m.yaml"); });
    return e ? std::to_string(e->where().line) + " " + e->where().key + ": " + e->reason() : std::string();
  };
  const std::string good = "    offset: 1 um\n    sensors: [{name: head, reference: 20, per_kelvin: 1 um}]\n    residual_sigma: 0.3 um\n";
  EXPECT_EQ(parseSpindleDriftModel("directions:\n  X:\n" + good + "    covariance: [[1, 0], [0, 1]]\n", "m.yaml").directions[0]->residualSigma, 0.3e-3);
  EXPECT_EQ(message("directions:\n  W:\n" + good), "2 directions.W: not a drift direction (X, Y, Z, A or B)");
  EXPECT_EQ(message("directions:\n  X:\n" + good + "    covariance: [[1, 0], [0]]\n"), "6 directions.X.covariance: expected a row of 2 numbers");
  EXPECT_EQ(message("directions:\n  X:\n" + good + "    covariance: [[1, 5], [0, 1]]\n"),
            "6 directions.X.covariance: expected a symmetric matrix with a non-negative diagonal, within the values' range squared");
  EXPECT_EQ(message("directions:\n  A:\n    offset: 1 um\n"), "3 directions.A.offset: expected an angle but '1 um' is a length");
  EXPECT_EQ(message("directions:\n  X:\n    offset: 20 mm\n"), "3 directions.X.offset: a value within +-10000 um");
  EXPECT_EQ(message("directions:\n  X:\n    offset: 1 um\n    sensors: [{name: h, reference: 20, per_kelvin: 1 um}, {name: h, reference: 20, per_kelvin: 1 um}]\n"),
            "4 directions.X.sensors.name: sensor 'h' given twice");
  EXPECT_EQ(message("directions: {}\n"), "1 directions: expected {X|Y|Z|A|B: {offset, sensors, residual_sigma, covariance}}");
}

TEST(ThermalStateFile, ReadsTheSpindleWithItsModelAndNamesWhatIsMissing) {
  const auto machine = test::bundled("three-axis-vertical");
  const std::string source = kThermalData + "state.yaml";  // the model's path is relative to the state's folder
  const auto state = parseThermalState(*machine,
                                       "spindle:\n  model: maho-spindle-drift-model.yaml\n  temperatures: {bed: 21, head: 31.5, column: 24, room: 20}\n"
                                       "  probe_above_tcp: 0.1 m\n",
                                       source);
  ASSERT_TRUE(state.spindle);
  EXPECT_TRUE(state.scales.empty());
  EXPECT_EQ(state.spindle->probeAboveTcp, 100.0);
  EXPECT_EQ(state.spindle->temperatures, Eigen::Vector3d(31.5, 24, 21)) << "in the model's order, a channel it does not use ignored";
  const auto message = [&](const Machine& m, const std::string& text) {
    const auto e = test::thrown<InputError>([&] { parseThermalState(m, text, source); });
    return e ? std::to_string(e->where().line) + " " + e->where().key + ": " + e->reason() : std::string();
  };
  EXPECT_EQ(message(*machine, "spindle:\n  model: maho-spindle-drift-model.yaml\n  temperatures: {head: 31.5, column: 24}\n  probe_above_tcp: 100 mm\n"),
            "3 spindle.temperatures.bed: missing: the model needs head, column, bed");
  EXPECT_EQ(message(*machine, "spindle:\n  model: maho-spindle-drift-model.yaml\n  temperatures: {head: 31.5, column: 24, bed: 21}\n"),
            "2 spindle.probe_above_tcp: missing: the model tilts the spindle, so say where its X and Y drift was read: probe set 1's distance "
            "from the TCP towards the spindle, e.g. 100 mm");
  EXPECT_EQ(message(*machine, "spindle:\n  model: nowhere.yaml\n  temperatures: {}\n"),
            fmt::format("2 spindle.model: {}nowhere.yaml: no such file", kThermalData));
  EXPECT_EQ(message(*test::bundled("maho"), "spindle:\n  model: maho-spindle-drift-model.yaml\n"),
            "2 spindle: the machine has no spindle for the drift to move: name it in the structure code, e.g. t-(C)-Z-b-Y-X-w");
  EXPECT_EQ(message(*machine, "description: nothing\n"),
            "1 : expected a mapping with scales: {AXIS: {sensors, temperatures, reference}} and/or spindle: {model, temperatures}");
}

}  // namespace
}  // namespace mtacc
