// An axis program (G-code) for the tilting table and the 3-axis machine, with a tool length for
// H1; each program that reads is also compensated and written, so that the reader's output is
// exercised by what consumes it.
#include <cmath>

#include "fuzz_input.hpp"
#include "mtacc/compensation/program_compensation.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/gcode_program.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto table = fuzz::bundled("tilting-table");
  static const ErrorModel errors = loadMachineErrors(*table);
  static const auto threeAxis = fuzz::bundled("three-axis-vertical");
  const std::string text = fuzz::text(data, size);
  return fuzz::asTheFrontEndsDo([&] {
    parseGcodeProgram(text, "fuzz.nc", *threeAxis, {{}, {{1, 20.0}}});
    const GcodeProgram program = parseGcodeProgram(text, "fuzz.nc", *table, {{}, {{1, 20.0}}});
    // The reader is the target: long programs and many turns of arcs only cost time.
    double turned = 0.0;
    for (const auto& m : program.moves) turned += std::abs(m.sweep);
    if (program.moves.size() > 200 || turned > 100.0) return;
    ProgramCompensationOptions options;
    options.tolerance = 1e-3;
    options.maxSplits = 6;
    const CompensatedProgram compensated = compensateProgram(table, errors, program, options);
    compensatedGcode(*table, program, compensated, "fuzz");
  });
}
