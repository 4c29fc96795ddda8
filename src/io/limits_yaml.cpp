#include "mtacc/io/limits_yaml.hpp"

#include "mtacc/core/text_file.hpp"

#include <regex>

#include "mtacc/core/units.hpp"
#include "mtacc/core/input_error.hpp"
#include "yaml_input.hpp"

namespace mtacc {

ErrorLimits loadErrorLimits(const Machine& machine, const std::string& path, AbsentAxes absent) {
  return parseErrorLimits(machine, readTextFile(path), path, absent);
}

ErrorLimits parseErrorLimits(const Machine& machine, const std::string& yamlText, const std::string& path, AbsentAxes absent) {
  const yamlin::Context ctx{path};
  const auto root = yamlin::loadText(yamlText, path);
  if (!root.IsMap() || !root["limits"] || !root["limits"].IsMap()) ctx.fail(root, "limits", "expected a 'limits:' mapping");
  ErrorLimits out;
  out.file = path;
  static const std::regex pattern(R"(^(E([XYZABC])([A-Z]\d*))\.(lin|hyst|rev|cyclic|([1-9])harm)$)");
  const ErrorModel zero = ErrorModel::zero(machine);
  for (const auto& kv : root["limits"]) {
    const auto name = kv.first.as<std::string>();
    const std::string key = "limits." + name;
    ErrorLimit l;
    l.key = name;
    YAML::Node range = kv.second;
    std::smatch m;
    const std::string axisName = std::regex_match(name, m, pattern) ? m[3].str() : name.size() > 2 ? name.substr(2) : "";
    if (absent == AbsentAxes::LeaveOut && machine.commandedAxisIndex(axisName) < 0) {
      out.leftOut.push_back(name);
      continue;
    }
    if (!m.empty()) {
      l.axis = machine.axisIndex(axisName);
      if (l.axis < 0) ctx.fail(kv.first, key, "unknown axis '" + axisName + "'");
      l.component = static_cast<int>(std::string("XYZABC").find(m[2].str()[0]));
      const std::string type = m[4];
      l.kind = type == "lin" ? ErrorLimit::Linear : type == "hyst" || type == "rev" ? ErrorLimit::Reversal
               : type == "cyclic" ? ErrorLimit::Cyclic : ErrorLimit::Harmonic;
      if (l.kind == ErrorLimit::Harmonic) l.order = std::stoi(m[5]);
      if (l.kind == ErrorLimit::Cyclic) {
        yamlin::rejectUnknownKeys(ctx, kv.second, key, {"range", "pitch"});
        const Dimension posDim = machine.axes[static_cast<size_t>(l.axis)].isRotary() ? Dimension::Angle : Dimension::Length;
        l.pitch = yamlin::size(ctx, kv.second["pitch"], key + ".pitch", posDim);
        range = kv.second["range"];
      }
    } else {
      try {
        l.location = findParameter(machine, zero, name);
      } catch (const InputError& e) {
        ctx.fail(kv.first, key, e.reason());
      }
      if (l.location.kind != ParameterKind::Location) ctx.fail(kv.first, key, "expected a location error or NAME.lin/.hyst (or .rev)/.cyclic/.<k>harm (k from 1 to 9)");
      l.axis = l.location.axis;
      l.component = l.location.component;
    }
    const Dimension dim = l.component < 3 ? Dimension::Length : Dimension::Angle;
    if (!yamlin::isSequence(range) || range.size() != 2) ctx.fail(range, key, "expected [lower, upper] with units");
    l.lower = yamlin::quantity(ctx, range[0], key, dim);
    l.upper = yamlin::quantity(ctx, range[1], key, dim);
    if (l.lower > l.upper) ctx.fail(range, key, "lower limit above upper limit");
    out.limits.push_back(l);
  }
  return out;
}

}  // namespace mtacc
