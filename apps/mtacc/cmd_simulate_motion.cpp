// mtacc simulate motion: Andolfatto et al. 2011's virtual machine — an NC program run at each feed of a ladder
// through interpolator and servo loops, with geometric errors, drift, structural deflection and
// instrument noise; the recorded signals, the truth and the decomposition set written to a folder.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

namespace mtacc::cli {
namespace {

struct MotionCliOptions : MachineOptions {
  MotionSimulationRequest motion;
  std::string noise = "0 um";
  std::uint64_t seed = 1;
  double clockOffsetMs = 18, jerkTimeMs = 20;
  std::string signalFormat = "csv";
};

}  // namespace

void addSimulateMotionCommand(CLI::App& simulate) {
  auto o = std::make_shared<MotionCliOptions>();
  auto* motion = simulate.add_subcommand("motion", "Andolfatto et al. 2011's virtual machine: an NC program run at each feed of a ladder, with servo loops, "
                                                "geometric errors, drift, structural deflection and instrument noise; the recorded signals, "
                                                "the truth and the decomposition set written to a directory");
  motion->add_option("machine", o->source.machine, "Machine file or bundled name")->required();
  motion->add_option("--errors", o->source.errorsFile, "Error description (YAML); default: the machine file's errors");
  motion->add_flag("--json", o->json, "Summary as JSON on stdout");
  motion->add_option("--noise", o->noise, "Standard deviation of the instrument's noise per component, e.g. 0.2um")->capture_default_str();
  motion->add_option("--seed", o->seed, "Random seed of the noise")->capture_default_str();
  motion->add_option("--program", o->motion.program, "NC program (G-code) in axis positions; its F words are replaced by each feed")->required();
  motion->add_option("--feeds", o->motion.feeds, "feeds in mm/min (FGROUP: mm and deg on one path length)")->delimiter(',')->capture_default_str()
      ->check(CLI::Range(1e-3, 1e6));
  motion->add_option("--structure", o->motion.structure, "structure model (YAML or bundled name, e.g. wcayfxzt-compact) for the dynamic error");
  motion->add_option("--acceleration", o->motion.limits.acceleration, "interpolator's acceleration limit, path units/s^2")->capture_default_str()
      ->check(CLI::Range(1e-3, 1e7));
  motion->add_option("--jerk-time-ms", o->jerkTimeMs, "moving-average filter of the interpolator, ms")->capture_default_str()->check(CLI::Range(0.0, 1e3));
  motion->add_option("--kv", o->motion.positionGains, "position loop gain, 1/s: one for every axis or one per axis, e.g. 40,45,50,35,30")
      ->delimiter(',')->capture_default_str()->check(CLI::Range(1e-3, 1e4));
  motion->add_option("--feed-forward", o->motion.feedForwards, "velocity feed-forward, 0..1: one for every axis or one per axis")->delimiter(',')
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  motion->add_option("--format", o->signalFormat, "signal files: csv or npy (NumPy structured arrays)")->capture_default_str();
  motion->add_option("--clock-offset-ms", o->clockOffsetMs, "offset of the command recording's clock, ms")->capture_default_str()
      ->check(CLI::Range(-1e4, 1e4));
  motion->add_option("-o,--output", o->motion.folder, "Directory to write the signal files and set.yaml into")->required();
  motion->callback([o] {
    auto request = o->motion;
    request.noise = parseQuantityAs(o->noise, Dimension::Length, "--noise");
    request.seed = o->seed;
    request.limits.jerkTime = o->jerkTimeMs * 1e-3;
    request.clockOffset = o->clockOffsetMs * 1e-3;
    request.format = signalFormatNamed(o->signalFormat, "--format");
    const auto s = simulateMotion(loadMachineSetup(o->source), request);
    if (o->json) {
      std::cout << toJson(s).dump(2) << "\n";
      return;
    }
    std::cout << fmt::format("ball at ({:.3f}, {:.3f}, {:.3f}) mm; largest |component| of each contribution, um\n", s.ball.x(), s.ball.y(), s.ball.z());
    std::cout << fmt::format("{:>9} {:>8} {:>9} | {:>22} | {:>22} | {:>22}\n", "feed", "time s", "samples", "contouring x y z", "geometric x y z",
                             "dynamic x y z");
    for (const auto& f : s.feeds)
      std::cout << fmt::format("{:>9.0f} {:>8.2f} {:>9} | {:>6.2f} {:>7.2f} {:>7.2f} | {:>6.2f} {:>7.2f} {:>7.2f} | {:>6.2f} {:>7.2f} {:>7.2f}\n", f.feed,
                               f.duration, f.instrumentSamples, f.contouringMax.x() * 1e3, f.contouringMax.y() * 1e3, f.contouringMax.z() * 1e3,
                               f.geometricMax.x() * 1e3, f.geometricMax.y() * 1e3, f.geometricMax.z() * 1e3, f.dynamicMax.x() * 1e3,
                               f.dynamicMax.y() * 1e3, f.dynamicMax.z() * 1e3);
    std::cout << "-> " << s.setFile << " (mtacc decompose MACHINE " << s.setFile << ")\n";
  });
}

}  // namespace mtacc::cli
