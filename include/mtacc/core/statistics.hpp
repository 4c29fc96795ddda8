#pragma once
// Distribution statistics for box plots (seed 000 Part I L4096-4126): extremes, quartiles and
// median.
#include <vector>

namespace mtacc {

struct BoxStatistics {
  double min, lowerQuartile, median, upperQuartile, max;
};
// Quartiles by linear interpolation between order statistics.
BoxStatistics boxStatistics(std::vector<double> values);

}  // namespace mtacc
