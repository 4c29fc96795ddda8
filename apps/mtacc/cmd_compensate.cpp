// mtacc compensate MACHINE --program IN.nc --gcode OUT.nc: the axis program compensated for the
// machine's errors, with what its path deviates from the program before and after. The --tables
// output is in cmd_compensate_tables.cpp.
#include <fmt/format.h>

#include <iostream>

#include <unistd.h>

#include "cmd_compensate.hpp"

namespace mtacc::cli {
namespace {

void run(const CompensateOptions& o) {
  if (compensateOutput(o.values) == CompensateOutput::Tables) return runCompensationTables(o);
  ProgramCompensationRequest request = programCompensationRequest(o.values);
  request.outputKey = "--gcode";
  // On a terminal, progress on one line, ended before anything else is printed (an error too).
  struct ProgressLine {
    bool shown = false;
    ~ProgressLine() {
      if (shown) std::cerr << "\n";
    }
  } progressLine;
  if (isatty(STDERR_FILENO)) request.progress = [&progressLine](const StreamProgress& p) {
    const double rate = p.lines / std::max(p.seconds, 1e-3), done = p.size > 0 ? static_cast<double>(p.bytes) / static_cast<double>(p.size) : 0.0;
    const double left = done > 0 ? p.seconds * (1.0 - done) / done : 0.0;
    std::cerr << fmt::format("\rmtacc: {} lines, {:.0f} lines/s, {:.0f} %, {:.0f} s left   ", p.lines, rate, 100.0 * done, left) << std::flush;
    progressLine.shown = true;
  };
  const auto r = compensateProgramFile(loadMachineSetup(o.source), request);
  const auto j = toJson(r);
  const auto& c = r.compensated;
  const auto& d = r.deviation;
  std::string human = fmt::format("{}: {} lines, {} moves, {} points written to {}\n", request.programFile, r.lines, r.moves, c.written,
                                  request.outputFile);
  human += "largest correction:";
  for (const auto& [axis, value] : j["largest_correction_um_urad"].items())
    human += fmt::format(" {} {:.2f}", axis, value.get<double>());
  human += " (um, urad)\n";
  human += fmt::format("TCP deviation from the program on the machine with its errors, {} samples along the feed moves:\n", d.after.samples);
  human += fmt::format("  as written   largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", d.before.maxPosition * 1e3,
                       d.before.rmsPosition * 1e3, d.before.maxDirection * 1e6);
  human += fmt::format("  compensated  largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", d.after.maxPosition * 1e3,
                       d.after.rmsPosition * 1e3, d.after.maxDirection * 1e6);
  if (r.check) {
    const auto& k = r.check->deviation;
    human += fmt::format("the same on the errors of {} (--check-errors):\n", r.check->errorsFile);
    human += fmt::format("  as written   largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", k.before.maxPosition * 1e3,
                         k.before.rmsPosition * 1e3, k.before.maxDirection * 1e6);
    human += fmt::format("  compensated  largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", k.after.maxPosition * 1e3,
                         k.after.rmsPosition * 1e3, k.after.maxDirection * 1e6);
    if (!r.check->notInModel.empty())
      human += fmt::format("  not in the compensating model: {}\n", fmt::join(r.check->notInModel, " "));
  }
  if (c.singular > 0)
    human += fmt::format("{} points near a singular orientation (first at line {}): their position is corrected, their direction not\n",
                         c.singular, c.firstProblemLine);
  if (c.notConverged > 0) human += fmt::format("warning: {} points did not converge (first at line {})\n", c.notConverged, c.firstProblemLine);
  std::string csv = "quantity,as_written,compensated\n";
  csv += fmt::format("max_position_um,{},{}\n", d.before.maxPosition * 1e3, d.after.maxPosition * 1e3);
  csv += fmt::format("rms_position_um,{},{}\n", d.before.rmsPosition * 1e3, d.after.rmsPosition * 1e3);
  csv += fmt::format("max_direction_urad,{},{}\n", d.before.maxDirection * 1e6, d.after.maxDirection * 1e6);
  emit(o, j, human, csv);
}

}  // namespace

void addCompensateCommand(const CommandLine& app) {
  auto o = std::make_shared<CompensateOptions>();
  auto cmd = app.subcommand("compensate", "compensate an axis program (G-code) for the machine's errors");
  cmd.machineOptions(*o);
  cmd.schemaOptions(compensateSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
