// mtacc plate: a measured hole or ball plate against the machine's error model (the 1991 BCR report §5.3):
// per feature the measured and simulated deviations and the residual, with its k = 2 bound.
// mtacc artefact: a calibrated artefact (step gauge, ball bar, plate, 3-D) against its certificate
// and the machine's error model. mtacc plate-identify: the component errors from several plates
// or artefacts (§7.7).
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/identified_errors.hpp"
#include "mtacc/workflows/artefacts.hpp"
#include "mtacc/workflows/plates.hpp"

namespace mtacc::cli {
namespace {

struct PlateCliOptions : MachineOptions {
  OptionValues values;
};

void run(const PlateCliOptions& o) {
  const std::string data = *OptionReader(plateComparisonSchema(), o.values).text("data");
  const auto c = comparePlateFile(loadMachineSetup(o.source), data);
  const auto j = toJson(c);
  const auto& p = c.measurement.placement;
  std::string human = fmt::format("Plate {} x {} (pitch {:g} mm) from {}, reference feature at ({:g}, {:g}, {:g}) mm\n\n", c.measurement.plate.rows,
                                  c.measurement.plate.columns, c.measurement.plate.pitch, data, p.origin.x(), p.origin.y(), p.origin.z());
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

void runArtefact(const PlateCliOptions& o) {
  const std::string data = *OptionReader(artefactEvaluationSchema(), o.values).text("data");
  const auto e = evaluateArtefactFile(loadMachineSetup(o.source), data);
  const auto j = toJson(e);
  const auto& m = e.measurement;
  const auto k = e.measured.deviations.cols();
  const std::string directions = std::string("uvw").substr(0, static_cast<size_t>(k));
  std::string human = fmt::format("{} ({}-D, probed {}) from {}, aligned by {}; deviations along {} in um, U at k = 2\n\n", m.artefact.name,
                                  m.artefact.dimension, j["probed"].get<std::string>(), data, j["alignment"]["method"].get<std::string>(),
                                  fmt::join(directions, ", "));
  std::string header = fmt::format("{:<10}", "feature"), csv = "feature";
  for (const char* what : {"measured", "U", "model", "residual"})
    for (const char d : directions) {
      header += fmt::format(" {:>10}", fmt::format("{} {}", what, d));
      csv += fmt::format(",{}_{}_um", what == std::string("U") ? "expanded_uncertainty" : what, d);
    }
  human += header + "\n";
  csv += "\n";
  for (size_t h = 0; h < m.artefact.features.size(); ++h) {
    const auto i = static_cast<Eigen::Index>(h);
    std::vector<double> v;
    for (const auto* matrix : {&e.measured.deviations, &e.expanded, &e.simulated.deviations, &e.residual})
      for (Eigen::Index d = 0; d < k; ++d) v.push_back((*matrix)(i, d) * 1e3);
    human += fmt::format("{:<10} {:>10.3f}\n", m.artefact.features[h].id, fmt::join(v, " "));
    csv += fmt::format("{},{}\n", m.artefact.features[h].id, fmt::join(v, ","));
  }
  human += "\n";
  for (const auto& d : j["directions"])
    human += fmt::format("along {}: range {:.3f} um (model {:.3f}), RMS {:.3f} um, largest {:.3f} um at {} (U {:.3f} um)\n",
                         d["direction"].get<std::string>(), d["range_um"].get<double>(), d["simulated_range_um"].get<double>(),
                         d["rms_um"].get<double>(), d["largest_um"].get<double>(), d["largest_feature"].get<std::string>(),
                         d["largest_expanded_uncertainty_um"].get<double>());
  const auto& u = j["uncertainty"];
  human += fmt::format("U (k = 2) up to {:.3f} um: certificate {:.3f} um{}, probing {:.3f} um{}; {} residual component(s) beyond "
                       "sqrt(U^2 + 2S_model^2)\n",
                       u["largest_um"].get<double>(), u["certificate_largest_um"].get<double>(), u["certificate_stated"] ? "" : " (not stated)",
                       u["probing_largest_um"].get<double>(), u["probe_stated"] ? "" : " (not stated)", e.beyond);
  emit(o, j, human, csv);
}

struct PlateIdentifyCliOptions : MachineOptions {
  OptionValues values;
  std::string errorsOut;
};

void runIdentify(const PlateIdentifyCliOptions& o) {
  const PlateIdentificationRequest request = plateIdentificationRequest(o.values);
  const auto s = identifyPlateFiles(loadMachineSetup(o.source), request.files, request.pieceLength);
  const auto j = toJson(s);
  if (!o.errorsOut.empty()) writeIdentifiedErrors(o.errorsOut, *s.machine, s.identified, identificationRecord(s), "--errors-out");
  std::string human = fmt::format("{} placements, {} readings; {} parameters (component functions of X, Y, Z in pieces of {:g} mm, "
                                  "squareness) + {} nuisance (translations, rotations); rank {} of {}\n",
                                  request.files.size(), s.result.readings, s.parameters.size(), request.pieceLength,
                                  s.result.names.size() - s.parameters.size(), s.result.observability.rank, s.result.names.size());
  human += s.weighted ? fmt::format("residual / the probes' stated noise: {:.3f}\n\n", s.result.sigma)
                      : fmt::format("residual standard deviation {:.3f} um (no probe 2S stated)\n\n", s.result.sigma * 1e3);
  std::string csv = "parameter,value,uncertainty,unit,determined\n";
  human += fmt::format("{:<14} {:>12} {:>12}  {}\n", "parameter", "value", "u", "unit");
  for (const auto& e : j["estimates"]) {
    const std::string name = e["name"], unit = e["unit"];
    const bool determined = e["determined"];
    const std::string u = determined ? fmt::format("{:.4f}", e["uncertainty"].get<double>()) : "";
    human += fmt::format("{:<14} {:>12.4f} {:>12}  {}{}\n", name, e["value"].get<double>(), determined ? u : "-", unit,
                         determined ? "" : "  (not determined)");
    csv += fmt::format("{},{},{},{},{}\n", name, e["value"].get<double>(), u, unit, determined ? 1 : 0);
  }
  if (!j["findings"].empty()) human += "\nWhat these plates cannot determine:\n";
  for (const auto& f : j["findings"]) human += "  " + f.get<std::string>() + "\n";
  emit(o, j, human, csv);
}

}  // namespace

void addPlateCommand(const CommandLine& app) {
  auto o = std::make_shared<PlateCliOptions>();
  auto cmd = app.subcommand("plate", "a measured hole or ball plate against the machine's error model (the 1991 BCR report)");
  cmd.machineOptions(*o);
  cmd.schemaOptions(plateComparisonSchema(), o->values);
  cmd.callback([o] { run(*o); });

  auto ao = std::make_shared<PlateCliOptions>();
  auto artefact = app.subcommand("artefact", "a calibrated artefact (step gauge, ball bar, plate, 3-D) against its certificate and the model");
  artefact.machineOptions(*ao);
  artefact.schemaOptions(artefactEvaluationSchema(), ao->values);
  artefact.callback([ao] { runArtefact(*ao); });

  auto io = std::make_shared<PlateIdentifyCliOptions>();
  auto identify = app.subcommand("plate-identify", "component errors and squareness from several measured plates or artefacts (the 1991 BCR report §7.7)");
  identify.machineOptions(*io);
  identify.schemaOptions(plateIdentificationSchema(), io->values);
  identify.option("--errors-out", io->errorsOut,
                       "write the identified functions as an errors file with the record of the data (as identify's), atomically");
  identify.callback([io] { runIdentify(*io); });
}

}  // namespace mtacc::cli
