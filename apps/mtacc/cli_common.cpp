#include "cli_common.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc::cli {

void addOutputOptions(CLI::App& cmd, MachineOptions& o) {
  cmd.add_flag("--json", o.json, "print one JSON object instead of tables");
  cmd.add_option("-o,--output", o.output, "write the result to FILE (CSV, or JSON with --json), atomically");
}

CLI::Validator loadInKg() {
  return CLI::Validator(
      [](const std::string& text) {
        double kg = -1.0;
        return CLI::detail::lexical_cast(text, kg) && kg >= 0.0 && kg <= 1e6 ? std::string()
                                                                             : "'" + text + "' is not a load: expected 0 to 1e6 kg";
      },
      "KG");
}

void addMachineOptions(CLI::App& cmd, MachineOptions& o) {
  cmd.add_option("machine", o.source.machine, "machine file, or the name of a bundled machine (e.g. tilting-table)")->required();
  cmd.add_option("--errors", o.source.errorsFile, "errors file (YAML with an 'errors:' mapping); default: the machine file's");
  cmd.add_option("--alignment", o.source.alignment,
                 "workpiece set-up: 'table' (fixed to the table frame) or 'machine' (aligned at the reference pose, "
                 "the workpiece-to-table transformation M_WC of Li et al. 2021); default: the machine file's");
  cmd.add_option_function<double>(
         "--load", [&o](double kg) { o.source.load = kg; },
         "workpiece load on the table in kg, scaling the errors' load-dependent stiffness changes; default: the errors' "
         "workpiece_load")
      ->check(loadInKg());
  cmd.add_option("--thermal", o.source.thermalFile,
                 "thermal state (YAML: the temperatures along the scales, docs/file-formats.md); default: cold, 20 degC");
  addOutputOptions(cmd, o);
}

void emit(const MachineOptions& o, const nlohmann::json& json, const std::string& human, const std::string& csv) {
  if (o.json) {
    const std::string text = json.dump(2) + "\n";
    if (o.output.empty()) std::cout << text;
    else writeFileAtomically(o.output, text);
    return;
  }
  if (!o.output.empty()) writeFileAtomically(o.output, csv);  // first: a failed write prints nothing
  std::cout << human;
}

namespace {
// Rounding residue below the printed digits shows as 0, not -0.
double displayed(const Axis& a, double v) {
  const double d = a.isRotary() ? v / kDeg : v;
  return std::abs(d) < 5e-9 ? 0.0 : d;
}
}  // namespace

std::string formatPose(const Machine& m, const double* q) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += fmt::format("{}{:>10.4f}", i ? " " : "", displayed(m.axes[static_cast<size_t>(i)], q[i]));
  return s;
}

std::string poseHeader(const Machine& m) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += fmt::format("{}{:>10}", i ? " " : "", m.axes[static_cast<size_t>(i)].name);
  return s;
}

std::string poseCsv(const Machine& m, const double* q) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += fmt::format("{},", displayed(m.axes[static_cast<size_t>(i)], q[i]));
  return s;
}

std::string poseCsvHeader(const Machine& m) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += m.axes[static_cast<size_t>(i)].name + ",";
  return s;
}

}  // namespace mtacc::cli
