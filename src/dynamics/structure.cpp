#include "mtacc/dynamics/structure.hpp"

#include <algorithm>
#include <cmath>

namespace mtacc {
namespace {

Mat3 parallelAxis(double mass, const Vec3& d) { return mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()); }

}  // namespace

BodyPart cuboidPart(const Vec3& s, double mass, const Vec3& centre) {
  BodyPart p{mass, centre, Mat3::Zero(), s / 2};
  p.inertia.diagonal() << s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y();
  p.inertia *= mass / 12;
  return p;
}

BodyPart cylinderPart(const CylinderShape& shape, double mass, const Vec3& centre) {
  const double r = shape.radius, ri = shape.innerRadius, l = shape.length;
  const int axis = shape.axis;
  BodyPart p{mass, centre, Mat3::Zero(), Vec3::Constant(r)};
  p.halfExtent[axis] = l / 2;
  const double along = mass * (r * r + ri * ri) / 2, across = mass * (3 * (r * r + ri * ri) + l * l) / 12;
  p.inertia.diagonal().setConstant(across);
  p.inertia(axis, axis) = along;
  return p;
}

BodyPart prismPart(const Vec3& size, double mass, const Vec3& centre) {
  const double a = size.x(), b = size.y(), l = size.z();
  BodyPart p{mass, centre, Mat3::Zero(), Vec3(2 * a / 3, 2 * b / 3, l / 2)};
  p.inertia(0, 0) = mass * (b * b / 18 + l * l / 12);
  p.inertia(1, 1) = mass * (a * a / 18 + l * l / 12);
  p.inertia(2, 2) = mass * (a * a + b * b) / 18;
  p.inertia(0, 1) = p.inertia(1, 0) = mass * a * b / 36;  // -integral x'y' dm
  return p;
}

RigidBody combineParts(const std::string& name, const std::vector<BodyPart>& parts) {
  RigidBody b;
  b.name = name;
  for (const auto& p : parts) {
    b.mass += p.mass;
    b.centre += p.mass * p.centre;
  }
  b.centre /= b.mass;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const auto& p : parts) {
    b.inertia += p.inertia + parallelAxis(p.mass, p.centre - b.centre);
    lo = lo.cwiseMin(p.centre - p.halfExtent);
    hi = hi.cwiseMax(p.centre + p.halfExtent);
  }
  b.size = hi - lo;
  b.boxCentre = (hi + lo) / 2;
  return b;
}

int StructureModel::axisIndex(const std::string& n) const {
  for (size_t i = 0; i < axes.size(); ++i)
    if (axes[i].name == n) return static_cast<int>(i);
  return -1;
}

int StructureModel::bodyIndex(const std::string& n) const {
  if (n == "ground") return kGround;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == n) return static_cast<int>(i);
  return -2;
}

int BeamSegments::segmentAt(double s) const {
  constexpr double bounds[4] = {1.0 / 8, 3.0 / 8, 5.0 / 8, 7.0 / 8};
  int k = 0;
  while (k < 4 && s > bounds[k]) ++k;
  return first + k;
}

// seed 000 §5.x: a flexible beam as five rigid segments, lengths 1:2:2:2:1, joined at four
// points by the beam's stiffness over the joint spacing L/4 (axial EA/l, shear, torsion
// G It/l, bending E I/l).
void addBeam(StructureModel& m, const BeamSpec& beam, int line) {
  const Vec3 from = beam.from;
  const double length = (beam.to - beam.from).norm();
  const Vec3 axis = (beam.to - beam.from) / length;
  const std::string& name = beam.name;
  const double perLength = beam.massPerLength, e = beam.youngsModulus, g = beam.shearModulus, area = beam.area,
               it = beam.torsionConstant, beta = beam.stiffnessDamping;
  const auto& inertia = beam.areaMoments;
  Mat3 frame = Mat3::Identity();
  frame.col(0) = axis;
  {
    Vec3 up = beam.up;
    if (std::abs(up.dot(axis)) > 0.99) up = Vec3::UnitX();
    frame.col(1) = up.cross(axis).normalized();
    frame.col(2) = axis.cross(frame.col(1));
  }
  m.beams.push_back({name, static_cast<int>(m.bodies.size()), from, axis, length});
  const double fractions[5] = {1, 2, 2, 2, 1};
  double s = 0;
  for (int k = 0; k < 5; ++k) {
    const double l = length * fractions[k] / 8;
    const Vec3 centre = from + axis * (s + l / 2);
    // Segment inertia: a cuboid of the section, along the beam axis.
    const Vec3 local(l, beam.section[0], beam.section[1]);
    const BodyPart part = cuboidPart(local, perLength * l, Vec3::Zero());
    RigidBody body;
    body.name = name + "." + std::to_string(k + 1);
    body.mass = part.mass;
    body.centre = centre;
    body.inertia = frame * part.inertia * frame.transpose();
    body.size = (frame * local).cwiseAbs();
    body.boxCentre = centre;
    body.line = line;
    m.bodies.push_back(body);
    s += l;
    if (k < 4) {
      const double spacing = length / 4;
      Connection c;
      c.name = name + ".joint" + std::to_string(k + 1);
      c.type = "beam";
      c.a = static_cast<int>(m.bodies.size()) - 1;
      c.b = c.a + 1;
      c.point = from + axis * s;
      c.frame = frame;
      const double shear = 12 * e * std::min(inertia[0], inertia[1]) / (spacing * spacing * spacing);
      c.stiffness << e * area / spacing, shear * 1e3, shear * 1e3, g * it / spacing, e * inertia[0] / spacing,
          e * inertia[1] / spacing;
      c.damping = beta * c.stiffness;
      c.line = line;
      m.connections.push_back(c);
    }
  }
}


}  // namespace mtacc
