// mtacc identify / observability: which error parameters a test plan (or a set of measured
// files) determines, and their least-squares estimates with standard uncertainties.
#include <fmt/format.h>

#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/measurement/identification.hpp"
#include "mtacc/measurement/measurement_csv.hpp"
#include "mtacc/measurement/test_plan.hpp"

namespace mtacc::cli {
namespace {

struct IdentifyOptions : MachineOptions {
  std::vector<std::string> data;
  std::string plan;
  std::string params;
  std::string setup;  // overrides every run's estimate list
  bool robust = false;
  std::string robustScale = "2 um";
  int threads = 0;
};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Setup {
  IdentificationProblem problem;
  std::vector<std::string> given;  // the names as the user wrote them
};

Setup buildProblem(const IdentifyOptions& o, bool needReadings) {
  const auto loaded = load(o);
  const auto nominal = compileNominal(loaded.machine);
  Setup s;
  s.problem.machine = loaded.machine;
  s.problem.start = loaded.errors;
  std::vector<std::string> names = splitList(o.params);
  if (!o.plan.empty()) {
    auto plan = loadTestPlan(nominal, o.plan);
    if (names.empty()) names = plan.parameters;
    if (!needReadings) s.problem.runs = std::move(plan.runs);
  }
  for (const auto& file : o.data) s.problem.runs.push_back(readMeasurementCsv(nominal, file));
  if (s.problem.runs.empty())
    throw InputError(InputLocation{"", 0, needReadings ? "--data" : "--plan"}, "no measurement run given");
  if (names.empty()) throw InputError(InputLocation{"", 0, "--params"}, "no parameter to determine (give --params or a plan with 'parameters')");
  for (const auto& n : names) {
    try {
      s.problem.parameters.push_back(findParameter(*loaded.machine, loaded.errors, n));
      s.given.push_back(n);
    } catch (const std::invalid_argument& e) {
      throw InputError(InputLocation{"", 0, "--params"}, e.what());
    }
  }
  if (!o.setup.empty()) {
    for (auto& run : s.problem.runs) run.estimate.clear();
    for (const auto& n : splitList(o.setup)) {
      const auto p = parseSetupParameter(n);
      if (!p) throw InputError(InputLocation{"", 0, "--setup"}, "unknown set-up parameter '" + n + "' (xT yT zT xW yW zW aN bN cN dL)");
      for (auto& run : s.problem.runs)
        if (appliesTo(*p, run.instrument)) run.estimate.push_back(*p);
    }
  }
  return s;
}

std::string unitFor(Dimension d) { return d == Dimension::Length ? "um" : "urad"; }
double display(double v, Dimension d) { return d == Dimension::Length ? v * 1e3 : v * 1e6; }

nlohmann::json reportJson(const ObservabilityReport& r) {
  nlohmann::json j;
  j["rank"] = r.rank;
  j["parameters"] = r.names.size();
  j["condition"] = r.condition;
  j["identifiable"] = r.identifiable();
  j["singular_values"] = std::vector<double>(r.singularValues.data(), r.singularValues.data() + r.singularValues.size());
  j["no_effect"] = r.noEffect;
  j["findings"] = r.findings();
  for (const auto& g : r.groups) j["groups"].push_back({{"parameters", g.names}, {"observable", g.observable}});
  return j;
}

std::string reportText(const ObservabilityReport& r, Eigen::Index readings) {
  std::string s = fmt::format("{} readings, {} unknowns: rank {}, condition number {:.3g} (columns scaled to unit norm)\n",
                              readings, r.names.size(), r.rank, r.condition);
  s += "singular values:";
  for (Eigen::Index i = 0; i < r.singularValues.size(); ++i) s += fmt::format(" {:.3g}", r.singularValues[i]);
  s += "\n";
  if (r.identifiable()) s += "every parameter is determined by the plan\n";
  for (const auto& f : r.findings()) s += "  - " + f + "\n";
  return s;
}

Eigen::Index countReadings(const IdentificationProblem& p) {
  Eigen::Index n = 0;
  for (const auto& r : p.runs) n += r.poses() * readingSize(r.instrument);
  return n;
}

void observability(const IdentifyOptions& o) {
  const auto s = buildProblem(o, false);
  const auto report = planObservability(s.problem, o.threads);
  auto j = reportJson(report);
  j["machine"] = s.problem.machine->name;
  j["runs"] = s.problem.runs.size();
  j["readings"] = countReadings(s.problem);
  std::string csv = "index,singular_value\n";
  for (Eigen::Index i = 0; i < report.singularValues.size(); ++i) csv += fmt::format("{},{}\n", i + 1, report.singularValues[i]);
  emit(o, j, fmt::format("Observability on {} ({} runs)\n", s.problem.machine->name, s.problem.runs.size()) +
                 reportText(report, countReadings(s.problem)),
       csv);
}

void identifyCommand(const IdentifyOptions& o) {
  const auto s = buildProblem(o, true);
  IdentificationOptions options;
  options.robust = o.robust;
  options.robustScale = parseQuantityArg(o.robustScale, Dimension::Length, "--robust-scale");
  options.threads = o.threads;
  IdentificationResult r;
  try {
    r = identify(s.problem, options);
  } catch (const NotIdentifiable& e) {
    throw InputError(InputLocation{"", 0, "--params"}, std::string("refused: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(InputLocation{"", 0, "--data"}, e.what());
  }
  nlohmann::json j;
  j["machine"] = s.problem.machine->name;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["readings"] = r.readings;
  j["degrees_of_freedom"] = r.degreesOfFreedom;
  j["sigma_um"] = r.sigma * 1e3;
  j["residual_rms_um"] = r.residualRms * 1e3;
  j["residual_max_um"] = r.residualMax * 1e3;
  j["robust"] = o.robust;
  j["observability"] = reportJson(r.observability);
  std::string human = fmt::format("Identification on {} from {} runs ({} readings, {} unknowns)\n", s.problem.machine->name,
                                  s.problem.runs.size(), r.readings, r.values.size());
  human += fmt::format("{:<22} {:>14} {:>14}  unit\n", "parameter", "value", "std. uncert.");
  std::string csv = "parameter,value,standard_uncertainty,unit\n";
  for (Eigen::Index k = 0; k < r.values.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    std::string name = r.columns.names[static_cast<size_t>(k)];
    if (static_cast<size_t>(k) < s.given.size() && s.given[static_cast<size_t>(k)] != name)
      name += " (" + s.given[static_cast<size_t>(k)] + ")";
    human += fmt::format("{:<22} {:>14.4f} {:>14.4f}  {}\n", name, display(r.values[k], d), display(r.uncertainty[k], d), unitFor(d));
    csv += fmt::format("{},{},{},{}\n", r.columns.names[static_cast<size_t>(k)], display(r.values[k], d),
                       display(r.uncertainty[k], d), unitFor(d));
    j["estimates"].push_back({{"parameter", r.columns.names[static_cast<size_t>(k)]},
                              {"value", display(r.values[k], d)},
                              {"standard_uncertainty", display(r.uncertainty[k], d)},
                              {"unit", unitFor(d)}});
  }
  human += fmt::format("\nresiduals: sigma {:.3f} um ({} degrees of freedom), RMS {:.3f} um, max {:.3f} um\n", r.sigma * 1e3,
                       r.degreesOfFreedom, r.residualRms * 1e3, r.residualMax * 1e3);
  human += fmt::format("solver: {} after {} iterations{}\n", r.converged ? "converged" : "NOT converged", r.iterations,
                       o.robust ? " (Huber loss)" : "");
  emit(o, j, human, csv);
}

void addOptions(CLI::App* cmd, IdentifyOptions& o) {
  addMachineOptions(*cmd, o);
  cmd->add_option("--data", o.data, "Measurement CSV file (repeat for several runs)");
  cmd->add_option("--plan", o.plan, "Test plan (YAML) or bundled plan name");
  cmd->add_option("--params", o.params, "Parameters to determine, e.g. X0B,Z0B,A0C (ISO names or aliases)");
  cmd->add_option("--setup", o.setup, "Set-up errors to estimate in every run, e.g. xW,yW,zW (overrides the files)");
  cmd->add_option("--threads", o.threads, "Threads (0 = all cores)")->capture_default_str();
}

}  // namespace

void addIdentifyCommands(CLI::App& app) {
  auto o = std::make_shared<IdentifyOptions>();
  auto* id = app.add_subcommand("identify", "Least-squares identification of error parameters from measurement files");
  addOptions(id, *o);
  id->add_flag("--robust", o->robust, "Huber loss instead of plain least squares");
  id->add_option("--robust-scale", o->robustScale, "Residual beyond which the Huber loss is linear")->capture_default_str();
  id->callback([o] { identifyCommand(*o); });

  auto* obs = app.add_subcommand("observability", "Which parameters a test plan can determine (SVD of its Jacobian)");
  addOptions(obs, *o);
  obs->callback([o] { observability(*o); });
}

}  // namespace mtacc::cli
