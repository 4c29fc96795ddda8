#pragma once
// Analytic sensitivities of the exact model: the derivative of the TCP position and
// orientation error with respect to every error parameter at any pose, evaluated at the
// current error state (not only at zero errors).
#include <vector>

#include <Eigen/Core>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

using ParameterJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// Rows: dx, dy, dz (mm per unit), then the rotation-vector error (rad per unit), all in the
// workpiece frame. One column per parameter (mm or rad). `model` must be compiled with
// errors (KinematicModel::withErrors).
ParameterJacobian parameterJacobian(const KinematicModel& model, const std::vector<Parameter>& parameters,
                                    const double* q, const int* dir = nullptr);

// The derivative of one tool-frame point (e.g. a ball centre offset from the TCP) in the
// workpiece frame with respect to the parameters (3 x n, mm per unit), and the point itself.
// Cheaper than parameterJacobian: no orientation rows, no nominal model.
struct PointJacobian {
  Vec3 point;
  Mat3 toolRotation;  // of the tool frame in the workpiece frame
  Eigen::Matrix<double, 3, Eigen::Dynamic> jacobian;
};
PointJacobian pointJacobian(const KinematicModel& model, const std::vector<Parameter>& parameters, const double* q,
                            const int* dir, const Vec3& toolPoint);

// What pointJacobian needs of a model and a parameter list, prepared once for many poses:
// for each parameter, the factors of the chains that carry it, with what of their
// derivatives does not depend on the pose. Refers to the model, which must outlive the plan.
struct PointJacobianPlan {
  // The hooked factors a chain may have (checked when planning).
  static constexpr int kMaxFactors = 32;
  struct Term {
    int parameter;               // column of the Jacobian
    int chain;                   // 0 tool, 1 workpiece, 2 workpiece at the reference pose (machine alignment)
    int factor;                  // the hooked factor, in that chain's program order
    const ChainElement* element;
    Hook hook;
    // Constant: dF = [rotation translation; 0 0] (location errors of rotary axes and the
    // spindle). JointTranslation: dF = [0, translation + q * translationPerUnit] (location
    // errors of a linear axis, q its joint value). PerPose: taken at each pose (motion errors).
    enum Kind { Constant, JointTranslation, PerPose } kind;
    bool rotates = false;        // Constant with a nonzero rotation part
    Mat3 rotation = Mat3::Zero();
    Vec3 translation = Vec3::Zero();
    Vec3 translationPerUnit = Vec3::Zero();
  };
  const KinematicModel* model = nullptr;
  std::vector<Parameter> parameters;
  std::vector<Term> terms;
  // Machine alignment: the workpiece chain at the reference pose, the same for every pose.
  std::vector<ChainFrame> referenceFrames;
  Pose reference = Pose::Identity();
  Mat3 referenceToWorkpiece = Mat3::Zero();  // M_WC's rotation times the reference pose's inverse rotation
};
PointJacobianPlan planPointJacobian(const KinematicModel& model, const std::vector<Parameter>& parameters);
// The same into `out`, reusing its storage (no allocation once sized).
void pointJacobian(const PointJacobianPlan& plan, const double* q, const int* dir, const Vec3& toolPoint, PointJacobian& out);

// The frame in which each axis's component errors act (after offset and location error,
// before the joint for fixed frames and after it for moving frames, at the axis location
// point), in the bed frame. Indexed like Machine::axes.
std::vector<Pose> errorFrames(const KinematicModel& model, const double* q);

}  // namespace mtacc
