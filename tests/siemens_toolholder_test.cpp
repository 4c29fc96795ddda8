// SINUMERIK's orientable toolholder ($TC_CARR, issue 45 item 2): the data set's kinematics against
// the two worked examples of Siemens' manuals, the bundled machines it reproduces, the errors it
// carries (leaving nothing) and the ones it cannot (named, leaving their own effect), the residual
// along a program, and the part program read back.
#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <regex>
#include <sstream>

#include "mtacc/compensation/siemens_toolholder.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// The manuals print the positions to 0.001 mm: agreement to half of that.
constexpr double kPrinted = 0.5e-3;

// SINUMERIK 840D sl function manual W1 "Tool compensation" (08/2005, 6FC5397-0BP10-0BA0), §4.1
// "Toolholder with orientation capability", p. 4-3: kinematic type P, l4 = (0, 0, 15), l3 = 0,
// the table at A0 B45, TCARR=1 X0 Y10 Z0 with T1 (13 mm long, "in the Z direction the tool
// selection leads to an additional offset of 13 mm"): "the position X10.607 Y10.000 Z8.607 is
// approached", the zero point offset by X10.607 = 15 sin 45 and Z-4.393 = -15 (1 - cos 45). The
// page reachable here starts at N170: l1, l2, v1, v2 are taken as 0, 0, A = (1, 0, 0), B = (0, 1, 0),
// as "the rotation of the 4th offset vector ... about the B axis" says. The point lies on the B
// axis's direction, so the frame's rotation (not applied without PAROT) does not move it.
TEST(SiemensToolholder, ManualExampleRotaryTableTypeP) {
  SiemensToolholder h;
  h.type = 'P';
  h.l[3] = {0.0, 0.0, 15.0};
  h.v = {Vec3::UnitX(), Vec3::UnitY()};
  const Vec3 at = h.machinePosition({0.0, 10.0, 0.0}, {0.0, 45.0 * kDeg}, {0.0, 0.0, 13.0});
  EXPECT_NEAR(at.x(), 10.607, kPrinted);
  EXPECT_NEAR(at.y(), 10.000, kPrinted);
  EXPECT_NEAR(at.z(), 8.607, kPrinted);
}

// SINUMERIK programming manual "Job planning", CUTMOD example (toolholder 2, kinematic type M,
// v2 = C = (0, 0, 1), all offset vectors 0, $TC_CARR13 = 30: "a rotation of 30 deg around the B
// axis", v1 = (0, 1, 0)): the tool's length vector (12, 0, 1) gives the machine position X12.000
// Y0.000 Z1.000 unrotated and X10.892 Y0.000 Z-5.134 with the holder turned (N180, N210).
TEST(SiemensToolholder, ManualExampleHeadAxisTypeM) {
  SiemensToolholder h;
  h.type = 'M';
  h.v = {Vec3::UnitY(), Vec3::UnitZ()};
  const Vec3 tool(12.0, 0.0, 1.0);
  EXPECT_LE((h.machinePosition(Vec3::Zero(), {0.0, 0.0}, tool) - Vec3(12.0, 0.0, 1.0)).norm(), 1e-12);
  const Vec3 turned = h.machinePosition(Vec3::Zero(), {30.0 * kDeg, 0.0}, tool);
  EXPECT_NEAR(turned.x(), 10.892, kPrinted);
  EXPECT_NEAR(turned.y(), 0.000, kPrinted);
  EXPECT_NEAR(turned.z(), -5.134, kPrinted);
}

// The data set read back from the part program's "$TC_CARRn[m]=value" blocks.
SiemensToolholder readProgram(const std::string& program) {
  std::istringstream file(program);
  std::map<int, std::string> values;
  const std::regex assignment(R"(N\d+ \$TC_CARR(\d+)\[1\]=(\S+))");
  std::string line;
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with(";") || line.ends_with("M17")) continue;
    EXPECT_TRUE(std::regex_match(line, m, assignment)) << line;
    EXPECT_TRUE(values.emplace(std::stoi(m[1]), m[2]).second) << line;
  }
  SiemensToolholder h;
  const int vectors[4] = {1, 4, 15, 18};
  for (size_t k = 0; k < 4; ++k) h.l[k] = {std::stod(values.at(vectors[k])), std::stod(values.at(vectors[k] + 1)), std::stod(values.at(vectors[k] + 2))};
  for (size_t k = 0; k < 2; ++k) {
    const int first = 7 + 3 * static_cast<int>(k);
    h.v[k] = {std::stod(values.at(first)), std::stod(values.at(first + 1)), std::stod(values.at(first + 2))};
    h.axes[k] = values.at(21 + static_cast<int>(k));
    h.offset[k] = std::stod(values.at(24 + static_cast<int>(k))) * kDeg;
  }
  h.type = values.at(23).at(1);
  return h;
}

// The data set read back from the transformation's machine data ("$MC_NAME_1[i]=value" lines).
SiemensToolholder readMachineData(const std::string& ini, const std::array<std::string, 2>& axes) {
  std::istringstream file(ini);
  std::map<std::string, double> values;
  const std::regex assignment(R"(\$MC_([A-Z0-9_]+)_1(\[(\d)\])?=(\S+))");
  std::string line;
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with(";") || line.starts_with("%") || line == "CHANDATA(1)" || line == "M17") continue;
    EXPECT_TRUE(std::regex_match(line, m, assignment)) << line;
    EXPECT_TRUE(values.emplace(std::string(m[1]) + std::string(m[2]), std::stod(m[4])).second) << line;
  }
  SiemensToolholder h;
  const int type = static_cast<int>(values.at("TRAFO_TYPE"));
  h.type = type == 24 ? 'T' : type == 40 ? 'P' : 'M';
  const auto vector = [&](const std::string& name) {
    return Vec3(values.at(name + "[0]"), values.at(name + "[1]"), values.at(name + "[2]"));
  };
  for (const auto& [name, l] : trafo5Vectors(h.type)) h.l[static_cast<size_t>(l)] = vector(name);
  h.v = {vector("TRAFO5_AXIS1"), vector("TRAFO5_AXIS2")};
  h.offset = {values.at("TRAFO5_ROT_AX_OFFSET[0]") * kDeg, values.at("TRAFO5_ROT_AX_OFFSET[1]") * kDeg};
  h.axes = axes;
  return h;
}

struct Case {
  std::string machine;
  char type;
  std::string axes, carried, notCarried, named;  // named: the parameter the error file's notCarried sets
};

// Errors the data set carries leave nothing over the poses; one it cannot, beside them, is named
// and leaves what it leaves alone; the part program reads back to the fitted data set.
void checkCase(const Case& c) {
  SCOPED_TRACE(c.machine);
  const auto setup = loadMachineSetup({c.machine, "", "", std::nullopt, ""});
  const auto zero = fitSiemensToolholder(setup.machine, ErrorModel::zero(*setup.machine));
  EXPECT_EQ(zero.nominal.type, c.type);
  EXPECT_EQ(zero.nominal.axes[0] + zero.nominal.axes[1], c.axes);
  EXPECT_LT(zero.residual.afterMax, 1e-9);
  EXPECT_GT(zero.residual.samples, 100);

  const ErrorModel carried = parseErrors(*setup.machine, "errors: {" + c.carried + "}\n", "carried.yaml");
  const SiemensToolholderFit f = fitSiemensToolholder(setup.machine, carried);
  EXPECT_GT(f.residual.beforeMax, 3e-3);
  EXPECT_LT(f.residual.afterMax, 1e-5);  // 0.01 um
  EXPECT_TRUE(f.notCarried.empty()) << (f.notCarried.empty() ? "" : f.notCarried[0]);

  const ErrorModel both = parseErrors(*setup.machine, "errors: {" + c.carried + ", " + c.notCarried + "}\n", "both.yaml");
  const ErrorModel alone = parseErrors(*setup.machine, "errors: {" + c.notCarried + "}\n", "alone.yaml");
  const SiemensToolholderFit withBoth = fitSiemensToolholder(setup.machine, both), withAlone = fitSiemensToolholder(setup.machine, alone);
  ASSERT_EQ(withBoth.notCarried.size(), 1u);
  EXPECT_TRUE(withBoth.notCarried[0].starts_with(c.named + " (")) << withBoth.notCarried[0];
  EXPECT_GT(withAlone.residual.afterMax, 1e-3);
  EXPECT_NEAR(withBoth.residual.afterMax, withAlone.residual.afterMax, 1e-3 * withAlone.residual.afterMax);

  // Both files read back to the fitted data set (the transformation's by the manual's mapping).
  for (const SiemensToolholder& read :
       {readProgram(siemensToolholderProgram(*setup.machine, f)), readMachineData(siemensTrafo5MachineData(*setup.machine, f), f.actual.axes)}) {
    EXPECT_EQ(read.type, f.actual.type);
    EXPECT_EQ(read.axes, f.actual.axes);
    for (double a : {-40.0, 0.0, 35.0})
      for (double b : {-120.0, 10.0, 90.0}) {
        const Vec3 point(120.0, -80.0, 50.0), tool(0.0, 0.0, 0.0);
        EXPECT_LE((read.machinePosition(point, {a * kDeg, b * kDeg}, tool) - f.actual.machinePosition(point, {a * kDeg, b * kDeg}, tool)).norm(),
                  1e-5)
            << a << " " << b;
      }
  }
}

// Each kind of bundled 5-axis machine. The data set holds the rotary lines' positions (X0C, Y0B),
// directions (A0C, B0B) and zero offsets (C.zero), and on a head the spindle's offsets (X0C1, Z0C1);
// not the linear axes' squareness (C0Y) or a scale error (EXX).
TEST(SiemensToolholder, SwivelTableTypeP) {
  checkCase({"tilting-table", 'P', "BC", "X0C: 5 um, Y0C: -4 um, Z0B: 3 um, A0C: 20 urad, A0B: 15 urad, C.zero: 30 urad", "C0Y: 25 urad", "C0Y"});
}

TEST(SiemensToolholder, SwivelHeadTypeT) {
  checkCase({"double-pivot-head", 'T', "CB", "X0B: 5 um, Y0C: -4 um, X0C1: 6 um, Z0C1: 7 um, B0C: 20 urad, A0B: 15 urad, B.zero: 30 urad",
             "EXX: {linear: {value: 8 um, over: 1000 mm}}", "EXX.c1"});
}

TEST(SiemensToolholder, HeadAndTableTypeM) {
  checkCase({"swivel-head-table", 'M', "BC", "X0C: 5 um, Y0C: -4 um, X0C1: 6 um, Z0C1: 7 um, A0B: 15 urad, B0C: 20 urad, B.zero: 30 urad",
             "C0Y: 25 urad", "C0Y"});
}

TEST(SiemensToolholder, OtherMachinesAreRefusedWithTheReason) {
  const auto setup = loadMachineSetup({"three-axis-vertical", "", "", std::nullopt, ""});
  const auto refused = test::thrown<InputError>([&] { fitSiemensToolholder(setup.machine, setup.errors); });
  EXPECT_NE(refused->reason().find("needs the commanded axes X, Y, Z and two rotary axes"), std::string::npos);
}

}  // namespace
}  // namespace mtacc
