#pragma once
// What a machine is: its axes, the two kinematic chains (bed -> tool, bed -> workpiece),
// the tool and the workpiece frame. Immutable once loaded; evaluation lives in kinematics/.
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/machine/structure_code.hpp"

namespace mtacc {

enum class AxisType { Linear, Rotary, Spindle };
enum class Side { Tool, Workpiece };
// Where an axis's component error motions act: in the frame that moves with the axis
// (after the joint) or in the frame of the guide / stator (before the joint). See
// docs/conventions.md; seed 003 §3.5 calls these moving and fixed frames.
enum class ErrorFrame { Moving, Fixed };
// How the workpiece sits on the machine (seed 001): fixed to the table frame (eq. 2), or
// aligned with the machine at a reference pose (eqs. 10-12, M_WC).
enum class WorkpieceAlignment { Table, Machine };

struct Travel {
  double min;
  double max;
};

struct Axis {
  std::string name;  // "X", "B", "C1", ...
  AxisType type = AxisType::Linear;
  Side side = Side::Tool;
  Vec3 direction = Vec3::UnitX();  // unit; motion of the tool relative to the workpiece (ISO 841)
  Vec3 location = Vec3::Zero();    // rotary: a point on the nominal axis line, in the axis frame (mm)
  Vec3 offset = Vec3::Zero();      // origin of the axis frame in the previous frame at home (mm)
  ErrorFrame errorFrame = ErrorFrame::Moving;
  std::optional<Travel> travel;  // mm or rad; empty for a continuous rotary axis or the spindle
  int line = 0;                  // line in the machine file, for messages

  bool commanded() const { return type != AxisType::Spindle; }
  // The machine direction a linear axis is named after: 0, 1, 2 for X (U), Y (V), Z (W).
  int ownComponent() const;
  bool isRotary() const { return type != AxisType::Linear; }
  // One unit of the axis in files and programs (mm, or deg for a rotary axis) in mtacc's
  // internal unit (mm, rad).
  double fileUnit() const { return isRotary() ? kDeg : 1.0; }
};

struct Machine {
  std::string name;
  std::string sourceFile;
  StructureCode structure;
  // All elements: the commanded axes in canonical order (linear X Y Z U V W, then rotary
  // A B C, each with its suffix), followed by the spindle if the code names one. Joint
  // vectors q hold the commanded axes in this order.
  std::vector<Axis> axes;
  std::vector<int> toolChain;       // indices into axes, from the bed to the tool
  std::vector<int> workpieceChain;  // indices into axes, from the bed to the workpiece
  Vec3 toolOffset = Vec3::Zero();   // TCP in the frame after the last tool-chain element (mm)
  Vec3 toolDirection = Vec3::UnitZ();  // unit vector from the TCP towards the spindle, same frame
  Vec3 workpieceOffset = Vec3::Zero();  // workpiece origin in the last workpiece-chain frame (mm)
  WorkpieceAlignment alignment = WorkpieceAlignment::Table;
  std::vector<double> referencePose;  // commanded axes; used by WorkpieceAlignment::Machine
  Vec3 vertical = Vec3::UnitZ();  // unit, the machine's up direction (seed 003's classification)

  int commandedCount() const;
  // The commanded axes' names in joint-vector order.
  std::vector<std::string> commandedAxisNames() const;
  int rotaryCount() const;
  // Index of the spindle in axes, or -1 when the structure code names none.
  int spindleIndex() const;
  // Index of an axis (the spindle included) by name, or -1.
  int axisIndex(const std::string& name) const;
  // Index of a commanded axis (an entry of a joint vector) by name, or -1.
  int commandedAxisIndex(const std::string& name) const;
  // Empty when every commanded axis is within its travel, else e.g.
  // "X=500 mm beyond travel [-400, 400] mm" for the first axis outside.
  std::string travelViolation(std::span<const double> q) const;
  // "X=10 mm, B=-15 deg" for messages.
  std::string describePose(const std::vector<double>& q) const;
};

}  // namespace mtacc
