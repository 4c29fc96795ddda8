// mtacc report MACHINE: the HTML accuracy report, built by the Python package (matplotlib
// figures) on top of the same library. Runs /usr/bin/python3 -m mtacc.report.
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "cli_common.hpp"

namespace mtacc::cli {
namespace {

struct ReportOptions {
  std::string machine;
  std::string errorsFile;
  std::string output = ".";
  std::string plan, structure, compare, load, decomposition, thermal;
  std::vector<std::string> positioning, components, plates, drift, data;
  int samples = 5;
};

[[noreturn]] void run(const ReportOptions& o) {
  const std::string pythonDir = MTACC_PYTHON_DIR;
  const char* old = std::getenv("PYTHONPATH");
  const std::string path = pythonDir + (old && *old ? ":" + std::string(old) : "");
  ::setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args{"/usr/bin/python3", "-m", "mtacc.report", o.machine, "-o", o.output,
                                "--samples", std::to_string(o.samples)};
  if (!o.errorsFile.empty()) {
    args.push_back("--errors");
    args.push_back(o.errorsFile);
  }
  for (const auto& [flag, value] :
       {std::pair{"--plan", o.plan}, {"--structure", o.structure}, {"--compare", o.compare}, {"--load", o.load},
        {"--decomposition", o.decomposition}, {"--thermal", o.thermal}})
    if (!value.empty()) {
      args.push_back(flag);
      args.push_back(value);
    }
  for (const auto& [flag, files] : {std::pair{"--positioning", &o.positioning}, {"--component", &o.components}, {"--plate", &o.plates}, {"--drift", &o.drift},
        {"--data", &o.data}})
    for (const auto& file : *files) {
      args.push_back(flag);
      args.push_back(file);
    }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw std::runtime_error("cannot start /usr/bin/python3 for the report");
}

}  // namespace

void addReportCommand(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand("report", "write the HTML accuracy report (self-contained, figures as SVG)");
  cmd->add_option("machine", o->machine, "machine file, or the name of a bundled machine")->required();
  cmd->add_option("-o,--output", o->output, "output directory (default: current)");
  cmd->add_option("--errors", o->errorsFile, "errors file (default: the machine file's)");
  cmd->add_option("--load", o->load, "workpiece load in kg for the errors' stiffness changes (default: the errors' workpiece_load)")
      ->check(loadInKg());
  cmd->add_option("--samples", o->samples, "positions per axis for the error budget (default 5)");
  cmd->add_option("--plan", o->plan, "test plan to simulate, evaluate and identify from (e.g. tilting-table-rtest)");
  cmd->add_option("--data", o->data, "the plan's measured files (CSV) to identify from, instead of simulating the plan");
  cmd->add_option("--structure", o->structure, "structure model for the dynamics section (e.g. tzyx-arm-x)");
  cmd->add_option("--compare", o->compare, "a second structure model to compare with (e.g. tzyx-arm-y)");
  cmd->add_option("--positioning", o->positioning, "ISO 230-2 positioning-test files for the positioning section");
  cmd->add_option("--plate", o->plates, "plate measurements (the 1991 BCR report) to compare with the model, one section each");
  cmd->add_option("--component", o->components, "direct-measurement runs (the 1991 BCR report) to fit and plot, one section each");
  cmd->add_option("--drift", o->drift, "thermal drift tests (ISO 230-3, the 1991 BCR report) to evaluate and plot, one section each");
  cmd->add_option("--thermal", o->thermal, "thermal state (YAML: the temperatures along the scales): the whole report is the warm machine's");
  cmd->add_option("--decomposition", o->decomposition, "a decomposition set (Andolfatto et al. 2011 recorded signals) for the error-decomposition section");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
