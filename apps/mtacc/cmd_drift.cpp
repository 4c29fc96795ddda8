// mtacc drift: a thermal drift test (ISO 230-3, the 1991 BCR report §2.6) from its probe, position and
// temperature readings: the drift per direction, its warm-up / cool-down hysteresis, and the
// temperatures that predict it (stepwise regression, linear in an axis's position where it moves).
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/thermal_drift.hpp"

namespace mtacc::cli {
namespace {

struct DriftCliOptions : MachineOptions {
  OptionValues values;
};

void run(const DriftCliOptions& o) {
  const DriftTestRequest request = driftTestRequest(o.values);
  const auto r = evaluateDriftTest(request);
  const auto j = toJson(r);
  const bool positional = j.contains("position_axis");
  const std::string axis = positional ? j["position_axis"].get<std::string>() : "";
  std::string human = fmt::format("{}: {}, {} samples over {:.2f} h, {} temperature sensors\n\n", r.test.file, j["test"].get<std::string>(),
                                  r.test.time.size(), j["duration_s"].get<double>() / 3600, r.test.sensors.size());
  human += fmt::format("{:>3} {:>12} {:>8} {:>10} | {:>24} | {}\n", "", "largest", "at h", "range", "hysteresis (cool - warm)",
                       "model: sensors (coefficient per K), cross-validated RMS");
  std::string csv = "direction,unit,largest,largest_at_s,range,hysteresis,hysteresis_at_C,sensors,cross_validated_rms,best_single_sensor_rms\n";
  for (const auto& d : j["directions"]) {
    const auto unit = d["unit"].get<std::string>();
    std::string hysteresis = "-", model = "-", sensors;
    if (d.contains("hysteresis"))
      hysteresis = fmt::format("{:.2f} {} at {:.1f} C", d["hysteresis"]["difference"].get<double>(), unit, d["hysteresis"]["at_C"].get<double>());
    if (d.contains("model")) {
      const auto& m = d["model"];
      for (const auto& s : m["sensors"]) {
        const std::string gradient = positional ? fmt::format(" {:+.4g} +- {:.2g} per mm {}", s["coefficient_per_K_per_mm"].get<double>(),
                                                              s["standard_error_per_K_per_mm"].get<double>(), axis)
                                                : "";
        sensors += fmt::format("{}{} ({:.4g} +- {:.2g}{})", sensors.empty() ? "" : ", ", s["sensor"].get<std::string>(),
                               s["coefficient_per_K"].get<double>(), s["standard_error_per_K"].get<double>(), gradient);
      }
      model = fmt::format("{}: {:.3f} {} (one sensor, {}: {:.3f})", sensors.empty() ? "offset only" : sensors, m["cross_validated_rms"].get<double>(),
                          unit, m["best_single_sensor"].get<std::string>(), m["best_single_sensor_rms"].get<double>());
    }
    human += fmt::format("{:>3} {:>8.3f} {:<4} {:>7.2f} {:>8.3f} {:<4}| {:>24} | {}\n", d["direction"].get<std::string>(), d["largest"].get<double>(),
                         unit, d["largest_at_s"].get<double>() / 3600, d["range"].get<double>(), unit, hysteresis, model);
    csv += fmt::format("{},{},{},{},{},{},{},\"{}\",{},{}\n", d["direction"].get<std::string>(), unit, d["largest"].get<double>(),
                       d["largest_at_s"].get<double>(), d["range"].get<double>(),
                       d.contains("hysteresis") ? fmt::format("{}", d["hysteresis"]["difference"].get<double>()) : "",
                       d.contains("hysteresis") ? fmt::format("{}", d["hysteresis"]["at_C"].get<double>()) : "", sensors,
                       d.contains("model") ? fmt::format("{}", d["model"]["cross_validated_rms"].get<double>()) : "",
                       d.contains("model") ? fmt::format("{}", d["model"]["best_single_sensor_rms"].get<double>()) : "");
  }
  if (r.kind == DriftTestKind::EnvironmentalVariation)
    human += "\nETVE: the range of each direction's drift over the test, the machine at rest\n";
  for (const auto& d : j["directions"])
    if (d.contains("hysteresis")) {
      human += fmt::format("\nhysteresis: the drift on cooling minus on warming at the same temperature of {}, in {} equal bins of the range "
                           "both cover\n",
                           j["hysteresis_sensor"].get<std::string>(), d["hysteresis"]["bins"].get<int>());
      break;
    }
  human += fmt::format("model: drift = offset + sum of coefficient x (T - T at the start) over the chosen sensors{}, chosen stepwise by "
                       "{}-fold\ncross-validated RMS in contiguous blocks; a model needing more than one sensor means one sensor cannot "
                       "explain the drift\n",
                       positional ? fmt::format(", each coefficient linear in {} (per mm of its position)", axis) : "", request.selection.folds);
  emit(o, j, human, csv);
}

}  // namespace

void addDriftCommand(const CommandLine& app) {
  auto o = std::make_shared<DriftCliOptions>();
  auto cmd = app.subcommand("drift", "thermal drift test (ISO 230-3, the 1991 BCR report: spindle, axis or the machine at rest): drift per "
                                          "direction, hysteresis, the temperatures that predict it");
  cmd.schemaOptions(driftTestSchema(), o->values);
  cmd.outputOptions(*o);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
