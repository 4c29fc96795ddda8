// mtacc ik: axis positions for TCP position and tool direction in the workpiece frame.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/kinematics/inverse.hpp"

namespace mtacc::cli {
namespace {

struct InverseOptions : MachineOptions {
  std::string tcp;
  std::string tool = "0,0,1";
  std::string targetsFile;
  std::string branch = "auto";
  bool all = false;
};

void run(const InverseOptions& o) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  const auto nominal = compileNominal(loaded.machine);
  IkOptions options;
  options.branch = parseTiltBranch(o.branch);
  std::vector<Vec3> positions, directions;
  if (o.tcp.empty() == o.targetsFile.empty())
    throw InputError(InputLocation{"", 0, "--tcp/--targets"}, "give exactly one of --tcp x,y,z or --targets FILE.csv");
  if (!o.tcp.empty()) {
    positions.push_back(parseVector(o.tcp, "--tcp"));
    directions.push_back(parseVector(o.tool, "--tool"));
  } else {
    const auto table = readCsv(o.targetsFile);
    const auto c = requireColumns(table, {"x", "y", "z", "i", "j", "k"});
    for (const auto& row : table.rows) {
      positions.emplace_back(row[static_cast<size_t>(c[0])], row[static_cast<size_t>(c[1])], row[static_cast<size_t>(c[2])]);
      directions.emplace_back(row[static_cast<size_t>(c[3])], row[static_cast<size_t>(c[4])], row[static_cast<size_t>(c[5])]);
    }
  }
  std::vector<IkSolution> solutions;
  if (o.all && positions.size() == 1)
    solutions = inverseKinematics(nominal, positions[0], directions[0], options).solutions;
  else
    solutions = solveIkPath(nominal, positions, directions, options);

  std::string header;
  std::string csv;
  for (int i = 0; i < m.commandedCount(); ++i) {
    header += fmt::format("{}{:>10}", i ? " " : "", m.axes[static_cast<size_t>(i)].name);
    csv += m.axes[static_cast<size_t>(i)].name + ",";
  }
  csv += "singular,within_travel\n";
  std::string human = header + "   notes\n";
  nlohmann::json j;
  j["machine"] = m.name;
  j["units"] = {{"linear", "mm"}, {"rotary", "deg"}};
  for (const auto& s : solutions) {
    std::string notes;
    if (s.singular) notes += "singular: " + s.singularAxis + " free (kept at the hint); ";
    if (!s.withinTravel) notes += s.travelViolation;
    human += formatPose(m, s.q.data()) + "   " + notes + "\n";
    for (int i = 0; i < m.commandedCount(); ++i)
      csv += fmt::format("{},", m.axes[static_cast<size_t>(i)].isRotary() ? s.q[static_cast<size_t>(i)] / kDeg : s.q[static_cast<size_t>(i)]);
    csv += fmt::format("{},{}\n", s.singular ? 1 : 0, s.withinTravel ? 1 : 0);
    j["solutions"].push_back({{"pose", poseJson(m, s.q.data())},
                              {"singular", s.singular},
                              {"free_axis", s.singularAxis},
                              {"within_travel", s.withinTravel},
                              {"travel_violation", s.travelViolation}});
  }
  emit(o, j, human, csv);
}

}  // namespace

void addInverseCommand(CLI::App& app) {
  auto o = std::make_shared<InverseOptions>();
  auto* cmd = app.add_subcommand("ik", "inverse kinematics: axis positions for a TCP position and tool direction");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--tcp", o->tcp, "TCP position x,y,z in the workpiece frame (mm)");
  cmd->add_option("--tool", o->tool, "tool direction i,j,k (TCP towards spindle), default 0,0,1");
  cmd->add_option("--targets", o->targetsFile, "CSV with columns x,y,z,i,j,k: solved as a continuous path");
  cmd->add_option("--branch", o->branch, "tilt branch of the first pose: auto, positive or negative");
  cmd->add_flag("--all", o->all, "list every solution of a single target (including those beyond travel)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
