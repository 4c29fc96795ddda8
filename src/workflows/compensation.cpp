#include "mtacc/workflows/compensation.hpp"

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {

ProgramCompensationResult compensateProgramFile(const MachineSetup& setup, const ProgramCompensationRequest& request) {
  const auto& o = request.options;
  if (!(o.tolerance > 0 && o.tolerance <= 1.0))
    throw InputError({"", 0, "tolerance"}, fmt::format("the tolerance must lie in (0, 1000] um, not {} um", o.tolerance * 1e3));
  if (!(o.directionTolerance > 0 && o.directionTolerance <= 0.01))
    throw InputError({"", 0, "direction_tolerance"},
                     fmt::format("the direction tolerance must lie in (0, 10000] urad, not {} urad", o.directionTolerance * 1e6));
  ProgramCompensationResult r{setup, {}, {}, {}, {}};
  r.program = readGcodeProgram(request.programFile, *setup.machine, {{}, request.toolLengths});
  if (r.program.moves.empty()) throw InputError({request.programFile, static_cast<int>(r.program.lines.size()), "program"},
                     "the program ends without moving an axis: nothing to compensate");
  r.compensated = compensateProgram(setup.machine, setup.errors, r.program, request.options);
  if (!r.compensated.travelViolation.empty())
    throw InputError({request.programFile, r.compensated.travelViolationLine, "travel"},
                     "the compensated commands leave the travel: " + r.compensated.travelViolation);
  r.deviation = programDeviation(setup.machine, setup.errors, r.program, r.compensated.points);
  const auto& d = r.deviation;
  const std::string header = fmt::format(
      "mtacc: {} compensated for {} and its errors ({} non-zero parameters)\n"
      "tolerance {:g} um, {:g} urad; TCP deviation on the machine with errors: before {:.2f} um, after {:.3f} um (largest)",
      request.programFile, setup.machine->name, nonZeroParameters(*setup.machine, setup.errors).size(), request.options.tolerance * 1e3,
      request.options.directionTolerance * 1e6, d.before.maxPosition * 1e3, d.after.maxPosition * 1e3);
  r.gcode = compensatedGcode(*setup.machine, r.program, r.compensated, header);
  return r;
}

nlohmann::json toJson(const ProgramCompensationResult& r) {
  const auto& c = r.compensated;
  const Machine& m = *r.setup.machine;
  auto deviation = [](const PathDeviation& d) {
    return nlohmann::json{{"max_position_um", d.maxPosition * 1e3}, {"rms_position_um", d.rmsPosition * 1e3},
                          {"max_direction_urad", d.maxDirection * 1e6}, {"samples", d.samples}};
  };
  nlohmann::json correction = nlohmann::json::object();
  for (int k = 0; k < m.commandedCount(); ++k) {
    const Axis& a = m.axes[static_cast<size_t>(k)];
    correction[a.name] = toDisplay(c.largestCorrection[static_cast<size_t>(k)], a.isRotary() ? Dimension::Angle : Dimension::Length);
  }
  return {{"machine", m.name},
          {"program", r.program.file},
          {"lines", r.program.lines.size()},
          {"moves", r.program.moves.size()},
          {"written_points", c.points.empty() ? 0 : c.points.size() - 1},
          {"largest_correction_um_urad", correction},
          {"largest_residual_um", c.largestResidual * 1e3},
          {"not_converged", c.notConverged},
          {"singular", c.singular},
          {"first_problem_line", c.firstProblemLine},
          {"deviation_before", deviation(r.deviation.before)},
          {"deviation_after", deviation(r.deviation.after)}};
}

}  // namespace mtacc
