#pragma once
// LinuxCNC's table-rotary-tilting kinematics (xyzac-trt-kins, xyzbc-trt-kins; trtfuncs.c): a
// table tilting about A (along X) or B (along Y) carries a rotary table C (along Z); the tool
// point moves in X, Y, Z. Their parameters place the two axis lines, and they are what the
// rotary axes' location errors map onto: fitted by least squares to the machine with its errors,
// they carry the lines' positions; not their orientations or zero offsets, nor the linear axes'
// errors, nor component errors, whose part is the residual the fit leaves.
#include <array>
#include <memory>
#include <string>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct LinuxcncTrt {
  char tilt = 'B';  // 'A': xyzac-trt-kins, 'B': xyzbc-trt-kins
  // mm, tool-offset 0. The C line passes through (x-rot-point, y-rot-point); the tilting line
  // through the rot point plus the offsets (y and z for A, x and z for B). z-rot-point is 0:
  // only its sum with z-offset matters.
  double xRotPoint = 0.0, yRotPoint = 0.0, xOffset = 0.0, yOffset = 0.0, zOffset = 0.0;

  std::string kinsName() const { return tilt == 'A' ? "xyzac-trt-kins" : "xyzbc-trt-kins"; }
  // LinuxCNC's inverse kinematics (its default, unconventional directions): the joints X, Y, Z
  // (mm) that put the tool point at `world` (mm, the table's frame) with the table at the angles
  // (rad) `tiltAngle` and `cAngle`: joints = R_tilt (R_z(c) (world - r) - d) + r + d.
  Vec3 joints(const Vec3& world, double tiltAngle, double cAngle) const;
};

struct LinuxcncTrtFit {
  LinuxcncTrt nominal;  // fitted to the nominal machine (it fits exactly, or the machine is refused)
  LinuxcncTrt actual;   // fitted to the machine with its errors
  // LinuxCNC's angle = sign x the machine's command, for the tilting axis and C.
  std::array<int, 2> sign{1, 1};
  Vec3 worldOrigin = Vec3::Zero();  // the machine's workpiece coordinates of LinuxCNC's world origin (mm)
  // The shift of that origin on the machine with its errors (mm): the work offset a probed
  // workpiece sets; the location errors in mtacc's convention move everything an axis carries.
  Vec3 workOffset = Vec3::Zero();
  // TCP position error of the machine with its errors over the poses, the work offset fitted in
  // both: before with the nominal parameters, after with the fitted ones.
  TableResidual residual;
};

// Throws InputError when the machine is not of this form: commanded axes other than X, Y, Z, A or
// B, and C; rotary axes not both on the table with the tilting axis carrying C; or a nominal
// geometry the kinematics do not reproduce (fit residual above 1 nm). The poses: a 3 x 3 x 3
// lattice over the middle half of each linear travel, 9 tilting angles over its travel (+-90 deg
// when it has none) and 12 of C, kept where the joints stay within travel.
LinuxcncTrtFit fitLinuxcncTrt(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors);

// The HAL commands "setp <kins>.<pin> <value>" (mm) with '#' comment lines stating what the
// parameters carry, the joint signs and the residual.
std::string linuxcncTrtHal(const Machine& machine, const LinuxcncTrtFit& fit);

}  // namespace mtacc
