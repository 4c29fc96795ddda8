#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mtacc/core/transform.hpp"

namespace mtacc {
namespace {

// fastSinCos against libm's sincos. libm is within 1 ulp of the true values; the kernel's
// reduction is exact and its series truncation below 1e-19, so the two differ by at most an ulp
// of 1 (2.2e-16) at any |x| < 1e5, including next to the multiples of pi/2 where the reduction
// cancels, and beyond 1e5 they are the same call.
TEST(FastSinCos, WithinOneUlpOfLibmOverTheReducedRange) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> argument(-1e5, 1e5), small(-4.0, 4.0);
  double worst = 0.0;
  auto compare = [&](double x) {
    double s, c, libmS, libmC;
    fastSinCos(x, s, c);
    ::sincos(x, &libmS, &libmC);
    worst = std::max({worst, std::abs(s - libmS), std::abs(c - libmC)});
  };
  for (int i = 0; i < 200000; ++i) {
    compare(argument(random));
    compare(small(random));
  }
  for (int k = -40000; k <= 40000; k += 7) {  // next to k pi/2, where r is tiny
    const double x = k * (M_PI / 2);
    compare(x);
    compare(std::nextafter(x, 1e300));
  }
  EXPECT_LE(worst, std::ldexp(1.0, -52));
  for (double x : {1e5, -3e7, 1e300}) {
    double s, c, libmS, libmC;
    fastSinCos(x, s, c);
    ::sincos(x, &libmS, &libmC);
    EXPECT_EQ(s, libmS) << x;
    EXPECT_EQ(c, libmC) << x;
  }
}

TEST(FastSinCos, QuadrantsAndSmallArgumentsAreExact) {
  const double cases[][3] = {{0.0, 0.0, 1.0}, {M_PI / 2, 1.0, 0.0}, {M_PI, 0.0, -1.0}, {-M_PI / 2, -1.0, 0.0}, {3 * M_PI / 2, -1.0, 0.0}};
  for (const auto& [x, sine, cosine] : cases) {
    double s, c;
    fastSinCos(x, s, c);
    EXPECT_NEAR(s, sine, 4e-16) << x;
    EXPECT_NEAR(c, cosine, 4e-16) << x;
  }
  double s, c;
  fastSinCos(1e-300, s, c);  // sin x = x exactly for tiny x
  EXPECT_EQ(s, 1e-300);
  EXPECT_EQ(c, 1.0);
}

// Both ways angleBetween takes (the series of asin below 1e-4 rad, atan2 above, either side of
// the switch) against the angle the vectors are built with: (1, 0, 0) and (cos t, sin t, 0),
// whose cross product is sin t exactly. Within 2 ulp of t: the rounding of sin t and cos t.
TEST(AngleBetween, WithinTwoUlpOfTheAngleBuiltOnEitherSideOfTheSeries) {
  for (const double t : {1e-12, 1e-8, 3e-5, 9.999e-5, 1.0001e-4, 1e-3, 0.5, 2.0, 3.0}) {
    const Vec3 a(1.0, 0.0, 0.0), b(std::cos(t), std::sin(t), 0.0);
    EXPECT_NEAR(angleBetween(a, b), t, 4.5e-16 * t) << t;
    EXPECT_NEAR(angleBetween(b, a), t, 4.5e-16 * t) << t;
  }
  EXPECT_EQ(angleBetween(Vec3(0.0, 0.0, 1.0), Vec3(0.0, 0.0, 1.0)), 0.0);
}

}  // namespace
}  // namespace mtacc
