// Issue 51's design at its size: the D-optimal choice of 60 R-test poses among 10,000 candidates
// (the identification benchmark's poses on the tilting table: five spheres, C turning at four B
// tilts and B tilting at four C positions) for its 13 location errors, each candidate a 3-reading
// block of the Jacobian about the nominal machine (0.5 um noise, the parameters in 1 um and 10 urad).
// mtacc's designExperiment (greedy start, Fedorov exchange scored by the determinant lemma from
// X M^-1 computed once per swap) and, side by side in the same run, NumPy doing the same steps
// (bench/experiment_design_numpy.py: every candidate scored at once by batched slogdet). One
// thread against one (OpenBLAS limited to one; the design is not threaded); mtacc runs before and
// after the baseline and the mean is compared. Target: under 5 s. Exits non-zero when the chosen
// poses or the criterion differ.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include "bench_support.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>

#include "mtacc/core/units.hpp"
#include "mtacc/identification/experiment_design.hpp"
#include "mtacc/identification/identification.hpp"
#include "mtacc/io/machine_yaml.hpp"

using namespace mtacc;

namespace {

const std::vector<std::string> kNames = {"X0B", "Y0B", "Z0B", "A0B", "C0B", "X0C", "Z0C", "A0C", "B0C", "C0C", "C0Y", "A0Z", "B0Z"};

}  // namespace

int main(int argc, char** argv) {
  const bool check = bench::agreementCheckOnly(argc, argv);
  const int steps = check ? 25 : 250;
  const auto machine = std::make_shared<const Machine>(loadMachine("tilting-table"));
  IdentificationProblem problem;
  problem.machine = machine;
  problem.start = ErrorModel::zero(*machine);
  for (const auto& name : kNames) problem.parameters.push_back(findParameter(*machine, problem.start, name));
  // The identification benchmark's poses, with no sphere on C's line (whose poses would all read
  // alike: ties the two implementations may break differently).
  problem.runs = bench::tiltingTableRTestRuns(compileNominal(machine), steps, {{120, 0, 60}, {0, 80, 160}, {-100, -50, 40}, {60, 60, 120}, {30, -70, 200}});
  Eigen::MatrixXd rows = nominalJacobian(problem, 1) / 0.5e-3;
  for (size_t k = 0; k < kNames.size(); ++k) rows.col(static_cast<Eigen::Index>(k)) *= problem.parameters[k].dimension == Dimension::Length ? 1e-3 : 1e-5;
  std::vector<Eigen::MatrixXd> candidates;
  for (Eigen::Index i = 0; i < rows.rows(); i += 3) candidates.push_back(rows.middleRows(i, 3));
  DesignOptions options;
  options.count = check ? 30 : 60;

  const auto timed = [&](Design& result) {
    const auto t0 = std::chrono::steady_clock::now();
    result = designExperiment(candidates, options);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  Design design;
  const double before = timed(design);

  const auto dir = std::filesystem::temp_directory_path() / ("mtacc-bench-design-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream((dir / "rows.bin").string(), std::ios::binary)
      .write(reinterpret_cast<const char*>(rows.data()), static_cast<std::streamsize>(rows.size() * sizeof(double)));
  std::ofstream((dir / "meta.json").string()) << nlohmann::json{{"candidates", candidates.size()}, {"rows", 3},
                                                                {"parameters", kNames.size()}, {"count", options.count},
                                                                {"ridge", options.ridge}, {"max_exchanges", options.maxExchanges}}
                                                     .dump();
  const std::string cmd = bench::benchDir() + "/experiment_design_numpy.py " + (dir / "rows.bin").string() + " " + (dir / "meta.json").string();
  const std::string pyOut = bench::runPythonBaseline(cmd);
  std::filesystem::remove_all(dir);
  const double after = timed(design), ours = (before + after) / 2;
  if (pyOut.empty()) {
    fmt::print(stderr, "bench_experiment_design_vs_numpy: the NumPy baseline failed ({})\n", cmd);
    return 1;
  }
  const auto py = nlohmann::json::parse(pyOut);
  const bool sameChoice = py["chosen"].get<std::vector<int>>() == design.chosen;
  const double criterionGap = std::abs(py["criterion"].get<double>() - design.criterion);

  fmt::print("D-optimal design: {} of {} candidate R-test poses (3 readings each) for {} parameters of the tilting table; "
             "log det M = {:.6f} after {} exchanges\n",
             options.count, candidates.size(), kNames.size(), design.criterion, design.exchanges);
  fmt::print("NumPy agrees: chosen poses {}, log det to {:.1e} ({} exchanges)\n", sameChoice ? "equal" : "DIFFER", criterionGap,
             py["exchanges"].get<int>());
  fmt::print("mtacc, 1 thread: {:.3f} s, mean of {:.3f} s before and {:.3f} s after the baseline (not threaded; target < 5 s)\n", ours,
             before, after);
  fmt::print("NumPy (batched slogdet of the lemma matrices), 1 thread: {:.3f} s\n", py["seconds"].get<double>());
  fmt::print("ratio at 1 thread against 1: mtacc is {:.1f}x faster\n", py["seconds"].get<double>() / ours);
  if (!sameChoice || criterionGap > 1e-8 * std::max(1.0, std::abs(design.criterion))) {
    fmt::print(stderr, "bench_experiment_design_vs_numpy: mtacc and NumPy disagree\n");
    return 1;
  }
  return 0;
}
