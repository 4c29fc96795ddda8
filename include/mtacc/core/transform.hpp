#pragma once
// Rigid transforms and the small-error transform used throughout the error model.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mtacc {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Pose = Eigen::Isometry3d;

// Six error components in ISO 230-1 order: translations along X, Y, Z, then rotations
// about X, Y, Z (the A, B, C of the names EXk, EYk, EZk, EAk, EBk, ECk and X0k ... C0k).
enum Component : int { kX = 0, kY = 1, kZ = 2, kA = 3, kB = 4, kC = 5 };

// sin and cos to full double precision. Error motions are small angles: a short Taylor
// series whose first omitted term lies below 1e-17 of the result for |x| < 1e-4 (and a
// longer one for |x| < 1e-2, below 1e-24); libm beyond.
inline void exactSinCos(double x, double& s, double& c) {
  const double x2 = x * x;
  if (x2 < 1e-8) {
    s = x * (1.0 - x2 * (1.0 / 6));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24));
    return;
  }
  if (x2 < 1e-4) {
    s = x * (1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880)))));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 - x2 * (1.0 / 3628800)))));
    return;
  }
  ::sincos(x, &s, &c);
}

// sin and cos of the joint angles and error harmonics, which the kinematics evaluate several times a
// pose: within 1 ulp of libm's (tests/transform_test.cpp), at a third of its cost, without its
// call and rounding-mode switch. The argument is reduced by pi/2 in two parts with FMA (exact
// to |x| of 1e5), then Taylor series to degree 17 and 18 on |r| <= pi/4, whose first omitted
// terms lie below 1e-19, evaluated by Estrin's scheme (short dependency chains); libm beyond 1e5.
inline void fastSinCos(double x, double& s, double& c) {
  if (!(std::abs(x) < 1e5)) {
    ::sincos(x, &s, &c);
    return;
  }
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kHalfPiHigh = 1.5707963267948966;       // pi/2 rounded to double
  constexpr double kHalfPiLow = 6.123233995736766036e-17;  // pi/2 - kHalfPiHigh
  const double k = std::nearbyint(x * kTwoOverPi);
  const double r = std::fma(-k, kHalfPiLow, std::fma(-k, kHalfPiHigh, x));
  const double z = r * r, z2 = z * z, z4 = z2 * z2;
  // sin r = r + r z (sum of (-1)^(n+1) z^(n-1) / (2n+1)!, n = 1..8)
  const double sineSeries = (-1.0 / 6 + z * (1.0 / 120)) + z2 * (-1.0 / 5040 + z * (1.0 / 362880)) +
                            z4 * ((-1.0 / 39916800 + z * (1.0 / 6227020800)) + z2 * (-1.0 / 1307674368000 + z * (1.0 / 355687428096000)));
  // cos r = 1 + z (sum of (-1)^n z^(n-1) / (2n)!, n = 1..9)
  const double cosineSeries = (-0.5 + z * (1.0 / 24)) + z2 * (-1.0 / 720 + z * (1.0 / 40320)) +
                              z4 * ((-1.0 / 3628800 + z * (1.0 / 479001600)) + z2 * (-1.0 / 87178291200 + z * (1.0 / 20922789888000)) +
                                    z4 * (-1.0 / 6402373705728000));
  const double sr = r + r * z * sineSeries, cr = 1.0 + z * cosineSeries;
  switch (static_cast<long>(k) & 3) {
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = -sr; break;
    case 2: s = -sr; c = -cr; break;
    default: s = -cr; c = sr; break;
  }
}

// The angle between two unit vectors (rad), accurate at any angle; below 1e-4 rad by the series
// of asin, whose first omitted term lies below 1e-17 of the result, without atan2's cost.
inline double angleBetween(const Vec3& a, const Vec3& b) {
  const double sine = a.cross(b).norm(), cosine = a.dot(b);
  if (sine < 1e-4 && cosine > 0) return sine * (1.0 + sine * sine * (1.0 / 6));
  return std::atan2(sine, cosine);
}

// R = Rx(a) * Ry(b) * Rz(c): the order of seed 003 eq. [3.8], exact (not linearised).
inline Mat3 rotationXYZ(double a, double b, double c) {
  double sa, ca, sb, cb, sc, cc;
  exactSinCos(a, sa, ca);
  exactSinCos(b, sb, cb);
  exactSinCos(c, sc, cc);
  Mat3 r;
  r << cb * cc, -cb * sc, sb,                                      //
      sa * sb * cc + ca * sc, -sa * sb * sc + ca * cc, -sa * cb,  //
      -ca * sb * cc + sa * sc, ca * sb * sc + sa * cc, ca * cb;
  return r;
}
// d R / d (a, b, c)[which] at (a, b, c).
Mat3 rotationXYZDerivative(double a, double b, double c, int which);

// Trans(e) * Rx(a) * Ry(b) * Rz(c) for error components (ex, ey, ez, a, b, c).
Pose errorTransform(const Vec6& components);
// d errorTransform / d components[which], as a 4x4 matrix (bottom row zero).
Mat4 errorTransformDerivative(const Vec6& components, int which);

// Right-handed rotation by angle about a unit axis.
Mat3 rotationAbout(const Vec3& unitAxis, double angle);

// Rotation vector (axis * angle) of a rotation matrix, and the inverse of the left
// Jacobian of SO(3) at that vector: d log(exp(w) R) / dw at w = 0.
Vec3 rotationVector(const Mat3& rotation);
Mat3 leftJacobianInverse(const Vec3& rotationVector);

Mat3 skew(const Vec3& v);

}  // namespace mtacc
