#pragma once
// How well an identified model knows the TCP: the covariance of its identified parameters (an
// identified errors file's record) carried to the TCP position by the parameter Jacobian, first
// order. After compensating with the model, this is the uncertainty of what is left.
#include <vector>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// Per pose (commanded axes, mm and rad), the standard uncertainty (k = 1) of the TCP position in
// the workpiece frame along x, y, z (mm). Throws InputError when the setup's errors carry no
// covariance (key "errors": not written by an identification).
std::vector<Vec3> tcpUncertainty(const MachineSetup& setup, Eigen::Ref<const JointMatrix> poses);

}  // namespace mtacc
