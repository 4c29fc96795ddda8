#include "mtacc/workflows/check.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mtacc/core/units.hpp"
#include "mtacc/identification/acting_alike.hpp"

namespace mtacc {
namespace {

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

}  // namespace

const char* axisTypeName(AxisType t) { return t == AxisType::Linear ? "linear" : t == AxisType::Rotary ? "rotary" : "spindle"; }

const OptionSchema& checkSchema() {
  static const OptionSchema schema{
      "check", {{"parameters", OptionKind::Flag, "list every error parameter by name (the JSON always holds them)"}}};
  return schema;
}

MachineCheck checkMachine(const MachineSetup& setup) {
  MachineCheck c{setup, parameterCatalogue(*setup.machine, setup.errors), nonZeroParameters(*setup.machine, setup.errors), 0, {}, {}, {},
                 classifyMachine(*setup.machine)};
  for (const auto& p : c.parameters) c.locationCount += p.kind == ParameterKind::Location ? 1 : 0;
  const Machine& m = *setup.machine;
  for (int a = 0; a < static_cast<int>(m.axes.size()); ++a)
    if (m.axes[static_cast<size_t>(a)].isRotary() && m.axes[static_cast<size_t>(a)].commanded())
      c.zeroOffsets.push_back(zeroOffsetExpression(m, zeroOffsetParameter(m, a)));
  c.actingAlike = locationErrorsActingAlike(setup.machine, c.parameters);
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
  const auto& k = c.machineClass;
  j["classification"] = {{"chains", k.chains},
                         {"linear_class", k.linear.empty() ? nlohmann::json(nullptr) : nlohmann::json(k.linear)},
                         {"example", k.example},
                         {"type_dependent_errors", k.typeDependentErrors},
                         {"rotary_class", k.rotary == 0 ? nlohmann::json(nullptr) : nlohmann::json(k.rotary)},
                         {"rotary_description", k.rotaryDescription},
                         {"notes", k.notes},
                         {"vertical_direction", vectorJson(m.vertical)}};
  j["location_errors_acting_alike"] = c.actingAlike;
  j["warnings"] = c.warnings;
  j["parameter_count"] = c.parameters.size();
  j["location_parameter_count"] = c.locationCount;
  j["valid"] = true;
  return j;
}

}  // namespace mtacc
