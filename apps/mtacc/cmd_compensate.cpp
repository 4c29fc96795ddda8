// mtacc compensate MACHINE --program IN.nc --gcode OUT.nc: the axis program compensated for the
// machine's errors, with what its path deviates from the program before and after. The --tables
// output is in cmd_compensate_tables.cpp.
#include <fmt/format.h>

#include <iostream>

#include <unistd.h>

#include "cmd_compensate.hpp"
#include "mtacc/core/input_error.hpp"

namespace mtacc::cli {
namespace {

void run(const CompensateOptions& o) {
  if (o.program.empty() == o.tables.empty())
    throw InputError({"", 0, "--program/--tables"}, "give --program IN.nc (a compensated program) or --tables DIR (controller tables)");
  if (o.everySeconds > 0 && o.tables.empty()) throw InputError({"", 0, "--every"}, "rewrites controller tables: give --tables DIR");
  if (!o.tables.empty()) return runCompensationTables(o);
  if (o.gcode.empty()) throw InputError({"", 0, "--gcode"}, "give the file to write the compensated program to (--gcode OUT.nc)");
  ProgramCompensationRequest request;
  request.programFile = o.program;
  request.toolLengths = parseToolLengths(o.toolLengths);
  request.options.tolerance = o.toleranceUm * 1e-3;
  request.options.directionTolerance = o.directionToleranceUrad * 1e-6;
  request.checkErrorsFile = o.checkErrors;
  request.outputFile = o.gcode;
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
  std::string human = fmt::format("{}: {} lines, {} moves, {} points written to {}\n", o.program, r.lines, r.moves, c.written, o.gcode);
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

void addCompensateCommand(CLI::App& app) {
  auto o = std::make_shared<CompensateOptions>();
  auto* cmd = app.add_subcommand("compensate", "compensate an axis program (G-code) for the machine's errors");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--program", o->program, "the G-code program to compensate (axis positions in mm and deg)");
  cmd->add_option("--gcode", o->gcode, "write the compensated program to FILE");
  addToolLengthOption(*cmd, o->toolLengths);
  cmd->add_option("--tolerance", o->toleranceUm, "TCP deviation allowed between written points, arc chords included [um]")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--direction-tolerance", o->directionToleranceUrad, "tool direction deviation allowed between written points [urad]")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 10000.0));
  cmd->add_option("--check-errors", o->checkErrors,
                  "program: also run the program, as written and compensated, on this errors file's machine (the machine as measured "
                  "again, or a simulation's truth)");
  cmd->add_option("--tables", o->tables, "write the correction grid, its one-axis functions and the controllers' files (Siemens, HEIDENHAIN, LinuxCNC, TwinCAT/ISG) to DIR");
  cmd->add_option("--check-program", o->checkProgram, "tables: also check each table along this program's feed moves (G-code)");
  cmd->add_option("--nodes", o->nodes, "tables: nodes along X, Y, Z over their travel")->capture_default_str();
  cmd->add_option("--pose", o->pose, "tables: the other axes' positions, e.g. B=0,C=0 (mm, deg; default 0)");
  cmd->add_option("--functions", o->functions, "tables: one-axis functions kept, the largest first")->capture_default_str()->check(CLI::Range(1, 9));
  cmd->add_option("--linuxcnc-type", o->linuxcncType, "tables: LinuxCNC COMP_FILE_TYPE, 1 (trims) or 0 (positions)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1));
  cmd->add_option("--every", o->everySeconds,
                  "tables with --thermal: read the thermal state again and rewrite the tables every SECONDS (a controller reads them "
                  "every 60), until stopped (Ctrl-C, SIGTERM) or --updates")
      ->check(CLI::Range(0.01, 86400.0));
  cmd->add_option("--updates", o->updates, "with --every: stop after this many writes (default: when stopped)")->check(CLI::Range(1, 1000000));
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
