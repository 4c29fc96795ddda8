// The machined surface by material removal (procedures/machined_surface): the swept-tool
// envelope against an independent sampling of the tool along the move, the pruned cutting
// against every move at every cell, and the actual path against the exact model.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "mtacc/io/cubic_test_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/procedures/zone_planes.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// The tool's lowest point on the vertical line through (x, y), sampled: the tool at 20,001
// positions along the move; a ball's bottom from the sphere equation, a flat end's from the
// intersection of the line with the disc's plane (Eigen::Hyperplane).
double sampledBottom(const CuttingTool& tool, const Vec3& a, const Vec3& b, const Vec3& axis, double x, double y) {
  double z = INFINITY;
  for (int k = 0; k <= 20000; ++k) {
    const Vec3 c = a + (b - a) * (k / 20000.0);
    if (tool.shape == ToolShape::Ball) {
      const double d2 = (x - c.x()) * (x - c.x()) + (y - c.y()) * (y - c.y());
      if (d2 <= tool.radius * tool.radius) z = std::min(z, c.z() - std::sqrt(tool.radius * tool.radius - d2));
    } else {
      const Eigen::ParametrizedLine<double, 3> line(Vec3(x, y, 0), Vec3::UnitZ());
      const Vec3 p = line.intersectionPoint(Eigen::Hyperplane<double, 3>(axis, c));
      if ((p - c).norm() <= tool.radius) z = std::min(z, p.z());
    }
  }
  return z;
}

TEST(MachinedSurface, SweptToolBottomAgreesWithSamplingTheMove) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto shape : {ToolShape::Ball, ToolShape::Flat}) {
    const CuttingTool tool{shape, 3.0};
    int hits = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const Vec3 a(u(rng), u(rng), 50 + 0.2 * u(rng));
      const Vec3 b = a + Vec3(4 * u(rng), 4 * u(rng), 0.5 * u(rng));  // inclined moves too
      const Vec3 axis = Vec3(0.6 * u(rng), 0.6 * u(rng), 1).normalized();
      const double x = 3 * u(rng), y = 3 * u(rng);
      const double exact = sweptToolBottom(tool, a, b, axis, x, y), sampled = sampledBottom(tool, a, b, axis, x, y);
      if (std::isinf(sampled)) {
        // The samples miss only a sliver along the rim: the exact bottom is then at its edge.
        if (!std::isinf(exact)) {
          EXPECT_LT(std::abs(exact - a.z()) + std::abs(exact - b.z()), 10) << trial;
        }
        continue;
      }
      ++hits;
      // Sampling at 1/20000 of the move finds a bottom no lower, and higher by at most the
      // depth change over half a step (|b - a| <= 6 mm, a slope up to 3 at the rim).
      EXPECT_LE(exact, sampled + 1e-12) << trial;
      EXPECT_NEAR(exact, sampled, shape == ToolShape::Ball ? 2e-4 : 1e-3) << trial;
    }
    EXPECT_GT(hits, 100);
  }
}

// The pruned cutting equals the plain minimum over every move at every cell, for moves in all
// directions, inclined, and both tools.
TEST(MachinedSurface, CuttingEqualsEveryMoveAtEveryCell) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto shape : {ToolShape::Ball, ToolShape::Flat}) {
    CutterPath path;
    path.tool = {shape, shape == ToolShape::Ball ? 1.5 : 1.0};
    path.starts = {0};
    for (int k = 0; k < 300; ++k) {
      path.points.push_back(Vec3(4 * u(rng), 4 * u(rng), 0.05 * u(rng)));
      path.axes.push_back(Vec3(0.3 * u(rng), 0.3 * u(rng), 1).normalized());
    }
    const HeightGrid grid = squareGrid(10, 0.05, "grid");
    HeightMap fast = stockHeightMap(grid, 0.0, 0.1);
    cutHeightMap(fast, path, 2);
    for (int j = 0; j < grid.ny; j += 3)
      for (int i = 0; i < grid.nx; i += 3) {
        double z = INFINITY;
        for (size_t k = 1; k < path.points.size(); ++k)
          z = std::min(z, sweptToolBottom(path.tool, path.points[k - 1], path.points[k], path.axes[k - 1], grid.x(i), grid.y(j)));
        ASSERT_EQ(std::min(static_cast<float>(z), 0.1f), static_cast<float>(fast.at(i, j))) << i << " " << j;
      }
  }
}

// The actual path follows the exact model within the chord tolerance, also where component
// errors bend it (the bundled tilting table's cyclic and harmonic errors of X, Y, Z).
TEST(MachinedSurface, ActualPathFollowsTheModelWithinTheChordTolerance) {
  const auto machine = test::bundled("tilting-table");
  const auto model = compile(machine, loadMachineErrors(*machine));
  auto spec = seed001CubicTest();
  spec.zones.resize(2);
  spec.pick = 4;  // a few long passes
  const auto path = cubicToolPath(compileNominal(machine), spec);
  const double tolerance = 1e-6;
  const auto cutter = cutterPath(model, path, spec.tool, tolerance);
  EXPECT_GT(cutter.moves(), 4 * path[0].q.rows());  // the errors bend the passes: refined
  // Midway along each commanded pass, the model's ball centre lies within the tolerance of
  // the cutter path's polyline.
  for (const auto& zone : path)
    for (Eigen::Index i = 1; i < zone.q.rows(); i += 2) {
      const Eigen::VectorXd q = 0.5 * (zone.q.row(i - 1) + zone.q.row(i)).transpose();
      const ToolPoint t = toolPoint(model, q.data(), zone.direction.row(i).data());
      const Vec3 centre = t.position + spec.tool.radius * t.direction;
      double nearest = INFINITY;
      for (size_t k = 1; k < cutter.points.size(); ++k) {
        const Vec3 a = cutter.points[k - 1], d = cutter.points[k] - a;
        const double s = std::clamp((centre - a).dot(d) / std::max(d.squaredNorm(), 1e-30), 0.0, 1.0);
        nearest = std::min(nearest, (a + s * d - centre).norm());
      }
      EXPECT_LT(nearest, 2 * tolerance);
    }
}

// A vertical flat end leaves the face itself: no scallop, the zone plane exactly the face.
TEST(MachinedSurface, FlatEndLeavesAFlatFace) {
  auto spec = seed001CubicTest();
  spec.tool = {ToolShape::Flat, 3.0};
  spec.zones = {spec.zones[0]};
  const auto nominal = compileNominal(test::bundled("tilting-table"));
  const auto cutter = cutterPath(nominal, cubicToolPath(nominal, spec), spec.tool);
  HeightMap map = stockHeightMap(squareGrid(spec.blockSize, 0.05, "grid"), spec.topHeight, spec.depth);
  cutHeightMap(map, cutter);
  const auto plane = zonePlanes(map, spec, 1.0)[0];
  EXPECT_LT(std::abs(plane.mean) + plane.residualPeakToValley, 1e-9);
}

// The measured planes referred to the reference zone (seed 001 evaluates every zone against the
// vertical one): the reference's own plane becomes zero, and each other zone keeps its height
// above the reference plane's extension to its centre and its slopes less the reference's.
TEST(ZonePlanes, ReferredToAZoneThatZonesPlaneIsZero) {
  CubicTestSpec spec;
  spec.zones = {{"ref", 0.0, 0.0}, {"east", 16.0, -8.0}};
  std::vector<ZonePlane> planes(2);
  planes[0].mean = 0.004, planes[0].slopeX = 2e-5, planes[0].slopeY = -3e-5;
  planes[1].mean = 0.010, planes[1].slopeX = 5e-5, planes[1].slopeY = 4e-5;
  const auto out = referencedToZone(planes, spec, 0);
  EXPECT_EQ(out[0].mean, 0.0);
  EXPECT_EQ(out[0].slopeX, 0.0);
  EXPECT_EQ(out[0].slopeY, 0.0);
  EXPECT_DOUBLE_EQ(out[1].mean, 0.010 - (0.004 + 2e-5 * 16.0 - 3e-5 * -8.0));
  EXPECT_DOUBLE_EQ(out[1].slopeX, 5e-5 - 2e-5);
  EXPECT_DOUBLE_EQ(out[1].slopeY, 4e-5 + 3e-5);
}

TEST(CubicTestSpec, BundledTestIsTheSeedsAndErrorsNameTheirKey) {
  const auto bundled = loadCubicTest("seed001-cubic");
  const auto seed = seed001CubicTest();
  ASSERT_EQ(bundled.zones.size(), seed.zones.size());
  for (size_t k = 0; k < seed.zones.size(); ++k) {
    EXPECT_EQ(bundled.zones[k].name, seed.zones[k].name);
    EXPECT_LT((bundled.zones[k].toolVector - seed.zones[k].toolVector).norm(), 1e-15);
  }
  EXPECT_EQ(bundled.blockSize, seed.blockSize);
  EXPECT_EQ(bundled.topHeight, seed.topHeight);
  EXPECT_EQ(bundled.pick, seed.pick);
  // A 4 x 4 grid has no centre zone: every zone is tilted, and none is the reference's vertical.
  const auto grid = parseCubicTest("zones: {grid: 4, tilt: 20 deg}\n", "t.yaml");
  EXPECT_EQ(grid.zones.size(), 16u);
  EXPECT_EQ(grid.zones[5].name, "r2c2");
  EXPECT_EQ(referenceZone(grid), 0u);
  const auto e = test::thrown<InputError>([] { parseCubicTest("block: 48 mm\nzone_size: 60 mm\n", "t.yaml"); });
  ASSERT_TRUE(e);
  EXPECT_EQ(std::string(e->what()), "t.yaml:2: zone_size: must be positive and at most the block size");
}

}  // namespace
}  // namespace mtacc
