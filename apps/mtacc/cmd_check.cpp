// mtacc check MACHINE: validate the description and print the chain and its error parameters.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/check.hpp"

namespace mtacc::cli {
namespace {

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

struct CheckOptions : MachineOptions {
  OptionValues values;
};

void run(const CheckOptions& o) {
  const bool listParameters = OptionReader(checkSchema(), o.values).flag("parameters");
  const auto c = checkMachine(loadMachineSetup(o.source));
  const Machine& m = *c.setup.machine;
  std::string human = fmt::format("Machine    {}\nFile       {}\nStructure  {}  (tool first: {})\n", m.name, m.sourceFile,
                                  m.structure.text, m.structure.toolFirst());
  human += fmt::format("Tool chain       bed -> {} -> tool\n", chainText(m, m.toolChain));
  human += fmt::format("Workpiece chain  bed -> {} -> workpiece\n", chainText(m, m.workpieceChain));
  const auto& k = c.machineClass;
  human += fmt::format("Class            {} ({}; vertical ({:g}, {:g}, {:g})), BCR 1991 Table 2.2{}\n", k.linear.empty() ? "none" : k.linear,
                       k.chains, m.vertical.x(), m.vertical.y(), m.vertical.z(),
                       k.linear.empty() ? "" : ": " + k.example + "; bends while traversing: " + fmt::format("{}", fmt::join(k.typeDependentErrors, "; ")));
  human += k.rotary ? fmt::format("Rotary class     {}, Table 2.3: {}\n", k.rotary, k.rotaryDescription) : std::string("Rotary class     none (Table 2.3)\n");
  for (const auto& n : k.notes) human += "                 " + n + "\n";
  human += "\n";
  human += fmt::format("{:<5} {:<8} {:<10} {:<26} {:<28} {:<22} {}\n", "axis", "type", "side", "direction",
                       "location / offset (mm)", "travel", "errors act in");
  std::string csv = "axis,type,side,dx,dy,dz,location_x,location_y,location_z,travel_min,travel_max,error_frame\n";
  for (const auto& a : m.axes) {
    const Vec3 place = a.type == AxisType::Linear ? a.offset : a.location + a.offset;
    const char* side = a.side == Side::Tool ? "tool" : "workpiece";
    const char* frame = a.errorFrame == ErrorFrame::Fixed ? "fixed" : "moving";
    human += fmt::format("{:<5} {:<8} {:<10} ({:6.3f}, {:6.3f}, {:6.3f})    ({:7.1f}, {:7.1f}, {:7.1f})    {:<22} {} frame\n",
                         a.name, axisTypeName(a.type), side, a.direction.x(), a.direction.y(), a.direction.z(), place.x(),
                         place.y(), place.z(), travelText(a), frame);
    const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", a.name, axisTypeName(a.type), side, a.direction.x(),
                       a.direction.y(), a.direction.z(), a.location.x(), a.location.y(), a.location.z(),
                       a.travel ? a.travel->min * f : 0.0, a.travel ? a.travel->max * f : 0.0, frame);
  }
  human += fmt::format("\nTool       TCP offset ({:g}, {:g}, {:g}) mm, direction ({:.3f}, {:.3f}, {:.3f})\n", m.toolOffset.x(),
                       m.toolOffset.y(), m.toolOffset.z(), m.toolDirection.x(), m.toolDirection.y(), m.toolDirection.z());
  human += fmt::format("Workpiece  offset ({:g}, {:g}, {:g}) mm, {}\n", m.workpieceOffset.x(), m.workpieceOffset.y(),
                       m.workpieceOffset.z(),
                       m.alignment == WorkpieceAlignment::Table ? "fixed to the table frame (Li et al. 2021 eq. 2)"
                                                                : "aligned with the machine at the reference pose (Li et al. 2021 eqs. 10-12)");
  human += fmt::format("\nError parameters: {} location, {} component-error coefficients; {} non-zero\n", c.locationCount,
                       c.parameters.size() - static_cast<size_t>(c.locationCount), c.nonZero.size());
  for (const auto& p : c.nonZero)
    human += fmt::format("  {:<10} {:>10.3f} {}\n", p.name, toDisplay(parameterValue(c.setup.errors, p), p.dimension),
                         displayUnit(p.dimension));
  if (listParameters) {
    human += "Every parameter, by the axis it belongs to (identify, observability and sensitivity take these names):\n";
    for (size_t axis = 0; axis < m.axes.size(); ++axis) {
      std::string names;
      for (const auto& p : c.parameters)
        if (p.axis == static_cast<int>(axis)) names += " " + p.name;
      if (!names.empty()) human += fmt::format("  {:<4}{}\n", m.axes[axis].name, names);
    }
  }
  if (listParameters && !c.zeroOffsets.empty()) {
    human += "Zero offsets about each rotary axis's own line (the position it takes when commanded 0):\n";
    for (const auto& z : c.zeroOffsets) human += "  " + z + "\n";
  }
  if (!c.actingAlike.empty()) {
    human += "Warning: location errors that no measurement on this machine separates (TCP and tool direction at "
             "poses within travel); identify one of each group and hold the others:\n";
    for (const auto& f : c.actingAlike) human += "  " + f + "\n";
  }
  for (const auto& w : c.warnings) human += "Warning: " + w + "\n";
  if (!c.setup.errors.stiffness.empty())
    human += fmt::format("Stiffness changes: {} at a workpiece load of {:g} kg (mtacc stiffness shows them)\n",
                         c.setup.errors.stiffness.size(), c.setup.errors.workpieceLoad);
  emit(o, toJson(c), human, csv);
}

}  // namespace

void addCheckCommand(const CommandLine& app) {
  auto o = std::make_shared<CheckOptions>();
  auto cmd = app.subcommand("check", "validate a machine and print its kinematic chain and error parameters");
  cmd.machineOptions(*o);
  cmd.schemaOptions(checkSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
