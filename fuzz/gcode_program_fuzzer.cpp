// An axis program (G-code) for the tilting table and the 3-axis machine, with a tool length for
// H1; each program that reads is also compensated and written, so that the reader's output is
// exercised by what consumes it, and streamed from a file through the workflow, whose program
// must equal the whole-program path's (a difference aborts: a finding).
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "fuzz_input.hpp"
#include "mtacc/compensation/program_compensation.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/compensation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto table = fuzz::bundled("tilting-table");
  static const ErrorModel errors = loadMachineErrors(*table);
  static const auto threeAxis = fuzz::bundled("three-axis-vertical");
  static const std::string file = "/tmp/mtacc-gcode-fuzz-" + std::to_string(::getpid()) + ".nc";
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
    const std::string whole = compensatedGcode(*table, program, compensated, "fuzz");
    if (program.moves.empty() || !compensated.travelViolation.empty()) return;
    std::ofstream(file, std::ios::binary) << text;
    ProgramCompensationRequest request;
    request.programFile = file;
    request.toolLengths = {{1, 20.0}};
    request.options = options;
    const std::string streamed = compensateProgramFile({table, errors, std::nullopt}, request).gcode;
    // The same after the preambles, whose headers differ.
    const auto body = [](const std::string& g) { return g.substr(g.find("G21 G90\n")); };
    if (body(streamed) != body(whole)) std::abort();
  });
}
