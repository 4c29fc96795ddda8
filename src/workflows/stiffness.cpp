#include "mtacc/workflows/stiffness.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/budget.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

LargestTcpError largestError(const PoseErrorMatrix& errors, const JointMatrix& poses) {
  LargestTcpError out;
  Eigen::Index at = 0;
  out.value = errors.leftCols<3>().rowwise().norm().maxCoeff(&at);
  out.pose.assign(poses.row(at).data(), poses.row(at).data() + poses.cols());
  return out;
}

}  // namespace

ErrorModel withoutStiffness(const ErrorModel& errors) {
  ErrorModel e = errors;
  e.stiffness.clear();
  return e;
}

ErrorModel stiffnessOnly(const Machine& machine, const ErrorModel& errors) {
  ErrorModel e = ErrorModel::zero(machine);
  e.stiffness = errors.stiffness;
  e.workpieceLoad = errors.workpieceLoad;
  return e;
}

const OptionSchema& stiffnessSchema() {
  static const OptionSchema schema{"stiffness",
                                   {{.key = "samples", .kind = OptionKind::Count, .help = "Positions per axis of the working-volume grid",
                                     .defaultText = "5", .low = 2, .high = 12, .outOfRange = "must be from 2 to 12"}}};
  return schema;
}

int stiffnessSamples(const OptionValues& values) { return *OptionReader(stiffnessSchema(), values).count("samples"); }

StiffnessSummary summariseStiffness(const MachineSetup& setup, int samplesPerAxis) {
  requireInRange(stiffnessSchema().at("samples"), samplesPerAxis);
  if (setup.errors.stiffness.empty())
    throw InputError(InputLocation{"", 0, ""},
                     "the errors of " + setup.machine->name +
                         " have no stiffness changes (with another axis's position or the workpiece load): give them as "
                         "'stiffness:' terms of an errors file (docs/file-formats.md, \"Finite stiffness\")");
  const Machine& m = *setup.machine;
  const JointMatrix grid = workingVolumeGrid(m, samplesPerAxis);
  const DirectionMatrix none;
  const PoseBatch poses{grid, none};
  const KinematicModel nominal = setup.nominal();
  const PoseErrorMatrix all = toolErrors(setup.actual(), nominal, poses);
  const PoseErrorMatrix geometric = toolErrors(compile(setup.machine, withoutStiffness(setup.errors)), nominal, poses);
  const PoseErrorMatrix alone = toolErrors(compile(setup.machine, stiffnessOnly(m, setup.errors)), nominal, poses);
  StiffnessSummary s{setup, samplesPerAxis, static_cast<int>(grid.rows()), {}, {}, {}};
  s.geometric = largestError(geometric, grid);
  s.stiffness = largestError(alone, grid);
  s.change = largestError(all - geometric, grid);
  return s;
}

nlohmann::json toJson(const StiffnessSummary& s) {
  const Machine& m = *s.setup.machine;
  const ErrorModel& errors = s.setup.errors;
  auto positionScale = [&](int axis) { return m.axes[static_cast<size_t>(axis)].isRotary() ? 1.0 / kDeg : 1.0; };
  nlohmann::json j;
  j["workpiece_load_kg"] = errors.workpieceLoad;
  j["terms"] = nlohmann::json::array();
  for (const auto& t : errors.stiffness) {
    const Dimension dim = t.component < 3 ? Dimension::Length : Dimension::Angle;
    const std::string name = motionErrorName(m, t.axis, t.component);
    const double factor = t.loadFactor(errors.workpieceLoad);
    nlohmann::json values = nlohmann::json::array();
    for (Eigen::Index i = 0; i < t.values.rows(); ++i) {
      nlohmann::json row = nlohmann::json::array();
      for (Eigen::Index k = 0; k < t.values.cols(); ++k) row.push_back(toDisplay(factor * t.values(i, k), dim));
      values.push_back(row);
    }
    nlohmann::json positions = nlohmann::json::array(), other = nlohmann::json::array();
    for (double p : t.positions) positions.push_back(p * positionScale(t.axis));
    if (t.otherAxis >= 0)
      for (double p : t.otherPositions) other.push_back(p * positionScale(t.otherAxis));
    j["terms"].push_back({{"error", name},
                          {"axis", m.axes[static_cast<size_t>(t.axis)].name},
                          {"with", t.otherAxis >= 0 ? nlohmann::json(m.axes[static_cast<size_t>(t.otherAxis)].name) : nlohmann::json(nullptr)},
                          {"reference_load_kg", t.referenceLoad > 0.0 ? nlohmann::json(t.referenceLoad) : nlohmann::json(nullptr)},
                          {"load_factor", factor},
                          {"largest", toDisplay(std::abs(factor) * t.values.cwiseAbs().maxCoeff(), dim)},
                          {"unit", displayUnit(dim)},
                          {"positions", positions},
                          {"with_positions", other},
                          {"values", values}});
  }
  j["samples_per_axis"] = s.samplesPerAxis;
  j["poses"] = s.poses;
  auto largest = [&](const LargestTcpError& e) { return nlohmann::json{{"position_error_um", toDisplay(e.value, Dimension::Length)}, {"pose", poseJson(m, e.pose.data())}}; };
  j["largest_tcp_error"] = {{"geometric", largest(s.geometric)}, {"stiffness_alone", largest(s.stiffness)}, {"added_by_stiffness", largest(s.change)}};
  return j;
}

}  // namespace mtacc
