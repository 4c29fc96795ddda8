#include "cli_common.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc::cli {

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
