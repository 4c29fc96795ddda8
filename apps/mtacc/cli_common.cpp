#include "cli_common.hpp"

#include <fmt/format.h>

#include <iostream>
#include <sstream>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_yaml.hpp"
#include "mtacc/io/atomic_file.hpp"
#include "mtacc/machine/machine_yaml.hpp"

namespace mtacc::cli {

void addMachineOptions(CLI::App& cmd, MachineOptions& o) {
  cmd.add_option("machine", o.machine, "machine file, or the name of a bundled machine (e.g. tilting-table)")->required();
  cmd.add_option("--errors", o.errorsFile, "errors file (YAML with an 'errors:' mapping); default: the machine file's");
  cmd.add_flag("--json", o.json, "print one JSON object instead of tables");
  cmd.add_option("-o,--output", o.output, "write the result to FILE (CSV, or JSON with --json), atomically");
  cmd.add_option("--alignment", o.alignment,
                 "workpiece set-up: 'table' (fixed to the table frame) or 'machine' (aligned at the reference pose, "
                 "seed 001 M_WC); default: the machine file's");
}

Loaded load(const MachineOptions& o) {
  Machine loaded = loadMachine(o.machine);
  if (o.alignment == "table") loaded.alignment = WorkpieceAlignment::Table;
  else if (o.alignment == "machine") loaded.alignment = WorkpieceAlignment::Machine;
  else if (!o.alignment.empty()) throw InputError(InputLocation{"", 0, "--alignment"}, "expected 'table' or 'machine'");
  auto machine = std::make_shared<const Machine>(std::move(loaded));
  ErrorModel errors = o.errorsFile.empty() ? loadMachineErrors(*machine) : loadErrors(*machine, o.errorsFile);
  return {machine, std::move(errors)};
}

std::vector<double> parsePose(const Machine& m, const std::string& text, bool partial) {
  std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
  std::vector<bool> seen(q.size(), false);
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw InputError(InputLocation{"", 0, "--pose"}, "expected AXIS=VALUE, got '" + item + "'");
    const std::string name = item.substr(0, eq);
    const int i = m.axisIndex(name);
    if (i < 0 || !m.axes[static_cast<size_t>(i)].commanded())
      throw InputError(InputLocation{"", 0, "--pose"}, "unknown axis '" + name + "'");
    double v = 0;
    try {
      size_t used = 0;
      v = std::stod(item.substr(eq + 1), &used);
      if (used != item.size() - eq - 1 || !std::isfinite(v)) throw std::invalid_argument("");
    } catch (const std::logic_error&) {
      throw InputError(InputLocation{"", 0, "--pose " + name}, "not a finite number: '" + item.substr(eq + 1) + "'");
    }
    q[static_cast<size_t>(i)] = m.axes[static_cast<size_t>(i)].isRotary() ? v * kDeg : v;
    seen[static_cast<size_t>(i)] = true;
  }
  for (size_t i = 0; i < q.size() && !partial; ++i)
    if (!seen[i]) throw InputError(InputLocation{"", 0, "--pose"}, "axis " + m.axes[i].name + " missing (mm for linear, deg for rotary axes)");
  return q;
}

Vec3 parseVector(const std::string& text, const std::string& what) {
  std::stringstream ss(text);
  std::string item;
  Vec3 v;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n == 3) break;
    try {
      size_t used = 0;
      v[n] = std::stod(item, &used);
      if (!std::isfinite(v[n])) throw std::invalid_argument("");
    } catch (const std::logic_error&) {
      throw InputError(InputLocation{"", 0, what}, "not a finite number: '" + item + "'");
    }
    ++n;
  }
  if (n != 3 || std::getline(ss, item)) throw InputError(InputLocation{"", 0, what}, "expected three numbers x,y,z");
  return v;
}

double parseQuantityArg(const std::string& text, Dimension expected, const std::string& what) {
  std::string reason;
  const auto q = parseQuantity(text, &reason);
  if (!q) throw InputError(InputLocation{"", 0, what}, reason);
  if (q->dimension != expected) throw InputError(InputLocation{"", 0, what}, std::string("expected ") + withArticle(expected));
  return q->value;
}

void emit(const MachineOptions& o, const nlohmann::json& json, const std::string& human, const std::string& csv) {
  if (o.json) {
    const std::string text = json.dump(2) + "\n";
    if (o.output.empty()) std::cout << text;
    else writeFileAtomically(o.output, text);
    return;
  }
  std::cout << human;
  if (!o.output.empty()) writeFileAtomically(o.output, csv);
}

nlohmann::json poseJson(const Machine& m, const double* q) {
  nlohmann::json j = nlohmann::json::object();
  for (int i = 0; i < m.commandedCount(); ++i) {
    const Axis& a = m.axes[static_cast<size_t>(i)];
    j[a.name] = a.isRotary() ? q[i] / kDeg : q[i];
  }
  return j;
}

std::string formatPose(const Machine& m, const double* q) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) {
    const Axis& a = m.axes[static_cast<size_t>(i)];
    s += fmt::format("{}{:>10.4f}", i ? " " : "", a.isRotary() ? q[i] / kDeg : q[i]);
  }
  return s;
}

std::string unitOf(Dimension d) { return d == Dimension::Length ? "um" : "urad"; }
double toDisplay(double v, Dimension d) { return d == Dimension::Length ? v * 1e3 : v * 1e6; }

}  // namespace mtacc::cli
