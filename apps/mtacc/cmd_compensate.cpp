// mtacc compensate MACHINE --program IN.nc --gcode OUT.nc: the axis program compensated for the
// machine's errors, with what its path deviates from the program before and after.
// mtacc compensate MACHINE --tables DIR: the correction grid, its one-axis functions and the
// controllers' files (Siemens, LinuxCNC, TwinCAT/ISG), with the residual each leaves; with
// --thermal STATE --every SECONDS rewritten for the state as it is each period.
#include <fmt/chrono.h>
#include <fmt/format.h>

#include <csignal>
#include <ctime>
#include <iostream>

#include <unistd.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/io/text_file.hpp"
#include "mtacc/workflows/compensation.hpp"

namespace mtacc::cli {
namespace {

struct CompensateOptions : MachineOptions {
  std::string program, gcode, toolLengths, checkErrors;
  std::string tables, nodes = "21,21,21", pose, checkProgram;
  int functions = 9, linuxcncType = 1;
  double everySeconds = 0.0;  // tables: 0 once; else rewritten each period
  int updates = 0;            // with everySeconds: 0 until a stop signal
  double toleranceUm = ProgramCompensationOptions{}.tolerance * 1e3;
  double directionToleranceUrad = ProgramCompensationOptions{}.directionTolerance * 1e6;
};

CompensationTablesRequest tablesRequest(const CompensateOptions& o) {
  CompensationTablesRequest request;
  const auto counts = splitList(o.nodes);
  if (counts.size() != 3) throw InputError({"", 0, "--nodes"}, "give the nodes along X, Y, Z, e.g. 21,21,21");
  for (size_t a = 0; a < 3; ++a) request.grid.counts[a] = parseCount(counts[a], "--nodes", 2, 1000);
  if (!o.pose.empty()) request.grid.pose = parsePose(*loadMachineSetup(o.source).machine, o.pose, "--pose", true);
  request.oneAxisFunctions = o.functions;
  request.linuxcncType = o.linuxcncType;
  request.checkProgram = o.checkProgram;
  return request;
}

void emitTables(const CompensateOptions& o, const CompensationTablesResult& r) {
  const auto j = toJson(r);
  std::string others;
  for (const auto& [axis, value] : j["grid"]["pose"].items())
    if (axis != "X" && axis != "Y" && axis != "Z") others += fmt::format("{}{}={:g}", others.empty() ? " with " : ", ", axis, value.get<double>());
  std::string human = fmt::format("Correction tables for {}: {} x {} x {} nodes over the travel of X, Y, Z{}; written to {}/\n", r.setup.machine->name,
                                  r.grid.counts[0], r.grid.counts[1], r.grid.counts[2], others, o.tables);
  human += fmt::format("TCP position error left over {} points (nodes and midpoints), um:  largest (rms)\n", r.gridResidual.samples);
  human += fmt::format("  {:<30} {:9.3f} ({:.3f})\n", "uncorrected", r.gridResidual.beforeMax * 1e3, r.gridResidual.beforeRms * 1e3);
  std::string csv = "format,after_max_um,after_rms_um,before_max_um,before_rms_um,moving_forward_max_um,moving_backward_max_um\n";
  for (const auto& t : j["tables"]) {
    const auto& res = t["residual"];
    const std::string format = t["format"];
    const std::string label = format == "grid"          ? "3-D grid, trilinear"
                              : format == "one-axis"    ? fmt::format("{} one-axis functions", r.oneAxis.functions.size())
                              : format == "siemens-cec" ? "Siemens CEC tables"
                              : format == "siemens-lec" ? "Siemens LEC tables per axis"
                              : format == "linuxcnc"    ? "LinuxCNC COMP_FILE per joint"
                              : format == "heidenhain"  ? "HEIDENHAIN .COM tables"
                                                        : "TwinCAT/ISG volumetric model";
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})   carries {}\n", label, res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                         t["carries"].get<std::string>());
    if (res.contains("moving_forward_max_um"))
      human += fmt::format("  {:<30} {:9.3f} / {:.3f} largest moving forward / backward (standing {:.3f})\n", "",
                           res["moving_forward_max_um"].get<double>(), res["moving_backward_max_um"].get<double>(), res["after_max_um"].get<double>());
    if (t.contains("not_carried"))
      for (const auto& left : t["not_carried"]) human += fmt::format("  {:<30} not carried: {}\n", "", left.get<std::string>());
    if (t.contains("along_program"))
      human += fmt::format("  {:<30} {:9.3f} ({:.3f})   along {} (uncorrected {:.3f}; moving as programmed {:.3f})\n", "",
                           t["along_program"]["after_max_um"].get<double>(), t["along_program"]["after_rms_um"].get<double>(), o.checkProgram,
                           t["along_program"]["before_max_um"].get<double>(), t["along_program"].value("moving_as_programmed_max_um", 0.0));
    csv += fmt::format("{},{},{},{},{},{},{}\n", t["format"].get<std::string>(), res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                       res["before_max_um"].get<double>(), res["before_rms_um"].get<double>(), res.value("moving_forward_max_um", 0.0),
                       res.value("moving_backward_max_um", 0.0));
  }
  if (!r.isg) human += fmt::format("TwinCAT/ISG volumetric model: none, {}\n", r.isgNotApplicable);
  // The controllers' kinematic data sets, each over the rotary axes' poses and along the check program.
  const auto kinematics = [&](const nlohmann::json& k, const std::string& title, const std::string& format) {
    if (!k["applicable"].get<bool>()) {
      human += fmt::format("{}: none, {}\n", title, k["reason"].get<std::string>());
      return;
    }
    const auto& res = k["residual"];
    human += fmt::format("{} in {}, over {} poses of the rotary axes, um:  largest (rms)\n", title, k["file"].get<std::string>(),
                         res["samples"].get<int>());
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})\n", "nominal parameters", res["before_max_um"].get<double>(), res["before_rms_um"].get<double>());
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})   carries {}\n", "fitted parameters", res["after_max_um"].get<double>(),
                         res["after_rms_um"].get<double>(), k["carries"].get<std::string>());
    for (const auto& left : k["not_carried"]) human += fmt::format("  {:<30} not carried: {}\n", "", left.get<std::string>());
    if (k.contains("along_program"))
      human += fmt::format("  {:<30} {:9.3f} ({:.3f})   along {} (uncorrected {:.3f})\n", "", k["along_program"]["after_max_um"].get<double>(),
                           k["along_program"]["after_rms_um"].get<double>(), o.checkProgram, k["along_program"]["before_max_um"].get<double>());
    csv += fmt::format("{},{},{},{},{},{},{}\n", format, res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                       res["before_max_um"].get<double>(), res["before_rms_um"].get<double>(), res.value("moving_forward_max_um", 0.0),
                       res.value("moving_backward_max_um", 0.0));
  };
  const auto& kins = j["linuxcnc_kins"];
  kinematics(kins, kins["applicable"].get<bool>() ? fmt::format("LinuxCNC {} parameters", kins["kins"].get<std::string>()) : "LinuxCNC kinematics parameters",
             "linuxcnc-kins");
  const auto& carr = j["siemens_toolholder"];
  kinematics(carr, carr["applicable"].get<bool>() ? fmt::format("SINUMERIK toolholder $TC_CARR, type {} (and the 5-axis transformation's MD)", carr["type"].get<std::string>())
                                                  : "SINUMERIK toolholder $TC_CARR",
             "siemens-toolholder");
  emit(o, j, human, csv);
}

volatile std::sig_atomic_t stopRequested = 0;
extern "C" void requestStop(int) { stopRequested = 1; }

// Each update's report as the one-off command prints it, and a line on stderr saying when.
void runTablesPeriodically(const CompensateOptions& o) {
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  keepTablesCurrent(o.source, {tablesRequest(o), o.tables, o.everySeconds, o.updates}, [] { return stopRequested != 0; },
                    [&](int update, const CompensationTablesResult& r, std::optional<double> moved) {
                      emitTables(o, r);
                      std::cerr << fmt::format("mtacc: update {} at {:%H:%M:%S}: tables for {} written to {}/{}\n", update,
                                               fmt::localtime(std::time(nullptr)), o.source.thermalFile, o.tables,
                                               moved ? fmt::format("; the grid moved by up to {:.3f} um since the last", *moved * 1e3) : "")
                                << std::flush;
                    });
}

void run(const CompensateOptions& o) {
  if (o.program.empty() == o.tables.empty())
    throw InputError({"", 0, "--program/--tables"}, "give --program IN.nc (a compensated program) or --tables DIR (controller tables)");
  if (o.everySeconds > 0 && o.tables.empty()) throw InputError({"", 0, "--every"}, "rewrites controller tables: give --tables DIR");
  if (!o.tables.empty()) {
    if (o.everySeconds > 0) {
      if (o.source.thermalFile.empty()) throw InputError({"", 0, "--every"}, "give --thermal STATE: the temperatures the tables follow");
      return runTablesPeriodically(o);
    }
    const auto r = compensationTables(loadMachineSetup(o.source), tablesRequest(o));
    writeCompensationTables(r, o.tables);
    emitTables(o, r);
    return;
  }
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
