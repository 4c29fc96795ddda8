#pragma once
// The compiled form of a machine with its errors: the Model of a Model/Data split (the Data,
// scratch for evaluations, is KinematicData in jacobian.hpp). Build once per machine, error
// state and parameter list; evaluate many poses with the free functions of forward.hpp,
// inverse.hpp and jacobian.hpp. Lengths in mm, angles in rad.
#include <memory>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// A frame along a chain: x_bed = rotation * x + origin.
struct ChainFrame {
  Mat3 rotation = Mat3::Identity();
  Vec3 origin = Vec3::Zero();
};

// The chains as programs of operations (private to src/kinematics).
struct ChainPrograms;

struct KinematicModel {
  std::shared_ptr<const Machine> machine;
  ErrorModel errors;
  bool withErrors = true;
  // The columns of the Jacobians evaluated on this model (compile's jacobianParameters).
  std::vector<Parameter> parameters;
  int jointCount = 0;
  Pose alignment = Pose::Identity();  // M_WC of seed 001 eq. 12 (identity for table alignment)
  bool aligned = false;               // alignment differs from the identity
  std::shared_ptr<const ChainPrograms> chains;
};

// Compiles the machine with its errors; the Jacobians of the model are taken with respect to
// jacobianParameters.
KinematicModel compile(std::shared_ptr<const Machine> machine, const ErrorModel& errors,
                       const std::vector<Parameter>& jacobianParameters = {});
// The nominal machine (no errors).
KinematicModel compileNominal(std::shared_ptr<const Machine> machine);

}  // namespace mtacc
