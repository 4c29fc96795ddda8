#pragma once
// The compiled form of a machine with its errors (the Model of the Model/Data split): the
// two chains as sequences of factors, constant factors merged, ready for fast evaluation.
// Build once per machine and error state; evaluate many poses with the free functions of
// forward.hpp, inverse.hpp and jacobian.hpp.
#include <array>
#include <memory>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// One step of a chain: what factor(s) an element contributes, in order
// offset -> [location error] -> [motion error, fixed frame] -> joint -> [motion error, moving frame].
struct ChainElement {
  int axis = -1;     // index into Machine::axes
  int joint = -1;    // index into the joint vector q, -1 for the spindle
  AxisType type = AxisType::Linear;
  ErrorFrame frame = ErrorFrame::Moving;
  double sign = 1.0;  // +1 tool side, -1 workpiece side (ISO 841: the axis moves the workpiece)
  Vec3 offset = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  Vec3 location = Vec3::Zero();  // rotary: point on the axis line; linear: origin
};

enum class Hook { None, Location, Motion, LinearJoint };

// A factor of a chain product, tagged with what error parameters it depends on.
struct Factor {
  Pose pose;
  Hook hook = Hook::None;
  int axis = -1;
};

// One operation of the compiled evaluation program.
struct ChainOp {
  // HookMarker (programs built for point Jacobians only): the frame here is recorded; markers
  // come in pairs around each factor that carries error parameters (of `axis`, as `hook`).
  enum Kind { Constant, LinearJoint, RotaryJoint, MotionError, HookMarker } kind = Constant;
  Hook hook = Hook::None;      // HookMarker
  Pose constant = Pose::Identity();  // Constant
  bool translationOnly = false;      // Constant: no rotation (the rotation product is skipped)
  int joint = -1;
  int axis = -1;
  Vec3 vector = Vec3::Zero();  // LinearJoint: translation per unit q; RotaryJoint: unit axis
  Vec3 base = Vec3::Zero();    // LinearJoint: translation at q = 0; RotaryJoint: point on the axis
  double sign = 1.0;           // RotaryJoint
  int principal = -1;          // RotaryJoint: 0, 1, 2 when the axis is +X, +Y, +Z (fast path), else -1
  bool hasBase = false;        // RotaryJoint: the axis does not pass through the frame origin
  // MotionError: table terms grouped by their grid, so that each grid is located once per
  // pose, with their cubic coefficients copied side by side ([interval][power][table], so
  // that the tables of one interval evaluate as one vectorisable loop);
  // residualMask has bit k set when component k has terms other than tables.
  struct TableGroup {
    std::vector<double> positions;
    bool uniform = false;
    double inverseStep = 0.0;
    std::vector<int> components;
    std::vector<double> coefficients;
  };
  std::vector<TableGroup> tableGroups;
  unsigned residualMask = 0;
  bool sixTablesOnOneGrid = false;  // exactly one group holding components 0..5 in order, nothing else
};

struct KinematicModel {
  std::shared_ptr<const Machine> machine;
  ErrorModel errors;
  bool withErrors = true;
  std::vector<ChainElement> toolChain;       // bed -> tool
  std::vector<ChainElement> workpieceChain;  // bed -> workpiece
  std::vector<ChainOp> toolProgram;
  std::vector<ChainOp> workpieceProgram;
  // The same with hook markers (models compiled with errors): for point Jacobians.
  std::vector<ChainOp> toolHookProgram, workpieceHookProgram;
  // The TCP and tool direction after the tool program's trailing constant (which does not
  // depend on the pose), and how many tool operations remain to apply per pose.
  Vec3 tcpStart = Vec3::Zero();
  Vec3 toolDirectionStart = Vec3::UnitZ();
  size_t toolOpsPerPose = 0;
  Pose toolFrame = Pose::Identity();       // Trans(tool offset); also the programs' last factor
  Pose workpieceFrame = Pose::Identity();  // Trans(workpiece offset)
  Vec3 toolDirection = Vec3::UnitZ();
  Pose alignment = Pose::Identity();  // M_WC of seed 001 eq. 12 (identity for table alignment)
  bool aligned = false;               // alignment differs from the identity
  int jointCount = 0;
  // Per axis (with errors): the location error transform and its derivatives with respect to
  // its six components, which do not depend on the pose.
  std::vector<Pose> locationTransforms;
  std::vector<std::array<Mat4, 6>> locationDerivatives;
  // Per linear axis: the direction tilted by its location errors, and its derivatives with
  // respect to the three tilts (A, B, C).
  std::vector<Vec3> tiltedDirections;
  std::vector<std::array<Vec3, 3>> tiltedDirectionDerivatives;
};

// Compiles the machine with its errors. withErrors = false gives the nominal machine.
KinematicModel compile(std::shared_ptr<const Machine> machine, const ErrorModel& errors, bool withErrors = true);
KinematicModel compileNominal(std::shared_ptr<const Machine> machine);

// The factors of one element at joint value q (direction of motion dir for reversal errors).
// Hooked factors are emitted even when their errors are zero, so that derivatives exist.
void elementFactors(const KinematicModel& model, const ChainElement& e, double q, int dir, std::vector<Factor>& out);

// The joint's own motion: translation along the (tilted) direction or rotation about the
// axis line; identity for the spindle.
Pose jointPose(const KinematicModel& model, const ChainElement& e, double q);

// Translation of a linear joint with its location errors (tilt of the direction, zero offset).
Vec3 linearJointTranslation(const KinematicModel& model, const ChainElement& e, double q);

}  // namespace mtacc
