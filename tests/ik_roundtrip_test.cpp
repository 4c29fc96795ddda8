// FK(IK(pose)) reproduces the pose on 10,000 random reachable poses of every bundled 5-axis
// machine (the inclined-axis machine included): random axis positions within travel give a
// reachable pose; every IK solution returned must map back onto it.
#include <gtest/gtest.h>

#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

class IkRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(IkRoundTrip, TenThousandRandomPoses) {
  const auto machine = test::bundled(GetParam());
  const auto model = compileNominal(machine);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int found = 0;
  double worstPosition = 0, worstDirection = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const auto q = test::randomPose(*machine, rng);
    const ToolPoint target = toolPoint(model, q.data());
    const auto result = inverseKinematics(model, target.position, target.direction);
    ASSERT_FALSE(result.solutions.empty());
    bool original = false;
    for (const auto& s : result.solutions) {
      const ToolPoint back = toolPoint(model, s.q.data());
      worstPosition = std::max(worstPosition, (back.position - target.position).norm());
      worstDirection = std::max(worstDirection, std::asin(std::min(1.0, back.direction.cross(target.direction).norm())));
      double d = 0;
      for (size_t i = 0; i < q.size(); ++i) d = std::max(d, std::abs(s.q[i] - q[i]));
      original = original || d < 1e-6;
    }
    found += original ? 1 : 0;
    EXPECT_TRUE(result.solutions.front().withinTravel) << machine->describePose(q);
  }
  EXPECT_LT(worstPosition, 1e-9);
  EXPECT_LT(worstDirection, 1e-12);
  // The generating pose is among the solutions except where a rotary angle is free.
  EXPECT_GT(found, 9990);
}

INSTANTIATE_TEST_SUITE_P(BundledFiveAxis, IkRoundTrip, ::testing::ValuesIn(test::kFiveAxisMachines),
                         test::MachineName());

TEST(IkRoundtrip, TiltingTableAtBZeroIsReportedAndKeepsTheHint) {
  const auto model = compileNominal(test::bundled("tilting-table"));
  IkOptions o;
  o.hint = std::vector<double>{0, 0, 0, 0, 0.7};
  const auto s = solveIk(model, Vec3(10, 20, 30), Vec3::UnitZ(), o);
  EXPECT_TRUE(s.singular);
  EXPECT_EQ(s.singularAxis, "C");
  EXPECT_NEAR(s.q[4], 0.7, 1e-12);
  EXPECT_NEAR(s.q[3], 0.0, 1e-12);
}

TEST(IkRoundtrip, PoseBeyondTravelIsRejectedWithTheAxis) {
  const auto model = compileNominal(test::bundled("tilting-table"));
  const auto beyond = test::thrown<UnreachablePose>([&] { solveIk(model, Vec3(1000, 0, 0), Vec3::UnitZ()); });
  ASSERT_TRUE(beyond);
  EXPECT_NE(std::string(beyond->what()).find("X=1000 mm beyond travel"), std::string::npos) << beyond->what();
  // A direction the B-C table cannot give the tool (tilt beyond B's travel of 120 deg).
  EXPECT_THROW(solveIk(model, Vec3(0, 0, 0), Vec3(0, 0, -1)), UnreachablePose);
  // One rotary axis cannot reach an arbitrary direction.
  EXPECT_THROW(inverseKinematics(compileNominal(test::bundled("three-axis-vertical")), Vec3(1, 1, 1), Vec3(1, 0, 1)),
               UnreachablePose);
}

}  // namespace
}  // namespace mtacc
