#include "mtacc/workflows/check.hpp"

#include <random>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/measurement/observability.hpp"

namespace mtacc {
namespace {

constexpr int kWorkspacePoses = 64;

std::string zeroOffsetExpression(const Machine& m, const Parameter& zero) {
  std::string terms;
  for (int k = 0; k < 3; ++k) {
    const double c = zero.turn[k];
    if (std::abs(c) < 1e-12) continue;
    const std::string name = std::string(1, "ABC"[k]) + "0" + m.axes[static_cast<size_t>(zero.axis)].name;
    const std::string factor = std::abs(std::abs(c) - 1.0) < 1e-12 ? "" : fmt::format("{:g} ", std::abs(c));
    terms += terms.empty() ? fmt::format("{}{}{}", c < 0 ? "-" : "", factor, name) : fmt::format(" {} {}{}", c < 0 ? "-" : "+", factor, name);
  }
  return zero.name + " = " + terms;
}

// Random poses within travel (a continuous axis over one turn), the same on every run.
std::vector<std::vector<double>> workspacePoses(const Machine& m) {
  std::mt19937 rng(20261126);
  std::vector<std::vector<double>> poses(kWorkspacePoses);
  for (auto& q : poses)
    for (const auto& a : m.axes) {
      if (!a.commanded()) continue;
      const Travel t = a.travel.value_or(Travel{-kPi, kPi});
      q.push_back(std::uniform_real_distribution<double>(t.min, t.max)(rng));
    }
  return poses;
}

// Parameters whose effects are parallel (one is a multiple of the other at every pose) act
// alike: "X0X, X0B and X0C act alike (X0X = X0B = -X0C in effect)". What remains after keeping
// one of each such class goes to the general analysis, for dependencies among several.
std::vector<std::string> locationErrorsActingAlike(const MachineSetup& setup, const std::vector<Parameter>& catalogue) {
  std::vector<Parameter> location;
  for (const auto& p : catalogue)
    if (p.kind == ParameterKind::Location) location.push_back(p);
  if (location.empty()) return {};
  const auto model = compile(setup.machine, ErrorModel::zero(*setup.machine), location);
  const auto nominal = setup.nominal();
  const auto poses = workspacePoses(*setup.machine);
  const auto n = static_cast<Eigen::Index>(location.size());
  Eigen::MatrixXd jacobian(6 * static_cast<Eigen::Index>(poses.size()), n);
  for (size_t i = 0; i < poses.size(); ++i)
    jacobian.middleRows(6 * static_cast<Eigen::Index>(i), 6) = parameterJacobian(model, nominal, poses[i].data());
  const Eigen::VectorXd norms = jacobian.colwise().norm().transpose();
  Eigen::VectorXd typical(n);
  for (Eigen::Index k = 0; k < n; ++k) typical[k] = location[static_cast<size_t>(k)].dimension == Dimension::Length ? 1e-3 : 1e-5;
  const double largestEffect = (norms.array() * typical.array()).maxCoeff();
  std::vector<std::string> findings, kept;
  std::vector<Eigen::Index> keptColumns;
  std::vector<bool> placed(static_cast<size_t>(n), false);
  auto hasEffect = [&](Eigen::Index k) { return norms[k] * typical[k] > kRankTolerance * largestEffect; };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (placed[static_cast<size_t>(i)] || !hasEffect(i)) continue;
    const std::string& first = location[static_cast<size_t>(i)].name;
    std::vector<std::string> members{first};
    std::string effect = first;
    bool scaled = false;
    for (Eigen::Index j = i + 1; j < n; ++j) {
      if (placed[static_cast<size_t>(j)] || !hasEffect(j)) continue;
      const double cosine = jacobian.col(i).dot(jacobian.col(j)) / (norms[i] * norms[j]);
      if (std::abs(cosine) < 1.0 - 1e-10) continue;
      placed[static_cast<size_t>(j)] = true;
      members.push_back(location[static_cast<size_t>(j)].name);
      // A unit of the first parameter has the effect of `ratio` units of this one.
      const double ratio = std::copysign(norms[i] / norms[j], cosine);
      const bool unit = std::abs(std::abs(ratio) - 1.0) < 1e-6;
      scaled = scaled || !unit;
      effect += fmt::format(" = {}{}{}", ratio < 0 ? "-" : "", unit ? "" : fmt::format("{:.4g} ", std::abs(ratio)), members.back());
    }
    if (members.size() > 1) {
      std::string list = members[0];
      for (size_t k = 1; k < members.size(); ++k) list += (k + 1 == members.size() ? " and " : ", ") + members[k];
      findings.push_back(fmt::format("{} act alike ({} in effect{})", list, effect, scaled ? "; lengths in mm, angles in rad" : ""));
    }
    kept.push_back(first);
    keptColumns.push_back(i);
  }
  Eigen::MatrixXd rest(jacobian.rows(), static_cast<Eigen::Index>(keptColumns.size()));
  Eigen::VectorXd restTypical(rest.cols());
  for (size_t k = 0; k < keptColumns.size(); ++k) {
    rest.col(static_cast<Eigen::Index>(k)) = jacobian.col(keptColumns[k]);
    restTypical[static_cast<Eigen::Index>(k)] = typical[keptColumns[k]];
  }
  for (Eigen::Index k = 0; k < n; ++k)
    if (!hasEffect(k)) findings.push_back(location[static_cast<size_t>(k)].name + " has no effect on this machine");
  for (auto& f : analyseObservability(std::move(rest), kept, restTypical, kRankTolerance, 1).findings("this machine"))
    findings.push_back(std::move(f));
  return findings;
}

}  // namespace

const char* axisTypeName(AxisType t) { return t == AxisType::Linear ? "linear" : t == AxisType::Rotary ? "rotary" : "spindle"; }

MachineCheck checkMachine(const MachineSetup& setup) {
  MachineCheck c{setup, parameterCatalogue(*setup.machine, setup.errors), nonZeroParameters(*setup.machine, setup.errors), 0, {}, {}, {}};
  for (const auto& p : c.parameters) c.locationCount += p.kind == ParameterKind::Location ? 1 : 0;
  const Machine& m = *setup.machine;
  for (int a = 0; a < static_cast<int>(m.axes.size()); ++a)
    if (m.axes[static_cast<size_t>(a)].isRotary() && m.axes[static_cast<size_t>(a)].commanded())
      c.zeroOffsets.push_back(zeroOffsetExpression(m, zeroOffsetParameter(m, a)));
  c.actingAlike = locationErrorsActingAlike(setup, c.parameters);
  if (m.spindleIndex() < 0) {
    std::vector<std::string> heads;
    for (const auto& a : m.axes)
      if (a.isRotary() && a.commanded() && a.side == Side::Tool && a.direction.cross(m.toolDirection).norm() > 1e-6) heads.push_back(a.name);
    if (!heads.empty()) {
      const bool hasC = m.axisIndex("C") >= 0;
      Eigen::Index along = 0;
      m.toolDirection.cwiseAbs().maxCoeff(&along);
      const std::string spindle = hasC ? "C1" : "C";
      c.warnings.push_back(fmt::format(
          "{} turns the tool across its line, but the structure code '{}' names no spindle element: the spindle's "
          "location errors on the head, among them the pivot length {}0{} (the tool's position along the spindle line "
          "about {}), are not parameters of this model. Add the spindle as '(C)' next to 't' (it is then named {})",
          fmt::join(heads, " and "), m.structure.text, "XYZ"[along], spindle, heads.front(), spindle));
    }
  }
  return c;
}

nlohmann::json toJson(const MachineCheck& c) {
  const Machine& m = *c.setup.machine;
  auto names = [&](const std::vector<int>& chain) {
    std::vector<std::string> n;
    for (int i : chain) n.push_back(m.axes[static_cast<size_t>(i)].name);
    return n;
  };
  nlohmann::json j;
  j["name"] = m.name;
  j["file"] = m.sourceFile;
  j["structure"] = m.structure.text;
  j["structure_tool_first"] = m.structure.toolFirst();
  j["tool_chain"] = names(m.toolChain);
  j["workpiece_chain"] = names(m.workpieceChain);
  j["axis_names"] = m.commandedAxisNames();
  for (const auto& a : m.axes) {
    const double f = 1.0 / a.fileUnit();
    j["axes"].push_back({{"name", a.name},
                         {"type", axisTypeName(a.type)},
                         {"side", a.side == Side::Tool ? "tool" : "workpiece"},
                         {"direction", vectorJson(a.direction)},
                         {"location_mm", vectorJson(a.location)},
                         {"offset_mm", vectorJson(a.offset)},
                         {"error_frame", a.errorFrame == ErrorFrame::Fixed ? "fixed" : "moving"},
                         {"travel", a.travel ? nlohmann::json{a.travel->min * f, a.travel->max * f} : nlohmann::json(nullptr)}});
  }
  j["tool"] = {{"offset_mm", vectorJson(m.toolOffset)}, {"direction", vectorJson(m.toolDirection)}};
  j["workpiece"] = {{"offset_mm", vectorJson(m.workpieceOffset)},
                    {"alignment", m.alignment == WorkpieceAlignment::Table ? "table" : "machine"}};
  j["errors"] = nlohmann::json::object();
  for (const auto& p : c.nonZero) {
    const double v = parameterValue(c.setup.errors, p);
    j["errors"][p.name] = {{"value", toDisplay(v, p.dimension)}, {"unit", displayUnit(p.dimension)}};
  }
  j["parameters"] = nlohmann::json::array();
  for (const auto& p : c.parameters) j["parameters"].push_back(p.name);
  j["stiffness_changes"] = c.setup.errors.stiffness.size();
  j["workpiece_load_kg"] = c.setup.errors.workpieceLoad;
  j["zero_offsets"] = c.zeroOffsets;
  j["location_errors_acting_alike"] = c.actingAlike;
  j["warnings"] = c.warnings;
  j["parameter_count"] = c.parameters.size();
  j["location_parameter_count"] = c.locationCount;
  j["valid"] = true;
  return j;
}

}  // namespace mtacc
