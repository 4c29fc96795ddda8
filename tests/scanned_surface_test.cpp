// The cubic machining test's face as a scanner measures it (seed 001 §5): a tilted plane
// evaluated exactly, the surface of mtacc's own material-removal simulation of the tilting
// table, scanned with noise, giving back the simulated zone heights, and the scan read from the
// PLY and STL files mtacc writes.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>

#include "mtacc/io/point_cloud.hpp"
#include "mtacc/io/surface_files.hpp"
#include "mtacc/workflows/cubic_test.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(ScannedSurface, TiltedPlaneIsEvaluatedExactly) {
  // 300,000 points at random places on z = top + 3 um + 1e-4 x - 2e-4 y: every zone plane has the
  // plane's tilts, its mean the plane at the zone centre, and referenced to zone I nothing is left.
  const auto spec = seed001CubicTest();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> across(-spec.blockSize / 2, spec.blockSize / 2);
  const auto plane = [&](double x, double y) { return 0.003 + 1e-4 * (x - spec.centreX) - 2e-4 * (y - spec.centreY); };
  std::vector<Vec3> points;
  for (int k = 0; k < 300000; ++k) {
    const double x = spec.centreX + across(rng), y = spec.centreY + across(rng);
    points.emplace_back(x, y, spec.topHeight + plane(x, y));
  }
  const auto s = scannedCubicTest(points, spec, 0.5, 1.0, referenceZone(spec), "scan");
  const auto planes = zonePlanes(s.map, spec, 1.0);
  for (size_t k = 0; k < planes.size(); ++k) {
    EXPECT_NEAR(planes[k].slopeX, 1e-4, 1e-9) << spec.zones[k].name;
    EXPECT_NEAR(planes[k].slopeY, -2e-4, 1e-9) << spec.zones[k].name;
    EXPECT_NEAR(planes[k].mean, plane(spec.zones[k].x, spec.zones[k].y), 1e-8) << spec.zones[k].name;
    EXPECT_LT(std::abs(s.zones[k].mean), 1e-8) << spec.zones[k].name;
    EXPECT_LT(std::hypot(s.zones[k].slopeX, s.zones[k].slopeY), 1e-9) << spec.zones[k].name;
  }
}

TEST(ScannedSurface, MachinedSurfaceScannedWithNoiseGivesTheSimulatedZones) {
  // The tilting table with its errors cuts the seed 001 test (surface on a 0.05 mm grid); a scan
  // of that surface, a point at every cell with 0.5 um of noise, evaluated on 0.5 mm cells: each
  // zone's height referenced to zone I is the simulation's within the noise (about 0.001 um on a
  // zone mean of 230,000 points; 0.02 um allows for the cells along the zone edges, which the
  // two grids cut differently), however large the zones' heights (several um here).
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  CubicTestRequest request;
  request.gridSpacing = 0.05;
  const auto s = cubicTestStudy(setup, request);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5e-3);
  std::vector<Vec3> points;
  const auto& g = s.actual.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) points.emplace_back(g.x(i), g.y(j), s.actual.reference + s.actual.at(i, j) + noise(rng));
  const auto scan = scannedCubicTest(points, request.spec, 0.5, request.inset, s.referenceZone, "scan");
  double largest = 0;
  for (size_t k = 0; k < s.zones.size(); ++k) {
    EXPECT_NEAR(scan.zones[k].mean, s.zones[k].measured.mean, 2e-5) << s.zones[k].name;
    largest = std::max(largest, std::abs(s.zones[k].measured.mean));
  }
  EXPECT_GT(largest, 1e-3);
  // The same surface as the PLY and the STL mtacc writes, read back as scans: the same zones to
  // the files' single precision (z about 50 mm: 4e-6 mm).
  for (const auto& [extension, bytes] : {std::pair{"ply", heightMapPly(s.actual, 1)}, {"stl", heightMapStl(s.actual, 1)}}) {
    const auto cloud = parsePointCloud(bytes, extension, std::string("surface.") + extension);
    EXPECT_EQ(cloud.size(), g.cells()) << extension;
    const auto fromFile = scannedCubicTest(cloud, request.spec, 0.5, request.inset, s.referenceZone, "surface");
    for (size_t k = 0; k < s.zones.size(); ++k) EXPECT_NEAR(fromFile.zones[k].mean, s.zones[k].measured.mean, 2e-5) << extension << " " << s.zones[k].name;
  }
}

TEST(ScannedSurface, AScanThatMissesAZoneIsRefused) {
  // Points over the left half of the face only: the zones on the right have no cell with a height.
  const auto spec = seed001CubicTest();
  std::vector<Vec3> points;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 400; ++j) points.emplace_back(spec.centreX - spec.blockSize / 2 + 0.06 * i, spec.centreY - spec.blockSize / 2 + 0.12 * j, spec.topHeight);
  EXPECT_THROW(scannedCubicTest(points, spec, 0.5, 1.0, referenceZone(spec), "scan"), InputError);
}

}  // namespace
}  // namespace mtacc
