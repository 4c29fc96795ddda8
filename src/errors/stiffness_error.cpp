#include "mtacc/errors/stiffness_error.hpp"

#include "mtacc/errors/error_function.hpp"

namespace mtacc {
namespace {

// The interval holding x and the fraction of the way through it (grids of at least two).
std::pair<Eigen::Index, double> linearWeight(const std::vector<double>& grid, double x) {
  const auto at = locateInGridSearch(grid, x < grid.front() ? grid.front() : (x > grid.back() ? grid.back() : x));
  return {static_cast<Eigen::Index>(at.interval), at.s / (grid[at.interval + 1] - grid[at.interval])};
}

}  // namespace

double StiffnessError::value(double q, double qOther) const {
  const auto own = linearWeight(positions, q);
  auto column = [&](Eigen::Index j) {
    return (1.0 - own.second) * values(own.first, j) + own.second * values(own.first + 1, j);
  };
  if (otherPositions.size() < 2) return column(0);
  const auto [j, t] = linearWeight(otherPositions, qOther);
  return (1.0 - t) * column(j) + t * column(j + 1);
}

}  // namespace mtacc
