#pragma once
// Distribution statistics for box plots (seed 000 Part I L4096-4126): extremes, quartiles and
// median.
#include <cstdint>
#include <vector>

namespace mtacc {

struct BoxStatistics {
  double min, lowerQuartile, median, upperQuartile, max;
};
// Quartiles by linear interpolation between order statistics.
BoxStatistics boxStatistics(std::vector<double> values);

// How much each box statistic of `sampleSize` values varies from one Monte Carlo run to the
// next, estimated from a larger run (`population`): the mean and the standard deviation of each
// statistic over `draws` subsamples drawn without replacement (subsampling, which holds for the
// extremes too when the population is several times the sample). Deterministic for a seed.
// Throws InvalidInput unless 2 <= sampleSize <= population / 2 and draws >= 2.
struct BoxStatisticsSpread {
  BoxStatistics mean, standardDeviation;
};
BoxStatisticsSpread boxStatisticsSpread(const std::vector<double>& population, int sampleSize, int draws, std::uint64_t seed);

}  // namespace mtacc
