// mtacc check MACHINE: validate the description and print the chain and its error parameters.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc::cli {
namespace {

const char* typeName(AxisType t) {
  return t == AxisType::Linear ? "linear" : t == AxisType::Rotary ? "rotary" : "spindle";
}

std::string chainText(const Machine& m, const std::vector<int>& chain) {
  std::string s;
  for (int i : chain) s += (s.empty() ? "" : " -> ") + m.axes[static_cast<size_t>(i)].name;
  return s.empty() ? "(none)" : s;
}

std::string travelText(const Axis& a) {
  if (!a.travel) return a.type == AxisType::Spindle ? "-" : "continuous";
  const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
  return fmt::format("{:g} .. {:g} {}", a.travel->min * f, a.travel->max * f, a.isRotary() ? "deg" : "mm");
}

void run(const MachineOptions& o) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  const auto catalogue = parameterCatalogue(m, loaded.errors);
  const auto nonZero = nonZeroParameters(m, loaded.errors);

  nlohmann::json j;
  j["name"] = m.name;
  j["file"] = m.sourceFile;
  j["structure"] = m.structure.text;
  j["structure_tool_first"] = m.structure.toolFirst();
  std::string human = fmt::format("Machine    {}\nFile       {}\nStructure  {}  (tool first: {})\n", m.name,
                                  m.sourceFile, m.structure.text, m.structure.toolFirst());
  human += fmt::format("Tool chain       bed -> {} -> tool\n", chainText(m, m.toolChain));
  human += fmt::format("Workpiece chain  bed -> {} -> workpiece\n\n", chainText(m, m.workpieceChain));
  human += fmt::format("{:<5} {:<8} {:<10} {:<26} {:<28} {:<22} {}\n", "axis", "type", "side", "direction",
                       "location / offset (mm)", "travel", "errors act in");
  std::string csv = "axis,type,side,dx,dy,dz,location_x,location_y,location_z,travel_min,travel_max,error_frame\n";
  for (const auto& a : m.axes) {
    const Vec3 place = a.type == AxisType::Linear ? a.offset : a.location + a.offset;
    human += fmt::format("{:<5} {:<8} {:<10} ({:6.3f}, {:6.3f}, {:6.3f})    ({:7.1f}, {:7.1f}, {:7.1f})    {:<22} {}\n",
                         a.name, typeName(a.type), a.side == Side::Tool ? "tool" : "workpiece", a.direction.x(),
                         a.direction.y(), a.direction.z(), place.x(), place.y(), place.z(), travelText(a),
                         a.errorFrame == ErrorFrame::Fixed ? "fixed frame" : "moving frame");
    nlohmann::json aj = {{"name", a.name},
                         {"type", typeName(a.type)},
                         {"side", a.side == Side::Tool ? "tool" : "workpiece"},
                         {"direction", {a.direction.x(), a.direction.y(), a.direction.z()}},
                         {"location_mm", {a.location.x(), a.location.y(), a.location.z()}},
                         {"offset_mm", {a.offset.x(), a.offset.y(), a.offset.z()}},
                         {"error_frame", a.errorFrame == ErrorFrame::Fixed ? "fixed" : "moving"}};
    const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
    if (a.travel) aj["travel"] = {a.travel->min * f, a.travel->max * f};
    j["axes"].push_back(aj);
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", a.name, typeName(a.type),
                       a.side == Side::Tool ? "tool" : "workpiece", a.direction.x(), a.direction.y(), a.direction.z(),
                       a.location.x(), a.location.y(), a.location.z(), a.travel ? a.travel->min * f : 0.0,
                       a.travel ? a.travel->max * f : 0.0, a.errorFrame == ErrorFrame::Fixed ? "fixed" : "moving");
  }
  human += fmt::format("\nTool       TCP offset ({:g}, {:g}, {:g}) mm, direction ({:.3f}, {:.3f}, {:.3f})\n",
                       m.toolOffset.x(), m.toolOffset.y(), m.toolOffset.z(), m.toolDirection.x(), m.toolDirection.y(),
                       m.toolDirection.z());
  human += fmt::format("Workpiece  offset ({:g}, {:g}, {:g}) mm, {}\n", m.workpieceOffset.x(), m.workpieceOffset.y(),
                       m.workpieceOffset.z(),
                       m.alignment == WorkpieceAlignment::Table ? "fixed to the table frame (seed 001 eq. 2)"
                                                                : "aligned with the machine at the reference pose (seed 001 eqs. 10-12)");
  j["tool"] = {{"offset_mm", {m.toolOffset.x(), m.toolOffset.y(), m.toolOffset.z()}},
               {"direction", {m.toolDirection.x(), m.toolDirection.y(), m.toolDirection.z()}}};
  j["workpiece"] = {{"offset_mm", {m.workpieceOffset.x(), m.workpieceOffset.y(), m.workpieceOffset.z()}},
                    {"alignment", m.alignment == WorkpieceAlignment::Table ? "table" : "machine"}};

  int location = 0;
  for (const auto& p : catalogue) location += p.kind == ParameterKind::Location ? 1 : 0;
  human += fmt::format("\nError parameters: {} location, {} component-error coefficients; {} non-zero\n", location,
                       catalogue.size() - static_cast<size_t>(location), nonZero.size());
  for (const auto& p : nonZero) {
    const double v = parameterValue(loaded.errors, p);
    human += fmt::format("  {:<10} {:>10.3f} {}\n", p.name, toDisplay(v, p.dimension), unitOf(p.dimension));
    j["errors"][p.name] = {{"value", toDisplay(v, p.dimension)}, {"unit", unitOf(p.dimension)}};
  }
  j["parameter_count"] = catalogue.size();
  j["valid"] = true;
  emit(o, j, human, csv);
}

}  // namespace

void addCheckCommand(CLI::App& app) {
  auto o = std::make_shared<MachineOptions>();
  auto* cmd = app.add_subcommand("check", "validate a machine and print its kinematic chain and error parameters");
  addMachineOptions(*cmd, *o);
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
