#pragma once
// The 5-axis cone-frustum test piece of seed 000 part I (Bossoni, ETH): geometry and tool path,
// axis motions through the generic inverse kinematics, and the equivalent cone form error
// caused by the machine's errors (exact procedure of §3.9 and the first-order shortcut).
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

struct ConeSpec {
  double alpha = 45 * 3.14159265358979323846 / 180;  // half apex angle; negative: upside down
  double beta = 30 * 3.14159265358979323846 / 180;   // inclination of the cone axis (about y)
  double radius = 40.0;                              // TCP path radius r, mm
  Vec3 centre{-65.0, 0.0, 150.0};                    // path centre O in the workpiece frame, mm
  double gamma = 0.0;                                // turn of the inclined cone about the workpiece z
  bool faceMilling = false;                          // tool normal to the surface instead of along the slant
};

// Recommended set-ups of seed 000 §3.6, the set-up cut at IWF for comparison (Table 3.6,
// "seed000-comparison") and the NAS 979 cone frustum (§2.1, Table 2.1). nullopt if unknown.
std::optional<ConeSpec> conePreset(const std::string& name);
// "tilting-table, swivel-head, double-pivot, seed000-comparison, nas979"
std::string conePresetNames();
// The §3.6 preset for a machine's family: both rotary axes on the workpiece side
// ("tilting-table"), both on the tool side ("double-pivot"), or one on each ("swivel-head");
// nullopt unless the machine has exactly two rotary axes.
std::optional<std::string> conePresetName(const Machine& machine);

// TCP points, tool directions and outward surface normals around the path (workpiece frame).
struct ConePath {
  std::vector<double> phi;  // rad, [0, 2 pi)
  std::vector<Vec3> points;
  std::vector<Vec3> tools;
  std::vector<Vec3> normals;
};
ConePath conePath(const ConeSpec& spec, int points);
// Points needed so that the chord between neighbours deviates at most `tolerance` (mm).
int pointsForChordTolerance(const ConeSpec& spec, double tolerance);

// Table 3.1 of seed 000 (L2352-2363): closed-form ranges of the rotary axes (for |alpha|, |beta|).
struct RotaryRanges {
  double tiltMin, tiltMax, tiltRange, rotaryRange;  // rad (|B| extremes, their difference, dC)
  std::string caseName;                              // "alpha > beta", "alpha < beta", "alpha = beta (...)"
};
RotaryRanges rotaryRangesClosedForm(double alpha, double beta, bool startAtPole = true);
// dC/dphi at phi = 0: sin(alpha) / sin(alpha - beta) (§3.4.4); infinite at alpha = beta.
double rotarySpeedFactorAtStart(double alpha, double beta);

struct AxisMotion {
  std::string axis;
  double min = 0, max = 0, range = 0;       // mm or rad
  bool moves = false;                       // range above rounding (1e-9 of the position)
  std::vector<double> reversalsPhi;         // rad, where the axis changes direction
  double maxSpeed = 0, maxAcceleration = 0; // per minute and per minute^2 at the feed (mm or rad)
};

struct ConeMotion {
  JointMatrix q;              // per point, commanded axes (mm, rad)
  DirectionMatrix direction;  // per point, sign of the motion of each axis
  std::vector<AxisMotion> axes;
  std::vector<std::string> warnings;    // singular or near-singular set-up
};

// How the path is driven: the tilt branch of the inverse kinematics and the contouring feed.
struct ConeDrive {
  TiltBranch branch = TiltBranch::Negative;
  double feed = 500.0;  // mm/min
};
// Solves the path through the generic inverse kinematics, continuous from phi = 0 on the
// drive's tilt branch, and analyses each axis at its feed.
ConeMotion coneMotion(const KinematicModel& nominal, const ConeSpec& spec, const ConePath& path,
                      const ConeDrive& drive = {});

// Equivalent cone form error, peak to valley (mm), of the TCP points a machine with errors
// produces when driven along the nominal axis positions of `motion`.
struct ConeFormResult {
  double formError = 0;               // mm, peak to valley
  std::vector<double> deviation;      // mm per point, after removing mean and first harmonic
  std::vector<double> rawDeviation;   // mm per point, normal deviation before the circle fit
};
// Exact procedure of §3.9: FK with errors -> LS plane, LS circle -> cone axis -> normal
// distances -> LS circle (mean and first harmonic removed) -> PV.
ConeFormResult coneFormErrorExact(const KinematicModel& actual, const ConeSpec& spec, const ConePath& path,
                                  const ConeMotion& motion);
// First order: e_i = n_i . (P_actual - P_nominal), mean and first harmonic removed, PV.
ConeFormResult coneFormErrorFirstOrder(const KinematicModel& actual, const KinematicModel& nominal,
                                       const ConePath& path, const ConeMotion& motion);

// Seed 000 §3.10.4: a deviation symmetric about phi = 0 / 180 deg (the plane of the cone
// axis and the rotary axis) is "top-bottom" (type 1); an antisymmetric one is "asymmetric"
// (type 2). Decided by the larger RMS of the symmetric and antisymmetric parts; needs points
// spaced evenly over the full turn.
enum class FormErrorType { TopBottom, Asymmetric };
FormErrorType formErrorType(const std::vector<double>& deviation);
const char* toString(FormErrorType t);

// Removes the least-squares a0 + a1 cos(phi) + b1 sin(phi) from values (in place).
void removeFirstHarmonic(const std::vector<double>& phi, std::vector<double>& values);

}  // namespace mtacc
