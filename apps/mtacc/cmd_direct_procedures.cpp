// mtacc squareness | yry: seed 003's App. B procedures that turn direct-measurement readings into
// an error: squareness from a calibrated square, yry from two straightness runs.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/direct_procedures.hpp"

namespace mtacc::cli {
namespace {

struct ProcedureCliOptions : MachineOptions {
  OptionValues values;
};

void runSquareness(const ProcedureCliOptions& o) {
  const auto r = squarenessFromOptions(o.values);
  const auto j = toJson(r);
  const std::string human = fmt::format(
      "Squareness from a calibrated square aligned to {} (1991 BCR report App. B.5): {} = {:.2f} arcsec\n"
      "  alpha {:.2f}, beta {:.2f}, square's own {:.2f} arcsec\n",
      r.alignedTo == 'x' ? "X" : "Z", j["rule"].get<std::string>(), j["squareness_arcsec"].get<double>(), j["alpha_arcsec"].get<double>(),
      j["beta_arcsec"].get<double>(), j["block_arcsec"].get<double>());
  const std::string csv = fmt::format("aligned_to,alpha_arcsec,beta_arcsec,block_arcsec,squareness_arcsec\n{},{},{},{},{}\n", r.alignedTo,
                                      j["alpha_arcsec"].get<double>(), j["beta_arcsec"].get<double>(), j["block_arcsec"].get<double>(),
                                      j["squareness_arcsec"].get<double>());
  emit(o, j, human, csv);
}

void runYry(const ProcedureCliOptions& o) {
  const auto r = yryFromOptions(o.values);
  std::string human = fmt::format("yry from two straightness runs at X = {:g} and {:g} mm (1991 BCR report eq. B.2)\n{:>10} {:>12}\n", r.x1,
                                  r.x2, "Y mm", "yry arcsec");
  std::string csv = "y_mm,yry_arcsec\n";
  const auto j = toJson(r);
  for (size_t i = 0; i < r.y.size(); ++i) {
    human += fmt::format("{:>10.3f} {:>12.3f}\n", r.y[i], j["yry_arcsec"][i].get<double>());
    csv += fmt::format("{},{}\n", r.y[i], j["yry_arcsec"][i].get<double>());
  }
  emit(o, j, human, csv);
}

}  // namespace

void addDirectProcedureCommands(const CommandLine& app) {
  auto square = std::make_shared<ProcedureCliOptions>();
  auto cmd = app.subcommand("squareness", "squareness of two axes from a calibrated square probed along both sides (seed 003 App. B.5)");
  cmd.outputOptions(*square);
  cmd.schemaOptions(squarenessSchema(), square->values);
  cmd.callback([square] { runSquareness(*square); });
  auto yaw = std::make_shared<ProcedureCliOptions>();
  auto yry = app.subcommand("yry", "yaw of the Y axis from two straightness runs at two X positions (seed 003 eq. B.2)");
  yry.outputOptions(*yaw);
  yry.schemaOptions(yrySchema(), yaw->values);
  yry.callback([yaw] { runYry(*yaw); });
}

}  // namespace mtacc::cli
