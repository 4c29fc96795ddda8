// The virtual machine's interpolator and the structure's deflection under axis accelerations.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "mtacc/dynamics/transient_deflection.hpp"
#include "mtacc/io/structure_yaml.hpp"
#include "mtacc/virtual_controller/motion_interpolator.hpp"

namespace mtacc {
namespace {

// An L-shaped path in X (mm) and C (rad): 60 mm, then 30 deg, so that the path units mix.
const std::vector<std::vector<double>> kPath{{0, 0}, {60, 0}, {60, 30 * kDeg}};
const std::vector<bool> kRotary{false, true};

TEST(MotionInterpolator, StartsAndEndsAtRestOnTheEndPointsWithinTheFeedAndAcceleration) {
  const InterpolatorLimits limits{.acceleration = 2000, .jerkTime = 0.01, .cornerRounding = 0.5, .dwell = 0.1};
  const double period = 1e-3, feed = 3000;  // 50 units/s
  const auto trace = interpolateMotion(kPath, kRotary, feed, limits, period);
  const auto& x = trace.channels[0];
  const auto& c = trace.channels[1];
  const size_t n = trace.samples();
  EXPECT_NEAR(x.front(), 0.0, 1e-12);
  EXPECT_NEAR(x.back(), 60.0, 1e-9);
  EXPECT_NEAR(c.back(), 30 * kDeg, 1e-12);
  EXPECT_EQ(x[50], x.front()) << "still at rest in the dwell";
  double fastest = 0, hardest = 0, nearestToCorner = 1e9;
  for (size_t k = 1; k + 1 < n; ++k) {
    const auto at = [&](size_t i) { return Eigen::Vector2d(x[i], c[i] / kDeg); };
    fastest = std::max(fastest, (at(k + 1) - at(k)).norm() / period);
    hardest = std::max(hardest, (at(k + 1) - 2 * at(k) + at(k - 1)).norm() / (period * period));
    nearestToCorner = std::min(nearestToCorner, (at(k) - Eigen::Vector2d(60, 0)).norm());
  }
  EXPECT_LE(fastest, feed / 60 * (1 + 1e-9));
  EXPECT_GT(fastest, 0.95 * feed / 60) << "the feed is reached on the straight blocks";
  EXPECT_LE(hardest, 1.6 * limits.acceleration) << "tangential and centripetal limits, each met, add at most to sqrt(2)";
  EXPECT_GT(nearestToCorner, 0.01) << "the corner is rounded";
  EXPECT_LT(nearestToCorner, 2.0) << "but stays within a few sigma";
}

TEST(MotionInterpolator, RejectsADegeneratePathAndBadLimits) {
  EXPECT_THROW(interpolateMotion({{1, 0}, {1, 0}}, kRotary, 1000, {}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion(kPath, kRotary, 0, {}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion(kPath, kRotary, 1000, {.acceleration = -1}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion(kPath, kRotary, 1000, {.dwell = NAN}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion({{0, 0}, {1, NAN}}, kRotary, 1000, {}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion({{0}, {1}}, kRotary, 1000, {}, 1e-3), InvalidInput);
  EXPECT_THROW(interpolateMotion(kPath, kRotary, 1000, {}, 1e-9), InvalidInput) << "10^8 samples";
}

// A held acceleration of X: once the modes have rung out the deflection is the quasi-static
// response of accelerationResponse (seed 000 Table 7.1 form).
TEST(TransientDeflection, AHeldAccelerationSettlesOnTheQuasiStaticResponse) {
  const auto model = loadStructure("wcayfxzt-compact");
  const std::vector<double> at(model.axes.size(), 0.0);
  const double period = 1e-4, acceleration = 2.0;  // s, m/s^2
  std::vector<std::vector<double>> series(model.axes.size());
  series[static_cast<size_t>(model.axisIndex("X"))].assign(20000, acceleration);
  const auto deflection = accelerationDeflection(model, at, series, period);
  const Vec3 expected = accelerationResponse(assembleStructure(model, at)).col(model.axisIndex("X")) * acceleration;
  EXPECT_GT(expected.norm(), 1e-6);
  EXPECT_LT((deflection.back() - expected).norm(), 1e-3 * expected.norm());
  EXPECT_EQ(deflection.front(), Vec3::Zero());
  EXPECT_THROW(accelerationDeflection(model, at, series, 0.0), InvalidInput);
  series[static_cast<size_t>(model.axisIndex("Y"))].assign(10, 1.0);
  EXPECT_THROW(accelerationDeflection(model, at, series, period), InvalidInput);
}

}  // namespace
}  // namespace mtacc
