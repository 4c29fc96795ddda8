// Seed 003 (TU Eindhoven BCR report), Appendix A: the Maho 5-axis machine. The frame
// translations tlt_k (origin of element frame k in tool coordinates, eqs. [A.20]-[A.25],
// seed lines 4011-4038; reference seed003_error_model_holeplate.md §4.2) must follow from the
// generic chain built from the bundled description data/machines/maho.yaml. The printed
// expressions are exact, so the tolerance is rounding (1e-9 mm).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(Seed003AppendixA, AppendixAFrameTranslations) {
  const auto machine = test::bundled("maho");
  const auto model = compileNominal(machine);
  const double L = 150.0;  // tool length of the bundled description
  const int X = machine->axisIndex("X"), Y = machine->axisIndex("Y"), Z = machine->axisIndex("Z");
  const int B = machine->axisIndex("B"), C = machine->axisIndex("C");
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> q(5);
    q[X] = 700 * u(rng);                      // qb2
    q[Y] = 500 * u(rng);                      // qb1
    q[Z] = 600 * u(rng);                      // qa1
    q[B] = 2 * kPi * u(rng);                  // qb3
    q[C] = (120 * u(rng) - 60) * kDeg;        // qa2
    const double qb2 = q[X], qb1 = q[Y], qa1 = q[Z], c = std::cos(q[C]), s = std::sin(q[C]);
    const Pose toolInv = toolChainPose(model, q.data(), nullptr).inverse();
    const auto frames = errorFrames(model, q.data());
    auto tlt = [&](int axis) { return Vec3(toolInv * frames[static_cast<size_t>(axis)].translation()); };

    const Vec3 a2(0, -(200 + L), 140);                                                          // [A.20]
    const Vec3 a1(210 * s, 210 * c - (200 + L), 805 - qa1);                                      // [A.21]
    const Vec3 base(-350 * c + 305 * s, 350 * s + 305 * c - (200 + L), 310 - qa1);               // [A.22]
    const Vec3 b1((632.5 + qb1) * s, (632.5 + qb1) * c - (200 + L), 825 - qa1);                  // [A.23]
    const Vec3 b2((700 + qb1) * s + (qb2 - 350) * c, (700 + qb1) * c - (qb2 - 350) * s - (200 + L), 685 - qa1);  // [A.24]
    const Vec3 b3((305 + qb1) * s + (qb2 - 350) * c, (305 + qb1) * c - (qb2 - 350) * s - (200 + L), 310 - qa1);  // [A.25]

    EXPECT_LT((tlt(C) - a2).norm(), 1e-9);
    EXPECT_LT((tlt(Z) - a1).norm(), 1e-9);
    EXPECT_LT((Vec3(toolInv.translation()) - base).norm(), 1e-9);
    EXPECT_LT((tlt(Y) - b1).norm(), 1e-9);
    EXPECT_LT((tlt(X) - b2).norm(), 1e-9);
    EXPECT_LT((tlt(B) - b3).norm(), 1e-9);
    // [A.18]: tlt_wp = tlt_b3, and at C = B = 0 the tool sits at (350 - qb2, L - 105 - qb1, qa1 - 310).
    EXPECT_LT((Vec3(toolInv * workpiecePose(model, q.data(), nullptr).translation()) - b3).norm(), 1e-9);
  }
  std::vector<double> home(5, 0.0);
  home[X] = 100;
  home[Y] = 50;
  home[Z] = 200;
  EXPECT_LT((toolPoint(model, home.data()).position - Vec3(350 - 100, L - 105 - 50, 200 - 310)).norm(), 1e-9);
}

TEST(Seed003AppendixA, AppendixAReferenceVectorsAtHome) {
  // Reference §13 item 1: at q = 0 and L = 150, tlt_a1 = (0, -140, 805), tlt_b2 = (-350, 350, 685),
  // tlt_b3 = tlt_0 = (-350, -45, 310).
  const auto machine = test::bundled("maho");
  const auto model = compileNominal(machine);
  const std::vector<double> q(5, 0.0);
  const Pose toolInv = toolChainPose(model, q.data(), nullptr).inverse();
  const auto frames = errorFrames(model, q.data());
  auto tlt = [&](const char* axis) { return Vec3(toolInv * frames[static_cast<size_t>(machine->axisIndex(axis))].translation()); };
  EXPECT_LT((tlt("Z") - Vec3(0, -140, 805)).norm(), 1e-9);
  EXPECT_LT((tlt("X") - Vec3(-350, 350, 685)).norm(), 1e-9);
  EXPECT_LT((tlt("B") - Vec3(-350, -45, 310)).norm(), 1e-9);
  EXPECT_LT((Vec3(toolInv.translation()) - Vec3(-350, -45, 310)).norm(), 1e-9);
}

}  // namespace
}  // namespace mtacc
