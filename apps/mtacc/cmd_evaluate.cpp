// mtacc evaluate: a ballbar file's ISO 230-4 circular deviation, radial deviation and
// hysteresis, its eccentricity and the usual diagnostics.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/measurement/circular_test.hpp"
#include "mtacc/measurement/measurement_csv.hpp"

namespace mtacc::cli {
namespace {

struct EvaluateOptions : MachineOptions {
  std::string data;
};

void run(const EvaluateOptions& o) {
  const auto loaded = load(o);
  const auto nominal = compileNominal(loaded.machine);
  const auto data = readMeasurementCsv(nominal, o.data);
  CircularTestResult r;
  try {
    r = evaluateCircularTest(data);
  } catch (const std::invalid_argument& e) {
    throw InputError(InputLocation{o.data, 0, ""}, e.what());
  }
  const auto& g = r.diagnostics;
  const Vec3 e = r.eccentricity.eccentricity;
  nlohmann::json j;
  j["file"] = o.data;
  j["run"] = data.name;
  j["points"] = data.poses();
  j["length_mm"] = data.setup.length;
  j["eccentricity_um"] = {e.x() * 1e3, e.y() * 1e3, e.z() * 1e3};
  j["offset_um"] = r.eccentricity.offset * 1e3;
  std::string human = fmt::format("Ballbar run '{}' ({} points, L = {:g} mm) from {}\n\n", data.name, data.poses(),
                                  data.setup.length, o.data);
  human += fmt::format("Eccentricity (least-squares first harmonics)  x {:8.3f}  y {:8.3f}  z {:8.3f} um\n\n",
                       e.x() * 1e3, e.y() * 1e3, e.z() * 1e3);
  human += "ISO 230-4                 circular deviation G   radial deviation F (min .. max)\n";
  for (const auto& d : r.directions) {
    human += fmt::format("  {:<24}{:>14.3f} um     {:8.3f} .. {:8.3f} um\n",
                         d.sense > 0 ? "counter-clockwise" : "clockwise", d.circularDeviation * 1e3, d.radialMin * 1e3,
                         d.radialMax * 1e3);
    j["directions"].push_back({{"sense", d.sense > 0 ? "ccw" : "cw"},
                               {"circular_deviation_um", d.circularDeviation * 1e3},
                               {"radial_deviation_min_um", d.radialMin * 1e3},
                               {"radial_deviation_max_um", d.radialMax * 1e3}});
  }
  if (r.bothDirections) human += fmt::format("  circular hysteresis H {:>16.3f} um\n", r.hysteresis * 1e3);
  j["hysteresis_um"] = r.bothDirections ? nlohmann::json(r.hysteresis * 1e3) : nlohmann::json(nullptr);
  human += "\nDiagnostics (fitted to both directions; a, b = the plot plane's axes)\n";
  human += fmt::format("  squareness (angle a-b minus 90 deg) {:10.2f} urad\n", g.squareness * 1e6);
  human += fmt::format("  scale mismatch s_a - s_b            {:10.2f} um/m\n", g.scaleMismatch * 1e6);
  if (r.bothDirections) human += fmt::format("  servo mismatch lag_a - lag_b        {:10.3f} ms\n", g.servoMismatch * 1e3);
  human += fmt::format("  backlash a / b                      {:10.3f} / {:.3f} um\n", g.backlashA * 1e3, g.backlashB * 1e3);
  human += fmt::format("  reversal spikes a / b               {:10.3f} / {:.3f} um\n", g.reversalSpikeA * 1e3,
                       g.reversalSpikeB * 1e3);
  human += fmt::format("  residual after the fit (RMS)        {:10.3f} um\n", g.residualRms * 1e3);
  j["diagnostics"] = {{"squareness_urad", g.squareness * 1e6},
                      {"scale_mismatch_um_per_m", g.scaleMismatch * 1e6},
                      {"servo_mismatch_ms", r.bothDirections ? nlohmann::json(g.servoMismatch * 1e3) : nlohmann::json(nullptr)},
                      {"backlash_a_um", g.backlashA * 1e3},
                      {"backlash_b_um", g.backlashB * 1e3},
                      {"reversal_spike_a_um", g.reversalSpikeA * 1e3},
                      {"reversal_spike_b_um", g.reversalSpikeB * 1e3},
                      {"residual_rms_um", g.residualRms * 1e3}};
  std::string csv = "quantity,value,unit\n";
  csv += fmt::format("eccentricity_x,{},um\neccentricity_y,{},um\neccentricity_z,{},um\n", e.x() * 1e3, e.y() * 1e3, e.z() * 1e3);
  for (const auto& d : r.directions)
    csv += fmt::format("circular_deviation_{0},{1},um\nradial_deviation_min_{0},{2},um\nradial_deviation_max_{0},{3},um\n",
                       d.sense > 0 ? "ccw" : "cw", d.circularDeviation * 1e3, d.radialMin * 1e3, d.radialMax * 1e3);
  if (r.bothDirections) csv += fmt::format("hysteresis,{},um\nservo_mismatch,{},ms\n", r.hysteresis * 1e3, g.servoMismatch * 1e3);
  csv += fmt::format("squareness,{},urad\nscale_mismatch,{},um/m\nbacklash_a,{},um\nbacklash_b,{},um\n", g.squareness * 1e6,
                     g.scaleMismatch * 1e6, g.backlashA * 1e3, g.backlashB * 1e3);
  csv += fmt::format("reversal_spike_a,{},um\nreversal_spike_b,{},um\n", g.reversalSpikeA * 1e3, g.reversalSpikeB * 1e3);
  emit(o, j, human, csv);
}

}  // namespace

void addEvaluateCommand(CLI::App& app) {
  auto o = std::make_shared<EvaluateOptions>();
  auto* cmd = app.add_subcommand("evaluate", "ISO 230-4 evaluation and diagnostics of a ballbar file");
  addMachineOptions(*cmd, *o);
  cmd->add_option("data", o->data, "Ballbar CSV (docs/file-formats.md)")->required();
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
