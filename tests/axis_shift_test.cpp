// The axis-shift convention for a rotary axis's radial error motion (errors/axis_shift.hpp): a
// shift t of the axis line is, by its meaning, the nominal machine with the axis line through a
// point moved by t (its `location`; the workpiece and tool frames stay where they are at home).
// The converted ISO translations must give that machine's tool pose at every pose: constant
// shifts on every rotary axis of every bundled machine, and a harmonic shift against the moved
// line at each pose.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

const char* kRotaryMachines[] = {"tilting-table", "swivel-head-table", "double-pivot-head", "inclined-a-table", "multitasking-b-c"};

double poseDifference(const KinematicModel& a, const KinematicModel& b, const std::vector<double>& q) {
  return poseError(toolInWorkpiece(a, q.data()), toolInWorkpiece(b, q.data())).norm();
}

// The nominal machine with axis k's line through location + t (t in the axis frame, mm).
KinematicModel lineMoved(const Machine& machine, size_t k, const Vec3& t) {
  auto moved = std::make_shared<Machine>(machine);
  moved->axes[k].location += t;
  return compileNominal(moved);
}

class AxisShift : public ::testing::TestWithParam<const char*> {};

TEST_P(AxisShift, AConstantShiftMovesTheAxisLine) {
  const auto machine = test::bundled(GetParam());
  std::mt19937_64 rng(7);
  int compared = 0;
  for (size_t k = 0; k < machine->axes.size(); ++k) {
    const Axis& axis = machine->axes[k];
    if (!axis.isRotary()) continue;
    for (int j = 0; j < 3; ++j) {
      const auto shifted = compile(machine, parseErrors(*machine, fmt::format("errors:\n  E{}{}: {{constant: 10 um, convention: axis-shift}}\n",
                                                                             "XYZ"[j], axis.name), "shift"));
      const auto moved = lineMoved(*machine, k, 10e-3 * Vec3::Unit(j));
      for (int p = 0; p < 20; ++p) {
        const auto q = test::randomPose(*machine, rng);
        EXPECT_LT(poseDifference(shifted, moved, q), 1e-12) << axis.name << " along " << "XYZ"[j];
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

TEST_P(AxisShift, AHarmonicShiftMovesTheAxisLineByItsValueAtEachPose) {
  const auto machine = test::bundled(GetParam());
  std::mt19937_64 rng(11);
  for (size_t k = 0; k < machine->axes.size(); ++k) {
    const Axis& axis = machine->axes[k];
    if (!axis.isRotary() || !axis.commanded()) continue;  // a spindle stands at 0: the constant test covers it
    // Two components at once: period 180 deg (order 2 per turn) with a zero and a phase, and a sine part.
    const auto shifted = compile(machine, parseErrors(*machine, fmt::format(
        "errors:\n"
        "  EX{0}: {{harmonics: {{period: 180 deg, zero: 10 deg, terms: [{{order: 1, amplitude: 10 um, phase: 20 deg}}]}}, convention: axis-shift}}\n"
        "  EZ{0}: {{harmonics: {{period: 360 deg, zero: 0 deg, terms: [{{order: 3, amplitude: 4 um, part: sine}}]}}, convention: axis-shift}}\n",
        axis.name), "shift"));
    for (int p = 0; p < 20; ++p) {
      const auto q = test::randomPose(*machine, rng);
      const double a = q[k];
      const Vec3 t(10e-3 * std::cos(2 * (a - 10 * kDeg) + 20 * kDeg), 0.0, 4e-3 * std::cos(3 * a - 0.5 * kPi));
      EXPECT_LT(poseDifference(shifted, lineMoved(*machine, k, t), q), 1e-12) << axis.name << " at " << a / kDeg << " deg";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BundledMachines, AxisShift, ::testing::ValuesIn(kRotaryMachines), test::MachineName());

TEST(AxisShiftInput, OnlyConstantsAndHarmonicsOfATurnOnARotaryAxisTranslation) {
  const auto machine = test::bundled("tilting-table");
  auto parse = [&](const std::string& entry) { parseErrors(*machine, "errors:\n  " + entry + "\n", "e.yaml"); };
  EXPECT_THROW(parse("EXX: {constant: 1 um, convention: axis-shift}"), InputError);  // a linear axis
  EXPECT_THROW(parse("EAC: {constant: 1 urad, convention: axis-shift}"), InputError);  // a rotation
  EXPECT_THROW(parse("EXC: {linear: {value: 1 um, over: 90 deg}, convention: axis-shift}"), InputError);
  EXPECT_THROW(parse("EXC: {harmonics: {period: 70 deg, terms: [{order: 1, amplitude: 1 um}]}, convention: axis-shift}"), InputError);
  EXPECT_THROW(parse("EXC: [{constant: 1 um, convention: axis-shift}]"), InputError);
  const auto e = test::thrown<InputError>([&] { parse("EXC: {constant: 1 um, convention: shifted}"); });
  ASSERT_TRUE(e);
  EXPECT_NE(std::string(e->what()).find("errors.EXC.convention"), std::string::npos) << e->what();
  EXPECT_NO_THROW(parse("EXC: {constant: 1 um, convention: translation}"));
}

}  // namespace
}  // namespace mtacc
