// mtacc budget: each error parameter alone, its largest TCP deviation over the working volume.
#include <fmt/format.h>

#include <unistd.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/budget.hpp"

namespace mtacc::cli {
namespace {

struct BudgetCliOptions : MachineOptions {
  OptionValues values;
  int rows = 25;
};

void run(const BudgetCliOptions& o) {
  if (o.rows < 0) throw InputError(InputLocation{"", 0, "--rows"}, "must not be negative");
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  BudgetOptions options = budgetOptions(o.values);
  const bool tty = !o.json && isatty(2);
  options.progress = [tty](size_t done, size_t total) {
    if (tty) std::cerr << fmt::format("\rbudget: {}/{} parameters", done, total) << (done == total ? "\n" : "") << std::flush;
  };
  const auto r = errorBudget(setup, options);
  std::string human = fmt::format("Error budget of {}\n{}\nover {} poses ({} per axis across the travel)\n\n", m.name,
                                  basisText(r), r.grid.rows(), r.samplesPerAxis);
  human += fmt::format("{:>4}  {:<10} {:>12}  {:>14}  {:>14}  worst pose\n", "rank", "error", "magnitude", "max TCP dev um",
                       "max tilt urad");
  std::string csv = "rank,error,magnitude,unit,max_position_error_um,max_orientation_error_urad\n";
  for (size_t k = 0; k < r.entries.size(); ++k) {
    const auto& e = r.entries[k];
    const double magnitude = toDisplay(e.magnitude, e.dimension);
    if (static_cast<int>(k) < o.rows)
      human += fmt::format("{:>4}  {:<10} {:>12}  {:>14.3f}  {:>14.2f}  {}\n", k + 1, e.name,
                           fmt::format("{:.3f} {}", magnitude, displayUnit(e.dimension)), e.maxPositionError * 1e3,
                           e.maxOrientationError * 1e6, m.describePose(e.worstPose));
    csv += fmt::format("{},{},{},{},{},{}\n", k + 1, e.name, magnitude, displayUnit(e.dimension), e.maxPositionError * 1e3,
                       e.maxOrientationError * 1e6);
  }
  if (r.entries.size() > static_cast<size_t>(o.rows))
    human += fmt::format("      ... {} more (use --rows, -o FILE or --json)\n", r.entries.size() - static_cast<size_t>(o.rows));
  human += fmt::format("\nAll errors of the description together: largest TCP deviation {:.3f} um\n",
                       r.combinedMaxPositionError * 1e3);
  emit(o, toJson(r), human, csv);
}

}  // namespace

void addBudgetCommand(const CommandLine& app) {
  auto o = std::make_shared<BudgetCliOptions>();
  auto cmd = app.subcommand("budget", "error budget: largest TCP deviation of each error over the working volume");
  cmd.machineOptions(*o);
  cmd.schemaOptions(budgetSchema(), o->values);
  cmd.option("--rows", o->rows, "rows to print (default 25)");
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
