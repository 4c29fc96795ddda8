// mtacc dynamics modes | frf | accel | map: the rigid-body structural dynamics of a structure
// model (seed 000 part II) at given axis positions, or over a grid of positions.
#include <fmt/format.h>

#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "mtacc/io/atomic_file.hpp"

namespace mtacc::cli {
namespace {

// MachineOptions::machine holds the structure model; --errors does not apply.
struct DynamicsOptions : MachineOptions {
  std::string at, method = "modal", quantity = "Hx/X", axes = "Y,Z", grid = "20x20", compare;
  double from = 0, to = 200, step = 1;
  int count = 12;
};

// "Y=400,Z=-300" (mm); the other axes at 0.
std::vector<double> positions(const StructureModel& m, const std::string& text) {
  std::vector<double> q(m.axes.size(), 0.0);
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    const int j = eq == std::string::npos ? -1 : m.axisIndex(item.substr(0, eq));
    if (j < 0) throw InputError(InputLocation{"", 0, "--at"}, "expected AXIS=mm for the axes of " + m.name + ", got '" + item + "'");
    try {
      q[static_cast<size_t>(j)] = std::stod(item.substr(eq + 1)) * 1e-3;
    } catch (const std::logic_error&) {
      throw InputError(InputLocation{"", 0, "--at"}, "not a number: '" + item.substr(eq + 1) + "'");
    }
  }
  return q;
}

void modes(const DynamicsOptions& o) {
  const auto model = loadStructure(o.machine);
  const auto mats = assembleStructure(model, positions(model, o.at));
  const auto undamped = undampedModes(model, mats);
  const auto damped = dampedModes(mats);
  const char* dofs[6] = {"x", "y", "z", "rx", "ry", "rz"};
  nlohmann::json j;
  j["model"] = model.name;
  std::string human = fmt::format("{}: {} bodies, {} DOF\n{:>4} {:>10} {:>10} {:>8}  dominant motion (kinetic energy)\n",
                                  model.name, model.bodies.size(), model.dofs(), "mode", "f [Hz]", "f_d [Hz]", "zeta [%]");
  std::string csv = "mode,frequency_hz,damped_frequency_hz,damping_ratio,body,dof\n";
  const auto n = std::min<Eigen::Index>(o.count, undamped.frequencies.size());
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::VectorXd phi = undamped.shapes.col(r);
    Eigen::Index k = 0;
    (mats.mass * phi).cwiseProduct(phi).maxCoeff(&k);
    const auto& body = model.bodies[static_cast<size_t>(k / 6)].name;
    const DampedMode d = static_cast<size_t>(r) < damped.size() ? damped[static_cast<size_t>(r)] : DampedMode{0, 0};
    human += fmt::format("{:>4} {:>10.2f} {:>10.2f} {:>8.2f}  {} {}\n", r + 1, undamped.frequencies[r], d.frequency,
                         d.dampingRatio * 100, body, dofs[k % 6]);
    csv += fmt::format("{},{},{},{},{},{}\n", r + 1, undamped.frequencies[r], d.frequency, d.dampingRatio, body, dofs[k % 6]);
    j["modes"].push_back({{"frequency_hz", undamped.frequencies[r]}, {"damped_frequency_hz", d.frequency},
                          {"damping_ratio", d.dampingRatio}, {"body", body}, {"dof", dofs[k % 6]}});
  }
  emit(o, j, human, csv);
}

void frf(const DynamicsOptions& o) {
  const auto model = loadStructure(o.machine);
  const auto mats = assembleStructure(model, positions(model, o.at));
  if (!(o.step > 0) || o.to < o.from || o.from < 0)
    throw InputError(InputLocation{"", 0, "--step"}, "need 0 <= from <= to and a positive step (Hz)");
  std::vector<double> f;
  for (double x = o.from; x <= o.to + 1e-9; x += o.step) f.push_back(x);
  Frf h;
  if (o.method == "modal") h = frfModal(mats, undampedModes(model, mats), f);
  else if (o.method == "direct") h = frfDirect(mats, f);
  else throw InputError(InputLocation{"", 0, "--method"}, "expected modal or direct");
  const char* c = "xyz";
  std::string csv = "frequency_hz";
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) csv += fmt::format(",H{}{}_um_per_N,H{}{}_phase_deg", c[i], c[k], c[i], c[k]);
  csv += "\n";
  nlohmann::json j;
  j["model"] = model.name;
  j["method"] = o.method;
  double peak = 0, peakF = 0;
  for (size_t s = 0; s < f.size(); ++s) {
    csv += fmt::format("{}", f[s]);
    nlohmann::json row;
    row["frequency_hz"] = f[s];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        const auto v = h[s](i, k);
        csv += fmt::format(",{},{}", std::abs(v) * 1e6, std::arg(v) / kDeg);
        row[fmt::format("H{}{}", c[i], c[k])] = {std::abs(v) * 1e6, std::arg(v) / kDeg};
      }
    if (std::abs(h[s](0, 0)) > peak) peak = std::abs(h[s](0, 0)), peakF = f[s];
    csv += "\n";
    j["frf"].push_back(row);
  }
  const Eigen::Matrix3d st = staticCompliance(mats) * 1e6;
  std::string human = fmt::format("{}: 3x3 FRF of the TCP relative to the workpiece, {} frequencies {:g}-{:g} Hz ({})\n",
                                  model.name, f.size(), o.from, o.to, o.method);
  human += fmt::format("static compliance [um/N]:\n  {:9.5f} {:9.5f} {:9.5f}\n  {:9.5f} {:9.5f} {:9.5f}\n  {:9.5f} {:9.5f} {:9.5f}\n",
                       st(0, 0), st(0, 1), st(0, 2), st(1, 0), st(1, 1), st(1, 2), st(2, 0), st(2, 1), st(2, 2));
  human += fmt::format("largest |Hxx| {:.4f} um/N at {:g} Hz; -o FILE writes magnitude and phase of all nine terms\n",
                       peak * 1e6, peakF);
  emit(o, j, human, csv);
}

void accel(const DynamicsOptions& o) {
  const auto model = loadStructure(o.machine);
  const auto mats = assembleStructure(model, positions(model, o.at));
  const Eigen::MatrixXd r = accelerationResponse(mats) * kStandardGravity * 1e6;
  nlohmann::json j;
  j["model"] = model.name;
  std::string human = fmt::format("{}: quasi-static TCP displacement per axis acceleration [um/g_n] (seed 000 Table 7.1 form)\n"
                                  "{:>8}", model.name, "");
  std::string csv = "response";
  for (const auto& a : model.axes) human += fmt::format(" {:>10}", a.name + "''"), csv += "," + a.name;
  human += "\n", csv += "\n";
  const char* c = "xyz";
  for (int i = 0; i < 3; ++i) {
    human += fmt::format("{:>8}", std::string("H") + c[i]);
    csv += std::string("H") + c[i];
    for (Eigen::Index k = 0; k < r.cols(); ++k) {
      human += fmt::format(" {:>10.2f}", r(i, k));
      csv += fmt::format(",{}", r(i, k));
      j["response_um_per_g"][std::string("H") + c[i]][model.axes[static_cast<size_t>(k)].name] = r(i, k);
    }
    human += "\n", csv += "\n";
  }
  emit(o, j, human, csv);
}

void map(const DynamicsOptions& o) {
  std::vector<StructureModel> models = {loadStructure(o.machine)};
  if (!o.compare.empty()) models.push_back(loadStructure(o.compare));
  const auto comma = o.axes.find(',');
  const auto x = o.grid.find('x');
  if (comma == std::string::npos || x == std::string::npos)
    throw InputError(InputLocation{"", 0, comma == std::string::npos ? "--axes" : "--grid"}, "expected e.g. --axes Y,Z --grid 20x20");
  int na = 0, nb = 0;
  try {
    na = std::stoi(o.grid.substr(0, x)), nb = std::stoi(o.grid.substr(x + 1));
  } catch (const std::exception&) {
    throw InputError(InputLocation{"", 0, "--grid"}, "expected e.g. 20x20");
  }
  nlohmann::json j;
  std::string human, csv = "model," + o.axes.substr(0, comma) + "_mm," + o.axes.substr(comma + 1) + "_mm,value\n";
  for (const auto& m : models) {
    const auto q = dynamicsQuantity(m, o.quantity);
    const auto r = dynamicsMap(m, positions(m, o.at), o.axes.substr(0, comma), o.axes.substr(comma + 1), na, nb, q);
    const auto& s = r.statistics;
    human += fmt::format("{}: {} over {} x {} positions in {}-{} [{}]\n  min {:.3f}  lower quartile {:.3f}  median {:.3f}  "
                         "upper quartile {:.3f}  max {:.3f}\n",
                         m.name, q.name, na, nb, r.axisA, r.axisB, q.unit, s.min, s.lowerQuartile, s.median, s.upperQuartile, s.max);
    for (size_t a = 0; a < r.a.size(); ++a)
      for (size_t b = 0; b < r.b.size(); ++b)
        csv += fmt::format("{},{},{},{}\n", m.name, r.a[a] * 1e3, r.b[b] * 1e3,
                           r.values(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
    j["maps"].push_back({{"model", m.name}, {"quantity", q.name}, {"unit", q.unit},
                         {"axes", {r.axisA, r.axisB}},
                         {"statistics", {{"min", s.min}, {"lower_quartile", s.lowerQuartile}, {"median", s.median},
                                         {"upper_quartile", s.upperQuartile}, {"max", s.max}}}});
  }
  emit(o, j, human, csv);
}

}  // namespace

void addDynamicsCommand(CLI::App& app) {
  auto o = std::make_shared<DynamicsOptions>();
  auto* dyn = app.add_subcommand("dynamics", "Rigid-body structural dynamics of a structure model (seed 000 part II)");
  dyn->require_subcommand(1);
  auto common = [&](CLI::App* c) {
    c->add_option("model", o->machine, "Structure model (YAML) or bundled name, e.g. tzyx-arm-x")->required();
    c->add_option("--at", o->at, "Axis positions in mm, e.g. Y=400,Z=-300 (others 0)");
    c->add_flag("--json", o->json, "One JSON object instead of tables");
    c->add_option("-o,--output", o->output, "Write the result to FILE (CSV, or JSON with --json), atomically");
  };
  auto* m = dyn->add_subcommand("modes", "Undamped and damped modes");
  common(m);
  m->add_option("--count", o->count, "Modes to list")->capture_default_str();
  m->callback([o] { modes(*o); });
  auto* f = dyn->add_subcommand("frf", "3x3 FRF of the TCP relative to the workpiece and the static compliance");
  common(f);
  f->add_option("--from", o->from, "First frequency, Hz")->capture_default_str();
  f->add_option("--to", o->to, "Last frequency, Hz")->capture_default_str();
  f->add_option("--step", o->step, "Frequency step, Hz")->capture_default_str();
  f->add_option("--method", o->method, "modal (all modes) or direct")->capture_default_str();
  f->callback([o] { frf(*o); });
  auto* a = dyn->add_subcommand("accel", "Quasi-static response to the acceleration of each axis, um/g_n");
  common(a);
  a->callback([o] { accel(*o); });
  auto* p = dyn->add_subcommand("map", "A quantity over a grid of two axes, with distribution statistics");
  common(p);
  p->add_option("--quantity", o->quantity, "Hx/X (um/g), Cxx (um/N) or f1 (Hz)")->capture_default_str();
  p->add_option("--axes", o->axes, "The two axes of the grid")->capture_default_str();
  p->add_option("--grid", o->grid, "Positions per axis")->capture_default_str();
  p->add_option("--compare", o->compare, "A second model evaluated on the same grid");
  p->callback([o] { map(*o); });
}

}  // namespace mtacc::cli
