#pragma once
// SINUMERIK's orientable toolholder ($TC_CARR1 ... $TC_CARR33, function manual W1 "Tool offset",
// the data set CYCLE800 swivels with and CYCLE996 measures): two rotary axes described by the
// offset vectors l1 ... l4, the axis vectors v1, v2 and the axes' angle offsets, for a swivel head
// (kinematic type T), a swivel table (P) or a head axis with a table axis (M). Fitted by least
// squares to the machine with its errors it carries the rotary axis lines' positions and
// directions, their zero offsets and, on a head, the spindle's offset from the pivots; what it
// cannot carry is named, error by error, and its effect is the residual the fit leaves.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct SiemensToolholder {
  char type = 'T';  // $TC_CARR23: 'T' both axes in the head, 'P' both in the table, 'M' v1 in the head, v2 in the table
  // l1 ... l4 (mm, $TC_CARR1-6, 15-20) in the axes' initial state, each from the tool tip side to
  // the machine side (CYCLE800's chains): T: l3 tool adapter to axis 2, l2 axis 2 to axis 1, l1
  // back to the toolholder's reference point; P: l2 machine reference to axis 1, l3 axis 1 to
  // axis 2, l4 back; M: l2 adapter to axis 1, l1 back; l3 machine reference to axis 2, l4 back.
  std::array<Vec3, 4> l{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  std::array<Vec3, 2> v{Vec3::UnitZ(), Vec3::UnitZ()};  // $TC_CARR7-12; used as unit vectors
  std::array<std::string, 2> axes;                     // $TC_CARR21, 22: the machine's axis names
  std::array<double, 2> offset{0.0, 0.0};              // $TC_CARR24, 25 (rad): each axis's position in the initial state

  // Where the controller puts the toolholder's reference point (the machine's X, Y, Z, mm) for
  // the tool tip at `point` (workpiece, mm) with the axes at `angles` (rad) and the tool vector
  // `tool` (tip to adapter, mm), each axis turning what it carries right-handed about v by its
  // angle less its offset (R1, R2): T: point + l1 + R1 (l2 + R2 (l3 + tool)); P: the point on the
  // table where it is, l2 + R1 (l3 + R2 (point + l4)), less its initial l2 + l3 + l4, plus tool;
  // M: the table's part l3 + R2 (point + l4) less l3 + l4, plus the head's l1 + R1 (l2 + tool).
  Vec3 machinePosition(const Vec3& point, const std::array<double, 2>& angles, const Vec3& tool) const;
  std::string carries() const;  // what of the machine's geometry the data set holds
};

struct SiemensToolholderFit {
  SiemensToolholder nominal;  // fitted to the nominal machine (it fits exactly, or the machine is refused)
  SiemensToolholder actual;   // fitted to the machine with its errors
  // The machine's workpiece coordinates of the controller's zero (mm, nominal), and its shift and
  // the rotation vector of its axes (rad) on the machine with its errors: the work offset and
  // rotation a probed workpiece sets (a table axis's location errors turn what it carries).
  Vec3 worldOrigin = Vec3::Zero(), workOffset = Vec3::Zero(), workRotation = Vec3::Zero();
  TableResidual residual;               // over the poses: before with the nominal data set, after with the fitted one
  std::vector<std::string> notCarried;  // the model's errors the data set cannot carry, named with what each leaves
};

// Throws InputError when the machine has other than linear X, Y, Z and two rotary axes, or a
// nominal geometry the data set does not reproduce (fit residual above 1 nm). The poses: a 3 x 3 x 3
// lattice over the middle half of each linear travel, 9 angles of the first rotary axis over its
// travel and 12 of the second, kept where the commands stay within travel.
SiemensToolholderFit fitSiemensToolholder(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors);

// The controller running the fitted data set, the workpiece probed on the machine with its errors:
// the change of the X, Y, Z commands q that reaches the point the nominal machine reaches at q.
CommandCorrection siemensToolholderCorrection(const std::shared_ptr<const Machine>& machine, const SiemensToolholderFit& fit);

// A part program assigning the data set to toolholder `number` (N blocks "$TC_CARRn[m]=value", mm
// and degrees, as the W1 examples write them), with ';' comments stating what it carries and what
// not, the work offset and the residual, ending with M17.
std::string siemensToolholderProgram(const Machine& machine, const SiemensToolholderFit& fit, int number = 1);

// The same data set as the generic 5-axis transformation's channel machine data (MD24100
// $MC_TRAFO_TYPE_1 = 24 for T, 40 for P, 56 for M; the offset vectors as TRAFO5_PART_OFFSET_1,
// _JOINT_OFFSET_1, _BASE_TOOL_1, _JOINT_OFFSET_PART_1 by the SINUMERIK Operate commissioning
// manual's table "Interrelation of TOOLCARRIER and 5-axis transformation"; v1, v2 as
// TRAFO5_AXIS1_1, _AXIS2_1; the angle offsets as TRAFO5_ROT_AX_OFFSET_1), as an INI file: ';'
// comments, CHANDATA(1), "$MC_...[i]=value" lines, M17.
std::string siemensTrafo5MachineData(const Machine& machine, const SiemensToolholderFit& fit);
struct Trafo5Vector {
  const char* name;  // machine data without the "$MC_" prefix and the "_1" suffix
  int l;             // which offset vector it holds (0 for l1 ... 3 for l4)
};
// Which offset vectors a kinematic type's transformation machine data hold.
std::vector<Trafo5Vector> trafo5Vectors(char type);

}  // namespace mtacc
