#pragma once
// The cone frustum as measured on a CMM (seed 000 App. A.4, Fig. A.4's tolerated elements): the
// reference plane A, sections of the reference cylinder C and of the cone, each a set of probed
// points. Per section the least-squares circle, its circularity (least squares and minimum
// zone), diameter and centre offset; the best-fit cone (axis, half angle, form error as the
// range of the normal deviations), its squareness to A and coaxiality with C; per point the
// radial and the normal form deviation, as seed 000 Fig. 3.58 plots them. Lengths in mm.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/procedures/circle_fit.hpp"

namespace mtacc {

struct ConeSection {
  std::string name;
  std::vector<Vec3> points;
};
struct ConePoints {
  std::vector<Vec3> plane;  // reference plane A; may be empty
  std::vector<ConeSection> cylinder, cone;
};

struct MeasuredSection {
  std::string name;
  CircleFit circle;
  double height = 0;  // of the centre along the axis from the first cone section
  double leastSquaresCircularity = 0, minimumZoneCircularity = 0;
  Vec3 minimumZoneCentre = Vec3::Zero();
  double axisOffset = 0;  // of the least-squares centre from the (best-fit cone or cylinder) axis
  // Per point: the angle about the axis from the frame's x (projected), rad in [0, 2 pi); the
  // deviation from the least-squares circle in the section plane, and normal to the cone
  // surface (radial x cos(half angle)).
  std::vector<double> phi, radial, normal;
};

struct MeasuredCone {
  std::vector<MeasuredSection> cone, cylinder;
  std::optional<Vec3> planeNormal;   // of A, towards the cone
  double flatness = 0;               // of A, range of the distances from its least-squares plane
  Vec3 axisPoint = Vec3::Zero(), axisDirection = Vec3::UnitZ();  // the cone's axis, towards the top
  // With two or more cone sections: the best-fit cone through all cone points (geometric least
  // squares, Gauss-Newton from the sections' axis and radii); the half angle positive when the
  // cone narrows towards the top; the range of the points' normal deviations from it.
  std::optional<double> halfAngle, formError;
  std::optional<double> squareness;  // angle of the cone axis to A's normal, rad
  std::optional<double> coaxiality;  // twice the largest distance of a cone section centre from C's axis
};

// `halfAngle`: the cone's nominal half angle, for the normal deviations of a single section (the
// best fit's with two or more). Throws InvalidInput for a section on one line or a plane
// without area.
MeasuredCone evaluateMeasuredCone(const ConePoints& points, double halfAngle);

}  // namespace mtacc
