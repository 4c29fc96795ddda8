#include "mtacc/workflows/program_deviation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace mtacc {
namespace {

GcodeProgram programWithFeedMoves(const std::string& file, const Machine& machine, const std::map<int, double>& toolLengths) {
  auto program = readGcodeProgram(file, machine, {{}, toolLengths});
  if (std::none_of(program.moves.begin(), program.moves.end(), [](const GcodeMove& m) { return m.mode != MotionMode::Rapid; }))
    throw InputError({file, static_cast<int>(program.lines.size()), "program"}, "the program has no feed moves: no path to follow");
  return program;
}

}  // namespace

ProgramDeviationResult programDeviationFile(const MachineSetup& setup, const ProgramDeviationRequest& request) {
  ProgramDeviationResult r{setup, programWithFeedMoves(request.programFile, *setup.machine, request.toolLengths), std::nullopt, {}};
  if (!request.intendedFile.empty()) r.intended = programWithFeedMoves(request.intendedFile, *setup.machine, request.toolLengths);
  try {
    r.deviation = programPathDeviation(setup.machine, setup.errors, r.program, r.intended ? &*r.intended : nullptr, request.options);
  } catch (const std::invalid_argument& e) {  // both programs have feed moves: the step is what is wrong
    throw InputError({"", 0, "step"}, fmt::format("{}, not {:g} mm", e.what(), request.options.step));
  }
  if (r.deviation.total.samples == 0)
    throw InputError({request.programFile, static_cast<int>(r.program.lines.size()), "program"},
                     fmt::format("every feed block moves the TCP less than 10 um ({} blocks): no path to follow", r.deviation.instantBlocks));
  return r;
}

nlohmann::json toJson(const ProgramDeviationResult& r) {
  const auto& d = r.deviation;
  nlohmann::json blocks = nlohmann::json::array();
  for (const auto& b : d.blocks)
    blocks.push_back({{"line", b.line}, {"max_position_um", b.maxPosition * 1e3}, {"max_direction_urad", b.maxDirection * 1e6}, {"samples", b.samples}});
  std::vector<const BlockDeviation*> worst;
  for (const auto& b : d.blocks) worst.push_back(&b);
  std::sort(worst.begin(), worst.end(), [](const auto* a, const auto* b) { return a->maxPosition > b->maxPosition; });
  nlohmann::json worstLines = nlohmann::json::array();
  for (size_t k = 0; k < std::min<size_t>(5, worst.size()); ++k) worstLines.push_back(worst[k]->line);
  return {{"machine", r.setup.machine->name},
          {"program", r.program.file},
          {"intended", r.intended ? nlohmann::json(r.intended->file) : nlohmann::json(nullptr)},
          {"non_zero_errors", nonZeroParameters(*r.setup.machine, r.setup.errors).size()},
          {"samples", d.total.samples},
          {"instant_blocks", d.instantBlocks},
          {"max_position_um", d.total.maxPosition * 1e3},
          {"rms_position_um", d.total.rmsPosition * 1e3},
          {"max_direction_urad", d.total.maxDirection * 1e6},
          {"intended_length_mm", r.intended ? nlohmann::json(d.intendedLength) : nlohmann::json(nullptr)},
          {"worst_blocks", worstLines},
          {"blocks", blocks}};
}

}  // namespace mtacc
