// mtacc compensate MACHINE --program IN.nc --gcode OUT.nc: the axis program compensated for the
// machine's errors, with what its path deviates from the program before and after.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/io/text_file.hpp"
#include "mtacc/workflows/compensation.hpp"

namespace mtacc::cli {
namespace {

struct CompensateOptions : MachineOptions {
  std::string program, gcode, toolLengths;
  double toleranceUm = ProgramCompensationOptions{}.tolerance * 1e3;
  double directionToleranceUrad = ProgramCompensationOptions{}.directionTolerance * 1e6;
};

void run(const CompensateOptions& o) {
  if (o.gcode.empty()) throw InputError({"", 0, "--gcode"}, "give the file to write the compensated program to (--gcode OUT.nc)");
  ProgramCompensationRequest request;
  request.programFile = o.program;
  for (const auto& a : parseAssignments(o.toolLengths, "--tool-length"))
    request.toolLengths[parseCount(a.name, "--tool-length", 0, 9999)] = parseNumber(a.value, "--tool-length " + a.name);
  request.options.tolerance = o.toleranceUm * 1e-3;
  request.options.directionTolerance = o.directionToleranceUrad * 1e-6;
  const auto r = compensateProgramFile(loadMachineSetup(o.source), request);
  writeFileAtomically(o.gcode, r.gcode, "--gcode");
  const auto j = toJson(r);
  const auto& c = r.compensated;
  const auto& d = r.deviation;
  std::string human = fmt::format("{}: {} lines, {} moves, {} points written to {}\n", o.program, r.program.lines.size(), r.program.moves.size(),
                                  j["written_points"].get<size_t>(), o.gcode);
  human += "largest correction:";
  for (const auto& [axis, value] : j["largest_correction_um_urad"].items())
    human += fmt::format(" {} {:.2f}", axis, value.get<double>());
  human += " (um, urad)\n";
  human += fmt::format("TCP deviation from the program on the machine with its errors, {} samples along the feed moves:\n", d.after.samples);
  human += fmt::format("  as written   largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", d.before.maxPosition * 1e3,
                       d.before.rmsPosition * 1e3, d.before.maxDirection * 1e6);
  human += fmt::format("  compensated  largest {:9.3f} um  rms {:9.3f} um  tool direction {:9.3f} urad\n", d.after.maxPosition * 1e3,
                       d.after.rmsPosition * 1e3, d.after.maxDirection * 1e6);
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
  cmd->add_option("--program", o->program, "the G-code program to compensate (axis positions in mm and deg)")->required();
  cmd->add_option("--gcode", o->gcode, "write the compensated program to FILE");
  cmd->add_option("--tool-length", o->toolLengths, "lengths of the tools named by G43 H<n>, e.g. 1=0,2=35.5 (mm beyond the machine's tool)");
  cmd->add_option("--tolerance", o->toleranceUm, "TCP deviation allowed between written points, arc chords included [um]")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--direction-tolerance", o->directionToleranceUrad, "tool direction deviation allowed between written points [urad]")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 10000.0));
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
