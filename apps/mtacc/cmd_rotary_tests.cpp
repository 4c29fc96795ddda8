// mtacc rotary-tests: the ISO 10791-6 tests around each rotary axis — set-ups, plan, programs, the
// results on the machine with its errors, and which location errors each result sees.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/rotary_axis_tests.hpp"

namespace mtacc::cli {
namespace {

struct RotaryTestsCliOptions {
  MachineOptions machine;
  OptionValues values;
};

void run(const RotaryTestsCliOptions& o) {
  const auto r = rotaryTestsFor(loadMachineSetup(o.machine.source), rotaryTestsRequest(o.values));
  const auto j = toJson(r);
  std::string human = fmt::format("ISO 10791-6 tests around the rotary axes of {}: each result on the machine with its errors (um), and the "
                                  "location errors it sees, each alone (um of range per um or urad)\n",
                                  r.machine);
  std::string csv = "test,quantity,range_um,sees\n";
  for (const auto& t : j["tests"]) {
    const auto& s = t["set_up"];
    const auto sphere = s["sphere_mm"].get<std::vector<double>>();
    human += fmt::format("\n{}: {}\n  {} {:.3f}..{:.3f} deg, {} at [{:.3f}, {:.3f}, {:.3f}] mm (workpiece frame)\n", t["name"].get<std::string>(),
                         t["description"].get<std::string>(), t["axis"].get<std::string>(), t["from_deg"].get<double>(),
                         t["to_deg"].get<double>(), s["instrument"] == "ballbar" ? "work ball" : "sphere", sphere[0], sphere[1], sphere[2]);
    for (const auto& [quantity, result] : t["results"].items()) {
      std::string sees;
      for (const auto& e : result["sees"])
        sees += fmt::format("{}{} {:.3g}", sees.empty() ? "" : ", ", e["parameter"].get<std::string>(), e["range_per_unit"].get<double>());
      human += fmt::format("  {:<10} {:9.3f} um   sees: {}\n", quantity, result["range_um"].get<double>(), sees.empty() ? "nothing" : sees);
      csv += fmt::format("{},{},{},\"{}\"\n", t["name"].get<std::string>(), quantity, result["range_um"].get<double>(), sees);
    }
  }
  for (const auto& note : r.set.notes) human += "\nnote: " + note;
  if (!r.set.notes.empty()) human += "\n";
  for (const auto& file : r.written) human += "\nwritten: " + file;
  if (!r.written.empty()) human += "\n";
  emit(o.machine, j, human, csv);
}

}  // namespace

void addRotaryTestsCommand(const CommandLine& app) {
  auto o = std::make_shared<RotaryTestsCliOptions>();
  auto cmd = app.subcommand("rotary-tests", "ISO 10791-6 tests around each rotary axis (R-test at two set-ups, ballbar radial, tangential, "
                                            "axial): plan, programs, results on the machine and what each result sees");
  cmd.alias("iso10791-6");
  cmd.machineOptions(o->machine);
  cmd.schemaOptions(rotaryTestsSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
