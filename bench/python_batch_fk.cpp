// The Python batch API against the C++ call it wraps: forward kinematics of 10,000 poses of
// the tilting-table example (with the machine file's own errors), Machine.fk(q) in Python
// (bench/python_batch_fk.py: the array in, the TCP and tool-direction arrays out) against
// forwardKinematics() in C++ on the same poses, both at one thread. Target: Python within
// 1.5x of the C++ per-pose cost. Medians of 15 calls each; C++ timed before and after Python.
// Exits non-zero when the two TCPs differ at all (the same numbers in, the same code run).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include "bench_support.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>

#include "mtacc/workflows/kinematics_batch.hpp"

using namespace mtacc;

namespace {

constexpr long kPoses = 10000;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = bench::agreementCheckOnly(argc, argv) ? 1 : 15;
  const MachineSetup setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const Machine& machine = *setup.machine;
  JointMatrix q(kPoses, machine.commandedCount());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (long i = 0; i < kPoses; ++i)
    for (int k = 0; k < q.cols(); ++k) {
      const Axis& a = machine.axes[static_cast<size_t>(k)];
      const double lo = a.travel ? a.travel->min : -kPi, hi = a.travel ? a.travel->max : kPi;
      // In mm and deg, rounded to what the CSV carries, then converted as the Python API does,
      // so that both sides compute on the same numbers.
      const double user = std::stod(fmt::format("{:.17g}", (lo + (hi - lo) * u(rng)) / (a.isRotary() ? kDeg : 1.0)));
      q(i, k) = a.isRotary() ? user * kDeg : user;
    }

  const auto dir = std::filesystem::temp_directory_path() / ("mtacc-bench-pyfk-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = (dir / "poses.csv").string();
  {
    std::ofstream out(file);
    for (long i = 0; i < kPoses; ++i)
      for (int k = 0; k < q.cols(); ++k)
        out << fmt::format("{:.17g}{}", machine.axes[static_cast<size_t>(k)].isRotary() ? q(i, k) / kDeg : q(i, k),
                           k + 1 < q.cols() ? "," : "\n");
  }

  std::vector<double> seconds;
  ForwardResult result;
  auto timeCpp = [&] {
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      result = forwardKinematics(setup, q, {}, {false, false, 1});
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
  };
  timeCpp();
  const std::string cmd =
      bench::benchDir() + "/python_batch_fk.py " + bench::pythonBuildDir() + " " + file + " " + std::to_string(repeats);
  const std::string pyOut = bench::runPythonBaseline(cmd);
  std::filesystem::remove_all(dir);
  timeCpp();
  if (pyOut.empty()) {
    fmt::print(stderr, "bench_python_batch_fk: the Python side failed ({})\n", cmd);
    return 1;
  }
  const auto py = nlohmann::json::parse(pyOut);
  double worst = 0;
  const auto& tcp = py["tcp"];
  for (size_t i = 0; i < tcp.size(); ++i)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(tcp[i][static_cast<size_t>(k)].get<double>() - result.tool.positions(static_cast<long>(i), k)));
  const double cpp = median(seconds) / kPoses, python = median(py["seconds"].get<std::vector<double>>()) / kPoses;
  fmt::print("forward kinematics of {} poses (tilting table with its own errors), 1 thread\n", kPoses);
  fmt::print("C++ forwardKinematics: {:.0f} ns per pose; Python Machine.fk: {:.0f} ns per pose; largest TCP difference {:.1e} mm\n",
             cpp * 1e9, python * 1e9, worst);
  fmt::print("ratio: Python costs {:.2f}x the C++ per-pose time (target <= 1.5x)\n", python / cpp);
  if (worst > 0) {
    fmt::print(stderr, "bench_python_batch_fk: the TCPs differ by {:.2g} mm\n", worst);
    return 1;
  }
  return 0;
}
