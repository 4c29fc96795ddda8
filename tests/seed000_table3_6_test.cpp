// Seed 000 (Bossoni) Table 3.6, lines 4202-4222 of the seed (reference
// seed000_part1_cone_test_piece.md §6.3): axis ranges of the cone-frustum test piece on the
// tilting-table machine, computed through the generic inverse kinematics. The table swaps
// alpha and beta (erratum 9): alpha = 45 deg, beta = 30 deg. Values are printed to 0.1 mm,
// so the tolerance is half a unit of the last digit (0.05 mm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mtacc/kinematics/inverse.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct Ranges {
  double dx, dy, dz, db, dc;
};

Ranges coneRanges(double r, const Vec3& centre) {
  const auto machine = test::bundled("tilting-table");
  const auto nominal = compileNominal(machine);
  const double alpha = 45 * kDeg, beta = 30 * kDeg;
  std::vector<Vec3> points, tools;
  const int n = 3600;
  for (int i = 0; i <= n; ++i) {
    const double phi = 2 * kPi * i / n;
    points.emplace_back(r * std::cos(beta) * std::cos(phi) + centre.x(), r * std::sin(phi) + centre.y(),
                        -r * std::sin(beta) * std::cos(phi) + centre.z());
    const Vec3 t0(-std::sin(alpha) * std::cos(phi), -std::sin(alpha) * std::sin(phi), std::cos(alpha));
    Mat3 rb;
    rb << std::cos(beta), 0, std::sin(beta), 0, 1, 0, -std::sin(beta), 0, std::cos(beta);
    tools.push_back(rb * t0);
  }
  IkOptions options;
  options.branch = TiltBranch::Negative;  // seed 000 L1178-1180: the negative-B solution
  const auto path = solveIkPath(nominal, points, tools, options);
  double lo[5], hi[5];
  std::fill(lo, lo + 5, 1e300);
  std::fill(hi, hi + 5, -1e300);
  for (const auto& s : path)
    for (int k = 0; k < 5; ++k) {
      lo[k] = std::min(lo[k], s.q[static_cast<size_t>(k)]);
      hi[k] = std::max(hi[k], s.q[static_cast<size_t>(k)]);
    }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], (hi[3] - lo[3]) / kDeg, (hi[4] - lo[4]) / kDeg};
}

TEST(Seed000, Table3_6ProposedSetup) {
  const auto r = coneRanges(40.0, Vec3(-65, 0, 150));
  EXPECT_NEAR(r.dx, 185.7, 0.05);
  EXPECT_NEAR(r.dy, 90.0, 0.05);
  EXPECT_NEAR(r.dz, 185.7, 0.05);
  EXPECT_NEAR(r.db, 60.0, 0.05);
  EXPECT_NEAR(r.dc, 360.0, 0.05);
}

TEST(Seed000, Table3_6ComparisonSetup) {
  const auto r = coneRanges(44.8, Vec3(48.9, 0, 66.1));
  EXPECT_NEAR(r.dx, 36.0, 0.05);
  EXPECT_NEAR(r.dy, 142.6, 0.05);
  EXPECT_NEAR(r.dz, 13.2, 0.05);
  EXPECT_NEAR(r.db, 60.0, 0.05);
  EXPECT_NEAR(r.dc, 360.0, 0.05);
}

}  // namespace
}  // namespace mtacc
