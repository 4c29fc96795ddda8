#pragma once
// Exact forward kinematics: the tool (TCP and tool direction) relative to the workpiece,
// nominal or with all errors, for one pose or a batch. Joint vectors hold the commanded
// axes in Machine::axes order, linear in mm, rotary in rad. `dir` (may be null) gives the
// direction of motion of each axis (+1, -1, 0) for reversal errors.
#include <Eigen/Core>

#include <functional>

#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

using JointMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using PointMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Bed -> tool frame (TCP) and bed -> workpiece frame.
Pose toolChainPose(const KinematicModel& model, const double* q, const int* dir);
Pose workpiecePose(const KinematicModel& model, const double* q, const int* dir);
// A frame along a chain: x_bed = rotation * x + origin.
struct ChainFrame {
  Mat3 rotation;
  Vec3 origin;
};
// Runs a program with hook markers (KinematicModel::toolHookProgram, workpieceHookProgram):
// the chain's pose, and in `hooks` (room for one per marker) the frame at each marker, in
// program order.
Pose runHookProgram(const KinematicModel& model, const std::vector<ChainOp>& program, const double* q, const int* dir,
                    ChainFrame* hooks);

// Tool frame in the workpiece frame (includes M_WC when the workpiece is aligned).
Pose toolInWorkpiece(const KinematicModel& model, const double* q, const int* dir = nullptr);

struct ToolPoint {
  Vec3 position;   // TCP in the workpiece frame, mm
  Vec3 direction;  // unit tool direction (TCP towards spindle) in the workpiece frame
};
ToolPoint toolPoint(const KinematicModel& model, const double* q, const int* dir = nullptr);

// Pose error, actual minus nominal, in the workpiece frame: (dx, dy, dz) in mm, then the
// rotation vector of R_actual * R_nominal^T in rad.
Vec6 poseError(const Pose& actual, const Pose& nominal);

// Batch evaluation over the rows of q (one pose per row). dir may be empty or the size of q.
// threads = 0 uses every core.
void toolPoints(const KinematicModel& model, const JointMatrix& q, const Eigen::MatrixXi& dir,
                PointMatrix& positions, PointMatrix& directions, int threads = 1);
// TCP position and orientation errors (n x 6) of `actual` against `nominal`.
Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> toolErrors(const KinematicModel& actual,
                                                                      const KinematicModel& nominal,
                                                                      const JointMatrix& q,
                                                                      const Eigen::MatrixXi& dir, int threads = 1);

// Runs body(begin, end) over [0, n) split across threads (0 = hardware concurrency).
void parallelFor(long n, int threads, const std::function<void(long, long)>& body);

}  // namespace mtacc
