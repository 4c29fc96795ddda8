#pragma once
// Circles through measured or simulated points in space: the least-squares plane and circle of a
// section (seed 000 §3.9's fit, used by the cone's form error and by the measured cone), and the
// minimum-zone circle (ISO 12181-2: the two concentric circles of least radial separation).
#include <vector>

#include "mtacc/core/transform.hpp"

namespace mtacc {

// The centroid of points and their principal directions, least spread first: a plane's normal is
// axes.col(0), a line's direction axes.col(2); spread holds the sums of squared distances along them.
struct PointSpread {
  Vec3 centroid = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Vec3 spread = Vec3::Zero();

  bool onOneLine() const { return !(spread[1] > 1e-12 * spread[2]); }
};
PointSpread pointSpread(const std::vector<Vec3>& points);

struct CircleFit {
  Vec3 centre = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // of the least-squares plane, oriented along `towards`
  Vec3 u = Vec3::UnitX(), v = Vec3::UnitY();  // in-plane axes (u = normal.unitOrthogonal())
  double radius = 0;
};
// The least-squares plane (centroid and the direction of least spread), the algebraic
// least-squares circle in it (Kasa: to first order in the form deviation the geometric fit), the
// radius the mean in-plane distance from the centre. Needs three points not on one line.
CircleFit fitCircle(const std::vector<Vec3>& points, const Vec3& towards);

// The in-plane distance of each point from `centre` minus `radius`, mm.
std::vector<double> radialDeviations(const std::vector<Vec3>& points, const CircleFit& circle);

struct MinimumZoneCircle {
  Vec3 centre = Vec3::Zero();  // in the fit's plane
  double width = 0;            // the circularity: outer minus inner radius, mm
};
// The minimum-zone circle in the least-squares circle's plane: the centre minimising the radial
// range, by Lawson's iteratively reweighted least squares for the Chebyshev fit of the
// deviations linearised about the centre, re-linearised until the centre moves less than 1e-9
// mm; its width is evaluated exactly and is never above the least-squares circle's range.
MinimumZoneCircle minimumZoneCircle(const std::vector<Vec3>& points, const CircleFit& circle);

}  // namespace mtacc
