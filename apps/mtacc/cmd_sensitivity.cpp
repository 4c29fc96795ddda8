// mtacc sensitivity: how every error parameter moves the TCP at one pose (analytic Jacobian)
// and the sensitivity coefficient k = E / epsilon of Li et al. 2021 eq. 15 along a direction.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/budget.hpp"

namespace mtacc::cli {
namespace {

struct SensitivityCliOptions : MachineOptions {
  std::string pose, direction, params, epsilonLength = "10 um", epsilonAngle = "30 urad";
};

void run(const SensitivityCliOptions& o) {
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  SensitivityRequest request;
  request.q = poseFromText(setup, o.pose, "--pose");
  if (!o.direction.empty()) request.direction = parseVector(o.direction, "--direction");
  request.parameters = splitList(o.params);
  request.epsilonLength = parseQuantityAs(o.epsilonLength, Dimension::Length, "--epsilon-length");
  request.epsilonAngle = parseQuantityAs(o.epsilonAngle, Dimension::Angle, "--epsilon-angle");
  const auto r = sensitivities(setup, request);
  const Vec3& n = r.direction;
  std::string human = fmt::format("Sensitivities at {}; direction ({:.4f}, {:.4f}, {:.4f})\n", formatPose(m, r.q.data()), n.x(),
                                  n.y(), n.z());
  human += fmt::format("{:<12} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10}\n", "parameter", "dx", "dy", "dz", "ea", "eb",
                       "ec", "k (1st)", "k=E/eps");
  std::string csv = "parameter,unit,dx,dy,dz,ea,eb,ec,k_first_order,k_exact\n";
  for (const auto& row : r.rows) {
    const auto &p = row.position, &a = row.orientation;
    const char* unit = displayUnit(row.parameter.dimension);
    human += fmt::format("{:<12} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:10.4f} {:10.4f}  um/{}\n", row.parameter.name,
                         p.x(), p.y(), p.z(), a.x(), a.y(), a.z(), row.kFirstOrder, row.kExact, unit);
    csv += fmt::format("{},um/{},{},{},{},{},{},{},{},{}\n", row.parameter.name, unit, p.x(), p.y(), p.z(), a.x(), a.y(), a.z(),
                       row.kFirstOrder, row.kExact);
  }
  emit(o, toJson(r), human, csv);
}

}  // namespace

void addSensitivityCommand(CLI::App& app) {
  auto o = std::make_shared<SensitivityCliOptions>();
  auto* cmd = app.add_subcommand("sensitivity", "TCP sensitivity to every error parameter at one pose");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--pose", o->pose, "axis positions, e.g. X=10,Y=0,Z=5,B=-15,C=30 (mm, deg)")->required();
  cmd->add_option("--direction", o->direction, "direction of E (surface normal) i,j,k in the workpiece frame; default: tool direction");
  cmd->add_option("--params", o->params, "comma-separated parameter names or aliases; default: all");
  cmd->add_option("--epsilon-length", o->epsilonLength, "epsilon of length parameters for k = E/eps (default 10 um)");
  cmd->add_option("--epsilon-angle", o->epsilonAngle, "epsilon of angular parameters for k = E/eps (default 30 urad)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
