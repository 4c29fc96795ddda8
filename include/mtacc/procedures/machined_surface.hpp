#pragma once
// The machined surface by material removal: a height field (Z-map) over a grid, lowered by the
// exact envelope of the tool swept along each straight move of the actual tool path — a
// capsule for a ball end, a swept disc for a flat end (its bottom; the shank is taken to clear
// the stock). Lengths in mm, workpiece frame.
#include <cstddef>
#include <vector>

#include "mtacc/core/parallel.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/procedures/cubic_test.hpp"

namespace mtacc {

// The cutter's reference point along the actual path — the ball centre of a ball end, the
// centre of the bottom disc of a flat end — and the tool axis there. Polylines follow one
// another; `starts` holds the index of each one's first point.
struct CutterPath {
  CuttingTool tool;
  std::vector<Vec3> points;
  std::vector<Vec3> axes;
  std::vector<size_t> starts;

  size_t moves() const { return points.size() - starts.size(); }
};

// Every CL point of the tool path through `model` (all its errors; the workpiece frame with
// M_WC when the workpiece is aligned). Each commanded straight move is followed by halving
// until the actual path departs from its chord by less than chordTolerance (mm); InputError
// (key chord_tolerance) when that takes more than kMaxCutterPoints points.
constexpr size_t kMaxCutterPoints = 50'000'000;
CutterPath cutterPath(const KinematicModel& model, const std::vector<CubicZonePath>& path, const CuttingTool& tool,
                      double chordTolerance = 1e-6);

// Cells of `spacing` over [x0, x0 + nx spacing] x [y0, y0 + ny spacing]; heights are taken at
// the cell centres.
struct HeightGrid {
  double x0 = 0, y0 = 0, spacing = 0.01;
  int nx = 0, ny = 0;

  double x(int i) const { return x0 + (i + 0.5) * spacing; }
  double y(int j) const { return y0 + (j + 0.5) * spacing; }
  size_t cells() const { return static_cast<size_t>(nx) * static_cast<size_t>(ny); }
};
// The grid of a square of side `size` centred on (cx, cy); throws InputError (key `key`) when
// the spacing is below 0.1 um or above the size, or the grid would exceed 3e9 cells (12 GB).
HeightGrid squareGrid(double size, double spacing, const std::string& key, double cx = 0, double cy = 0);

// Heights relative to `reference` (the nominal face), single precision: 1e-8 mm resolution
// for the 0.1 mm of stock, far below what matters. Row j holds y(j), left to right.
struct HeightMap {
  HeightGrid grid;
  double reference = 0;
  std::vector<float> height;

  double at(int i, int j) const { return height[static_cast<size_t>(j) * static_cast<size_t>(grid.nx) + static_cast<size_t>(i)]; }
};
HeightMap stockHeightMap(const HeightGrid& grid, double reference, double stock);

// The lowest point of the tool swept from a to b (cutter reference points, tool axis `axis`)
// on the vertical line through (x, y); +infinity when the line misses it.
double sweptToolBottom(const CuttingTool& tool, const Vec3& a, const Vec3& b, const Vec3& axis, double x, double y);

// Lowers `map` to every move of the path: each cell becomes the lowest of its height and every
// swept tool's bottom over it. Exact (the same as testing every move at every cell); moves
// that cannot reach below a tile's surface are pruned tile by tile.
void cutHeightMap(HeightMap& map, const CutterPath& path, int threads = kAllCores);

}  // namespace mtacc
