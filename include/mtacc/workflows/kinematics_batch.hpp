#pragma once
// Workflows `fk`, `errors` and `ik`: the tool relative to the workpiece at many poses (with
// the TCP error there), and the axis positions for given TCP positions and tool directions.
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct ForwardOptions {
  bool nominal = false;  // the tool points of the nominal machine (errors are still reported)
  bool errors = true;    // also the pose errors against the nominal machine
  int threads = kAllCores;
};

struct ForwardResult {
  std::shared_ptr<const Machine> machine;
  bool nominal = false;
  JointMatrix q;             // mm, rad
  ToolPointBatch tool;       // TCP (mm) and tool direction, workpiece frame
  PoseErrorMatrix error;     // actual minus nominal: mm, then the rotation vector in rad
  double maxPositionError = 0;  // mm
};

// InputError for the first pose beyond travel, naming the row's file line when `lines` is
// given, else the row (or "pose" for a single one).
void requireWithinTravel(const Machine& machine, const JointMatrix& q, const std::vector<int>& lines = {},
                         const std::string& file = "");

// Every pose must be within travel (requireWithinTravel).
ForwardResult forwardKinematics(const MachineSetup& setup, const JointMatrix& q, const DirectionMatrix& direction,
                                const ForwardOptions& options = {}, const std::vector<int>& lines = {},
                                const std::string& file = "");
// The same on the setup's models compiled already (`actual` with its errors, `nominal`): a
// caller evaluating a pose at a time compiles once.
ForwardResult forwardKinematics(const KinematicModel& actual, const KinematicModel& nominal, const JointMatrix& q,
                                const DirectionMatrix& direction, const ForwardOptions& options = {},
                                const std::vector<int>& lines = {}, const std::string& file = "");
// The poses of an axis-position file (docs/file-formats.md "Axis positions"), each named by its line.
ForwardResult forwardKinematicsOfFile(const MachineSetup& setup, const std::string& file, const ForwardOptions& options = {});
nlohmann::json toJson(const ForwardResult& result);

// d(pose error)/d(parameter) at each pose: rows dx, dy, dz [mm] and the rotation vector [rad],
// one column per parameter (its unit: mm or rad). Every pose must be within travel.
struct ParameterJacobians {
  std::vector<std::string> parameters;
  std::vector<ParameterJacobian> perPose;  // 6 x parameters, one per row of q
};
// `names`: the parameters to differentiate by; empty: every parameter of the machine's catalogue.
ParameterJacobians parameterJacobians(const MachineSetup& setup, const JointMatrix& q, const std::vector<std::string>& names);

struct InverseRequest {
  std::vector<Vec3> positions;   // TCP, mm, workpiece frame
  std::vector<Vec3> directions;  // tool direction (TCP towards spindle)
  IkOptions options;
  bool all = false;              // every solution of a single target, those beyond travel included
  bool withErrors = false;       // the commands for the machine with its errors (the inverse error model)
  // Where the targets come from, for messages: a file and each target's line; otherwise a
  // single target is named by the keys "tcp" and "tool", several by their number.
  std::string file;
  std::vector<int> lines;
};

// The targets of an IK target file (docs/file-formats.md "IK targets"), with the file and its lines.
InverseRequest inverseTargetsOfFile(const std::string& file);

struct InverseResult {
  std::shared_ptr<const Machine> machine;
  std::vector<IkSolution> solutions;          // nominal machine
  std::vector<ErrorIkSolution> withErrors;    // withErrors: one per target instead
};

// A single target: its preferred solution (or all); several: one continuous path. With
// withErrors, each target's commands on the machine with its errors, started from the nominal
// solution (the previous target's commands as the hint along a path).
InverseResult inverseKinematics(const MachineSetup& setup, const InverseRequest& request);
// The same on the setup's models compiled already (`actual` is used only withErrors).
InverseResult inverseKinematics(const KinematicModel& actual, const KinematicModel& nominal, const InverseRequest& request);
nlohmann::json toJson(const InverseResult& result);

}  // namespace mtacc
