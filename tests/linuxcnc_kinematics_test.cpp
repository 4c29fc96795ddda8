// LinuxCNC's 5-axis kinematics parameters (issue 17, item 3; issue 45, item 2): each module's
// inverse kinematics against LinuxCNC's own formulas, the nominal machines they reproduce, the
// errors their pins carry (leaving nothing) and the ones they cannot (named, leaving their own
// effect), the residual on a machine with its full error model, and the HAL file read back.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <random>
#include <regex>
#include <sstream>

#include "mtacc/compensation/linuxcnc_kinematics.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "test_helpers.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::shared_ptr<const Machine> example(const std::string& file) {
  return std::make_shared<const Machine>(loadMachine(test::testDataDir() + "/../../docs/examples/" + file));
}

// trtfuncs.c (LinuxCNC 2.9, xyzacKinematicsInverse and xyzbcKinematicsInverse), tool-offset 0,
// written out term by term as LinuxCNC does.
Vec3 trtfuncsInverse(char tilt, double xr, double yr, double zr, double dx, double dy, double dz, const Vec3& p, double tiltDeg, double cDeg) {
  const double t = tiltDeg * kDeg, c = cDeg * kDeg, x = p.x() - xr, y = p.y() - yr, z = p.z() - zr;
  if (tilt == 'A')
    return {std::cos(c) * x - std::sin(c) * y + xr,
            std::sin(c) * std::cos(t) * x + std::cos(c) * std::cos(t) * y - std::sin(t) * z - std::cos(t) * dy + std::sin(t) * dz + dy + yr,
            std::sin(c) * std::sin(t) * x + std::cos(c) * std::sin(t) * y + std::cos(t) * z - std::sin(t) * dy - std::cos(t) * dz + dz + zr};
  const double dpx = -std::cos(t) * dx - std::sin(t) * dz + dx, dpz = std::sin(t) * dx - std::cos(t) * dz + dz;
  return {std::cos(c) * std::cos(t) * x - std::sin(c) * std::cos(t) * y + std::sin(t) * z + dpx + xr, std::sin(c) * x + std::cos(c) * y + yr,
          -std::cos(c) * std::sin(t) * x + std::sin(c) * std::sin(t) * y + std::cos(t) * z + dpz + zr};
}

TEST(LinuxcncKinematics, JointsAreTrtfuncsInverseKinematics) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-50.0, 50.0), position(-300.0, 300.0), angle(-180.0, 180.0);
  for (char tilt : {'A', 'B'})
    for (int k = 0; k < 200; ++k) {
      LinuxcncKinematics p;
      p.module = tilt == 'A' ? LinuxcncKinematics::Module::XyzacTrt : LinuxcncKinematics::Module::XyzbcTrt;
      p.xRotPoint = offset(rng), p.yRotPoint = offset(rng), p.xOffset = offset(rng), p.yOffset = offset(rng), p.zOffset = offset(rng);
      const Vec3 world(position(rng), position(rng), position(rng));
      const double t = angle(rng), c = angle(rng);
      const Vec3 expected = trtfuncsInverse(tilt, p.xRotPoint, p.yRotPoint, 0.0, p.xOffset, p.yOffset, p.zOffset, world, t, c);
      EXPECT_LE((p.joints(world, t * kDeg, c * kDeg) - expected).norm(), 1e-9) << tilt << k;
    }
}

// docs/examples/xyzac-trt.yaml places the C line at x = 10 and the A line at y = 20, z = -80 mm:
// LinuxCNC's parameters reproduce it to rounding, with its default directions (signs +1).
TEST(LinuxcncKinematics, TheExampleTrunnionIsXyzacTrtKins) {
  const auto machine = example("xyzac-trt.yaml");
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(machine, ErrorModel::zero(*machine));
  EXPECT_EQ(f.nominal.name(), "xyzac-trt-kins");
  EXPECT_EQ(f.sign, (std::array<int, 2>{1, 1}));
  EXPECT_NEAR(f.nominal.xRotPoint, 10.0, 1e-9);
  EXPECT_NEAR(f.nominal.yRotPoint + f.nominal.yOffset, 20.0, 1e-9);
  EXPECT_NEAR(f.nominal.zOffset, -80.0, 1e-9);
  EXPECT_LT(f.residual.afterMax, 1e-9);
  EXPECT_GT(f.residual.samples, 100);
}

// The bundled tilting table (B carrying C, both through the workpiece origin) is xyzbc-trt-kins.
// With only the location errors of its B and C lines, the fitted parameters reproduce the machine
// with its errors: they carry the lines' positions. In mtacc's convention (L . J, docs/conventions)
// the tool point at the joints q is q = R_B (R_C w + dC) + dB for dB = (X0B, Y0B, Z0B), dC = (X0C,
// Y0C, Z0C); LinuxCNC's q = R_B (R_C (w - t - r) - d) + r + d with the work offset t equals it for
// t = (-r_x, -r_y, -d_z), d_x = -X0C, r_x = X0B + X0C, r_y = Y0B + Y0C, d_z = Z0B (Z0C = 0 here).
TEST(LinuxcncKinematics, TheTiltingTableCarriesItsRotaryAxesPositions) {
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const ErrorModel positions = parseErrors(*setup.machine, "errors: {X0B: 6 um, Z0B: -4 um, X0C: -5 um, Y0C: 4 um}\n", "positions.yaml");
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(setup.machine, positions);
  EXPECT_EQ(f.nominal.name(), "xyzbc-trt-kins");
  EXPECT_GT(f.residual.beforeMax, 5e-3);
  EXPECT_LT(f.residual.afterMax, 1e-9);
  EXPECT_NEAR(f.actual.xRotPoint, 1e-3, 1e-9);
  EXPECT_NEAR(f.actual.yRotPoint, 4e-3, 1e-9);
  EXPECT_NEAR(f.actual.xOffset, 5e-3, 1e-9);
  EXPECT_NEAR(f.actual.zOffset, -4e-3, 1e-9);
  EXPECT_LE((f.workOffset - Vec3(-1e-3, -4e-3, 4e-3)).norm(), 1e-9);
}

// With its full error model (squareness and straightness of the linear axes, orientations of the
// rotary axes, component errors) the parameters carry only what the lines' positions can: the
// residual is pinned to 2 % of the figures printed here (mtacc's own, no source prints them: a
// guard against regressions).
TEST(LinuxcncKinematics, ResidualOnTheTiltingTableWithItsFullErrorModel) {
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(setup.machine, setup.errors);
  std::cout << "tilting table, full model: " << f.residual.beforeMax * 1e3 << " um (rms " << f.residual.beforeRms * 1e3 << ") -> "
            << f.residual.afterMax * 1e3 << " um (rms " << f.residual.afterRms * 1e3 << ") over " << f.residual.samples << " poses\n";
  EXPECT_NEAR(f.residual.beforeRms * 1e3, 16.77, 0.02 * 16.77);
  EXPECT_NEAR(f.residual.afterRms * 1e3, 14.02, 0.02 * 14.02);
  EXPECT_NEAR(f.residual.afterMax * 1e3, 32.51, 0.02 * 32.51);
}

// The pins of a HAL file as LinuxCNC's halcmd reads "setp <module>.<pin> <value>" lines.
std::map<std::string, double> halPins(const std::string& hal, const std::string& module) {
  std::istringstream file(hal);
  std::map<std::string, double> pins;
  const std::regex setp("setp " + std::regex_replace(module, std::regex("-"), "\\-") + R"(\.([a-z-]+) (\S+))");
  std::string line;
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with("#")) continue;
    EXPECT_TRUE(std::regex_match(line, m, setp)) << line;
    EXPECT_TRUE(pins.emplace(m[1], std::stod(m[2])).second) << line;
  }
  return pins;
}

TEST(LinuxcncKinematics, HalFileReadsBackToTheParameters) {
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(setup.machine, setup.errors);
  const auto pins = halPins(linuxcncKinematicsHal(*setup.machine, f), "xyzbc-trt-kins");
  ASSERT_EQ(pins.size(), 6u);
  EXPECT_NEAR(pins.at("x-rot-point"), f.actual.xRotPoint, 1e-7);
  EXPECT_NEAR(pins.at("y-rot-point"), f.actual.yRotPoint, 1e-7);
  EXPECT_EQ(pins.at("z-rot-point"), 0.0);
  EXPECT_NEAR(pins.at("x-offset"), f.actual.xOffset, 1e-7);
  EXPECT_EQ(pins.at("y-offset"), 0.0);
  EXPECT_NEAR(pins.at("z-offset"), f.actual.zOffset, 1e-7);
}

TEST(LinuxcncKinematics, OtherMachinesAreRefusedWithTheReason) {
  auto reason = [](const std::string& name) {
    const auto setup = loadMachineSetup({name, "", "", std::nullopt, ""});
    return test::thrown<InputError>([&] { fitLinuxcncKinematics(setup.machine, setup.errors); })->reason();
  };
  EXPECT_NE(reason("three-axis-vertical").find("need the commanded axes X, Y, Z, A or B, and C"), std::string::npos);
  EXPECT_NE(reason("inclined-a-table").find("is not LinuxCNC's xyzac-trt-kins"), std::string::npos);
  const auto headOnTable = std::make_shared<const Machine>(parseMachine(R"(name: C head over a B table
structure: t-C-Z-Y-b-X-B-w
axes:
  X: {direction: [1, 0, 0], travel: [-500 mm, 500 mm]}
  Y: {direction: [0, 1, 0], travel: [-500 mm, 500 mm]}
  Z: {direction: [0, 0, 1], travel: [-500 mm, 500 mm]}
  B: {direction: [0, 1, 0], travel: [-90 deg, 90 deg]}
  C: {direction: [0, 0, 1], travel: continuous}
)", "c-head-b-table.yaml"));
  const auto refused = test::thrown<InputError>([&] { fitLinuxcncKinematics(headOnTable, ErrorModel::zero(*headOnTable)); });
  EXPECT_NE(refused->reason().find("this machine has B on the table and C on the head"), std::string::npos) << refused->reason();
}

// 5axiskins.c (LinuxCNC 2.9, fiveaxis_KinematicsInverse, W = 0) written out: s2r(r, t, p) =
// r (sin p cos t, sin p sin t, cos p) with t = C, p = 180 deg - B; joints = world - s2r - (0, 0, L).
Vec3 fiveAxisInverse(double pivot, const Vec3& p, double bDeg, double cDeg) {
  const double t = cDeg * kDeg, phi = (180.0 - bDeg) * kDeg;
  const Vec3 r(pivot * std::sin(phi) * std::cos(t), pivot * std::sin(phi) * std::sin(t), pivot * std::cos(phi));
  return {p.x() - r.x(), p.y() - r.y(), p.z() - pivot - r.z()};
}

// maxkins.c (LinuxCNC 2.9, kinematicsInverse, U = V = W = 0) written out in its polar form.
Vec3 maxkinsInverse(double pivot, bool conventional, const Vec3& p, double bDeg, double cDeg) {
  const double con = conventional ? 1.0 : -1.0, b = bDeg * kDeg;
  const double zb = pivot * std::cos(b), xb = pivot * std::sin(b);
  const double xyr = std::hypot(p.x(), p.y()), theta = std::atan2(p.y(), p.x()) - cDeg * kDeg;
  return {xyr * std::cos(theta) + con * xb, xyr * std::sin(theta), p.z() + zb - pivot};
}

TEST(LinuxcncKinematics, JointsAreTheHeadModulesInverseKinematics) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> length(50.0, 400.0), position(-300.0, 300.0), angle(-180.0, 180.0);
  for (int k = 0; k < 200; ++k) {
    LinuxcncKinematics five, max;
    five.module = LinuxcncKinematics::Module::FiveAxis;
    max.module = LinuxcncKinematics::Module::Max;
    five.pivotLength = max.pivotLength = length(rng);
    max.conventionalDirections = k % 2 == 1;
    const Vec3 world(position(rng), position(rng), position(rng));
    const double b = angle(rng), c = angle(rng);
    EXPECT_LE((five.joints(world, b * kDeg, c * kDeg) - fiveAxisInverse(five.pivotLength, world, b, c)).norm(), 1e-9) << k;
    EXPECT_LE((max.joints(world, b * kDeg, c * kDeg) - maxkinsInverse(max.pivotLength, max.conventionalDirections, world, b, c)).norm(), 1e-9)
        << k;
  }
}

// Each error alone that the pins carry leaves nothing; each that they cannot is named, and with
// the carried ones beside it the fit leaves what it leaves alone.
struct CarriedCase {
  std::string machine, module, carried, notCarried;
};

void checkCarriedAndNamed(const CarriedCase& c) {
  const auto setup = loadMachineSetup({c.machine, "", "", std::nullopt, ""});
  const ErrorModel carried = parseErrors(*setup.machine, "errors: {" + c.carried + "}\n", "carried.yaml");
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(setup.machine, carried);
  EXPECT_EQ(f.actual.name(), c.module);
  EXPECT_GT(f.residual.beforeMax, 3e-3) << c.carried;
  EXPECT_LT(f.residual.afterMax, 1e-5) << c.carried;  // 0.01 um
  EXPECT_TRUE(f.notCarried.empty()) << fmt::format("{}", fmt::join(f.notCarried, "; "));

  const ErrorModel both = parseErrors(*setup.machine, "errors: {" + c.carried + ", " + c.notCarried + "}\n", "both.yaml");
  const ErrorModel alone = parseErrors(*setup.machine, "errors: {" + c.notCarried + "}\n", "alone.yaml");
  const LinuxcncKinematicsFit withBoth = fitLinuxcncKinematics(setup.machine, both), withAlone = fitLinuxcncKinematics(setup.machine, alone);
  ASSERT_EQ(withBoth.notCarried.size(), 1u);
  const std::string name = c.notCarried.substr(0, c.notCarried.find(':'));
  EXPECT_TRUE(withBoth.notCarried[0].starts_with(name + " (")) << withBoth.notCarried[0];
  EXPECT_GT(withAlone.residual.afterMax, 1e-3);
  EXPECT_NEAR(withBoth.residual.afterMax, withAlone.residual.afterMax, 1e-3 * withAlone.residual.afterMax);
  EXPECT_NEAR(withBoth.residual.afterRms, withAlone.residual.afterRms, 1e-3 * withAlone.residual.afterRms);
}

// The bundled head machine is the module, with its pivot length (mm), to rounding.
LinuxcncKinematicsFit checkNominal(const std::shared_ptr<const Machine>& machine, const std::string& module, double pivotLength) {
  const LinuxcncKinematicsFit f = fitLinuxcncKinematics(machine, ErrorModel::zero(*machine));
  EXPECT_EQ(f.nominal.name(), module);
  EXPECT_NEAR(f.nominal.pivotLength, pivotLength, 1e-9);
  EXPECT_LT(f.residual.afterMax, 1e-9);
  EXPECT_GT(f.residual.samples, 100);
  return f;
}

// The double pivot head is 5axiskins: its pivot length is 200 mm (the machine file's tool); an
// error of the spindle along its own axis (Z0C1) changes it, and the pin carries it.
TEST(LinuxcncKinematics, TheDoublePivotHeadIs5axiskinsAndItsPivotLengthCarriesZ0C1) {
  const auto setup = loadMachineSetup({"double-pivot-head", "", "", std::nullopt, ""});
  checkNominal(setup.machine, "5axiskins", 200.0);
  const ErrorModel longer = parseErrors(*setup.machine, "errors: {Z0C1: 7 um}\n", "z0c1.yaml");
  EXPECT_NEAR(fitLinuxcncKinematics(setup.machine, longer).actual.pivotLength - 200.0, -7e-3, 1e-8);
  checkCarriedAndNamed({"double-pivot-head", "5axiskins", "Z0C1: 7 um, X0X: 4 um, Z0Z: -3 um", "X0C1: 6 um"});
}

// The swivel head over the C table is maxkins: pivot length 150 mm, the C line at the joints'
// zero. The spindle's length (Z0C1) goes to the pin, the C line's position (X0C, Y0C) to the
// joints' zero, the head's offset to both; a tilt of the B line (A0B) cannot be carried.
TEST(LinuxcncKinematics, TheSwivelHeadTableIsMaxkinsAndCarriesPivotAndCLine) {
  const auto setup = loadMachineSetup({"swivel-head-table", "", "", std::nullopt, ""});
  EXPECT_TRUE(checkNominal(setup.machine, "maxkins", 150.0).nominal.conventionalDirections);
  const ErrorModel cLine = parseErrors(*setup.machine, "errors: {X0C: 5 um, Y0C: -4 um}\n", "c.yaml");
  const LinuxcncKinematicsFit shifted = fitLinuxcncKinematics(setup.machine, cLine);
  EXPECT_LT(shifted.residual.afterMax, 1e-8);
  EXPECT_NEAR(std::hypot(shifted.jointOriginShift.x(), shifted.jointOriginShift.y()), std::hypot(5e-3, 4e-3), 1e-8);
  checkCarriedAndNamed({"swivel-head-table", "maxkins", "Z0C1: 7 um, X0C: 5 um, Y0C: -4 um, X0B: 3 um", "A0B: 20 urad"});
}

// The trunnion's pins carry its lines' positions; the C line's tilt about X (A0C) they cannot.
TEST(LinuxcncKinematics, TheTiltingTablesPinsNameTheLinesTilt) {
  checkCarriedAndNamed({"tilting-table", "xyzbc-trt-kins", "X0B: 6 um, Z0B: -4 um, X0C: -5 um, Y0C: 4 um", "A0C: 30 urad"});
}

TEST(LinuxcncKinematics, HeadModulesHalFilesReadBack) {
  for (const auto& [machine, module] : {std::pair{"double-pivot-head", "5axiskins"}, std::pair{"swivel-head-table", "maxkins"}}) {
    const auto setup = loadMachineSetup({machine, "", "", std::nullopt, ""});
    const LinuxcncKinematicsFit f = fitLinuxcncKinematics(setup.machine, setup.errors);
    const std::string hal = linuxcncKinematicsHal(*setup.machine, f);
    const auto pins = halPins(hal, module);
    EXPECT_NEAR(pins.at("pivot-length"), f.actual.pivotLength, 1e-7) << machine;
    if (std::string(module) == "maxkins") {
      EXPECT_EQ(pins.at("conventional-directions"), f.actual.conventionalDirections ? 1.0 : 0.0);
    }
    EXPECT_EQ(pins.size(), std::string(module) == "maxkins" ? 2u : 1u);
    for (const auto& left : f.notCarried) EXPECT_NE(hal.find("# not carried: " + left + "\n"), std::string::npos) << left;
  }
}

}  // namespace
}  // namespace mtacc
