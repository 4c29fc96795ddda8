// mtacc report MACHINE: the HTML accuracy report, built by the Python package (matplotlib
// figures) on top of the same library. Runs /usr/bin/python3 -m mtacc.report.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
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
  const std::string pythonDir = MTACC_PYTHON_DIR;
  const char* old = std::getenv("PYTHONPATH");
  std::string path = pythonDir;
  if (old && *old) path.append(":").append(old);
  ::setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args{"/usr/bin/python3", "-m", "mtacc.report", o.machine};
  for (const auto& [key, given] : o.values)
    for (const auto& value : given) {
      std::string flag = "--" + key;
      std::replace(flag.begin(), flag.end(), '_', '-');
      args.push_back(flag);
      args.push_back(value);
    }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw std::runtime_error("cannot start /usr/bin/python3 for the report");
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
