#include "mtacc/workflows/identified_errors.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "mtacc/core/units.hpp"
#include "mtacc/core/version.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/file_hash.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

// A YAML scalar that reads back as the same string, whatever it holds (a JSON string is a
// double-quoted YAML scalar).
std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

std::string quantity(double v, Dimension d) { return fmt::format("{:.15g} {}", toDisplay(v, d), displayUnit(d)); }
std::string quantity(double v, const EstimateUnit& u) { return fmt::format("{:.15g} {}", v * u.scale, u.unit); }

std::vector<EstimateUnit> unitsOf(const std::vector<Dimension>& dimensions) {
  std::vector<EstimateUnit> units;
  for (const Dimension d : dimensions) units.push_back(EstimateUnit::of(d));
  return units;
}

std::string optionalNumber(const std::optional<double>& v) { return v ? fmt::format("{:.15g}", *v) : "null"; }

}  // namespace

IdentificationRecord identificationRecord(const IdentificationStudy& outcome) {
  const IdentificationResult& r = outcome.result;
  IdentificationRecord record{outcome.command, outcome.plan, outcome.dataFiles, {}, {}, outcome.held, r.columns.names,
                              unitsOf(r.columns.dimensions), r.values, r.uncertainty, r.covariance};
  const auto& q = outcome.quality;
  record.fit = {{"readings", std::to_string(r.readings)},
                {"degrees_of_freedom", std::to_string(r.degreesOfFreedom)},
                {"sigma", fmt::format("{:.15g} um", r.sigma * 1e3)},
                {"residual_rms", fmt::format("{:.15g} um", r.residualRms * 1e3)},
                {"residual_max", fmt::format("{:.15g} um", r.residualMax * 1e3)},
                {"noise_source", q.noiseSource.empty() ? "null" : quoted(q.noiseSource)},
                {"chi_square", optionalNumber(q.chiSquare)},
                {"p_value", optionalNumber(q.pValue)},
                {"solver", fmt::format("{{converged: {}, iterations: {}, robust: {}}}", r.converged, r.iterations, outcome.robust)}};
  record.heldAt = outcome.heldAtZero ? "zero (--from-nominal)" : "the machine file's or --errors' values";
  return record;
}

IdentificationRecord identificationRecord(const PlateIdentificationStudy& s) {
  const PlateIdentification& r = s.result;
  IdentificationRecord record{"plate-identify", "", s.files, {}, {}, {}, r.names, {}, r.values, r.uncertainty, r.covariance};
  for (size_t k = 0; k < r.names.size(); ++k) {
    record.units.push_back(EstimateUnit::of(k < s.parameters.size() ? s.parameters[k].dimension
                                            : isNuisanceRotation(r.names[k]) ? Dimension::Angle : Dimension::Length));
    if (!r.determined[k]) record.uncertainty[static_cast<Eigen::Index>(k)] = std::nan("");
  }
  record.fit = {{"readings", std::to_string(r.readings)},
                {"degrees_of_freedom", std::to_string(r.degreesOfFreedom)},
                {s.weighted ? "sigma_over_probe_noise" : "sigma", s.weighted ? fmt::format("{:.15g}", r.sigma)
                                                                            : fmt::format("{:.15g} um", r.sigma * 1e3)}};
  record.heldAt = "zero: the plates identify the linear axes' functions and squareness alone";
  return record;
}

IdentificationRecord identificationRecord(const ComponentFitStudy& s) {
  const auto& c = s.data.component;
  const Machine& machine = *s.machine;
  const bool rotary = machine.axes[static_cast<size_t>(c.axis)].isRotary();
  const Dimension valueDimension = c.component < 3 ? Dimension::Length : Dimension::Angle;
  const std::string name = motionErrorName(machine, c.axis, c.component);
  IdentificationRecord record{"fit", "", {s.data.file}, {}, "the machine file's or --errors' values: fit determines " + name + " alone", {}, {}, {}, {}, {}, {}};
  // The fit's parameters are the trend's coefficients and the periodic term's free parameters;
  // the function's are the trend's and the periodic term's coefficients (periodicMap * free).
  const auto trend = static_cast<Eigen::Index>(s.fit.trend.coefficients.size());
  const Eigen::Index periodic = s.fit.periodic ? s.fit.periodicMap.rows() : 0;
  Eigen::MatrixXd toCoefficients = Eigen::MatrixXd::Zero(trend + periodic, s.fit.covariance.rows());
  toCoefficients.topLeftCorner(trend, trend).setIdentity();
  if (periodic) toCoefficients.bottomRightCorner(periodic, s.fit.periodicMap.cols()) = s.fit.periodicMap;
  record.covariance = toCoefficients * s.fit.covariance * toCoefficients.transpose();
  record.uncertainty = record.covariance.diagonal().cwiseSqrt();
  record.values.resize(trend + periodic);
  // Each coefficient named as the written function names the same basis function (its terms
  // hold every power at every interior break; the fit's are among them).
  const ErrorFunction& written = s.errors.axes[static_cast<size_t>(c.axis)].motion[static_cast<size_t>(c.component)];
  const auto suffixes = written.parameterSuffixes();
  Eigen::Index k = 0;
  size_t offset = 0, term = 0;
  for (const PiecewiseTerm* fitted : {&s.fit.trend, s.fit.periodic ? &*s.fit.periodic : nullptr}) {
    if (!fitted) continue;
    const auto& form = std::get<PiecewiseTerm>(written.terms()[term++]).coefficients;
    for (const auto& coefficient : fitted->coefficients) {
      const auto same = std::find_if(form.begin(), form.end(), [&](const auto& w) { return w.knot == coefficient.knot && w.power == coefficient.power; });
      record.values[k] = coefficient.value;
      record.names.push_back(name + "." + suffixes[offset + static_cast<size_t>(same - form.begin())]);
      record.units.push_back(EstimateUnit::coefficient(valueDimension, rotary, coefficient.power));
      ++k;
    }
    offset += form.size();
  }
  record.fit = {{"positions", std::to_string(s.curve.positions.size())},
                {"runs_each_way", std::to_string(s.data.runs.forward.cols())},
                {"degrees_of_freedom", std::to_string(s.fit.degreesOfFreedom)},
                {"residual_std", quantity(s.fit.residualStd, valueDimension)},
                {"removed_terms", s.fit.removed.empty() ? "[]" : "[" + fmt::format("{}", fmt::join(s.fit.removed, ", ")) + "]"}};
  return record;
}

std::string identifiedErrorsYaml(const Machine& machine, const ErrorModel& errors, const IdentificationRecord& record) {
  std::string y = "# Identified by mtacc: the estimates below merged onto the errors held (listed under\n"
                  "# identification.held). Read it with --errors; docs/file-formats.md, \"Identified errors\".\n";
  y += errorsYaml(machine, errors);
  y += "identification:\n";
  y += fmt::format("  by: {}\n", quoted(std::string("mtacc ") + version() + " " + record.command));
  y += fmt::format("  date: {:%Y-%m-%dT%H:%M:%SZ}\n", std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
  y += fmt::format("  machine: {{name: {}, file: {}}}\n", quoted(machine.name), quoted(machine.sourceFile));
  y += fmt::format("  plan: {}\n", record.plan.empty() ? "null" : quoted(record.plan));
  y += "  data:";
  if (record.dataFiles.empty()) y += " []";
  y += "\n";
  for (const auto& file : record.dataFiles) y += fmt::format("    - {{file: {}, sha256: {}}}\n", quoted(file), sha256OfFile(file));
  for (const auto& [key, value] : record.fit) y += fmt::format("  {}: {}\n", key, value);
  y += fmt::format("  held_at: {}\n", quoted(record.heldAt));
  y += "  held:";
  if (record.held.empty()) y += " {}";
  y += "\n";
  for (const auto& name : record.held) {
    const Parameter p = findParameter(machine, errors, name);
    y += fmt::format("    {}: {}\n", name, quantity(parameterValue(errors, p), p.dimension));
  }
  y += "  estimates:  # the machine's parameters, then the set-up unknowns of each run or placement\n";
  for (Eigen::Index k = 0; k < record.values.size(); ++k) {
    const auto& d = record.units[static_cast<size_t>(k)];
    const double u = record.uncertainty[k];
    y += fmt::format("    - {{parameter: {}, value: {}, standard_uncertainty: {}}}\n", quoted(record.names[static_cast<size_t>(k)]),
                     quantity(record.values[k], d), std::isnan(u) ? std::string("null") : quantity(u, d));
  }
  y += "  covariance:  # of the estimates in their order, in the products of their units (um^2, um urad, urad^2, ...)\n";
  for (Eigen::Index a = 0; a < record.values.size(); ++a) {
    y += "    - [";
    for (Eigen::Index b = 0; b < record.values.size(); ++b) {
      const double c = record.covariance(a, b) * record.units[static_cast<size_t>(a)].scale * record.units[static_cast<size_t>(b)].scale;
      y += (b ? ", " : "") + (std::isfinite(c) ? fmt::format("{:.15g}", c) : std::string("null"));  // null: not determined
    }
    y += "]\n";
  }
  return y;
}

void writeIdentifiedErrors(const std::string& path, const Machine& machine, const ErrorModel& errors,
                           const IdentificationRecord& record, const std::string& key) {
  writeFileAtomically(path, identifiedErrorsYaml(machine, errors, record), key);
}

void writeIdentifiedErrors(const std::string& path, const IdentificationStudy& outcome, const std::string& key) {
  writeIdentifiedErrors(path, *outcome.machine, outcome.result.errors, identificationRecord(outcome), key);
}

}  // namespace mtacc
