#include "mtacc/compensation/isg_volumetric.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"

namespace mtacc {
namespace {


double argument(const Axis& axis, double q) { return axis.isRotary() ? q / kDeg : q; }

void checkRoles(const Machine& m) {
  const InputLocation at{m.sourceFile, 0, "axes"};
  for (const Axis& axis : m.axes) {
    if (!axis.commanded()) continue;
    const std::string letters = axis.isRotary() ? "ABC" : "XYZ";
    const auto letter = axis.name.size() == 1 ? letters.find(axis.name[0]) : std::string::npos;
    if (letter == std::string::npos)
      throw InputError(at, fmt::format("ISG's volumetric model has linear X, Y, Z and rotary A, B, C only, not the axis {}", axis.name));
    if (axis.isRotary() && std::abs(axis.direction[static_cast<Eigen::Index>(letter)]) < 1.0 - 1e-12)
      throw InputError(at, fmt::format("ISG's volumetric model turns {} about the machine's {}: the machine file inclines it", axis.name,
                                       "XYZ"[letter]));
  }
  for (const char* name : {"X", "Y", "Z"})
    if (m.commandedAxisIndex(name) < 0) throw InputError(at, fmt::format("ISG's volumetric model needs a linear axis {}", name));
}

// The part of the model the files cannot hold, named.
// The spindle: the axis past the last commanded one on the tool side, or none.
int spindleAxis(const Machine& m) {
  for (size_t a = 0; a < m.axes.size(); ++a)
    if (!m.axes[a].commanded() && m.axes[a].side == Side::Tool) return static_cast<int>(a);
  return -1;
}

// The part of the model the files and the tool's offsets cannot hold, named: of the spindle, all
// but its offsets.
std::vector<std::string> notCarried(const Machine& m, const ErrorModel& errors) {
  std::vector<std::string> left{"the tool direction (the controller corrects the position only)"};
  if (const int spindle = spindleAxis(m); spindle >= 0) {
    std::vector<std::string> names;
    for (const auto& p : nonZeroParameters(m, errors))
      if (p.axis == spindle && !(p.kind == ParameterKind::Location && p.component < 3)) names.push_back(p.name);
    if (!names.empty())
      left.push_back(fmt::format("the errors of the spindle {} ({}): the controller's chain ends at the last commanded axis, and the tool's "
                                 "offsets hold only the spindle's offsets", m.axes[static_cast<size_t>(spindle)].name, fmt::join(names, ", ")));
  }
  if (const auto reversal = reversalFunctions(m, errors); !reversal.empty())
    left.push_back(fmt::format("the reversal terms of {} (the tables have no direction of motion)", fmt::join(reversal, ", ")));
  if (!errors.stiffness.empty())
    left.push_back(fmt::format("{} changes of component errors with another axis or the load (mtacc does not write them as "
                               "multi-dimensional tables)", errors.stiffness.size()));
  return left;
}

// The spindle's offsets, for the tool data the files do not hold.
std::string toolOffsetNote(const IsgVolumetricModel& model) {
  if (model.toolOffset.isZero()) return "";
  return fmt::format("// the spindle's offsets turn with the tool: add ({:.7f}, {:.7f}, {:.7f}) mm to the tool's kinematic offsets (P-TOOL-00009)\n",
                     model.toolOffset.x(), model.toolOffset.y(), model.toolOffset.z());
}

}  // namespace

IsgVolumetricModel isgVolumetricModel(const Machine& m, const ErrorModel& errors, int records) {
  checkRoles(m);
  if (records < 2 || records > 10000) throw InputError({"", 0, "records"}, fmt::format("{} records per table: give 2 to 10000", records));
  IsgVolumetricModel model;
  for (auto it = m.workpieceChain.rbegin(); it != m.workpieceChain.rend(); ++it)
    if (m.axes[static_cast<size_t>(*it)].commanded()) {
      model.chain += m.axes[static_cast<size_t>(*it)].name;
      ++model.workpieceAxes;
    }
  for (int index : m.toolChain)
    if (m.axes[static_cast<size_t>(index)].commanded()) model.chain += m.axes[static_cast<size_t>(index)].name;

  for (const Parameter& p : parameterCatalogue(m, errors))
    if (p.kind == ParameterKind::Location && m.axes[static_cast<size_t>(p.axis)].commanded())
      model.positionErrors.emplace_back(p.name, parameterValue(errors, p));
  for (size_t a = 0; a < m.axes.size(); ++a) {
    const Axis& axis = m.axes[a];
    const auto& motion = errors.axes[a].motion;
    if (!axis.commanded() || std::all_of(motion.begin(), motion.end(), [](const ErrorFunction& f) { return f.empty(); })) continue;
    const AxisSpan span = harmonicSpan(axis);  // the travel, or one turn
    IsgVolumetricModel::ComponentTable table;
    table.axis = static_cast<int>(a);
    for (int r = 0; r < records; ++r) {
      const double q = span.min + span.range * r / (records - 1);
      table.arguments.push_back(argument(axis, q));
      for (size_t c = 0; c < 6; ++c) table.values[c].push_back(motion[c].value(q, 0));
    }
    model.components.push_back(std::move(table));
  }
  if (const int spindle = spindleAxis(m); spindle >= 0) model.toolOffset = errors.axes[static_cast<size_t>(spindle)].location.head<3>();
  model.notCarried = notCarried(m, errors);
  return model;
}

ErrorModel isgControllerModel(const Machine& m, const IsgVolumetricModel& model) {
  ErrorModel e = ErrorModel::zero(m);
  if (const int spindle = spindleAxis(m); spindle >= 0) e.axes[static_cast<size_t>(spindle)].location.head<3>() = model.toolOffset;
  for (const auto& [name, value] : model.positionErrors) setParameterValue(e, findParameter(m, e, name), value);
  for (const auto& table : model.components) {
    const Axis& axis = m.axes[static_cast<size_t>(table.axis)];
    std::vector<double> positions;
    for (double argument : table.arguments) positions.push_back(axis.isRotary() ? argument * kDeg : argument);
    for (size_t c = 0; c < 6; ++c)
      if (anyNonZero(table.values[c])) e.axes[static_cast<size_t>(table.axis)].motion[c].add(TableTerm(positions, table.values[c], Interpolation::Linear));
  }
  return e;
}

CommandCorrection isgCorrection(const std::shared_ptr<const Machine>& machine, const ErrorModel& controllerModel) {
  struct State {
    KinematicModel model, nominal;
    ErrorIkJacobian jacobian;
    ErrorIkOptions options;
    std::array<size_t, 3> xyz;
  };
  auto s = std::make_shared<State>(State{compile(machine, controllerModel), compileNominal(machine), {}, {}, {}});
  s->options = positionCorrectionOptions();
  for (size_t k = 0; k < 3; ++k) s->xyz[k] = static_cast<size_t>(machine->commandedAxisIndex(kLinearAxisNames[k]));
  // A continuous rotary axis is a modulo axis to the controller: it evaluates its tables at the
  // position within the turn, 0 to 360 degrees, whatever turn the command is in.
  std::vector<size_t> modulo;
  for (size_t k = 0; k < static_cast<size_t>(machine->commandedCount()); ++k)
    if (machine->axes[k].isRotary() && !machine->axes[k].travel) modulo.push_back(k);
  return [s, modulo](const std::vector<double>& command) {
    std::vector<double> q = command;
    for (size_t k : modulo) q[k] -= 2.0 * kPi * std::floor(q[k] / (2.0 * kPi));
    const ToolPoint wanted = toolPoint(s->nominal, q.data());
    const ErrorIkSolution solution = refineWithErrors(s->model, wanted.position, wanted.direction, q, s->options, s->jacobian);
    Vec3 c;
    for (size_t k = 0; k < 3; ++k) c[static_cast<Eigen::Index>(k)] = solution.q[s->xyz[k]] - q[s->xyz[k]];
    return c;
  };
}

std::string isgCsv(const Machine& m, const IsgVolumetricModel& model) {
  std::string out = fmt::format("// mtacc: the ISO 230-1 model of {} for TwinCAT/ISG volumetric compensation (TF5280), chain {}, workpiece_axes {}\n"
                                "// values in mm and rad; arguments in mm (X, Y, Z) and degrees (A, B, C); linear between the records\n",
                                m.name, model.chain, model.workpieceAxes);
  for (const auto& left : model.notCarried) out += "// not carried: " + left + "\n";
  out += toolOffsetNote(model);
  auto it = std::back_inserter(out);
  std::vector<std::string> names;
  std::vector<double> values;
  for (const auto& [name, value] : model.positionErrors) {
    names.push_back(name);
    values.push_back(value);
  }
  fmt::format_to(it, "{}\n{:.10f}\n", fmt::join(names, " "), fmt::join(values, " "));
  for (const auto& table : model.components) {
    const std::string& axis = m.axes[static_cast<size_t>(table.axis)].name;
    fmt::format_to(it, "#\n{}", axis);
    for (size_t c = 0; c < 6; ++c)
      if (anyNonZero(table.values[c])) fmt::format_to(it, " {}", motionErrorName(m, table.axis, static_cast<int>(c)));
    out += "\n";
    for (size_t r = 0; r < table.arguments.size(); ++r) {
      fmt::format_to(it, "{:.6f}", table.arguments[r]);
      for (size_t c = 0; c < 6; ++c)
        if (anyNonZero(table.values[c])) fmt::format_to(it, " {:.10f}", table.values[c][r]);
      out += "\n";
    }
  }
  return out;
}

std::string etalonExchange(const Machine& m, const IsgVolumetricModel& model) {
  std::string out = fmt::format("// mtacc: the ISO 230-1 model of {} in Etalon's exchange format (\"Vendor\" variant) for TwinCAT/ISG\n"
                                "// values in mm and rad; Gridpoints: argument (mm; degrees for A, B, C) and value\n",
                                m.name);
  for (const auto& left : model.notCarried) out += "// not carried: " + left + "\n";
  out += toolOffsetNote(model);
  auto it = std::back_inserter(out);
  for (const auto& [name, value] : model.positionErrors) fmt::format_to(it, "[{}]\nVALUE = {:.10f}\n", name, value);
  for (const auto& table : model.components)
    for (size_t c = 0; c < 6; ++c) {
      if (!anyNonZero(table.values[c])) continue;
      const std::string name = motionErrorName(m, table.axis, static_cast<int>(c));
      fmt::format_to(it, "[{}]\nGridpoints = {{\n", name);
      for (size_t r = 0; r < table.arguments.size(); ++r) fmt::format_to(it, "{:.6f} {:.10f}\n", table.arguments[r], table.values[c][r]);
      fmt::format_to(it, "}} // end of {}\n", name);
    }
  return out;
}

std::string isgCompensationList(const Machine& m, const IsgVolumetricModel& model, const std::string& csvFile) {
  size_t records = 1;
  for (const auto& table : model.components) records += table.arguments.size();
  std::string out = fmt::format("# mtacc: TwinCAT/ISG volumetric compensation list for {}\n"
                                "# the logical axis numbers are the machine file's order: set the control's\n"
                                "# the start-up list needs vol_comp[0].max_records >= {} and vol_comp[0].file_name naming this list\n",
                                m.name, records);
  auto it = std::back_inserter(out);
  for (int k = 0; k < m.commandedCount(); ++k) fmt::format_to(it, "{} {}\n", static_cast<char>(std::tolower(m.axes[static_cast<size_t>(k)].name[0])), k + 1);
  fmt::format_to(it, "chain {}\nworkpiece_axes {}\nfile[0] {}\nfile_format[0] ISG_CSV\ninterpolation GRID\n", model.chain, model.workpieceAxes, csvFile);
  return out;
}

}  // namespace mtacc
