#pragma once
// Exact forward kinematics: the tool (TCP and tool direction) relative to the workpiece,
// nominal or with all errors, for one pose or a batch. Joint vectors hold the commanded
// axes in Machine::axes order, linear in mm, rotary in rad. `dir` (may be null) gives the
// direction of motion of each axis (+1, -1, 0) for reversal errors.
#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

// Bed -> tool frame (TCP) and bed -> workpiece frame.
Pose toolChainPose(const KinematicModel& model, const double* q, const int* dir);
Pose workpiecePose(const KinematicModel& model, const double* q, const int* dir);
// Tool frame in the workpiece frame (includes M_WC when the workpiece is aligned).
Pose toolInWorkpiece(const KinematicModel& model, const double* q, const int* dir = nullptr);

struct ToolPoint {
  Vec3 position;   // TCP in the workpiece frame, mm
  Vec3 direction;  // unit tool direction (TCP towards spindle) in the workpiece frame
};
ToolPoint toolPoint(const KinematicModel& model, const double* q, const int* dir = nullptr);
// The TCP alone (mm, workpiece frame): toolPoint's position without carrying the direction.
Vec3 toolPosition(const KinematicModel& model, const double* q, const int* dir = nullptr);
// The TCP (as toolPosition) and workpiecePose's rotation in one pass through the chains.
struct ToolPositionAndWorkpieceRotation {
  Vec3 position;
  Mat3 workpieceRotation;
};
ToolPositionAndWorkpieceRotation toolPositionAndWorkpieceRotation(const KinematicModel& model, const double* q, const int* dir = nullptr);

// Pose error, actual minus nominal, in the workpiece frame: (dx, dy, dz) in mm, then the
// rotation vector of R_actual * R_nominal^T in rad.
Vec6 poseError(const Pose& actual, const Pose& nominal);

// Poses, one per row of q, with their directions of motion (empty, or one row per pose).
struct PoseBatch {
  const JointMatrix& q;
  const DirectionMatrix& direction;
};
// TCP positions (mm) and tool directions, one row per pose, workpiece frame.
struct ToolPointBatch {
  PointMatrix positions;
  PointMatrix directions;
};
// Batch evaluation into `out` (its storage reused).
void toolPoints(const KinematicModel& model, const PoseBatch& poses, ToolPointBatch& out, int threads = kAllCores);
// TCP positions only (mm, workpiece frame), no direction of motion.
PointMatrix toolPositions(const KinematicModel& model, const JointMatrix& q, int threads = kAllCores);
// TCP position and orientation errors (n x 6) of `actual` against `nominal`.
PoseErrorMatrix toolErrors(const KinematicModel& actual, const KinematicModel& nominal, const PoseBatch& poses,
                           int threads = kAllCores);

// The frame in which each axis's component errors act (after offset and location error,
// before the joint for fixed frames and after it for moving frames, at the axis location
// point), in the bed frame. Indexed like Machine::axes.
std::vector<Pose> errorFrames(const KinematicModel& model, const double* q);

}  // namespace mtacc
