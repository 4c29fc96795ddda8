#pragma once
// LinuxCNC's 5-axis kinematics modules and their parameters (HAL pins): the table-rotary-tilting
// modules xyzac-trt-kins and xyzbc-trt-kins (trtfuncs.c: a table tilting about A or B carries a
// rotary table C), 5axiskins (a head tilting about B carried by a head turning about C, both
// lines through the pivot) and maxkins (a head tilting about B over a rotary table C). Fitted by
// least squares to the machine with its errors, the pins carry what they can of the errors: the
// rotary axis lines' positions for the trt modules, the pivot length for the head modules. What
// they cannot carry is named, error by error, and its effect is the residual the fit leaves.
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct LinuxcncKinematics {
  enum class Module { XyzacTrt, XyzbcTrt, FiveAxis, Max };
  Module module = Module::XyzbcTrt;
  // trt (mm, tool-offset 0): the C line passes through (x-rot-point, y-rot-point); the tilting
  // line through the rot point plus the offsets (y and z for A, x and z for B). z-rot-point is 0:
  // only its sum with z-offset matters.
  double xRotPoint = 0.0, yRotPoint = 0.0, xOffset = 0.0, yOffset = 0.0, zOffset = 0.0;
  // 5axiskins, maxkins: pivot-length (mm), the pivot to the tool tip with the machine file's tool.
  double pivotLength = 0.0;
  // maxkins: its pin conventional-directions (B turns the conventional way; the default is the opposite).
  bool conventionalDirections = false;

  std::string name() const;  // the module, its pins' prefix: "xyzbc-trt-kins", "5axiskins", "maxkins"
  char tilt() const { return module == Module::XyzacTrt ? 'A' : 'B'; }
  std::string carries() const;  // what of the machine's geometry the pins hold
  // LinuxCNC's inverse kinematics with U, V, W at 0: the joints X, Y, Z (mm) that put the tool tip
  // at `world` (mm) with the tilting axis at `tiltAngle` and C at `cAngle` (rad, LinuxCNC's angles).
  //   trt:       R_tilt (R_z(c) (world - r) - d) + r + d
  //   5axiskins: world - L (sin t cos c, sin t sin c, 1 - cos t)
  //   maxkins:   R_z(-c) world + (k L sin t, 0, -L (1 - cos t)), k = +1 conventional, -1 not
  Vec3 joints(const Vec3& world, double tiltAngle, double cAngle) const;
  // The pins the module reads, as written to the HAL file.
  std::vector<std::pair<std::string, double>> pins() const;
};

struct LinuxcncKinematicsFit {
  LinuxcncKinematics nominal;  // fitted to the nominal machine (it fits exactly, or the machine is refused)
  LinuxcncKinematics actual;   // fitted to the machine with its errors
  // LinuxCNC's angle = sign x the machine's command, for the tilting axis and C.
  std::array<int, 2> sign{1, 1};
  Vec3 worldOrigin = Vec3::Zero();  // the machine's workpiece coordinates of LinuxCNC's world origin (mm)
  // The shift of that origin on the machine with its errors (mm): the work offset a probed
  // workpiece sets; the location errors in mtacc's convention move everything an axis carries.
  Vec3 workOffset = Vec3::Zero();
  // maxkins: the machine's X, Y, Z commands at LinuxCNC's joint zero, where the tool tip is on the
  // C line at B = 0 (nominal), and its shift on the machine with its errors (mm): what the joints'
  // HOME_OFFSET sets. Zero for the other modules, whose joints are the machine's commands.
  Vec3 jointOrigin = Vec3::Zero(), jointOriginShift = Vec3::Zero();
  // TCP position error of the machine with its errors over the poses, the work offset fitted in
  // both: before with the nominal parameters, after with the fitted ones.
  TableResidual residual;
  // The model's errors the pins cannot carry, each named with what it leaves alone (largest over
  // the poses, um), and what the standing kinematics never see (reversals, stiffness changes).
  std::vector<std::string> notCarried;
};

// Throws InputError when the machine is none of the modules: commanded axes other than X, Y, Z, A
// or B, and C; rotary axes in another arrangement; or a nominal geometry the module does not
// reproduce (fit residual above 1 nm). The poses: a 3 x 3 x 3 lattice over the middle half of each
// linear travel, 9 tilting angles over its travel (+-90 deg when it has none) and 12 of C, kept
// where the joints stay within travel.
LinuxcncKinematicsFit fitLinuxcncKinematics(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors);

// LinuxCNC running the fitted module, the workpiece probed on the machine with its errors: the
// change of the X, Y, Z commands q that it makes to reach the point the nominal machine reaches at q.
CommandCorrection linuxcncCorrection(const std::shared_ptr<const Machine>& machine, const LinuxcncKinematicsFit& fit);

// The HAL commands "setp <module>.<pin> <value>" (mm) with '#' comment lines stating what the
// parameters carry and what not, the joint signs, the origins and the residual.
std::string linuxcncKinematicsHal(const Machine& machine, const LinuxcncKinematicsFit& fit);

}  // namespace mtacc
