#include "mtacc/workflows/kinematics_batch.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {

void requireWithinTravel(const Machine& m, const JointMatrix& q, const std::vector<int>& lines, const std::string& file) {
  for (Eigen::Index r = 0; r < q.rows(); ++r) {
    const auto violation = m.travelViolation({q.row(r).data(), static_cast<size_t>(q.cols())});
    if (violation.empty()) continue;
    if (static_cast<size_t>(r) < lines.size()) throw InputError(InputLocation{file, lines[static_cast<size_t>(r)], ""}, "pose " + violation);
    throw InputError(InputLocation{file, 0, q.rows() == 1 ? "pose" : "row " + std::to_string(r)}, "pose " + violation);
  }
}

ParameterJacobians parameterJacobians(const MachineSetup& setup, const JointMatrix& q, const std::vector<std::string>& names) {
  requireWithinTravel(*setup.machine, q);
  const auto params = names.empty() ? parameterCatalogue(*setup.machine, setup.errors) : findParameters(setup, names);
  ParameterJacobians out;
  for (const auto& p : params) out.parameters.push_back(p.name);
  const auto model = compile(setup.machine, setup.errors, params);
  const auto nominal = setup.nominal();
  for (Eigen::Index r = 0; r < q.rows(); ++r) out.perPose.push_back(parameterJacobian(model, nominal, q.row(r).data()));
  return out;
}

ForwardResult forwardKinematics(const MachineSetup& setup, const JointMatrix& q, const DirectionMatrix& direction,
                                const ForwardOptions& options, const std::vector<int>& lines, const std::string& file) {
  return forwardKinematics(setup.actual(), setup.nominal(), q, direction, options, lines, file);
}

ForwardResult forwardKinematics(const KinematicModel& actualModel, const KinematicModel& nominal, const JointMatrix& q,
                                const DirectionMatrix& direction, const ForwardOptions& options, const std::vector<int>& lines,
                                const std::string& file) {
  if (options.threads < 0) throw InputError(InputLocation{"", 0, "threads"}, "must be 0 (all cores) or a positive count");
  requireWithinTravel(*nominal.machine, q, lines, file);
  ForwardResult out;
  out.machine = nominal.machine;
  out.nominal = options.nominal;
  out.q = q;
  const KinematicModel& actual = options.nominal ? nominal : actualModel;
  toolPoints(actual, {q, direction}, out.tool, options.threads);
  if (!options.errors) return out;
  out.error = toolErrors(actual, nominal, {q, direction}, options.threads);
  for (Eigen::Index r = 0; r < out.error.rows(); ++r)
    out.maxPositionError = std::max(out.maxPositionError, out.error.row(r).head<3>().norm());
  return out;
}

nlohmann::json toJson(const ForwardResult& r) {
  const Machine& m = *r.machine;
  nlohmann::json j;
  j["machine"] = m.name;
  j["nominal"] = r.nominal;
  j["poses"] = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.q.rows(); ++i) {
    const Vec3 e = r.error.row(i).head<3>().transpose() * 1e3;
    const Vec3 a = r.error.row(i).tail<3>().transpose() * 1e6;
    j["poses"].push_back({{"pose", poseJson(m, r.q.row(i).data())},
                          {"tcp_mm", vectorJson(r.tool.positions.row(i).transpose())},
                          {"tool_direction", vectorJson(r.tool.directions.row(i).transpose())},
                          {"position_error_um", vectorJson(e)},
                          {"orientation_error_urad", vectorJson(a)}});
  }
  j["max_position_error_um"] = r.maxPositionError * 1e3;
  return j;
}

InverseResult inverseKinematics(const MachineSetup& setup, const InverseRequest& request) {
  // The actual model only when it is used: compiling it costs more than one solution.
  const auto nominal = setup.nominal();
  return inverseKinematics(request.withErrors ? setup.actual() : nominal, nominal, request);
}

InverseResult inverseKinematics(const KinematicModel& actual, const KinematicModel& nominal, const InverseRequest& request) {
  if (request.positions.empty() || request.positions.size() != request.directions.size())
    throw InputError(InputLocation{"", 0, "targets"}, "expected as many tool directions as TCP positions, at least one");
  auto where = [&](size_t i, const char* singleKey) {
    if (i < request.lines.size()) return InputLocation{request.file, request.lines[i], ""};
    return InputLocation{request.file, 0, request.positions.size() == 1 ? singleKey : "target " + std::to_string(i + 1)};
  };
  for (size_t i = 0; i < request.positions.size(); ++i) {
    if (!(request.positions[i].cwiseAbs().maxCoeff() <= kLargestLength))
      throw InputError(where(i, "tcp"), "the TCP lies beyond ±1 km");
    if (!(request.directions[i].cwiseAbs().maxCoeff() > 0) || !request.directions[i].allFinite())
      throw InputError(where(i, "tool"), "the tool direction has zero length");
  }
  InverseResult out{nominal.machine, {}, {}};
  try {
    if (request.withErrors) {
      if (request.all) throw InputError(InputLocation{"", 0, "all"}, "every solution is listed for the nominal machine only, not with its errors");
      ErrorIkOptions o;
      o.ik = request.options;
      for (size_t i = 0; i < request.positions.size(); ++i) {
        try {
          out.withErrors.push_back(solveIkWithErrors(actual, nominal, request.positions[i], request.directions[i], o));
        } catch (const UnreachablePose& e) {
          throw UnreachableTarget(i, e.what());
        }
        o.ik.hint = out.withErrors.back().q;
        o.ik.branch = TiltBranch::Auto;
      }
    } else if (request.all && request.positions.size() == 1)
      out.solutions = inverseKinematics(nominal, request.positions[0], request.directions[0], request.options).solutions;
    else
      out.solutions = solveIkPath(nominal, request.positions, request.directions, request.options);
  } catch (const UnreachableTarget& e) {
    throw UnreachableInput(where(e.index, "tcp"), std::string("unreachable: ") + e.what());
  }
  return out;
}

nlohmann::json toJson(const InverseResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine->name;
  j["units"] = {{"linear", "mm"}, {"rotary", "deg"}};
  j["solutions"] = nlohmann::json::array();
  for (const auto& s : r.solutions)
    j["solutions"].push_back({{"pose", poseJson(*r.machine, s.q.data())},
                              {"singular", s.singular},
                              {"free_axis", s.singularAxis},
                              {"within_travel", s.withinTravel},
                              {"travel_violation", s.travelViolation}});
  for (const auto& s : r.withErrors)
    j["solutions"].push_back({{"pose", poseJson(*r.machine, s.q.data())},
                              {"nominal_pose", poseJson(*r.machine, s.nominalQ.data())},
                              {"position_residual_um", toDisplay(s.positionResidual, Dimension::Length)},
                              {"direction_residual_urad", toDisplay(s.directionResidual, Dimension::Angle)},
                              {"direction_controlled", s.directionControlled},
                              {"iterations", s.iterations},
                              {"converged", s.converged},
                              {"singular", s.singular},
                              {"within_travel", s.travelViolation.empty()},
                              {"travel_violation", s.travelViolation}});
  return j;
}

ForwardResult forwardKinematicsOfFile(const MachineSetup& setup, const std::string& file, const ForwardOptions& options) {
  const auto table = readCsv(file);
  const auto poses = posesFromCsv(*setup.machine, table);
  return forwardKinematics(setup, poses.q, poses.direction, options, table.lines, file);
}

InverseRequest inverseTargetsOfFile(const std::string& file) {
  const auto table = readCsv(file);
  const auto c = requireColumns(table, {"x", "y", "z", "i", "j", "k"});
  InverseRequest request;
  request.file = file;
  request.lines = table.lines;
  for (const auto& row : table.rows) {
    auto at = [&](int k) { return row[static_cast<size_t>(c[static_cast<size_t>(k)])]; };
    request.positions.emplace_back(at(0), at(1), at(2));
    request.directions.emplace_back(at(3), at(4), at(5));
  }
  return request;
}

}  // namespace mtacc
