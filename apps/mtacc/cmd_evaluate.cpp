// mtacc evaluate: a ballbar file's ISO 230-4 circular deviation, radial deviation and
// hysteresis, its eccentricity and the usual diagnostics.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/measurement_runs.hpp"

namespace mtacc::cli {
namespace {

struct EvaluateCliOptions : MachineOptions {
  std::string data;
};

void run(const EvaluateCliOptions& o) {
  const auto e = evaluateBallbarFile(loadMachineSetup(o.source), o.data);
  const auto& r = e.result;
  const auto& g = r.diagnostics;
  const Vec3 ecc = r.eccentricity.eccentricity * 1e3;
  std::string human = fmt::format("Ballbar run '{}' ({} points, L = {:g} mm) from {}\n\n", e.run.name, e.run.poses(),
                                  e.run.setup.length, o.data);
  human += fmt::format("Eccentricity (least-squares first harmonics)  x {:8.3f}  y {:8.3f}  z {:8.3f} um\n\n", ecc.x(), ecc.y(),
                       ecc.z());
  human += "ISO 230-4                 circular deviation G   radial deviation F (min .. max)\n";
  std::string csv = "quantity,value,unit\n";
  csv += fmt::format("eccentricity_x,{},um\neccentricity_y,{},um\neccentricity_z,{},um\n", ecc.x(), ecc.y(), ecc.z());
  for (const auto& d : r.directions) {
    human += fmt::format("  {:<24}{:>14.3f} um     {:8.3f} .. {:8.3f} um\n", d.sense > 0 ? "counter-clockwise" : "clockwise",
                         d.circularDeviation * 1e3, d.radialMin * 1e3, d.radialMax * 1e3);
    csv += fmt::format("circular_deviation_{0},{1},um\nradial_deviation_min_{0},{2},um\nradial_deviation_max_{0},{3},um\n",
                       d.sense > 0 ? "ccw" : "cw", d.circularDeviation * 1e3, d.radialMin * 1e3, d.radialMax * 1e3);
  }
  if (r.bothDirections) {
    human += fmt::format("  circular hysteresis H {:>16.3f} um\n", r.hysteresis * 1e3);
    csv += fmt::format("hysteresis,{},um\nservo_mismatch,{},ms\n", r.hysteresis * 1e3, g.servoMismatch * 1e3);
  }
  human += "\nDiagnostics (fitted to both directions; a, b = the plot plane's axes)\n";
  human += fmt::format("  squareness (angle a-b minus 90 deg) {:10.2f} urad\n", g.squareness * 1e6);
  human += fmt::format("  scale mismatch s_a - s_b            {:10.2f} um/m\n", g.scaleMismatch * 1e6);
  if (r.bothDirections) human += fmt::format("  servo mismatch lag_a - lag_b        {:10.3f} ms\n", g.servoMismatch * 1e3);
  human += fmt::format("  backlash a / b                      {:10.3f} / {:.3f} um\n", g.backlashA * 1e3, g.backlashB * 1e3);
  human += fmt::format("  reversal spikes a / b               {:10.3f} / {:.3f} um\n", g.reversalSpikeA * 1e3, g.reversalSpikeB * 1e3);
  human += fmt::format("  residual after the fit (RMS)        {:10.3f} um\n", g.residualRms * 1e3);
  csv += fmt::format("squareness,{},urad\nscale_mismatch,{},um/m\nbacklash_a,{},um\nbacklash_b,{},um\n", g.squareness * 1e6,
                     g.scaleMismatch * 1e6, g.backlashA * 1e3, g.backlashB * 1e3);
  csv += fmt::format("reversal_spike_a,{},um\nreversal_spike_b,{},um\n", g.reversalSpikeA * 1e3, g.reversalSpikeB * 1e3);
  emit(o, toJson(e), human, csv);
}

}  // namespace

void addEvaluateCommand(CLI::App& app) {
  auto o = std::make_shared<EvaluateCliOptions>();
  auto* cmd = app.add_subcommand("evaluate", "ISO 230-4 evaluation and diagnostics of a ballbar file");
  addMachineOptions(*cmd, *o);
  cmd->add_option("data", o->data, "Ballbar CSV (docs/file-formats.md)")->required();
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
