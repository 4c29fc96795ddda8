// mtacc ik: axis positions for TCP position and tool direction in the workpiece frame.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/kinematics_options.hpp"

namespace mtacc::cli {
namespace {

struct InverseCliOptions : MachineOptions {
  OptionValues values;
};

void run(const InverseCliOptions& o) {
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  const auto r = inverseKinematics(setup, inverseRequest(setup, o.values));
  std::string human = poseHeader(m) + "   notes\n";
  std::string csv = poseCsvHeader(m) + "singular,within_travel\n";
  for (const auto& s : r.solutions) {
    std::string notes;
    if (s.singular) notes += "singular: " + s.singularAxis + " free (kept at the hint); ";
    if (!s.withinTravel) notes += s.travelViolation;
    human += formatPose(m, s.q.data()) + "   " + notes + "\n";
    csv += poseCsv(m, s.q.data()) + fmt::format("{},{}\n", s.singular ? 1 : 0, s.withinTravel ? 1 : 0);
  }
  if (!r.withErrors.empty()) {
    human = poseHeader(m) + "   residual um, urad; notes\n";
    csv = poseCsvHeader(m) + "position_residual_um,direction_residual_urad,converged,singular,within_travel\n";
  }
  for (const auto& s : r.withErrors) {
    std::string notes = s.converged ? "" : "not converged; ";
    if (s.singular) notes += "near a singular orientation: the position reached, the direction not corrected; ";
    if (!s.directionControlled) notes += "direction not corrected (fewer than two rotary axes); ";
    notes += s.travelViolation;
    const double position = toDisplay(s.positionResidual, Dimension::Length), direction = toDisplay(s.directionResidual, Dimension::Angle);
    human += formatPose(m, s.q.data()) + fmt::format("   {:.2e}, {:.2e}; {}\n", position, direction, notes);
    csv += poseCsv(m, s.q.data()) + fmt::format("{},{},{},{},{}\n", position, direction, s.converged ? 1 : 0, s.singular ? 1 : 0,
                                                 s.travelViolation.empty() ? 1 : 0);
  }
  emit(o, toJson(r), human, csv);
}

}  // namespace

void addInverseCommand(const CommandLine& app) {
  auto o = std::make_shared<InverseCliOptions>();
  auto cmd = app.subcommand("ik", "inverse kinematics: axis positions for a TCP position and tool direction");
  cmd.machineOptions(*o);
  cmd.schemaOptions(inverseSchema(), o->values);
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
