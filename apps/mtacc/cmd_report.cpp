// mtacc report MACHINE: the HTML accuracy report, built by the Python package (matplotlib
// figures) on top of the same library: /usr/bin/python3 -m mtacc.report.
#include <algorithm>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "mtacc/workflows/report_paths.hpp"

namespace mtacc::cli {
namespace {

struct ReportOptions {
  std::string machine;
  OptionValues values;  // reportSchema()'s, passed on as the same flags
};

[[noreturn]] void run(const ReportOptions& o) {
  std::vector<std::string> args{o.machine};
  for (const auto& [key, given] : o.values)
    for (const auto& value : given) {
      std::string flag = "--" + key;
      std::replace(flag.begin(), flag.end(), '_', '-');
      args.push_back(flag);
      args.push_back(value);
    }
  runPythonModule("mtacc.report", args);
}

}  // namespace

void addReportCommand(const CommandLine& app) {
  auto o = std::make_shared<ReportOptions>();
  auto cmd = app.subcommand("report", "write the HTML accuracy report (self-contained, figures as SVG)");
  cmd.argument("machine", o->machine, "machine file, or the name of a bundled machine");
  cmd.schemaOptions(reportSchema(), o->values, {{"output", "-o"}});
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
