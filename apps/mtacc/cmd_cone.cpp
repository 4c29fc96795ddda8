// mtacc cone MACHINE: the 5-axis cone-frustum test piece of seed 000 — tool path and NC
// program, axis motions, single-error influences, Monte Carlo over tolerance limits.
#include <fmt/format.h>

#include <iostream>
#include <unistd.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/atomic_file.hpp"
#include "mtacc/machine/machine_yaml.hpp"
#include "mtacc/procedures/monte_carlo.hpp"

namespace mtacc::cli {
namespace {

struct ConeOptions : MachineOptions {
  std::string preset;
  double alpha = 45, beta = 30, radius = 40, gamma = 0;
  std::string centre = "-65,0,150";
  bool faceMilling = false;
  int points = 720;
  double chordTolerance = 0;
  std::string branch = "negative";
  double feed = 500;
  bool singleErrors = false;
  int monteCarlo = 0;
  std::string limits;
  std::uint64_t seed = 1;
  std::string gcode;
  std::string clData;
};

std::string formatAxisValue(const Axis& a, double v) { return fmt::format("{:.4f}", a.isRotary() ? v / kDeg : v); }

std::string gcodeProgram(const Machine& m, const ConeSpec& s, const ConeMotion& motion, double feed) {
  std::string g = fmt::format("; mtacc cone-frustum test piece (seed 000): alpha {:g} deg, beta {:g} deg, r {:g} mm\n",
                              s.alpha / kDeg, s.beta / kDeg, s.radius);
  g += fmt::format("; machine {}; axis positions in mm and deg; TCP feed {:g} mm/min\nG90 G94\n", m.name, feed);
  for (size_t i = 0; i < motion.q.size(); ++i) {
    const auto& q = motion.q[i];
    std::string line = fmt::format("N{} G01", 10 * (i + 1));
    for (int k = 0; k < m.commandedCount(); ++k) {
      const double v = q[static_cast<size_t>(k)];
      line += fmt::format(" {}{}", m.axes[static_cast<size_t>(k)].name, formatAxisValue(m.axes[static_cast<size_t>(k)], v));
    }
    if (i == 0) line += fmt::format(" F{:g}", feed);
    g += line + "\n";
  }
  return g + "M30\n";
}

void run(const ConeOptions& o) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  ConeSpec spec;
  if (!o.preset.empty()) {
    const auto p = conePreset(o.preset);
    if (!p) throw InputError(InputLocation{"", 0, "--preset"}, "unknown preset '" + o.preset + "' (tilting-table, swivel-head, double-pivot, nas979)");
    spec = *p;
  } else {
    spec.alpha = o.alpha * kDeg;
    spec.beta = o.beta * kDeg;
    spec.radius = o.radius;
    spec.gamma = o.gamma * kDeg;
    spec.centre = parseVector(o.centre, "--centre");
  }
  spec.faceMilling = o.faceMilling;
  if (!(spec.radius > 0)) throw InputError(InputLocation{"", 0, "--radius"}, "must be positive");
  if (!(o.feed > 0)) throw InputError(InputLocation{"", 0, "--feed"}, "must be positive");
  const int n = o.chordTolerance > 0 ? pointsForChordTolerance(spec, o.chordTolerance) : o.points;
  if (n < 8 || n > 1000000) throw InputError(InputLocation{"", 0, "--points"}, "must be between 8 and 1000000");
  const auto nominal = compileNominal(loaded.machine);
  const auto path = conePath(spec, n);
  const auto motion = coneMotion(nominal, spec, path, parseTiltBranch(o.branch), o.feed);
  const auto closed = rotaryRangesClosedForm(spec.alpha, spec.beta);

  nlohmann::json j;
  j["machine"] = m.name;
  j["cone"] = {{"alpha_deg", spec.alpha / kDeg}, {"beta_deg", spec.beta / kDeg}, {"radius_mm", spec.radius},
               {"gamma_deg", spec.gamma / kDeg}, {"centre_mm", {spec.centre.x(), spec.centre.y(), spec.centre.z()}},
               {"points", n}, {"milling", spec.faceMilling ? "face" : "end"}};
  std::string human = fmt::format("Cone frustum on {}: alpha {:g} deg, beta {:g} deg, r {:g} mm, centre ({:g}, {:g}, {:g}) mm, "
                                  "{} points, feed {:g} mm/min\n",
                                  m.name, spec.alpha / kDeg, spec.beta / kDeg, spec.radius, spec.centre.x(), spec.centre.y(),
                                  spec.centre.z(), n, o.feed);
  for (const auto& w : motion.warnings) {
    human += "warning: " + w + "\n";
    j["warnings"].push_back(w);
  }
  human += fmt::format("\n{:<5} {:>11} {:>11} {:>11} {:>10} {:>14} {:>16}\n", "axis", "min", "max", "range", "reversals",
                       "max speed /s", "max accel. /s^2");
  std::string csv = "axis,min,max,range,reversals,max_speed_per_s,max_acceleration_per_s2\n";
  for (size_t k = 0; k < motion.axes.size(); ++k) {
    const auto& a = motion.axes[k];
    const bool rot = m.axes[k].isRotary();
    const double f = rot ? 1.0 / kDeg : 1.0;
    const char* unit = rot ? "deg" : "mm";
    human += fmt::format("{:<5} {:>11.3f} {:>11.3f} {:>11.3f} {:>10} {:>10.3f} {:<3} {:>12.3f} {:<3}\n", a.axis, a.min * f,
                         a.max * f, a.range * f, a.reversalsPhi.size(), a.maxSpeed * f / 60, unit,
                         a.maxAcceleration * f / 3600, unit);
    csv += fmt::format("{},{},{},{},{},{},{}\n", a.axis, a.min * f, a.max * f, a.range * f, a.reversalsPhi.size(),
                       a.maxSpeed * f / 60, a.maxAcceleration * f / 3600);
    std::vector<double> rev;
    for (double p : a.reversalsPhi) rev.push_back(p / kDeg);
    j["axes"].push_back({{"axis", a.axis}, {"unit", unit}, {"min", a.min * f}, {"max", a.max * f}, {"range", a.range * f},
                         {"reversals_phi_deg", rev}, {"max_speed_per_s", a.maxSpeed * f / 60},
                         {"max_acceleration_per_s2", a.maxAcceleration * f / 3600}});
  }
  human += fmt::format("closed form (seed 000 Table 3.1, {}): tilt {:.3f} .. {:.3f} deg (range {:.3f}), rotary range {:.3f} deg\n",
                       closed.caseName, closed.tiltMin / kDeg, closed.tiltMax / kDeg, closed.tiltRange / kDeg,
                       closed.rotaryRange / kDeg);
  j["closed_form"] = {{"case", closed.caseName}, {"tilt_min_deg", closed.tiltMin / kDeg}, {"tilt_max_deg", closed.tiltMax / kDeg},
                      {"tilt_range_deg", closed.tiltRange / kDeg}, {"rotary_range_deg", closed.rotaryRange / kDeg}};

  if (!nonZeroParameters(m, loaded.errors).empty()) {
    const auto actual = compile(loaded.machine, loaded.errors);
    const auto exact = coneFormErrorExact(actual, spec, path, motion);
    const auto first = coneFormErrorFirstOrder(actual, nominal, path, motion);
    human += fmt::format("\nequivalent cone form error of the machine's errors: {:.3f} um (first order {:.3f} um)\n",
                         exact.formError * 1e3, first.formError * 1e3);
    j["form_error_um"] = exact.formError * 1e3;
    j["form_error_first_order_um"] = first.formError * 1e3;
  }
  if (o.singleErrors) {
    struct Row {
      std::string name;
      double formError;
      FormErrorType type;
    };
    std::vector<Row> rows;
    for (const auto& p : nonZeroParameters(m, loaded.errors)) {
      ErrorModel single = loaded.errors;
      for (const auto& q : parameterCatalogue(m, single))
        if (q.name != p.name) setParameterValue(single, q, 0.0);
      const auto r = coneFormErrorExact(compile(loaded.machine, single), spec, path, motion);
      rows.push_back({p.name, r.formError, formErrorType(r.deviation)});
    }
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.formError > b.formError; });
    human += "\nsingle errors (each alone at its value): equivalent cone form error, form type (seed 000 §3.10.4)\n";
    for (const auto& r : rows) {
      human += fmt::format("  {:<10} {:8.3f} um  {}\n", r.name, r.formError * 1e3, toString(r.type));
      j["single_errors"].push_back({{"error", r.name}, {"form_error_um", r.formError * 1e3}, {"type", toString(r.type)}});
    }
  }
  if (o.monteCarlo > 0) {
    const std::string file = o.limits.empty() ? bundledDataDir() + "/limits/seed000-table3.9.yaml" : o.limits;
    const auto limits = loadErrorLimits(m, file);
    const bool tty = !o.json && isatty(2);
    const auto mc = coneMonteCarlo(loaded.machine, limits, spec, path, motion, o.monteCarlo, o.seed, [&](int d, int t) {
      if (tty) std::cerr << fmt::format("\rmonte carlo: {}/{} samples", d, t) << (d == t ? "\n" : "") << std::flush;
    });
    const auto& s = mc.statistics;
    human += fmt::format("\nMonte Carlo, {} samples within {}: equivalent cone form error [um]\n"
                         "  min {:.2f}  lower quartile {:.2f}  median {:.2f}  upper quartile {:.2f}  max {:.2f}\n",
                         o.monteCarlo, file, s.min * 1e3, s.lowerQuartile * 1e3, s.median * 1e3, s.upperQuartile * 1e3,
                         s.max * 1e3);
    j["monte_carlo"] = {{"samples", o.monteCarlo}, {"limits", file}, {"seed", o.seed},
                        {"min_um", s.min * 1e3}, {"lower_quartile_um", s.lowerQuartile * 1e3}, {"median_um", s.median * 1e3},
                        {"upper_quartile_um", s.upperQuartile * 1e3}, {"max_um", s.max * 1e3}};
  }
  if (!o.clData.empty()) {
    std::string cl = "phi_deg,x,y,z,i,j,k,nx,ny,nz\n";
    for (size_t i = 0; i < path.phi.size(); ++i) {
      const auto &p = path.points[i], &t = path.tools[i], &nv = path.normals[i];
      cl += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", path.phi[i] / kDeg, p.x(), p.y(), p.z(), t.x(), t.y(), t.z(), nv.x(),
                        nv.y(), nv.z());
    }
    writeFileAtomically(o.clData, cl);
    human += "\nCL data written: " + o.clData + "\n";
  }
  if (!o.gcode.empty()) {
    writeFileAtomically(o.gcode, gcodeProgram(m, spec, motion, o.feed));
    human += "\nNC program written: " + o.gcode + "\n";
  }
  emit(o, j, human, csv);
}

}  // namespace

void addConeCommand(CLI::App& app) {
  auto o = std::make_shared<ConeOptions>();
  auto* cmd = app.add_subcommand("cone", "5-axis cone-frustum test piece (seed 000): path, axis motions, error influence");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--preset", o->preset, "tilting-table, swivel-head, double-pivot (seed 000 §3.6) or nas979");
  cmd->add_option("--alpha", o->alpha, "cone angle (half apex angle) [deg], negative: upside down (default 45)");
  cmd->add_option("--beta", o->beta, "inclination of the cone axis [deg] (default 30)");
  cmd->add_option("--radius", o->radius, "TCP path radius [mm] (default 40)");
  cmd->add_option("--centre", o->centre, "path centre x,y,z in the workpiece frame [mm] (default -65,0,150)");
  cmd->add_option("--gamma", o->gamma, "turn of the inclined cone about the workpiece z [deg] (default 0)");
  cmd->add_flag("--face-milling", o->faceMilling, "tool normal to the cone surface instead of along the slant");
  cmd->add_option("--points", o->points, "points around the path (default 720)");
  cmd->add_option("--chord-tolerance", o->chordTolerance, "choose the points for this chord error [mm] instead");
  cmd->add_option("--branch", o->branch, "tilt branch at phi = 0: negative (seed 000), positive or auto");
  cmd->add_option("--feed", o->feed, "contouring feed [mm/min] for axis speeds (default 500)");
  cmd->add_flag("--single-errors", o->singleErrors, "form error of each non-zero error alone");
  cmd->add_option("--monte-carlo", o->monteCarlo, "number of Monte Carlo samples (e.g. 1000)");
  cmd->add_option("--limits", o->limits, "limits file (default: seed 000 Table 3.9)");
  cmd->add_option("--seed", o->seed, "random seed of the Monte Carlo (default 1)");
  cmd->add_option("--gcode", o->gcode, "write the NC program of the path to FILE");
  cmd->add_option("--cl", o->clData, "write the CL data (phi, TCP, tool vector, surface normal) to FILE.csv");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
