#include "mtacc/procedures/scanned_surface.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace mtacc {

HeightMap scannedHeightMap(const std::vector<Vec3>& points, const HeightGrid& grid, double reference) {
  // Per cell the sums of the normal equations of z = c0 + c1 dx + c2 dy about its centre.
  struct Sums {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  };
  std::vector<Sums> cells(grid.cells());
  for (const auto& p : points) {
    const double fi = std::floor((p.x() - grid.x0) / grid.spacing), fj = std::floor((p.y() - grid.y0) / grid.spacing);
    if (!(fi >= 0 && fi < grid.nx && fj >= 0 && fj < grid.ny)) continue;
    const int i = static_cast<int>(fi), j = static_cast<int>(fj);
    const Eigen::Vector3d a(1.0, (p.x() - grid.x(i)) / grid.spacing, (p.y() - grid.y(j)) / grid.spacing);
    auto& s = cells[static_cast<size_t>(j) * static_cast<size_t>(grid.nx) + static_cast<size_t>(i)];
    s.normal += a * a.transpose();
    s.rhs += a * (p.z() - reference);
  }
  HeightMap map;
  map.grid = grid;
  map.reference = reference;
  map.height.resize(grid.cells());
  for (size_t k = 0; k < cells.size(); ++k) {
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(cells[k].normal);
    map.height[k] = cells[k].normal(0, 0) >= 3 && lu.rank() == 3 ? static_cast<float>(lu.solve(cells[k].rhs)[0]) : NAN;
  }
  return map;
}

size_t filledCells(const HeightMap& map) {
  size_t n = 0;
  for (const float h : map.height) n += std::isfinite(h);
  return n;
}

}  // namespace mtacc
