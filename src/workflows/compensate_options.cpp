#include "mtacc/workflows/compensate_options.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"

namespace mtacc {

const OptionSchema& compensateSchema() {
  static const OptionSchema schema{
      "compensate",
      {{"program", OptionKind::Text, "the G-code program to compensate (axis positions in mm and deg)"},
       {"gcode", OptionKind::Text, "write the compensated program to FILE"},
       toolLengthOption(),
       {.key = "tolerance", .kind = OptionKind::Number, .help = "TCP deviation allowed between written points, arc chords included [um]",
        .defaultText = "0.1", .low = 0.01, .high = 1000, .outOfRange = "must be from 0.01 to 1000 um"},
       {.key = "direction_tolerance", .kind = OptionKind::Number, .help = "tool direction deviation allowed between written points [urad]",
        .defaultText = "5", .low = 0.01, .high = 10000, .outOfRange = "must be from 0.01 to 10000 urad"},
       {"check_errors", OptionKind::Text,
        "program: also run the program, as written and compensated, on this errors file's machine (the machine as measured again, or a "
        "simulation's truth)"},
       {"tables", OptionKind::Text,
        "write the correction grid, its one-axis functions and the controllers' files (Siemens, HEIDENHAIN, LinuxCNC, TwinCAT/ISG) to DIR"},
       {"check_program", OptionKind::Text, "tables: also check each table along this program's feed moves (G-code)"},
       {"nodes", OptionKind::Text, "tables: nodes along X, Y, Z over their travel, each 2 to 1000", "21,21,21"},
       {"pose", OptionKind::Text, "tables: the other axes' positions, e.g. B=0,C=0 (mm, deg; default 0)"},
       {.key = "functions", .kind = OptionKind::Count, .help = "tables: one-axis functions kept, the largest first", .defaultText = "9", .low = 1,
        .high = 9, .outOfRange = "must be from 1 to 9"},
       {.key = "linuxcnc_type", .kind = OptionKind::Count, .help = "tables: LinuxCNC COMP_FILE_TYPE, 1 (trims) or 0 (positions)",
        .defaultText = "1", .low = 0, .high = 1, .outOfRange = "must be 0 or 1"},
       {.key = "every", .kind = OptionKind::Number,
        .help = "tables with --thermal: read the thermal state again and rewrite the tables every SECONDS (a controller reads them every "
                "60), until stopped (Ctrl-C, SIGTERM) or --updates",
        .low = 0.01, .high = 86400, .outOfRange = "must be from 0.01 to 86400 s"},
       {.key = "updates", .kind = OptionKind::Count, .help = "with --every: stop after this many writes (default: when stopped)", .low = 1,
        .high = 1000000, .outOfRange = "must be from 1 to 1000000"}}};
  return schema;
}

ProgramCompensationRequest programCompensationRequest(const OptionValues& values) {
  const OptionReader read(compensateSchema(), values);
  ProgramCompensationRequest r;
  r.programFile = read.text("program").value_or("");
  r.toolLengths = toolLengthsFromText(read.text("tool_length").value_or(""), "tool_length");
  r.options.tolerance = *read.number("tolerance") * 1e-3;
  r.options.directionTolerance = *read.number("direction_tolerance") * 1e-6;
  r.checkErrorsFile = read.text("check_errors").value_or("");
  r.outputFile = read.text("gcode").value_or("");
  return r;
}

CompensationTablesRequest compensationTablesRequest(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(compensateSchema(), values);
  CompensationTablesRequest r;
  const auto counts = splitList(*read.text("nodes"));
  if (counts.size() != 3) throw InputError({"", 0, "nodes"}, "give the nodes along X, Y, Z, e.g. 21,21,21");
  for (size_t a = 0; a < 3; ++a) r.grid.counts[a] = parseCount(counts[a], "nodes", 2, 1000);
  if (const auto pose = read.text("pose"); pose && !pose->empty()) r.grid.pose = poseFromText(setup, *pose, "pose", true);
  r.oneAxisFunctions = *read.count("functions");
  r.linuxcncType = *read.count("linuxcnc_type");
  r.checkProgram = read.text("check_program").value_or("");
  return r;
}

CompensateOutput compensateOutput(const OptionValues& values) {
  const OptionReader read(compensateSchema(), values);
  const bool program = read.text("program").has_value(), tables = read.text("tables").has_value();
  if (program == tables)
    throw InputError({"", 0, "--program/--tables"}, "give --program IN.nc (a compensated program) or --tables DIR (controller tables)");
  if (read.number("every") && !tables) throw InputError({"", 0, "every"}, "rewrites controller tables: give --tables DIR");
  if (program && !read.text("gcode")) throw InputError({"", 0, "gcode"}, "give the file to write the compensated program to (--gcode OUT.nc)");
  return program ? CompensateOutput::Program : CompensateOutput::Tables;
}

}  // namespace mtacc
