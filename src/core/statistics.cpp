#include "mtacc/core/statistics.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

BoxStatistics boxStatistics(std::vector<double> v) {
  if (v.empty()) return {0, 0, 0, 0, 0};
  std::sort(v.begin(), v.end());
  auto quantile = [&](double p) {
    const double pos = p * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] + f * (v[i + 1] - v[i]) : v[i];
  };
  return {v.front(), quantile(0.25), quantile(0.5), quantile(0.75), v.back()};
}

BoxStatisticsSpread boxStatisticsSpread(const std::vector<double>& population, int sampleSize, int draws, std::uint64_t seed) {
  if (sampleSize < 2 || 2 * static_cast<size_t>(sampleSize) > population.size() || draws < 2)
    throw InvalidInput(fmt::format("box statistics' spread: samples of {} from {} values, {} draws (need 2 <= sample <= half the "
                                   "values and 2 draws or more)",
                                   sampleSize, population.size(), draws));
  std::mt19937_64 rng(seed);
  std::vector<double> pool = population;
  std::array<Eigen::VectorXd, 5> statistic;
  for (auto& s : statistic) s.resize(draws);
  const auto n = static_cast<size_t>(sampleSize);
  for (int d = 0; d < draws; ++d) {
    for (size_t i = 0; i < n; ++i) std::swap(pool[i], pool[i + std::uniform_int_distribution<size_t>(0, pool.size() - 1 - i)(rng)]);
    const auto b = boxStatistics(std::vector<double>(pool.begin(), pool.begin() + static_cast<long>(n)));
    const double values[5] = {b.min, b.lowerQuartile, b.median, b.upperQuartile, b.max};
    for (int k = 0; k < 5; ++k) statistic[static_cast<size_t>(k)][d] = values[k];
  }
  double mean[5], deviation[5];
  for (size_t k = 0; k < 5; ++k) {
    mean[k] = statistic[k].mean();
    deviation[k] = std::sqrt((statistic[k].array() - mean[k]).square().sum() / (draws - 1));
  }
  return {{mean[0], mean[1], mean[2], mean[3], mean[4]}, {deviation[0], deviation[1], deviation[2], deviation[3], deviation[4]}};
}

}  // namespace mtacc
