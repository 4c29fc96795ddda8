// mtacc positioning: ISO 230-2 accuracy and repeatability of positioning of one axis.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/workflows/positioning.hpp"

namespace mtacc::cli {
namespace {

struct PositioningCliOptions : MachineOptions {
  OptionValues values;
};

std::string formatBudget(const PositioningEvaluation& e, const PositioningUnits& u) {
  const double s = u.deviationScale;
  std::string out = fmt::format("\nUncertainty (ISO/TR 230-9, k = 2) over {:g} {}, {}; conditions: {}\n", e.uncertainty.measuredLength * u.targetScale,
                                u.target, e.conditions.instrument, e.conditionsFile.empty() ? "the defaults" : e.conditionsFile);
  for (const auto& k : e.uncertainty.contributors)
    out += fmt::format("  {:<15} {:8.4f} {}  {}{}\n", k.symbol, k.standard * s, u.deviation, k.source, k.defaulted ? " (default)" : "");
  out += "  and the finite number of cycles, per value (docs/conventions.md \"Measurement uncertainty\")\n";
  if (!e.conditions.defaulted.empty())
    out += fmt::format("  defaults used for: {}\n", fmt::join(e.conditions.defaulted, ", "));
  if (!e.conformance) return out;
  const auto& c = *e.conformance;
  out += fmt::format("\nVerdicts (tolerances: {}; {})\n", c.toleranceFile, describe(c.rule));
  for (const auto& v : c.verdicts)
    out += fmt::format("  {:<11} {:9.3f} ± {:6.3f} {}   tolerance {:8.3f} ({})   {}\n", v.quantity, v.value * s, v.expanded * s, u.deviation,
                       v.tolerance * s, v.toleranceText, toString(v.verdict));
  out += fmt::format("  overall: {}\n", toString(c.overall()));
  return out;
}

void run(const PositioningCliOptions& o) {
  const auto request = positioningRequest(o.values);
  const std::string& data = request.data;
  const auto e = evaluatePositioningFile(request);
  const auto& r = e.result;
  const auto u = positioningUnits(e.test.axis);
  const double s = u.deviationScale;
  std::string human = fmt::format("ISO 230-2 positioning test '{}' ({} axis, {} targets x {} cycles each way) from {}\n\n", e.test.name,
                                  e.test.axis == PositioningAxis::Linear ? "linear" : "rotary", r.positions.size(), r.cycles, data);
  human += fmt::format("{:>12} {:>9} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8}   ({})\n", fmt::format("target {}", u.target),
                       "mean ↑", "mean ↓", "mean", "B_i", "s ↑", "s ↓", "R ↑", "R ↓", "R_i", u.deviation);
  std::string csv = "# ISO 230-2 axis values, " + std::string(u.deviation) + "\n";
  csv += fmt::format("# A_forward: {}\n# A_backward: {}\n# A: {}\n# B: {}\n# B_mean: {}\n", r.accuracyForward * s, r.accuracyBackward * s,
                     r.accuracy * s, r.reversal * s, r.meanReversal * s);
  csv += fmt::format("# E_forward: {}\n# E_backward: {}\n# E: {}\n# M: {}\n# R_forward: {}\n# R_backward: {}\n# R: {}\n",
                     r.systematicForward * s, r.systematicBackward * s, r.systematic * s, r.meanDeviationRange * s,
                     r.repeatabilityForward * s, r.repeatabilityBackward * s, r.repeatability * s);
  csv += fmt::format("target_{0},mean_forward_{1},mean_backward_{1},mean_{1},reversal_{1},s_forward_{1},s_backward_{1},"
                     "repeatability_forward_{1},repeatability_backward_{1},repeatability_{1}\n",
                     u.target, u.deviation);
  for (const auto& p : r.positions) {
    human += fmt::format("{:>12.4f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f}\n", p.target * u.targetScale,
                         p.meanForward * s, p.meanBackward * s, p.mean * s, p.reversal * s, p.sForward * s, p.sBackward * s,
                         p.repeatabilityForward * s, p.repeatabilityBackward * s, p.repeatability * s);
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", p.target * u.targetScale, p.meanForward * s, p.meanBackward * s, p.mean * s,
                       p.reversal * s, p.sForward * s, p.sBackward * s, p.repeatabilityForward * s, p.repeatabilityBackward * s,
                       p.repeatability * s);
  }
  const auto U = [&](const char* q) { return e.uncertainty.at(q).expanded * s; };
  human += fmt::format("\nAxis values ({})                          ↑          ↓   bidirectional   U (k = 2)\n", u.deviation);
  human += fmt::format("  accuracy of positioning A            {:9.3f}  {:9.3f}  {:9.3f}      {:6.3f}\n", r.accuracyForward * s,
                       r.accuracyBackward * s, r.accuracy * s, U("A"));
  human += fmt::format("  systematic positional deviation E    {:9.3f}  {:9.3f}  {:9.3f}      {:6.3f}\n", r.systematicForward * s,
                       r.systematicBackward * s, r.systematic * s, U("E"));
  human += fmt::format("  repeatability of positioning R       {:9.3f}  {:9.3f}  {:9.3f}      {:6.3f}\n", r.repeatabilityForward * s,
                       r.repeatabilityBackward * s, r.repeatability * s, U("R"));
  human += fmt::format("  range of mean bidirectional deviation M                      {:9.3f}      {:6.3f}\n", r.meanDeviationRange * s, U("M"));
  human += fmt::format("  reversal value B                                             {:9.3f}      {:6.3f}\n", r.reversal * s, U("B"));
  human += fmt::format("  mean reversal value (mean of B_i)                            {:9.3f}\n", r.meanReversal * s);
  human += formatBudget(e, u);
  for (const auto& q : e.uncertainty.quantities) csv += fmt::format("# U_{}: {}\n", q.quantity, q.expanded * s);
  for (const auto& note : r.notes) std::cerr << "mtacc: note: " << note << "\n";
  emit(o, toJson(e), human, csv);
}

}  // namespace

void addPositioningCommand(const CommandLine& app) {
  auto o = std::make_shared<PositioningCliOptions>();
  auto cmd = app.subcommand("positioning", "ISO 230-2 accuracy and repeatability of positioning of a linear or rotary axis");
  cmd.alias("iso230-2");
  cmd.outputOptions(*o);
  cmd.schemaOptions(positioningSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
