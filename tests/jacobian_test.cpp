// The analytic parameter Jacobian against central finite differences of the exact model, for
// every parameter (location errors, the rotary axes' zero offsets and every coefficient of
// every component error function)
// at random poses, with non-zero errors present so that the linearisation point matters.
// Requirement: relative error <= 1e-6 per column and block (position, orientation). The
// comparison allows, on top, the rounding error of the finite difference itself
// (4 eps |value| / h), which matters only for columns that nearly vanish.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

void checkJacobian(std::shared_ptr<const Machine> machine, ErrorModel errors, int poses) {
  const auto nominal = compileNominal(machine);
  auto params = parameterCatalogue(*machine, errors);
  for (int a = 0; a < static_cast<int>(machine->axes.size()); ++a)  // the zero offsets too: B.zero, C.zero
    if (machine->axes[static_cast<size_t>(a)].isRotary() && machine->axes[static_cast<size_t>(a)].commanded())
      params.push_back(zeroOffsetParameter(*machine, a));
  const auto model = compile(machine, errors, params);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < poses; ++trial) {
    const auto q = test::randomPose(*machine, rng);
    std::vector<int> dir(q.size());
    for (auto& d : dir) d = u(rng) < 0.5 ? -1 : 1;
    const Pose nominalPose = toolInWorkpiece(nominal, q.data());
    const auto jac = parameterJacobian(model, nominal, q.data(), dir.data());
    for (size_t k = 0; k < params.size(); ++k) {
      const double h = params[k].dimension == Dimension::Length ? 1e-3 : 1e-5;
      const double v = parameterValue(errors, params[k]);
      auto errorAt = [&](double value) {
        ErrorModel e = errors;
        setParameterValue(e, params[k], value);
        return poseError(toolInWorkpiece(compile(machine, e), q.data(), dir.data()), nominalPose);
      };
      const Vec6 fd = (errorAt(v + h) - errorAt(v - h)) / (2 * h);
      const Vec6 an = jac.col(static_cast<Eigen::Index>(k));
      const double magnitude[2] = {nominalPose.translation().norm() + 1.0, 1.0};
      for (int block = 0; block < 2; ++block) {
        const double ref = fd.segment<3>(3 * block).norm();
        const double diff = (an.segment<3>(3 * block) - fd.segment<3>(3 * block)).norm();
        const double rounding = 4 * std::numeric_limits<double>::epsilon() * magnitude[block] / h;
        EXPECT_LE(diff, 1e-6 * ref + rounding)
            << params[k].name << " block " << block << " |fd| " << ref << " at " << machine->describePose(q);
      }
    }
  }
}

TEST(Jacobian, TiltingTableRealisticErrorsTableAlignment) {
  const auto machine = test::bundled("tilting-table");
  checkJacobian(machine, loadMachineErrors(*machine), 5);
}

TEST(Jacobian, TiltingTableRealisticErrorsMachineAlignment) {
  auto machine = std::make_shared<Machine>(loadMachine("tilting-table"));
  machine->alignment = WorkpieceAlignment::Machine;
  machine->referencePose = {10, -20, 30, 0, 0};
  checkJacobian(machine, loadMachineErrors(*machine), 5);
}

// Random location errors on every machine, plus motion errors of each kind on the Maho's
// fixed and moving frames.
class JacobianAllMachines : public ::testing::TestWithParam<const char*> {};

TEST_P(JacobianAllMachines, RandomLocationErrors) {
  const auto machine = test::bundled(GetParam());
  ErrorModel errors = ErrorModel::zero(*machine);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& p : parameterCatalogue(*machine, errors))
    setParameterValue(errors, p, p.dimension == Dimension::Length ? 0.02 * u(rng) : 1e-4 * u(rng));
  checkJacobian(machine, errors, 4);
}

INSTANTIATE_TEST_SUITE_P(Bundled, JacobianAllMachines, ::testing::ValuesIn(test::kFiveAxisMachines),
                         test::MachineName());

const char* kMahoMotionErrors = R"(
  zry: {linear: {value: 20 urad, over: 600 mm}, constant: 3 urad}
  zrx: {harmonics: {terms: [{order: 1, amplitude: 5 urad}]}}
  ztx: {reversal: 2 um}
  yrz: {table: {positions: [0 mm, 100 mm, 250 mm, 500 mm], values: [0 urad, 4 urad, -3 urad, 1 urad]}}
  xtx: {cyclic: {pitch: 39.6 mm, amplitude: 0.8 um}, polynomial: {scale: 700 mm, coefficients: [1 um, -3 um, 2 um]}}
  xrx: {table: {positions: [0 mm, 350 mm, 700 mm], values: [1 urad, -2 urad, 0 urad], interpolation: linear}}
  brz: 4 arcsec
  ctz: {harmonics: {terms: [{order: 2, amplitude: 1 um, phase: 30 deg}]}}
  X0B: 10 um
  A0C: 20 urad
)";

TEST(Jacobian, MahoMotionErrorsOnFixedAndMovingFrames) {
  const auto machine = test::bundled("maho");
  checkJacobian(machine, parseErrors(*machine, std::string("errors:") + kMahoMotionErrors, "maho-test"), 6);
}

// Stiffness changes are not parameters, but they are part of the factor every motion-error
// column is taken at: with changes on axes whose other components have parameters (xtx, xrx on
// X; yrz on Y), with and without the load, the columns stay exact.
TEST(Jacobian, MahoMotionErrorsWithStiffnessChanges) {
  const auto machine = test::bundled("maho");
  const std::string changes = R"(
  xry: {stiffness: {load: 260 kg, unit: arcsec, positions: [0 mm, 350 mm, 700 mm], values: [5.5, 0.4, 4.1]}}
  EAY: {stiffness: {load: 260 kg, with: X, unit: arcsec, positions: [0 mm, 500 mm], with_positions: [0 mm, 700 mm],
                    values: [[3, 3.2], [0.4, 0.5]]}}
  EBY: {stiffness: {with: X, unit: urad, positions: [0 mm, 500 mm], with_positions: [0 mm, 700 mm], values: [[-4, 4], [-1, 1]]}}
)";
  const auto errors = parseErrors(*machine, "workpiece_load: 400 kg\nerrors:" + std::string(kMahoMotionErrors) + changes, "maho-test");
  ASSERT_EQ(errors.stiffness.size(), 3u);
  checkJacobian(machine, errors, 4);
}

}  // namespace
}  // namespace mtacc
