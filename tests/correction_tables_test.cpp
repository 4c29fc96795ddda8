// Controller tables (issue 17, item 3): the 3-D correction grid, its one-axis reduction and the
// LinuxCNC COMP_FILE, each written, read back, applied by a simulated controller, and the
// residual it leaves pinned.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/cone_program.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/procedures/cone.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

MachineSetup bundledSetup(const std::string& name) { return loadMachineSetup({name, "", "", std::nullopt, ""}); }

TEST(CorrectionGrid, NodesHoldTheInverseErrorModelAndTheControllerMatchesIt) {
  const auto setup = bundledSetup("three-axis-vertical");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{7, 6, 6}, {}});
  const KinematicModel actual = setup.actual(), nominal = setup.nominal();
  // At a node the corrected commands reach the nominal TCP (the tolerance the grid is solved to).
  for (int k : {0, 5})
    for (int j : {0, 3})
      for (int i : {0, 4, 6}) {
        std::vector<double> q = {grid.node(0, i), grid.node(1, j), grid.node(2, k)};
        const Vec3 wanted = toolPoint(nominal, q.data()).position;
        const Vec3 c = grid.interpolate({q[0], q[1], q[2]});
        for (int a = 0; a < 3; ++a) q[static_cast<size_t>(a)] += c[a];
        EXPECT_LE((toolPoint(actual, q.data()).position - wanted).norm(), 1e-7);
      }
  // Trilinear: halfway between two nodes along X, the mean of the two.
  const Vec3 halfway = grid.interpolate({0.5 * (grid.node(0, 2) + grid.node(0, 3)), grid.node(1, 1), grid.node(2, 4)});
  EXPECT_LE((halfway - 0.5 * (grid.at(2, 1, 4) + grid.at(3, 1, 4))).norm(), 1e-15);
  // Beyond the last node: the end value.
  EXPECT_EQ(grid.interpolate({1e4, grid.node(1, 5), grid.node(2, 5)}), grid.at(6, 5, 5));
}

// Each Z layer is solved from scratch, so the threads do not change a single bit of the grid.
TEST(CorrectionGrid, TheSameOnAnyNumberOfThreads) {
  const auto setup = bundledSetup("maho");
  const CorrectionGrid one = correctionGrid(setup.machine, setup.errors, {{9, 7, 8}, {}, 1});
  const CorrectionGrid three = correctionGrid(setup.machine, setup.errors, {{9, 7, 8}, {}, 3});
  ASSERT_EQ(one.corrections.size(), three.corrections.size());
  for (size_t n = 0; n < one.corrections.size(); ++n) EXPECT_EQ(one.corrections[n], three.corrections[n]) << n;
}

// The residual each table leaves over the working volume of the 3-axis machine with its bundled
// errors (squareness, scale, straightness as harmonics, pitch and yaw, reversal-free state):
// pinned to 2 % of the figures printed here (mtacc's own figures, no source prints them: a guard
// against a change that moves them unnoticed).
TEST(CorrectionGrid, ResidualOfEachTableOnTheThreeAxisMachine) {
  const auto setup = bundledSetup("three-axis-vertical");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{11, 11, 11}, {}});
  const auto trilinear = tableResidual(setup.machine, setup.errors, grid, [&](const Vec3& p) { return grid.interpolate(p); });
  const OneAxisReduction all = reduceToOneAxisFunctions(grid, 9);
  // What a LinuxCNC COMP_FILE per joint carries: each axis's correction of its own command.
  OneAxisReduction own = all;
  std::erase_if(own.functions, [](const AxisFunction& f) { return f.input != f.output; });
  const auto oneAxis = tableResidual(setup.machine, setup.errors, grid, [&](const Vec3& p) { return all.correction(p); });
  const auto ownAxes = tableResidual(setup.machine, setup.errors, grid, [&](const Vec3& p) { return own.correction(p); });
  std::cout << "before " << trilinear.beforeMax * 1e3 << " um; trilinear grid " << trilinear.afterMax * 1e3 << " um; 9 one-axis "
            << oneAxis.afterMax * 1e3 << " um (reduction residual " << all.residualMax * 1e3 << " um); own-axis (LinuxCNC) "
            << ownAxes.afterMax * 1e3 << " um\n";
  EXPECT_NEAR(trilinear.beforeMax * 1e3, 28.27, 0.02 * 28.27);
  EXPECT_NEAR(trilinear.afterMax * 1e3, 0.0986, 0.02 * 0.0986);  // within 5 % of before: the grid carries it all
  EXPECT_NEAR(oneAxis.afterMax * 1e3, 2.254, 0.02 * 2.254);       // the cross terms of pitch and yaw (Abbe) stay
  EXPECT_NEAR(all.residualMax * 1e3, 2.254, 0.02 * 2.254);
  EXPECT_NEAR(ownAxes.afterMax * 1e3, 13.94, 0.02 * 13.94);      // squareness and straightness need the cross-axis tables
  EXPECT_EQ(trilinear.samples, 21 * 21 * 21);
}

// Along a test path: ballbar circles in three planes on the 3-axis machine. A grid fine enough
// for the path's curvature carries its error as a compensated program does; on the 5-axis
// cone frustum, whose rotary axes move, the linear-axis grid taken at B = C = 0 cannot.
TEST(CorrectionGrid, ResidualAlongATestPath) {
  const auto setup = bundledSetup("three-axis-vertical");
  const GcodeProgram circles = parseGcodeProgram(
      "G17 G0 X400 Y200 Z250\nG2 X400 Y200 I-100 F1000\nG18 G0 X300 Y200 Z350\nG2 X300 Z350 K-100\n", "circles.nc", *setup.machine);
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{24, 22, 22}, {}});  // nodes off the circles' quarter points
  const auto along = tableResidualAlong(setup.machine, setup.errors, circles, grid, [&](const Vec3& p) { return grid.interpolate(p); });
  std::cout << "circles: " << along.beforeMax * 1e3 << " um -> " << along.afterMax * 1e3 << " um over " << along.samples << " samples\n";
  EXPECT_EQ(along.samples, 34);  // two feed moves, 17 points each
  EXPECT_LE(along.afterMax, 0.05 * along.beforeMax);

  const auto table = bundledSetup("tilting-table");
  const ConeSpec spec;
  const GcodeProgram cone = parseGcodeProgram(coneNcProgram(*table.machine, spec, coneMotion(table.nominal(), spec, conePath(spec, 72)).q, 500.0),
                                              "cone.nc", *table.machine);
  const CorrectionGrid at0 = correctionGrid(table.machine, table.errors, {{11, 11, 11}, {}});
  const auto onCone = tableResidualAlong(table.machine, table.errors, cone, at0, [&](const Vec3& p) { return at0.interpolate(p); });
  std::cout << "cone: " << onCone.beforeMax * 1e3 << " um -> " << onCone.afterMax * 1e3 << " um\n";
  EXPECT_GT(onCone.afterMax, 0.3 * onCone.beforeMax);
}

TEST(OneAxisReduction, AnAdditiveCorrectionIsReproducedExactly) {
  // A grid whose corrections are sums of one-axis functions: the reduction leaves nothing.
  CorrectionGrid g;
  g.counts = {5, 4, 3};
  g.start = {0, -10, 5};
  g.step = {10, 5, 20};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i) {
        const double x = g.node(0, i), y = g.node(1, j), z = g.node(2, k);
        g.corrections.emplace_back(1e-3 * std::sin(x / 7) + 2e-4 * y, 3e-4 * z * z / 100 - 1e-4, 5e-5 * x + 1e-3);
      }
  const OneAxisReduction r = reduceToOneAxisFunctions(g, 9);
  EXPECT_LE(r.residualMax, 1e-15);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i)
        EXPECT_LE((r.correction({g.node(0, i), g.node(1, j), g.node(2, k)}) - g.at(i, j, k)).norm(), 1e-15);
  // Fewer functions leave the smallest out: the residual is what they carried.
  const OneAxisReduction four = reduceToOneAxisFunctions(g, 4);
  EXPECT_EQ(four.functions.size(), 4u);
  EXPECT_GT(four.residualMax, 0.0);
}

TEST(CorrectionGrid, CsvReadsBackAndAppliesAsWritten) {
  const auto setup = bundledSetup("three-axis-vertical");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{4, 3, 3}, {}});
  const CsvTable table = parseCsv(correctionGridCsv(*setup.machine, grid), "grid.csv");
  ASSERT_EQ(table.header, (std::vector<std::string>{"x_mm", "y_mm", "z_mm", "dx_mm", "dy_mm", "dz_mm"}));
  ASSERT_EQ(table.rows.size(), 36u);
  for (size_t n = 0; n < table.rows.size(); ++n) {
    const int i = static_cast<int>(n % 4), j = static_cast<int>(n / 4 % 3), k = static_cast<int>(n / 12);
    EXPECT_NEAR(table.rows[n][0], grid.node(0, i), 1e-6);
    EXPECT_NEAR(table.rows[n][2], grid.node(2, k), 1e-6);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(table.rows[n][static_cast<size_t>(3 + c)], grid.at(i, j, k)[c], 5e-8);  // 7 decimals
  }
}

// LinuxCNC motion.h: EMCMOT_COMP_SIZE 256 entries per joint; each line "nominal forward
// reverse"; type 1 trims are added to the command (control.c), type 0 holds nominal + trim.
TEST(LinuxcncCompFile, TripletsWithinTheLimitAndTheControllerInterpolatesThem) {
  const auto setup = bundledSetup("three-axis-vertical");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{41, 3, 3}, {}});
  const OneAxisReduction r = reduceToOneAxisFunctions(grid, 9);
  const auto own = std::find_if(r.functions.begin(), r.functions.end(), [](const AxisFunction& f) { return f.input == 0 && f.output == 0; });
  ASSERT_NE(own, r.functions.end());
  const ReversalTrims reversal = reversalTrims(setup.machine, setup.errors, grid, 0);
  for (int type : {0, 1}) {
    std::istringstream file(linuxcncCompFile(*own, reversal, type));
    std::vector<std::array<double, 3>> triplets;
    std::string line;
    while (std::getline(file, line)) {
      std::istringstream words(line);
      std::array<double, 3> t{};
      std::string extra;
      ASSERT_TRUE(words >> t[0] >> t[1] >> t[2]) << line;
      EXPECT_FALSE(words >> extra) << line;
      if (!triplets.empty()) {
        EXPECT_GT(t[0], triplets.back()[0]);
      }
      triplets.push_back(t);
    }
    ASSERT_EQ(triplets.size(), 41u);
    // The simulated controller: the trim interpolated linearly between entries.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(triplets.front()[0], triplets.back()[0]);
    for (int s = 0; s < 200; ++s) {
      const double p = x(rng);
      const auto upper = std::upper_bound(triplets.begin(), triplets.end(), p, [](double v, const auto& t) { return v < t[0]; });
      const auto& b = *std::min(upper, triplets.end() - 1);
      const auto& a = *(&b - 1);
      // The mean of the forward and reverse trims: the machine's EXX reversal (2 um) is symmetric.
      const double trimA = (type == 1 ? a[1] + a[2] : a[1] + a[2] - 2 * a[0]) / 2, trimB = (type == 1 ? b[1] + b[2] : b[1] + b[2] - 2 * b[0]) / 2;
      const double trim = trimA + (p - a[0]) / (b[0] - a[0]) * (trimB - trimA);
      EXPECT_NEAR(trim, own->at(p), 2e-7);  // the file's 6 and 7 decimals
    }
    // Issue 46: the forward and reverse columns differ by the reversal. EXX is +1 um moving
    // forward; X carries the table, so the tool lands 1 um back on the workpiece and the forward
    // correction is the larger.
    for (const auto& t : triplets) EXPECT_NEAR(t[1] - t[2], 2e-3, 2e-7) << t[0];
  }
  AxisFunction tooLong = *own;
  tooLong.positions.resize(257, 0.0);
  tooLong.values.resize(257, 0.0);
  EXPECT_NE(test::thrown<InputError>([&] { linuxcncCompFile(tooLong, reversal, 1); })->reason().find("at most 256"), std::string::npos);
}

// Issue 46's acceptance: a machine whose only errors are each axis's positioning error with a
// reversal. Its LinuxCNC trims applied as LinuxCNC's motion controller applies them (the forward
// column moving forward, the reverse column moving backward, linear between the entries) put the
// TCP where the nominal machine puts it, moving either way, between the nodes too.
// A machine whose only errors are each axis's positioning error with a reversal (issue 46).
ErrorModel reversalErrors(const Machine& machine) {
  return parseErrors(machine,
                     "errors:\n  EXX: {linear: {value: 4 um, over: 600 mm}, reversal: 3 um}\n"
                     "  EYY: {reversal: 2 um}\n  EZZ: {linear: {value: -2 um, over: 500 mm}, reversal: 1.5 um}\n",
                     "reversals.yaml", ErrorsKey::Required);
}

// The largest TCP error left at 300 random points of the grid's box, each axis moving a random
// way, the commands as a controller corrects them (`commanded`, from the point and the motion).
using ControllerCommands = std::function<std::vector<double>(const std::vector<double>& q, const std::vector<int>& motion)>;
double largestMovingResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid,
                             const ControllerCommands& commanded) {
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  std::mt19937 rng(5);
  double largest = 0.0;
  for (int s = 0; s < 300; ++s) {
    std::vector<double> q(3);
    std::vector<int> motion(3);
    for (int a = 0; a < 3; ++a) {
      q[static_cast<size_t>(a)] = std::uniform_real_distribution<double>(grid.node(a, 0), grid.node(a, grid.counts[static_cast<size_t>(a)] - 1))(rng);
      motion[static_cast<size_t>(a)] = rng() % 2 ? 1 : -1;
    }
    const std::vector<double> c = commanded(q, motion);
    largest = std::max(largest, (toolPoint(actual, c.data(), motion.data()).position - toolPoint(nominal, q.data()).position).norm());
  }
  return largest;
}

std::array<ReversalTrims, 3> trimsOf(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid) {
  std::array<ReversalTrims, 3> trims;
  for (int a = 0; a < 3; ++a) trims[static_cast<size_t>(a)] = reversalTrims(machine, errors, grid, a);
  return trims;
}

TEST(LinuxcncCompFile, ForwardAndReverseTrimsCorrectTheReversalMovingEachWay) {
  const auto machine = test::bundled("three-axis-vertical");
  const ErrorModel errors = reversalErrors(*machine);
  const CorrectionGrid grid = correctionGrid(machine, errors, {{31, 21, 26}, {}});
  OneAxisReduction own = reduceToOneAxisFunctions(grid, 9);
  std::erase_if(own.functions, [](const AxisFunction& f) { return f.input != f.output; });
  ASSERT_EQ(own.functions.size(), 3u);
  std::array<std::vector<std::array<double, 3>>, 3> tables;
  for (const auto& f : own.functions) {
    std::istringstream file(linuxcncCompFile(f, reversalTrims(machine, errors, grid, f.input), 1));
    std::array<double, 3> t{};
    while (file >> t[0] >> t[1] >> t[2]) tables[static_cast<size_t>(f.input)].push_back(t);
  }
  auto trim = [&](int axis, double p, int direction) {
    const auto& rows = tables[static_cast<size_t>(axis)];
    const auto upper = std::upper_bound(rows.begin(), rows.end(), p, [](double v, const auto& t) { return v < t[0]; });
    const auto& b = *std::min(upper, rows.end() - 1);
    const auto& a = *(&b - 1);
    const size_t column = direction > 0 ? 1 : 2;
    return a[column] + (p - a[0]) / (b[0] - a[0]) * (b[column] - a[column]);
  };
  const double largest = largestMovingResidual(machine, errors, grid, [&](const std::vector<double>& q, const std::vector<int>& motion) {
    std::vector<double> c = q;
    for (int a = 0; a < 3; ++a) c[static_cast<size_t>(a)] += trim(a, q[static_cast<size_t>(a)], motion[static_cast<size_t>(a)]);
    return c;
  });
  RecordProperty("largest_um", std::to_string(largest * 1e3));
  EXPECT_LT(largest, 1e-5);  // 0.01 um: the file's 7 decimals and the linear interpolation of a linear error
}

// Siemens CEC (840D sl function manual K3): per table $AN_CEC_INPUT_AXIS, _OUTPUT_AXIS, _STEP, _MIN,
// _MAX, _DIRECTION, _MULT_BY_TABLE, _IS_MODULO and the values $AN_CEC[t, N]; the file
// %_N_NC_CEC_INI ends with M17. Read back, interpolated as the control does, it is the reduction.
// A %_N_NC_CEC_INI file's tables by index, as the control reads them.
struct CecTable {
  std::string input, output;
  double step = 0, min = 0, max = 0;
  int direction = 0;
  std::vector<double> values;
  // Linear between the points, the end values beyond.
  double at(double p) const {
    const double u = std::clamp((p - min) / step, 0.0, static_cast<double>(values.size() - 1));
    const auto k = std::min(static_cast<size_t>(u), values.size() - 2);
    return values[k] + (u - static_cast<double>(k)) * (values[k + 1] - values[k]);
  }
};

std::map<int, CecTable> readCecTables(const std::string& text) {
  std::istringstream file(text);
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line, "%_N_NC_CEC_INI");
  std::map<int, CecTable> tables;
  const std::regex field(R"(\$AN_CEC_(\w+)\[(\d+)\]=\(?([^)]*)\)?)"), value(R"(\$AN_CEC\[(\d+),(\d+)\]=(\S+))");
  std::string last;
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with(";")) continue;
    last = line;
    if (std::regex_match(line, m, value)) {
      auto& t = tables[std::stoi(m[1])];
      EXPECT_EQ(static_cast<size_t>(std::stoi(m[2])), t.values.size());
      t.values.push_back(std::stod(m[3]));
    } else if (std::regex_match(line, m, field)) {
      auto& t = tables[std::stoi(m[2])];
      const std::string name = m[1], text = m[3];
      if (name == "INPUT_AXIS") t.input = text;
      else if (name == "OUTPUT_AXIS") t.output = text;
      else if (name == "STEP") t.step = std::stod(text);
      else if (name == "MIN") t.min = std::stod(text);
      else if (name == "MAX") t.max = std::stod(text);
      else if (name == "DIRECTION") t.direction = std::stoi(text);
      else EXPECT_TRUE((name == "MULT_BY_TABLE" || name == "IS_MODULO") && text == "0") << line;
    } else {
      EXPECT_EQ(line, "M17");
    }
  }
  EXPECT_EQ(last, "M17");
  for (const auto& [index, t] : tables) EXPECT_NEAR(t.min + t.step * static_cast<double>(t.values.size() - 1), t.max, 1e-5) << index;
  return tables;
}

// The control's correction from CEC tables: each table whose direction is 0 or that of its input
// axis's motion (`motion` empty: standing, the direction-free tables only) adds to its output axis.
Vec3 cecCorrection(const std::map<int, CecTable>& tables, const Vec3& p, const std::vector<int>& motion) {
  const char* names[3] = {"X", "Y", "Z"};
  const auto index = [&](const std::string& axis) { return static_cast<int>(std::find(names, names + 3, axis) - names); };
  Vec3 c = Vec3::Zero();
  for (const auto& [number, t] : tables) {
    const int in = index(t.input);
    if (t.direction != 0 && (motion.empty() || motion[static_cast<size_t>(in)] != t.direction)) continue;
    c[index(t.output)] += t.at(p[in]);
  }
  return c;
}

TEST(SiemensCec, TablesReadBackAndInterpolateToTheReduction) {
  const auto setup = bundledSetup("maho");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{8, 6, 7}, {}});
  const OneAxisReduction r = reduceToOneAxisFunctions(grid, 6);
  const auto tables = readCecTables(siemensCecTables(r.functions, {}, setup.machine->describePose(grid.pose)));
  ASSERT_EQ(tables.size(), 6u);
  std::mt19937 rng(5);
  for (int s = 0; s < 100; ++s) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = std::uniform_real_distribution<double>(grid.start[a], grid.node(a, grid.counts[a] - 1))(rng);
    EXPECT_LE((cecCorrection(tables, p, {}) - r.correction(p)).norm(), 2e-7);  // 7 decimals
  }
}

// SINUMERIK's reversal (issue 46): two CEC tables on each axis's own command, one applying moving
// positive ($AN_CEC_DIRECTION 1), one moving negative (-1): "position-dependent backlash
// compensation can be implemented using two tables" (K3, 03/2013, p. 249). With the one-axis
// functions, applied as the control applies them, they leave below 0.01 um moving each way on a
// machine with positioning errors and reversals; the two tables differ by the reversal.
TEST(SiemensCec, DirectionTablesCorrectTheReversalMovingEachWay) {
  const auto machine = test::bundled("three-axis-vertical");
  const ErrorModel errors = reversalErrors(*machine);
  const CorrectionGrid grid = correctionGrid(machine, errors, {{31, 21, 26}, {}});
  const OneAxisReduction r = reduceToOneAxisFunctions(grid, 9);
  const auto reversal = axisReversalTables(*machine, grid, trimsOf(machine, errors, grid), {});
  ASSERT_EQ(reversal.size(), 3u);
  const auto tables = readCecTables(siemensCecTables(r.functions, reversal, machine->describePose(grid.pose)));
  ASSERT_EQ(tables.size(), r.functions.size() + 6);
  const auto& forwardX = tables.at(static_cast<int>(r.functions.size())), &reverseX = tables.at(static_cast<int>(r.functions.size()) + 1);
  EXPECT_EQ(forwardX.input, "X");
  EXPECT_EQ(forwardX.output, "X");
  EXPECT_EQ(forwardX.direction, 1);
  EXPECT_EQ(reverseX.direction, -1);
  for (size_t n = 0; n < forwardX.values.size(); ++n) EXPECT_NEAR(forwardX.values[n] - reverseX.values[n], 0.003, 1e-6) << n;
  const double largest = largestMovingResidual(machine, errors, grid, [&](const std::vector<double>& q, const std::vector<int>& motion) {
    const Vec3 c = cecCorrection(tables, {q[0], q[1], q[2]}, motion);
    return std::vector<double>{q[0] + c.x(), q[1] + c.y(), q[2] + c.z()};
  });
  RecordProperty("largest_um", std::to_string(largest * 1e3));
  EXPECT_LT(largest, 1e-5);
  // Beside the LEC (each axis's own function, read back below), the same tables alone.
  OneAxisReduction own = r;
  std::erase_if(own.functions, [](const AxisFunction& f) { return f.input != f.output; });
  const auto alone = readCecTables(siemensCecTables({}, reversal, ""));
  ASSERT_EQ(alone.size(), 6u);
  EXPECT_LT(largestMovingResidual(machine, errors, grid, [&](const std::vector<double>& q, const std::vector<int>& motion) {
              const Vec3 p(q[0], q[1], q[2]), c = own.correction(p) + cecCorrection(alone, p, motion);
              return std::vector<double>{q[0] + c.x(), q[1] + c.y(), q[2] + c.z()};
            }), 1e-5);
}

// Siemens LEC (840D sl function manual K3, 4.4): per axis $AA_ENC_COMP[e, N, axis] and
// $AA_ENC_COMP_STEP, _MIN, _MAX, _IS_MODULO [e, axis] in %_N_AX_EEC_INI, ending with M17; a positive
// value moves the axis negative (808D function manual, LEC), the first and last values hold beyond
// the table. Read back and applied so, it is each axis's own function.
TEST(SiemensLec, TablesReadBackAndInterpolateToEachAxisOwnFunction) {
  const auto setup = bundledSetup("three-axis-vertical");
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{9, 7, 5}, {}});
  OneAxisReduction own = reduceToOneAxisFunctions(grid, 9);
  std::erase_if(own.functions, [](const AxisFunction& f) { return f.input != f.output; });
  ASSERT_EQ(own.functions.size(), 3u);
  std::istringstream file(siemensLecTables(own.functions, *setup.machine, {}, setup.machine->describePose(grid.pose)));
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line, "%_N_AX_EEC_INI");
  struct Table {
    double step = 0, min = 0, max = 0;
    std::vector<double> values;
  };
  std::map<std::string, Table> tables;
  const std::regex field(R"(\$AA_ENC_COMP_(\w+)\[0,(\w+)\]=(\S+))"), value(R"(\$AA_ENC_COMP\[0,(\d+),(\w+)\]=(\S+))");
  std::vector<std::string> others;
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with(";")) continue;
    if (std::regex_match(line, m, value)) {
      auto& t = tables[m[2]];
      ASSERT_EQ(static_cast<size_t>(std::stoi(m[1])), t.values.size());
      t.values.push_back(std::stod(m[3]));
    } else if (std::regex_match(line, m, field)) {
      auto& t = tables[m[2]];
      const std::string name = m[1];
      if (name == "STEP") t.step = std::stod(m[3]);
      else if (name == "MIN") t.min = std::stod(m[3]);
      else if (name == "MAX") t.max = std::stod(m[3]);
      else EXPECT_TRUE(name == "IS_MODULO" && m[3] == "0") << line;
    } else {
      others.push_back(line);
    }
  }
  EXPECT_EQ(others, (std::vector<std::string>{"CHANDATA(1)", "M17"}));
  ASSERT_EQ(tables.size(), 3u);
  const char* names[3] = {"X", "Y", "Z"};
  auto controller = [&](const Vec3& p) {
    Vec3 c;
    for (int a = 0; a < 3; ++a) {
      const Table& t = tables.at(names[a]);
      const double u = std::clamp((p[a] - t.min) / t.step, 0.0, static_cast<double>(t.values.size() - 1));
      const auto k = std::min(static_cast<size_t>(u), t.values.size() - 2);
      c[a] = -(t.values[k] + (u - static_cast<double>(k)) * (t.values[k + 1] - t.values[k]));
    }
    return c;
  };
  std::mt19937 rng(7);
  for (int s = 0; s < 100; ++s) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = std::uniform_real_distribution<double>(grid.start[a] - 10.0, grid.node(a, grid.counts[a] - 1) + 10.0)(rng);
    EXPECT_LE((controller(p) - own.correction(p)).norm(), 2e-7);  // 7 decimals
  }
  for (const auto& [axis, t] : tables) EXPECT_NEAR(t.min + t.step * static_cast<double>(t.values.size() - 1), t.max, 1e-5) << axis;
  EXPECT_NE(test::thrown<InputError>([&] { siemensLecTables({AxisFunction{0, 1, {0.0, 1.0}, {0.0, 0.0}}}, *setup.machine, {}, ""); })->reason().find("own command"),
            std::string::npos);
}

// The rotary axes' own corrections (issue 45, item 3) in the LEC file, in degrees by the machine
// file's names, C modulo over the turn, and as LinuxCNC COMP_FILEs on the rotary joints (degrees,
// the forward and reverse columns differing by B's reversal): both read back to the tables.
TEST(SiemensLec, RotaryAxesOwnCorrectionsReadBackInDegrees) {
  const auto machine = bundledSetup("tilting-table").machine;
  const ErrorModel own = parseErrors(*machine, "errors:\n  C.zero: -20 urad\n  EBB: {harmonics: {period: 360 deg, terms: [{order: 1, "
                                               "amplitude: 8 urad}]}, reversal: 6 urad}\n", "own.yaml");
  const std::vector<double> pose(static_cast<size_t>(machine->commandedCount()), 0.0);
  const auto rotary = rotaryPositioning(machine, own, pose);
  ASSERT_EQ(rotary.size(), 2u);
  std::istringstream file(siemensLecTables({}, *machine, rotary, machine->describePose(pose)));
  std::map<std::string, std::vector<double>> values;
  std::map<std::string, std::string> fields;
  const std::regex field(R"(\$AA_ENC_COMP_(\w+)\[0,(\w+)\]=(\S+))"), value(R"(\$AA_ENC_COMP\[0,(\d+),(\w+)\]=(\S+))");
  std::string line;
  while (std::getline(file, line)) {
    std::smatch m;
    if (std::regex_match(line, m, value)) values[m[2]].push_back(std::stod(m[3]));
    else if (std::regex_match(line, m, field)) fields[std::string(m[1]) + m[2].str()] = m[3];
  }
  for (const auto& t : rotary) {
    const std::string name = machine->axes[static_cast<size_t>(t.axis)].name;
    ASSERT_EQ(values[name].size(), t.positions.size()) << name;
    for (size_t n = 0; n < t.positions.size(); ++n) EXPECT_NEAR(-values[name][n] * kDeg, t.standing[n], 1e-7 * kDeg) << name << n;
    EXPECT_NEAR(std::stod(fields["MIN" + name]), t.positions.front() / kDeg, 1e-6);
    EXPECT_NEAR(std::stod(fields["MAX" + name]), t.positions.back() / kDeg, 1e-6);
    EXPECT_EQ(fields["IS_MODULO" + name], name == "C" ? "1" : "0");
    std::istringstream comp(linuxcncCompFile(t, 1));
    size_t n = 0;
    double position, forward, reverse, largestReversal = 0.0;
    while (comp >> position >> forward >> reverse) {
      ASSERT_LT(n, t.positions.size());
      EXPECT_NEAR(position * kDeg, t.positions[n], 1e-6 * kDeg);
      EXPECT_NEAR(forward * kDeg, t.forward[n], 1e-9 * kDeg);
      EXPECT_NEAR(reverse * kDeg, t.reverse[n], 1e-9 * kDeg);
      largestReversal = std::max(largestReversal, std::abs(forward - reverse) * kDeg);
      ++n;
    }
    EXPECT_EQ(n, t.positions.size());
    EXPECT_NEAR(largestReversal, name == "B" ? 6e-6 : 0.0, 1e-9) << name;
  }
}

}  // namespace
}  // namespace mtacc
