// mtacc design: the measurement plan that determines the parameters (or the TCP) best in the machine
// time available, among the runs the instruments at hand can make; the plan file, its predicted
// uncertainties, its time, a Pareto table of time against uncertainty, the user's plan beside it.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/measurement_design.hpp"

namespace mtacc::cli {
namespace {

struct DesignCliOptions {
  MachineOptions machine;
  OptionValues values;
};

// The report is the Python package's: it designs again with the same options and writes the HTML.
[[noreturn]] void writeHtml(const DesignCliOptions& o, const std::string& html) {
  OptionValues options = o.values;
  options.erase("html");
  std::vector<std::string> args{o.machine.source.machine, "--options", nlohmann::json(options).dump(), "--html", html};
  if (!o.machine.source.errorsFile.empty()) args.insert(args.end(), {"--errors", o.machine.source.errorsFile});
  runPythonModule("mtacc.measurement_design", args);
}

void run(const DesignCliOptions& o) {
  const auto d = designMeasurement(loadMachineSetup(o.machine.source), measurementDesignRequest(o.values));
  if (const auto html = OptionReader(measurementDesignSchema(), o.values).text("html")) writeHtml(o, *html);  // bad input was reported above
  const auto j = toJson(d);
  const auto& design = j["design"];
  std::string human = fmt::format("Measurement design for {}: {}-optimal among {} candidate runs, {:.1f} min of the {:g} min available "
                                  "({} runs, {} exchanges)\n",
                                  d.machine->name, j["criterion"].get<std::string>(), d.candidates, design["time_min"].get<double>(),
                                  d.budget, d.chosen.size(), d.design.exchanges);
  for (const auto& r : j["runs"])
    human += fmt::format("  {:<28} {:5.1f} min  {}\n", r["name"].get<std::string>(), r["time_min"].get<double>(), r["description"].get<std::string>());
  human += "\nPredicted uncertainties (k = 2):\n";
  const auto own = j.contains("own_plan") && j["own_plan"].contains("parameters") ? &j["own_plan"] : nullptr;
  human += fmt::format("  {:<12} {:>12}{}\n", "parameter", "design", own ? fmt::format(" {:>12}", "your plan") : "");
  for (size_t k = 0; k < design["parameters"].size(); ++k) {
    const auto& p = design["parameters"][k];
    human += fmt::format("  {:<12} {:>7.3g} {:<4}{}\n", p["name"].get<std::string>(), p["u_k2"].get<double>(), p["unit"].get<std::string>(),
                         own ? fmt::format(" {:>7.3g} {:<4}", (*own)["parameters"][k]["u_k2"].get<double>(), p["unit"].get<std::string>()) : "");
  }
  human += fmt::format("  {:<12} {:>7.3g} um  {}\n", "TCP (rms)", design["tcp_rms_k2_um"].get<double>(),
                       own ? fmt::format("{:>7.3g} um", (*own)["tcp_rms_k2_um"].get<double>()) : "");
  human += fmt::format("  {:<12} {:>7.3g} um  {}\n", "TCP (max)", design["tcp_max_k2_um"].get<double>(),
                       own ? fmt::format("{:>7.3g} um", (*own)["tcp_max_k2_um"].get<double>()) : "");
  human += fmt::format("  {:<12} {:>7.1f} min {}\n", "time", design["time_min"].get<double>(),
                       own ? fmt::format("{:>7.1f} min", (*own)["time_min"].get<double>()) : "");
  if (j.contains("own_plan") && j["own_plan"].contains("refused")) human += "  your plan: " + j["own_plan"]["refused"].get<std::string>() + "\n";
  human += fmt::format("\nTime against uncertainty (k = 2; TCP over {} poses of the working volume):\n  {:>8} {:>8} {:>5} {:>10} {:>10} {:>12} {:>12}\n",
                       d.volumePoses, "budget", "min", "runs", "TCP rms um", "TCP max um", "worst um", "worst urad");
  std::string csv = "budget_min,time_min,runs,criterion_value,tcp_rms_k2_um,tcp_max_k2_um,worst_length_k2_um,worst_angle_k2_urad\n";
  for (const auto& p : j["pareto"]) {
    if (p.contains("refused")) {
      human += fmt::format("  {:>8.1f} too short: {}\n", p["budget_min"].get<double>(), p["refused"].get<std::string>());
      continue;
    }
    human += fmt::format("  {:>8.1f} {:>8.1f} {:>5} {:>10.3g} {:>10.3g} {:>12.3g} {:>12.3g}\n", p["budget_min"].get<double>(),
                         p["time_min"].get<double>(), p["runs"].get<size_t>(), p["tcp_rms_k2_um"].get<double>(), p["tcp_max_k2_um"].get<double>(),
                         p["worst_length_k2_um"].get<double>(), p["worst_angle_k2_urad"].get<double>());
    csv += fmt::format("{},{},{},{},{},{},{},{}\n", p["budget_min"].get<double>(), p["time_min"].get<double>(), p["runs"].get<size_t>(),
                       p["criterion_value"].get<double>(), p["tcp_rms_k2_um"].get<double>(), p["tcp_max_k2_um"].get<double>(),
                       p["worst_length_k2_um"].get<double>(), p["worst_angle_k2_urad"].get<double>());
  }
  for (const auto& note : d.notes) human += "note: " + note + "\n";
  for (const auto& file : d.written) human += "written: " + file + "\n";
  emit(o.machine, j, human, csv);
}

}  // namespace

void addDesignCommand(const CommandLine& app) {
  auto o = std::make_shared<DesignCliOptions>();
  auto cmd = app.subcommand("design", "design the measurement: the runs that determine the parameters (or the TCP) best in the machine time "
                                      "available, written as a plan");
  cmd.machineOptions(o->machine);
  cmd.schemaOptions(measurementDesignSchema(), o->values, {{"parameters", "--params"}});
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
