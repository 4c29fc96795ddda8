#pragma once
// Analytic sensitivities of the exact model: the derivative of a tool point, and of the TCP
// and the tool orientation, with respect to the model's parameters (compile's
// jacobianParameters) at any pose, at the model's error state (not only at zero errors).
#include <vector>

#include <Eigen/Core>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

// One tool-frame point (e.g. a ball centre offset from the TCP) in the workpiece frame, and
// its derivative with respect to the parameters (one column each, mm per unit).
struct PointJacobian {
  Vec3 point = Vec3::Zero();
  Mat3 toolRotation = Mat3::Identity();  // of the tool frame in the workpiece frame
  Eigen::Matrix<double, 3, Eigen::Dynamic> jacobian;
};

// Scratch for the Jacobians (the Data of the Model/Data split), one per thread, reused from
// pose to pose: sized for a model at its first use, it allocates nothing after.
struct KinematicData {
  PointJacobian point;  // the result of the last evaluation
  // The rate of turn of the tool frame per parameter (rad per unit, workpiece frame), when asked.
  Eigen::Matrix<double, 3, Eigen::Dynamic> rotation;
  std::vector<ChainFrame> toolFrames, workpieceFrames;  // at the markers of the chains
  // Per hooked factor: the map of a direction before it to the workpiece frame, the point in
  // the frame after it, the motion errors there, and whether they are set for this pose.
  std::vector<Mat3> maps;
  std::vector<Vec3> local;
  std::vector<Vec6> motion;
  std::vector<unsigned char> ready;
};

// The tool point toolPoint (tool frame, mm) and its derivatives at pose q, into data.point.
// `model` must be compiled with errors.
const PointJacobian& pointJacobian(const KinematicModel& model, const double* q, const int* dir, const Vec3& toolPoint,
                                   KinematicData& data);

// Rows: dx, dy, dz of the TCP (mm per unit), then the rotation-vector error of the tool
// orientation against `nominal` (rad per unit), all in the workpiece frame; one column per
// parameter of `model`.
using ParameterJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;
ParameterJacobian parameterJacobian(const KinematicModel& model, const KinematicModel& nominal, const double* q,
                                    const int* dir = nullptr);

}  // namespace mtacc
