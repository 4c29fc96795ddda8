// mtacc identify / observability: which error parameters a test plan (or a set of measured
// files) determines, and their least-squares estimates with standard uncertainties.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/identified_errors.hpp"

namespace mtacc::cli {
namespace {

struct IdentifyCliOptions : MachineOptions {
  OptionValues values;
  std::string errorsOut;
  bool strict = false;
};

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

std::string proposalText(const ObservabilityResult& r) {
  if (!r.proposal) return "";
  const auto& s = *r.proposal;
  std::string t = "what the plan can determine instead: identify";
  for (const auto& k : s.kept) t += " " + k.name;
  t += ", hold at zero";
  for (const auto& h : s.held) t += " " + h.name;
  t += "; each estimate then stands for:\n";
  for (size_t k = 0; k < s.kept.size(); ++k) t += fmt::format("  {:<10} {}\n", s.kept[k].name, s.standsFor(k));
  return t;
}

std::string predictionText(const ObservabilityResult& r) {
  if (!r.prediction) return "predicted uncertainties: state the readings' noise (--noise, or 'noise:' in the plan's runs)\n";
  const auto& p = *r.prediction;
  std::string t = fmt::format("predicted standard uncertainty with the noise of {} (first order, about the nominal machine):\n"
                              "{:<22} {:>12} {:>12}  unit\n", r.noiseSource, "parameter", "u (k = 1)", "U (k = 2)");
  for (size_t a = 0; a < r.parameterCount; ++a) {
    const auto d = p.columns.dimensions[a];
    const double u = toDisplay(p.uncertainty[static_cast<Eigen::Index>(a)], d);
    t += fmt::format("{:<22} {:>12.4f} {:>12.4f}  {}\n", p.columns.names[a], u, 2.0 * u, displayUnit(d));
  }
  for (const auto& pair : strongCorrelations(p.columns.names, p.covariance, r.parameterCount)) t += "  correlated: " + pair + "\n";
  return t;
}

void observability(const IdentifyCliOptions& o) {
  const auto r = planObservability(loadMachineSetup(o.source), identificationRequest(observabilitySchema(), o.values));
  std::string csv = "index,singular_value\n";
  for (Eigen::Index i = 0; i < r.report.singularValues.size(); ++i) csv += fmt::format("{},{}\n", i + 1, r.report.singularValues[i]);
  emit(o, toJson(r),
       fmt::format("Observability on {} ({} runs)\n", r.machine->name, r.runs) + reportText(r.report, r.readings) + proposalText(r) +
           predictionText(r),
       csv);
}

void identify(const IdentifyCliOptions& o) {
  emitIdentification(o, identifyParameters(loadMachineSetup(o.source), identificationRequest(identificationSchema(), o.values)), o.strict,
                     o.errorsOut);
}

}  // namespace

void addErrorsOutOption(const CommandLine& cmd, std::string& errorsOut) {
  cmd.option("--errors-out", errorsOut,
                 "Write the identified errors (the estimates merged onto the errors held, with a record of the data) "
                 "as an errors file that --errors reads");
}

void emitIdentification(const MachineOptions& o, const IdentificationStudy& out, bool strict, const std::string& errorsOut) {
  if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, out, "--errors-out");
  const auto& r = out.result;
  std::string human = fmt::format("Identification on {} from {} runs ({} readings, {} unknowns)\n", out.machine->name, out.runs,
                                  r.readings, r.values.size());
  human += fmt::format("{:<22} {:>14} {:>14}  unit\n", "parameter", "value", "std. uncert.");
  std::string csv = "parameter,value,standard_uncertainty,unit";
  for (const auto& name : r.columns.names) csv += ",r_" + name;  // the correlation matrix, one row per unknown
  csv += "\n";
  for (Eigen::Index k = 0; k < r.values.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    const auto& name = r.columns.names[static_cast<size_t>(k)];
    if (static_cast<size_t>(k) == out.given.size()) human += "set-up errors of each run (<run>.<error>):\n";
    const bool aliased = static_cast<size_t>(k) < out.given.size() && out.given[static_cast<size_t>(k)] != name;
    human += fmt::format("{:<22} {:>14.4f} {:>14.4f}  {}\n", aliased ? name + " (" + out.given[static_cast<size_t>(k)] + ")" : name,
                         toDisplay(r.values[k], d), toDisplay(r.uncertainty[k], d), displayUnit(d));
    csv += fmt::format("{},{},{},{}", name, toDisplay(r.values[k], d), toDisplay(r.uncertainty[k], d), displayUnit(d));
    for (Eigen::Index b = 0; b < r.values.size(); ++b) csv += fmt::format(",{:.6f}", correlationOf(r, k, b));
    csv += "\n";
  }
  for (const auto& h : out.harmonics)
    human += fmt::format("{:<22} amplitude {:.4f} ± {:.4f} {}, phase {:.2f} ± {:.2f} deg (cos(x + phase))\n", h.name,
                         toDisplay(h.amplitude, h.dimension), toDisplay(h.amplitudeUncertainty, h.dimension),
                         displayUnit(h.dimension), h.phase / kDeg, h.phaseUncertainty / kDeg);
  human += fmt::format("\nresiduals: sigma {:.3f} um ({} degrees of freedom), RMS {:.3f} um, max {:.3f} um\n", r.sigma * 1e3,
                       r.degreesOfFreedom, r.residualRms * 1e3, r.residualMax * 1e3);
  human += fmt::format("solver: {} after {} iterations{}\n", r.converged ? "converged" : "NOT converged", r.iterations,
                       out.robust ? " (Huber loss)" : "");
  if (!out.held.empty()) {
    const size_t shown = std::min<size_t>(out.held.size(), 8);
    human += fmt::format("held at the machine file's (or --errors') values, not determined: {}{} ({}); --from-nominal holds them at zero\n",
                         fmt::join(out.held.begin(), out.held.begin() + static_cast<std::ptrdiff_t>(shown), ", "),
                         shown < out.held.size() ? ", ..." : "", out.held.size());
  }
  const auto& q = out.quality;
  if (q.pValue)
    human += fmt::format("goodness of fit against the noise of {}: chi-square {:.4g}, {} degrees of freedom, p = {:.3g}\n",
                         q.noiseSource, *q.chiSquare, r.degreesOfFreedom, *q.pValue);
  else
    human += "goodness of fit: not tested (state the reading noise with --noise or '# noise:' in the files)\n";
  if (!errorsOut.empty()) human += "identified errors written to " + errorsOut + " (read them with --errors)\n";
  emit(o, toJson(out), human, csv);
  for (const auto& w : q.warnings) std::cerr << "mtacc: warning: " << w << "\n";
  if (strict && !q.warnings.empty()) throw StrictFailure{q.warnings.size()};
}

void addIdentifyCommands(const CommandLine& app) {
  const std::map<std::string, std::string> aliases{{"parameters", "--params"}};
  auto o = std::make_shared<IdentifyCliOptions>();
  auto id = app.subcommand("identify", "Least-squares identification of error parameters from measurement files");
  id.machineOptions(*o);
  id.schemaOptions(identificationSchema(), o->values, aliases);
  id.flag("--strict", o->strict, "Exit with status 4 when the fit or the conditioning draws a warning");
  addErrorsOutOption(id, o->errorsOut);
  id.callback([o] { identify(*o); });

  auto obs = app.subcommand("observability", "Which parameters a test plan can determine (SVD of its Jacobian)");
  obs.machineOptions(*o);
  obs.schemaOptions(observabilitySchema(), o->values, aliases);
  obs.callback([o] { observability(*o); });
}

}  // namespace mtacc::cli
