#include "mtacc/workflows/identified_errors.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>

#include "mtacc/core/units.hpp"
#include "mtacc/core/version.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/file_hash.hpp"
#include "mtacc/io/text_file.hpp"

namespace mtacc {
namespace {

// A YAML scalar that reads back as the same string, whatever it holds (a JSON string is a
// double-quoted YAML scalar).
std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

std::string quantity(double v, Dimension d) { return fmt::format("{:.15g} {}", toDisplay(v, d), displayUnit(d)); }

std::string optionalNumber(const std::optional<double>& v) { return v ? fmt::format("{:.15g}", *v) : "null"; }

}  // namespace

std::string identifiedErrorsYaml(const IdentificationOutcome& outcome) {
  const IdentificationResult& r = outcome.result;
  const Machine& machine = *outcome.machine;
  std::string y = "# Identified by mtacc: the estimates below merged onto the errors held (listed under\n"
                  "# identification.held). Read it with --errors; docs/file-formats.md, \"Identified errors\".\n";
  y += errorsYaml(machine, r.errors);
  y += "identification:\n";
  y += fmt::format("  by: {}\n", quoted(std::string("mtacc ") + version() + " " + outcome.command));
  y += fmt::format("  date: {:%Y-%m-%dT%H:%M:%SZ}\n", std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
  y += fmt::format("  machine: {{name: {}, file: {}}}\n", quoted(machine.name), quoted(machine.sourceFile));
  y += fmt::format("  plan: {}\n", outcome.plan.empty() ? "null" : quoted(outcome.plan));
  y += "  data:\n";
  for (const auto& file : outcome.dataFiles) y += fmt::format("    - {{file: {}, sha256: {}}}\n", quoted(file), sha256OfFile(file));
  if (outcome.dataFiles.empty()) y += "    []\n";
  y += fmt::format("  readings: {}\n  degrees_of_freedom: {}\n", r.readings, r.degreesOfFreedom);
  y += fmt::format("  sigma: {:.15g} um\n  residual_rms: {:.15g} um\n  residual_max: {:.15g} um\n", r.sigma * 1e3,
                   r.residualRms * 1e3, r.residualMax * 1e3);
  const auto& q = outcome.quality;
  y += fmt::format("  noise_source: {}\n  chi_square: {}\n  p_value: {}\n", q.noiseSource.empty() ? "null" : quoted(q.noiseSource),
                   optionalNumber(q.chiSquare), optionalNumber(q.pValue));
  y += fmt::format("  solver: {{converged: {}, iterations: {}, robust: {}}}\n", r.converged, r.iterations, outcome.robust);
  y += fmt::format("  held_at: {}\n", outcome.heldAtZero ? "zero (--from-nominal)" : "the machine file's or --errors' values");
  y += "  held:";
  if (outcome.held.empty()) y += " {}";
  y += "\n";
  for (const auto& name : outcome.held) {
    const Parameter p = findParameter(machine, r.errors, name);
    y += fmt::format("    {}: {}\n", name, quantity(parameterValue(r.errors, p), p.dimension));
  }
  y += "  estimates:  # the machine's parameters, then each run's set-up errors (<run>.<error>)\n";
  for (Eigen::Index k = 0; k < r.values.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    y += fmt::format("    - {{parameter: {}, value: {}, standard_uncertainty: {}}}\n", quoted(r.columns.names[static_cast<size_t>(k)]),
                     quantity(r.values[k], d), quantity(r.uncertainty[k], d));
  }
  y += "  covariance:  # of the estimates in their order, in um and urad (um^2, um urad, urad^2)\n";
  for (Eigen::Index a = 0; a < r.values.size(); ++a) {
    y += "    - [";
    for (Eigen::Index b = 0; b < r.values.size(); ++b)
      y += fmt::format("{}{:.15g}", b ? ", " : "",
                       toDisplay(toDisplay(r.covariance(a, b), r.columns.dimensions[static_cast<size_t>(a)]),
                                 r.columns.dimensions[static_cast<size_t>(b)]));
    y += "]\n";
  }
  return y;
}

void writeIdentifiedErrors(const std::string& path, const IdentificationOutcome& outcome, const std::string& key) {
  writeFileAtomically(path, identifiedErrorsYaml(outcome), key);
}

}  // namespace mtacc
