// mtacc fk / mtacc errors: the tool relative to the workpiece at given axis positions, and
// the TCP error (actual minus nominal) there.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/csv.hpp"

namespace mtacc::cli {
namespace {

struct ForwardOptions : MachineOptions {
  std::string pose;
  std::string posesFile;
  bool nominal = false;
};

PoseTable readPoses(const Machine& m, const ForwardOptions& o) {
  if (o.pose.empty() == o.posesFile.empty())
    throw InputError(InputLocation{"", 0, "--pose/--poses"}, "give exactly one of --pose AXIS=VALUE,... or --poses FILE.csv");
  if (!o.posesFile.empty()) {
    const auto table = readCsv(o.posesFile);
    auto poses = posesFromCsv(m, table);
    for (long r = 0; r < poses.q.rows(); ++r) {
      const std::vector<double> q(poses.q.row(r).data(), poses.q.row(r).data() + poses.q.cols());
      const auto violation = m.travelViolation(q);
      if (!violation.empty()) throw InputError(InputLocation{o.posesFile, table.lines[static_cast<size_t>(r)], ""}, "pose " + violation);
    }
    return poses;
  }
  const auto q = parsePose(m, o.pose);
  const auto violation = m.travelViolation(q);
  if (!violation.empty()) throw InputError(InputLocation{"", 0, "--pose"}, "pose " + violation);
  PoseTable t;
  t.q = Eigen::Map<const Eigen::RowVectorXd>(q.data(), static_cast<long>(q.size()));
  return t;
}

std::string axisHeader(const Machine& m) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += fmt::format("{}{:>10}", i ? " " : "", m.axes[static_cast<size_t>(i)].name);
  return s;
}

std::string axisCsvHeader(const Machine& m) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i) s += m.axes[static_cast<size_t>(i)].name + ",";
  return s;
}

std::string axisCsv(const Machine& m, const double* q) {
  std::string s;
  for (int i = 0; i < m.commandedCount(); ++i)
    s += fmt::format("{},", m.axes[static_cast<size_t>(i)].isRotary() ? q[i] / kDeg : q[i]);
  return s;
}

void runForward(const ForwardOptions& o, bool errorsOnly) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  const auto poses = readPoses(m, o);
  const auto nominal = compileNominal(loaded.machine);
  const auto actual = o.nominal ? nominal : compile(loaded.machine, loaded.errors);
  PointMatrix pos, dir;
  toolPoints(actual, poses.q, poses.direction, pos, dir, 0);
  const auto err = toolErrors(actual, nominal, poses.q, poses.direction, 0);

  nlohmann::json j;
  j["machine"] = m.name;
  j["units"] = {{"axes", "mm, deg"}, {"tcp", "mm"}, {"position_error", "um"}, {"orientation_error", "urad"}};
  std::string human = fmt::format("{} | {:>11} {:>11} {:>11} | {:>7} {:>7} {:>7} | {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}\n",
                                  axisHeader(m), "x mm", "y mm", "z mm", "i", "j", "k", "dx um", "dy um", "dz um",
                                  "ea urad", "eb urad", "ec urad");
  if (errorsOnly)
    human = fmt::format("{} | {:>8} {:>8} {:>8} {:>8} | {:>8} {:>8} {:>8}\n", axisHeader(m), "dx um", "dy um", "dz um",
                        "|d| um", "ea urad", "eb urad", "ec urad");
  std::string csv = axisCsvHeader(m) + (errorsOnly ? "" : "x,y,z,i,j,k,") + "dx_um,dy_um,dz_um,ea_urad,eb_urad,ec_urad\n";
  double worst = 0;
  for (long r = 0; r < poses.q.rows(); ++r) {
    const double* q = poses.q.row(r).data();
    const Vec3 e = err.row(r).head<3>().transpose() * 1e3;
    const Vec3 a = err.row(r).tail<3>().transpose() * 1e6;
    worst = std::max(worst, e.norm());
    nlohmann::json row = {{"pose", poseJson(m, q)},
                          {"position_error", {e.x(), e.y(), e.z()}},
                          {"orientation_error", {a.x(), a.y(), a.z()}}};
    if (!errorsOnly) {
      row["tcp"] = {pos(r, 0), pos(r, 1), pos(r, 2)};
      row["tool_direction"] = {dir(r, 0), dir(r, 1), dir(r, 2)};
      human += fmt::format("{} | {:11.4f} {:11.4f} {:11.4f} | {:7.4f} {:7.4f} {:7.4f} | {:8.3f} {:8.3f} {:8.3f} {:8.2f} {:8.2f} {:8.2f}\n",
                           formatPose(m, q), pos(r, 0), pos(r, 1), pos(r, 2), dir(r, 0), dir(r, 1), dir(r, 2), e.x(),
                           e.y(), e.z(), a.x(), a.y(), a.z());
      csv += axisCsv(m, q) + fmt::format("{},{},{},{},{},{},", pos(r, 0), pos(r, 1), pos(r, 2), dir(r, 0), dir(r, 1), dir(r, 2));
    } else {
      human += fmt::format("{} | {:8.3f} {:8.3f} {:8.3f} {:8.3f} | {:8.2f} {:8.2f} {:8.2f}\n", formatPose(m, q), e.x(),
                           e.y(), e.z(), e.norm(), a.x(), a.y(), a.z());
      csv += axisCsv(m, q);
    }
    csv += fmt::format("{},{},{},{},{},{}\n", e.x(), e.y(), e.z(), a.x(), a.y(), a.z());
    j["poses"].push_back(row);
  }
  j["max_position_error_um"] = worst;
  human += fmt::format("{} pose(s); largest TCP position error {:.3f} um{}\n", poses.q.rows(), worst,
                       o.nominal ? " (nominal machine)" : "");
  emit(o, j, human, csv);
}

}  // namespace

void addForwardCommands(CLI::App& app) {
  for (const bool errorsOnly : {false, true}) {
    auto o = std::make_shared<ForwardOptions>();
    auto* cmd = errorsOnly ? app.add_subcommand("errors", "TCP position and orientation errors at axis positions")
                           : app.add_subcommand("fk", "forward kinematics: tool relative to the workpiece at axis positions");
    addMachineOptions(*cmd, *o);
    cmd->add_option("--pose", o->pose, "axis positions, e.g. X=10,Y=0,Z=5,B=-15,C=30 (mm, deg)");
    cmd->add_option("--poses", o->posesFile, "CSV with one column per axis (mm, deg), optional <axis>_dir columns");
    if (!errorsOnly) cmd->add_flag("--nominal", o->nominal, "ignore the errors (nominal machine)");
    cmd->callback([o, errorsOnly] { runForward(*o, errorsOnly); });
  }
}

}  // namespace mtacc::cli
