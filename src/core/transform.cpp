#include "mtacc/core/transform.hpp"

#include <cmath>

namespace mtacc {
namespace {
Mat3 rx(double a) {
  Mat3 r;
  const double c = std::cos(a), s = std::sin(a);
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}
Mat3 ry(double b) {
  Mat3 r;
  const double c = std::cos(b), s = std::sin(b);
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}
Mat3 rz(double g) {
  Mat3 r;
  const double c = std::cos(g), s = std::sin(g);
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}
Mat3 drx(double a) {
  Mat3 r;
  const double c = std::cos(a), s = std::sin(a);
  r << 0, 0, 0, 0, -s, -c, 0, c, -s;
  return r;
}
Mat3 dry(double b) {
  Mat3 r;
  const double c = std::cos(b), s = std::sin(b);
  r << -s, 0, c, 0, 0, 0, -c, 0, -s;
  return r;
}
Mat3 drz(double g) {
  Mat3 r;
  const double c = std::cos(g), s = std::sin(g);
  r << -s, -c, 0, c, -s, 0, 0, 0, 0;
  return r;
}
}  // namespace

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Mat3 rotationXYZDerivative(double a, double b, double c, int which) {
  switch (which) {
    case 0: return drx(a) * ry(b) * rz(c);
    case 1: return rx(a) * dry(b) * rz(c);
    default: return rx(a) * ry(b) * drz(c);
  }
}

Pose errorTransform(const Vec6& e) {
  Pose t = Pose::Identity();
  t.linear() = rotationXYZ(e[kA], e[kB], e[kC]);
  t.translation() = e.head<3>();
  return t;
}

Mat4 errorTransformDerivative(const Vec6& e, int which) {
  Mat4 d = Mat4::Zero();
  if (which < 3) {
    d(which, 3) = 1.0;
  } else {
    d.topLeftCorner<3, 3>() = rotationXYZDerivative(e[kA], e[kB], e[kC], which - 3);
  }
  return d;
}

Mat3 rotationAbout(const Vec3& unitAxis, double angle) {
  return Eigen::AngleAxisd(angle, unitAxis).toRotationMatrix();
}

Vec3 rotationVector(const Mat3& rotation) {
  const Eigen::AngleAxisd aa(rotation);
  return aa.axis() * aa.angle();
}

Mat3 leftJacobianInverse(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 k = skew(phi);
  if (theta < 1e-6) return Mat3::Identity() - 0.5 * k + (1.0 / 12.0) * k * k;
  const double coeff =
      1.0 / (theta * theta) - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  return Mat3::Identity() - 0.5 * k + coeff * k * k;
}

}  // namespace mtacc
