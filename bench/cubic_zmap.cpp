// The whole cubic machining test of seed 001 (9 zones, 0.1 mm pick, ball of 3 mm radius) on
// the tilting table with the eight errors of its Table 5 and M_WC: tool path through the
// inverse kinematics, every CL point through the exact error model, and the machined surface
// by material removal on a 10 um grid over the 48 x 48 mm block (23 million cells). Target:
// the whole test under 2 s on one core.
// Side by side in the same run, the material removal against a NumPy z-buffer of the same moves
// (bench/machined_surface_numpy.py: per move, the swept ball's lowest point over every cell of
// its bounding box at once, the buffer lowered there), both cutting the same three windows of
// 1000 x 1000 cells (zone I's centre, the corner where II-3, III-3 and II-4 meet, the block's
// corner) with every move of the test: the z-buffer takes minutes on the whole grid. The ratio
// is that of the two removals on the windows, one thread against one. Exits non-zero when any
// window cell differs by more than one unit in the last place of its single-precision height
// (both evaluate the same closed form in double; the order of the operations may round the last
// bit differently before the height is stored as a float). Medians of 3 (mtacc before and after
// the baseline) and of the baseline's 2.
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/procedures/machined_surface.hpp"
#include "bench_support.hpp"

using namespace mtacc;

namespace {

const char* kTable5 = R"(errors:
  dxBY: 14.6 um
  dyBY: -8.9 um
  dzBY: -14.2 um
  alphaBY: -0.0023 deg
  betaBY: 0.0029 deg
  gammaBY: -0.00002 deg
  alphaCB: -0.00017 deg
  dxCB: 9.4 um
)";

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

int main(int argc, char** argv) {
  const bool check = bench::agreementCheckOnly(argc, argv);
  const int repeats = check ? 1 : 3;
  auto machine = std::make_shared<Machine>(loadMachine("tilting-table"));
  machine->alignment = WorkpieceAlignment::Machine;
  const auto model = compile(machine, parseErrors(*machine, kTable5, "seed 001 Table 5"));
  const auto nominal = compileNominal(machine);
  const CubicTestSpec spec = seed001CubicTest();
  const HeightGrid grid = squareGrid(spec.blockSize, 0.01, "grid");
  if (spec.tool.shape != ToolShape::Ball) {
    fmt::print(stderr, "bench_cubic_zmap: the baseline models a ball-end tool\n");
    return 1;
  }
  // Windows of the block's grid (--check: one of 300 x 300 cells in zone I).
  const auto window = [&](int i0, int j0, int side) {
    HeightGrid w = grid;
    w.x0 = grid.x(i0) - 0.5 * grid.spacing, w.y0 = grid.y(j0) - 0.5 * grid.spacing, w.nx = w.ny = side;
    return w;
  };
  const std::vector<HeightGrid> windows =
      check ? std::vector{window(2250, 2250, 300)} : std::vector{window(1900, 1900, 1000), window(2700, 2700, 1000), window(0, 0, 1000)};

  const auto path = cubicToolPath(nominal, spec);
  const CutterPath cutter = cutterPath(model, path, spec.tool);
  std::vector<double> whole;
  for (int r = 0; !check && r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    auto map = stockHeightMap(grid, spec.topHeight, spec.depth);
    cutHeightMap(map, cutterPath(model, cubicToolPath(nominal, spec), spec.tool), 1);
    whole.push_back(seconds(start));
  }
  std::vector<HeightMap> maps;
  const auto removal = [&](int threads) {
    const auto start = std::chrono::steady_clock::now();
    maps.clear();
    for (const auto& w : windows) {
      maps.push_back(stockHeightMap(w, spec.topHeight, spec.depth));
      cutHeightMap(maps.back(), cutter, threads);
    }
    return seconds(start);
  };
  std::vector<double> cutOne, cutTwo;
  for (int r = 0; r < repeats; ++r) cutOne.push_back(removal(1));

  // The moves and the windows for the baseline.
  const auto dir = std::filesystem::temp_directory_path() / ("mtacc-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::vector<double> moves;
  for (size_t p = 0; p < cutter.starts.size(); ++p) {
    const size_t end = p + 1 < cutter.starts.size() ? cutter.starts[p + 1] : cutter.points.size();
    for (size_t i = cutter.starts[p] + 1; i < end; ++i)
      for (const Vec3* v : {&cutter.points[i - 1], &cutter.points[i]}) moves.insert(moves.end(), v->data(), v->data() + 3);
  }
  const auto movesFile = (dir / "moves.bin").string(), gridsFile = (dir / "grids.json").string(),
             heightsFile = (dir / "heights.bin").string();
  std::ofstream(movesFile, std::ios::binary)
      .write(reinterpret_cast<const char*>(moves.data()), static_cast<std::streamsize>(moves.size() * sizeof(double)));
  nlohmann::json grids{{"spacing", grid.spacing}, {"radius", spec.tool.radius}, {"reference", spec.topHeight}, {"depth", spec.depth}};
  size_t cells = 0;
  for (const auto& w : windows) {
    grids["windows"].push_back({{"x0", w.x0}, {"y0", w.y0}, {"nx", w.nx}, {"ny", w.ny}});
    cells += w.cells();
  }
  std::ofstream(gridsFile) << grids.dump();
  const std::string cmd = bench::benchDir() + "/machined_surface_numpy.py " + movesFile + " " + gridsFile + " " + heightsFile + " " +
                          std::to_string(check ? 1 : 2);
  const std::string pyOut = bench::runPythonBaseline(cmd);
  std::vector<float> theirs(cells);
  std::ifstream(heightsFile, std::ios::binary)
      .read(reinterpret_cast<char*>(theirs.data()), static_cast<std::streamsize>(theirs.size() * sizeof(float)));
  std::filesystem::remove_all(dir);
  for (int r = 0; r < repeats; ++r) cutOne.push_back(removal(1));
  for (int r = 0; r < repeats; ++r) cutTwo.push_back(removal(2));
  if (pyOut.empty()) {
    fmt::print(stderr, "bench_cubic_zmap: the NumPy baseline failed ({})\n", cmd);
    return 1;
  }
  size_t beyond = 0, cut = 0, k = 0;
  double worst = 0;
  for (const auto& map : maps)
    for (const float ours : map.height) {
      const float other = theirs[k++];
      const double larger = std::max(std::abs(ours), std::abs(other)), difference = std::abs(static_cast<double>(ours) - other);
      worst = std::max(worst, difference);
      if (difference > std::nextafter(static_cast<float>(larger), INFINITY) - larger) ++beyond;
      if (ours < static_cast<float>(spec.depth)) ++cut;
    }
  const double ours = bench::median(cutOne), numpy = bench::median(nlohmann::json::parse(pyOut)["seconds"].get<std::vector<double>>());
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);

  fmt::print("cubic machining test (seed 001), tilting table with Table 5 errors and M_WC, 10 um grid:\n");
  fmt::print("  {} x {} = {:.1f} million cells, {} tool moves after chord refinement\n", grid.nx, grid.ny, grid.cells() / 1e6,
             moves.size() / 6);
  if (!check)
    fmt::print("  mtacc, the whole test (tool path, exact model, removal on the whole grid), 1 thread: {:.3f} s (target < 2 s)\n",
               bench::median(whole));
  fmt::print("  material removal on {} window(s), {:.1f} million cells ({:.1f} million cut), every move:\n", windows.size(), cells / 1e6,
             cut / 1e6);
  fmt::print("    mtacc {:.4f} s at 1 thread ({:.4f} s at 2); NumPy z-buffer {:.2f} s at 1 thread\n", ours, bench::median(cutTwo), numpy);
  fmt::print("  ratio (1 thread against 1 thread): mtacc's removal is {:.0f}x faster than the NumPy z-buffer\n", numpy / ours);
  fmt::print("  agreement over the {} window cells: largest difference {:.3g} mm, {} cells beyond one float unit\n", cells, worst,
             beyond);
  fmt::print("  memory: the whole grid's height map {:.0f} MB (4 bytes per cell); peak resident {:.0f} MB\n", grid.cells() * 4 / 1e6,
             usage.ru_maxrss / 1e3);
  if (!check)
    fmt::print("  scaling: time and memory grow with the cells, (size / spacing)^2: a 200 mm block at 5 um has {:.2g} cells "
               "({:.1f} GB, about {:.0f} s on one core)\n",
               std::pow(200 / 0.005, 2), std::pow(200 / 0.005, 2) * 4 / 1e9, bench::median(whole) * std::pow(200 / 0.005, 2) / grid.cells());
  if (beyond > 0 || cut == 0) {
    fmt::print(stderr, "bench_cubic_zmap: {} (limit: one float unit per cell)\n",
               cut == 0 ? "no cell was cut" : fmt::format("{} cells differ from the NumPy z-buffer", beyond));
    return 1;
  }
  return 0;
}
