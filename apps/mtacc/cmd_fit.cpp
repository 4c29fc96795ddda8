// mtacc fit: a component error from its direct-measurement runs (the 1991 BCR report): corrections, the
// mean of the runs, the C1 piecewise-polynomial fit with stepwise removal, and its YAML entry.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/identified_errors.hpp"

namespace mtacc::cli {
namespace {

struct FitCliOptions : MachineOptions {
  OptionValues values;
  std::string errorsOut;
};

void run(const FitCliOptions& o) {
  const ComponentFitRequest request = componentFitRequest(o.values);
  const auto s = fitComponentFile(loadMachineSetup(o.source), request);
  const auto j = toJson(s);
  if (!o.errorsOut.empty()) writeIdentifiedErrors(o.errorsOut, *s.machine, s.errors, identificationRecord(s), "--errors-out");
  const std::string unit = j["unit"], posUnit = j["position_unit"];
  const auto& f = j["fit"];
  std::string human = fmt::format("Component {} ({}) of axis {} from {}: {} positions, {} runs each way\n", s.data.componentName,
                                  j["iso_name"].get<std::string>(), j["axis"].get<std::string>(), s.data.file, s.curve.positions.size(),
                                  s.data.runs.forward.cols());
  for (const auto& c : s.corrections) human += "  corrected: " + c + "\n";
  human += fmt::format("\nFit: degree {}, breaks", request.degree);
  for (const double b : f["breaks"]) human += fmt::format(" {:g}", b);
  human += fmt::format(" {}; {} terms kept", posUnit, s.fit.trend.coefficients.size());
  if (!s.fit.removed.empty()) human += ", removed as not significant: " + fmt::format("{}", fmt::join(s.fit.removed, " "));
  if (s.fit.periodic) human += fmt::format("; periodic term of {:g} {}", f["periodic"].get<double>(), posUnit);
  human += fmt::format("\nresidual standard deviation {:.4g} {} ({} degrees of freedom)\n\n", f["residual_std"].get<double>(), unit,
                       s.fit.degreesOfFreedom);
  human += fmt::format("{:>10} {:>10} {:>10} {:>10} {:>10} {:>10}   ({} / {})\n", "position", "mean", "forward", "backward", "fit", "u(fit)",
                       posUnit, unit);
  std::string csv = fmt::format("position_{0},mean_{1},mean_forward_{1},mean_backward_{1},fit_{1},fit_uncertainty_{1}\n", posUnit, unit);
  for (size_t i = 0; i < s.curve.positions.size(); ++i) {
    const std::vector<double> row{j["positions"][i], j["mean"][i], j["mean_forward"][i], j["mean_backward"][i], f["at_positions"][i],
                                  f["uncertainty_at_positions"][i]};
    human += fmt::format("{:>10.3f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f}\n", row[0], row[1], row[2], row[3], row[4], row[5]);
    csv += fmt::format("{}\n", fmt::join(row, ","));
  }
  if (!s.disturbances.readings.empty()) {
    human += fmt::format("\n{} disturbed reading(s) (beyond {:g} robust standard deviations of their position)", s.disturbances.readings.size(),
                         request.disturbanceThreshold);
    if (s.disturbances.interval) human += fmt::format(", recurring every {:.1f} min", *s.disturbances.interval / 60.0);
    human += "\n";
  }
  if (!s.disturbances.unsettledRuns.empty())
    human += fmt::format("\nRuns 1 to {} have not settled: their mean lies beyond {:g} robust standard deviations of the run means{}\n",
                         s.disturbances.unsettledRuns.size(), request.disturbanceThreshold,
                         request.removeDisturbed ? " (left out)" : " (--remove-disturbed leaves them out)");
  human += '\n';
  human += o.errorsOut.empty() ? "Error function (machine YAML, under errors:):\n" + s.yaml
                               : "The machine's errors with the fitted function written to " + o.errorsOut + "\n";
  emit(o, j, human, csv);
}

}  // namespace

void addFitCommand(const CommandLine& app) {
  auto o = std::make_shared<FitCliOptions>();
  auto cmd = app.subcommand("fit", "fit a component error to its direct-measurement runs (the 1991 BCR report: C1 piecewise polynomial)");
  cmd.machineOptions(*o);
  cmd.schemaOptions(componentFitSchema(), o->values);
  cmd.option("--errors-out", o->errorsOut,
                  "write the machine's errors with the fitted function in place, its coefficients' covariance and the data's hash "
                  "(an errors file that --errors reads), atomically");
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
