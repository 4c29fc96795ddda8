#pragma once
// The cubic machining test of seed 001 (Li, Sato et al., Precision Engineering 71 (2021)) on
// any five-axis machine: a block whose top face is cut in square zones by 3-axis zig-zag
// passes, the rotary axes clamped per zone so that the tool leans towards the block centre.
// Every nominal face is the same plane, so a step between zones or a tilt inside one shows the
// machine's errors. Lengths in mm, angles in rad, points in the workpiece frame.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

enum class ToolShape { Ball, Flat };

struct CuttingTool {
  ToolShape shape = ToolShape::Ball;
  double radius = 3.0;  // ball radius, or flat-end (disc) radius
};

struct CubicZone {
  std::string name;
  double x = 0, y = 0;             // centre of the square zone, workpiece frame
  Vec3 toolVector = Vec3::UnitZ();  // unit, from the tool tip towards the holder (seed 001 Table 1)
};

struct CubicTestSpec {
  double blockSize = 48;   // side of the square top face
  double centreX = 0, centreY = 0;  // centre of the top face in the workpiece frame
  double zoneSize = 16;    // side of each square zone
  double topHeight = 50;   // z of the finished top face (its height above the B/C pivot)
  std::vector<CubicZone> zones;
  CuttingTool tool;
  double pick = 0.1;       // zig-zag pitch
  double depth = 0.1;      // stock above the finished face
  double feed = 2000;      // mm/min
  TiltBranch branch = TiltBranch::Positive;  // seed 001 Table 2 has B = +30 deg in every zone
};

// n x n zones of blockSize / n over the face centred at (cx, cy): the tool normal to the face in
// the centre zone (n odd) and tilted by `tilt` towards the block centre elsewhere (seed 001
// L88). For n = 3 the zones carry the seed's names (I, II-1..4, III-1..4, Fig. 2) in its
// machining order (L227); otherwise "r<row>c<column>" from the lower left.
std::vector<CubicZone> cubicZoneGrid(int n, double blockSize, double tilt, double cx = 0, double cy = 0);
// Seed 001 §2, Table 4: 48 mm block, 3 x 3 zones tilted 30 deg, ball-end mill of 6 mm
// diameter, 0.1 mm pick and depth, 2000 mm/min; top face 50 mm above the pivot (not given in
// the seed; irrelevant to first order, extraction §7).
CubicTestSpec seed001CubicTest();
// What makes a spec a test that cannot be cut: the offending key ("pick", "zones[3]") and why.
struct SpecProblem {
  std::string key, what;
};
std::optional<SpecProblem> cubicTestSpecProblem(const CubicTestSpec& spec);

// The tool tip (the NC point) for a contact point on the face (seed 001 eq. 1 for the ball;
// for a flat end, the disc centre whose lowest rim point is the contact point).
Vec3 toolTipForContact(const Vec3& contact, const Vec3& toolVector, const CuttingTool& tool);

// One zone's zig-zag passes along x at pitch `pick` in y, contact points over the whole zone,
// with its clamped rotary axes.
struct CubicZonePath {
  std::vector<double> clamped;  // the commanded axes at the zone's first point (rotary axes fixed)
  PointMatrix tips;             // tool tips (CL points) along the path
  JointMatrix q;                // commanded axes at each tip
  DirectionMatrix direction;    // direction of motion of each axis arriving at each point
  // Clear of the stock (kCubicClearance along the tool above the first and the last tip).
  std::vector<double> approach, retract;
};
constexpr double kCubicClearance = 5.0;  // mm above the stock

// The test's tool path through the machine's inverse kinematics, zone by zone. Throws
// UnreachableTarget when a zone cannot be reached within travel.
std::vector<CubicZonePath> cubicToolPath(const KinematicModel& nominal, const CubicTestSpec& spec);

// The direction each axis moves arriving at each row of q (the first row: leaving it): +1, -1 or 0.
DirectionMatrix motionDirections(const JointMatrix& q);
// The cutting runs of recorded axis positions (seed 001 §4.1, Eqs 13-14: the CL data from the
// actual positions a servo tool records): the maximal runs in which every rotary axis stays
// within `still` rad of its value at the run's start (the test cuts with the rotary axes
// clamped and repositions clear of the stock between zones), each a path the machined surface
// follows from sample to sample; runs of a single sample are left out.
std::vector<CubicZonePath> recordedCuttingRuns(const Machine& machine, const JointMatrix& q, double still = 1.7e-5);

// The test as a measurement plan: one directional-probe run per zone reading the height of the
// surface (the workpiece-z deviation of the ball centre, or of the contact point of a flat end)
// at the zone centre and, with `slopes`, a quarter zone along x and along y from it, so that
// the readings carry the zone's mean height and in-zone tilt.
std::vector<MeasurementRun> cubicZoneRuns(const KinematicModel& nominal, const CubicTestSpec& spec, bool slopes);
// The points of a zone run, relative to the zone centre.
std::vector<std::array<double, 2>> cubicZoneRunPoints(const CubicTestSpec& spec, bool slopes);

}  // namespace mtacc
