// mtacc multitasking DATA: the twelve location errors of a B-head / C-spindle multi-tasking
// machine from the eccentricities of six ball-bar runs (seed 002 §5).
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/multitasking_identification.hpp"

namespace mtacc::cli {
namespace {

struct MultitaskingCliOptions : MachineOptions {
  OptionValues values;
  std::string errorsOut;
};

void run(const MultitaskingCliOptions& o) {
  const auto r = identifyMultitasking(o.values, o.errorsOut);
  const auto j = toJson(r);
  std::string human = fmt::format("Location errors of a multi-tasking machine (B head, C spindle) from the six ball-bar runs of {}\n"
                                  "(Eqs 17-28 of Applied Sciences 10, 1811; names of its Table 1)\n\n",
                                  r.input.file);
  std::string csv = "name,value,unit,iso\n";
  for (const auto& [name, d] : j["deviations"].items()) {
    human += fmt::format("  {:<8} {:>10.3f} {:<7} = {}\n", name, d["value"].get<double>(), d["unit"].get<std::string>(), d["iso"].get<std::string>());
    csv += fmt::format("{},{},{},{}\n", name, d["value"].get<double>(), d["unit"].get<std::string>(), d["iso"].get<std::string>());
  }
  emit(o, j, human, csv);
}

}  // namespace

void addMultitaskingCommand(const CommandLine& app) {
  auto o = std::make_shared<MultitaskingCliOptions>();
  auto cmd = app.subcommand("multitasking", "twelve location errors of a B-head / C-spindle multi-tasking machine from six ball-bar runs' eccentricities (seed 002)");
  cmd.outputOptions(*o);
  cmd.schemaOptions(multitaskingSchema(), o->values);
  cmd.option("--errors-out", o->errorsOut, "Write the twelve deviations as an errors file (seed 002's names, which --errors reads) to FILE, atomically");
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
