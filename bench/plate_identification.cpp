// Identification of the Maho machine's component errors from a seed 003 plate campaign: 24
// placements of a 9 x 9 plate (cubePlacements), the 18 component functions of X, Y, Z as C1
// piecewise quadratics and three squarenesses (plateParameters: 143 parameters) plus a translation
// and rotation per plate, from 3888 coordinates with the probes' noise. mtacc's identifyFromArtefacts
// (design matrix from the exact model's Jacobians, weighted, one QR and the SVD of its R: solution,
// covariance, observability) against NumPy + SciPy (bench/plate_scipy.py): the same linear model
// with the design matrix built vectorised from the first-order F-matrix form of seed 003 §4.4
// and solved by an SVD (scipy.linalg.svd), which gives the same minimum-norm solution,
// covariance and rank. One thread against one; two threads printed beside. Target: < 100 ms.
// Exits non-zero when the design matrices or the estimates disagree.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/identification/plate_identification.hpp"
#include "bench_support.hpp"

using namespace mtacc;

namespace {

// The parameter's function as the baseline evaluates it: which axis and component, and the
// piecewise term's breaks, period and the coefficient's knot and power; or a tilt.
nlohmann::json describe(const Machine& m, const ErrorModel& shape, const Parameter& p) {
  if (p.kind == ParameterKind::Location) return {{"tilt", p.name}};
  int knot = 0, power = 0, nth = 1;
  const std::string suffix = p.name.substr(p.name.find('.') + 1);
  std::sscanf(suffix.c_str(), "k%dc%d#%d", &knot, &power, &nth);
  int seen = 0;
  for (const auto& term : shape.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)].terms())
    if (const auto* piece = std::get_if<PiecewiseTerm>(&term); piece && ++seen == nth)
      return {{"axis", m.axes[static_cast<size_t>(p.axis)].name}, {"component", p.component}, {"knot", knot}, {"power", power},
              {"breaks", piece->breaks}, {"period", piece->period}, {"zero", piece->zero}};
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = bench::agreementCheckOnly(argc, argv) ? 1 : 7;  // the problem's size is already small
  const auto machine = std::make_shared<const Machine>(loadMachine("maho"));
  const auto truth = loadMachineErrors(*machine);
  const auto actual = compile(machine, truth), nominal = compileNominal(machine);
  const Plate plate;
  const auto placements = cubePlacements(nominal, plate);
  const auto noise = seed003ProbeNoise(placements);
  const auto campaign = simulatePlateCampaign(actual, nominal, plate, placements, noise, 17);
  const ErrorModel shape = plateShape(*machine, truth);
  const auto parameters = plateParameters(*machine, shape);

  // The campaign for the baseline: per placement u, v, the stylus in the workpiece frame, the
  // noise, and per feature X, Y, Z, the feature's plate coordinates and the deviations.
  nlohmann::json data;
  const Mat3 tool = toolInWorkpiece(nominal, machine->referencePose.data()).linear();
  const int X = machine->axisIndex("X"), Y = machine->axisIndex("Y"), Z = machine->axisIndex("Z");
  for (size_t k = 0; k < placements.size(); ++k) {
    const auto& p = placements[k];
    const auto& q = campaign[k].poses;
    const auto& d = campaign[k].deviations;
    nlohmann::json features = nlohmann::json::array();
    for (Eigen::Index h = 0; h < q.rows(); ++h) {
      const Vec3 c = campaign[k].positions.row(h).transpose();
      features.push_back({q(h, X), q(h, Y), q(h, Z), c.dot(p.u), c.dot(p.v), d(h, 0), d(h, 1)});
    }
    const Vec3 stylus = tool * p.stylus;
    data["placements"].push_back({{"u", {p.u.x(), p.u.y(), p.u.z()}},
                                  {"v", {p.v.x(), p.v.y(), p.v.z()}},
                                  {"stylus", {stylus.x(), stylus.y(), stylus.z()}},
                                  {"noise", {noise[k].x(), noise[k].y()}},
                                  {"features", features}});
  }
  for (const auto& p : parameters) data["parameters"].push_back(describe(*machine, shape, p));
  const auto dir = std::filesystem::temp_directory_path() / ("mtacc-bench-plates-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto campaignFile = (dir / "campaign.json").string();
  std::ofstream(campaignFile) << data.dump();
  // mtacc's own design matrix, weighted as identifyFromArtefacts weights it, for the baseline to compare its own against.
  ErrorModel zero = shape;
  for (const auto& p : parameterCatalogue(*machine, zero)) setParameterValue(zero, p, 0.0);
  Eigen::MatrixXd design = artefactDesignMatrix(compile(machine, zero, parameters), campaign, 1);
  for (Eigen::Index row = 0, k = 0; k < static_cast<Eigen::Index>(placements.size()); ++k)
    for (Eigen::Index h = 0; h < campaign[static_cast<size_t>(k)].poses.rows(); ++h, row += 2) {
      design.row(row) /= noise[static_cast<size_t>(k)].x();
      design.row(row + 1) /= noise[static_cast<size_t>(k)].y();
    }
  {
    std::ofstream out((dir / "design.bin").string(), std::ios::binary);
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = design;
    out.write(reinterpret_cast<const char*>(rows.data()), static_cast<std::streamsize>(rows.size() * sizeof(double)));
  }

  std::vector<double> seconds, secondsTwo;
  PlateIdentification result;
  auto timeMtacc = [&](int threads, std::vector<double>& into) {
    for (int k = 0; k < repeats; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      result = identifyFromArtefacts(machine, shape, parameters, campaign, threads);
      into.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
  };
  timeMtacc(1, seconds);
  const std::string cmd = bench::benchDir() + "/plate_scipy.py " + dir.string() + " " + std::to_string(design.rows()) + " " +
                          std::to_string(design.cols()) + " " + std::to_string(repeats);
  const std::string pyOut = bench::runPythonBaseline(cmd);
  std::filesystem::remove_all(dir);
  timeMtacc(2, secondsTwo);
  timeMtacc(1, seconds);
  if (pyOut.empty()) {
    fmt::print(stderr, "bench_plate_identification: the SciPy baseline failed ({})\n", cmd);
    return 1;
  }
  const auto py = nlohmann::json::parse(pyOut);
  const auto values = py["values"].get<std::vector<double>>();
  double worst = 0;
  int determined = 0;
  for (size_t k = 0; k < parameters.size(); ++k) {
    if (!result.determined[k]) continue;
    ++determined;
    worst = std::max(worst, std::abs(values[k] - result.values[static_cast<Eigen::Index>(k)]) / result.uncertainty[static_cast<Eigen::Index>(k)]);
  }
  const double ours = bench::median(seconds), theirs = bench::median(py["seconds"].get<std::vector<double>>());
  fmt::print("Plate campaign on the Maho machine (App. D errors): {} placements x {} features, {} readings; {} machine parameters "
             "+ {} nuisance, rank {} ({} parameters determined)\n",
             placements.size(), plate.rows * plate.columns, result.readings, parameters.size(), 3 * placements.size(), result.observability.rank,
             determined);
  fmt::print("design matrices: largest difference mtacc vs NumPy {:.2g} (weighted units; largest entry {:.3g})\n",
             py["design_difference"].get<double>(), design.cwiseAbs().maxCoeff());
  fmt::print("estimates: largest difference {:.2g} standard uncertainties over the determined parameters; rank mtacc {} / NumPy {}\n", worst,
             result.observability.rank, py["rank"].get<int>());
  fmt::print("mtacc identifyFromArtefacts (Jacobians, QR, SVD solve, covariance, observability), 1 thread: median "
             "{:.1f} ms over {} runs (half before, half after SciPy); 2 threads: median {:.1f} ms (target < 100 ms)\n",
             ours * 1e3, seconds.size(), bench::median(secondsTwo) * 1e3);
  fmt::print("NumPy design matrix (vectorised F-matrix model) + scipy.linalg.svd solve, covariance and rank, 1 thread: median {:.1f} ms "
             "(building {:.1f} ms, solving {:.1f} ms)\n",
             theirs * 1e3, bench::median(py["build_seconds"].get<std::vector<double>>()) * 1e3, bench::median(py["solve_seconds"].get<std::vector<double>>()) * 1e3);
  fmt::print("ratio at 1 thread against 1: mtacc is {:.1f}x faster\n", theirs / ours);
  if (py["design_difference"].get<double>() > 1e-6 * design.cwiseAbs().maxCoeff() || worst > 1e-3 || py["rank"].get<int>() != result.observability.rank) {
    fmt::print(stderr, "bench_plate_identification: mtacc and the baseline disagree\n");
    return 1;
  }
  return 0;
}
