// mtacc cone MACHINE: the 5-axis cone-frustum test piece of Bossoni 2009 — tool path and NC
// program, axis motions, single-error influences, Monte Carlo over tolerance limits.
#include <fmt/format.h>

#include <iostream>
#include <unistd.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/test_piece_files.hpp"

namespace mtacc::cli {
namespace {

struct ConeCliOptions : MachineOptions {
  OptionValues values;
};

void run(const ConeCliOptions& o) {
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  ConeStudyRequest options = coneStudyRequest(m, o.values);
  const bool tty = !o.json && isatty(2);
  options.progress = [tty](int d, int t) {
    if (tty) std::cerr << fmt::format("\rmonte carlo: {}/{} samples", d, t) << (d == t ? "\n" : "") << std::flush;
  };
  const auto s = coneStudy(setup, options);
  const ConeSpec& spec = s.options.spec;
  std::string human = fmt::format("Cone frustum on {}: alpha {:g} deg, beta {:g} deg, r {:g} mm, centre ({:g}, {:g}, {:g}) mm, "
                                  "{} points, feed {:g} mm/min\n",
                                  m.name, spec.alpha / kDeg, spec.beta / kDeg, spec.radius, spec.centre.x(), spec.centre.y(),
                                  spec.centre.z(), s.options.points, s.options.feed);
  for (const auto& w : s.motion.warnings) human += "warning: " + w + "\n";
  human += fmt::format("\n{:<5} {:>11} {:>11} {:>11} {:>10} {:>14} {:>16}\n", "axis", "min", "max", "range", "reversals",
                       "max speed /s", "max accel. /s^2");
  std::string csv = "axis,min,max,range,reversals,max_speed_per_s,max_acceleration_per_s2\n";
  for (size_t k = 0; k < s.motion.axes.size(); ++k) {
    const auto& a = s.motion.axes[k];
    const bool rotary = m.axes[k].isRotary();
    const double f = rotary ? 1.0 / kDeg : 1.0;
    const char* unit = rotary ? "deg" : "mm";
    human += fmt::format("{:<5} {:>11.3f} {:>11.3f} {:>11.3f} {:>10} {:>10.3f} {:<3} {:>12.3f} {:<3}\n", a.axis, a.min * f,
                         a.max * f, a.range * f, a.reversalsPhi.size(), a.maxSpeed * f / 60, unit, a.maxAcceleration * f / 3600, unit);
    csv += fmt::format("{},{},{},{},{},{},{}\n", a.axis, a.min * f, a.max * f, a.range * f, a.reversalsPhi.size(),
                       a.maxSpeed * f / 60, a.maxAcceleration * f / 3600);
  }
  const auto& c = s.closedForm;
  human += fmt::format("closed form (Bossoni 2009 Table 3.1, {}): tilt {:.3f} .. {:.3f} deg (range {:.3f}), rotary range {:.3f} deg\n",
                       c.caseName, c.tiltMin / kDeg, c.tiltMax / kDeg, c.tiltRange / kDeg, c.rotaryRange / kDeg);
  if (s.form)
    human += fmt::format("\nequivalent cone form error of the machine's errors: {:.3f} um (first order {:.3f} um)\n",
                         s.form->formError * 1e3, s.firstOrderFormError * 1e3);
  if (!s.singleErrors.empty())
    human += "\nsingle errors (each alone at its value): equivalent cone form error, form type (Bossoni 2009 §3.10.4)\n";
  for (const auto& e : s.singleErrors)
    human += fmt::format("  {:<10} {:8.3f} um  {}\n", e.name, e.form.formError * 1e3, toString(e.type));
  if (s.monteCarlo) {
    const auto& st = s.monteCarlo->statistics;
    human += fmt::format("\nMonte Carlo, {} samples within {}: equivalent cone form error [um]\n"
                         "  min {:.2f}  lower quartile {:.2f}  median {:.2f}  upper quartile {:.2f}  max {:.2f}\n",
                         s.options.monteCarlo, s.limits.file, st.min * 1e3, st.lowerQuartile * 1e3, st.median * 1e3,
                         st.upperQuartile * 1e3, st.max * 1e3);
    for (const auto& n : s.monteCarlo->notes) human += "  note: " + n + "\n";
  }
  if (s.measured) {
    const auto& m = *s.measured;
    human += fmt::format("\nmeasured cone ({}): {} cone and {} cylinder sections\n", s.options.measuredFile, m.cone.size(), m.cylinder.size());
    human += fmt::format("  {:<10} {:>12} {:>10} {:>16} {:>16} {:>14}\n", "section", "diameter mm", "height mm", "circularity LS um",
                         "minimum zone um", "axis offset um");
    for (const auto* list : {&m.cone, &m.cylinder})
      for (const auto& c : *list)
        human += fmt::format("  {:<10} {:>12.4f} {:>10.3f} {:>16.3f} {:>16.3f} {:>14.3f}\n", c.name, 2 * c.circle.radius, c.height,
                             c.leastSquaresCircularity * 1e3, c.minimumZoneCircularity * 1e3, c.axisOffset * 1e3);
    if (m.halfAngle) human += fmt::format("  best-fit cone: half angle {:.4f} deg, form error {:.3f} um\n", *m.halfAngle / kDeg, *m.formError * 1e3);
    if (m.squareness) human += fmt::format("  squareness of the cone axis to plane A {:.1f} urad, flatness of A {:.3f} um\n", *m.squareness * 1e6, m.flatness * 1e3);
    if (m.coaxiality) human += fmt::format("  coaxiality with cylinder C {:.3f} um\n", *m.coaxiality * 1e3);
    const auto& c = *s.comparison;
    human += fmt::format("  section {} beside the simulation: normal form {:.3f} um measured, {:.3f} um simulated, RMS difference {:.3f} um\n",
                         m.cone[c.section].name, c.measuredRange * 1e3, c.simulatedRange * 1e3, c.rmsDifference * 1e3);
  }
  for (const auto& line : writeConeFiles(s, coneFiles(o.values))) human += "\n" + line + "\n";
  emit(o, toJson(s), human, csv);
}

}  // namespace

void addConeCommand(const CommandLine& app) {
  auto o = std::make_shared<ConeCliOptions>();
  auto cmd = app.subcommand("cone", "5-axis cone-frustum test piece (Bossoni 2009): path, axis motions, error influence");
  cmd.machineOptions(*o);
  cmd.schemaOptions(coneSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
