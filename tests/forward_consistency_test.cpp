// The fast TCP evaluation (point and direction carried factor by factor) and the full pose
// composition evaluate the same chain: they agree to rounding on every bundled machine with
// location errors and every kind of component error, for both workpiece alignments; so do the
// TCP alone and the TCP with the workpiece's rotation.
#include <gtest/gtest.h>

#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

ErrorModel richErrors(const Machine& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ErrorModel e = ErrorModel::zero(m);
  for (const auto& p : parameterCatalogue(m, e))
    setParameterValue(e, p, p.dimension == Dimension::Length ? 0.02 * u(rng) : 1e-4 * u(rng));
  for (size_t a = 0; a < m.axes.size(); ++a) {
    const Axis& axis = m.axes[a];
    const double lo = axis.travel ? axis.travel->min : 0.0, hi = axis.travel ? axis.travel->max : 2 * kPi;
    for (int c = 0; c < 6; ++c) {
      const double s = c < 3 ? 0.005 : 2e-5;
      auto& f = e.axes[a].motion[static_cast<size_t>(c)];
      f.add(PolynomialTerm{lo, hi - lo, {s * u(rng), s * u(rng), s * u(rng)}});
      f.add(HarmonicTerm{hi - lo, lo, 2, s * u(rng), u(rng)});
      f.add(ReversalTerm{s * u(rng)});
      f.add(TableTerm({lo, lo + 0.3 * (hi - lo), hi}, {s * u(rng), s * u(rng), s * u(rng)}, Interpolation::CubicSpline));
      f.add(TableTerm({lo, 0.5 * (lo + hi), hi}, {s * u(rng), s * u(rng), s * u(rng)}, Interpolation::Linear));
    }
  }
  return e;
}

class ForwardConsistency : public ::testing::TestWithParam<const char*> {};

TEST_P(ForwardConsistency, ToolPointEqualsPoseComposition) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto alignment : {WorkpieceAlignment::Table, WorkpieceAlignment::Machine}) {
    auto machine = std::make_shared<Machine>(loadMachine(GetParam()));
    machine->alignment = alignment;
    const auto model = compile(machine, richErrors(*machine, rng));
    for (int trial = 0; trial < 200; ++trial) {
      const auto q = test::randomPose(*machine, rng);
      std::vector<int> dir(q.size());
      for (auto& d : dir) d = static_cast<int>(3 * u(rng)) - 1;
      const ToolPoint fast = toolPoint(model, q.data(), dir.data());
      const Pose full = toolInWorkpiece(model, q.data(), dir.data());
      EXPECT_LT((fast.position - full.translation()).norm(), 1e-10);
      EXPECT_LT((fast.direction - full.linear() * machine->toolDirection).norm(), 1e-13);
      EXPECT_LT((toolPosition(model, q.data(), dir.data()) - full.translation()).norm(), 1e-10);
      const auto fused = toolPositionAndWorkpieceRotation(model, q.data(), dir.data());
      EXPECT_LT((fused.position - full.translation()).norm(), 1e-10);
      EXPECT_LT((fused.workpieceRotation - workpiecePose(model, q.data(), dir.data()).linear()).norm(), 1e-13);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, ForwardConsistency,
                         ::testing::Values("tilting-table", "swivel-head-table", "double-pivot-head", "inclined-a-table",
                                           "multitasking-b-c", "maho", "three-axis-vertical"),
                         test::MachineName());

TEST(ForwardConsistency, BatchOnTwoThreadsEqualsOneThread) {
  const auto machine = test::bundled("tilting-table");
  const auto model = compile(machine, loadMachineErrors(*machine));
  JointMatrix q(5000, 5);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (long i = 0; i < q.rows(); ++i) q.row(i) << 300 * u(rng), 200 * u(rng), 200 * u(rng), 1.5 * u(rng), 3 * u(rng);
  ToolPointBatch one, two;
  toolPoints(model, {q, {}}, one, 1);
  toolPoints(model, {q, {}}, two, 2);
  EXPECT_EQ(one.positions, two.positions);
  EXPECT_EQ(one.directions, two.directions);
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

// The compiled model groups harmonic terms by frequency (integer multiples from the multiple-
// angle product) and folds polynomial and reversal terms: on a 3-axis machine the TCP's X
// deviation is EXX itself, which must equal ErrorFunction::value to rounding.
TEST(ForwardConsistency, CompiledComponentErrorsEqualTheErrorFunction) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto nominal = compileNominal(machine);
  const int x = machine->axisIndex("X");
  const double lo = machine->axes[static_cast<size_t>(x)].travel->min, range = machine->axes[static_cast<size_t>(x)].travel->max - lo;
  ErrorFunction f;
  for (const int order : {1, 2, 3, 5, 16, 17}) f.add(HarmonicTerm{2 * range, lo, order, 1e-3 / order, 0.3 * order});
  f.add(HarmonicTerm{2 * range / 3, lo, 1, 2e-4, 1.1});    // the third harmonic again, as seed 000's limits write it
  f.add(HarmonicTerm{range, lo + 7.0, 2, 3e-4, -0.4});     // another zero
  f.add(HarmonicTerm{30.0, 0.0, 1, 5e-4, 2.0, true});      // a pitch error
  f.add(PolynomialTerm{lo, range, {1e-3, -2e-3, 5e-4}});
  f.add(ReversalTerm{4e-3});
  f.add(ReversalTerm{-1e-3});
  auto errors = ErrorModel::zero(*machine);
  errors.axes[static_cast<size_t>(x)].motion[0] = f;
  const auto model = compile(machine, errors);
  auto unit = ErrorModel::zero(*machine);
  unit.axes[static_cast<size_t>(x)].motion[0].add(PolynomialTerm{0.0, 1.0, {1.0}});
  std::vector<double> q0(3, 0.0);
  const double sign = toolPoint(compile(machine, unit), q0.data()).position.x() - toolPoint(nominal, q0.data()).position.x();
  ASSERT_NEAR(std::abs(sign), 1.0, 1e-12);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const auto q = test::randomPose(*machine, rng);
    const std::vector<int> dir = {static_cast<int>(3 * u(rng)) - 1, 0, 0};
    const double deviation = toolPoint(model, q.data(), dir.data()).position.x() - toolPoint(nominal, q.data(), dir.data()).position.x();
    EXPECT_NEAR(deviation, sign * f.value(q[static_cast<size_t>(x)], dir[0]), 1e-12) << "X = " << q[static_cast<size_t>(x)];
  }
}

}  // namespace
}  // namespace mtacc
