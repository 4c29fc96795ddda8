// mtacc fk / mtacc errors: the tool relative to the workpiece at given axis positions, and
// the TCP error (actual minus nominal) there.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/workflows/kinematics_options.hpp"

namespace mtacc::cli {
namespace {

struct ForwardCliOptions : MachineOptions {
  OptionValues values;
};

void runForward(const ForwardCliOptions& o, bool errorsCommand) {
  const OptionSchema& schema = errorsCommand ? errorsSchema() : forwardSchema();
  const bool errorsOnly = errorsCommand && !OptionReader(schema, o.values).flag("with_tcp");
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  const ForwardResult r = forwardKinematicsOf(setup, schema, o.values);
  std::string human = errorsOnly ? fmt::format("{} | {:>8} {:>8} {:>8} {:>8} | {:>8} {:>8} {:>8}\n", poseHeader(m), "dx um",
                                               "dy um", "dz um", "|d| um", "ea urad", "eb urad", "ec urad")
                                 : fmt::format("{} | {:>11} {:>11} {:>11} | {:>7} {:>7} {:>7} | {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}\n",
                                               poseHeader(m), "x mm", "y mm", "z mm", "i", "j", "k", "dx um", "dy um", "dz um",
                                               "ea urad", "eb urad", "ec urad");
  std::string csv = poseCsvHeader(m) + (errorsOnly ? "" : "x,y,z,i,j,k,") + "dx_um,dy_um,dz_um,ea_urad,eb_urad,ec_urad\n";
  for (Eigen::Index i = 0; i < r.q.rows(); ++i) {
    const double* q = r.q.row(i).data();
    const Vec3 e = r.error.row(i).head<3>().transpose() * 1e3, a = r.error.row(i).tail<3>().transpose() * 1e6;
    const Vec3 p = r.tool.positions.row(i).transpose(), d = r.tool.directions.row(i).transpose();
    if (errorsOnly) {
      human += fmt::format("{} | {:8.3f} {:8.3f} {:8.3f} {:8.3f} | {:8.2f} {:8.2f} {:8.2f}\n", formatPose(m, q), e.x(), e.y(),
                           e.z(), e.norm(), a.x(), a.y(), a.z());
      csv += poseCsv(m, q);
    } else {
      human += fmt::format("{} | {:11.4f} {:11.4f} {:11.4f} | {:7.4f} {:7.4f} {:7.4f} | {:8.3f} {:8.3f} {:8.3f} {:8.2f} {:8.2f} {:8.2f}\n",
                           formatPose(m, q), p.x(), p.y(), p.z(), d.x(), d.y(), d.z(), e.x(), e.y(), e.z(), a.x(), a.y(), a.z());
      csv += poseCsv(m, q) + fmt::format("{},{},{},{},{},{},", p.x(), p.y(), p.z(), d.x(), d.y(), d.z());
    }
    csv += fmt::format("{},{},{},{},{},{}\n", e.x(), e.y(), e.z(), a.x(), a.y(), a.z());
  }
  human += fmt::format("{} pose(s); largest TCP position error {:.3f} um{}\n", r.q.rows(), r.maxPositionError * 1e3,
                       r.nominal ? " (nominal machine)" : "");
  emit(o, toJson(r), human, csv);
}

}  // namespace

void addForwardCommands(const CommandLine& app) {
  for (const bool errorsOnly : {false, true}) {
    auto o = std::make_shared<ForwardCliOptions>();
    auto cmd = errorsOnly ? app.subcommand("errors", "TCP position and orientation errors at axis positions")
                           : app.subcommand("fk", "forward kinematics: tool relative to the workpiece at axis positions");
    cmd.machineOptions(*o);
    cmd.schemaOptions(errorsOnly ? errorsSchema() : forwardSchema(), o->values);
    cmd.callback([o, errorsOnly] { runForward(*o, errorsOnly); });
  }
}

}  // namespace mtacc::cli
