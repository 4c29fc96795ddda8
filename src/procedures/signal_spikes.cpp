#include "mtacc/procedures/signal_spikes.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace mtacc {
namespace {

double median(std::vector<double> v) {
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

}  // namespace

std::vector<size_t> spikeSamples(const SampledTrace& trace, double threshold, double floor) {
  std::set<size_t> spikes;
  const size_t n = trace.samples(), half = kSpikeWindow / 2;
  if (n < kSpikeWindow) return {};
  for (const auto& channel : trace.channels) {
    std::vector<double> departure(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t from = std::min(i > half ? i - half : 0, n - kSpikeWindow);
      departure[i] = channel[i] - median({channel.begin() + static_cast<std::ptrdiff_t>(from),
                                          channel.begin() + static_cast<std::ptrdiff_t>(from + kSpikeWindow)});
    }
    std::vector<double> magnitude(n);
    std::transform(departure.begin(), departure.end(), magnitude.begin(), [](double d) { return std::abs(d); });
    const double limit = std::max(threshold * 1.4826 * median(magnitude), floor);
    for (size_t i = 0; i < n; ++i)
      if (magnitude[i] > limit) spikes.insert(i);
  }
  return {spikes.begin(), spikes.end()};
}

}  // namespace mtacc
