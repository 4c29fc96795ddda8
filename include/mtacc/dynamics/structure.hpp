#pragma once
// The rigid-body model of a machine's structure (seed 000 part II, ch. 5-7): bodies with
// mass, centre of gravity and inertia, connecting elements as 6-DOF spring-dampers, the axes
// that move bodies, the tool centre point and the workpiece point. SI units inside (m, kg,
// N, s); the YAML file (docs/file-formats.md, "Structure models") states its own.
#include <array>
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"

namespace mtacc {

constexpr int kGround = -1;  // body index of the inertial system

struct RigidBody {
  std::string name;
  double mass = 0;                 // kg
  Vec3 centre = Vec3::Zero();      // centre of gravity at the home position, m
  Mat3 inertia = Mat3::Zero();     // about the centre of gravity, global axes, kg m^2
  Vec3 size = Vec3::Zero();        // bounding box for drawing, m (0 when unknown)
  Vec3 boxCentre = Vec3::Zero();   // its centre, m
  int line = 0;
};

// A primitive of a body; several are combined by the parallel-axis theorem.
struct BodyPart {
  double mass = 0;
  Vec3 centre = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();  // about its own centre
  Vec3 halfExtent = Vec3::Zero();  // of its bounding box, for drawing
};
BodyPart cuboidPart(const Vec3& size, double mass, const Vec3& centre);
struct CylinderShape {
  double radius = 0;       // m
  double innerRadius = 0;  // m, 0 for a solid cylinder
  double length = 0;       // m
  int axis = 2;            // 0, 1, 2 = x, y, z
};
BodyPart cylinderPart(const CylinderShape& shape, double mass, const Vec3& centre);
// Right triangular prism: legs size.x (along x) and size.y (along y) from the right-angle
// edge, extruded by size.z along z; `centre` is its centroid.
BodyPart prismPart(const Vec3& size, double mass, const Vec3& centre);
RigidBody combineParts(const std::string& name, const std::vector<BodyPart>& parts);

// A 6-DOF spring-damper between body a and body b (either may be kGround) at `point`, with
// local axes as the columns of `frame`: stiffness and damping along x, y, z, about x, y, z.
// The point moves with body b (or with a: a carriage fixed on a that a moving beam slides
// through). A side given as a flexible beam attaches to the segment under the point at each
// position (a carriage riding along the beam).
struct Connection {
  std::string name;
  std::string type;  // guide, drive, direct_drive, bearing, setup, spring, beam
  int a = kGround, b = kGround;
  bool followsA = false;
  int beamA = -1, beamB = -1;  // index into StructureModel::beams when a side is a beam
  Vec3 point = Vec3::Zero();   // at the home position, m
  Mat3 frame = Mat3::Identity();
  Vec6 stiffness = Vec6::Zero();  // N/m, N m/rad
  Vec6 damping = Vec6::Zero();    // N s/m, N m s/rad
  int line = 0;
};

struct StructureAxis {
  std::string name;
  Vec3 direction = Vec3::UnitX();
  std::vector<int> moves;  // bodies the axis carries (the driven body and everything on it)
  double min = 0, max = 0;  // travel, m
};

// A flexible beam's segments (consecutive bodies) and where they meet along its axis.
struct BeamSegments {
  std::string name;
  int first = 0;                 // body index of segment 1; segments are first .. first + 4
  Vec3 from = Vec3::Zero(), axis = Vec3::UnitX();  // at the home position, m
  double length = 0;
  // The segment (its body index) at the fraction s of the length from `from`: the segments
  // are 1:2:2:2:1 of the length; points before the start or beyond the end go to the ends.
  int segmentAt(double s) const;
};

struct StructureModel {
  std::string name;
  std::vector<BeamSegments> beams;
  std::string sourceFile;
  std::vector<RigidBody> bodies;
  std::vector<Connection> connections;
  std::vector<StructureAxis> axes;
  int tcpBody = kGround;
  Vec3 tcpPoint = Vec3::Zero();
  int workpieceBody = kGround;
  Vec3 workpiecePoint = Vec3::Zero();

  int dofs() const { return 6 * static_cast<int>(bodies.size()); }
  int axisIndex(const std::string& name) const;
  int bodyIndex(const std::string& name) const;  // kGround for "ground"; -2 if unknown
};

// A flexible beam as written in a structure file (SI units).
struct BeamSpec {
  std::string name;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // m
  std::array<double, 2> section{};               // width, height of the cross-section, m
  double massPerLength = 0;                      // kg/m
  double youngsModulus = 0, shearModulus = 0;    // E, G, N/m^2
  double area = 0, torsionConstant = 0;          // A m^2, It m^4
  std::array<double, 2> areaMoments{};           // I about the section's two axes, m^4
  double stiffnessDamping = 0;                   // beta: damping = beta * stiffness
  Vec3 up = Vec3::UnitZ();
};
// Adds the beam as five rigid segments and the four connections that join them.
void addBeam(StructureModel& model, const BeamSpec& beam, int line);

}  // namespace mtacc
