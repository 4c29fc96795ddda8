#pragma once
// The standard measurement paths on any machine, as runs ready to simulate or to pair with
// measured readings: ISO 230-4 ballbar circles, the simultaneous rotary-axis ballbar tests
// of seed 002 (Table 2), the cone-frustum-equivalent ballbar path (seed 000 ch. 4), R-test
// and touch-probe sphere tests over a rotary axis (ISO 10791-6), and the nine zones of seed
// 001's cubic machining test (directional probe).
#include <string>
#include <vector>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

// An axis's line at pose q: its location point and direction in the machine (bed) frame.
struct AxisLine {
  Vec3 point, direction;
};
AxisLine axisLine(const KinematicModel& nominal, const std::vector<double>& q, int axis);

// Sets the linear axes of q so that the nominal tool point (tool frame, relative to the
// TCP) lies at `target` (workpiece frame); the rotary axes keep their values. Throws
// UnreachablePose when no linear motion reaches it.
void placeToolPoint(const KinematicModel& nominal, std::vector<double>& q, const Vec3& toolPoint, const Vec3& target);

// Plot plane of a circular test: "XY", "YZ", "ZX" (first axis: angle 0, counter-clockwise
// towards the second). Throws InvalidInput for other names.
std::array<Vec3, 2> planeAxes(const std::string& plane);

// The centre ball is set at the actual tool ball with the centre commanded.
struct BallbarCircleSpec {
  std::string plane = "XY";
  Vec3 centre = Vec3::Zero();  // work ball, nominal, workpiece frame (mm)
  double radius = 100.0;       // bar length (mm)
  std::vector<double> pose;    // the other axes (rotary ones fixed); empty = all zero
  int points = 360;            // per direction
  bool bothDirections = true;  // counter-clockwise, then clockwise
  double feed = 1000.0;        // mm/min
  Vec3 toolBall = Vec3::Zero();
};
MeasurementRun ballbarCircle(const KinematicModel& nominal, const BallbarCircleSpec& spec);

enum class RotaryTestMode { Radial, Tangential, Axial, X, Y, Z };
// "radial", "tangential", "axial", "x", "y", "z"
RotaryTestMode parseRotaryTestMode(const std::string& name);

// Seed 002 Table 2: one rotary axis turns while the linear axes keep the bar length L. The
// work ball is set at the actual tool ball at the start pose with the rotary axes at zero
// (Eqs 11-12). Radial: the bar points from the tool ball towards the axis (tool-side axis)
// or from the work ball towards the axis (workpiece-side axis); tangential: axis x the plot
// direction;
// axial: along the axis; x/y/z: fixed machine directions. Plot angle: direction of the
// moving element from the axis (seed 002 §8).
struct BallbarRotarySpec {
  std::string axis = "C";
  RotaryTestMode mode = RotaryTestMode::Radial;
  double length = 100.0;
  Vec3 workBall = Vec3::Zero();  // nominal, workpiece frame
  Vec3 toolBall = Vec3::Zero();  // relative to the TCP, tool frame
  double from = 0.0, to = 2 * 3.14159265358979323846;
  int points = 360;
  std::vector<double> pose;  // the other axes; empty = all zero
  double feed = 1000.0;
};
MeasurementRun ballbarRotaryTest(const KinematicModel& nominal, const BallbarRotarySpec& spec);

// R-test (or touch probe): one rotary axis steps through `angles` while the linear axes keep
// the nominal ball at the sphere; one run per sphere position (workpiece frame).
struct SphereTestSpec {
  Instrument instrument = Instrument::RTest;
  std::string axis = "C";
  std::vector<double> angles;
  std::vector<Vec3> spheres;
  Vec3 toolBall = Vec3::Zero();
  std::vector<double> pose;  // the other axes; empty = all zero
};
std::vector<MeasurementRun> sphereTest(const KinematicModel& nominal, const SphereTestSpec& spec);
// n angles from `from` to `to`, both included (n = 1: `from` alone).
std::vector<double> evenAngles(double from, double to, int n);

// Points of one generated run, at most (a reading every 0.0036 deg of a circle).
constexpr int kMaxPointsPerRun = 100000;

}  // namespace mtacc
