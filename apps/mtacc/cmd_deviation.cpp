// mtacc deviation MACHINE --program P [--intended P0]: the program run on the machine with its
// errors (--errors: a model other than the one that compensated it, e.g. the machine as measured
// again), against the path it (or P0) was meant to cut: largest and RMS TCP deviation, the tool
// direction's, and the blocks where it is largest.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/program_deviation.hpp"

namespace mtacc::cli {
namespace {

struct DeviationOptions : MachineOptions {
  OptionValues values;
};

void run(const DeviationOptions& o) {
  const ProgramDeviationRequest request = programDeviationRequest(o.values);
  const auto r = programDeviationFile(loadMachineSetup(o.source), request);
  const auto j = toJson(r);
  const auto& d = r.deviation;
  std::string human = fmt::format("{} on {} with {} non-zero errors{}, against {}:\n", request.programFile, r.setup.machine->name,
                                  j["non_zero_errors"].get<size_t>(), o.source.errorsFile.empty() ? "" : " (" + o.source.errorsFile + ")",
                                  r.intended ? "the nominal path of " + r.intended->file + " (closest point)" : "its own nominal path");
  human += fmt::format("  {} samples along {} feed blocks, every {:g} mm of path{}\n", d.total.samples, d.blocks.size(), request.options.step,
                       d.instantBlocks ? fmt::format(" ({} blocks of under 10 um passed in an instant, not sampled)", d.instantBlocks) : "");
  human += fmt::format("  TCP deviation   largest {:9.3f} um   rms {:9.3f} um\n", d.total.maxPosition * 1e3, d.total.rmsPosition * 1e3);
  human += fmt::format("  tool direction  largest {:9.3f} urad\n", d.total.maxDirection * 1e6);
  if (!j["uncertainty_k2_max_um"].is_null()) {
    const auto u = j["uncertainty_k2_max_um"].get<std::vector<double>>();
    human += fmt::format("  what the model does not know of the TCP (k = 2, from its identification's covariance), largest: "
                         "{:.3f} {:.3f} {:.3f} um (x y z)\n", u[0], u[1], u[2]);
  }
  human += "  largest at lines:";
  for (const auto& line : j["worst_blocks"]) human += fmt::format(" {}", line.get<int>());
  human += "\n";
  std::string csv = "line,max_position_um,max_direction_urad,samples\n";
  for (const auto& b : d.blocks) csv += fmt::format("{},{},{},{}\n", b.line, b.maxPosition * 1e3, b.maxDirection * 1e6, b.samples);
  emit(o, j, human, csv);
}

}  // namespace

void addDeviationCommand(const CommandLine& app) {
  auto o = std::make_shared<DeviationOptions>();
  auto cmd = app.subcommand("deviation", "a program run on the machine with its errors, against the path it was meant to cut");
  cmd.machineOptions(*o);
  cmd.schemaOptions(programDeviationSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
