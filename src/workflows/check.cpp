#include "mtacc/workflows/check.hpp"

#include "mtacc/core/units.hpp"

namespace mtacc {

const char* axisTypeName(AxisType t) { return t == AxisType::Linear ? "linear" : t == AxisType::Rotary ? "rotary" : "spindle"; }

MachineCheck checkMachine(const MachineSetup& setup) {
  MachineCheck c{setup, parameterCatalogue(*setup.machine, setup.errors), nonZeroParameters(*setup.machine, setup.errors)};
  for (const auto& p : c.parameters) c.locationCount += p.kind == ParameterKind::Location ? 1 : 0;
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
  j["axis_names"] = nlohmann::json::array();
  for (const auto& a : m.axes) {
    if (a.commanded()) j["axis_names"].push_back(a.name);
    const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
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
  j["parameter_count"] = c.parameters.size();
  j["location_parameter_count"] = c.locationCount;
  j["valid"] = true;
  return j;
}

}  // namespace mtacc
