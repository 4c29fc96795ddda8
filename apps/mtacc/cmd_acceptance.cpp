// mtacc acceptance MACHINE --tests FILE: every test of an acceptance tests file with its result,
// uncertainty, tolerance and verdict; --html writes the report (the Python package builds it).
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/acceptance.hpp"

namespace mtacc::cli {
namespace {

struct AcceptanceCliOptions {
  MachineOptions machine;
  OptionValues values;
};

[[noreturn]] void writeHtml(const AcceptanceCliOptions& o, const std::string& tests, const std::string& html) {
  std::vector<std::string> args{o.machine.source.machine, "--tests", tests, "--html", html};
  if (!o.machine.source.errorsFile.empty()) args.insert(args.end(), {"--errors", o.machine.source.errorsFile});
  runPythonModule("mtacc.acceptance", args);
}

void run(const AcceptanceCliOptions& o) {
  const OptionReader reader(acceptanceSchema(), o.values);
  const std::string tests = *reader.text("tests");
  if (const auto html = reader.text("html")) {
    runAcceptance(loadMachineSetup(o.machine.source), tests);  // bad input is reported here, in one line, before Python starts
    writeHtml(o, tests, *html);
  }
  const auto r = runAcceptance(loadMachineSetup(o.machine.source), tests);
  const auto j = toJson(r);
  std::string human = fmt::format("{}: {} ({})\n\n{:<34} {:<12} {:<14} {:>12} {:>10} {:>12}  {}\n", r.title, r.machine, r.file, "test",
                                  "standard", "quantity", "result", "U (k = 2)", "tolerance", "verdict");
  std::string csv = "test,standard,quantity,value,U,tolerance,unit,verdict\n";
  for (const auto& s : j["summary"]) {
    const auto unit = s["unit"].get<std::string>();
    human += fmt::format("{:<34} {:<12} {:<14} {:>9.3f} {:<2} {:>10.3f} {:>12.3f}  {}\n", s["test"].get<std::string>(),
                         s["standard"].get<std::string>(), s["quantity"].get<std::string>(), s["value"].get<double>(), unit == "um" ? "um" : "\"",
                         s["U"].get<double>(), s["tolerance"].get<double>(), s["verdict"].get<std::string>());
    csv += fmt::format("\"{}\",{},{},{},{},{},{},{}\n", s["test"].get<std::string>(), s["standard"].get<std::string>(),
                       s["quantity"].get<std::string>(), s["value"].get<double>(), s["U"].get<double>(), s["tolerance"].get<double>(), unit,
                       s["verdict"].get<std::string>());
  }
  human += fmt::format("\noverall: {}\n", j["overall"].get<std::string>());
  for (const auto& t : r.tests) {
    human += fmt::format("\n{} ({}, {}): {}\n", t.spec.name, t.standard, t.instrument, describe(t.conformance.rule));
    for (const auto& k : t.uncertainty.contributors)
      human += fmt::format("  {:<15} {:8.4f} {}  {}{}\n", k.symbol, k.standard * t.scale, t.unit, k.source, k.defaulted ? " (default)" : "");
  }
  emit(o.machine, j, human, csv);
}

}  // namespace

void addAcceptanceCommand(const CommandLine& app) {
  auto o = std::make_shared<AcceptanceCliOptions>();
  auto cmd = app.subcommand("acceptance", "acceptance by the standards: each test of a tests file with its result, ISO/TR 230-9 "
                                          "uncertainty, tolerance and ISO 14253-1 verdict (--html: the report)");
  cmd.machineOptions(o->machine);
  cmd.schemaOptions(acceptanceSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
