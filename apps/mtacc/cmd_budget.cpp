// mtacc budget: each error parameter alone, its largest TCP deviation over the working volume.
#include <fmt/format.h>

#include <unistd.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/budget.hpp"

namespace mtacc::cli {
namespace {

struct BudgetOptions : MachineOptions {
  int samples = 5;
  std::string length;
  std::string angle;
  int rows = 25;
};

void run(const BudgetOptions& o) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  if (o.samples < 2 || o.samples > 50) throw InputError(InputLocation{"", 0, "--samples"}, "must be between 2 and 50");
  const bool atMagnitude = !o.length.empty() || !o.angle.empty();
  std::vector<BudgetItem> items;
  std::string basis;
  if (atMagnitude || nonZeroParameters(m, loaded.errors).empty()) {
    const double length = parseQuantityArg(o.length.empty() ? "10 um" : o.length, Dimension::Length, "--length");
    const double angle = parseQuantityArg(o.angle.empty() ? "30 urad" : o.angle, Dimension::Angle, "--angle");
    items = budgetItemsAtMagnitude(m, length, angle);
    basis = fmt::format("every location error and every component error as a constant, at {:g} um / {:g} urad",
                        length * 1e3, angle * 1e6);
  } else {
    items = budgetItemsOfModel(m, loaded.errors);
    basis = "each non-zero error of the machine's error description, alone, at its value";
  }
  const auto grid = workingVolumeGrid(m, o.samples);
  const bool tty = !o.json && isatty(2);
  const auto entries = errorBudget(loaded.machine, items, grid, 0, [&](size_t done, size_t total) {
    if (tty) std::cerr << fmt::format("\rbudget: {}/{} parameters", done, total) << (done == total ? "\n" : "") << std::flush;
  });
  // All errors together, for scale.
  const auto all = compile(loaded.machine, loaded.errors);
  const auto combined = toolErrors(all, compileNominal(loaded.machine), grid, {}, 0);
  double combinedMax = 0;
  for (long r = 0; r < combined.rows(); ++r) combinedMax = std::max(combinedMax, combined.row(r).head<3>().norm());

  nlohmann::json j;
  j["machine"] = m.name;
  j["basis"] = basis;
  j["poses"] = grid.rows();
  j["samples_per_axis"] = o.samples;
  j["combined_max_position_error_um"] = combinedMax * 1e3;
  std::string human = fmt::format("Error budget of {}\n{}\nover {} poses ({} per axis across the travel)\n\n", m.name,
                                  basis, grid.rows(), o.samples);
  human += fmt::format("{:>4}  {:<10} {:>12}  {:>14}  {:>14}  worst pose\n", "rank", "error", "magnitude",
                       "max TCP dev um", "max tilt urad");
  std::string csv = "rank,error,magnitude,unit,max_position_error_um,max_orientation_error_urad\n";
  for (size_t k = 0; k < entries.size(); ++k) {
    const auto& e = entries[k];
    const std::string mag = fmt::format("{:.3f} {}", toDisplay(e.magnitude, e.dimension), unitOf(e.dimension));
    if (static_cast<int>(k) < o.rows)
      human += fmt::format("{:>4}  {:<10} {:>12}  {:>14.3f}  {:>14.2f}  {}\n", k + 1, e.name, mag, e.maxPositionError * 1e3,
                           e.maxOrientationError * 1e6, m.describePose(e.worstPose));
    csv += fmt::format("{},{},{},{},{},{}\n", k + 1, e.name, toDisplay(e.magnitude, e.dimension), unitOf(e.dimension),
                       e.maxPositionError * 1e3, e.maxOrientationError * 1e6);
    j["entries"].push_back({{"error", e.name},
                            {"magnitude", toDisplay(e.magnitude, e.dimension)},
                            {"unit", unitOf(e.dimension)},
                            {"max_position_error_um", e.maxPositionError * 1e3},
                            {"max_orientation_error_urad", e.maxOrientationError * 1e6},
                            {"worst_pose", poseJson(m, e.worstPose.data())}});
  }
  if (static_cast<int>(entries.size()) > o.rows)
    human += fmt::format("      ... {} more (use --rows, -o FILE or --json)\n", entries.size() - static_cast<size_t>(o.rows));
  human += fmt::format("\nAll errors of the description together: largest TCP deviation {:.3f} um\n", combinedMax * 1e3);
  emit(o, j, human, csv);
}

}  // namespace

void addBudgetCommand(CLI::App& app) {
  auto o = std::make_shared<BudgetOptions>();
  auto* cmd = app.add_subcommand("budget", "error budget: largest TCP deviation of each error over the working volume");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--samples", o->samples, "positions per axis across its travel (default 5)");
  cmd->add_option("--length", o->length, "budget every length error at this magnitude, e.g. '10 um'");
  cmd->add_option("--angle", o->angle, "budget every angular error at this magnitude, e.g. '30 urad'");
  cmd->add_option("--rows", o->rows, "rows to print (default 25)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
