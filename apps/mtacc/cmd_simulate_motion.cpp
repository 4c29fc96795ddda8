// mtacc simulate motion: Andolfatto et al. 2011's virtual machine — an NC program run at each feed of a ladder
// through interpolator and servo loops, with geometric errors, drift, structural deflection and
// instrument noise; the recorded signals, the truth and the decomposition set written to a folder.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_simulate.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

namespace mtacc::cli {
namespace {

struct MotionCliOptions : MachineOptions {
  OptionValues values;
};

}  // namespace

void addSimulateMotionCommand(const CommandLine& simulate) {
  auto o = std::make_shared<MotionCliOptions>();
  auto motion = simulate.subcommand("motion", "Andolfatto et al. 2011's virtual machine: an NC program run at each feed of a ladder, with servo loops, "
                                                "geometric errors, drift, structural deflection and instrument noise; the recorded signals, "
                                                "the truth and the decomposition set written to a directory");
  motion.argument("machine", o->source.machine, "Machine file or bundled name");
  motion.option("--errors", o->source.errorsFile, "Error description (YAML); default: the machine file's errors");
  motion.flag("--json", o->json, "Summary as JSON on stdout");
  motion.schemaOptions(motionSimulationSchema(), o->values, {{"output", "-o"}});
  motion.callback([o] {
    const auto s = simulateMotion(loadMachineSetup(o->source), motionSimulationRequest(o->values));
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
