// The thermal drift tests (ISO 230-3, seed 003 §2.6): the mandrel's tilts from two probe heights,
// the file's reading and its located errors, and `mtacc drift`'s workflow on the bundled tests
// that the virtual thermal machine recorded (data/thermal: the spindle's, the environmental
// variation's, a Z axis's).
#include <gtest/gtest.h>

#include <cstdlib>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/drift_test_csv.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/thermal_drift.hpp"
#include "test_helpers.hpp"
#include "thermal_machines.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

const std::string kThermalData = test::testDataDir() + "/../../data/thermal/";
const std::string kBundled = kThermalData + "maho-spindle-drift.csv";
const std::string kEnvironment = kThermalData + "maho-environmental-variation.csv";
const std::string kZAxis = kThermalData + "z-axis-drift.csv";
constexpr const char* kNote = "seed 003's drift test (5000 rpm 6 h, 8 h at rest) by the virtual thermal machine of tests/thermal_machines.hpp";

TEST(DriftTest, TiltsOfARigidMandrelFromTwoHeights) {
  // The mandrel turns by B = 20 urad about Y and A = -15 urad about X through (0, 0, 300 mm) and
  // moves by (3, -2, 5) um: a point at height z moves by (3 + B (z - 300), -2 - A (z - 300)) um.
  const double b = 20e-6, a = -15e-6;
  const auto at = [&](double z, double base, double tilt) { return Eigen::Vector2d(0.0, base * 1e-3 + tilt * (z - 300)); };
  MandrelProbes p;
  p.z1 = 50;
  p.z2 = 150;
  p.x1 = at(50, 3, b);
  p.x2 = at(150, 3, b);
  p.y1 = at(50, -2, -a);
  p.y2 = at(150, -2, -a);
  p.x1[0] = p.x2[0] = p.y1[0] = p.y2[0] = 0.0;
  const auto d = mandrelDrift(p);
  EXPECT_NEAR((*d[DriftDirection::B])[1], b, 1e-15);
  EXPECT_NEAR((*d[DriftDirection::A])[1], a, 1e-15);
  EXPECT_NEAR((*d[DriftDirection::X])[1], 3e-3 + b * -250, 1e-15);
  EXPECT_FALSE(d[DriftDirection::Z]);
  p.z2 = 50;
  EXPECT_TRUE(test::thrown<InvalidInput>([&] { mandrelDrift(p); }));
}

TEST(DriftTest, TheBundledTestsAreWhatTheVirtualMachineRecords) {
  const std::pair<std::string, std::string> files[] = {
      {kBundled, driftTestCsv(test::mahoDriftTest(), kNote)},
      {kEnvironment, driftTestCsv(test::mahoEnvironmentTest(), "ISO 230-3 environmental temperature variation test: spindle at rest, "
                                                               "the room swinging 1.5 K over the day; virtual thermal machine of "
                                                               "tests/thermal_machines.hpp")},
      {kZAxis, driftTestCsv(test::zAxisDriftTest(), "Z axis thermal drift: Z traversing 6 h, then 8 h at rest, read at Z = 0, -200, "
                                                    "-400 mm in turn; virtual thermal machine of tests/thermal_machines.hpp")}};
  for (const auto& [file, text] : files) {
    if (std::getenv("MTACC_REGENERATE_DATA")) writeFileAtomically(file, text);
    EXPECT_EQ(readTextFile(file), text) << file << ": regenerate with MTACC_REGENERATE_DATA=1 ./build/tests/mtacc_tests --gtest_filter=DriftTest.*";
  }
}

TEST(DriftTest, TheFileReadsBackWhatWasWritten) {
  const auto written = test::mahoDriftTest();
  const auto read = parseDriftTestCsv(driftTestCsv(written, kNote), "t.csv");
  EXPECT_EQ(read.sensors, written.sensors);
  EXPECT_EQ(read.sensorLocations, written.sensorLocations);
  EXPECT_EQ(read.probes.z2, 150.0);
  EXPECT_LT((read.probes.y1 - written.probes.y1).cwiseAbs().maxCoeff(), 0.5e-6);  // written to 1 nm
  EXPECT_LT((read.temperatures - written.temperatures).cwiseAbs().maxCoeff(), 0.5e-3);
  EXPECT_EQ(*read.spindleSpeed, *written.spindleSpeed);
  const auto axis = test::zAxisDriftTest();
  const auto readAxis = parseDriftTestCsv(driftTestCsv(axis, kNote), "t.csv");
  EXPECT_EQ(readAxis.axes, std::vector<std::string>{"Z"});
  EXPECT_EQ(readAxis.positions, axis.positions);
}

TEST(DriftTest, BadFilesNameTheirLineAndColumn) {
  const auto message = [](const std::string& text) {
    const auto e = test::thrown<InputError>([&] { parseDriftTestCsv(text, "t.csv"); });
    return e ? std::to_string(e->where().line) + " " + e->where().key + ": " + e->reason() : std::string();
  };
  const std::string head = "# probe_z: 50, 150 mm\ntime_s,x1_um,x2_um,head_C\n";
  EXPECT_EQ(message(head + "0,0,0,20\n30,1,1,21\n20,2,2,22\n"), "5 time_s: time does not increase (20 s after 30 s)");
  EXPECT_EQ(message(head + "0,0,0,20\n30,1,1,21\n30,2,2,22\n"), "5 time_s: time does not increase (30 s after 30 s)");  // a row twice
  EXPECT_EQ(message(head + "0,0,0,20\n30,1,1,210\n60,2,2,22\n"), "4 head_C: a temperature outside -50 .. 150 degC");
  EXPECT_EQ(message(head + "0,0,0,20\n30,1,nan,21\n60,2,2,22\n"), "4 x2_um: not a finite number: 'nan'");
  EXPECT_EQ(message(head + "0,0,0,20\n30,1,1,21\n"), "4 time_s: 2 samples, at least 3 needed");
  EXPECT_EQ(message(head + "0,0,0,20\n30,20000,1,21\n60,2,2,22\n"), "4 x1_um: a probe reading beyond +-10 mm (10000 um)");
  EXPECT_EQ(message("time_s,x1_um,x2_um\n0,0,0\n1,1,1\n2,2,2\n"), "1 probe_z: two probe sets need '# probe_z: z1, z2 mm' for the tilts");
  EXPECT_EQ(message("time_s,x1_um,head\n0,0,0\n1,1,1\n2,2,2\n"),
            "1 head: unknown column (expected time_s, x1_um, y1_um, x2_um, y2_um, z_um, spindle_rpm, axis positions such as Z_mm and "
            "temperatures NAME_C)");
  EXPECT_EQ(message("time_s,x1_um,x1_um\n0,0,0\n1,1,1\n2,2,2\n"), "1 x1_um: column given twice");
  EXPECT_EQ(message("time_s,x1_um,Z_mm\n0,0,0\n1,1,-1e6\n2,2,2\n"), "3 Z_mm: an axis position beyond +-100 m");
  EXPECT_EQ(message("# sensor: column, top\ntime_s,x1_um,head_C\n0,0,20\n1,1,21\n2,2,22\n"), "1 sensor: no column 'column_C' for sensor 'column'");
  EXPECT_EQ(message("# probe_z: 50, 50 mm\ntime_s,y1_um,y2_um\n0,0,0\n1,1,1\n2,2,2\n"), "1 probe_z: the two probe sets at one height: no tilt");
  EXPECT_EQ(message("# drift: 5000 rpm\ntime_s,y1_um\n0,0\n1,1\n2,2\n"), "1 drift: unknown key (expected probe_z, sensor, note)");
  EXPECT_EQ(message("time_s,head_C\n0,20\n1,21\n2,22\n"), "1 x1_um: no probe column (x1_um, y1_um, x2_um, y2_um, z_um)");
}

TEST(DriftTest, TheWorkflowFindsTheSeedsHysteresisAndTheSensorsThatPredictEachDirection) {
  const auto r = evaluateDriftTest({kBundled, "", {}, "", ""});
  ASSERT_EQ(r.directions.size(), 5u);
  EXPECT_EQ(r.test.sensors[static_cast<size_t>(r.hysteresisSensor)], "head");  // it changes most
  const auto sensorsOf = [&](DriftDirection d) {
    std::vector<std::string> names;
    for (const int s : r.directions[static_cast<size_t>(d)].model->model.sensors) names.push_back(r.test.sensors[static_cast<size_t>(s)]);
    std::sort(names.begin(), names.end());
    return names;
  };
  EXPECT_EQ(sensorsOf(DriftDirection::Y), (std::vector<std::string>{"column", "head"}));
  EXPECT_EQ(sensorsOf(DriftDirection::Z), (std::vector<std::string>{"bed", "column", "head"}));
  const auto& y = r.directions[static_cast<size_t>(DriftDirection::Y)];
  // The column lags the head: on cooling the Y drift is larger at the same head temperature,
  // as in the seed (40 against 52 um, L992-998), and no single sensor explains it.
  ASSERT_TRUE(y.hysteresis);
  EXPECT_GT(y.hysteresis->difference, 5e-3);
  EXPECT_GT(y.model->bestSingleSensorRms, 10 * y.model->crossValidatedRms);
  // B from the two X probes over 100 mm: (0.5 - 0.3) um/K of the head is 2 urad/K, (0.1 - 0.2) um/K of the column -1 urad/K.
  const auto& b = r.directions[static_cast<size_t>(DriftDirection::B)].model->model;
  ASSERT_EQ(sensorsOf(DriftDirection::B), (std::vector<std::string>{"column", "head"}));
  for (size_t s = 0; s < 2; ++s) {
    const double truth = r.test.sensors[static_cast<size_t>(b.sensors[s])] == "head" ? 2e-6 : -1e-6;
    EXPECT_LT(std::fabs(b.coefficients[static_cast<long>(s)] - truth), 3 * b.standardErrors()[static_cast<long>(s)]) << s;
  }
  const auto j = toJson(r);
  EXPECT_EQ(j["directions"][1]["direction"], "Y");
  EXPECT_EQ(j["directions"][4]["unit"], "urad");
}

TEST(DriftTest, TheRestingMachinesRangeIsItsEnvironmentalVariationError) {
  const auto r = evaluateDriftTest({kEnvironment, "", {}, "", ""});
  EXPECT_EQ(r.kind, DriftTestKind::EnvironmentalVariation);
  EXPECT_EQ(r.positionAxis, -1);
  EXPECT_EQ(r.test.sensors[static_cast<size_t>(r.hysteresisSensor)], "room");
  // The room's 3 K peak to peak moves the head and column by about 2 and 1.5 K (their lags
  // damp it), so Y ranges by several um; the model needs the lagging nodes, not the room alone.
  const auto& y = r.directions[1];
  EXPECT_GT(y.extremes.range, 3e-3);
  EXPECT_LT(y.model->crossValidatedRms, 1.2 * 0.3e-3);
  EXPECT_GT(y.model->bestSingleSensorRms, 2 * y.model->crossValidatedRms);
  EXPECT_EQ(toJson(r)["test"], "environmental temperature variation (ISO 230-3 ETVE), the machine at rest");
  EXPECT_EQ(evaluateDriftTest({kBundled, "", {}, "", ""}).kind, DriftTestKind::Spindle);
}

TEST(DriftTest, TheAxisDriftIsModelledAlongTheAxis) {
  const auto r = evaluateDriftTest({kZAxis, "", {}, "", ""});
  EXPECT_EQ(r.kind, DriftTestKind::AxisMotion);
  ASSERT_EQ(r.positionAxis, 0);
  const auto& z = r.directions[1];
  ASSERT_EQ(z.direction, DriftDirection::Z);
  const auto& m = z.model->model;
  ASSERT_TRUE(m.positionDependent);
  const auto head = std::find(m.sensors.begin(), m.sensors.end(), 1);
  ASSERT_NE(head, m.sensors.end());
  const long i = head - m.sensors.begin();
  EXPECT_LT(std::fabs(m.positionCoefficients[i] - 5e-6), 3 * m.positionStandardErrors()[i]);
  EXPECT_LT(std::fabs(m.coefficients[i] + 1.2e-3), 3 * m.standardErrors()[i]);
  EXPECT_LT(z.model->crossValidatedRms, 1.2 * 0.3e-3);
  const auto j = toJson(r, 100);
  EXPECT_EQ(j["position_axis"], "Z");
  EXPECT_EQ(j["series"]["position_mm"].size(), j["series"]["time_s"].size());
  EXPECT_TRUE(j["directions"][1]["model"]["sensors"][0].contains("coefficient_per_K_per_mm"));

  const auto unknown = test::thrown<InputError>([&] { evaluateDriftTest({kZAxis, "", {}, "X", ""}); });
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->where().key, "position");
  EXPECT_EQ(unknown->reason(), "'X': the file's axis positions are Z");
  const auto file = testing::TempDir() + "mtacc-two-axes-drift.csv";
  writeFileAtomically(file, "time_s,y1_um,X_mm,Z_mm,Y_mm\n0,0,0,0,5\n1,1,1,-1,5\n2,2,2,-2,5\n");
  const auto both = test::thrown<InputError>([&] { evaluateDriftTest({file, "", {}, "", ""}); });
  ASSERT_TRUE(both);
  EXPECT_EQ(both->reason(), "axes X, Z move in " + file + ": choose the one the drift depends on");
  const auto still = test::thrown<InputError>([&] { evaluateDriftTest({file, "", {}, "Y", ""}); });
  ASSERT_TRUE(still);
  EXPECT_EQ(still->what(), file + ":1: Y_mm: the axis does not move: no position dependence to fit");
}

TEST(DriftTest, AnUnknownHysteresisSensorAndTooShortARecordAreRefused) {
  const auto e = test::thrown<InputError>([&] { evaluateDriftTest({kBundled, "spindle", {}, "", ""}); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().key, "sensor");
  EXPECT_EQ(e->reason(), "'spindle': the file's temperatures are room, head, column, bed, motor");
  const auto file = testing::TempDir() + "mtacc-short-drift.csv";
  writeFileAtomically(file, "time_s,y1_um,a_C,b_C\n0,0,20,20\n1,1,21,20.5\n2,2,22,21\n3,2,22,21.5\n4,2,22,21.7\n5,2,22,21.8\n");
  const auto shortRecord = test::thrown<InputError>([&] { evaluateDriftTest({file, "", {}, "", ""}); });
  ASSERT_TRUE(shortRecord);
  EXPECT_EQ(shortRecord->what(), file + ":1: Y drift: 6 samples in 5 folds: at least 4 per fold needed for up to 2 sensors");
}

}  // namespace
}  // namespace mtacc
