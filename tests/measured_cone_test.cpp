// The cone frustum measured on a CMM (seed 000 App. A.4): circles and minimum zones of known
// analytical shapes, an exact cone with its datum plane and cylinder, and the points of mtacc's
// own machining simulation of the tilting table with noise, whose section form the evaluation
// returns within the noise.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <numbers>
#include <random>

#include "mtacc/core/units.hpp"
#include "mtacc/io/cone_points_csv.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/cone_study.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

constexpr double kTurn = 2 * std::numbers::pi;

std::vector<Vec3> around(int n, const std::function<Vec3(double)>& at) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) out.push_back(at(kTurn * i / n));
  return out;
}

double rangeOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end()); }

TEST(MeasuredCone, EllipseOfKnownEccentricity) {
  // Semi-axes 50.02 and 49.98 mm in a plane tilted out of XY: by symmetry both the least-squares
  // and the minimum-zone circle are centred on the ellipse, and both circularities are a - b.
  const Mat3 tilt = Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  const Vec3 centre(5.0, -7.0, 20.0);
  const auto pts = around(360, [&](double t) { return Vec3(centre + tilt * Vec3(50.02 * std::cos(t), 49.98 * std::sin(t), 0.0)); });
  const auto circle = fitCircle(pts, Vec3::UnitZ());
  EXPECT_LT((circle.centre - centre).norm(), 1e-12);
  EXPECT_NEAR(rangeOf(radialDeviations(pts, circle)), 0.04, 1e-12);
  const auto zone = minimumZoneCircle(pts, circle);
  EXPECT_NEAR(zone.width, 0.04, 1e-12);
  EXPECT_LT((zone.centre - centre).norm(), 1e-9);
}

TEST(MeasuredCone, MinimumZoneMatchesABruteForceSearch) {
  // A three- and five-lobed section 30 mm in radius off the origin: the minimum zone found by
  // Lawson's iteration against the width minimised over a grid of centres (two levels, the
  // finer at 4 nm; the width changes by at most 2 x 4 nm across a cell), and strictly below
  // the least-squares circle's range.
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 0.0005);
  const auto pts = around(240, [&](double t) {
    const double r = 30.0 + 0.010 * std::cos(3 * t) + 0.006 * std::sin(5 * t + 0.4) + 0.004 * std::cos(2 * t) + g(rng);
    return Vec3(1.0 + r * std::cos(t), 2.0 + r * std::sin(t), 0.0);
  });
  const auto circle = fitCircle(pts, Vec3::UnitZ());
  const auto zone = minimumZoneCircle(pts, circle);
  const auto widthAt = [&](double x, double y) {
    double low = INFINITY, high = -INFINITY;
    for (const auto& p : pts) {
      const double r = std::hypot(p.x() - x, p.y() - y);
      low = std::min(low, r);
      high = std::max(high, r);
    }
    return high - low;
  };
  double bestX = circle.centre.x(), bestY = circle.centre.y(), best = widthAt(bestX, bestY);
  for (const double step : {0.2e-3, 0.004e-3}) {
    const double x0 = bestX, y0 = bestY;
    for (int i = -100; i <= 100; ++i)
      for (int j = -100; j <= 100; ++j)
        if (const double w = widthAt(x0 + i * step, y0 + j * step); w < best) {
          best = w;
          bestX = x0 + i * step;
          bestY = y0 + j * step;
        }
  }
  EXPECT_NEAR(zone.width, best, 1e-5);
  EXPECT_LE(zone.width, best + 1e-9);
  EXPECT_GT(rangeOf(radialDeviations(pts, circle)) - zone.width, 1e-4);
}

// Points on a cone with its axis through `apexSide` along `axis`, radius r(z) = r0 - z tan(alpha).
std::vector<Vec3> coneSection(const Vec3& point, const Vec3& axis, double r0, double alpha, double z, int n) {
  const Vec3 x = axis.unitOrthogonal(), y = axis.cross(x);
  const double r = r0 - z * std::tan(alpha);
  return around(n, [&](double t) { return Vec3(point + z * axis + r * (std::cos(t) * x + std::sin(t) * y)); });
}

TEST(MeasuredCone, ExactConeWithItsDatumPlaneAndCylinder) {
  // Axis 2.24e-2 rad off the normal of plane A (z = 0), half angle 15 deg, three sections, and
  // the cylinder on the same axis: the half angle, squareness and a form, circularities and
  // coaxiality of zero come back to rounding.
  const Vec3 axis = Vec3(0.01, -0.02, 1.0).normalized(), point(5.0, -3.0, 0.0);
  const double alpha = 15 * kDeg;
  ConePoints in;
  for (int k = 0; k < 5; ++k) in.plane.push_back(Vec3(40.0 * std::cos(k), 40.0 * std::sin(k), 0.0));
  for (const double z : {20.0, 30.0, 40.0}) in.cone.push_back({fmt::format("z{}", z), coneSection(point, axis, 50.0, alpha, z, 72)});
  for (const double z : {3.0, 8.0}) in.cylinder.push_back({fmt::format("c{}", z), coneSection(point, axis, 60.0, 0.0, z, 36)});
  const auto m = evaluateMeasuredCone(in, 10 * kDeg);
  ASSERT_TRUE(m.halfAngle && m.formError && m.squareness && m.coaxiality);
  EXPECT_NEAR(*m.halfAngle, alpha, 1e-10);
  EXPECT_LT(*m.formError, 1e-9);
  EXPECT_NEAR(*m.squareness, std::acos(axis.z()), 1e-10);
  EXPECT_LT(*m.coaxiality, 1e-9);
  EXPECT_LT(m.flatness, 1e-12);
  EXPECT_LT((m.axisDirection - axis).norm(), 1e-10);
  for (const auto& s : m.cone) {
    EXPECT_LT(s.minimumZoneCircularity, 1e-9);
    EXPECT_NEAR(s.circle.radius, 50.0 - (s.circle.centre - point).dot(axis) * std::tan(alpha), 1e-9);
  }
}

TEST(MeasuredCone, MachiningSimulationWithNoiseGivesItsForm) {
  // The tilting table with its errors cuts the preset cone; the tool points of two paths 10 mm
  // apart along the cone axis, carried into the cone's own frame (the CMM's, x towards phi = 0)
  // and, as a CMM probes a section at one height, slid along the slant to the section's nominal
  // height, with 0.2 um of noise, are the "measured" cone. The section at the path's radius returns
  // the simulated normal form: the RMS difference is the noise's (0.2 um; 0.3 allows for 360
  // samples), the two ranges within the noise's own range.
  const test::TestFolder folder("mtacc-measured-cone");
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const auto nominal = setup.nominal(), actual = setup.actual();
  ConeStudyRequest request;
  request.spec = *conePreset("tilting-table");
  request.points = 360;
  const ConeSpec& spec = request.spec;
  const Mat3 frame = Eigen::AngleAxisd(spec.gamma, Vec3::UnitZ()).toRotationMatrix() * Eigen::AngleAxisd(spec.beta, Vec3::UnitY()).toRotationMatrix();
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.2e-3);
  std::string csv = "element,section,x,y,z\n";
  for (const double h : {0.0, 10.0}) {
    ConeSpec at = spec;
    at.centre = spec.centre + frame * Vec3(0.0, 0.0, h);
    at.radius = spec.radius - h * std::tan(spec.alpha);
    const auto path = conePath(at, 360);
    const auto motion = coneMotion(nominal, at, path);
    for (Eigen::Index i = 0; i < motion.q.rows(); ++i) {
      const Vec3 p = toolPoint(actual, motion.q.row(i).data(), motion.direction.row(i).data()).position;
      const Vec3 local = frame.transpose() * (p - spec.centre);
      const double rho = std::hypot(local.x(), local.y()) + (local.z() - h) * std::tan(spec.alpha);
      const double phi = std::atan2(local.y(), local.x());
      const Vec3 cmm = Vec3(rho * std::cos(phi), rho * std::sin(phi), h) + Vec3(noise(rng), noise(rng), noise(rng));
      csv += fmt::format("cone,h{},{:.9f},{:.9f},{:.9f}\n", h, cmm.x(), cmm.y(), cmm.z());
    }
  }
  request.measuredFile = (folder.dir() / "cone.csv").string();
  std::ofstream(request.measuredFile) << csv;
  const auto s = coneStudy(setup, request);
  ASSERT_TRUE(s.form && s.comparison && s.measured);
  EXPECT_GT(s.form->formError, 2e-3);
  EXPECT_EQ(s.measured->cone[s.comparison->section].name, "h0");
  EXPECT_LT(s.comparison->rmsDifference, 0.3e-3);
  EXPECT_NEAR(s.comparison->measuredRange, s.comparison->simulatedRange, 6 * 0.2e-3);
  EXPECT_NEAR(*s.measured->halfAngle, spec.alpha, 1e-4);
}

}  // namespace
}  // namespace mtacc
