// A rotary axis's zero offset about its own line ("B.zero", docs/conventions.md): the axis
// commanded to q stands at q + B.zero, on axes along a machine axis and inclined ones, on the
// tool side and on the table; setting it keeps the line's turn across its direction; an errors
// file may name it.
#include <gtest/gtest.h>

#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

class ZeroOffsetAllMachines : public ::testing::TestWithParam<const char*> {};

// First order in the offset: the difference is of order |t| offset^2 (1e3 mm x 1e-10 = 1e-7 mm).
TEST_P(ZeroOffsetAllMachines, IsThePositionTheAxisTakesWhenCommanded) {
  const auto machine = test::bundled(GetParam());
  const auto nominal = compileNominal(machine);
  std::mt19937 rng(5);
  const double offset = 1e-5;
  for (int a = 0; a < static_cast<int>(machine->axes.size()); ++a) {
    const Axis& axis = machine->axes[static_cast<size_t>(a)];
    if (!axis.isRotary() || !axis.commanded()) continue;
    ErrorModel errors = ErrorModel::zero(*machine);
    setParameterValue(errors, findParameter(*machine, errors, axis.name + ".zero"), offset);
    const auto actual = compile(machine, errors);
    for (int trial = 0; trial < 4; ++trial) {
      const auto q = test::randomPose(*machine, rng);
      auto turned = q;
      turned[static_cast<size_t>(machine->commandedAxisIndex(axis.name))] += offset;
      const Pose withError = toolInWorkpiece(actual, q.data()), commanded = toolInWorkpiece(nominal, turned.data());
      EXPECT_LE((withError.translation() - commanded.translation()).norm(), 1e-7) << axis.name << " " << machine->describePose(q);
      EXPECT_LE((withError.linear() - commanded.linear()).norm(), 1e-9) << axis.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, ZeroOffsetAllMachines, ::testing::ValuesIn(test::kFiveAxisMachines), test::MachineName());

TEST(ZeroOffset, InclinedAxisCombinesTheMachineRotationsAndKeepsTheCrossTurn) {
  const auto machine = test::bundled("inclined-a-table");  // A along (1, 0, 1)/sqrt(2), a table axis
  ErrorModel errors = ErrorModel::zero(*machine);
  const Parameter b0a = findParameter(*machine, errors, "B0A"), zero = findParameter(*machine, errors, "A.zero");
  EXPECT_EQ(zero.kind, ParameterKind::ZeroOffset);
  EXPECT_NEAR((zero.turn - Vec3(-1, 0, -1) / std::sqrt(2.0)).norm(), 0.0, 1e-15);  // the table turns the other way
  setParameterValue(errors, b0a, 3e-6);  // across the line: A.zero stays 0
  EXPECT_DOUBLE_EQ(parameterValue(errors, zero), 0.0);
  setParameterValue(errors, zero, 8e-6);
  EXPECT_NEAR(parameterValue(errors, zero), 8e-6, 1e-20);
  EXPECT_NEAR(parameterValue(errors, b0a), 3e-6, 1e-20);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "A0A")), -8e-6 / std::sqrt(2.0), 1e-20);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "C0A")), -8e-6 / std::sqrt(2.0), 1e-20);
}

TEST(ZeroOffset, LinearAxisZeroIsItsOwnSlotAndErrorsFilesNameIt) {
  const auto machine = test::bundled("swivel-head-table");
  const ErrorModel none = ErrorModel::zero(*machine);
  EXPECT_EQ(findParameter(*machine, none, "Y.zero").name, "Y0Y");
  const ErrorModel e = parseErrors(*machine, "errors:\n  B0B: 4 urad\n  B.zero: 6 urad\n  C.zero: 2 urad\n", "zero.yaml");
  EXPECT_NEAR(parameterValue(e, findParameter(*machine, e, "B0B")), 10e-6, 1e-18);  // B along +Y, tool side: adds
  EXPECT_NEAR(parameterValue(e, findParameter(*machine, e, "C0C")), -2e-6, 1e-18);  // C a table: C.zero = -C0C
  try {
    findParameter(*machine, none, "Q.zero");
    FAIL() << "Q.zero accepted";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("B.zero C.zero"), std::string::npos) << err.what();
  }
}

}  // namespace
}  // namespace mtacc
