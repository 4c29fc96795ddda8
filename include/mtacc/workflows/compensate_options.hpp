#pragma once
// The options of `compensate`, declared once for its two outputs: a compensated program
// (program, gcode, tool_length, tolerance, direction_tolerance, check_errors) and controller
// tables (tables, nodes, pose, functions, linuxcnc_type, check_program, every, updates).
#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/compensation.hpp"

namespace mtacc {

const OptionSchema& compensateSchema();

// The program's request; its output file is `gcode` (none: the result keeps the text).
ProgramCompensationRequest programCompensationRequest(const OptionValues& values);
// The tables' request; `pose` is read against the machine of `setup`.
CompensationTablesRequest compensationTablesRequest(const MachineSetup& setup, const OptionValues& values);

// Which output the values ask for. Throws InputError when they give both or neither, a program
// without its gcode file, or `every` without tables.
enum class CompensateOutput { Program, Tables };
CompensateOutput compensateOutput(const OptionValues& values);

}  // namespace mtacc
