// Compensated NC programs (issue 17, item 2): the G-code reader, and the ballbar, cone-frustum
// and cubic-test programs compensated, written, read back and run on the machine with its
// errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <numbers>

#include "mtacc/compensation/program_compensation.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/cone_program.hpp"
#include "mtacc/io/cubic_program.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"
#include "mtacc/procedures/cone.hpp"
#include "mtacc/procedures/cubic_test.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

MachineSetup bundledSetup(const std::string& name) { return loadMachineSetup({name, "", "", std::nullopt, ""}); }

// The acceptance of issue 17: the compensated program, written as G-code and read back (its
// rounding to 5 decimals included), run on the machine with its errors, leaves at most 5 % of
// the program's own deviation from its nominal path.
ProgramDeviation compensatedAndReadBack(const MachineSetup& setup, const std::string& text, const std::string& name) {
  const GcodeProgram program = parseGcodeProgram(text, name, *setup.machine);
  const CompensatedProgram compensated = compensateProgram(setup.machine, setup.errors, program);
  EXPECT_EQ(compensated.notConverged, 0) << name;
  EXPECT_TRUE(compensated.travelViolation.empty()) << compensated.travelViolation;
  const std::string written = compensatedGcode(*setup.machine, program, compensated, "test");
  const GcodeProgram readBack = parseGcodeProgram(written, name + " compensated", *setup.machine);
  EXPECT_EQ(readBack.moves.size() + 1, compensated.points.size()) << name;
  std::vector<CompensatedPoint> points = compensated.points;
  for (size_t i = 1; i < points.size() && i - 1 < readBack.moves.size(); ++i) points[i].q.assign(readBack.moves[i - 1].to.begin(), readBack.moves[i - 1].to.end());
  const ProgramDeviation d = programDeviation(setup.machine, setup.errors, program, points);
  std::cout << name << ": " << program.moves.size() << " moves, " << readBack.moves.size() << " written; largest TCP deviation "
            << d.before.maxPosition * 1e3 << " um as written, " << d.after.maxPosition * 1e3 << " um compensated; direction "
            << d.before.maxDirection * 1e6 << " -> " << d.after.maxDirection * 1e6 << " urad\n";
  EXPECT_GT(d.before.maxPosition, 1e-3) << name << ": the errors must matter for the test to say anything";
  EXPECT_LE(d.after.maxPosition, 0.05 * d.before.maxPosition) << name;
  return d;
}

// ISO 230-4 ballbar circles, radius 100 mm, in the three planes and both directions, as G2/G3
// full circles (I, J, K centre offsets).
std::string ballbarProgram() {
  return "(ballbar circles, ISO 230-4, r = 100 mm)\n"
         "G21 G90 G17\n"
         "G0 X400 Y200 Z250\n"
         "G2 X400 Y200 I-100 F1000\n"
         "G3 X400 Y200 I-100\n"
         "G18 G0 X300 Y200 Z350\n"
         "G2 X300 Z350 K-100\n"
         "G3 X300 Z350 K-100\n"
         "G19 G0 X300 Y300 Z250\n"
         "G2 Y300 Z250 J-100\n"
         "G3 Y300 Z250 J-100\n"
         "M30\n";
}

TEST(ProgramCompensation, BallbarCirclesInThreePlanesOnTheThreeAxisMachine) {
  const auto d = compensatedAndReadBack(bundledSetup("three-axis-vertical"), ballbarProgram(), "ballbar circles");
  EXPECT_EQ(d.after.samples, d.before.samples);
}

TEST(ProgramCompensation, BallbarCircleOnTheMahoWithItsTablesAndStiffness) {
  auto setup = bundledSetup("maho");
  const std::string circle = "G21 G90 G17\nG0 X350 Y250 Z300 B0 C0\nG2 X350 Y250 I-100 F1000\nM30\n";
  compensatedAndReadBack(setup, circle, "Maho ballbar circle");
}

TEST(ProgramCompensation, ConeFrustumProgramOnTheTiltingTable) {
  const auto setup = bundledSetup("tilting-table");
  const ConeSpec spec;
  const ConePath path = conePath(spec, 720);
  const auto motion = coneMotion(setup.nominal(), spec, path);
  compensatedAndReadBack(setup, coneNcProgram(*setup.machine, spec, motion.q, 500.0), "cone frustum");
}

TEST(ProgramCompensation, CubicMachiningTestProgramOnTheTiltingTable) {
  const auto setup = bundledSetup("tilting-table");
  const auto spec = loadCubicTest("seed001-cubic");
  compensatedAndReadBack(setup, cubicNcProgram(*setup.machine, spec, cubicToolPath(setup.nominal(), spec)), "cubic test");
}

TEST(GcodeReader, ArcByRadiusEqualsArcByCentre) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto byCentre = parseGcodeProgram("G0 X100 Y100 Z50\nG2 X200 Y100 I50 F500\n", "a.nc", *machine);
  const auto byRadius = parseGcodeProgram("G0 X100 Y100 Z50\nG2 X200 Y100 R50 F500\n", "b.nc", *machine);
  const auto larger = parseGcodeProgram("G0 X100 Y100 Z50\nG2 X200 Y100 R-60 F500\n", "c.nc", *machine);
  const GcodeMove &c = byCentre.moves[1], &r = byRadius.moves[1];
  EXPECT_NEAR(r.centre[0], 150.0, 1e-12);
  EXPECT_NEAR(r.centre[1], 100.0, 1e-12);
  EXPECT_NEAR(c.sweep, -std::numbers::pi, 1e-12);  // clockwise half circle through Y = 150
  EXPECT_NEAR(c.at(0.5)[1], 150.0, 1e-12);
  EXPECT_NEAR(r.at(0.5)[1], 150.0, 1e-12);
  EXPECT_LT(larger.moves[1].sweep, -std::numbers::pi);  // R < 0: the arc longer than half a circle
}

TEST(GcodeReader, IncrementalInchAndHelix) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto p = parseGcodeProgram("G20 G91\nG0 X1 Y1 Z1\nG1 X1 F10\nG3 X0 Y0 Z0.5 I0 J1\nG21 G90 G1 X10\n", "inch.nc", *machine);
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_NEAR(p.moves[1].to[0], 2 * 25.4, 1e-12);
  EXPECT_NEAR(p.moves[1].feed, 254.0, 1e-12);
  EXPECT_NEAR(p.moves[2].sweep, 2 * std::numbers::pi, 1e-12);  // full circle, rising 0.5 in
  EXPECT_NEAR(p.moves[2].at(0.5)[2], 1.25 * 25.4, 1e-12);
  EXPECT_NEAR(p.moves[3].to[0], 10.0, 1e-12);
}

// Every way a coordinate is written (signs, leading and trailing zeros, no whole part, no
// fraction, up to 20 digits after the point) reads as the correctly rounded value strtod gives.
TEST(GcodeReader, NumbersReadCorrectlyRounded) {
  const auto machine = test::bundled("tilting-table");
  std::mt19937 random(17);
  std::uniform_int_distribution<int> digit(0, 9), length(0, 20), form(0, 5);
  std::vector<std::string> written;
  std::string program = "G1 F100\n";
  for (int n = 0; n < 20000; ++n) {
    std::string number = form(random) == 0 ? "-" : form(random) == 0 ? "+" : "";
    const int whole = std::uniform_int_distribution<int>(0, 3)(random);
    number += std::to_string(std::uniform_int_distribution<int>(0, 399)(random)).substr(0, static_cast<size_t>(std::max(whole, 1)));
    if (whole == 0 && form(random) < 2) number.pop_back();  // ".5"
    if (form(random) > 0) {
      number += '.';
      for (int k = length(random); k > 0; --k) number += static_cast<char>('0' + digit(random));
    }
    if (number.find_first_of("0123456789") == std::string::npos) number += '0';
    written.push_back(number);
    program += "X" + number + "\n";
  }
  const GcodeProgram p = parseGcodeProgram(program, "numbers.nc", *machine);
  ASSERT_EQ(p.moves.size(), written.size());
  for (size_t i = 0; i < written.size(); ++i) EXPECT_EQ(p.moves[i].to[0], std::strtod(written[i].c_str(), nullptr)) << written[i];
}

// A clockwise full circle from 3 o'clock: X and Y reverse at its quadrant points, each axis
// standing at the instant it reverses; a straight move has one direction throughout.
TEST(GcodeReader, DirectionsOfMotionAndReversalsAlongAnArc) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto p = parseGcodeProgram("G0 X200 Y100 Z50\nG2 X200 Y100 I-50 F500\nG1 X100 Y150\n", "circle.nc", *machine);
  const GcodeMove &circle = p.moves[1], &line = p.moves[2];
  const std::vector<double> quadrants = circle.reversals();
  ASSERT_EQ(quadrants.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(quadrants[static_cast<size_t>(k)], 0.25 * (k + 1), 1e-12);
  EXPECT_EQ(circle.motion(0.1), (std::vector<int>{-1, -1, 0}));  // going down on the right
  EXPECT_EQ(circle.motion(0.25), (std::vector<int>{-1, 0, 0}));  // at the bottom: Y stands
  EXPECT_EQ(circle.motion(0.4), (std::vector<int>{-1, 1, 0}));
  EXPECT_EQ(circle.motion(0.5), (std::vector<int>{0, 1, 0}));  // at the left: X stands
  EXPECT_EQ(circle.motion(0.9), (std::vector<int>{1, -1, 0}));
  EXPECT_TRUE(line.reversals().empty());
  EXPECT_EQ(line.motion(0.3), (std::vector<int>{-1, 1, 0}));
}

// X moves +X, then stands while Y moves: its backlash stays taken up on the + side (EXX
// reversal 2 um: +1 um), so the commands at the end equal the inverse error model with X moving
// +, 1 um of X away from X standing (no reversal).
TEST(ProgramCompensation, AnAxisStandingKeepsTheSideItLastMovedTo) {
  const auto setup = bundledSetup("three-axis-vertical");
  const auto p = parseGcodeProgram("G0 X100 Y100 Z50\nG1 X110 F500\nG1 Y120\nG1 Y140\n", "stand.nc", *setup.machine);
  const CompensatedProgram c = compensateProgram(setup.machine, setup.errors, p);
  // The start and the rapid's end, X's step as it sets off and its end, and the two ends of Y's
  // moves (Y has no reversal error: no step of no length as it sets off).
  ASSERT_EQ(c.points.size(), 6u);
  const auto actual = compile(setup.machine, setup.errors), nominal = compileNominal(setup.machine);
  const std::vector<double> end(p.moves.back().to.begin(), p.moves.back().to.end());
  const ToolPoint wanted = toolPoint(nominal, end.data());
  auto solvedWith = [&](std::vector<int> motion) {
    ErrorIkJacobian jacobian;
    return refineWithErrors(actual, wanted.position, wanted.direction, end, ProgramCompensationOptions{}.ik, jacobian, false, motion.data()).q[0];
  };
  EXPECT_NEAR(c.points.back().q[0], solvedWith({1, 1, 0}), 1e-6);
  EXPECT_NEAR(std::abs(solvedWith({0, 1, 0}) - solvedWith({1, 1, 0})), 1e-3, 1e-6);
}

// A rotary axis's step at its reversal is written where the five decimals in degrees show it:
// C's reversal of 2 urad (+-1 urad) on the tilting table steps C by 2 urad = 0.000115 deg as it
// turns back, X, Y, Z, B standing; the step is a point of its own at the same place.
TEST(ProgramCompensation, ARotaryAxisStepsAtItsReversalWhereTheDecimalsShowIt) {
  const auto machine = test::bundled("tilting-table");
  const ErrorModel errors = parseErrors(*machine, "errors:\n  ECC: {reversal: 2 urad}\n", "c.yaml", ErrorsKey::Required);
  const auto p = parseGcodeProgram("G0 X100 Y20 Z50 B-30 C0\nG1 C10 F1000\nG1 C5\n", "turn.nc", *machine);
  const CompensatedProgram c = compensateProgram(machine, errors, p);
  // The start, the rapid's end, C's step as it sets off, C's end, the step as it turns back, C's end.
  ASSERT_EQ(c.points.size(), 6u);
  const auto& before = c.points[3].q, &step = c.points[4].q;
  EXPECT_EQ(c.points[4].move, 2);
  EXPECT_EQ(c.points[4].s, 0.0);
  EXPECT_NEAR(std::abs(step[4] - before[4]), 2e-6, 1e-9);
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(step[k], before[k], 1e-9) << k;
}

// Issue 47: block numbers as far as SINUMERIK and HEIDENHAIN count them (2^31 - 1), kept as
// written on the compensated block's line.
TEST(GcodeReader, BlockNumbersRunAsFarAsTheControllersCount) {
  const auto setup = bundledSetup("three-axis-vertical");
  const auto p = parseGcodeProgram("N99990 G0 X10 Y10 Z50\nN100010 G1 X20 F300\nN2147483647 G1 X30\n", "numbered.nc", *setup.machine);
  const std::string out = compensatedGcode(*setup.machine, p, compensateProgram(setup.machine, setup.errors, p), "header");
  for (const char* number : {"\nN99990 G0 X", "\nN100010 G1 X", "\nN2147483647 G1 X"}) EXPECT_NE(out.find(number), std::string::npos) << out;
  EXPECT_THROW(parseGcodeProgram("N2147483648 G0 X10\n", "numbered.nc", *setup.machine), InputError);
  EXPECT_THROW(parseGcodeProgram("G0 X100001\n", "numbered.nc", *setup.machine), InputError);  // an axis word keeps its bound
}

// Issue 52: the travel check of the compensated commands, stated directly (the corpus has a
// case too). X's zero offset of -5 um moves every X command +5 um: a move ending at X's upper
// limit (600 mm) is written beyond it, and the first such point's line is named; 5 um short of
// the limit it stays inside.
TEST(ProgramCompensation, ACompensatedCommandBeyondTravelIsFoundWithItsLine) {
  const auto machine = test::bundled("three-axis-vertical");
  const ErrorModel errors = parseErrors(*machine, "errors:\n  X0X: -5 um\n", "offset.yaml", ErrorsKey::Required);
  const auto beyond = parseGcodeProgram("G0 X100 Y100 Z50\nG1 X300 F500\nG1 X600\n", "limit.nc", *machine);
  const CompensatedProgram c = compensateProgram(machine, errors, beyond);
  EXPECT_NE(c.travelViolation.find("X"), std::string::npos) << c.travelViolation;
  EXPECT_EQ(c.travelViolationLine, 3);
  const auto inside = parseGcodeProgram("G0 X100 Y100 Z50\nG1 X300 F500\nG1 X599.994\n", "limit.nc", *machine);
  EXPECT_EQ(compensateProgram(machine, errors, inside).travelViolation, "");
}

TEST(GcodeReader, KeptWordsAndCommentsStayInPlace) {
  const auto setup = bundledSetup("three-axis-vertical");
  const auto p = parseGcodeProgram("%\nO100 (part 7)\nN10 G0 X10 Y10 Z10 M3 S1000\nN20 G1 X20 F300 M30 ; end\n%\n", "kept.nc", *setup.machine);
  const std::string out = compensatedGcode(*setup.machine, p, compensateProgram(setup.machine, setup.errors, p), "header");
  EXPECT_TRUE(out.starts_with("%\n(header)\nG21 G90\nO100 (part 7)\nN10 M3 S1000 G0 X")) << out;
  // X sets off in +X after standing: the first written point steps by the reversal's half (EXX
  // reversal 2 um) on N20's line, then the move; the stop after the motion, the comment kept.
  EXPECT_NE(out.find("\nN20 G1 X10.00130 "), std::string::npos) << out;
  EXPECT_TRUE(out.ends_with(" M30 ; end\n%\n")) << out;
}

// The writer's words: each axis with five decimals as fmt's "{:.5f}" writes it (rotary axes in
// degrees), a value that rounds to zero without its sign, and values beyond the fast path (1e12)
// as fmt writes them. Random values away from a rounding tie (v * 1e5 within 1e-4 of a half)
// match fmt character for character.
TEST(GcodeWriter, AxisWordsWithFiveDecimals) {
  const auto machine = test::bundled("tilting-table");
  const auto program = parseGcodeProgram("G0 X0 Y0 Z0 B0 C0\n", "words.nc", *machine);
  CompensatedProgram points;
  points.points.push_back({0, 0.0, {0, 0, 0, 0, 0}});
  points.points.push_back({0, 1.0, {-0.000001, 123.456789, -98765.4321, -0.5, 1e12}});
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1000.0, 1000.0);
  std::vector<double> drawn;
  while (drawn.size() < 2000) {
    const double v = value(random), scaled = std::abs(v) * 1e5;
    if (std::abs(scaled - std::floor(scaled) - 0.5) > 1e-4) drawn.push_back(v);
  }
  for (const double v : drawn) points.points.push_back({0, 1.0, {v, 0, 0, 0, 0}});
  const std::string out = compensatedGcode(*machine, program, points, "");
  const auto lines = splitList(out, '\n');
  ASSERT_EQ(lines.size(), 2 + drawn.size());  // "G21 G90", the first point, the drawn ones
  EXPECT_EQ(lines[1], fmt::format("G0 X0.00000 Y123.45679 Z-98765.43210 B{:.5f} C{:.5f}", -0.5 / kDeg, 1e12 / kDeg));
  for (size_t i = 0; i < drawn.size(); ++i)
    EXPECT_EQ(lines[2 + i], fmt::format("G0 X{:.5f} Y0.00000 Z0.00000 B0.00000 C0.00000", drawn[i])) << drawn[i];
}

TEST(GcodeReader, ToolLengthMovesTheCompensatedPoint) {
  const auto setup = bundledSetup("three-axis-vertical");
  const std::string text = "G43 H2\nG0 X0 Y10 Z100\nG1 X500 F500\n";
  EXPECT_NE(test::thrown<InputError>([&] { parseGcodeProgram(text, "t.nc", *setup.machine); })->reason().find("length of tool 2"),
            std::string::npos);
  const auto shortTool = parseGcodeProgram(text, "t.nc", *setup.machine, {{}, {{2, 0.0}}});
  const auto longTool = parseGcodeProgram(text, "t.nc", *setup.machine, {{}, {{2, 100.0}}});
  EXPECT_EQ(longTool.moves[1].toolLength, 100.0);
  const auto a = compensateProgram(setup.machine, setup.errors, shortTool), b = compensateProgram(setup.machine, setup.errors, longTool);
  // A longer tool sees the pitch of X (EBX, 12.5 urad at X = 500) over a 100 mm longer arm: its
  // X correction differs by 1.25 um.
  EXPECT_NEAR(std::abs(a.points.back().q[0] - b.points.back().q[0]), 100.0 * 12.5e-6, 1e-6);
}

// Each bad program: the message names the file and line.
TEST(GcodeReader, BadProgramsAreLocated) {
  const auto machine = test::bundled("three-axis-vertical");
  const std::pair<const char*, const char*> cases[] = {
      {"G0 X1\nG1 X2 Q5 F100\n", "the word Q is not supported"},
      {"G0 X0 Y0\nG2 X10 Y0 I4 F100\n", "inconsistent arc"},
      {"G0 X1\nG1 X2\n", "before any feed"},
      {"G0 X1\nG0 G1 X2 F100\n", "two motion G codes"},
      {"G0 X1\nX2 X3\n", "given twice"},
      {"G0 X1\nG2 X2 F100\n", "centre (I, J, K) or its radius"},
      {"G0 X1\nG1 X2 I1 F100\n", "arc words without an arc"},
      {"G0 X1\nG43.4 X2\n", "G43.4 is not supported"},
      {"G0 X1\nG1 A10 F100\n", "has no axis A"},
      {"G0 X1\nG1 X1..2 F100\n", "is not a word"},
      {"G0 X1\nG1 X2 F100 (open\n", "not closed"},
      {"G0 X1\nG2 X2 R0.1 F100\n", "shorter than half the chord"},
      {"G0 X1\nG1 X9000 F100\n", "beyond travel"},
      {"G0 X1\nG1 X2 F-5\n", "feed must be positive"},
  };
  for (const auto& [program, why] : cases) {
    const char* text = program;
    const auto e = test::thrown<InputError>([&] { parseGcodeProgram(text, "bad.nc", *machine); });
    ASSERT_TRUE(e) << text;
    EXPECT_EQ(e->where().file, "bad.nc");
    EXPECT_EQ(e->where().line, 2) << text;
    EXPECT_NE(e->reason().find(why), std::string::npos) << text << " -> " << e->reason();
  }
}

}  // namespace
}  // namespace mtacc
