// mtacc dynamics modes | frf | accel | map: the rigid-body structural dynamics of a structure
// model (Bossoni 2009 part II) at given axis positions, or over a grid of positions.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/dynamics.hpp"

namespace mtacc::cli {
namespace {

struct DynamicsCliOptions : MachineOptions {
  std::string model, at, method = "auto", quantity = "Hx/X", axes = "Y,Z", grid = "20x20", compare;
  double from = 0, to = 200, step = 1;
  int count = 12;
};

void modes(const DynamicsCliOptions& o) {
  const auto model = loadStructureModel(o.model);
  const auto r = structureModes(model, structurePositions(model, o.at));
  std::string human = fmt::format("{}: {} bodies, {} DOF\n{:>4} {:>10} {:>10} {:>8}  dominant motion (kinetic energy)\n",
                                  model.name, model.bodies.size(), model.dofs(), "mode", "f [Hz]", "f_d [Hz]", "zeta [%]");
  std::string csv = "mode,frequency_hz,damped_frequency_hz,damping_ratio,body,dof\n";
  for (Eigen::Index k = 0; k < std::min<Eigen::Index>(o.count, r.undamped.frequencies.size()); ++k) {
    const auto i = static_cast<size_t>(k);
    const DampedMode d = i < r.damped.size() ? r.damped[i] : DampedMode{0, 0};
    human += fmt::format("{:>4} {:>10.2f} {:>10.2f} {:>8.2f}  {} {}\n", k + 1, r.undamped.frequencies[k], d.frequency,
                         d.dampingRatio * 100, r.bodies[i], r.dofs[i]);
    csv += fmt::format("{},{},{},{},{},{}\n", k + 1, r.undamped.frequencies[k], d.frequency, d.dampingRatio, r.bodies[i], r.dofs[i]);
  }
  emit(o, toJson(r, o.count), human, csv);
}

void frf(const DynamicsCliOptions& o) {
  const auto model = loadStructureModel(o.model);
  const auto r = structureFrf(model, {structurePositions(model, o.at), frequencyGrid(o.from, o.to, o.step), o.method});
  static const char* kAxes = "xyz";
  std::string csv = "frequency_hz";
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) csv += fmt::format(",H{0}{1}_um_per_N,H{0}{1}_phase_deg", kAxes[i], kAxes[k]);
  csv += "\n";
  double peak = 0, peakFrequency = 0;
  for (size_t s = 0; s < r.frequencies.size(); ++s) {
    csv += fmt::format("{}", r.frequencies[s]);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) csv += fmt::format(",{},{}", std::abs(r.frf[s](i, k)) * 1e6, std::arg(r.frf[s](i, k)) / kDeg);
    csv += "\n";
    if (std::abs(r.frf[s](0, 0)) > peak) peak = std::abs(r.frf[s](0, 0)), peakFrequency = r.frequencies[s];
  }
  const Eigen::Matrix3d st = r.staticCompliance * 1e6;
  std::string human = fmt::format("{}: 3x3 FRF of the TCP relative to the workpiece, {} frequencies {:g}-{:g} Hz ({})\n",
                                  model.name, r.frequencies.size(), o.from, o.to,
                                  r.method == "modal" ? "modal sum over all modes" : "direct solve");
  for (const auto& w : r.warnings) human += "warning: " + w + "\n";
  human += fmt::format("static compliance [um/N]:\n  {:9.5f} {:9.5f} {:9.5f}\n  {:9.5f} {:9.5f} {:9.5f}\n  {:9.5f} {:9.5f} {:9.5f}\n",
                       st(0, 0), st(0, 1), st(0, 2), st(1, 0), st(1, 1), st(1, 2), st(2, 0), st(2, 1), st(2, 2));
  human += fmt::format("largest |Hxx| {:.4f} um/N at {:g} Hz; -o FILE writes magnitude and phase of all nine terms\n", peak * 1e6,
                       peakFrequency);
  emit(o, toJson(r), human, csv);
}

void accel(const DynamicsCliOptions& o) {
  const auto model = loadStructureModel(o.model);
  const auto r = structureAcceleration(model, structurePositions(model, o.at));
  std::string human = fmt::format("{}: quasi-static TCP displacement per axis acceleration [um/g_n] (Bossoni 2009 Table 7.1 form)\n{:>8}",
                                  model.name, "");
  std::string csv = "response";
  for (const auto& a : r.axes) human += fmt::format(" {:>10}", a + "''"), csv += "," + a;
  human += "\n", csv += "\n";
  for (int i = 0; i < 3; ++i) {
    const std::string row = std::string("H") + "xyz"[i];
    human += fmt::format("{:>8}", row);
    csv += row;
    for (Eigen::Index k = 0; k < r.response.cols(); ++k) {
      human += fmt::format(" {:>10.2f}", r.response(i, k));
      csv += fmt::format(",{}", r.response(i, k));
    }
    human += "\n", csv += "\n";
  }
  emit(o, toJson(r), human, csv);
}

void map(const DynamicsCliOptions& o) {
  const auto axes = splitList(o.axes), grid = splitList(o.grid, 'x');
  if (axes.size() != 2) throw InputError(InputLocation{"", 0, "--axes"}, "expected two axes, e.g. --axes Y,Z");
  if (grid.size() != 2) throw InputError(InputLocation{"", 0, "--grid"}, "expected e.g. --grid 20x20");
  std::vector<StructureModel> models = {loadStructureModel(o.model)};
  if (!o.compare.empty()) models.push_back(loadStructureModel(o.compare));
  nlohmann::json j;
  std::string human, csv = "model," + axes[0] + "_mm," + axes[1] + "_mm,value\n";
  for (const auto& m : models) {
    const MapRequest request{o.quantity, {axes[0], axes[1], parseCount(grid[0], "--grid", 2, 1000),
                                          parseCount(grid[1], "--grid", 2, 1000), structurePositions(m, o.at)}};
    const auto r = structureMap(m, request);
    const auto& s = r.map.statistics;
    human += fmt::format("{}: {} over {} x {} positions in {}-{} [{}]\n  min {:.3f}  lower quartile {:.3f}  median {:.3f}  "
                         "upper quartile {:.3f}  max {:.3f}\n",
                         m.name, r.quantity.name, request.grid.countA, request.grid.countB, r.map.axisA, r.map.axisB, r.quantity.unit, s.min,
                         s.lowerQuartile, s.median, s.upperQuartile, s.max);
    for (size_t a = 0; a < r.map.a.size(); ++a)
      for (size_t b = 0; b < r.map.b.size(); ++b)
        csv += fmt::format("{},{},{},{}\n", m.name, r.map.a[a] * 1e3, r.map.b[b] * 1e3,
                           r.map.values(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
    j["maps"].push_back(toJson(r));
  }
  emit(o, j, human, csv);
}

}  // namespace

void addDynamicsCommand(CLI::App& app) {
  auto o = std::make_shared<DynamicsCliOptions>();
  auto* dyn = app.add_subcommand("dynamics", "Rigid-body structural dynamics of a structure model (Bossoni 2009 part II)");
  dyn->require_subcommand(1);
  auto common = [&](CLI::App* c) {
    c->add_option("model", o->model, "Structure model (YAML) or bundled name, e.g. tzyx-arm-x")->required();
    c->add_option("--at", o->at, "Axis positions in mm, e.g. Y=400,Z=-300 (others 0)");
    addOutputOptions(*c, *o);
  };
  auto* m = dyn->add_subcommand("modes", "Undamped and damped modes");
  common(m);
  m->add_option("--count", o->count, "Modes to list")->capture_default_str()->check(CLI::Range(1, 100000));
  m->callback([o] { modes(*o); });
  auto* f = dyn->add_subcommand("frf", "3x3 FRF of the TCP relative to the workpiece and the static compliance");
  common(f);
  f->add_option("--from", o->from, "First frequency, Hz")->capture_default_str();
  f->add_option("--to", o->to, "Last frequency, Hz")->capture_default_str();
  f->add_option("--step", o->step, "Frequency step, Hz")->capture_default_str();
  f->add_option("--method", o->method, "auto (the modal sum where the damping is proportional, else direct), modal or direct")->capture_default_str();
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
