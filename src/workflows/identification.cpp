#include "mtacc/workflows/identification.hpp"

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

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
  p.problem.start = request.fromNominal ? withParametersZero(*setup.machine, setup.errors) : setup.errors;
  p.given = request.parameters;
  InputLocation namedAt{"", 0, "parameters"};
  if (!request.plan.empty()) {
    auto plan = loadTestPlan(nominal, request.plan);
    if (p.given.empty()) {
      p.given = plan.parameters;
      namedAt = plan.parametersAt;
    }
    if (planRuns) p.problem.runs = std::move(plan.runs);
  }
  std::map<std::string, std::string> seen;  // canonical path -> as given
  for (const auto& file : request.data) {
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(file, ec).string();
    if (const auto [it, added] = seen.emplace(ec ? file : canonical, file); !added)
      throw InputError(InputLocation{"", 0, "data"}, "'" + file + "' is given twice (also as '" + it->second + "')");
    p.problem.runs.push_back(readMeasurementCsv(nominal, file));
  }
  p.problem.runs.insert(p.problem.runs.end(), request.runs.begin(), request.runs.end());
  if (p.problem.runs.empty()) throw InputError(InputLocation{"", 0, planRuns ? "plan" : "data"}, "no measurement run given");
  if (p.given.empty())
    throw InputError(InputLocation{"", 0, "parameters"}, "no parameter to determine (name them, or use a plan with 'parameters')");
  p.problem.parameters = findPlanParameters(setup.machine, p.problem.start, p.given, namedAt);
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

std::string IdentifiableSetProposal::standsFor(size_t k) const {
  const Parameter& p = kept[k];
  std::string s = p.name;
  for (size_t d = 0; d < held.size(); ++d) {
    const Parameter& h = held[d];
    const double c = coefficients(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(d)) * toDisplay(1.0, p.dimension) /
                     toDisplay(1.0, h.dimension);
    if (c == 0.0) continue;
    const std::string unit = p.dimension == h.dimension ? "" : fmt::format(" {}/{}", displayUnit(p.dimension), displayUnit(h.dimension));
    s += fmt::format(" {} {:.4g}{} {}", c < 0 ? "-" : "+", std::abs(c), unit, h.name);
  }
  return s;
}

const OptionSchema& identificationSchema() {
  static const OptionSchema schema{
      "identify",
      {{"data", OptionKind::List, "Measurement CSV files"},
       {"plan", OptionKind::Text, "Test plan (YAML) or bundled plan name: its runs (observability) and its parameter list"},
       {"parameters", OptionKind::List, "Parameters to determine, e.g. X0B,Z0B,A0C (ISO names or aliases); default: the plan's list"},
       {"setup", OptionKind::List, "Set-up errors to estimate in every run, e.g. xW,yW,zW (overrides the files)"},
       {"robust", OptionKind::Flag, "Huber loss instead of plain least squares"},
       {.key = "robust_scale", .kind = OptionKind::Quantity, .help = "Residual beyond which the Huber loss is linear", .defaultText = "2 um",
        .low = 1e-6, .high = 1.0, .outOfRange = "must be from 1 nm to 1 mm"},
       {.key = "noise", .kind = OptionKind::Quantity,
        .help = "Reading noise (standard deviation): identify tests the fit against it, observability predicts the uncertainties "
                "from it; default: the files' '# noise:' lines, the plan's runs' 'noise:'",
        .low = 1e-6, .high = 1.0, .outOfRange = "must be from 1 nm to 1 mm"},
       {.key = "uncertainty_fraction", .kind = OptionKind::Number,
        .help = "Warn when a standard uncertainty exceeds this fraction of the plausible magnitude (50 um, 200 urad)",
        .defaultText = "0.1", .low = 0, .high = 1, .lowExcluded = true, .outOfRange = "must be above 0 and at most 1"},
       {"from_nominal", OptionKind::Flag,
        "Hold the errors not determined at zero (the nominal machine) instead of the machine file's or the errors file's values"},
       threadsOption()}};
  return schema;
}

const OptionSchema& observabilitySchema() {
  static const OptionSchema schema =
      identificationSchema().subset("observability", {"data", "plan", "parameters", "setup", "noise", "from_nominal", "threads"});
  return schema;
}

IdentificationRequest identificationRequest(const OptionSchema& schema, const OptionValues& values) {
  const OptionReader read(schema, values);
  IdentificationRequest r;
  r.data = read.list("data");
  r.plan = read.text("plan").value_or("");
  r.parameters = read.list("parameters");
  if (values.contains("setup")) r.setup = read.list("setup");
  r.noise = read.quantity("noise");
  r.fromNominal = read.flag("from_nominal");
  r.threads = *read.count("threads");
  if (schema.find("robust")) {
    r.robust = read.flag("robust");
    r.robustScale = *read.quantity("robust_scale");
    r.uncertaintyFraction = *read.number("uncertainty_fraction");
  }
  return r;
}

ObservabilityResult planObservability(const MachineSetup& setup, const IdentificationRequest& request) {
  if (request.noise) requireInRange(observabilitySchema().at("noise"), *request.noise);
  requireInRange(observabilitySchema().at("threads"), request.threads);
  auto p = buildProblem(setup, request, true);
  ObservabilityResult out{setup.machine, p.problem.runs.size(), countReadings(p.problem), planObservability(p.problem, request.threads), std::nullopt, std::nullopt, "", 0};
  IdentificationProblem determinable = p.problem;
  if (!out.report.identifiable()) {
    const auto columns = proposeIdentifiableSet(p.problem, request.threads);
    IdentifiableSetProposal proposal{{}, {}, columns.standsFor};
    for (const auto k : columns.kept) proposal.kept.push_back(p.problem.parameters[static_cast<size_t>(k)]);
    for (const auto d : columns.dropped) proposal.held.push_back(p.problem.parameters[static_cast<size_t>(d)]);
    determinable.parameters = proposal.kept;
    out.proposal = std::move(proposal);
  }
  std::vector<double> noise;
  for (const auto& run : p.problem.runs)
    if (const auto n = request.noise ? request.noise : run.noise) noise.push_back(*n);
  if (noise.size() == p.problem.runs.size() && !noise.empty()) {
    out.noiseSource = request.noise ? "--noise" : "the runs' own noise";
    out.parameterCount = determinable.parameters.size();
    try {
      out.prediction = predictUncertainty(determinable, noise, request.threads);
    } catch (const NotIdentifiable&) {
      // The set-up unknowns alone cannot be determined: no prediction, the findings say why.
    }
  }
  return out;
}

nlohmann::json toJson(const ObservabilityReport& r) {
  nlohmann::json j;
  j["names"] = r.names;
  j["rank"] = r.rank;
  j["parameters"] = r.names.size();
  j["condition"] = r.condition;
  j["identifiable"] = r.identifiable();
  j["singular_values"] = std::vector<double>(r.singularValues.data(), r.singularValues.data() + r.singularValues.size());
  j["singular_vectors"] = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.singularVectors.rows(); ++i) {
    const Eigen::RowVectorXd row = r.singularVectors.row(i);
    j["singular_vectors"].push_back(std::vector<double>(row.data(), row.data() + row.size()));
  }
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
  j["identifiable_set"] = nullptr;
  if (r.proposal) {
    const auto& s = *r.proposal;
    nlohmann::json kept = nlohmann::json::array(), held = nlohmann::json::array();
    for (size_t k = 0; k < s.kept.size(); ++k) kept.push_back({{"parameter", s.kept[k].name}, {"stands_for", s.standsFor(k)}});
    for (const auto& h : s.held) held.push_back(h.name);
    j["identifiable_set"] = {{"parameters", kept}, {"held", held}};
  }
  j["prediction"] = nullptr;
  if (r.prediction) {
    const auto& pr = *r.prediction;
    nlohmann::json estimates = nlohmann::json::array(), correlation = nlohmann::json::array();
    const Eigen::Index n = pr.uncertainty.size();
    for (Eigen::Index a = 0; a < n; ++a) {
      const auto d = pr.columns.dimensions[static_cast<size_t>(a)];
      estimates.push_back({{"parameter", pr.columns.names[static_cast<size_t>(a)]},
                           {"standard_uncertainty", toDisplay(pr.uncertainty[a], d)},
                           {"expanded_uncertainty_k2", 2.0 * toDisplay(pr.uncertainty[a], d)},
                           {"unit", displayUnit(d)},
                           {"setup", static_cast<size_t>(a) >= r.parameterCount}});
      nlohmann::json row = nlohmann::json::array();
      for (Eigen::Index b = 0; b < n; ++b) row.push_back(pr.covariance(a, b) / (pr.uncertainty[a] * pr.uncertainty[b]));
      correlation.push_back(row);
    }
    j["prediction"] = {{"noise_source", r.noiseSource}, {"estimates", estimates}, {"correlation", correlation},
                       {"correlations_above_0_9", strongCorrelations(pr.columns.names, pr.covariance, static_cast<size_t>(n))}};
  }
  return j;
}

IdentificationStudy identifyParameters(const MachineSetup& setup, const IdentificationRequest& request) {
  const OptionSchema& schema = identificationSchema();
  if (request.robust) requireInRange(schema.at("robust_scale"), request.robustScale);
  if (request.noise) requireInRange(schema.at("noise"), *request.noise);
  requireInRange(schema.at("uncertainty_fraction"), request.uncertaintyFraction);
  requireInRange(schema.at("threads"), request.threads);
  auto p = buildProblem(setup, request, false);
  IdentificationOptions options;
  options.robust = request.robust;
  options.robustScale = request.robustScale;
  options.threads = request.threads;
  IdentificationStudy out{setup.machine, p.problem.runs.size(), p.given, {}, request.robust, {}, {}, {},
                            "identify", request.plan, request.data, request.fromNominal};
  // A rotary axis's zero offset estimated (B.zero) turns its line: the A0k B0k C0k it moves are
  // estimated with it, not held.
  auto estimated = [&](const Parameter& h) {
    return std::any_of(p.problem.parameters.begin(), p.problem.parameters.end(), [&](const Parameter& q) {
      return q.name == h.name || (q.kind == ParameterKind::ZeroOffset && h.kind == ParameterKind::Location && q.axis == h.axis &&
                                  h.component >= 3 && q.turn[h.component - 3] != 0.0);
    });
  };
  for (const Parameter& held : nonZeroParameters(*setup.machine, p.problem.start))
    if (!estimated(held)) out.held.push_back(held.name);
  try {
    out.result = identify(p.problem, options);
  } catch (const NotIdentifiable& e) {
    throw InputError(InputLocation{"", 0, "parameters"}, std::string("refused: ") + e.what());
  } catch (const InvalidInput& e) {
    throw InputError(InputLocation{"", 0, "data"}, e.what());
  }
  out.quality = fitQuality(out.result, request.noise, request.uncertaintyFraction);
  if (out.quality.chiSquare) out.quality.noiseSource = request.noise ? "--noise" : "the files' '# noise:' lines";
  out.harmonics = harmonicEstimates(out.result);
  return out;
}

nlohmann::json toJson(const IdentificationStudy& o) {
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
  j["held"] = o.held;
  j["observability"] = toJson(r.observability);
  const auto& q = o.quality;
  nlohmann::json poorly = nlohmann::json::array();
  for (size_t k : q.poorlyDetermined) poorly.push_back(r.columns.names[k]);
  j["quality"] = {{"noise_source", q.noiseSource.empty() ? nlohmann::json(nullptr) : nlohmann::json(q.noiseSource)},
                  {"chi_square", q.chiSquare ? nlohmann::json(*q.chiSquare) : nlohmann::json(nullptr)},
                  {"p_value", q.pValue ? nlohmann::json(*q.pValue) : nlohmann::json(nullptr)},
                  {"fit_significance", kFitSignificance},
                  {"poorly_determined", poorly},
                  {"warnings", q.warnings}};
  // Covariance in the display units (um, urad; products of them), and the correlation.
  const Eigen::Index n = r.values.size();
  nlohmann::json covariance = nlohmann::json::array(), correlation = nlohmann::json::array();
  for (Eigen::Index a = 0; a < n; ++a) {
    nlohmann::json covRow = nlohmann::json::array(), corRow = nlohmann::json::array();
    const auto da = r.columns.dimensions[static_cast<size_t>(a)];
    for (Eigen::Index b = 0; b < n; ++b) {
      const auto db = r.columns.dimensions[static_cast<size_t>(b)];
      covRow.push_back(toDisplay(toDisplay(r.covariance(a, b), da), db));
      corRow.push_back(correlationOf(r, a, b));
    }
    covariance.push_back(covRow);
    correlation.push_back(corRow);
  }
  j["covariance"] = covariance;
  j["correlation"] = correlation;
  j["correlations_above_0_9"] = strongCorrelations(r.columns.names, r.covariance, o.given.size());  // of the machine's parameters
  j["estimates"] = nlohmann::json::array();
  for (Eigen::Index k = 0; k < r.values.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    const auto& name = r.columns.names[static_cast<size_t>(k)];
    const bool aliased = static_cast<size_t>(k) < o.given.size() && o.given[static_cast<size_t>(k)] != name;
    j["estimates"].push_back({{"parameter", name},
                              {"setup", static_cast<size_t>(k) >= o.given.size()},
                              {"given_as", aliased ? nlohmann::json(o.given[static_cast<size_t>(k)]) : nlohmann::json(nullptr)},
                              {"value", toDisplay(r.values[k], d)},
                              {"standard_uncertainty", toDisplay(r.uncertainty[k], d)},
                              {"unit", displayUnit(d)}});
  }
  // Each run's residuals (reading minus model, um; one row per pose), their RMS and largest.
  j["run_residuals"] = nlohmann::json::array();
  Eigen::Index row = 0;
  for (size_t k = 0; k < r.runs.size(); ++k) {
    const auto& run = r.runs[k];
    const Eigen::Index m = readingSize(run.instrument), n = run.poses() * m;
    nlohmann::json poses = nlohmann::json::array();
    for (Eigen::Index i = 0; i < run.poses(); ++i) {
      nlohmann::json reading = nlohmann::json::array();
      for (Eigen::Index c = 0; c < m; ++c) reading.push_back(r.residual[row + i * m + c] * 1e3);
      poses.push_back(reading);
    }
    const auto segment = r.residual.segment(row, n);
    j["run_residuals"].push_back({{"run", run.name},
                                  {"instrument", instrumentName(run.instrument)},
                                  {"rms_um", std::sqrt(segment.squaredNorm() / static_cast<double>(n)) * 1e3},
                                  {"max_um", segment.cwiseAbs().maxCoeff() * 1e3},
                                  {"noise_um", run.noise ? nlohmann::json(*run.noise * 1e3) : nlohmann::json(nullptr)},
                                  {"residuals_um", poses}});
    row += n;
  }
  j["harmonics"] = nlohmann::json::array();
  for (const auto& h : o.harmonics)
    j["harmonics"].push_back({{"term", h.name},
                              {"amplitude", toDisplay(h.amplitude, h.dimension)},
                              {"amplitude_uncertainty", toDisplay(h.amplitudeUncertainty, h.dimension)},
                              {"unit", displayUnit(h.dimension)},
                              {"phase_deg", h.phase / kDeg},
                              {"phase_uncertainty_deg", h.phaseUncertainty / kDeg}});
  return j;
}

}  // namespace mtacc
