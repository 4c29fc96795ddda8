#include "mtacc/core/statistics.hpp"

#include <algorithm>

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

}  // namespace mtacc
