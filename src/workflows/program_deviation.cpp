#include "mtacc/workflows/program_deviation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "mtacc/workflows/tcp_uncertainty.hpp"

namespace mtacc {
namespace {

GcodeProgram programWithFeedMoves(const std::string& file, const Machine& machine, const std::map<int, double>& toolLengths) {
  auto program = readGcodeProgram(file, machine, {{}, toolLengths});
  if (std::none_of(program.moves.begin(), program.moves.end(), [](const GcodeMove& m) { return m.mode != MotionMode::Rapid; }))
    throw InputError({file, static_cast<int>(program.lines.size()), "program"}, "the program has no feed moves: no path to follow");
  return program;
}

}  // namespace

const OptionSchema& programDeviationSchema() {
  static const OptionSchema schema{
      "deviation",
      {{.key = "program", .kind = OptionKind::Text, .help = "the G-code program run (axis positions in mm and deg)", .required = true},
       {"intended", OptionKind::Text, "the program whose nominal path was meant (e.g. the one compensated into --program); default: --program's own"},
       toolLengthOption(),
       // its range (0.001 to 100 mm) is checked where the path is sampled
       {"step", OptionKind::Number, "nominal TCP path between samples [mm] (at least 4 a block)", "0.5"}}};
  return schema;
}

ProgramDeviationRequest programDeviationRequest(const OptionValues& values) {
  const OptionReader read(programDeviationSchema(), values);
  ProgramDeviationRequest r;
  r.programFile = *read.text("program");
  r.intendedFile = read.text("intended").value_or("");
  r.toolLengths = toolLengthsFromText(read.text("tool_length").value_or(""), "tool_length");
  r.options.step = *read.number("step");
  return r;
}

ProgramDeviationResult programDeviationFile(const MachineSetup& setup, const ProgramDeviationRequest& request) {
  ProgramDeviationResult r{setup, programWithFeedMoves(request.programFile, *setup.machine, request.toolLengths), std::nullopt, {}, {}};
  if (!request.intendedFile.empty()) r.intended = programWithFeedMoves(request.intendedFile, *setup.machine, request.toolLengths);
  try {
    r.deviation = programPathDeviation(setup.machine, setup.errors, r.program, r.intended ? &*r.intended : nullptr, request.options);
  } catch (const InvalidInput& e) {  // both programs have feed moves: the step is what is wrong
    throw InputError({"", 0, "step"}, fmt::format("{}, not {:g} mm", e.what(), request.options.step));
  }
  if (setup.covariance) {
    std::map<int, const GcodeMove*> byLine;
    for (const auto& m : r.program.moves) byLine[m.line] = &m;
    JointMatrix ends(static_cast<Eigen::Index>(r.deviation.blocks.size()), setup.machine->commandedCount());
    for (size_t b = 0; b < r.deviation.blocks.size(); ++b) {
      const auto& to = byLine.at(r.deviation.blocks[b].line)->to;
      for (size_t k = 0; k < to.size(); ++k) ends(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(k)) = to[k];
    }
    r.uncertainty = tcpUncertainty(setup, ends);
  }
  if (r.deviation.total.samples == 0)
    throw InputError({request.programFile, static_cast<int>(r.program.lines.size()), "program"},
                     fmt::format("every feed block moves the TCP less than 10 um ({} blocks): no path to follow", r.deviation.instantBlocks));
  return r;
}

nlohmann::json toJson(const ProgramDeviationResult& r) {
  const auto& d = r.deviation;
  const auto k2 = [](const Vec3& u) { return nlohmann::json::array({2e3 * u.x(), 2e3 * u.y(), 2e3 * u.z()}); };
  nlohmann::json blocks = nlohmann::json::array();
  Vec3 largest = Vec3::Zero();
  for (size_t k = 0; k < d.blocks.size(); ++k) {
    const auto& b = d.blocks[k];
    blocks.push_back({{"line", b.line}, {"max_position_um", b.maxPosition * 1e3}, {"max_direction_urad", b.maxDirection * 1e6}, {"samples", b.samples}});
    if (!r.uncertainty.empty()) {
      blocks.back()["uncertainty_k2_um"] = k2(r.uncertainty[k]);
      largest = largest.cwiseMax(r.uncertainty[k]);
    }
  }
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
          {"uncertainty_k2_max_um", r.uncertainty.empty() ? nlohmann::json(nullptr) : k2(largest)},
          {"blocks", blocks}};
}

}  // namespace mtacc
