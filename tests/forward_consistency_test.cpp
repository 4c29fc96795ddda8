// The fast TCP evaluation (point and direction carried factor by factor) and the full pose
// composition evaluate the same chain: they agree to rounding on every bundled machine with
// location errors and every kind of component error, for both workpiece alignments.
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
