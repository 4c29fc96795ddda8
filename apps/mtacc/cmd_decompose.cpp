// mtacc decompose: recorded command, encoder and instrument signals of one trajectory at several
// feeds, split into contouring, link, motion, drift and dynamic errors (Andolfatto et al. 2011), with the
// paper's shares (Table 1), maxima (Tables 2-3), dynamic RMS (Table 4) and power law (eq. 23).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/workflows/recorded_decomposition.hpp"

namespace mtacc::cli {
namespace {

struct DecomposeCliOptions : MachineOptions {
  OptionValues values;
  bool strict = false;
};

void run(const DecomposeCliOptions& o) {
  const DecompositionRequest request = decompositionRequest(o.values);
  const auto r = decomposeRecordedSet(loadMachineSetup(o.source), loadDecompositionSet(request));
  const auto j = toJson(r, request.seriesPoints);
  std::string human = fmt::format("{} tests; motion errors fitted at {:g} mm/min (Legendre degree {} in the normalised {}), {} interpolation\n\n",
                                  r.tests.size(), j["reference_feed_mm_per_min"].get<double>(), r.set.degree, j["parameter"].get<std::string>(),
                                  j["interpolation"].get<std::string>());
  human += fmt::format("{:>9} {:>9} | {:>6} {:>6} {:>6} | {:>6} {:>6} {:>6} {:>6} {:>6} | {:>20} | {:>20}\n", "feed", "offset", "c %",
                       "qs %", "d %", "c %", "l %", "m %", "td %", "d %", "drift x y z um", "d RMS x y z um");
  std::string csv =
      "feed_mm_per_min,clock_offset_ms,samples_used,contouring_pct,quasi_static_pct,dynamic_pct,split_contouring_pct,link_pct,motion_pct,"
      "drift_pct,split_dynamic_pct,drift_x_um,drift_y_um,drift_z_um,contouring_max_x_um,contouring_max_y_um,contouring_max_z_um,"
      "quasi_static_max_x_um,quasi_static_max_y_um,quasi_static_max_z_um,dynamic_max_x_um,dynamic_max_y_um,dynamic_max_z_um,"
      "dynamic_rms_x_um,dynamic_rms_y_um,dynamic_rms_z_um,contouring_orthogonal_max_x_um,contouring_orthogonal_max_y_um,"
      "contouring_orthogonal_max_z_um,contouring_orthogonal_undefined_samples\n";
  for (const auto& t : j["tests"]) {
    const auto& s = t["shares_percent"];
    const auto& p = t["split_shares_percent"];
    const auto drift = t["drift_um"].get<std::vector<double>>(), rms = t["dynamic_rms_um"].get<std::vector<double>>();
    human += fmt::format("{:>9.0f} {:>6.3f} ms | {:>6.1f} {:>6.1f} {:>6.1f} | {:>6.1f} {:>6.1f} {:>6.1f} {:>6.1f} {:>6.1f} | {:>6.2f} {:>6.2f} {:>6.2f} | {:>6.3f} {:>6.3f} {:>6.3f}\n",
                         t["feed_mm_per_min"].get<double>(), t["clock_offset_ms"].get<double>(), s["contouring"].get<double>(),
                         s["quasi_static"].get<double>(), s["dynamic"].get<double>(), p["contouring"].get<double>(), p["link"].get<double>(),
                         p["motion"].get<double>(), p["drift"].get<double>(), p["dynamic"].get<double>(), drift[0], drift[1], drift[2], rms[0],
                         rms[1], rms[2]);
    std::vector<double> row{t["feed_mm_per_min"].get<double>(), t["clock_offset_ms"].get<double>(), t["samples_used"].get<double>(),
                            s["contouring"].get<double>(), s["quasi_static"].get<double>(), s["dynamic"].get<double>(),
                            p["contouring"].get<double>(), p["link"].get<double>(), p["motion"].get<double>(), p["drift"].get<double>(),
                            p["dynamic"].get<double>()};
    row.insert(row.end(), drift.begin(), drift.end());
    for (const char* key : {"contouring_max_um", "quasi_static_max_um", "dynamic_max_um", "dynamic_rms_um", "contouring_orthogonal_max_um"})
      for (double v : t[key]) row.push_back(v);
    row.push_back(t["contouring_orthogonal_undefined_samples"].get<double>());
    csv += fmt::format("{}\n", fmt::join(row, ","));
  }
  human += "\ncontouring error orthogonal to the commanded path (L120, Fig. 4; eq. 10's c is the whole difference), largest |x| |y| |z| um:\n";
  for (const auto& t : j["tests"]) {
    const auto c = t["contouring_orthogonal_max_um"].get<std::vector<double>>();
    const auto undefined = t["contouring_orthogonal_undefined_samples"].get<size_t>();
    human += fmt::format("{:>9.0f} mm/min: {:.3f} {:.3f} {:.3f}{}\n", t["feed_mm_per_min"].get<double>(), c[0], c[1], c[2],
                         undefined ? fmt::format(" ({} samples where the path stands still have no tangent)", undefined) : std::string());
  }
  human += "\nshares: eq. 21 over |c| + |qs| + |d| (as printed), then the five-way split over its own five norms (Table 1, erratum E1)\n";
  human += "offset: the command sample stamped s belongs at encoder time s + offset; the mean of the dynamic error is booked as drift,\n"
           "and only the sum of link and motion errors is fixed by the reference test\n";
  if (!j["link_uncertainty"].is_null()) {
    human += fmt::format("link errors' standard uncertainty (k = 1), from the covariance of the errors file's {} identified parameters:\n",
                         j["link_uncertainty"]["parameters"].size());
    for (const auto& t : j["tests"]) {
      const auto max = t["link_uncertainty_um"]["max"].get<std::vector<double>>(), rms = t["link_uncertainty_um"]["rms"].get<std::vector<double>>();
      human += fmt::format("{:>9.0f} mm/min: max {:.3f} {:.3f} {:.3f} um, RMS {:.3f} {:.3f} {:.3f} um\n", t["feed_mm_per_min"].get<double>(), max[0],
                           max[1], max[2], rms[0], rms[1], rms[2]);
    }
  }
  for (const auto& [direction, law] : j["dynamic_rms_power_law"].items())
    human += fmt::format("dynamic RMS {} = {:.4g} um * F^{:.3f} (F in mm/min; largest misfit {:.1f} %)\n", direction, law["kappa_um"].get<double>(),
                         law["exponent"].get<double>(), 100 * law["largest_relative_misfit"].get<double>());
  emit(o, j, human, csv);
  for (const auto& w : r.warnings) std::cerr << "mtacc: warning: " << w << "\n";
  if (o.strict && !r.warnings.empty()) throw StrictFailure{r.warnings.size()};
}

}  // namespace

void addDecomposeCommand(const CommandLine& app) {
  auto o = std::make_shared<DecomposeCliOptions>();
  auto cmd = app.subcommand("decompose", "recorded TCP errors over feeds split into contouring, link, motion, drift and dynamic errors (Andolfatto et al. 2011)");
  cmd.machineOptions(*o);
  cmd.schemaOptions(decompositionSchema(), o->values);
  cmd.flag("--strict", o->strict, "exit with status 4 when a result is doubtful (offset at the search limit, instrument spikes)");
  cmd.callback([o] { run(*o); });
}

}  // namespace mtacc::cli
