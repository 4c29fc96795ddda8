#include "bench_support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <string_view>

#include <Eigen/Core>

#include "mtacc/core/units.hpp"
#include "mtacc/measurement/standard_paths.hpp"

namespace mtacc::bench {

namespace {

// The vector instruction sets this file was compiled for (with the library's flags), as the
// compiler and Eigen see them.
std::string instructionSets() {
  std::string isa =
#if defined(__AVX512F__)
      "AVX-512"
#elif defined(__AVX2__)
      "AVX2"
#elif defined(__AVX__)
      "AVX"
#else
      "SSE2"
#endif
#if defined(__FMA__)
      " + FMA"
#endif
      ;
  return isa + " (Eigen: " + Eigen::SimdInstructionSetsInUse() + ")";
}

}  // namespace

double median(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

bool agreementCheckOnly(int argc, char** argv) {
  const std::string blas = runPythonBaseline(benchDir() + "/blas_info.py");
  fmt::print("build: mtacc for {}; NumPy's {}", instructionSets(), blas.empty() ? "BLAS: unknown (blas_info.py failed)\n" : blas);
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--check") {
      fmt::print("--check: the agreement check at a small size; the times printed are not the benchmark's "
                 "(scripts/bench.sh runs it at full size)\n");
      return true;
    }
  return false;
}

std::vector<MeasurementRun> tiltingTableRTestRuns(const KinematicModel& nominal, int steps, const std::vector<Vec3>& spheres) {
  std::vector<MeasurementRun> runs;
  for (int k = 0; k < 4; ++k) {
    SphereTestSpec c;
    c.axis = "C";
    for (int i = 0; i < steps; ++i) c.angles.push_back(2 * kPi * i / steps);
    c.spheres = spheres;
    c.pose = {0, 0, 0, -30.0 * k * kDeg, 0};
    for (auto& r : sphereTest(nominal, c)) runs.push_back(std::move(r));
    SphereTestSpec b;
    b.axis = "B";
    for (int i = 0; i < steps; ++i) b.angles.push_back(-90.0 * kDeg * i / (steps - 1));
    b.spheres = spheres;
    b.pose = {0, 0, 0, 0, 90.0 * k * kDeg};
    for (auto& r : sphereTest(nominal, b)) runs.push_back(std::move(r));
  }
  for (size_t i = 0; i < runs.size(); ++i) runs[i].name += "-" + std::to_string(i);
  return runs;
}

std::string benchDir() { return MTACC_BENCH_DIR; }
std::string pythonBuildDir() { return MTACC_PYTHON_DIR; }

std::string runPythonBaseline(const std::string& arguments) {
  const std::string cmd = "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 /usr/bin/python3 " + arguments;
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, n);
    if (::pclose(p) != 0) out.clear();
  }
  return out;
}

}  // namespace mtacc::bench
