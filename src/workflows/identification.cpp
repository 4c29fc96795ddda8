#include "mtacc/workflows/identification.hpp"

#include <filesystem>
#include <map>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/measurement_csv.hpp"
#include "mtacc/io/plan_yaml.hpp"

namespace mtacc {
namespace {

struct Problem {
  IdentificationProblem problem;
  std::vector<std::string> given;
};

Problem buildProblem(const MachineSetup& setup, const IdentificationRequest& request, bool planRuns) {
  const auto nominal = setup.nominal();
  Problem p;
  p.problem.machine = setup.machine;
  p.problem.start = setup.errors;
  p.given = request.parameters;
  if (!request.plan.empty()) {
    auto plan = loadTestPlan(nominal, request.plan);
    if (p.given.empty()) p.given = plan.parameters;
    if (planRuns) p.problem.runs = std::move(plan.runs);
  }
  std::map<std::string, std::string> seen;  // canonical path -> as given
  for (const auto& file : request.data) {
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(file, ec).string();
    if (const auto [it, added] = seen.emplace(ec ? file : canonical, file); !added)
      throw InputError(InputLocation{file, 0, "data"}, "the same file is given twice (also as '" + it->second + "')");
    p.problem.runs.push_back(readMeasurementCsv(nominal, file));
  }
  if (p.problem.runs.empty()) throw InputError(InputLocation{"", 0, planRuns ? "plan" : "data"}, "no measurement run given");
  if (p.given.empty())
    throw InputError(InputLocation{"", 0, "parameters"}, "no parameter to determine (name them, or use a plan with 'parameters')");
  p.problem.parameters = findParameters(setup, p.given);
  if (request.setup) {
    for (auto& run : p.problem.runs) run.estimate.clear();
    for (const auto& n : *request.setup) {
      const auto s = parseSetupParameter(n);
      if (!s) throw InputError(InputLocation{"", 0, "setup"}, "unknown set-up parameter '" + n + "' (xT yT zT xW yW zW aN bN cN dL)");
      for (auto& run : p.problem.runs)
        if (appliesTo(*s, run.instrument)) run.estimate.push_back(*s);
    }
  }
  return p;
}

Eigen::Index countReadings(const IdentificationProblem& p) {
  Eigen::Index n = 0;
  for (const auto& r : p.runs) n += r.poses() * readingSize(r.instrument);
  return n;
}

}  // namespace

ObservabilityResult planObservability(const MachineSetup& setup, const IdentificationRequest& request) {
  const auto p = buildProblem(setup, request, true);
  return {setup.machine, p.problem.runs.size(), countReadings(p.problem), planObservability(p.problem, request.threads)};
}

nlohmann::json toJson(const ObservabilityReport& r) {
  nlohmann::json j;
  j["names"] = r.names;
  j["rank"] = r.rank;
  j["parameters"] = r.names.size();
  j["condition"] = r.condition;
  j["identifiable"] = r.identifiable();
  j["singular_values"] = std::vector<double>(r.singularValues.data(), r.singularValues.data() + r.singularValues.size());
  j["no_effect"] = r.noEffect;
  j["findings"] = r.findings();
  j["groups"] = nlohmann::json::array();
  for (const auto& g : r.groups) j["groups"].push_back({{"parameters", g.names}, {"observable", g.observable}});
  return j;
}

nlohmann::json toJson(const ObservabilityResult& r) {
  auto j = toJson(r.report);
  j["machine"] = r.machine->name;
  j["runs"] = r.runs;
  j["readings"] = r.readings;
  return j;
}

IdentificationOutcome identifyParameters(const MachineSetup& setup, const IdentificationRequest& request) {
  auto p = buildProblem(setup, request, false);
  IdentificationOptions options;
  options.robust = request.robust;
  options.robustScale = request.robustScale;
  options.threads = request.threads;
  IdentificationOutcome out{setup.machine, p.problem.runs.size(), p.given, request.robust, {}};
  try {
    out.result = identify(p.problem, options);
  } catch (const NotIdentifiable& e) {
    throw InputError(InputLocation{"", 0, "parameters"}, std::string("refused: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(InputLocation{"", 0, "data"}, e.what());
  }
  return out;
}

nlohmann::json toJson(const IdentificationOutcome& o) {
  const auto& r = o.result;
  nlohmann::json j;
  j["machine"] = o.machine->name;
  j["runs"] = o.runs;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["readings"] = r.readings;
  j["degrees_of_freedom"] = r.degreesOfFreedom;
  j["sigma_um"] = r.sigma * 1e3;
  j["residual_rms_um"] = r.residualRms * 1e3;
  j["residual_max_um"] = r.residualMax * 1e3;
  j["robust"] = o.robust;
  j["observability"] = toJson(r.observability);
  j["estimates"] = nlohmann::json::array();
  for (Eigen::Index k = 0; k < r.values.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    const auto& name = r.columns.names[static_cast<size_t>(k)];
    const bool aliased = static_cast<size_t>(k) < o.given.size() && o.given[static_cast<size_t>(k)] != name;
    j["estimates"].push_back({{"parameter", name},
                              {"given_as", aliased ? nlohmann::json(o.given[static_cast<size_t>(k)]) : nlohmann::json(nullptr)},
                              {"value", toDisplay(r.values[k], d)},
                              {"standard_uncertainty", toDisplay(r.uncertainty[k], d)},
                              {"unit", displayUnit(d)}});
  }
  return j;
}

}  // namespace mtacc
