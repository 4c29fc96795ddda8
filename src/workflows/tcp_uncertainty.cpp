#include "mtacc/workflows/tcp_uncertainty.hpp"

#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {

std::vector<Vec3> tcpUncertainty(const MachineSetup& setup, Eigen::Ref<const JointMatrix> poses) {
  if (!setup.covariance)
    throw InputError({"", 0, "errors"}, "these errors carry no covariance: give an errors file written by an identification (--errors-out)");
  const auto& c = *setup.covariance;
  const KinematicModel model = compile(setup.machine, setup.errors, c.parameters);
  KinematicData data;
  std::vector<Vec3> out(static_cast<size_t>(poses.rows()));
  for (Eigen::Index i = 0; i < poses.rows(); ++i) {
    const auto& j = pointJacobian(model, poses.row(i).data(), nullptr, Vec3::Zero(), data).jacobian;
    out[static_cast<size_t>(i)] = (j * c.covariance * j.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  return out;
}

}  // namespace mtacc
