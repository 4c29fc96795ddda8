// mtacc sensitivity: how every error parameter moves the TCP at one pose (analytic Jacobian)
// and the sensitivity coefficient k = E / epsilon of Li et al. 2021 eq. 15 along a direction.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/budget.hpp"

namespace mtacc::cli {
namespace {

struct SensitivityCliOptions : MachineOptions {
  OptionValues values;
};

void run(const SensitivityCliOptions& o) {
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  const auto r = sensitivities(setup, sensitivityRequest(setup, o.values));
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

void addSensitivityCommand(const CommandLine& app) {
  auto o = std::make_shared<SensitivityCliOptions>();
  auto cmd = app.subcommand("sensitivity", "TCP sensitivity to every error parameter at one pose");
  cmd.machineOptions(*o);
  cmd.schemaOptions(sensitivitySchema(), o->values, {{"parameters", "--params"}});
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
