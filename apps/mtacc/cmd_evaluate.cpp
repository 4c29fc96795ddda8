// mtacc evaluate: a ballbar file's ISO 230-4 circular deviation, radial deviation and
// hysteresis, its eccentricity and the usual diagnostics; an R-test file's displacements about
// the axis that moves (ISO 10791-6).
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/measurement_runs.hpp"

namespace mtacc::cli {
namespace {

struct EvaluateCliOptions : MachineOptions {
  OptionValues values;
};

void emitRTest(const EvaluateCliOptions& o, const std::string& data, const RTestRunEvaluation& e) {
  const auto& r = e.result;
  const Axis& axis = e.machine->axes[static_cast<size_t>(r.movingAxis)];
  const double unit = axis.isRotary() ? 1.0 / kDeg : 1.0;
  std::string human = fmt::format("R-test run '{}' ({} poses, {} from {:g} to {:g} {}) from {}\n\n", e.run.name, e.run.poses(), axis.name,
                                  r.position.minCoeff() * unit, r.position.maxCoeff() * unit, axis.isRotary() ? "deg" : "mm", data);
  const auto& a = r.aboutTheAxis;
  human += fmt::format("{:>10}  {:>9} {:>9} {:>9}", axis.name, "dX", "dY", "dZ");
  if (a) human += fmt::format("  {:>9} {:>9} {:>9}", "radial", "axial", "tangent.");
  human += "   (um)\n";
  std::string csv = fmt::format("{}_{},dx_um,dy_um,dz_um{}\n", axis.name, axis.isRotary() ? "deg" : "mm",
                                a ? ",radial_um,axial_um,tangential_um" : "");
  for (Eigen::Index i = 0; i < r.displacement.rows(); ++i) {
    const auto d = r.displacement.row(i) * 1e3;
    human += fmt::format("{:>10.3f}  {:>9.3f} {:>9.3f} {:>9.3f}", r.position[i] * unit, d[0], d[1], d[2]);
    csv += fmt::format("{},{},{},{}", r.position[i] * unit, d[0], d[1], d[2]);
    if (a) {
      const auto c = a->components.row(i) * 1e3;
      human += fmt::format("  {:>9.3f} {:>9.3f} {:>9.3f}", c[0], c[1], c[2]);
      csv += fmt::format(",{},{},{}", c[0], c[1], c[2]);
    }
    human += "\n";
    csv += "\n";
  }
  human += fmt::format("{:>10}  {:>9.3f} {:>9.3f} {:>9.3f}", "range", r.range.x() * 1e3, r.range.y() * 1e3, r.range.z() * 1e3);
  if (a) human += fmt::format("  {:>9.3f} {:>9.3f} {:>9.3f}", a->range.x() * 1e3, a->range.y() * 1e3, a->range.z() * 1e3);
  human += "\n";
  if (a)
    human += fmt::format("\nthe ball's circle about {}: radius {:.3f} mm, centre ({:.3f}, {:.3f}, {:.3f}) mm, "
                         "direction ({:.4f}, {:.4f}, {:.4f}) at the first pose; tangential along the axis's positive motion\n",
                         axis.name, a->radius, a->point.x(), a->point.y(), a->point.z(), a->direction.x(), a->direction.y(),
                         a->direction.z());
  else
    human += "\nno rotary axis moves, or its ball is on its line: components along X, Y, Z only\n";
  emit(o, toJson(e), human, csv);
}

void run(const EvaluateCliOptions& o) {
  const std::string data = *OptionReader(evaluationSchema(), o.values).text("data");
  const auto evaluation = evaluateMeasurementFile(loadMachineSetup(o.source), data);
  if (const auto* rtest = std::get_if<RTestRunEvaluation>(&evaluation)) return emitRTest(o, data, *rtest);
  const auto& e = std::get<CircularEvaluation>(evaluation);
  const auto& r = e.result;
  const auto& g = r.diagnostics;
  const Vec3 ecc = r.eccentricity.eccentricity * 1e3;
  std::string human = fmt::format("Ballbar run '{}' ({} points, L = {:g} mm) from {}\n\n", e.run.name, e.run.poses(),
                                  e.run.setup.length, data);
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

void addEvaluateCommand(const CommandLine& app) {
  auto o = std::make_shared<EvaluateCliOptions>();
  auto cmd = app.subcommand("evaluate", "ISO 230-4 evaluation and diagnostics of a ballbar file, or an R-test run about its axis");
  cmd.machineOptions(*o);
  cmd.schemaOptions(evaluationSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
