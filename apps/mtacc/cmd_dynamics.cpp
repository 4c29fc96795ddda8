// mtacc dynamics modes | frf | accel | map: the rigid-body structural dynamics of a structure
// model (Bossoni 2009 part II) at given axis positions, or over a grid of positions.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/dynamics_options.hpp"

namespace mtacc::cli {
namespace {

struct DynamicsCliOptions : MachineOptions {
  std::string model;
  OptionValues values;  // the subcommand's schema's
};

void modes(const DynamicsCliOptions& o) {
  const auto model = loadStructureModel(o.model);
  const auto r = structureModes(model, structurePositionsOf(model, structureModesSchema(), o.values));
  const int count = modesCount(o.values);
  std::string human = fmt::format("{}: {} bodies, {} DOF\n{:>4} {:>10} {:>10} {:>8}  dominant motion (kinetic energy)\n",
                                  model.name, model.bodies.size(), model.dofs(), "mode", "f [Hz]", "f_d [Hz]", "zeta [%]");
  std::string csv = "mode,frequency_hz,damped_frequency_hz,damping_ratio,body,dof\n";
  for (Eigen::Index k = 0; k < std::min<Eigen::Index>(count, r.undamped.frequencies.size()); ++k) {
    const auto i = static_cast<size_t>(k);
    const DampedMode d = i < r.damped.size() ? r.damped[i] : DampedMode{0, 0};
    human += fmt::format("{:>4} {:>10.2f} {:>10.2f} {:>8.2f}  {} {}\n", k + 1, r.undamped.frequencies[k], d.frequency,
                         d.dampingRatio * 100, r.bodies[i], r.dofs[i]);
    csv += fmt::format("{},{},{},{},{},{}\n", k + 1, r.undamped.frequencies[k], d.frequency, d.dampingRatio, r.bodies[i], r.dofs[i]);
  }
  emit(o, toJson(r, count), human, csv);
}

void frf(const DynamicsCliOptions& o) {
  const auto model = loadStructureModel(o.model);
  const auto r = structureFrf(model, structureFrfRequest(model, o.values));
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
                                  model.name, r.frequencies.size(), r.frequencies.front(), r.frequencies.back(),
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
  const auto r = structureAcceleration(model, structurePositionsOf(model, structureAccelerationSchema(), o.values));
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
  std::vector<StructureModel> models = {loadStructureModel(o.model)};
  if (const auto compare = mapComparison(o.values)) models.push_back(loadStructureModel(*compare));
  nlohmann::json j;
  std::string human, csv;
  for (const auto& m : models) {
    const MapRequest request = structureMapRequest(m, o.values);
    if (csv.empty()) csv = "model," + request.grid.axisA + "_mm," + request.grid.axisB + "_mm,value\n";
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

void addDynamicsCommand(const CommandLine& app) {
  auto dyn = app.subcommand("dynamics", "Rigid-body structural dynamics of a structure model (Bossoni 2009 part II)");
  dyn.requireSubcommand();
  const auto add = [dyn](const char* name, const char* help, const OptionSchema& schema, void (*run)(const DynamicsCliOptions&)) {
    auto o = std::make_shared<DynamicsCliOptions>();
    auto c = dyn.subcommand(name, help);
    c.argument("model", o->model, "Structure model (YAML) or bundled name, e.g. tzyx-arm-x");
    c.outputOptions(*o);
    c.schemaOptions(schema, o->values);
    c.callback([o, run] { run(*o); });
  };
  add("modes", "Undamped and damped modes", structureModesSchema(), modes);
  add("frf", "3x3 FRF of the TCP relative to the workpiece and the static compliance", structureFrfSchema(), frf);
  add("accel", "Quasi-static response to the acceleration of each axis, um/g_n", structureAccelerationSchema(), accel);
  add("map", "A quantity over a grid of two axes, with distribution statistics", structureMapSchema(), map);
}

}  // namespace mtacc::cli
