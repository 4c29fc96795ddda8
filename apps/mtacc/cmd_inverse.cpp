// mtacc ik: axis positions for TCP position and tool direction in the workpiece frame.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/workflows/kinematics_batch.hpp"

namespace mtacc::cli {
namespace {

struct InverseCliOptions : MachineOptions {
  std::string tcp, tool = "0,0,1", targetsFile, branch = "auto", near;
  bool all = false, withErrors = false;
};

void run(const InverseCliOptions& o) {
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  if (o.tcp.empty() == o.targetsFile.empty())
    throw InputError(InputLocation{"", 0, "--tcp/--targets"}, "give exactly one of --tcp x,y,z or --targets FILE.csv");
  InverseRequest request = o.targetsFile.empty() ? InverseRequest{} : inverseTargetsOfFile(o.targetsFile);
  request.options.branch = parseTiltBranch(o.branch);
  if (!o.near.empty()) request.options.hint = poseFromText(setup, o.near, "--near", true);
  request.all = o.all;
  request.withErrors = o.withErrors;
  if (!o.tcp.empty()) {
    request.positions.push_back(parseVector(o.tcp, "--tcp"));
    request.directions.push_back(parseVector(o.tool, "--tool"));
  }
  const auto r = inverseKinematics(setup, request);
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

void addInverseCommand(CLI::App& app) {
  auto o = std::make_shared<InverseCliOptions>();
  auto* cmd = app.add_subcommand("ik", "inverse kinematics: axis positions for a TCP position and tool direction");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--tcp", o->tcp, "TCP position x,y,z in the workpiece frame (mm)");
  cmd->add_option("--tool", o->tool, "tool direction i,j,k (TCP towards spindle), default 0,0,1");
  cmd->add_option("--targets", o->targetsFile, "CSV with columns x,y,z,i,j,k: solved as a continuous path");
  cmd->add_option("--branch", o->branch, "tilt branch of the first pose: auto, positive or negative");
  cmd->add_option("--near", o->near,
                  "a pose to stay near, e.g. B=30,C=170 (mm, deg; axes not named 0): rotary angles closest to it, a free angle "
                  "at a singular pose kept at its value");
  cmd->add_flag("--with-errors", o->withErrors,
                "the commands that reach the pose on the machine with its errors (the inverse error model), with the "
                "residual");
  cmd->add_flag("--all", o->all, "list every solution of a single target (including those beyond travel)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
