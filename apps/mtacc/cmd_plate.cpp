// mtacc plate: a measured hole or ball plate against the machine's error model (seed 003 §5.3):
// per feature the measured and simulated deviations and the residual, with its k = 2 bound.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/plates.hpp"

namespace mtacc::cli {
namespace {

struct PlateCliOptions : MachineOptions {
  std::string data;
};

void run(const PlateCliOptions& o) {
  const auto c = comparePlateFile(loadMachineSetup(o.source), o.data);
  const auto j = toJson(c);
  const auto& p = c.measurement.placement;
  std::string human = fmt::format("Plate {} x {} (pitch {:g} mm) from {}, reference feature at ({:g}, {:g}, {:g}) mm\n\n", c.measurement.plate.rows,
                                  c.measurement.plate.columns, c.measurement.plate.pitch, o.data, p.origin.x(), p.origin.y(), p.origin.z());
  human += fmt::format("{:>4} {:>4} {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9}   (deviations along u, v in um)\n", "row", "col",
                       "u mm", "v mm", "measured", "", "model", "", "residual", "");
  std::string csv = "row,column,u_mm,v_mm,measured_u_um,measured_v_um,model_u_um,model_v_um,residual_u_um,residual_v_um\n";
  for (size_t k = 0; k < c.poses.features.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const auto [row, column] = c.poses.features[k];
    const std::vector<double> v{c.nominal[k].x(), c.nominal[k].y(), c.measured(i, 0) * 1e3, c.measured(i, 1) * 1e3, c.simulated(i, 0) * 1e3,
                                c.simulated(i, 1) * 1e3, c.residual(i, 0) * 1e3, c.residual(i, 1) * 1e3};
    human += fmt::format("{:>4} {:>4} {:>9.2f} {:>9.2f} | {:>9.3f} {:>9.3f} | {:>9.3f} {:>9.3f} | {:>9.3f} {:>9.3f}\n", row, column, v[0], v[1],
                         v[2], v[3], v[4], v[5], v[6], v[7]);
    csv += fmt::format("{},{},{}\n", row, column, fmt::join(v, ","));
  }
  human += fmt::format("\nresidual RMS {:.3f} um, largest {:.3f} um", j["residual_rms_um"].get<double>(), j["residual_max_um"].get<double>());
  if (c.bound)
    human += fmt::format("; k = 2 bound {:.2f} um (simulation, plate calibration, probe), {} component(s) beyond it", *c.bound * 1e3, c.beyond);
  human += "\n";
  emit(o, j, human, csv);
}

}  // namespace

void addPlateCommand(CLI::App& app) {
  auto o = std::make_shared<PlateCliOptions>();
  auto* cmd = app.add_subcommand("plate", "a measured hole or ball plate against the machine's error model (seed 003)");
  addMachineOptions(*cmd, *o);
  cmd->add_option("data", o->data, "plate measurement CSV (docs/file-formats.md \"Plate measurements\")")->required();
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
