// mtacc stiffness MACHINE: the finite-stiffness changes of the errors at the workpiece load, and
// the TCP errors they cause over the working volume beside those of the geometric errors.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/stiffness.hpp"

namespace mtacc::cli {
namespace {

struct StiffnessOptions {
  MachineOptions machine;
  OptionValues values;
};

std::string poseText(const nlohmann::json& pose) {
  std::string s;
  for (const auto& [axis, value] : pose.items()) s += fmt::format("{}{}={:g}", s.empty() ? "" : " ", axis, value.get<double>());
  return s;
}

void run(const StiffnessOptions& o) {
  const auto summary = summariseStiffness(loadMachineSetup(o.machine.source), stiffnessSamples(o.values));
  const auto j = toJson(summary);
  std::string human = fmt::format("Finite stiffness of {}: workpiece load {:g} kg\n", summary.setup.machine->name,
                                  j["workpiece_load_kg"].get<double>());
  std::string csv = "error,axis,with,position,with_position,value,unit\n";
  for (const auto& t : j["terms"]) {
    const bool with = !t["with"].is_null();
    const std::string along = t["axis"].get<std::string>() + (with ? " and " + t["with"].get<std::string>() : "");
    const std::string load = t["reference_load_kg"].is_null()
                                 ? "independent of the load"
                                 : fmt::format("measured under {:g} kg, scaled x{:.3g}", t["reference_load_kg"].get<double>(),
                                               t["load_factor"].get<double>());
    for (size_t i = 0; i < t["positions"].size(); ++i)
      for (size_t k = 0; k < t["values"][i].size(); ++k) {
        const double v = t["values"][i][k];
        csv += fmt::format("{},{},{},{},{},{},{}\n", t["error"].get<std::string>(), t["axis"].get<std::string>(),
                           with ? t["with"].get<std::string>() : "", t["positions"][i].get<double>(),
                           with ? fmt::format("{}", t["with_positions"][k].get<double>()) : "", v, t["unit"].get<std::string>());
      }
    human += fmt::format("  {:<5} along {:<8} {:<40} largest {:.3f} {}\n", t["error"].get<std::string>(), along, load, t["largest"].get<double>(),
                         t["unit"].get<std::string>());
  }
  human += fmt::format("Largest TCP position error over {} poses ({} per axis):\n", summary.poses, summary.samplesPerAxis);
  for (const auto& [key, label] : {std::pair{"geometric", "geometric errors alone"}, std::pair{"stiffness_alone", "stiffness changes alone"},
                                   std::pair{"added_by_stiffness", "added by the stiffness changes"}}) {
    const auto& e = j["largest_tcp_error"][key];
    human += fmt::format("  {:<32} {:8.3f} um at {}\n", label, e["position_error_um"].get<double>(), poseText(e["pose"]));
  }
  emit(o.machine, j, human, csv);
}

}  // namespace

void addStiffnessCommand(const CommandLine& app) {
  auto o = std::make_shared<StiffnessOptions>();
  auto cmd = app.subcommand("stiffness",
                                 "finite-stiffness changes of the errors (the 1991 BCR report) at the workpiece load, and the TCP errors they cause");
  cmd.machineOptions(o->machine);
  cmd.schemaOptions(stiffnessSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
